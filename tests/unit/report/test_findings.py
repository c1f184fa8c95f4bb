"""The findings scorecard's data and checks, without simulations (synthetic payloads)."""

from __future__ import annotations

import os
import re
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from mrsuspension import ValidationError
from mrsuspension.report.findings import (
    CLAIMS,
    CLAIMS_BY_ID,
    ROAD,
    SAR,
    SKIPPED,
    Claim,
    Scorecard,
    evaluate,
    html_section,
    units,
)
from mrsuspension.report.findings import checks as F
from mrsuspension.report.findings.claims import KNOWN

#: the dissertation's text: MRSUS_DISSERTATION, or shared/seed/ beside the checkout
_SEED = Path(
    os.environ.get(
        "MRSUS_DISSERTATION",
        Path(__file__).resolve().parents[4] / "shared" / "seed" / "dissertation.txt",
    )
)


def _norm(text: str) -> str:
    quotes = {"\u201c": '"', "\u201d": '"', "\u2018": "'", "\u2019": "'"}
    for a, b in quotes.items():
        text = text.replace(a, b)
    return re.sub(r"\s+", " ", text)


@pytest.mark.skipif(not _SEED.exists(), reason=f"dissertation text not found at {_SEED}")
def test_every_quote_is_verbatim() -> None:
    text = _norm(_SEED.read_text(encoding="utf-8"))
    missing = [c.id for c in CLAIMS if _norm(c.quote) not in text]
    assert not missing, missing


def test_claims_are_well_formed() -> None:
    ids = [c.id for c in CLAIMS]
    assert len(ids) == len(set(ids))
    assert len(CLAIMS) >= 30
    for c in CLAIMS:
        assert c.id.startswith(c.section.split(".")[0]), c.id
        for section in (c.section, *c.also):
            assert re.fullmatch(r"[4-8](\.\d+){1,2}", section), (c.id, section)
        assert c.check.runs, c.id
        assert set(c.depends_on) <= {ROAD, SAR}, c.id
        assert len(c.quote) >= 20, c.id
        assert c.claim.endswith("."), c.id


def test_road_claims_say_so() -> None:
    """Every claim on a random road depends on the road presets, and only those do."""
    for c in CLAIMS:
        on_road = any(r.kind == "psd" for r in c.check.runs.values())
        assert on_road == (ROAD in c.depends_on), c.id


def test_known_failures_name_existing_claims_and_a_cause() -> None:
    assert set(KNOWN) <= set(CLAIMS_BY_ID)
    for claim_id, cause in KNOWN.items():
        assert CLAIMS_BY_ID[claim_id].known == cause
        assert len(cause) > 20, claim_id
    assert all(len(s) == 3 and all(s) for s in SKIPPED)


def test_runs_reuse_the_report_figures() -> None:
    run = F.fig("4.12", "m_s = 422 kg")
    assert run.kind == "time"
    assert run.scenario["vehicle"] == {"sprung_mass": 422.0}
    assert F.fig("4.5", "policy I (k_c = 3)").scenario["excitation"]["frequencies"][0] == 0.5
    assert F.table("5.1", 703.0).scenario["controller"]["law"] == "inverse-hilo"
    with pytest.raises(ValidationError, match="no figure"):
        F.fig("4.5", "policy V")
    with pytest.raises(ValidationError, match="no shock table"):
        F.table("4.1", 500.0)
    with pytest.raises(ValidationError, match="run kind"):
        F.Run.of("movie", {})
    # quick units of the claims: shared, far fewer than the references to them
    assert len(units(quick=True)) < sum(len(c.check.runs) for c in CLAIMS) / 2


# -- checks on synthetic payloads ---------------------------------------------------------
_A, _B, _C = (F.Run.of("pulse", {"vehicle": {"sprung_mass": m}}) for m in (422.0, 563.0, 703.0))


def test_compare_and_monotone() -> None:
    m = F.SHOCK["SDR_s"]
    check = F.compare(m, {"a": _A}, {"b": _B, "c": _C}, "<", 0.9)
    assert check({"a": {"SDR_s": 0.5}, "b": {"SDR_s": 0.6}, "c": {"SDR_s": 0.7}}).holds
    v = check({"a": {"SDR_s": 0.55}, "b": {"SDR_s": 0.6}, "c": {"SDR_s": 0.7}})
    assert not v.holds
    assert "b" in v.why
    inc = F.monotone(m, {"a": _A, "b": _B, "c": _C})
    assert inc({"a": {"SDR_s": 1}, "b": {"SDR_s": 2}, "c": {"SDR_s": 3}}).holds
    assert not inc({"a": {"SDR_s": 1}, "b": {"SDR_s": 3}, "c": {"SDR_s": 2}}).holds
    with pytest.raises(ValidationError, match="direction"):
        F.monotone(m, {"a": _A}, "sideways")


def test_spread_change_and_ratio() -> None:
    m = F.SHOCK["SAR_s"]
    runs = {"a": _A, "b": _B}
    assert F.spread(m, runs, 0.1)({"a": {"SAR_s": 1.0}, "b": {"SAR_s": 1.05}}).holds
    assert not F.spread(m, runs, 0.1)({"a": {"SAR_s": 1.0}, "b": {"SAR_s": 1.2}}).holds
    change = F.change(m, ("b", _B), {"a": (_A, 0.32)})
    assert change({"a": {"SAR_s": 1.3}, "b": {"SAR_s": 1.0}}).holds  # +30 % for +32 %
    assert not change({"a": {"SAR_s": 0.7}, "b": {"SAR_s": 1.0}}).holds  # wrong sign
    assert not change({"a": {"SAR_s": 1.1}, "b": {"SAR_s": 1.0}}).holds  # +10 %: too small
    ratio = F.ratio(m, ("a", _A), ("b", _B), 0.35, 0.65)
    assert ratio({"a": {"SAR_s": 0.5}, "b": {"SAR_s": 1.0}}).holds
    assert not ratio({"a": {"SAR_s": 0.7}, "b": {"SAR_s": 1.0}}).holds


def test_fraction_of_frequencies() -> None:
    f = np.linspace(0.5, 15.0, 10)
    lo = {"frequency": f, "T_as": np.ones(10)}
    hi = {"frequency": f, "T_as": np.r_[np.zeros(4), 2 * np.ones(6)]}
    runs = (F.Run.of("freq", {}), F.Run.of("freq", {"controller": {"law": "passive"}}))
    check = F.fraction("T_as", ("x", runs[0]), {"y": runs[1]}, "<")
    assert check({"x": lo, "y": hi}).holds  # 60 % > 50 %
    every = F.fraction("T_as", ("x", runs[0]), {"y": runs[1]}, "<", at_least=1.0,
                       strictly_more=False)  # fmt: skip
    assert not every({"x": lo, "y": hi}).holds


def test_dtr_and_rank() -> None:
    w0 = 653.0 * 9.81
    nominal = {"peak_tire_force": 10000.0, "static load [N]": w0}
    light = {"peak_tire_force": 10000.0 - 0.26 * w0, "static load [N]": w0}
    check = F.dtr_values(("b", _B), {"a": (_A, 0.26)})
    assert check({"b": nominal, "a": light}).holds
    assert "0.26" in check({"b": nominal, "a": light}).numbers
    metric = F.SHOCK["SDR_s"]
    rank = F.rank(F.relative_spread(metric), "spread", {"x": {"1": _A, "2": _B},
                  "y": {"1": _A, "2": _C}}, "x")  # fmt: skip
    pay = {"x: 1": {"SDR_s": 1.0}, "x: 2": {"SDR_s": 1.1}, "y: 1": {"SDR_s": 1.0}}
    assert rank({**pay, "y: 2": {"SDR_s": 1.5}}).holds
    tie = rank({**pay, "y: 2": {"SDR_s": 1.1}})
    assert not tie.holds
    assert tie.why == "a tie"


def test_all_of_rejects_one_label_for_two_runs() -> None:
    m = F.SHOCK["SDR_s"]
    with pytest.raises(ValidationError, match="two different runs"):
        F.all_of(F.compare(m, {"a": _A}, {"b": _B}), F.compare(m, {"a": _C}, {"b": _B}))


def test_history_metrics() -> None:
    t = np.arange(0.0, 4.0, 1e-3)
    slow = np.sin(2 * np.pi * 1.5 * t)
    payload = {
        "time": t,
        "a_u": slow + 0.5 * np.sin(2 * np.pi * 10.0 * t),
        "v_r": np.cos(2 * np.pi * 1.5 * t),
        "F_d": 1000.0 * np.cos(2 * np.pi * 1.5 * t) + 500.0,
    }
    share = F.hf_fraction("a_u")(payload)
    assert share == pytest.approx(0.5 / np.sqrt(1.25), rel=1e-3)
    ratio = F.band_amplitude("a_u", 8, 12)(payload) / F.band_amplitude("a_u", 1.4, 1.6)(payload)
    assert ratio == pytest.approx(0.5, rel=1e-2)
    assert F.phase_peak("F_d", "compression")(payload) == pytest.approx(1500.0, rel=1e-6)
    assert F.phase_peak("F_d", "rebound")(payload) == pytest.approx(500.0, rel=1e-3)


def test_evaluate_reuses_given_payloads_and_reports_errors() -> None:
    """A claim evaluated on a payload handed in is not run again; a broken check is an
    error row, not an exception."""
    claim = CLAIMS_BY_ID["4.3.2-gamma"]
    payloads = {r.unit(quick=True): {"gamma": 2.4} for r in claim.check.runs.values()}
    payloads[claim.check.runs["SCM"].unit(quick=True)] = {"gamma": 1.0}
    card = evaluate(quick=True, claims=[claim], payloads=payloads)
    assert isinstance(card, Scorecard)
    n = len({r.unit(quick=True) for r in claim.check.runs.values()})  # SCM, ACM per reading
    assert (card.reused, card.runs, card.cpu_time) == (n, n, 0.0)
    assert card[claim.id].holds
    assert card[claim.id].status == "held"
    broken = evaluate(quick=True, claims=[claim], payloads={u: {} for u in payloads})
    assert broken[claim.id].status == "error"
    assert "KeyError" in broken[claim.id].explanation
    row = card.rows()[0]
    assert (row["holds"], row["section"]) == ("yes", claim.sections)


def test_chapters_option_accepts_findings() -> None:
    from mrsuspension.cli import _chapters

    assert _chapters("4, findings,beyond") == [4, "findings", "beyond"]
    with pytest.raises(ValidationError, match="'findings'"):
        _chapters("scorecard")


def test_claims_markdown_lists_every_claim() -> None:
    from mrsuspension.report.findings import claims_markdown

    page = claims_markdown()
    for c in CLAIMS:
        assert f"| {c.id} | {c.sections} |" in page


# -- readings: the kept one, the others, none --------------------------------------------
def test_dtr_readings_differ_over_the_mass_only() -> None:
    w0, w = 653.0 * 9.81, 512.0 * 9.81  # 563 and 422 kg
    nominal = {"peak_tire_force": w0 + 5000.0, "static load [N]": w0}
    light = {"peak_tire_force": w + 5000.0, "static load [N]": w}  # same dynamic peak
    got = {r: F.dtr_of(nominal, light, r) for r in F.DTR_READINGS}
    assert got["3.44"] == pytest.approx((w0 - w) / w0)  # the static-load change, 0.216
    assert got["dynamic"] == pytest.approx(0.0, abs=1e-12)
    assert got["ratio"] == pytest.approx(5000.0 / w - 5000.0 / w0)
    assert got["peak"] == pytest.approx((w0 - w) / (w0 + 5000.0))  # over the nominal peak
    same_mass = {"peak_tire_force": w0 + 4000.0, "static load [N]": w0}
    by_load = [r for r in F.DTR_READINGS if r != "peak"]  # the readings over a static load
    assert len({round(F.dtr_of(nominal, same_mass, r), 12) for r in by_load}) == 1
    assert F.dtr_of(nominal, same_mass, "peak") == pytest.approx(1000.0 / (w0 + 5000.0))
    with pytest.raises(ValidationError, match="DTR reading"):
        F.dtr_of(nominal, light, "static")


def test_no_larger_reads_ties_and_controlled_peak_skips_the_first_stroke() -> None:
    ms = {"x": lambda g: g["r"]["x"]}
    groups = {"A": {"r": _A}, "B": {"r": _B}, "C": {"r": _A}}
    pay = {"A: r": {"x": 1.0}, "B: r": {"x": 1.005}, "C: r": {"x": 1.2}}
    assert not F.no_larger(ms, groups, "A")(pay).holds  # a tie with B: smaller than C only
    assert F.no_larger(ms, groups, "A", against="any")(pay).holds
    v = F.no_larger(ms, groups, "A", tie=0.001)(pay)
    assert v.holds
    assert "A 1" in v.numbers
    worse = F.no_larger(ms, groups, "A")({**pay, "B: r": {"x": 0.9}})
    assert not worse.holds
    assert "x: A 1 > B 0.9" in worse.why
    with pytest.raises(ValidationError, match="against"):
        F.no_larger(ms, groups, "A", against="all")
    m = F.controlled_peak("a_s")
    assert (
        m({"v_r": [0.0, 0.0, 0.5, 0.2, -0.3, 0.1], "a_s": [0.0, 7.0, 9.0, 1.0, 2.0, -4.0]}) == 4.0
    )
    with pytest.raises(ValidationError, match="never ends"):
        m({"v_r": [0.0, 0.5], "a_s": [1.0, 2.0]})
    with pytest.raises(ValidationError, match="no compression stroke"):
        m({"v_r": [0.0, -0.5], "a_s": [1.0, 2.0]})


def _claim(check: F.Check) -> Claim:
    return Claim("4.9-test", "4.9", "a quote of twenty characters", "A test.", check)


def test_readings_give_the_stated_reading_or_none() -> None:
    m = F.SHOCK["SDR_s"]
    lower = F.compare(m, {"a": _A}, {"b": _B}, "<")
    higher = F.compare(m, {"a": _A}, {"b": _B}, ">")
    both = F.readings(("kept: lower", lower), ("other: higher", higher))
    pay = {"a": {"SDR_s": 0.9}, "b": {"SDR_s": 0.8}}
    v = both(pay)
    assert (v.holds, v.reading, v.exhausted) == (True, "other: higher", False)
    assert "under other: higher" in v.numbers
    assert "kept: lower" in v.why
    kept = both({"a": {"SDR_s": 0.7}, "b": {"SDR_s": 0.8}})
    assert (kept.holds, kept.reading) == (True, "")
    none = F.readings(("kept: lower", lower))(pay)
    assert (none.holds, none.exhausted) == (False, True)
    assert none.why.startswith("not held for any admissible reading")
    # all_of: a part held under a reading carries it; exhausted only if every failure is
    plain = F.compare(m, {"c": _C}, {"b": _B}, "<")
    joined = F.all_of(both, plain)
    assert joined({**pay, "c": {"SDR_s": 0.5}}).reading == "other: higher"
    assert not joined({**pay, "c": {"SDR_s": 0.9}}).exhausted
    assert F.all_of(F.readings(("kept: lower", lower)), plain)(
        {**pay, "c": {"SDR_s": 0.5}}
    ).exhausted
    # the scorecard's statuses, counts and html
    payloads = {
        _A.unit(quick=True): {"SDR_s": 0.9},
        _B.unit(quick=True): {"SDR_s": 0.8},
    }
    card = evaluate(
        quick=True,
        claims=[_claim(both), replace(_claim(F.readings(("kept: lower", lower))), id="4.9-none")],
        payloads=payloads,
    )
    assert [r.status for r in card.results] == [
        "held under a stated reading",
        "not held for any admissible value",
    ]
    assert "Held under the stated reading: other: higher" in card.results[0].explanation
    counts = card.counts()
    assert counts["held under a stated reading"] == counts["not held for any admissible value"] == 1
    assert counts["held"] == counts["not held"] == 0
    page = html_section(card)
    assert "held under a stated reading" in page
    assert "#eef6d8" in page
    assert "not held for any admissible value" in page


def test_retabled_changes_only_the_named_laws_runs() -> None:
    sm = F.Run.of("time", {"controller": {"law": "sliding-mode", "mode": "ACM"}})
    check = F.compare(F.MEAN_CURRENT, {"sm": sm}, {"passive": _B}, "<")
    beta = F.retabled(check, "beta 2", "sliding-mode", controller={"beta": 2.0})
    assert set(beta.runs) == {"sm [beta 2]", "passive [beta 2]"}
    assert beta.runs["sm [beta 2]"].scenario["controller"]["beta"] == 2.0
    assert beta.runs["passive [beta 2]"] == _B
    v = beta(
        {"sm [beta 2]": {"mean current [A]": 0.1}, "passive [beta 2]": {"mean current [A]": 0.2}}
    )
    assert v.holds


def test_pulse_end_and_the_dlc_over_the_nominal_load() -> None:
    assert F.pulse_end(_B) == pytest.approx(0.5 + 3 * np.pi / (3 * 10.4), rel=1e-3)
    fast = F.Run.of("pulse", {"excitation": {"speed": 100.0}})
    assert F.pulse_end(fast) == pytest.approx(0.5 + 3 * np.pi / (3 * 20.8), rel=1e-3)
    with pytest.raises(ValidationError, match="not a rounded-pulse run"):
        F.pulse_end(F.Run.of("time", {}))
    assert F.ROAD_DLC_NOMINAL({"std F_T [N]": 0.1 * 653.0 * 9.81}) == pytest.approx(0.1)
    window = F.residual("x_s", 0.8)
    t = np.arange(0.0, 4.0, 1e-3)
    x = np.where(t < 0.8, 1.0, 0.0)
    assert window({"time": t, "x_s": x}) == 0.0
    assert F.residual("x_s", 0.5)({"time": t, "x_s": x}) > 0.0


def test_failing_road_claims_are_checked_on_the_identified_spectra() -> None:
    """Issue 30, group 4: the random-road claims that fail on the reference presets carry
    the identified road spectra as a reading (and 4.4.3's the white rough road too)."""
    from mrsuspension.report.findings.claims.common import ROAD_WHITE_ROUGH

    for claim_id in ("4.4.2-road-current", "4.4.3-road-ride-comparable", "5.5.2-road-dlc"):
        runs = [r for r in CLAIMS_BY_ID[claim_id].check.runs.values() if r.kind == "psd"]
        spectra = [r.scenario.get("excitation", {}).get("spectrum") for r in runs]
        assert spectra.count("identified") > 0, claim_id
        assert len(spectra) == spectra.count("identified") * (3 if "comparable" in claim_id else 2)
        assert claim_id not in KNOWN  # held under the stated reading
    assert "6.3-road-dlc" in KNOWN
    runs = CLAIMS_BY_ID["4.4.3-road-ride-comparable"].check.runs.values()
    white = {
        r.scenario["excitation"]["profile"]: r.scenario["excitation"]["waviness"]
        for r in runs
        if "waviness" in r.scenario.get("excitation", {})
    }
    assert white == {k: v["waviness"] for k, v in ROAD_WHITE_ROUGH.items()}


def test_swept_reads_every_admissible_value_of_the_unknowns_involved() -> None:
    """Issue 30, group 5: the ADFG centre where an ADFG law runs outside SCM, beta where
    sliding mode runs, nothing else; a check with no unknown is its own only reading."""
    from mrsuspension.report.findings.claims.common import _ADFG_SWEEP, _BETAS, _swept

    acm = F.Run.of("pulse", {"controller": {"law": "skyhook-hilo", "mode": "ACM"}})
    scm = F.Run.of("pulse", {"controller": {"law": "skyhook-hilo", "mode": "SCM"}})
    sliding = F.Run.of("pulse", {"controller": {"law": "sliding-mode", "mode": "ACM"}})
    passive = F.Run.of("pulse", {"controller": {"law": "passive"}})

    def lower(run: F.Run) -> F.Check:
        return F.compare(F.SHOCK["SDR_s"], {"x": run}, {"passive": passive}, "<")

    swept = _swept(lower(acm))
    centres = [r.scenario["controller"].get("adfg_centre") for r in swept.runs.values()]
    assert sorted(c for c in centres if c is not None) == sorted(_ADFG_SWEEP)
    assert {
        r.scenario["controller"].get("beta") for r in _swept(lower(sliding)).runs.values()
    } >= set(_BETAS)
    only = _swept(lower(scm))
    assert sorted(only.runs) == ["passive", "x"]
    fails = {k: {"SDR_s": 0.9 if k.startswith("x") else 0.8} for k in swept.runs}
    verdict = swept(fails)
    assert not verdict.holds
    assert verdict.exhausted
    verdict = only({"x": {"SDR_s": 0.9}, "passive": {"SDR_s": 0.8}})
    assert verdict.exhausted
    assert "no unknown parameter involved" in verdict.numbers
    held = {
        k: {"SDR_s": 0.7 if k.startswith("x [adfg 0]") else fails[k]["SDR_s"]} for k in swept.runs
    }
    verdict = swept(held)
    assert verdict.holds
    assert verdict.reading == "ADFG centre 0"


def test_a_kept_reading_that_held_under_its_own_reading_keeps_its_name() -> None:
    """A sweep (readings) around a check that is itself read two ways: the inner reading
    that held reaches the scorecard, so the claim is not counted as plainly held."""
    m = F.SHOCK["SDR_s"]
    lower = F.compare(m, {"a": _A}, {"b": _B}, "<")
    higher = F.compare(m, {"a": _A}, {"b": _B}, ">")
    inner = F.readings(("kept: lower", lower), ("other: higher", higher))
    outer = F.readings(("defaults", inner), ("never", F.compare(m, {"a": _A}, {"b": _B}, "<")))
    v = outer({"a": {"SDR_s": 0.9}, "b": {"SDR_s": 0.8}})
    assert (v.holds, v.reading) == (True, "other: higher")
    assert "kept: lower" in v.why
    plain = outer({"a": {"SDR_s": 0.7}, "b": {"SDR_s": 0.8}})
    assert (plain.holds, plain.reading) == (True, "")


def test_the_full_build_sweeps_the_frequency_response_claims() -> None:
    """Issue 30: the claims of SWEPT_IN_FULL are checked over the control unknowns in the
    full build only; quick mode (CI) keeps their own check and names them in its note."""
    from mrsuspension.report.findings import SWEPT_IN_FULL, check_of, history_keys

    assert len(SWEPT_IN_FULL) == 7
    quick_units, full_units = set(units(True)), set(units(False))
    for claim_id in SWEPT_IN_FULL:
        claim = CLAIMS_BY_ID[claim_id]
        assert claim.known  # not held under any value: a strict xfail
        assert check_of(claim, quick=True) is claim.check
        full = check_of(claim, quick=False)
        assert full is check_of(claim, quick=False)  # built once
        assert set(claim.check.runs) < set(full.runs)
        values = {
            (
                r.scenario.get("controller", {}).get("adfg_centre"),
                r.scenario["controller"].get("beta"),
            )
            for r in full.runs.values()
        }
        assert len(values) > 2, claim_id  # the defaults and at least two swept values
        assert {r.unit(quick=False) for r in full.runs.values()} <= full_units
    assert len(full_units) > len(quick_units)
    assert {k for k, _ in history_keys(False)} == {"history"}
    other = CLAIMS_BY_ID["4.3.2-gamma"]
    assert check_of(other, quick=False) is other.check
    from mrsuspension.report.findings import ClaimResult

    swept = CLAIMS_BY_ID["6.5-rattle-space"]
    result = ClaimResult(swept, False, "not held", "numbers", "why")
    note = "also checks these claims over the admissible range"
    assert note in html_section(Scorecard([result], quick=True))
    assert note not in html_section(Scorecard([result], quick=False))
    assert note not in html_section(Scorecard([], quick=True))
