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
    ``held``; ``not held``; ``dissertation inconsistent`` (the dissertation contradicts
    itself on the claim: the row names the evidence and which reading is tested);
    ``error`` (the check could not be evaluated). A claim with ``known`` set is expected not
    to hold (the integration test makes it a strict xfail): ``known`` holds the suspected
    cause, for the lead developer's bug hunt.
Depends on
    ``depends_on`` names what a claim is sensitive to beyond the model: ``ROAD`` (the
    preset roads, being redefined by PSD level: every claim on a random road) and ``SAR``
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
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any

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
    "evaluate",
    "run_payloads",
    "units",
]

#: Claim statuses, in table order
STATUSES: tuple[str, ...] = ("held", "not held", "dissertation inconsistent", "error")
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
            "not held": status.count("not held"),
            "dissertation inconsistent": status.count("dissertation inconsistent"),
            "inconsistent, tested reading held": sum(
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
                f"{r.status:26s} {r.numbers}"
            )
            if r.explanation:
                lines.append(f"{'':28s} -> {r.explanation}")
        return "\n".join(lines)


def _status(claim: Claim, verdict: Verdict) -> tuple[str, str]:
    if claim.inconsistent:
        note = f"Dissertation inconsistent: {claim.inconsistent}"
        if not verdict.holds:
            note += f" Not held: {verdict.why}."
            if claim.known:
                note += f" Suspected cause: {claim.known}."
        return "dissertation inconsistent", note
    if verdict.holds:
        return "held", ""
    cause = claim.known or "none recorded: a new failure (not in claims.KNOWN)"
    return "not held", f"{verdict.why}. Suspected cause: {cause}"


def run_payloads(
    keys: Iterable[tuple[str, Unit]], workers: int | None = 1
) -> dict[tuple[str, Unit], Payload]:
    """Run the given payload keys (one process, or a pool of ``workers``)."""
    todo = list(dict.fromkeys(keys))
    if not todo:
        return {}
    if workers == 1 or len(todo) == 1:
        return {k: run_key(k) for k in todo}
    from concurrent.futures import ProcessPoolExecutor

    with ProcessPoolExecutor(max_workers=workers) as pool:
        return dict(zip(todo, pool.map(run_key, todo), strict=True))


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

    Returns
    -------
    Scorecard
    """
    chosen = CLAIMS if claims is None else claims
    start = time.perf_counter()
    keys = [r.key(quick) for c in chosen for r in c.check.runs.values()]
    have: dict[tuple[str, Unit], Payload] = {}
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
