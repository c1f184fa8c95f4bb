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
from mrsuspension.report.findings.claims import CLAIMS, SKIPPED

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
    "Check",
    "Claim",
    "ClaimResult",
    "Run",
    "Scorecard",
    "Verdict",
    "build",
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
    keys = [r.key(quick) for c in chosen for r in c.check.runs.values()]
    return [k for k in dict.fromkeys(keys) if k[0] == "history"]


def units(quick: bool, claims: Sequence[Claim] | None = None) -> list[Unit]:
    """The report units the claims need (``history`` runs excluded), for the report pool."""
    chosen = CLAIMS if claims is None else claims
    keys = {r.key(quick) for c in chosen for r in c.check.runs.values()}
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
        laws), else the full report's (30 frequencies, 0.1 ms).
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
    keys = [r.key(quick) for c in chosen for r in c.check.runs.values()]
    have: dict[tuple[str, Unit], Payload] = dict(runs or {})
    for key in dict.fromkeys(keys):
        if key[0] == "unit" and payloads is not None and key[1] in payloads:
            have[key] = payloads[key[1]]
    reused = len(have)
    fresh = run_payloads([k for k in dict.fromkeys(keys) if k not in have], workers)
    have.update(fresh)
    cpu = sum(float(p.get("run cpu time [s]", 0.0)) for p in fresh.values())
    results = []
    for c in chosen:
        named = {label: have[r.key(quick)] for label, r in c.check.runs.items()}
        try:
            verdict = c.check(named)
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


def html_section(card: Scorecard, csv_name: str = "findings.csv") -> str:
    """The "Findings scorecard" section: counts, then claim | section | holds? | numbers.

    Examples
    --------
    >>> card = Scorecard([], quick=True)
    >>> "Findings scorecard" in html_section(card)
    True
    """
    import html

    counts = card.counts()
    summary = ", ".join(f"<b>{v}</b> {html.escape(k)}" for k, v in counts.items())
    rows = []
    for r in card.results:
        c = r.claim
        tags = f" <span class='meta'>[depends on {', '.join(c.depends_on)}]</span>" * bool(
            c.depends_on
        )
        note = f"<br><span class='meta'>{html.escape(r.explanation)}</span>" * bool(r.explanation)
        rows.append(
            f"<tr style='background:{_CSS[r.status]}'>"
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
    legend = "".join(
        f"<span style='background:{colour};padding:0 .4em'>{html.escape(status)}</span> "
        for status, colour in _CSS.items()
    )
    return (
        "<h2 id='findings'>Findings scorecard</h2>"
        f"<p>{summary}.</p>"
        "<p>Every qualitative claim of the dissertation's Chapters 4-6 (texts and summaries) "
        "and of the Chapter 8 conclusions that a quarter-car simulation can test, checked "
        "on the model (mrsuspension.report.findings; docs/report.md gives the readings of "
        "'slightly', 'insensitive', 'considerably'). 'Dissertation inconsistent': the "
        "dissertation contradicts itself on the claim; the row names the evidence and the "
        "reading tested. 'Held under a stated reading': the claim holds only under another "
        "admissible reading than the kept one (of an ambiguous measure, a time window, an "
        "unknown parameter), named in the row with both readings' numbers; 'not held for any "
        "admissible value': it fails under every reading it was checked over. Claims marked 'depends on road' use the preset random roads, "
        "'sar' the shock-acceleration denominator (being redefined). "
        f"{timing['distinct runs']} distinct runs, {timing['reused from the report']} of them "
        "made in the report's process pool (the figures' own runs where the scenarios "
        f"coincide), {timing['run cpu time [s]']} s of CPU for the rest. "
        f"<a href='{html.escape(csv_name)}'>{html.escape(csv_name)}</a></p>"
        f"<p>{legend}</p>"
        "<table><tr><th class='l'>claim</th><th class='l'>section</th>"
        "<th class='l'>holds?</th><th class='l'>our numbers</th></tr>"
        + "".join(rows)
        + "</table><h3>Not tested (no quarter-car simulation can)</h3><ul>"
        + skipped
        + "</ul>"
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
