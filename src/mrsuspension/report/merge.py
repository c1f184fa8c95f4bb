"""Partial reports merged into an existing one (``mrsus reproduce --chapters``).

A report's index page holds one section per *part* (``findings``, ``ch2`` ... ``ch6``,
``beyond``), each between ``<!-- mrsus-part:KEY -->`` and ``<!-- /mrsus-part:KEY -->``;
``manifest.json`` records under ``parts`` when, in which mode and by which version each
part was built. Rebuilding some chapters into a folder that holds a report keeps the
other parts: their files are carried over, their sections and manifest entries kept,
and the index says when the parts come from runs in different modes or versions.
"""

from __future__ import annotations

import html
import json
import re
from collections.abc import Iterable, Mapping
from pathlib import Path
from typing import Any

__all__ = [
    "PART_ORDER",
    "merge_manifest",
    "mixed_note",
    "part_files",
    "previous_report",
    "wrap_part",
]

#: the parts of a report in page order (chapters between findings and beyond)
PART_ORDER: tuple[str, ...] = (
    "findings",
    *(f"ch{n}" for n in range(1, 10)),
    "beyond",
    "vehicles",
    "benchmark",
)

_MARKED = re.compile(
    r"<!-- mrsus-part:(?P<key>[\w-]+) -->(?P<body>.*?)<!-- /mrsus-part:(?P=key) -->", re.S
)
# reports written before the markers: each section starts with its <h2 id=...>
_HEADING = re.compile(r"<h2 id='(?P<key>findings|ch\d+|beyond|vehicles|benchmark)'>")


def wrap_part(key: str, body: str) -> str:
    """A part's section with the markers a later merge finds it by.

    Examples
    --------
    >>> wrap_part("ch3", "<h2 id='ch3'>Chapter 3</h2>")
    "<!-- mrsus-part:ch3 --><h2 id='ch3'>Chapter 3</h2><!-- /mrsus-part:ch3 -->"
    """
    return f"<!-- mrsus-part:{key} -->{body}<!-- /mrsus-part:{key} -->"


def part_files(key: str) -> tuple[str, ...]:
    """The entries of a report folder that belong to part ``key`` (replaced on a rebuild).

    Examples
    --------
    >>> part_files("ch3"), part_files("findings"), part_files("beyond")
    (('chapter3',), ('findings.csv',), ('beyond',))
    """
    if key.startswith("ch"):
        return (f"chapter{key[2:]}",)
    if key == "findings":
        return ("findings.csv",)
    return (key,)


def _sections(page: str) -> dict[str, str]:
    """The part sections of an index page: marked ones, else split at the headings."""
    marked = {m["key"]: m["body"] for m in _MARKED.finditer(page)}
    if marked:
        return marked
    starts = [(m.start(), m["key"]) for m in _HEADING.finditer(page)]
    end = page.rfind("</body>")
    bounds = [s for s, _ in starts[1:]] + [end if end >= 0 else len(page)]
    return {key: page[s:e] for (s, key), e in zip(starts, bounds, strict=True)}


def previous_report(folder: str | Path) -> tuple[dict[str, Any], dict[str, str]]:
    """The manifest and the part sections (key -> HTML) of the report in ``folder``.

    A part the manifest lists whose section cannot be found in the page (a hand-edited
    index) gets a short section linking its figures, so that nothing kept is unlinked.

    Examples
    --------
    >>> import tempfile
    >>> with tempfile.TemporaryDirectory() as d:
    ...     _ = Path(d, "manifest.json").write_text('{"chapters": {"2": {}}}')
    ...     _ = Path(d, "index.html").write_text(
    ...         "<body>" + wrap_part("ch2", "<h2 id='ch2'>Two</h2>") + "</body>")
    ...     manifest, sections = previous_report(d)
    >>> sections
    {'ch2': "<h2 id='ch2'>Two</h2>"}
    """
    folder = Path(folder)
    try:
        manifest = json.loads((folder / "manifest.json").read_text())
    except (OSError, ValueError):
        manifest = {}
    if not isinstance(manifest, dict):
        manifest = {}
    try:
        page = (folder / "index.html").read_text()
    except OSError:
        page = ""
    sections = _sections(page)
    for key in _manifest_parts(manifest):
        if key not in sections:
            sections[key] = _stub(folder, key)
    return manifest, sections


def _manifest_parts(manifest: Mapping[str, Any]) -> list[str]:
    keys = [f"ch{c}" for c in manifest.get("chapters", {})]
    keys += [k for k in ("findings", "beyond") if k in manifest]
    return keys


def _stub(folder: Path, key: str) -> str:
    """A section for a kept part whose section was lost: links to its figures."""
    links = []
    for entry in part_files(key):
        path = folder / entry
        files = sorted(path.rglob("*.png")) if path.is_dir() else [path] if path.exists() else []
        links += [p.relative_to(folder).as_posix() for p in files]
    items = "".join(f"<li><a href='{html.escape(a)}'>{html.escape(a)}</a></li>" for a in links)
    return (
        f"<h2 id='{key}'>{html.escape(key)} (kept from the previous report)</h2>"
        f"<p class='meta'>Its section was not found in the previous index page; its files:</p>"
        f"<ul>{items}</ul>"
    )


def merge_manifest(
    old: Mapping[str, Any], new: Mapping[str, Any], rebuilt: Iterable[str], kept: Iterable[str]
) -> dict[str, Any]:
    """``new`` (this run's manifest) with the entries of the ``kept`` parts taken from
    ``old``, and ``parts`` recording the run each part came from.

    Examples
    --------
    >>> old = {"version": "0.1", "chapters": {"2": {"n": 1}, "3": {"n": 2}},
    ...        "parts": {"ch2": {"quick": False}, "ch3": {"quick": False}}}
    >>> new = {"version": "0.2", "chapters": {"3": {"n": 9}},
    ...        "parts": {"ch3": {"quick": True}}}
    >>> merged = merge_manifest(old, new, ["ch3"], ["ch2"])
    >>> merged["chapters"], merged["parts"]
    ({'2': {'n': 1}, '3': {'n': 9}}, {'ch2': {'quick': False}, 'ch3': {'quick': True}})
    """
    merged = dict(new)
    chapters = dict(new.get("chapters", {}))
    parts = dict(new.get("parts", {}))
    old_parts = old.get("parts", {})
    for key in kept:
        if key.startswith("ch"):
            if key[2:] in old.get("chapters", {}):
                chapters[key[2:]] = old["chapters"][key[2:]]
        elif key in old:
            merged[key] = old[key]
        # a report made before parts were recorded: its run is the manifest's
        parts[key] = old_parts.get(key, {"version": old.get("version"), "quick": None})
    merged["chapters"] = {k: chapters[k] for k in sorted(chapters, key=int)}
    merged["parts"] = {k: parts[k] for k in sorted(parts, key=_page_position)}
    return merged


def _page_position(key: str) -> int:
    return PART_ORDER.index(key) if key in PART_ORDER else len(PART_ORDER)


def mixed_note(parts: Mapping[str, Mapping[str, Any]]) -> str:
    """A paragraph for the index when the parts come from runs in different modes or
    versions ('' when they do not).

    Examples
    --------
    >>> mixed_note({"ch2": {"quick": False, "version": "1"},
    ...             "ch3": {"quick": True, "version": "1"}})[:60]
    "<p class='meta'><b>Merged report:</b> its parts come from ru"
    """
    modes = {_mode(p.get("quick")) for p in parts.values()}
    versions = {str(p.get("version")) for p in parts.values()}
    if len(modes) <= 1 and len(versions) <= 1:
        return ""
    rows = "".join(
        f"<li>{html.escape(key)}: {_mode(p.get('quick'))} mode, mrsuspension "
        f"{html.escape(str(p.get('version')))}, built {html.escape(str(p.get('built', 'unknown')))}"
        "</li>"
        for key, p in parts.items()
    )
    what = " and ".join(
        w for w, differ in (("modes", len(modes) > 1), ("versions", len(versions) > 1)) if differ
    )
    return (
        f"<p class='meta'><b>Merged report:</b> its parts come from runs in different {what} "
        f"(rebuild them together for comparable numbers):</p><ul class='meta'>{rows}</ul>"
    )


def _mode(quick: object) -> str:
    return "unknown" if quick is None else "quick" if quick else "full"
