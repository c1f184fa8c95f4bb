"""``mrsus study``: run a parameter study file."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer

from mrsuspension.cli.errors import user_errors
from mrsuspension.errors import ValidationError, check_count

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
    no_cache: Annotated[
        bool, typer.Option("--no-cache", help="ignore and do not write the cache")
    ] = False,
    as_json: JsonOpt = False,
) -> None:
    """Run a parameter study (a scenario and a grid of fields) and print or save the measures."""
    from mrsuspension.studies import Study, run_study
    from mrsuspension.studies.study import check_scheduler

    with user_errors():
        if workers is not None:
            check_count("--workers", workers)
        if out is not None and (out.is_dir() or out.suffix.lower() not in (".nc", ".csv")):
            what = "a folder" if out.is_dir() else "not a .nc or .csv file"
            raise ValidationError(f"--out {str(out)!r} is {what}: expected a .nc or .csv file")
        st = Study.load(path)
        if scheduler is not None:
            scheduler = check_scheduler(scheduler)
        result = run_study(
            st,
            executor=scheduler or "local",
            workers=workers,
            progress=not as_json,
            cache_dir=False if no_cache else None,
        )
        saved = result.save(out) if out is not None else None
    df = result.to_pandas()
    if as_json:
        typer.echo(df.to_json(orient="records"))
        return
    typer.echo(df.to_string(index=False))
    if saved is not None:
        typer.echo(f"wrote {saved}")
