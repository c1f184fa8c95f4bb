"""The tutorials of ``docs/tutorials/*.py`` on the documentation site (a mkdocs hook).

Each tutorial is a jupytext percent-format script: ``# %% [markdown]`` cells of text
(every line a comment) and ``# %%`` cells of code. This hook (``hooks:`` in mkdocs.yml)
renders each as a page, ``tutorials/<name>.md`` (the text as Markdown, the code in
Python blocks), and lists the pages in a "Tutorials" section of the navigation after
"Home", in file-name order, titled by each tutorial's first heading. A new tutorial is
one more file in ``docs/tutorials/``: no list to edit. The scripts themselves are copied
to the site beside their pages (a download link on each page).

:func:`cells` is shared with the test that runs the tutorials
(``tests/integration/test_tutorials.py``).
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from pathlib import Path
from typing import Any

#: the folder of the tutorials, under docs_dir
FOLDER = "tutorials"
_MARKER = re.compile(r"^# %%(?:\s*\[(?P<kind>\w+)\])?.*$")


@dataclass(frozen=True)
class Cell:
    """One cell of a percent-format script: ``kind`` ("code" or "markdown"), its text
    (a Markdown cell without its comment marks) and the 0-based line it starts on."""

    kind: str
    source: str
    line: int


def cells(text: str) -> list[Cell]:
    """The cells of a jupytext percent-format script, in order (empty cells dropped).

    Examples
    --------
    >>> [(c.kind, c.source, c.line) for c in cells("# %% [markdown]\\n# # Title\\n# %%\\nx = 1\\n")]
    [('markdown', '# Title', 1), ('code', 'x = 1', 3)]
    """
    out: list[Cell] = []
    kind: str | None = None  # text before the first marker is not a cell
    start, lines = 0, list[str]()

    def close() -> None:
        if kind is None:
            return
        body = [re.sub(r"^# ?", "", ln) for ln in lines] if kind == "markdown" else lines
        source = "\n".join(body).strip("\n")
        if source.strip():
            out.append(Cell(kind, source, start))

    for number, line in enumerate(text.splitlines()):
        m = _MARKER.match(line)
        if m:
            close()
            kind = "markdown" if m.group("kind") in ("markdown", "md") else "code"
            start, lines = number + 1, []
        else:
            lines.append(line)
    close()
    return out


def title(text: str, fallback: str) -> str:
    """The first Markdown heading of a tutorial (its page title), else ``fallback``."""
    for cell in cells(text):
        if cell.kind == "markdown":
            for line in cell.source.splitlines():
                if line.startswith("# "):
                    return line[2:].strip()
    return fallback


def render(path: Path) -> str:
    """A tutorial as a Markdown page: its text, its code in Python blocks, how to run it."""
    text = path.read_text(encoding="utf-8")
    parts: list[str] = []
    for n, cell in enumerate(cells(text)):
        if cell.kind == "markdown":
            parts.append(cell.source)
        else:
            parts.append(f"```python\n{cell.source}\n```")
        if n == 0:
            parts.append(
                '!!! note "Run it"\n'
                f"    The tutorial is [`{path.name}`]({path.name}), a script of notebook cells\n"
                "    (jupytext percent format). Open it as a notebook\n"
                f"    (`jupytext --to notebook {path.name}`) or run it as it is\n"
                f"    (`python {path.name}`); it writes its figures to `tutorial-output/`\n"
                "    and runs in seconds. The test suite runs every tutorial\n"
                "    (`tests/integration/test_tutorials.py`)."
            )
    return "\n\n".join(parts) + "\n"


def tutorial_paths(docs_dir: str | Path) -> list[Path]:
    """The tutorials, in file-name order."""
    return sorted((Path(docs_dir) / FOLDER).glob("*.py"))


# -- mkdocs events ------------------------------------------------------------------------
def on_config(config: Any) -> Any:
    """Add the "Tutorials" section to the navigation, after "Home"."""
    pages = [
        {title(p.read_text(encoding="utf-8"), p.stem): f"{FOLDER}/{p.stem}.md"}
        for p in tutorial_paths(config["docs_dir"])
    ]
    nav = config.get("nav")
    if pages and nav is not None:
        nav[:] = [n for n in nav if not (isinstance(n, dict) and "Tutorials" in n)]
        nav.insert(1, {"Tutorials": pages})
    return config


def on_files(files: Any, config: Any) -> Any:
    """A generated page per tutorial (the scripts are copied as they are)."""
    from mkdocs.structure.files import File

    for path in tutorial_paths(config["docs_dir"]):
        files.append(File.generated(config, f"{FOLDER}/{path.stem}.md", content=render(path)))
    return files
