"""Links to the documentation that resolve for every user, also after ``pip install``.

A wheel ships no ``docs/`` folder, so help texts, notes and messages name a page by its
online address (the project's ``Documentation`` URL in ``pyproject.toml``), never by a
path in a source checkout.

Examples
--------
>>> doc("scenarios")
'https://github.com/mrsuspension/mrsuspension/blob/main/docs/scenarios.md'
>>> doc("model", "section-9")
'https://github.com/mrsuspension/mrsuspension/blob/main/docs/model.md#section-9'
"""

from __future__ import annotations

__all__ = ["DOCS_URL", "doc"]

#: where the pages of ``docs/`` are read online (``pyproject.toml`` [project.urls])
DOCS_URL = "https://github.com/mrsuspension/mrsuspension/blob/main/docs"


def doc(page: str, anchor: str | None = None) -> str:
    """The online address of ``docs/<page>.md`` (and of a heading's ``anchor``)."""
    return f"{DOCS_URL}/{page}.md" + (f"#{anchor}" if anchor else "")
