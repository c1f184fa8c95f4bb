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

__all__ = ["FigureRecord", "build_report"]


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
"""


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


def _chapter_2(
    folder: Path, quick: bool, progress: Callable[[str], None]
) -> tuple[str, dict[str, Any]]:
    from mrsuspension import parameters
    from mrsuspension.characterisation import characterise, table_2_1
    from mrsuspension.errata import ERRATA
    from mrsuspension.report import ch2

    sections: list[str] = []
    manifest: dict[str, Any] = {"figures": [], "tables": []}
    for build in ch2.CHAPTER_2_FIGURES:
        progress(f"chapter 2: {build.__doc__.splitlines()[0] if build.__doc__ else build.__name__}")
        rec = build()
        rec.save(folder)
        manifest["figures"].append(
            {"number": rec.number, "title": rec.title, "files": rec.files, "data": rec.data}
        )
        sections.append(
            f'<figure id="{rec.slug}"><img src="chapter2/{rec.slug}.png" alt="Fig. {rec.number}">'
            f"<figcaption><b>Fig. {html.escape(rec.number)}: {html.escape(rec.title)}.</b> "
            f"{html.escape(rec.caption)} "
            f'<a href="chapter2/{rec.slug}.svg">SVG</a></figcaption></figure>'
        )
    # Table 2.1 on the default model
    progress("chapter 2: Table 2.1 test matrix on the symmetric model")
    conds = table_2_1() if not quick else table_2_1(frequencies=[0.5, 1.5, 5.0, 15.0])
    result = characterise(ch2.band_model(0.5), [c for c in conds if c.frequency <= 5.0])
    result_hi = characterise(ch2.band_model(7.5), [c for c in conds if c.frequency > 5.0])
    rows = result.summary_rows() + result_hi.summary_rows()
    rows.sort(key=lambda r: (r["amplitude [m]"], r["frequency [Hz]"], r["current [A]"]))
    import csv

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


def _figure_sections(
    chapter: int,
    builders: Sequence[Callable[[bool], FigureRecord]],
    folder: Path,
    quick: bool,
    progress: Callable[[str], None],
) -> tuple[list[str], list[dict[str, Any]]]:
    """Build, save and describe each figure of a chapter (figure builders take ``quick``)."""
    sections: list[str] = []
    records: list[dict[str, Any]] = []
    for build in builders:
        doc = build.__doc__.splitlines()[0] if build.__doc__ else build.__name__
        progress(f"chapter {chapter}: {doc}")
        rec = build(quick)
        rec.save(folder)
        records.append(
            {"number": rec.number, "title": rec.title, "files": rec.files, "data": rec.data}
        )
        sections.append(
            f'<figure id="{rec.slug}"><img src="chapter{chapter}/{rec.slug}.png" '
            f'alt="Fig. {rec.number}"><figcaption><b>Fig. {html.escape(rec.number)}: '
            f"{html.escape(rec.title)}.</b> {html.escape(rec.caption)} "
            f'<a href="chapter{chapter}/{rec.slug}.svg">SVG</a></figcaption></figure>'
        )
    return sections, records


def _chapter_3(
    folder: Path, quick: bool, progress: Callable[[str], None]
) -> tuple[str, dict[str, Any]]:
    from mrsuspension.report import ch3

    sections, records = _figure_sections(3, ch3.CHAPTER_3_FIGURES, folder, quick, progress)
    body = (
        "<h2 id='ch3'>Chapter 3: semi-active control synthesis, reference model and "
        "excitations</h2>" + "".join(sections)
    )
    return body, {"figures": records, "tables": []}


def _chapter_4(
    folder: Path, quick: bool, progress: Callable[[str], None]
) -> tuple[str, dict[str, Any]]:
    import csv

    from mrsuspension.report import ch4

    builders = ch4.CHAPTER_4_FIGURES + (() if quick else ch4.CHAPTER_4_FULL_FIGURES)
    sections, records = _figure_sections(4, builders, folder, quick, progress)
    progress("chapter 4: Tables 4.1-4.5 shock response measures")
    tables = []
    table_sections = []
    for tab in ch4.shock_tables(quick):
        slug = "table_" + tab["number"].replace(".", "_")
        with (folder / f"{slug}.csv").open("w", newline="") as fh:
            w = csv.DictWriter(fh, fieldnames=list(tab["rows"][0]))
            w.writeheader()
            w.writerows(tab["rows"])
        tables.append({**tab, "file": f"chapter4/{slug}.csv"})
        table_sections.append(
            f"<h3 id='{slug}'>Table {html.escape(tab['number'])}: {html.escape(tab['title'])}"
            f"</h3><p>{html.escape(tab['caption'])} <a href='chapter4/{slug}.csv'>{slug}.csv"
            "</a></p>" + _table(tab["rows"], "{:.3g}")
        )
    skipped = (
        ""
        if not quick
        else "<p>Quick mode: the frequency-response figures 4.3b (hysteresis) and 4.7 "
        "(SCM vs ACM) are built only in the full report.</p>"
    )
    body = (
        "<h2 id='ch4'>Chapter 4: hi-lo semi-active MR suspension, simulation studies</h2>"
        "<p>Frequency responses come from studies (two-stage swept excitation, a = 2.5 cm, "
        "f_T = 2.1 Hz); time histories, rounded-pulse and random-road responses run the "
        "engine directly. The numbers behind every curve are in manifest.json; each table "
        "sets our model's values beside the dissertation's.</p>"
        + skipped
        + "".join(sections)
        + "".join(table_sections)
    )
    return body, {"figures": records, "tables": tables}


def _chapter_5(
    folder: Path, quick: bool, progress: Callable[[str], None]
) -> tuple[str, dict[str, Any]]:
    from mrsuspension.report import ch5

    sections, records = _figure_sections(5, ch5.CHAPTER_5_FIGURES, folder, quick, progress)
    body = (
        "<h2 id='ch5'>Chapter 5: inverse-model hi-lo semi-active damping</h2>"
        "<p>Time histories run the engine directly (2.5 cm at 1.5 Hz); frequency responses "
        "come from studies. The force gain k_d is damper.force_gain.</p>" + "".join(sections)
    )
    return body, {"figures": records, "tables": []}


def _chapter_6(
    folder: Path, quick: bool, progress: Callable[[str], None]
) -> tuple[str, dict[str, Any]]:
    import csv

    from mrsuspension.report import ch6

    sections, records = _figure_sections(6, ch6.CHAPTER_6_FIGURES, folder, quick, progress)
    progress("chapter 6: section 6.5 controller comparison")
    rows = ch6.comparison_table(quick)
    with (folder / "table_6_5_comparison.csv").open("w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    body = (
        "<h2 id='ch6'>Chapter 6: inverse-model sliding-mode semi-active damping</h2>"
        + "".join(sections)
        + "<h3 id='table_6_5'>Section 6.5: comparison of the controllers</h3>"
        "<p>Passive 0 A, skyhook hi-lo ACM (k_c = 3, n = 2), inverse-model hi-lo ACM and "
        "sliding mode ACM (both k_d = 2.5) under a 1.5 Hz / 2.5 cm harmonic (steady state, "
        "t &ge; 4 s), a 3.5 cm rounded pulse (mu = 3, 50 km/h) and the 'rough' road preset "
        "at 50 km/h (whole records). DLC = std(F_T)/static load. "
        "<a href='chapter6/table_6_5_comparison.csv'>table_6_5_comparison.csv</a></p>"
        + _table(rows)
    )
    table = {"number": "6.5", "file": "chapter6/table_6_5_comparison.csv", "rows": rows}
    return body, {"figures": records, "tables": [table]}


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
    chapters : iterable of int or "beyond", optional
        Chapters to build (default: every available one and the "beyond the
        dissertation" section, :mod:`mrsuspension.report.beyond`).
    quick : bool
        Coarser grids for a fast check.
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
    chosen: list[int] = (
        sorted(_CHAPTERS) if requested is None else sorted(int(c) for c in requested - {"beyond"})
    )
    for c in chosen:
        if c not in _CHAPTERS:
            raise ValidationError(
                f"chapter {c} is not available; available: "
                f"{', '.join(map(str, sorted(_CHAPTERS)))}, beyond"
            )
    if not chosen and not beyond:
        raise ValidationError("no chapters selected")
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    say = progress or (lambda _msg: None)
    start = time.perf_counter()
    bodies: list[str] = []
    manifest: dict[str, Any] = {"version": __version__, "chapters": {}}
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
    (out / "manifest.json").write_text(json.dumps(manifest, indent=2, default=float) + "\n")
    toc = "".join(f"<li><a href='#ch{c}'>Chapter {c}</a></li>" for c in chosen)
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
