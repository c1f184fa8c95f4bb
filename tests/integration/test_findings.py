"""Every testable claim of the dissertation's Chapters 4-6 and 8, on the model.

One test per claim of :data:`mrsuspension.report.findings.CLAIMS`, over one module-scoped
scorecard: every distinct run is made once (quick settings: 0.5 ms step, 0.25 ms for the
inverse-model laws, a 40-point frequency grid; about 15 s of CPU once the kernels are
compiled). A claim that holds must hold. A claim in ``claims.KNOWN`` (the model does not
reproduce it, or the dissertation contradicts itself and the tested reading fails) is a
strict xfail whose reason is the suspected cause; the assertion message carries our
numbers. When a fix makes such a claim hold, its test fails as XPASS: take the claim out
of ``KNOWN``. A check that cannot be evaluated fails either way.
"""

from __future__ import annotations

import pytest

from mrsuspension.report.findings import CLAIMS, Claim, Scorecard, evaluate


@pytest.fixture(scope="module")
def scorecard() -> Scorecard:
    return evaluate(quick=True)


def _param(claim: Claim) -> object:
    marks = []
    if claim.known:
        what = "dissertation inconsistent" if claim.inconsistent else "not held"
        marks.append(
            pytest.mark.xfail(strict=True, raises=AssertionError, reason=f"{what}: {claim.known}")
        )
    return pytest.param(claim, id=claim.id, marks=marks)


@pytest.mark.parametrize("claim", [_param(c) for c in CLAIMS])
def test_claim(claim: Claim, scorecard: Scorecard) -> None:
    result = scorecard[claim.id]
    if result.status == "error":
        pytest.fail(f"{claim.id}: the check could not be evaluated: {result.explanation}")
    assert result.holds, (
        f"{claim.id} ({claim.sections}) does not hold: {claim.claim} Ours: {result.numbers}. "
        f"{result.explanation}"
    )


def test_counts_add_up(scorecard: Scorecard) -> None:
    counts = scorecard.counts()
    assert counts["tested"] == len(CLAIMS)
    statuses = (
        "held",
        "held under a stated reading",
        "not held",
        "not held for any admissible value",
        "dissertation inconsistent",
    )
    assert sum(counts[s] for s in statuses) == len(CLAIMS)
    # every claim whose check tries readings or values says which held, or that none did
    for r in scorecard.results:
        if r.status == "held under a stated reading":
            assert r.holds, r.claim.id
            assert "Held under the stated reading: " in r.explanation, r.claim.id
        if r.status == "not held for any admissible value":
            assert not r.holds
            assert "not held for any admissible reading" in r.explanation
    assert counts["error"] == 0
    # the shared runs: far fewer than the claims' run references
    references = sum(len(c.check.runs) for c in CLAIMS)
    assert scorecard.runs < references / 2, (scorecard.runs, references)


def test_quick_mode_flags_the_verdicts_the_full_report_changes(scorecard: Scorecard) -> None:
    """Issue 31: the two verdicts quick mode reads otherwise are named, and hold in full."""
    from mrsuspension.report.findings import CLAIMS_BY_ID, QUICK_DIFFERS, html_section

    assert QUICK_DIFFERS
    for claim_id, full in QUICK_DIFFERS.items():
        assert scorecard[claim_id].status != full, f"{claim_id} no longer differs in quick mode"
    full_card = evaluate(quick=False, claims=[CLAIMS_BY_ID[i] for i in QUICK_DIFFERS])
    assert {r.claim.id: r.status for r in full_card.results} == QUICK_DIFFERS
    page = html_section(scorecard)
    for claim_id in QUICK_DIFFERS:
        assert f"<b>{claim_id}</b>: {scorecard[claim_id].status} here" in page
    assert "quick mode only" not in html_section(full_card)
