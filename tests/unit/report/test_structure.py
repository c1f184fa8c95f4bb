"""The report's structure: one toolkit, a chapter registry, no import cycles.

The import graph is read with ``ast`` (every import: module level, inside functions and
under ``TYPE_CHECKING``); ``from pkg import module`` counts as an import of the module
only. The registry's module names (``chapters.CHAPTERS``) count as imports of them.
"""

from __future__ import annotations

import ast
import functools
from pathlib import Path

import pytest

from _helpers import raises_validation
from mrsuspension.report.chapters import CHAPTERS, chapter, choices, parse_chapters, resolve

SRC = Path(__file__).resolve().parents[3] / "src"
PACKAGE = SRC / "mrsuspension"


def _name(path: Path) -> str:
    parts = list(path.relative_to(SRC).with_suffix("").parts)
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


MODULES = {_name(p): p for p in PACKAGE.rglob("*.py")}


def _imports(path: Path) -> set[str]:
    me = _name(path)
    package = me if path.name == "__init__.py" else me.rpartition(".")[0]
    out: set[str] = set()
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.Import):
            out.update(a.name for a in node.names)
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package.split(".")[: len(package.split(".")) - node.level + 1]
                module = ".".join(base + ([node.module] if node.module else []))
            else:
                module = node.module or ""
            names = {f"{module}.{a.name}" for a in node.names}
            subs = names & MODULES.keys()
            out.update(subs if subs == names else subs | {module})
    return {m for m in out if m in MODULES and m != me}


@functools.cache
def _structure() -> tuple[dict[str, set[str]], set[str], set[str]]:
    """``(GRAPH, REPORT, CHAPTER_MODULES)``: the import graph (parsed when a test first
    needs it, not at collection: every pytest process collects this module), the report's
    modules and its chapter modules."""
    graph = {m: _imports(p) for m, p in MODULES.items()}
    graph["mrsuspension.report.chapters"] |= {f"mrsuspension.report.{m}" for m in CHAPTERS.values()}
    report = {
        m for m in graph if m == "mrsuspension.report" or m.startswith("mrsuspension.report.")
    }
    chapters = {
        m for m in report if m.rsplit(".", 1)[-1][:2] == "ch" and m.rsplit(".", 1)[-1][2:].isdigit()
    }
    return graph, report, chapters


def _cycles(nodes: set[str]) -> list[list[str]]:
    """Strongly connected components with more than one module (Tarjan)."""
    edges = {m: _structure()[0][m] & nodes for m in nodes}
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    found: list[list[str]] = []

    def visit(v: str) -> None:
        index[v] = low[v] = len(index)
        stack.append(v)
        for w in edges[v]:
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            component = []
            while True:
                w = stack.pop()
                component.append(w)
                if w == v:
                    break
            if len(component) > 1:
                found.append(sorted(component))

    for v in sorted(nodes):
        if v not in index:
            visit(v)
    return found


def test_report_has_no_import_cycles() -> None:
    _, REPORT, _ = _structure()
    assert len(REPORT) >= 15
    assert _cycles(REPORT) == []


def test_no_chapter_imports_another() -> None:
    GRAPH, _, CHAPTER_MODULES = _structure()
    assert {"mrsuspension.report.ch2", "mrsuspension.report.ch7"} <= CHAPTER_MODULES
    cross = sorted((a, b) for a in CHAPTER_MODULES for b in GRAPH[a] if b in CHAPTER_MODULES)
    assert cross == []


#: modules below the toolkit: they import nothing of the report
LEAVES = {"mrsuspension.report.legibility"}


def test_toolkit_is_the_bottom_of_the_report() -> None:
    GRAPH, REPORT, _ = _structure()
    assert GRAPH["mrsuspension.report.toolkit"] & REPORT <= LEAVES
    for leaf in LEAVES:
        assert GRAPH[leaf] & REPORT == set(), leaf


def test_hil_does_not_import_the_report() -> None:
    GRAPH, REPORT, _ = _structure()
    up = sorted(
        (a, b) for a in GRAPH if a.startswith("mrsuspension.hil") for b in GRAPH[a] if b in REPORT
    )
    assert up == []


@pytest.mark.parametrize("number", sorted(CHAPTERS))
def test_every_registered_chapter_has_its_entry(number: int) -> None:
    entry = chapter(number)
    assert entry.number == number
    jobs = entry.jobs(True)
    assert jobs.figures or jobs.specials


def test_chapter_choices_come_from_the_registry() -> None:
    assert choices() == (
        *(str(n) for n in sorted(CHAPTERS)),
        "findings",
        "beyond",
        "vehicles",
        "benchmark",
    )
    assert parse_chapters(" 4,findings, 2") == [4, "findings", 2]
    assert resolve(["beyond", 3]) == ([3], {"beyond"})
    raises_validation(lambda: parse_chapters("4,x"), "--chapters", "'x'", "'findings'")
    raises_validation(lambda: parse_chapters("2,beyonf"), "unknown chapter 'beyonf'", "'beyond'?")
    raises_validation(lambda: parse_chapters(" , "), "--chapters", "at least one")
    raises_validation(lambda: resolve([7]), "chapter 7", "beyond")
    raises_validation(lambda: resolve([]), "no chapters")
    raises_validation(lambda: chapter(9), "chapter 9")
