"""The documentation site builds with warnings as errors (``mkdocs build --strict``)."""

from __future__ import annotations

import os
import re
import subprocess
import sys
import time
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


def test_docs_site_builds_strict(tmp_path: Path) -> None:
    pytest.importorskip("mkdocs")
    pytest.importorskip("mkdocstrings_handlers.python")
    site = tmp_path / "site"
    env = {**os.environ, "NO_MKDOCS_2_WARNING": "1"}
    start = time.monotonic()
    proc = subprocess.run(
        [sys.executable, "-m", "mkdocs", "build", "--strict", "--site-dir", str(site)],
        cwd=ROOT,
        env=env,
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert proc.returncode == 0, proc.stderr[-4000:]
    assert time.monotonic() - start < 60
    assert (site / "index.html").is_file()
    engine = (site / "api" / "engine" / "index.html").read_text()
    assert 'id="mrsuspension.engine.SimulationResult.load"' in engine  # from the docstrings


def test_every_docs_page_is_in_the_nav() -> None:
    nav = (ROOT / "mkdocs.yml").read_text()
    pages = sorted(p.relative_to(ROOT / "docs").as_posix() for p in (ROOT / "docs").rglob("*.md"))
    assert [p for p in pages if f" {p}\n" not in nav] == []


# The model reference the code cites is docs/model.md (issue 28): the old citations of a
# specification outside the repository must not come back, and every section the code cites
# must exist. The old pattern is split so that this file does not match it.
_OLD_CITATION = re.compile("MODEL" + "_SPEC" + r"|\bspec(?: sections?)? (?:\d|§)", re.IGNORECASE)
_CITATION = re.compile(
    r"model reference,? sections? "
    r"(\d+(?:\.\d+)?(?:\([a-z]\))?(?:\s*(?:-|and|/|,)\s*\d+(?:\.\d+)?(?:\([a-z]\))?)*)"
)
_ANCHOR = re.compile(r"^#{2,3} (\d+(?:\.\d+)?)[. ].*\{#section-([\d-]+)\}\s*$", re.MULTILINE)


def _text_files(*roots: str) -> list[tuple[Path, str]]:
    """(path, text) of every text file under ``roots`` (no caches, no binary files)."""
    out = []
    for root in roots:
        base = ROOT / root
        paths = [base] if base.is_file() else sorted(base.rglob("*"))
        for path in paths:
            if not path.is_file() or "__pycache__" in path.parts:
                continue
            data = path.read_bytes()
            if b"\0" in data[:8192]:
                continue
            try:
                out.append((path, data.decode("utf-8")))
            except UnicodeDecodeError:
                continue
    return out


def test_citations_resolve_in_the_model_reference() -> None:
    model = (ROOT / "docs" / "model.md").read_text()
    sections = {}
    for number, anchor in _ANCHOR.findall(model):
        assert anchor == number.replace(".", "-"), f"section {number} has anchor {anchor}"
        sections[number] = anchor
    numbered = {str(n) for n in range(1, 13)} | {f"2.{n}" for n in range(1, 6)}
    assert set(sections) == numbered, sorted(sections, key=lambda s: [int(p) for p in s.split(".")])
    # items cited by letter, e.g. "section 8(c)", are bold labels "**(c)**" in the page
    old, unresolved, cited = [], [], 0
    for path, text in _text_files("src", "docs", "tests", "README.md"):
        rel = path.relative_to(ROOT).as_posix()
        old += [f"{rel}: {m.group(0)!r}" for m in _OLD_CITATION.finditer(text)]
        if not rel.startswith("src/"):
            continue
        for m in _CITATION.finditer(text):
            cited += 1
            for number, letter in re.findall(r"(\d+(?:\.\d+)?)(?:\(([a-z])\))?", m.group(1)):
                if number not in sections or (letter and f"**({letter})**" not in model):
                    unresolved.append(f"{rel}: {m.group(0)!r}")
    hint = "cite docs/model.md ('model reference, section N') instead:\n"
    assert old == [], hint + "\n".join(old)
    assert unresolved == [], "no such section in docs/model.md:\n" + "\n".join(unresolved)
    assert cited > 100  # the code does cite it
