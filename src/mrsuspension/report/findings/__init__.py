"""The findings scorecard: the dissertation's testable claims (Chapters 4-6 and 8), checked.

Every qualitative claim of the texts and summaries of Chapters 4, 5 and 6 and of the
Chapter 8 conclusions that a quarter-car simulation can test is a :class:`Claim` here:
an id, the section, a short verbatim quote, our reading of it as a check over named runs,
and what it depends on. :func:`evaluate` runs every distinct scenario once (the runs are
the report's own figure families and shock tables, so inside ``mrsus reproduce`` they are
shared with the figures), evaluates every claim and returns a :class:`Scorecard`: per claim
whether it holds, our numbers with units and, where it does not hold, why.

Runs
    A :class:`Run` is a scenario under one kind of analysis. :func:`fig` takes a variant of
    a report figure (``fig("4.5", "policy I (k_c = 3)")``), :func:`table` a row of a shock
    table (``table("4.1", 422.0)``); both accept overrides. Kinds ``time``, ``freq``,
    ``pulse`` and ``psd`` are the report's units (:func:`~mrsuspension.report.families.
    run_unit`: a harmonic 2.5 cm / 1.5 Hz steady window, the two-stage swept frequency
    response, the 3.5 cm rounded pulse, the ``rough`` preset road); ``history`` is the same
    harmonic run kept whole over its steady state (t >= 4 s) with the switching condition
    ``z_c``, for force tracking, drift and spectra.
Readings
    Words are read as: "insensitive" / "comparable" / "only slight": a spread (max - min
    over mean) of at most 10 % (``INSENSITIVE``) or 25 % (``SLIGHT``); "considerably" /
    "significantly" lower: at most 0.85 times (``CONSIDERABLY``); "about X" / "in the
    order of X": within 25 % (``ABOUT``); a stated percentage change: the same sign and a
    size within half to one and a half times the stated one; "in the majority of the
    frequency range": at more than half of the grid frequencies; "resonant" / "peak"
    transmissibility: the maximum over 0.5-4 Hz. Frequency bands: body resonance 0.5-4 Hz,
    ride range as the quote says, wheel hop 7-15 Hz.
Statuses
    ``held``; ``held under a stated reading`` (it holds only under another admissible
    reading than the kept one, :func:`~mrsuspension.report.findings.checks.readings`: the
    row names it); ``not held``; ``not held for any admissible value`` (it fails under every
    reading and parameter value it was checked over); ``dissertation inconsistent`` (the dissertation contradicts
    itself on the claim: the row names the evidence and which reading is tested);
    ``error`` (the check could not be evaluated). A claim with ``known`` set is expected not
    to hold (the integration test makes it a strict xfail): ``known`` holds the suspected
    cause, for the lead developer's bug hunt.
Depends on
    ``depends_on`` names what a claim is sensitive to beyond the model: ``ROAD`` (the
    preset roads, stand-ins defined by their PSD level: every claim on a random road) and ``SAR``
    (the shock-acceleration denominator: absolute SAR values only; ratios between runs of
    the same pulse shape do not depend on it). ``python -m mrsuspension.report.findings
    --depends-on road`` re-evaluates only those.

Examples
--------
>>> len(CLAIMS) > 30
True
>>> claim = CLAIMS_BY_ID["4.3.2-gamma"]
>>> claim.section, claim.check.runs["ACM"].kind
('4.3.2', 'time')
"""

from __future__ import annotations

import time
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from mrsuspension._docs import doc
from mrsuspension._pool import pool_map
from mrsuspension.report.families import Unit
from mrsuspension.report.findings.checks import (
    ABOUT,
    CONSIDERABLY,
    INSENSITIVE,
    ROAD,
    SAR,
    SLIGHT,
    Check,
    Claim,
    Payload,
    Run,
    Verdict,
    run_key,
)
from mrsuspension.report.findings.claims import CLAIMS, SKIPPED, SWEPT_IN_FULL

__all__ = [
    "ABOUT",
    "CLAIMS",
    "CLAIMS_BY_ID",
    "CONSIDERABLY",
    "CSV_COLUMNS",
    "INSENSITIVE",
    "ROAD",
    "SAR",
    "SKIPPED",
    "SLIGHT",
    "STATUSES",
    "SWEPT_IN_FULL",
    "Check",
    "Claim",
    "ClaimResult",
    "Run",
    "Scorecard",
    "Verdict",
    "build",
    "check_of",
    "claims_markdown",
    "evaluate",
    "history_keys",
    "html_section",
    "run_payloads",
    "units",
    "write_csv",
]

#: Claim statuses, in table order: "held under a stated reading" holds only under a reading
#: other than the kept one (of a measure, a window, an unknown; the row names it); "not
#: held for any admissible value" fails under every reading and value it was checked over
STATUSES: tuple[str, ...] = (
    "held",
    "held under a stated reading",
    "not held",
    "not held for any admissible value",
    "dissertation inconsistent",
    "error",
)
CLAIMS_BY_ID: dict[str, Claim] = {c.id: c for c in CLAIMS}


@dataclass(frozen=True)
class ClaimResult:
    """A claim evaluated: holds, status, our numbers and the explanation."""

    claim: Claim
    holds: bool
    status: str
    numbers: str
    explanation: str = ""

    def row(self) -> dict[str, str]:
        """The claim as a flat table row (CSV, manifest)."""
        c = self.claim
        return {
            "id": c.id,
            "section": c.sections,
            "claim": c.claim,
            "quote": c.quote,
            "holds": "yes" if self.holds else "no",
            "status": self.status,
            "our numbers": self.numbers,
            "explanation": self.explanation,
            "depends on": " ".join(c.depends_on),
        }


@dataclass
class Scorecard:
    """Every claim evaluated, with counts and the cost of the runs."""

    results: list[ClaimResult]
    quick: bool
    runs: int = 0
    reused: int = 0
    cpu_time: float = 0.0
    wall_time: float = 0.0

    def __getitem__(self, claim_id: str) -> ClaimResult:
        for r in self.results:
            if r.claim.id == claim_id:
                return r
        raise KeyError(claim_id)

    def counts(self) -> dict[str, int]:
        """Tested, held, not held, dissertation inconsistent (held / not), errors."""
        status = [r.status for r in self.results]
        return {
            "tested": len(self.results),
            "held": status.count("held"),
            "held under a stated reading": status.count("held under a stated reading"),
            "not held": status.count("not held"),
            "not held for any admissible value": status.count("not held for any admissible value"),
            "dissertation inconsistent": status.count("dissertation inconsistent"),
            "of which the tested reading held": sum(
                r.status == "dissertation inconsistent" and r.holds for r in self.results
            ),
            "error": status.count("error"),
            "skipped (not testable)": len(SKIPPED),
        }

    def rows(self) -> list[dict[str, str]]:
        """One flat row per claim (see :meth:`ClaimResult.row`)."""
        return [r.row() for r in self.results]

    def timing(self) -> dict[str, Any]:
        """Distinct runs, how many were reused from the report, CPU and wall time [s]."""
        return {
            "distinct runs": self.runs,
            "reused from the report": self.reused,
            "run cpu time [s]": round(self.cpu_time, 2),
            "wall time [s]": round(self.wall_time, 2),
            "quick": self.quick,
        }

    def text(self) -> str:
        """A plain-text table (id, section, holds, status, numbers) with the counts."""
        lines = [", ".join(f"{k}: {v}" for k, v in self.counts().items())]
        for r in self.results:
            lines.append(
                f"{r.claim.id:28s} {r.claim.sections:12s} {'yes' if r.holds else 'no ':3s} "
                f"{r.status:34s} {r.numbers}"
            )
            if r.explanation:
                lines.append(f"{'':28s} -> {r.explanation}")
        return "\n".join(lines)


def _status(claim: Claim, verdict: Verdict) -> tuple[str, str]:
    if claim.inconsistent:
        note = f"Dissertation inconsistent: {claim.inconsistent}"
        if verdict.holds and verdict.reading:
            note += f" Held under the stated reading: {verdict.reading}."
        if not verdict.holds:
            note += f" Not held: {verdict.why}."
            if claim.known:
                note += f" Suspected cause: {claim.known}."
        return "dissertation inconsistent", note
    if verdict.holds and verdict.reading:
        return "held under a stated reading", (
            f"Held under the stated reading: {verdict.reading} (the kept reading fails: "
            f"{verdict.why})."
        )
    if verdict.holds:
        return "held", ""
    cause = claim.known or "none recorded: a new failure (not in claims.KNOWN)"
    status = "not held for any admissible value" if verdict.exhausted else "not held"
    return status, f"{verdict.why}. Suspected cause: {cause}"


_FULL_CHECKS: dict[str, Check] = {}


def check_of(claim: Claim, quick: bool) -> Check:
    """The check ``claim`` is evaluated with: its own, except in the full build for the
    claims of :data:`SWEPT_IN_FULL`, which are checked over the admissible range of the
    control unknowns their runs involve (``claims.common._swept``; built once).

    Examples
    --------
    >>> claim = CLAIMS_BY_ID["6.5-rattle-space"]
    >>> check_of(claim, quick=True) is claim.check
    True
    >>> len(check_of(claim, quick=False).runs) > len(claim.check.runs)
    True
    """
    if quick or claim.id not in SWEPT_IN_FULL:
        return claim.check
    if claim.id not in _FULL_CHECKS:
        from mrsuspension.report.findings.claims.common import _swept

        _FULL_CHECKS[claim.id] = _swept(claim.check)
    return _FULL_CHECKS[claim.id]


def run_payloads(
    keys: Iterable[tuple[str, Unit]], workers: int | None = 1
) -> dict[tuple[str, Unit], Payload]:
    """Run the given payload keys (one process, or a pool of ``workers``)."""
    todo = list(dict.fromkeys(keys))
    return dict(zip(todo, pool_map(run_key, todo, workers=workers), strict=True))


def history_keys(quick: bool, claims: Sequence[Claim] | None = None) -> list[tuple[str, Unit]]:
    """The payload keys of the claims' ``history`` runs (not report units), in order.

    The report runs them as one task of its process pool (:func:`run_payloads`) and hands
    the payloads to :func:`build` (``runs``), so no second pool starts.

    Examples
    --------
    >>> {kind for kind, _ in history_keys(True)}
    {'history'}
    """
    chosen = CLAIMS if claims is None else claims
    keys = [r.key(quick) for c in chosen for r in check_of(c, quick).runs.values()]
    return [k for k in dict.fromkeys(keys) if k[0] == "history"]


def units(quick: bool, claims: Sequence[Claim] | None = None) -> list[Unit]:
    """The report units the claims need (``history`` runs excluded), for the report pool."""
    chosen = CLAIMS if claims is None else claims
    keys = {r.key(quick) for c in chosen for r in check_of(c, quick).runs.values()}
    return [u for kind, u in keys if kind == "unit"]


def evaluate(
    quick: bool = True,
    *,
    claims: Sequence[Claim] | None = None,
    payloads: Mapping[Unit, Payload] | None = None,
    workers: int | None = 1,
    runs: Mapping[tuple[str, Unit], Payload] | None = None,
) -> Scorecard:
    """Run every distinct scenario the claims need once, then evaluate every claim.

    Parameters
    ----------
    quick : bool
        The report's quick settings (10 frequencies, 0.5 ms step; 0.25 ms for the inverse
        laws), else the full report's (30 frequencies, 0.1 ms; the claims of
        :data:`SWEPT_IN_FULL` then under their sensitivity sweep, :func:`check_of`).
    claims : sequence of Claim, optional
        Default :data:`CLAIMS`.
    payloads : mapping, optional
        Payloads already run (``Built.payloads`` of the report's pool, by unit): reused.
    workers : int, optional
        Processes for the missing runs (1: in this process).
    runs : mapping, optional
        Payloads already run, by payload key (e.g. :func:`history_keys` run in the
        report's pool): reused.

    Returns
    -------
    Scorecard
    """
    chosen = CLAIMS if claims is None else claims
    start = time.perf_counter()
    checks = [check_of(c, quick) for c in chosen]
    keys = [r.key(quick) for check in checks for r in check.runs.values()]
    have: dict[tuple[str, Unit], Payload] = dict(runs or {})
    for key in dict.fromkeys(keys):
        if key[0] == "unit" and payloads is not None and key[1] in payloads:
            have[key] = payloads[key[1]]
    reused = len(have)
    fresh = run_payloads([k for k in dict.fromkeys(keys) if k not in have], workers)
    have.update(fresh)
    cpu = sum(float(p.get("run cpu time [s]", 0.0)) for p in fresh.values())
    results = []
    for c, check in zip(chosen, checks, strict=True):
        named = {label: have[r.key(quick)] for label, r in check.runs.items()}
        try:
            verdict = check(named)
        except Exception as exc:  # a broken check must not hide the others
            results.append(ClaimResult(c, False, "error", "", f"{type(exc).__name__}: {exc}"))
            continue
        status, note = _status(c, verdict)
        results.append(ClaimResult(c, verdict.holds, status, verdict.numbers, note))
    return Scorecard(
        results,
        quick,
        runs=len(have),
        reused=reused,
        cpu_time=cpu,
        wall_time=time.perf_counter() - start,
    )


# ---------------------------------------------------------------------------------------
# The report section

_CSS = {
    "held": "#e3f4e1",
    "held under a stated reading": "#eef6d8",
    "not held": "#fbe0dd",
    "not held for any admissible value": "#f4c9c3",
    "dissertation inconsistent": "#fff1c2",
    "error": "#e4e4e4",
}
#: Claims whose verdict in quick mode (coarse grids, shorter runs) differs from the full
#: report's: claim id -> the full report's status. Found by evaluating both (2026-11-27:
#: exactly these two of 163); ``tests/integration/test_report.py`` holds the quick side
#: and evaluates these claims in full mode.
QUICK_DIFFERS: dict[str, str] = {
    "6.4.1-more-robust-than-hilo": "held",
    "6.6-load-sensitivity": "held",
}
#: Columns of findings.csv (and of each claim in manifest.json)
CSV_COLUMNS: tuple[str, ...] = (
    "id",
    "section",
    "claim",
    "quote",
    "holds",
    "status",
    "our numbers",
    "explanation",
    "depends on",
)


def write_csv(card: Scorecard, path: Path) -> Path:
    """Write one row per claim (:data:`CSV_COLUMNS`) to ``path``."""
    import csv

    with path.open("w", newline="", encoding="utf-8") as fh:
        w = csv.DictWriter(fh, fieldnames=list(CSV_COLUMNS))
        w.writeheader()
        w.writerows(card.rows())
    return path


def _chapter(sections: str) -> str:
    """``"Chapter N"`` of a claim's first section (``"4.3.2, 8"`` -> ``"Chapter 4"``)."""
    head = sections.strip().split(",")[0].strip()
    return f"Chapter {head.split('.')[0]}" if head[:1].isdigit() else "other"


def summary_table(card: Scorecard) -> str:
    """Counts per chapter and status, as an html table (the scorecard's summary).

    Examples
    --------
    >>> "<table" in summary_table(Scorecard([], quick=True))
    True
    """
    import html

    chapters: dict[str, dict[str, int]] = {}
    for r in card.results:
        row = chapters.setdefault(_chapter(r.claim.sections), dict.fromkeys(STATUSES, 0))
        row[r.status] = row.get(r.status, 0) + 1
    shown = [s for s in STATUSES if any(row[s] for row in chapters.values())] or ["held"]
    head = "".join(f"<th style='background:{_CSS[s]}'>{html.escape(s)}</th>" for s in shown)
    body = "".join(
        f"<tr><td class='l'>{html.escape(ch)}</td><td>{sum(row.values())}</td>"
        + "".join(f"<td>{row[s] or ''}</td>" for s in shown)
        + "</tr>"
        for ch, row in sorted(chapters.items())
    )
    total = {s: sum(row[s] for row in chapters.values()) for s in shown}
    foot = (
        f"<tr><th class='l'>all</th><th>{len(card.results)}</th>"
        + "".join(f"<th>{total[s]}</th>" for s in shown)
        + "</tr>"
    )
    return (
        f"<table class='summary'><tr><th class='l'>part</th><th>tested</th>{head}</tr>"
        f"{body}{foot}</table>"
    )


#: The scorecard's filter: status boxes and a text box show or hide the claim rows
#: (``data-status``, ``data-text``); plain JavaScript, no outside resource.
_FILTER_JS = """
(function () {
  var boxes = document.querySelectorAll('#findings-filter input[type=checkbox]');
  var text = document.getElementById('findings-text');
  var count = document.getElementById('findings-shown');
  function apply() {
    var on = {};
    boxes.forEach(function (b) { on[b.value] = b.checked; });
    var words = text.value.toLowerCase().trim();
    var n = 0;
    document.querySelectorAll('#findings-table tr[data-status]').forEach(function (row) {
      var show = on[row.dataset.status] && (!words || row.dataset.text.indexOf(words) >= 0);
      row.style.display = show ? '' : 'none';
      if (show) { n += 1; }
    });
    count.textContent = n;
  }
  boxes.forEach(function (b) { b.addEventListener('change', apply); });
  text.addEventListener('input', apply);
  apply();
})();
"""


def html_section(card: Scorecard, csv_name: str = "findings.csv") -> str:
    """The "Findings scorecard" section: a summary by chapter and status, then every claim
    (claim | section | holds? | numbers) in a folded table with a status and text filter.

    In quick mode the claims whose verdict differs in the full report
    (:data:`QUICK_DIFFERS`) are flagged in their row and listed under the summary.

    Examples
    --------
    >>> card = Scorecard([], quick=True)
    >>> page = html_section(card)
    >>> "Findings scorecard" in page, "findings-filter" in page
    (True, True)
    """
    import html

    counts = card.counts()
    summary = ", ".join(f"<b>{v}</b> {html.escape(k)}" for k, v in counts.items())
    rows = []
    flagged = []
    for r in card.results:
        c = r.claim
        tags = f" <span class='meta'>[depends on {', '.join(c.depends_on)}]</span>" * bool(
            c.depends_on
        )
        note = f"<br><span class='meta'>{html.escape(r.explanation)}</span>" * bool(r.explanation)
        full = QUICK_DIFFERS.get(c.id) if card.quick else None
        if full is not None:
            flagged.append((c.id, r.status, full))
            note += f"<br><b>quick mode only: the full report gives {html.escape(full)}</b>"
        text = " ".join((c.id, c.claim, c.sections, r.status, r.numbers)).lower()
        rows.append(
            f"<tr data-status='{html.escape(r.status)}' data-text='{html.escape(text)}' "
            f"style='background:{_CSS[r.status]}'>"
            f"<td class='l'><b>{html.escape(c.id)}</b><br>{html.escape(c.claim)}<br>"
            f"<i>&ldquo;{html.escape(c.quote)}&rdquo;</i>{tags}</td>"
            f"<td class='l'>{html.escape(c.sections)}</td>"
            f"<td class='l'>{'yes' if r.holds else 'no'}<br>{html.escape(r.status)}</td>"
            f"<td class='l'>{html.escape(r.numbers)}{note}</td></tr>"
        )
    skipped = "".join(
        f"<li>{html.escape(s)}: {html.escape(what)} ({html.escape(why)})</li>"
        for s, what, why in SKIPPED
    )
    timing = card.timing()
    boxes = "".join(
        f"<label style='background:{colour};padding:0 .4em;margin-right:.3em'>"
        f"<input type='checkbox' value='{html.escape(status)}' checked> "
        f"{html.escape(status)} ({counts.get(status, 0)})</label>"
        for status, colour in _CSS.items()
        if status != "error" or counts.get("error")
    )
    quick_note = ""
    if card.quick:
        items = "".join(
            f"<li><b>{html.escape(i)}</b>: {html.escape(q)} here, {html.escape(f)} in the full "
            "report</li>"
            for i, q, f in flagged
        )
        quick_note = "<p class='meta'>Quick mode: coarse grids and shorter runs. " + (
            f"These verdicts differ from the full report's:</p><ul>{items}</ul>"
            if items
            else "No verdict is known to differ from the full report's.</p>"
        )
        swept = ", ".join(
            sorted(i for i in SWEPT_IN_FULL if i in {r.claim.id for r in card.results})
        )
        if swept:
            quick_note += (
                "<p class='meta'>The full report also checks these claims over the admissible "
                "range of the control unknowns their runs involve (the ADFG centre 0-0.5, "
                "sliding mode's beta 1-2), which quick mode leaves out for its cost: "
                f"{html.escape(swept)}.</p>"
            )
    return (
        "<h2 id='findings'>Findings scorecard</h2>"
        f"<p>{summary}.</p>"
        f"{summary_table(card)}{quick_note}"
        "<p>Every qualitative claim of the dissertation's Chapters 4-6 (texts and summaries) "
        "and of the Chapter 8 conclusions that a quarter-car simulation can test, checked "
        "on the model (mrsuspension.report.findings; "
        f"<a href='{doc('report')}'>the report's documentation</a> gives the readings of "
        "'slightly', 'insensitive', 'considerably'). 'Dissertation inconsistent': the "
        "dissertation contradicts itself on the claim; the row names the evidence and the "
        "reading tested. 'Held under a stated reading': the claim holds only under another "
        "admissible reading than the kept one (of an ambiguous measure, a time window, an "
        "unknown parameter), named in the row with both readings' numbers; 'not held for any "
        "admissible value': it fails under every reading it was checked over. Claims marked "
        "'depends on road' use the preset random roads, 'sar' the shock-acceleration "
        f"denominator. {timing['distinct runs']} distinct runs, "
        f"{timing['reused from the report']} of them made in the report's process pool (the "
        "figures' own runs where the scenarios coincide), "
        f"{timing['run cpu time [s]']} s of CPU for the rest. "
        f"<a href='{html.escape(csv_name)}'>{html.escape(csv_name)}</a></p>"
        f"<details id='findings-claims'><summary>Every claim ({len(card.results)}): "
        "open to read, filter by status or text</summary>"
        f"<p id='findings-filter'>{boxes} <input id='findings-text' type='search' "
        "placeholder='filter: id, words, section'> <span class='meta'><span "
        "id='findings-shown'></span> shown</span></p>"
        "<table id='findings-table'><tr><th class='l'>claim</th><th class='l'>section</th>"
        "<th class='l'>holds?</th><th class='l'>our numbers</th></tr>"
        + "".join(rows)
        + "</table></details><h3>Not tested (no quarter-car simulation can)</h3><ul>"
        + skipped
        + f"</ul><script>{_FILTER_JS}</script>"
    )


def build(
    folder: Path,
    quick: bool,
    progress: Callable[[str], None] | None = None,
    payloads: Mapping[Unit, Payload] | None = None,
    runs: Mapping[tuple[str, Unit], Payload] | None = None,
) -> tuple[str, dict[str, Any]]:
    """Evaluate the scorecard (reusing ``payloads`` and ``runs``, see :func:`evaluate`),
    write ``findings.csv`` into ``folder``.

    Returns
    -------
    tuple
        The HTML section and its manifest entry (counts, timing, every claim's row).
    """
    import os

    say = progress or (lambda _m: None)
    say("findings: evaluating the dissertation's claims")
    from mrsuspension.report.families import in_worker

    workers = 1 if in_worker() else (os.cpu_count() or 1)
    card = evaluate(quick, payloads=payloads, workers=workers, runs=runs)
    folder.mkdir(parents=True, exist_ok=True)
    write_csv(card, folder / "findings.csv")
    manifest = {
        "file": "findings.csv",
        "counts": card.counts(),
        "timing": card.timing(),
        "claims": card.rows(),
        "skipped": [{"section": s, "claim": w, "why": y} for s, w, y in SKIPPED],
    }
    return html_section(card), manifest


def claims_markdown() -> str:
    """The claims as a Markdown table (id, sections, what is tested, depends on) and the
    skipped ones, for ``docs/report.md`` (results change with the model: see the report).

    Examples
    --------
    >>> "| 4.3.2-gamma | 4.3.2, 4.6 |" in claims_markdown()
    True
    """

    def cell(text: str) -> str:
        return text.replace("|", "\\|")

    lines = [
        f"### The {len(CLAIMS)} claims",
        "",
        "| Claim | Sections | Tested | Depends on |",
        "|---|---|---|---|",
    ]
    lines += [
        f"| {c.id} | {c.sections} | {cell(c.claim)}"
        f"{' *Dissertation inconsistent.*' if c.inconsistent else ''} "
        f"| {' '.join(c.depends_on) or '-'} |"
        for c in CLAIMS
    ]
    lines += ["", f"### Not tested ({len(SKIPPED)})", ""]
    lines += [f"- {s}: {what} ({why})." for s, what, why in SKIPPED]
    return "\n".join(lines) + "\n"
