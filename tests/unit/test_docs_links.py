"""Every documentation link a user sees resolves after ``pip install`` (issue 31).

Help texts, notes, messages and report pages name documentation pages by their online
address (:func:`mrsuspension._docs.doc`), never by a ``docs/...`` path of a source
checkout (a wheel has none); every page they name exists; the address is the project's.
"""

from __future__ import annotations

import ast
import re
import tomllib
from pathlib import Path

from mrsuspension._docs import DOCS_URL, doc

ROOT = Path(__file__).resolve().parents[2]
SRC = ROOT / "src" / "mrsuspension"
RELATIVE = re.compile(r"(?<![/\w])docs/[\w-]+\.md")
#: text that writes a page of docs/ itself, where sibling pages link relatively
DOCS_WRITERS = {"src/mrsuspension/report/__init__.py"}  # docs/report.md
CALL = re.compile(r"\bdoc\(\s*['\"]([\w-]+)['\"]")


def _docstrings(tree: ast.AST) -> set[int]:
    out = set()
    for node in ast.walk(tree):
        body = getattr(node, "body", None)
        if (
            isinstance(node, ast.Module | ast.FunctionDef | ast.AsyncFunctionDef | ast.ClassDef)
            and body
            and isinstance(body[0], ast.Expr)
            and isinstance(body[0].value, ast.Constant)
        ):
            out.add(id(body[0].value))
    return out


def test_no_user_facing_text_names_a_checkout_path() -> None:
    offenders = []
    for path in sorted(SRC.rglob("*.py")):
        if str(path.relative_to(ROOT)) in DOCS_WRITERS:
            continue
        tree = ast.parse(path.read_text())
        skip = _docstrings(tree)
        for node in ast.walk(tree):
            text = node.value if isinstance(node, ast.Constant) else None
            if isinstance(text, str) and id(node) not in skip and RELATIVE.search(text):
                offenders.append(f"{path.relative_to(ROOT)}:{node.lineno}")
    assert not offenders, f"use mrsuspension._docs.doc(...) instead of docs/...: {offenders}"


def test_every_linked_page_exists_and_the_address_is_the_projects() -> None:
    pages = {m for p in SRC.rglob("*.py") for m in CALL.findall(p.read_text())}
    assert {"scenarios", "hil", "optimisation"} <= pages
    for page in pages:
        assert (ROOT / "docs" / f"{page}.md").is_file(), page
    urls = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]["urls"]
    assert DOCS_URL.replace("/blob/", "/tree/") == urls["Documentation"]
    assert doc("hil", "endings").endswith("/docs/hil.md#endings")
