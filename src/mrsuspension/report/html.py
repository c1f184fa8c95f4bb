"""The HTML report: every registered chapter's figures (PNG + SVG), tables and provenance on
one index page.

:func:`build_report` takes the chapters from the registry
(:mod:`mrsuspension.report.chapters`), runs what they all need in one process pool
(:func:`~mrsuspension.report.families.build_all`) and hands each chapter's ``build`` a
:class:`~mrsuspension.report.toolkit.Context` holding the pool's results.
"""

from __future__ import annotations

import html
import json
import platform
import time
from collections.abc import Callable, Iterable, Sequence
from pathlib import Path
from typing import Any

from mrsuspension.report.toolkit import Context, FigureRecord, shock_table_html

__all__ = ["FigureRecord", "build_report", "shock_table_html"]


_STYLE = """
body{font-family:system-ui,sans-serif;max-width:1100px;margin:2em auto;padding:0 1em;color:#222}
h1{font-size:1.6em} h2{border-bottom:1px solid #ccc;padding-bottom:.2em;margin-top:2em}
figure{margin:1.5em 0;border:1px solid #eee;padding:.5em} figure img{max-width:100%}
figcaption{font-size:.9em;color:#444} table{border-collapse:collapse;font-size:.85em;margin:.5em 0}
td,th{border:1px solid #ccc;padding:.2em .5em;text-align:right} th{background:#f4f4f4}
td.l,th.l{text-align:left} code{background:#f4f4f4;padding:0 .2em} .meta{color:#666;font-size:.85em}
td.green{background:#d4edda} td.amber{background:#ffe8b3} td.red{background:#f8d0d0}
span.green,span.amber,span.red{padding:0 .4em;border:1px solid #ccc}
span.green{background:#d4edda} span.amber{background:#ffe8b3} span.red{background:#f8d0d0}
"""


def _build(
    chapters: Sequence[int],
    out: Path,
    quick: bool,
    progress: Callable[[str], None],
    findings: bool = False,
) -> Any:
    """Run the jobs of ``chapters`` (and the findings scorecard's runs) in one process pool
    (see families.build_all); the pool's results (``families.Built``)."""
    from mrsuspension.report.chapters import chapter
    from mrsuspension.report.families import build_all

    figures: dict[str, Any] = {}
    tables: list[Any] = []
    specials: list[Any] = []
    calls: dict[str, Any] = {}
    for c in chapters:
        job = chapter(c).jobs(quick)
        figures.update(job.figures)
        tables.extend(job.tables)
        specials.extend(job.specials)
        calls.update(job.calls)
    for sub in {*figures, *(s[0] for s in specials)}:
        (out / sub).mkdir(parents=True, exist_ok=True)
    extra = []
    if findings:
        from mrsuspension.report import findings as scorecard

        extra = scorecard.units(quick)
    return build_all(
        figures,
        tables,
        quick,
        out,
        specials=specials,
        calls=calls,
        units=extra,
        progress=progress,
    )


def build_report(
    out: str | Path = "results",
    *,
    chapters: Iterable[int | str] | None = None,
    quick: bool = False,
    progress: Callable[[str], None] | None = None,
) -> Path:
    """Regenerate the dissertation's analyses into ``out/index.html``.

    Parameters
    ----------
    out : path
        Output folder (created). Figures go to ``out/chapterN/``.
    chapters : iterable of int, "findings" or "beyond", optional
        Chapters to build (default: every chapter of the registry,
        :data:`mrsuspension.report.chapters.CHAPTERS`, the findings scorecard,
        :mod:`mrsuspension.report.findings`, and the "beyond the dissertation" section,
        :mod:`mrsuspension.report.beyond`; :func:`mrsuspension.report.chapters.choices`).
    quick : bool
        Coarser grids for a fast check, PNG only (else PNG and SVG).
    progress : callable, optional
        Called with a message before each step.

    Returns
    -------
    pathlib.Path
        The index page.
    """
    from mrsuspension import __version__
    from mrsuspension.report.chapters import chapter, resolve

    chosen, sections = resolve(chapters)
    beyond = "beyond" in sections
    findings = "findings" in sections
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    say = progress or (lambda _msg: None)
    start = time.perf_counter()
    bodies: list[str] = []
    manifest: dict[str, Any] = {"version": __version__, "chapters": {}}
    built = _build(chosen, out, quick, say, findings=findings)
    manifest["pool"] = built.timing
    if findings:
        from mrsuspension.report import findings as scorecard

        body, info = scorecard.build(out, quick, say, payloads=built.payloads)
        bodies.append(body)
        manifest["findings"] = info
    for c in chosen:
        context = Context(c, out / f"chapter{c}", quick, built, say)
        body, info = chapter(c).build(context)
        bodies.append(body)
        manifest["chapters"][str(c)] = info
    if beyond:
        from mrsuspension.report import beyond as beyond_section

        body, info = beyond_section.build(out / "beyond", quick, say)
        bodies.append(body)
        manifest["beyond"] = info
    if "vehicles" in sections:
        from mrsuspension.report import vehicles as vehicles_section

        body, info = vehicles_section.build(out / "vehicles", quick, say)
        bodies.append(body)
        manifest["vehicles"] = info
    elapsed = time.perf_counter() - start
    manifest["run_time_s"] = round(elapsed, 2)
    (out / "manifest.json").write_text(json.dumps(manifest, indent=2, default=float) + "\n")
    toc = "<li><a href='#findings'>Findings scorecard</a></li>" if findings else ""
    toc += "".join(f"<li><a href='#ch{c}'>Chapter {c}</a></li>" for c in chosen)
    toc += "<li><a href='#beyond'>Beyond the dissertation</a></li>" if beyond else ""
    toc += (
        "<li><a href='#vehicles'>Beyond the quarter car</a></li>" if "vehicles" in sections else ""
    )
    page = (
        "<!doctype html><html><head><meta charset='utf-8'>"
        "<title>mrsuspension report</title>"
        f"<style>{_STYLE}</style></head><body>"
        "<h1>mrsuspension: reproduction of the dissertation's analyses</h1>"
        f"<p class='meta'>mrsuspension {html.escape(__version__)}, Python "
        f"{platform.python_version()}, generated {time.strftime('%Y-%m-%d %H:%M:%S')} in "
        f"{elapsed:.1f} s{' (quick mode)' if quick else ''}. Raw numbers: "
        "<a href='manifest.json'>manifest.json</a>.</p>"
        f"<ul>{toc}</ul>" + "".join(bodies) + "</body></html>"
    )
    index = out / "index.html"
    index.write_text(page)
    return index
