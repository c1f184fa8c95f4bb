"""Chapter 4 findings of the dissertation, each checked on a short study.

Studies use the two-stage swept amplitude (2.5 cm, f_T = 2.1 Hz), coarse frequency grids
and a 0.5 ms step (the measures agree with the 0.1 ms default to 4 digits). Where our model
does not reproduce a finding as the dissertation states it, the test states the claim
unchanged and is marked ``xfail(strict=True)`` with our numbers, so it turns into a
failure the day the model starts to agree.
"""

from __future__ import annotations

import itertools
from typing import Any

import numpy as np
import pytest

from mrsuspension.studies import Study, StudyResult, run_study

# Section 4.3.1: gains chosen for the same peak current (about 0.5 A), SCM defaults
POLICIES = {
    "I": {"controller": {"law": "skyhook-hilo", "gain": 3.0}},
    "II": {"controller": {"law": "policy-ii", "gain": 10.0}},
    "III": {"controller": {"law": "policy-iii", "gain": 10.0}},
    "IV": {"controller": {"law": "policy-iv", "gain": 300.0}},
}


def _sweep(frequencies: str) -> dict[str, Any]:
    return {
        "excitation": {
            "kind": "swept",
            "amplitude": 0.025,
            "transition_frequency": 2.1,
            "frequencies": frequencies,
        },
        "simulation": {"dt": 5e-4},
    }


def _run(data: dict[str, Any]) -> StudyResult:
    return run_study(Study.from_dict(data), progress=False, cache_dir=False)


#: 14 log-spaced frequencies plus the 2.2-2.4 Hz band where policy I jumps to a
#: large-amplitude response (a coarse log grid steps over it)
POLICY_FREQUENCIES = sorted(
    {round(float(f), 6) for f in np.geomspace(0.5, 15.0, 14)} | {2.2, 2.25, 2.3, 2.35, 2.4}
)


@pytest.fixture(scope="module")
def policies() -> StudyResult:
    return _run(
        {
            **_sweep("log:14:0.5:15"),
            "excitation": {
                "kind": "swept",
                "amplitude": 0.025,
                "transition_frequency": 2.1,
                "frequencies": POLICY_FREQUENCIES,
            },
            "study": {"name": "policies-4.3.1", "measures": ["T_as", "DLC"]},
            "cases": {"policy": POLICIES},
        }
    )


@pytest.fixture(scope="module")
def policies_identified_range() -> StudyResult:
    """The policies with v_m clamped to the identified velocity range (v_max = 0.75 m/s)."""
    return _run(
        {
            **_sweep("log:14:0.5:15"),
            "excitation": {
                "kind": "swept",
                "amplitude": 0.025,
                "transition_frequency": 2.1,
                "frequencies": POLICY_FREQUENCIES,
            },
            "damper": {"v_max": 0.75},
            "study": {"name": "policies-4.3.1-vmax", "measures": ["T_as"]},
            "cases": {"policy": POLICIES},
        }
    )


@pytest.fixture(scope="module")
def passive() -> StudyResult:
    return _run(
        {
            **_sweep("lin:21:1:3.5"),  # fine enough to find the body-resonance peak
            "controller": {"law": "passive"},
            "study": {"name": "passive-current", "measures": ["T_as"]},
            "grid": {"controller.current": [0.0, 0.05, 0.1, 0.2]},
        }
    )


@pytest.fixture(scope="module")
def masses() -> StudyResult:
    return _run(
        {
            **_sweep("log:14:0.5:15"),
            "controller": {"law": "skyhook-hilo", "mode": "ACM", "gain": 3.0},
            "study": {"name": "sprung-mass-4.4.1", "measures": ["DLC"]},
            "grid": {"vehicle.sprung_mass": [422.0, 563.0, 703.0]},
        }
    )


def test_policy_i_lowest_t_as_from_3_to_8_hz(policies: StudyResult) -> None:
    """4.3.1: policy I attenuates the body acceleration better than II and III at 3-8 Hz."""
    t_as = policies["T_as"]
    band = t_as.sel(frequency=slice(3.0, 8.0))
    assert band.sizes["frequency"] >= 3
    one = band.sel(policy="I").values
    for other in ("II", "III"):
        assert np.all(one < band.sel(policy=other).values), (other, band.to_pandas())


def _iv_highest(result: StudyResult) -> None:
    peak = result["T_as"].sel(frequency=slice(0.5, 4.0)).max("frequency")
    iv = float(peak.sel(policy="IV"))
    for other in ("I", "II", "III"):
        assert iv > float(peak.sel(policy=other)), peak.to_pandas()


@pytest.mark.xfail(
    strict=True,
    reason=(
        "does not hold with the spec's default clamp v_max = 1 m/s: near 2.3 Hz policy I "
        "runs away into a high-force regime (T_as = 5.9 at 2.35 Hz with dt = 0.5 ms, 6.8 "
        "at 2.3 Hz with 0.1 ms, T_au about 30, |F_d| up to 50 kN, a 140 Hz wheel "
        "oscillation). Mechanism: the window estimate v_m climbs past the identified range "
        "(0.05-0.75 m/s); F_t = F0 (1 + exp(a1 v_m)) and the hysteresis width v_h = k4 v_m "
        "grow with it, so the damper produces kN at zero velocity, which raises |v_d| and "
        "v_m further until the clamp. Policy IV peaks at 4.4, II and III at 1.71 and 1.78. "
        "With v_max = 0.75 m/s the claim holds (next test)"
    ),
)
def test_policy_iv_highest_body_resonance_peak(policies: StudyResult) -> None:
    """4.3.1: policy IV (relative-displacement modulation) gives the highest resonant T_as."""
    _iv_highest(policies)


def test_policy_iv_highest_peak_within_identified_range(
    policies_identified_range: StudyResult,
) -> None:
    """4.3.1 holds when v_m stays in the identified range: IV 2.74 against I 2.44."""
    _iv_highest(policies_identified_range)
    t_as_i = policies_identified_range["T_as"].sel(policy="I", frequency=slice(2.2, 2.4))
    assert float(t_as_i.max()) < 3.0  # no runaway


def _peaks(passive: StudyResult) -> list[float]:
    return [float(v) for v in passive["T_as"].max("frequency").values]


def test_passive_current_lowers_resonance_peak_up_to_0_1_a(passive: StudyResult) -> None:
    """4.3.2 (Fig. 4.9 compares 0 and 0.1 A): more passive current, lower T_as peak."""
    peaks = _peaks(passive)[:3]  # 0, 0.05, 0.1 A
    assert peaks[0] > peaks[1] > peaks[2], peaks


@pytest.mark.xfail(
    strict=True,
    reason=(
        "does not hold in our model at 0.2 A: peak T_as = 3.14, 2.51, 2.19, 2.26 for "
        "0, 0.05, 0.1, 0.2 A; at 0.2 A the damper nears lock-up and the peak moves from "
        "1.5 Hz to 2.25 Hz and rises again"
    ),
)
def test_passive_current_lowers_resonance_peak_0_to_0_2_a(passive: StudyResult) -> None:
    """4.3.2/7.3.1 as stated for 0, 0.05, 0.1 and 0.2 A."""
    peaks = _peaks(passive)
    assert all(a > b for a, b in itertools.pairwise(peaks)), peaks


def test_lighter_vehicle_highest_peak_dlc(masses: StudyResult) -> None:
    """4.4.1: the 422 kg vehicle has the highest DLC at resonance."""
    peak = masses["DLC"].max("frequency")
    light = float(peak.sel({"vehicle.sprung_mass": 422.0}))
    assert light > float(peak.sel({"vehicle.sprung_mass": 563.0}))
    assert light > float(peak.sel({"vehicle.sprung_mass": 703.0}))


@pytest.mark.xfail(
    strict=True,
    reason=(
        "does not hold in our model below the body resonance: DLC at 1.1 Hz = 0.122, "
        "0.147, 0.174 for 422, 563, 703 kg (lighter is lower up to about 1.9 Hz); it holds "
        "from 2.4 Hz up (e.g. 0.084 > 0.060 > 0.046 at 4.1 Hz)"
    ),
)
def test_lighter_vehicle_higher_dlc_at_every_frequency(masses: StudyResult) -> None:
    """4.4.1 as stated: 'the lower mass yields higher DLC in the entire frequency range'."""
    dlc = masses["DLC"]
    light = dlc.sel({"vehicle.sprung_mass": 422.0}).values
    for m in (563.0, 703.0):
        assert np.all(light > dlc.sel({"vehicle.sprung_mass": m}).values), dlc.to_pandas()
