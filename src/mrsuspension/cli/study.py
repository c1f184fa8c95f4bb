"""``mrsus study``: run a parameter study file."""

from __future__ import annotations

import warnings
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Annotated

import typer

from mrsuspension.cli.errors import user_errors
from mrsuspension.errors import check_count, check_range

__all__ = ["study"]

JsonOpt = Annotated[bool, typer.Option("--json", help="print the result as one JSON object")]


def study(
    path: Annotated[Path, typer.Argument(help="study file (TOML)")],
    out: Annotated[
        Path | None, typer.Option("--out", "-o", help="write results (.nc or .csv)")
    ] = None,
    scheduler: Annotated[
        str | None,
        typer.Option(help="Dask scheduler address, e.g. tcp://host:8786 (default: local pool)"),
    ] = None,
    workers: Annotated[
        int | None, typer.Option(help="local processes (default: all cores)")
    ] = None,
    scheduler_timeout: Annotated[
        float,
        typer.Option(
            help="seconds [s] the scheduler gets to accept the connection, and again to answer"
        ),
    ] = 10.0,
    no_cache: Annotated[
        bool, typer.Option("--no-cache", help="ignore and do not write the cache")
    ] = False,
    as_json: JsonOpt = False,
) -> None:
    """Run a parameter study (a scenario and a grid of fields) and print or save the measures.

    Results are cached by the study and the package code (``mrsus cache info``); a
    result read from the cache is announced on stderr (``from cache: FILE``). ``--out``
    is checked before any computing and written only when the study has finished; it
    replaces an earlier ``--out`` (and its ``.json`` sidecar) only if mrsus wrote it.
    """
    from mrsuspension._output import prepare_output_file
    from mrsuspension.cli.compiling import notify_if_compiling
    from mrsuspension.studies import Study, run_study
    from mrsuspension.studies.study import check_scheduler

    with user_errors():
        if workers is not None:
            check_count("--workers", workers)
        check_range("--scheduler-timeout", scheduler_timeout, 0.0, 3600.0, unit="s",
                    low_inclusive=False)  # fmt: skip
        st = Study.load(path, progress=not as_json)  # a big grid: progress while checked
        if scheduler is not None:
            scheduler = check_scheduler(scheduler, scheduler_timeout)
        with (
            prepare_output_file(
                out, suffixes=(".nc", ".csv"), sidecars={".csv": (".json",)}, command="study"
            ) as target,
            _cache_warnings(),
        ):
            notify_if_compiling()
            result = run_study(
                st,
                executor=scheduler or "local",
                workers=workers,
                progress=not as_json,
                cache_dir=False if no_cache else None,
                scheduler_timeout=scheduler_timeout,
            )
            if target is not None:
                result.save(target)
    if result.from_cache:
        typer.echo(f"from cache: {result.cache_file}", err=True)
    saved = out
    df = result.to_pandas()
    if as_json:
        typer.echo(df.to_json(orient="records"))
        return
    from mrsuspension._notebook import with_unit_headers

    typer.echo(with_unit_headers(df).to_string(index=False))  # "seat_z [m/s^2]"
    if saved is not None:
        typer.echo(f"wrote {saved}")


@contextmanager
def _cache_warnings() -> Iterator[None]:
    """Print the study cache's warnings as one ``warning:`` line each on stderr."""
    from mrsuspension.studies.run import StudyCacheWarning

    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", StudyCacheWarning)
        try:
            yield
        finally:
            for w in caught:
                if issubclass(w.category, StudyCacheWarning):
                    typer.echo(f"warning: {w.message}", err=True)
                else:  # not ours: as Python would show it
                    warnings.showwarning(w.message, w.category, w.filename, w.lineno)
