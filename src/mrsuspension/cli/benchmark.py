"""``mrsus benchmark``: the benchmark of semi-active laws (:mod:`mrsuspension.benchmark.study`).

:mod:`mrsuspension.cli` registers :func:`benchmark_command`. Input errors are reported in
one line on stderr with exit code 2; a law that beats the semi-active optimum (a model or
solver error) is reported on stderr with exit code 1, after the outputs are written.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Annotated

import typer

from mrsuspension._docs import doc
from mrsuspension.cli.errors import user_errors
from mrsuspension.errors import check_count

__all__ = ["benchmark_command"]


def benchmark_command(
    spec: Annotated[
        Path | None,
        typer.Argument(
            help=f"benchmark spec (TOML, see {doc('benchmark')}; default: the default set)",
            show_default=False,
        ),
    ] = None,
    quick: Annotated[
        bool, typer.Option("--quick", help="the quick set (seconds) instead of the default set")
    ] = False,
    out: Annotated[
        Path | None,
        typer.Option(
            "--out", "-o", help="folder for benchmark.csv, best.csv, benchmark.json and PNGs"
        ),
    ] = None,
    workers: Annotated[
        int | None, typer.Option(help="local processes (default: all cores)")
    ] = None,
    scheduler: Annotated[
        str | None,
        typer.Option(help="Dask scheduler address, e.g. tcp://host:8786 (default: local pool)"),
    ] = None,
    as_json: Annotated[
        bool, typer.Option("--json", help="print the result as one JSON object")
    ] = False,
    force: Annotated[
        bool, typer.Option("--force", help="replace an --out folder holding other output")
    ] = False,
) -> None:
    """Tune every semi-active law on a training road and score it on other roads, speeds
    and the quarter and full car: ratios to passive and the distance to the optimum."""
    from mrsuspension._output import check_output_folder, prepare_output, save_listed
    from mrsuspension.benchmark.study import BenchmarkSpec, run_benchmark
    from mrsuspension.errors import ValidationError

    with user_errors():
        if workers is not None:
            check_count("--workers", workers)
        if out is not None:
            check_output_folder("--out", out, "benchmark", force=force)
        if spec is not None and quick:
            raise ValidationError("give a spec file or --quick, not both")
        if spec is not None:
            the_spec = BenchmarkSpec.load(spec)
        else:
            the_spec = BenchmarkSpec.quick() if quick else BenchmarkSpec()
        if scheduler is not None:
            from mrsuspension.studies.study import check_scheduler

            scheduler = check_scheduler(scheduler)
        files: list[str] = []
        with prepare_output(out, "benchmark", force=force) as folder:  # checked before the work
            from mrsuspension.cli.compiling import notify_if_compiling

            notify_if_compiling()
            result = run_benchmark(
                the_spec, workers=workers, scheduler=scheduler, progress=not as_json
            )
            if out is not None and folder is not None:
                files = save_listed(out, folder, result.save)
    if as_json:
        data = result.to_dict()
        data["files"] = files
        typer.echo(json.dumps(data, allow_nan=False))
    else:
        typer.echo(result.summary())
        for f in files:
            typer.echo(f"wrote {f}")
    if result.violations:
        for v in result.violations:
            typer.echo(f"error: bound violated: {v}", err=True)
        raise typer.Exit(1)
