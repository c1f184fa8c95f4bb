"""The HTML report: figures (PNG + SVG), tables and provenance on one index page."""

from __future__ import annotations

import html
import json
import platform
import time
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from mrsuspension.errors import ValidationError

__all__ = ["FigureRecord", "build_report", "shock_table_html"]


@dataclass
class FigureRecord:
    """A figure with its number, caption, and the numbers behind it."""

    number: str
    title: str
    caption: str
    figure: Any  # matplotlib.figure.Figure
    data: dict[str, Any] = field(default_factory=dict)
    files: list[str] = field(default_factory=list)

    @property
    def slug(self) -> str:
        """File stem, e.g. ``fig_2_3``."""
        return "fig_" + self.number.replace(".", "_")

    def save(self, folder: Path, formats: Sequence[str] = ("png", "svg")) -> list[Path]:
        """Write the figure in each format and close it."""
        import matplotlib.pyplot as plt

        folder.mkdir(parents=True, exist_ok=True)
        self.figure.suptitle(f"Fig. {self.number}: {self.title}", fontsize=10)
        paths = []
        for fmt in formats:
            path = folder / f"{self.slug}.{fmt}"
            self.figure.savefig(path, dpi=110)
            paths.append(path)
        plt.close(self.figure)
        self.files = [p.name for p in paths]
        return paths


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

#: The legend of the shock tables' cell colours (families.AGREEMENT_BANDS)
_LEGEND = (
    "<p class='meta'>Each measure: ours | the dissertation's | ours/theirs (DTR: ours - "
    "theirs). <span class='green'>within 10 %</span> <span class='amber'>within 25 %"
    "</span> <span class='red'>beyond 25 %</span>; DTR by the absolute difference: within "
    "0.025, within 0.05, beyond.</p>"
)


def _table(rows: Sequence[dict[str, Any]], fmt: str = "{:.4g}") -> str:
    if not rows:
        return ""
    keys = list(rows[0])
    head = "".join(f"<th>{html.escape(str(k))}</th>" for k in keys)
    body = []
    for r in rows:
        cells = []
        for k in keys:
            v = r[k]
            text = fmt.format(v) if isinstance(v, float) else str(v)
            cls = "" if isinstance(v, int | float) else ' class="l"'
            cells.append(f"<td{cls}>{html.escape(text)}</td>")
        body.append("<tr>" + "".join(cells) + "</tr>")
    return f"<table><tr>{head}</tr>{''.join(body)}</table>"


def table_2_1_rows(quick: bool) -> list[dict[str, Any]]:
    """Table 2.1's test matrix on the symmetric model (both frequency bands), sorted."""
    from mrsuspension.characterisation import characterise, table_2_1
    from mrsuspension.report import ch2

    conds = table_2_1() if not quick else table_2_1(frequencies=[0.5, 1.5, 5.0, 15.0])
    result = characterise(ch2.band_model(0.5), [c for c in conds if c.frequency <= 5.0])
    result_hi = characterise(ch2.band_model(7.5), [c for c in conds if c.frequency > 5.0])
    rows: list[dict[str, Any]] = result.summary_rows() + result_hi.summary_rows()
    rows.sort(key=lambda r: (r["amplitude [m]"], r["frequency [Hz]"], r["current [A]"]))
    return rows


def _jobs_2(quick: bool) -> dict[str, Any]:
    from mrsuspension.report import ch2

    return {
        "specials": [("chapter2", b, None) for b in ch2.CHAPTER_2_FIGURES],
        "calls": {"table 2.1": (table_2_1_rows, (quick,))},
    }


def _chapter_2(
    folder: Path, quick: bool, progress: Callable[[str], None]
) -> tuple[str, dict[str, Any]]:
    from mrsuspension import parameters
    from mrsuspension.errata import ERRATA

    built = _prebuilt(2, folder.parent, quick, progress)
    sections, records = _figure_sections(2, built, folder)
    manifest: dict[str, Any] = {"figures": records, "tables": []}
    rows = built.calls["table 2.1"]
    import csv

    folder.mkdir(parents=True, exist_ok=True)
    with (folder / "table_2_1_model.csv").open("w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    manifest["tables"].append(
        {"number": "2.1", "file": "chapter2/table_2_1_model.csv", "rows": len(rows)}
    )
    # parameter tables
    ptables = []
    for name in ("wang-symmetric-low", "wang-symmetric-high", "wang-asymmetric"):
        p = parameters.get(name)
        ptables.append(
            f"<h3>{html.escape(name)} (Table {p.table})</h3><p class='meta'>{html.escape(p.source)}</p>"
            + _table(
                [{"parameter": k, "value": v, "unit": p.units.get(k, "")} for k, v in p.items()]
            )
        )
    errata = _table(
        [
            {
                "#": e.number,
                "where": e.location,
                "dissertation": e.printed,
                "mrsuspension": e.correction,
            }
            for e in ERRATA
        ]
    )
    body = (
        "<h2 id='ch2'>Chapter 2: characterisation and modelling of the MR damper</h2>"
        + "".join(sections)
        + f"<h3>Table 2.1 test matrix on the model ({len(rows)} tests)</h3>"
        "<p>Peak forces, energy per cycle and equivalent damping of every test, with the "
        "Table 2.2 set of each frequency band: "
        "<a href='chapter2/table_2_1_model.csv'>table_2_1_model.csv</a>. Tests far outside "
        "the identified velocity range (about 0.05-0.75 m/s) extrapolate the exponential "
        "transition force (2.7) and give unphysically large forces.</p>"
        + _table(
            [r for r in rows if r["current [A]"] in (0.0, 0.4)][:: 1 if quick else 2], fmt="{:.4g}"
        )
        + "<h3>Parameter sets</h3>"
        + "".join(ptables)
        + "<h3>Errata applied (MODEL_SPEC section 12)</h3>"
        + errata
    )
    return body, manifest


def _number_key(number: str) -> tuple[int, int, str]:
    """Sort key of a figure number: ``"4.3b"`` -> (4, 3, "b"); non-numeric parts last."""
    chapter, _, rest = number.partition(".")
    digits = "".join(c for c in rest if c.isdigit())
    tail = rest[len(digits) :]
    return (int(chapter) if chapter.isdigit() else 99, int(digits) if digits else 999, tail)


def _figure_sections(
    chapter: int, built: Any, folder: Path
) -> tuple[list[str], list[dict[str, Any]]]:
    """HTML and manifest records of a chapter's built figures, in figure-number order."""
    prefix = f"{folder.name}/"
    records = sorted(
        (rec for key, rec in built.figures.items() if key.startswith(prefix)),
        key=lambda r: _number_key(r["number"]),
    )
    sections = []
    for rec in records:
        slug = "fig_" + rec["number"].replace(".", "_")
        svg = (
            f' <a href="chapter{chapter}/{slug}.svg">SVG</a>'
            if f"{slug}.svg" in rec["files"]
            else ""
        )
        sections.append(
            f'<figure id="{slug}"><img src="chapter{chapter}/{slug}.png" '
            f'alt="Fig. {html.escape(rec["number"])}"><figcaption><b>Fig. '
            f"{html.escape(rec['number'])}: {html.escape(rec['title'])}.</b> "
            f"{html.escape(rec['caption'])}{svg}</figcaption></figure>"
        )
    return sections, records


def _cell(value: Any, fmt: str = "{:.3g}") -> str:
    if value is None:
        return "-"
    return fmt.format(value) if isinstance(value, float) else str(value)


def shock_table_html(tab: dict[str, Any]) -> str:
    """A shock table (:func:`~mrsuspension.report.families.shock_table`) as HTML.

    One group of three columns per measure, ours | dissertation | ratio (DTR: the
    difference), each group's cells coloured by its ``agreement`` band, then the peak
    tire force; a summary line below gives each measure's share of cells within 25 %
    (DTR: within 0.05).

    Examples
    --------
    >>> row = {"m_s (kg)": 563.0, "SDR_s model": 0.7, "SDR_s dissertation": 0.71,
    ...        "SDR_s ratio": 0.986, "SDR_s agreement": "green"}
    >>> tab = {"rows": [row], "summary": {"SDR_s": {"within": 1, "cells": 1, "share": 1.0}}}
    >>> html_text = shock_table_html(tab)
    >>> '<td class="green">0.986</td>' in html_text, "SDR_s 1/1" in html_text
    (True, True)
    """
    from mrsuspension.report.families import TABLE_MEASURES

    rows = tab["rows"]
    if not rows:
        return ""
    column = next(iter(rows[0]))
    measures = [k for k in TABLE_MEASURES if f"{k} model" in rows[0]]
    last = "DTR difference"
    extra = [
        k
        for k in rows[0]
        if k != column and not any(k.startswith(f"{m} ") for m in measures) and k != last
    ]
    top = f"<th rowspan='2' class='l'>{html.escape(column)}</th>" + "".join(
        f"<th colspan='3'>{html.escape(m)}</th>" for m in measures
    )
    top += "".join(f"<th rowspan='2'>{html.escape(k)}</th>" for k in extra)
    sub = "".join(
        "<th>ours</th><th>diss.</th><th>" + ("diff." if m == "DTR" else "ratio") + "</th>"
        for m in measures
    )
    body = []
    for r in rows:
        cells = [f"<td class='l'>{html.escape(_cell(r[column], '{:g}'))}</td>"]
        for m in measures:
            band = html.escape(str(r.get(f"{m} agreement", "")))
            third = r.get("DTR difference") if m == "DTR" else r.get(f"{m} ratio")
            for v in (r[f"{m} model"], r[f"{m} dissertation"], third):
                cells.append(f'<td class="{band}">{html.escape(_cell(v))}</td>')
        cells += [f"<td>{html.escape(_cell(r[k], '{:.4g}'))}</td>" for k in extra]
        body.append("<tr>" + "".join(cells) + "</tr>")
    summary = tab.get("summary", {})
    line = ", ".join(
        f"{m} {s['within']}/{s['cells']} ({100 * s['share']:.0f} %)" for m, s in summary.items()
    )
    return f"<table><tr>{top}</tr><tr>{sub}</tr>{''.join(body)}</table>" + (
        f"<p class='meta'>Cells within 25 % (DTR: within 0.05): {line}.</p>" if line else ""
    )


def _table_sections(
    chapter: int, tables: Sequence[dict[str, Any]], folder: Path
) -> tuple[str, list[dict[str, Any]]]:
    """Write each shock table as CSV; the HTML of all of them and their manifest entries."""
    import csv

    out = []
    parts = []
    for tab in tables:
        slug = "table_" + tab["number"].replace(".", "_")
        with (folder / f"{slug}.csv").open("w", newline="") as fh:
            w = csv.DictWriter(fh, fieldnames=list(tab["rows"][0]))
            w.writeheader()
            w.writerows(tab["rows"])
        out.append({**tab, "file": f"chapter{chapter}/{slug}.csv"})
        parts.append(
            f"<h3 id='{slug}'>Table {html.escape(tab['number'])}: {html.escape(tab['title'])}"
            f"</h3><p>{html.escape(tab['caption'])} <a href='chapter{chapter}/{slug}.csv'>"
            f"{slug}.csv</a></p>" + shock_table_html(tab)
        )
    return (_LEGEND if parts else "") + "".join(parts), out


def _jobs_3(quick: bool) -> dict[str, Any]:
    from mrsuspension.report import ch3

    return {"specials": [("chapter3", b, quick) for b in ch3.CHAPTER_3_FIGURES]}


def _chapter_3(
    folder: Path, quick: bool, progress: Callable[[str], None]
) -> tuple[str, dict[str, Any]]:
    built = _prebuilt(3, folder.parent, quick, progress)
    sections, records = _figure_sections(3, built, folder)
    body = (
        "<h2 id='ch3'>Chapter 3: semi-active control synthesis, reference model and "
        "excitations</h2>" + "".join(sections)
    )
    return body, {"figures": records, "tables": []}


def _jobs_4(quick: bool) -> dict[str, Any]:
    from mrsuspension.report import ch4

    return {"figures": {"chapter4": ch4.FIGURES}, "tables": ch4.TABLES}


_FAMILY_NOTE = (
    "<p>Every figure below is a figure family (mrsuspension.report.families): a base "
    "scenario and its variants, run once each and shared between figures and tables. Time "
    "histories: 2.5 cm harmonic at 1.5 Hz (steady state 6-7.4 s); frequency responses: "
    "two-stage swept excitation a = 2.5 cm, f_T = 2.1 Hz, 0.5-15 Hz; transients: rounded "
    "pulse mu = 3, a_m = 3.5 cm, 50 km/h; random responses: the 'rough' preset road at "
    "50 km/h, a stand-in for the dissertation's Canadian roads (which are not available), "
    "defined by its PSD level (G_d(n) = G_d(n0) (n/0.1)^-1, G_d(n0) tuned against the "
    "dissertation's DLCs). "
    "Each record in manifest.json holds the scenario of every curve and the numbers behind "
    "it; each table sets our values beside the dissertation's.{quick}</p>"
)


def _note(quick: bool) -> str:
    return _FAMILY_NOTE.format(
        quick=" Quick mode: 10 frequencies and a 0.5 ms step (0.25 ms for the inverse-model "
        "laws); PNG only."
        if quick
        else ""
    )


def _chapter_4(
    folder: Path, quick: bool, progress: Callable[[str], None]
) -> tuple[str, dict[str, Any]]:
    built = _prebuilt(4, folder.parent, quick, progress)
    sections, records = _figure_sections(4, built, folder)
    from mrsuspension.report import ch4

    tables_html, tables = _table_sections(4, [built.tables[t.number] for t in ch4.TABLES], folder)
    body = (
        "<h2 id='ch4'>Chapter 4: hi-lo semi-active MR suspension, simulation studies</h2>"
        + _note(quick)
        + "".join(sections)
        + tables_html
    )
    return body, {"figures": records, "tables": tables}


def _jobs_5(quick: bool) -> dict[str, Any]:
    from mrsuspension.report import ch5

    return {"figures": {"chapter5": ch5.FIGURES}, "tables": ch5.TABLES}


def _chapter_5(
    folder: Path, quick: bool, progress: Callable[[str], None]
) -> tuple[str, dict[str, Any]]:
    from mrsuspension.report import ch5

    built = _prebuilt(5, folder.parent, quick, progress)
    sections, records = _figure_sections(5, built, folder)
    tables_html, tables = _table_sections(5, [built.tables[t.number] for t in ch5.TABLES], folder)
    body = (
        "<h2 id='ch5'>Chapter 5: inverse-model hi-lo semi-active damping</h2>"
        + _note(quick)
        + "<p>The force gain k_d is damper.force_gain.</p>"
        + "".join(sections)
        + tables_html
    )
    return body, {"figures": records, "tables": tables}


def _jobs_6(quick: bool) -> dict[str, Any]:
    from mrsuspension.report import ch6

    return {
        "figures": {"chapter6": ch6.FIGURES},
        "tables": ch6.TABLES,
        "calls": {"comparison 6.5": (ch6.comparison_table, (quick,))},
    }


def _chapter_6(
    folder: Path, quick: bool, progress: Callable[[str], None]
) -> tuple[str, dict[str, Any]]:
    import csv

    from mrsuspension.report import ch6

    built = _prebuilt(6, folder.parent, quick, progress)
    sections, records = _figure_sections(6, built, folder)
    tables_html, tables = _table_sections(6, [built.tables[t.number] for t in ch6.TABLES], folder)
    rows = built.calls["comparison 6.5"]
    with (folder / "table_6_5_comparison.csv").open("w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    body = (
        "<h2 id='ch6'>Chapter 6: inverse-model sliding-mode semi-active damping</h2>"
        + _note(quick)
        + "".join(sections)
        + tables_html
        + "<h3 id='table_6_5'>Section 6.5: comparison of the controllers</h3>"
        "<p>Passive 0 A, skyhook hi-lo ACM (k_c = 3, n = 2), inverse-model hi-lo ACM and "
        "sliding mode ACM (both k_d = 2.5) under a 1.5 Hz / 2.5 cm harmonic (steady state, "
        "t &ge; 4 s), a 3.5 cm rounded pulse (mu = 3, 50 km/h) and the 'rough' road preset "
        "at 50 km/h (whole records). DLC = std(F_T)/static load. "
        "<a href='chapter6/table_6_5_comparison.csv'>table_6_5_comparison.csv</a></p>"
        + _table(rows)
    )
    tables.append({"number": "6.5", "file": "chapter6/table_6_5_comparison.csv", "rows": rows})
    return body, {"figures": records, "tables": tables}


#: Per chapter: what it needs built (``build_all`` keyword arguments), so that
#: :func:`build_report` can run every chapter's simulations and figures in one pool
_JOBS: dict[int, Callable[[bool], dict[str, Any]]] = {
    2: _jobs_2,
    3: _jobs_3,
    4: _jobs_4,
    5: _jobs_5,
    6: _jobs_6,
}
#: What the last pool run built: (output folder, quick, chapters) -> Built
_BUILT: dict[tuple[str, bool], tuple[frozenset[int], Any]] = {}


def _build(
    chapters: Iterable[int],
    out: Path,
    quick: bool,
    progress: Callable[[str], None],
    findings: bool = False,
) -> Any:
    """Run the jobs of ``chapters`` (and the findings scorecard's runs) in one process pool
    (see families.build_all)."""
    from mrsuspension.report.families import build_all

    figures: dict[str, Any] = {}
    tables: list[Any] = []
    specials: list[Any] = []
    calls: dict[str, Any] = {}
    chosen = [c for c in chapters if c in _JOBS]
    for c in chosen:
        job = _JOBS[c](quick)
        figures.update(job.get("figures", {}))
        tables.extend(job.get("tables", ()))
        specials.extend(job.get("specials", ()))
        calls.update(job.get("calls", {}))
    for sub in {*figures, *(s[0] for s in specials)}:
        (out / sub).mkdir(parents=True, exist_ok=True)
    extra = []
    if findings:
        from mrsuspension.report import findings as scorecard

        extra = scorecard.units(quick)
    built = build_all(
        figures,
        tables,
        quick,
        out,
        specials=specials,
        calls=calls,
        units=extra,
        progress=progress,
    )
    _BUILT[(str(out), quick)] = (frozenset(chosen), built)
    return built


def _prebuilt(chapter: int, out: Path, quick: bool, progress: Callable[[str], None]) -> Any:
    """The pool results holding ``chapter`` (built now, for it alone, if missing)."""
    done = _BUILT.get((str(out), quick))
    if done is not None and chapter in done[0]:
        return done[1]
    return _build([chapter], out, quick, progress)


_CHAPTERS: dict[int, Callable[[Path, bool, Callable[[str], None]], tuple[str, dict[str, Any]]]] = {
    2: _chapter_2,
    3: _chapter_3,
    4: _chapter_4,
    5: _chapter_5,
    6: _chapter_6,
}


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
        Chapters to build (default: chapters 2-6, the findings scorecard,
        :mod:`mrsuspension.report.findings`, and the "beyond the dissertation" section,
        :mod:`mrsuspension.report.beyond`).
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

    requested = None if chapters is None else set(chapters)
    beyond = requested is None or "beyond" in requested
    findings = requested is None or "findings" in requested
    chosen: list[int] = (
        sorted(_CHAPTERS)
        if requested is None
        else sorted(int(c) for c in requested - {"beyond", "findings"})
    )
    for c in chosen:
        if c not in _CHAPTERS:
            raise ValidationError(
                f"chapter {c} is not available; available: "
                f"{', '.join(map(str, sorted(_CHAPTERS)))}, findings, beyond"
            )
    if not chosen and not beyond and not findings:
        raise ValidationError("no chapters selected")
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
        body, info = _CHAPTERS[c](out / f"chapter{c}", quick, say)
        bodies.append(body)
        manifest["chapters"][str(c)] = info
    if beyond:
        from mrsuspension.report import beyond as beyond_section

        body, info = beyond_section.build(out / "beyond", quick, say)
        bodies.append(body)
        manifest["beyond"] = info
    elapsed = time.perf_counter() - start
    manifest["run_time_s"] = round(elapsed, 2)
    _BUILT.pop((str(out), quick), None)
    (out / "manifest.json").write_text(json.dumps(manifest, indent=2, default=float) + "\n")
    toc = "<li><a href='#findings'>Findings scorecard</a></li>" if findings else ""
    toc += "".join(f"<li><a href='#ch{c}'>Chapter {c}</a></li>" for c in chosen)
    toc += "<li><a href='#beyond'>Beyond the dissertation</a></li>" if beyond else ""
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
