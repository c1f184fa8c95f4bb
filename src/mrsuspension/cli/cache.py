"""``mrsus cache info|clear``: the folder of cached study results.

:mod:`mrsuspension.cli` registers :data:`app`. Results are cached by
:func:`~mrsuspension.studies.run.run_study` under
:func:`~mrsuspension.studies.run.default_cache_dir` (``$MRSUSPENSION_CACHE/studies``).
"""

from __future__ import annotations

from pathlib import Path

import typer

__all__ = ["app", "cache_clear", "cache_info"]

app = typer.Typer(
    help="Show or empty the study cache.", no_args_is_help=True, rich_markup_mode=None
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
