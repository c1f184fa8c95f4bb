"""The tutorials under docs/tutorials/ run, cell by cell, as a notebook would (issue 31).

Each tutorial is a jupytext percent-format script (``# %%`` code cells, ``# %% [markdown]``
text cells): this test executes its code cells in order in one namespace, in this
process (a kernel's start-up would cost more than most tutorials), from a temporary
folder, and checks that every cell ran, that it printed, and that it wrote its figure.
A new tutorial is one more file: it is found here and on the docs site
(``tools/mkdocs_tutorials.py``) by its name.

Run time of each: ``pytest tests/integration/test_tutorials.py --durations=0``.
"""

from __future__ import annotations

import contextlib
import io
import re
import subprocess
import sys
import time
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
TUTORIALS = sorted((ROOT / "docs" / "tutorials").glob("*.py"))
sys.path.insert(0, str(ROOT / "tools"))
from mkdocs_tutorials import cells  # noqa: E402  (tools/, shared with the docs site)

#: what a tutorial may take, in seconds of wall time on a loaded 2-core machine
BUDGET = 90.0


def test_there_are_tutorials() -> None:
    letters = {p.name[0] for p in TUTORIALS}
    assert {"a", "b", "c", "d", "e"} <= letters, [p.name for p in TUTORIALS]


@pytest.mark.parametrize("path", TUTORIALS, ids=lambda p: p.stem)
def test_tutorial_runs(path: Path, tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    text = path.read_text()
    if "mrsuspension.monitor" in text:
        pytest.importorskip("uvicorn")
        pytest.importorskip("starlette")
    parsed = cells(text)
    assert parsed[0].kind == "markdown", path.name
    assert parsed[0].source.startswith("# ("), path.name  # "# (a) Title"
    code = [c for c in parsed if c.kind == "code"]
    assert len(code) >= 2
    monkeypatch.chdir(tmp_path)
    # not "__main__": a run's loop process (spawn) must not re-import the tutorial
    namespace: dict[str, object] = {"__name__": "__tutorial__", "__file__": str(path)}
    start = time.monotonic()
    try:
        for n, cell in enumerate(code, start=1):
            out = io.StringIO()
            with contextlib.redirect_stdout(out):
                # padded so that a traceback names the tutorial's own line numbers
                exec(compile("\n" * cell.line + cell.source, str(path), "exec"), namespace)
            printed = out.getvalue()
            sys.stdout.write(printed)
            assert printed.strip(), f"{path.name}: cell {n} printed nothing"
            assert not re.search(r"\bnan\b", printed, re.IGNORECASE), f"cell {n}: {printed}"
    finally:  # a server a failed tutorial left running (e.g. the monitor)
        for value in namespace.values():
            if isinstance(value, subprocess.Popen) and value.poll() is None:
                value.kill()
                value.wait(timeout=30)
    figures = sorted(p.name for p in (tmp_path / "tutorial-output").glob("*.png"))
    assert figures, f"{path.name} wrote no figure"
    assert all((tmp_path / "tutorial-output" / f).stat().st_size > 5_000 for f in figures)
    assert time.monotonic() - start < BUDGET
