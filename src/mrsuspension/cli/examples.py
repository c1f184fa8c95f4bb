"""``mrsus examples list|copy``: the README's example files from an installed package."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer

from mrsuspension.cli.errors import user_errors

__all__ = ["app", "examples_copy", "examples_list"]

app = typer.Typer(
    help="List the example scenarios, studies and scripts, or copy them next to your work.",
    no_args_is_help=True,
    rich_markup_mode=None,
)


@app.command("list")
def examples_list() -> None:
    """Print every example file with the first line of its comment."""
    from mrsuspension.examples import examples_root, list_examples

    with user_errors():
        rows = list_examples()
        typer.echo(f"examples in {examples_root()}:")
    width = max(len(name) for name, _ in rows)
    for name, summary in rows:
        typer.echo(f"  {name:<{width}}  {summary}")
    typer.echo("copy them with: mrsus examples copy all (or a folder, or a file)")


@app.command("copy")
def examples_copy(
    names: Annotated[list[str], typer.Argument(help="files, folders (scenarios, ...) or all")],
    to: Annotated[
        Path, typer.Option("--to", help="target folder (the README's paths: ./examples)")
    ] = Path("examples"),
) -> None:
    """Copy examples into a folder (./examples by default); never replaces a file."""
    from mrsuspension._output import check_output_folder
    from mrsuspension.examples import copy_examples

    with user_errors():
        check_output_folder("--to", to)
        written = copy_examples(names, to)
    for path in written:
        typer.echo(f"wrote {path}")
