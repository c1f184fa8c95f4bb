"""``mrsus reproduce``: regenerate the dissertation's analyses into an HTML report."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer

from mrsuspension._output import check_output_folder, marked_command, prepare_output
from mrsuspension.cli.errors import user_errors

__all__ = ["reproduce"]


def _chapters(text: str) -> list[int | str]:
    """``--chapters``: the registry's chapter numbers and sections, comma-separated
    (:func:`mrsuspension.report.chapters.parse_chapters`, imported on use)."""
    from mrsuspension.report.chapters import parse_chapters

    return parse_chapters(text)


def reproduce(
    out: Annotated[Path, typer.Option("--out", "-o", help="output folder")] = Path("results"),
    chapters: Annotated[
        str | None,
        typer.Option(help="comma-separated chapters and sections, e.g. 2,4,findings,beyond"),
    ] = None,
    quick: Annotated[bool, typer.Option("--quick", help="coarse grids, for a fast check")] = False,
    svg: Annotated[
        bool, typer.Option("--svg", help="also write every figure as SVG (PNG always)")
    ] = False,
    check_layout: Annotated[
        bool,
        typer.Option(
            "--check-layout",
            hidden=True,
            help="record each figure's overlapping texts and legends over data (for tests)",
        ),
    ] = False,
    force: Annotated[
        bool, typer.Option("--force", help="replace an --out folder holding other output")
    ] = False,
) -> None:
    """Regenerate the dissertation's analyses into OUT/index.html (the main job).

    The report is written whole into a temporary folder that replaces OUT when complete.
    With --chapters, a report already in OUT is updated: the chosen chapters are
    rebuilt, the others kept (files, index and manifest entries).
    """
    import sys

    from rich.console import Console

    from mrsuspension._progress import plain_status
    from mrsuspension.cli.compiling import notify_if_compiling
    from mrsuspension.report import build_report

    console = Console(stderr=True)
    with user_errors():
        check_output_folder("--out", out, "reproduce", force=force)
        chosen = None if chapters is None else _chapters(chapters)
        previous = _merge_into(out, chosen)
        with prepare_output(out, "reproduce", force=force) as staged:
            assert staged is not None
            notify_if_compiling()
            if not sys.stderr.isatty():  # a log: plain lines every few seconds, no spinner
                build_report(
                    staged, chapters=chosen, quick=quick, progress=plain_status(), svg=svg,
                    check_layout=check_layout, previous=previous,
                )  # fmt: skip
            else:
                with console.status("starting") as status:
                    build_report(
                        staged, chapters=chosen, quick=quick,
                        progress=lambda m: status.update(m), svg=svg,
                        check_layout=check_layout, previous=previous,
                    )  # fmt: skip
    if previous is not None:
        typer.echo(f"merged into the report in {out} (chapters not chosen kept)", err=True)
    typer.echo(f"report written to {out / 'index.html'}")


def _merge_into(out: Path, chosen: list[int | str] | None) -> Path | None:
    """The report folder a partial run (``--chapters``) merges into: ``out`` when it holds
    a report written by ``mrsus reproduce``; None for a full run or a new folder."""
    if chosen is None or not (out / "index.html").is_file():
        return None
    return out if marked_command(out) == "reproduce" else None
