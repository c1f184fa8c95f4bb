"""``mrsus cache info|clear|warm``: cached study results, and compiled kernels.

:mod:`mrsuspension.cli` registers :data:`app`. Results are cached by
:func:`~mrsuspension.studies.run.run_study` under
:func:`~mrsuspension.studies.run.default_cache_dir` (``$MRSUSPENSION_CACHE/studies``);
``warm`` fills numba's cache of compiled kernels
(:func:`~mrsuspension.cli.compiling.warm_kernels`).
"""

from __future__ import annotations

from pathlib import Path

import typer

__all__ = ["app", "cache_clear", "cache_info", "cache_warm"]

app = typer.Typer(
    help="Show or empty the study cache; compile the engine ahead of time (warm).",
    no_args_is_help=True,
    rich_markup_mode=None,
)


def _folder() -> Path:
    """The cache folder (imported when a cache command runs: studies load the engine)."""
    from mrsuspension.studies.run import default_cache_dir

    return default_cache_dir()


def _entries(folder: Path) -> list[Path]:
    """The cache's files: results (``.nc``) and leftovers of interrupted writes (``.tmp``)."""
    if not folder.is_dir():
        return []
    return sorted(p for p in folder.iterdir() if p.is_file() and p.suffix in (".nc", ".tmp"))


@app.command("info")
def cache_info() -> None:
    """Print the cache folder, its number of cached results and their size."""
    folder = _folder()
    files = _entries(folder)
    size = sum(p.stat().st_size for p in files)
    typer.echo(f"folder: {folder}")
    typer.echo(f"files: {len(files)}")
    typer.echo(f"size: {size / 1e6:.2f} MB ({size} bytes)")


@app.command("clear")
def cache_clear() -> None:
    """Delete every cached study result (the next runs recompute them)."""
    folder = _folder()
    files = _entries(folder)
    size = sum(p.stat().st_size for p in files)
    for p in files:
        p.unlink(missing_ok=True)
    typer.echo(f"removed {len(files)} files ({size / 1e6:.2f} MB) from {folder}")


@app.command("warm")
def cache_warm(
    workers: int | None = typer.Option(
        None, "--workers", "-j", help="processes compiling side by side (default: one per core)"
    ),
) -> None:
    """Compile every kernel into numba's cache now (the first run then starts at once).

    Prints each entry point as it compiles, with the time taken (a fraction of a second
    each when the cache is already warm). ``make`` runs it after installing and before
    the tests.
    """
    import time

    from mrsuspension.cli.compiling import warm_kernels
    from mrsuspension.cli.errors import user_errors
    from mrsuspension.errors import check_count

    with user_errors():
        if workers is not None:
            check_count("--workers", workers)
    t0 = time.perf_counter()
    rows = warm_kernels(say=lambda m: typer.echo(m, err=True), workers=workers)
    typer.echo(
        f"compiled kernels ready: {len(rows)} entry points in {time.perf_counter() - t0:.1f} s"
    )
