"""``mrsus optimize``: tune a controller for a problem file (see :mod:`mrsuspension.optimize`).

:mod:`mrsuspension.cli` registers :func:`optimize_command`. Input errors are reported in
one line on stderr with exit code 2.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Annotated

import typer

from mrsuspension._docs import doc
from mrsuspension._output import check_output_folder
from mrsuspension.cli.errors import user_errors
from mrsuspension.errors import check_count

__all__ = ["optimize_command"]


def optimize_command(
    problem: Annotated[
        Path,
        typer.Argument(
            help=f"optimisation problem (TOML, see {doc('optimisation')})", show_default=False
        ),
    ],
    out: Annotated[
        Path | None,
        typer.Option("--out", "-o", help="folder for optimization.json and convergence.png"),
    ] = None,
    max_evaluations: Annotated[
        int | None,
        typer.Option("--max-evaluations", help="candidate budget (default: the problem's)"),
    ] = None,
    workers: Annotated[
        int | None, typer.Option(help="processes (default: the problem's, else all cores)")
    ] = None,
    as_json: Annotated[
        bool, typer.Option("--json", help="print the result as one JSON object")
    ] = False,
    force: Annotated[
        bool, typer.Option("--force", help="replace an --out folder holding other output")
    ] = False,
) -> None:
    """Tune scenario fields (e.g. a controller's gains) for a weighted objective over roads."""
    from mrsuspension._output import prepare_output, save_listed
    from mrsuspension.optimize import OptimizationProblem, optimize

    with user_errors():
        if workers is not None:
            check_count("--workers", workers)
        if max_evaluations is not None:
            from mrsuspension.optimize import MAX_EVALUATIONS

            check_count(
                "--max-evaluations",
                max_evaluations,
                1,
                MAX_EVALUATIONS,
                why=" (every candidate runs one simulation per road)",
            )
        if out is not None:
            check_output_folder("--out", out, "optimize", force=force)
        prob = OptimizationProblem.load(problem)
        files: list[str] = []
        with prepare_output(out, "optimize", force=force) as folder:  # checked before the work
            from mrsuspension.cli.compiling import notify_if_compiling

            notify_if_compiling()
            result = optimize(
                prob, max_evaluations=max_evaluations, workers=workers, progress=not as_json
            )
            if out is not None and folder is not None:
                files = save_listed(out, folder, result.save)
    if as_json:
        data = result.to_dict()
        data["files"] = files
        typer.echo(json.dumps(data))
        return
    typer.echo(
        f"{prob.name}: best objective J = {result.objective:.4g} (reference = 1) after "
        f"{result.evaluations} evaluations in {result.generations} generations "
        f"({result.run_time:.1f} s; {result.message})"
    )
    for name, value in result.best.items():
        typer.echo(f"  {name} = {value:.6g}")
    measures = list(prob.weights)
    typer.echo(f"{'road':34} {'measure':26} {'best':>11} {'reference':>11} {'ratio':>7}")
    for road in result.measures:
        for m in measures:
            best, ref = result.measures[road][m], result.reference[road][m]
            ratio = best / ref if ref else float("nan")
            typer.echo(f"{road[:34]:34} {m:26} {best:11.4g} {ref:11.4g} {ratio:7.3f}")
    for f in files:
        typer.echo(f"wrote {f}")
