"""The import graph has layers and no cycles (read from the source with ``ast``).

Data flows one way (``/work/shared/STYLE.md``): parameters -> models -> (controller,
excitation) -> engine -> result -> measures -> report, with the HiL loop, the monitor and
the CLI on top. :data:`LAYERS` gives every top-level module or package of
``mrsuspension`` a rank; a module may import its own package and packages of a lower or
equal rank, never a higher one. Every import counts, also those inside functions (a lazy
import is still a dependency); only ``if TYPE_CHECKING:`` blocks are left out.

Known offences not fixed yet are listed in :data:`KNOWN_UPWARD` and
:data:`KNOWN_CYCLES`; each entry must still occur (so a fix removes its entry).
"""

from __future__ import annotations

import ast
import functools
from collections import defaultdict
from collections.abc import Iterator
from pathlib import Path

import pytest

SRC = Path(__file__).resolve().parents[2] / "src"
PACKAGE = "mrsuspension"

#: top-level module or package -> rank (lower: further upstream)
LAYERS: dict[str, int] = {
    "errors": 0,
    "_numba_cache": 0,
    "_pool": 0,
    "_lazy": 0,
    "_jsonsafe": 0,
    "_progress": 0,
    "_output": 0,
    "_inputs": 0,
    "_docs": 0,  # online links to docs/ pages
    "_notebook": 0,  # notebook conventions: Measures, html tables, figures without pyplot
    "examples": 0,  # the packaged example files (`mrsus examples`)
    "errata": 0,
    "parameters": 1,
    "measures": 1,
    "shaping": 1,
    "excitation": 1,
    "dampers": 2,
    "vehicle": 3,
    "control": 4,
    "engine": 5,
    "characterisation": 6,
    "scenario": 6,
    "_batch": 7,
    "studies": 7,
    "identify": 7,
    "optimize": 8,
    "tradeoff": 8,
    # the semi-active optimum and the benchmark of laws (it runs the optimiser, and a
    # study's Dask check): imported only by report, cli
    "benchmark": 9,
    "bench": 8,
    "report": 10,
    "hil": 9,
    "monitor": 11,
    "cli": 12,
    "__main__": 14,  # ``python -m mrsuspension``: runs the CLI
    "": 13,  # the package's __init__ (curated public API)
}

#: (importing module, imported top-level package) pairs that go upward today
KNOWN_UPWARD: set[tuple[str, str]] = set()

#: import cycles between modules today (each a set of modules)
KNOWN_CYCLES: set[frozenset[str]] = set()

#: packages whose layering is checked with no exception (the controller work's scope)
CLEAN = ("control", "vehicle", "engine")


def _module_name(path: Path) -> str:
    parts = path.relative_to(SRC).with_suffix("").parts
    if parts[-1] == "__init__":
        parts = parts[:-1]
    return ".".join(parts)


def _is_type_checking(node: ast.If) -> bool:
    test = node.test
    return (isinstance(test, ast.Name) and test.id == "TYPE_CHECKING") or (
        isinstance(test, ast.Attribute) and test.attr == "TYPE_CHECKING"
    )


def _imports(tree: ast.AST, module: str, is_package: bool) -> Iterator[list[str]]:
    """Per import statement outside TYPE_CHECKING blocks, the absolute names it may load.

    ``from a.b import c`` gives ``["a.b", "a.b.c"]``: ``c`` may be a submodule.
    """
    for node in ast.iter_child_nodes(tree):
        if isinstance(node, ast.If) and _is_type_checking(node):
            yield from (n for s in node.orelse for n in _imports(s, module, is_package))
            continue
        if isinstance(node, ast.Import):
            yield from ([alias.name] for alias in node.names)
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = module.split(".")
                if not is_package:
                    base = base[:-1]
                base = base[: len(base) - node.level + 1]
                target = ".".join(base + ([node.module] if node.module else []))
            else:
                target = node.module or ""
            yield [target, *(f"{target}.{alias.name}" for alias in node.names)]
        else:
            yield from _imports(node, module, is_package)


def _resolve(name: str, files: dict[str, Path]) -> str:
    """The longest module of the package that ``name`` refers to ("" if none)."""
    while name and name not in files:
        name = name.rpartition(".")[0]
    return name


def _graph() -> dict[str, set[str]]:
    files = {_module_name(p): p for p in (SRC / PACKAGE).rglob("*.py")}
    graph: dict[str, set[str]] = defaultdict(set)
    for module, path in files.items():
        tree = ast.parse(path.read_text(encoding="utf-8"))
        for names in _imports(tree, module, path.name == "__init__.py"):
            base, *members = names
            # ``from package import submodule`` depends on the submodule, not on the
            # package's __init__ (which any import of a submodule runs anyway)
            subs = [m for m in members if m in files]
            targets = subs if subs else [_resolve(base, files)]
            for target in targets:
                # a module's own ancestors are imported with it anyway
                if target and target != module and not module.startswith(target + "."):
                    graph[module].add(target)
        graph.setdefault(module, set())
    return graph


def _top(module: str) -> str:
    parts = module.split(".")
    return parts[1] if len(parts) > 1 else ""


@functools.cache
def graph() -> dict[str, set[str]]:
    """The package's import graph (parsed once, when a test first needs it, not at
    collection: every pytest process collects this module)."""
    return _graph()


def _upward() -> set[tuple[str, str]]:
    out = set()
    for module, targets in graph().items():
        for target in targets:
            if LAYERS[_top(target)] > LAYERS[_top(module)]:
                out.add((module, _top(target)))
    return out


def _cycles() -> set[frozenset[str]]:
    """Strongly connected components of more than one module (Tarjan)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    found: set[frozenset[str]] = set()
    counter = [0]

    def visit(v: str) -> None:
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on_stack.add(v)
        for w in graph()[v]:
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            component = set()
            while True:
                w = stack.pop()
                on_stack.discard(w)
                component.add(w)
                if w == v:
                    break
            if len(component) > 1:
                found.add(frozenset(component))

    for v in sorted(graph()):
        if v not in index:
            visit(v)
    return found


def test_every_top_level_module_has_a_layer() -> None:
    missing = sorted({_top(m) for m in graph()} - set(LAYERS))
    assert not missing, f"give these a rank in LAYERS: {missing}"


def test_no_module_imports_a_higher_layer() -> None:
    new = sorted(_upward() - KNOWN_UPWARD)
    assert not new, f"upward imports (module, package): {new}"


def test_no_import_cycles_between_modules() -> None:
    new = sorted(sorted(c) for c in _cycles() - KNOWN_CYCLES)
    assert not new, f"import cycles: {new}"


def test_known_exceptions_still_exist() -> None:
    """A fixed offence must leave the exception lists (they only shrink)."""
    assert _upward() >= KNOWN_UPWARD, sorted(KNOWN_UPWARD - _upward())
    assert _cycles() >= KNOWN_CYCLES, [sorted(c) for c in KNOWN_CYCLES - _cycles()]


@pytest.mark.parametrize("package", CLEAN)
def test_controller_vehicle_and_engine_layers_have_no_exception(package: str) -> None:
    offences = [(m, t) for m, t in _upward() | KNOWN_UPWARD if _top(m) == package]
    cycles = [sorted(c) for c in _cycles() if any(_top(m) == package for m in c)]
    assert not offences
    assert not cycles


@pytest.mark.parametrize("package", ["control", "vehicle"])
def test_control_and_vehicle_do_not_import_the_engine(package: str) -> None:
    users = sorted(
        m
        for m, targets in graph().items()
        if _top(m) == package and any(_top(t) == "engine" for t in targets)
    )
    assert not users
