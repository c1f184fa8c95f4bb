"""The HTML report: every registered chapter's figures (PNG + SVG), tables and provenance on
one index page.

:func:`build_report` takes the chapters from the registry
(:mod:`mrsuspension.report.chapters`), runs what they all need in one process pool
(:func:`~mrsuspension.report.families.build_all`) and hands each chapter's ``build`` a
:class:`~mrsuspension.report.toolkit.Context` holding the pool's results.
"""

from __future__ import annotations

import functools
import html
import json
import platform
import time
from collections.abc import Callable, Iterable, Sequence
from pathlib import Path
from typing import Any

from mrsuspension.report.merge import (
    PART_ORDER,
    merge_manifest,
    mixed_note,
    part_files,
    previous_report,
    wrap_part,
)
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
    beyond: bool = False,
    formats: Sequence[str] = ("png",),
    check: bool = False,
    vehicles: bool = False,
    benchmark: bool = False,
) -> Any:
    """Run the jobs of ``chapters`` (and the findings scorecard's runs, and the "beyond"
    section) in one process pool (see families.build_all); the pool's results
    (``families.Built``)."""
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
    if beyond:  # its trade-off and optimiser runs, beside the chapters' (first: the longest)
        from mrsuspension.report import beyond as section

        calls = {
            "beyond": (
                _build_beyond,
                (section.build, out / "beyond", quick, tuple(formats), check),
            ),
            **calls,
        }
    if vehicles:  # the full-car runs: one task beside the chapters'
        from mrsuspension.report import vehicles as section_v

        calls = {
            "vehicles": (
                _build_beyond,
                (section_v.build, out / "vehicles", quick, tuple(formats), check),
            ),
            **calls,
        }
    if benchmark:  # the benchmark of semi-active laws: one task beside the chapters'
        from mrsuspension.report import benchmark as section_b

        calls = {
            "benchmark": (
                _build_beyond,
                (section_b.build, out / "benchmark", quick, tuple(formats), check),
            ),
            **calls,
        }
    # the findings scorecard's units join the pool's, listed once the pool has started
    # (its history runs are one more task)
    later = functools.partial(_findings_work, quick) if findings else None
    return build_all(
        figures,
        tables,
        quick,
        out,
        specials=specials,
        calls=calls,
        later=later,
        progress=progress,
        formats=formats,
        check=check,
    )


def _findings_work(quick: bool) -> tuple[list[Any], dict[str, Any]]:
    """The findings scorecard's units and its history runs (a call), for ``build_all``'s
    ``later``: importing the claims takes the parent about 0.6 s."""
    from mrsuspension.report import findings as scorecard

    history = (scorecard.run_payloads, (scorecard.history_keys(quick), 1))
    return scorecard.units(quick), {"findings history": history}


def _build_beyond(
    build: Callable[..., tuple[str, dict[str, Any]]],
    folder: Path,
    quick: bool,
    formats: Sequence[str],
    check: bool,
) -> tuple[str, dict[str, Any]]:
    """A section ("beyond", "vehicles", "benchmark") as a task of the report's pool (no progress)."""
    return build(folder, quick, lambda _msg: None, formats=formats, check=check)


def _chapter_timing(figures: Sequence[dict[str, Any]], build_time: float) -> dict[str, Any]:
    """A chapter's timing for the manifest: its figures' draw and run times, when its last
    figure was done (seconds after the pool started: figures are drawn as their runs
    finish, in parallel across chapters) and how long writing its section took."""
    done = [f["done at [s]"] for f in figures if "done at [s]" in f]
    return {
        "figures": len(figures),
        "last figure done at [s]": round(max(done), 2) if done else None,
        "render wall time [s]": round(sum(f.get("render time [s]", 0.0) for f in figures), 2),
        "render cpu time [s]": round(sum(f.get("render cpu time [s]", 0.0) for f in figures), 2),
        "simulation time [s]": round(sum(f.get("simulation time [s]", 0.0) for f in figures), 2),
        "section build time [s]": round(build_time, 3),
    }


def build_report(
    out: str | Path = "results",
    *,
    chapters: Iterable[int | str] | None = None,
    quick: bool = False,
    progress: Callable[[str], None] | None = None,
    svg: bool = False,
    check_layout: bool = False,
    previous: str | Path | None = None,
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
        Coarser grids for a fast check.
    progress : callable, optional
        Called with a message before each step.
    svg : bool
        Also write every figure as SVG (PNG always; SVG costs about as much again as the
        drawing, so only on request).
    check_layout : bool
        Record each figure's ``layout issues`` (overlapping texts, a legend over the
        data, no title; :func:`~mrsuspension.report.legibility.layout_issues`) in
        ``manifest.json``; the report's tests require none.
    previous : path, optional
        A report folder to merge with (:mod:`mrsuspension.report.merge`): its parts not
        rebuilt here are copied into ``out`` and kept in the index and the manifest.

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
    vehicles = "vehicles" in sections
    benchmark = "benchmark" in sections
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    say = progress or (lambda _msg: None)
    start = time.perf_counter()
    bodies: list[str] = []
    manifest: dict[str, Any] = {"version": __version__, "chapters": {}}
    formats = ("png", "svg") if svg else ("png",)
    built = _build(
        chosen,
        out,
        quick,
        say,
        findings=findings,
        beyond=beyond,
        formats=formats,
        check=check_layout,
        vehicles=vehicles,
        benchmark=benchmark,
    )
    manifest["pool"] = built.timing
    if findings:
        from mrsuspension.report import findings as scorecard

        body, info = scorecard.build(
            out, quick, say, payloads=built.payloads, runs=built.calls["findings history"]
        )
        bodies.append(wrap_part("findings", body))
        manifest["findings"] = info
    for c in chosen:
        context = Context(c, out / f"chapter{c}", quick, built, say)
        t0 = time.perf_counter()
        body, info = chapter(c).build(context)
        bodies.append(wrap_part(f"ch{c}", body))
        info["timing"] = _chapter_timing(info.get("figures", []), time.perf_counter() - t0)
        manifest["chapters"][str(c)] = info
    if beyond:
        body, info = built.calls["beyond"]
        bodies.append(wrap_part("beyond", body))
        info["timing"] = _chapter_timing(info["figures"], 0.0)
        info["timing"]["wall time [s]"] = round(built.call_times["beyond"], 2)
        manifest["beyond"] = info
    if vehicles:
        body, info = built.calls["vehicles"]
        bodies.append(wrap_part("vehicles", body))
        info["timing"] = _chapter_timing(info["figures"], 0.0)
        info["timing"]["wall time [s]"] = round(built.call_times["vehicles"], 2)
        manifest["vehicles"] = info
    if benchmark:
        body, info = built.calls["benchmark"]
        bodies.append(wrap_part("benchmark", body))
        info["timing"] = _chapter_timing(info["figures"], 0.0)
        info["timing"]["wall time [s]"] = round(built.call_times["benchmark"], 2)
        manifest["benchmark"] = info
    elapsed = time.perf_counter() - start
    manifest["run_time_s"] = round(elapsed, 2)
    keys = [*(["findings"] if findings else []), *(f"ch{c}" for c in chosen)]
    keys += ["beyond"] if beyond else []
    keys += ["vehicles"] if vehicles else []
    keys += ["benchmark"] if benchmark else []
    built_at = time.strftime("%Y-%m-%dT%H:%M:%S%z")
    manifest["parts"] = {
        k: {"built": built_at, "quick": quick, "version": __version__} for k in keys
    }
    note = ""
    if previous is not None:
        manifest, bodies, keys = _merged(
            Path(previous), out, manifest, dict(zip(keys, bodies, strict=True))
        )
        note = mixed_note(manifest["parts"])
    (out / "manifest.json").write_text(json.dumps(manifest, indent=2, default=float) + "\n")
    toc = "".join(f"<li><a href='#{k}'>{html.escape(_TITLES.get(k, k))}</a></li>" for k in keys)
    page = (
        "<!doctype html><html><head><meta charset='utf-8'>"
        "<title>mrsuspension report</title>"
        f"<style>{_STYLE}</style></head><body>"
        "<h1>mrsuspension: reproduction of the dissertation's analyses</h1>"
        f"<p class='meta'>mrsuspension {html.escape(__version__)}, Python "
        f"{platform.python_version()}, generated {time.strftime('%Y-%m-%d %H:%M:%S')} in "
        f"{elapsed:.1f} s{' (quick mode)' if quick else ''}. Raw numbers: "
        "<a href='manifest.json'>manifest.json</a>.</p>"
        f"{note}<ul>{toc}</ul>" + "".join(bodies) + "</body></html>"
    )
    index = out / "index.html"
    index.write_text(page)
    return index


_TITLES = {
    "findings": "Findings scorecard",
    "beyond": "Beyond the dissertation",
    "vehicles": "Beyond the quarter car",
    "benchmark": "Benchmark of semi-active laws",
}
_TITLES.update({f"ch{n}": f"Chapter {n}" for n in range(1, 10)})


def _merged(
    previous: Path, out: Path, manifest: dict[str, Any], bodies: dict[str, str]
) -> tuple[dict[str, Any], list[str], list[str]]:
    """Merge this run's parts into the report in ``previous`` (the parts not rebuilt are
    copied into ``out``): the manifest, the sections in page order and their keys."""
    from mrsuspension._output import carry_over

    old_manifest, old_sections = previous_report(previous)
    kept = [k for k in old_sections if k not in bodies]
    skip = {"index.html", "manifest.json", *(f for k in bodies for f in part_files(k))}
    skip |= {p.name for p in out.iterdir()}  # never over what this run wrote
    carry_over(previous, out, skip=skip)
    sections = {**{k: wrap_part(k, old_sections[k]) for k in kept}, **bodies}
    keys = sorted(sections, key=lambda k: PART_ORDER.index(k) if k in PART_ORDER else 99)
    merged = merge_manifest(old_manifest, manifest, bodies, kept)
    return merged, [sections[k] for k in keys], keys
