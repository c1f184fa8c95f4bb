"""The dissertation's testable claims (Chapters 4-6 texts and summaries, Chapter 8), as data.

Each :class:`~mrsuspension.report.findings.checks.Claim` quotes the dissertation verbatim
(``quote``), states our reading (``claim``) and tests it on the report's runs
(:func:`~mrsuspension.report.findings.checks.fig`, :func:`~mrsuspension.report.findings.
checks.table`). Sections follow the dissertation; ``also`` lists the summaries and
conclusions that restate a claim. :data:`SKIPPED` lists what no quarter-car simulation can
test, with the reason.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Mapping
from dataclasses import replace
from typing import Any

import numpy as np

from mrsuspension.control import CONTROLLERS, HiLo, SlidingMode, law_options
from mrsuspension.control.shaped import ADFG_CENTRE_IDENTIFIED
from mrsuspension.control.sliding import BETA_COVERING
from mrsuspension.report.findings.checks import (
    ABOUT,
    CONSIDERABLY,
    DTR_READINGS,
    GAMMA,
    INSENSITIVE,
    MEAN_CURRENT,
    ROAD,
    ROAD_DLC,
    ROAD_DLC_NOMINAL,
    SAR,
    SHOCK,
    SLIGHT,
    TRACKING,
    Check,
    Claim,
    Payload,
    Run,
    Verdict,
    about,
    about_each,
    all_of,
    amplitude,
    band_amplitude,
    change,
    compare,
    dtr_of,
    dtr_values,
    fig,
    figs,
    fmean,
    fpeak,
    fraction,
    hf_fraction,
    max_rate,
    mean_of,
    monotone,
    peak,
    phase_peak,
    psd_mean,
    pulse_end,
    rank,
    ratio,
    readings,
    relative_spread,
    relative_tracking,
    relative_tracking_all,
    residual,
    retabled,
    rms_rate,
    road_current_std,
    rows,
    spread,
    time_above,
    within,
)

__all__ = ["CLAIMS", "KNOWN", "SKIPPED"]


# -- the runs, named once -----------------------------------------------------------------
def _policies(number: str, **kw: Any) -> dict[str, Run]:
    """Policies I-IV (SCM, k_c = 3, 10, 10, 300) of a Chapter 4 policy figure."""
    labels = {
        "I": "policy I (k_c = 3)",
        "II": "policy II (k_c = 10)",
        "III": "policy III (k_c = 10)",
        "IV": "policy IV (k_c = 300)",
    }
    return {k: fig(number, v, **kw) for k, v in labels.items()}


def _one(runs: Mapping[str, Run], label: str) -> tuple[str, Run]:
    return label, runs[label]


def _sub(runs: Mapping[str, Run], *labels: str) -> dict[str, Run]:
    return {k: runs[k] for k in labels}


POL_T = _policies("4.4")
POL_F = _policies("4.5")
SKY_T = figs("4.6")  # SCM, ACM (k_c = 3, n = 2)
SKY_H = figs("4.6", kind="history")
SKY_F15 = figs("4.7")  # constant 1.5 cm over 0.5-15 Hz (the figure's own base)
P4_T = figs("4.8")  # passive 0 A, passive 0.1 A, skyhook hi-lo ACM
P4_F = figs("4.9")
P4_P = figs("4.10")
P4_R = figs("4.11")
M4_T, M4_F, M4_P, M4_R = figs("4.12"), figs("4.13"), figs("4.14"), figs("4.15")
V4_P, V4_R = figs("4.16"), figs("4.17")
A4_T, A4_F, A4_P = figs("4.18"), figs("4.19"), figs("4.20")
R4 = figs("4.21")
K4_T, K4_F, K4_P, K4_R = figs("4.22"), figs("4.23"), figs("4.24"), figs("4.25")
N4_T, N4_F, N4_P, N4_R = figs("4.26"), figs("4.27"), figs("4.28"), figs("4.29")
T41, T42, T43, T44, T45 = rows("4.1"), rows("4.2"), rows("4.3"), rows("4.4"), rows("4.5")

INV_SCM1 = {  # Figs 5.1-5.3: SCM, k_d = 1
    "mean damper + mean inverse": fig("5.1", "mean damper + mean inverse"),
    "hysteretic damper + mean inverse": fig("5.2", "hysteretic damper + mean inverse"),
    "hysteretic damper + hysteretic inverse": fig("5.3", "hysteretic damper + hysteretic inverse"),
}
INV_H1 = fig("5.3", "hysteretic damper + hysteretic inverse", kind="history")
INV_MODES = figs("5.4")  # SCM, ACM at k_d = 1
INV_MIX = figs("5.5")  # ACM, k_d = 1: mean/mean, hyst/hyst, hyst/mean
INV_KD = figs("5.6")  # ACM, k_d = 1, 2, 2.5
INV_KD_SCM = figs("5.6", controller={"mode": "SCM"})
INV_KD_F = figs("5.7")
P5_T, P5_F, P5_P, P5_R = figs("5.8"), figs("5.9"), figs("5.10"), figs("5.11")
M5_T, M5_F, M5_P, M5_R = figs("5.12"), figs("5.13"), figs("5.14"), figs("5.15")
V5_P, V5_R = figs("5.16"), figs("5.17")
A5_T, A5_F, A5_P = figs("5.18"), figs("5.19"), figs("5.20")
R5 = figs("5.21")
T51, T52, T53 = rows("5.1"), rows("5.2"), rows("5.3")

SM_MIX_SCM = {  # Figs 6.1-6.2: sliding mode SCM, k_d = 1 (section 6.2), the figures' own runs
    "hysteretic damper + mean inverse": fig("6.1", "hysteretic damper + mean inverse"),
    "hysteretic damper + hysteretic inverse": fig("6.2", "hysteretic damper + hysteretic inverse"),
}
#: Figs 6.3-6.4: sliding mode SCM and ACM at k_d = 2.5 (section 6.2), the figures' own runs;
#: beside them Fig 6.2 (SCM, k_d = 1), the case the text compares them with
SM_34 = {
    "SCM k_d = 2.5": fig("6.3", "sliding mode SCM"),
    "ACM k_d = 2.5": fig("6.4", "sliding mode ACM"),
    "SCM k_d = 1": fig("6.2", "hysteretic damper + hysteretic inverse"),
}
SM_H1 = fig("6.5", "SCM k_d = 1", kind="history")
SM_G = figs("6.5")  # ACM k_d = 2.5, SCM k_d = 1, SCM k_d = 2.5
SM_G_H = figs("6.5", kind="history")
SM_G_F = figs("6.6")
SM_ACM1_F = fig("6.6", "ACM k_d = 2.5", damper={"force_gain": 1.0})
P6_T, P6_F, P6_P, P6_R = figs("6.7"), figs("6.8"), figs("6.9"), figs("6.10")
M6_T, M6_F, M6_P, M6_R = figs("6.11"), figs("6.12"), figs("6.13"), figs("6.14")
V6_P, V6_R = figs("6.15"), figs("6.16")
A6_T, A6_F, A6_P = figs("6.17"), figs("6.18"), figs("6.19")
R6 = figs("6.20")
T61, T62, T63 = rows("6.1"), rows("6.2"), rows("6.3")

INV_H = fig("5.8", "inverse-model hi-lo ACM", kind="history")
SM_H = fig("6.7", "sliding mode ACM", kind="history")
#: Section 6.5: the three ACM controllers (inverse laws with k_d = 2.5)
CTRL_F = {
    "skyhook hi-lo": P4_F["skyhook hi-lo ACM"],
    "inverse hi-lo": P5_F["inverse-model hi-lo ACM"],
    "sliding mode": P6_F["sliding mode ACM"],
}
PASSIVE_F = _sub(P4_F, "passive 0 A", "passive 0.1 A")

_M = ("m_s = 422 kg", "m_s = 563 kg", "m_s = 703 kg")
_X = ("m_s = 422 kg", "m_s = 703 kg")


def _road_levels(cases: Mapping[str, tuple[Run, float]], tol: float = ABOUT) -> Check:
    """Road DLCs within ``tol`` of the dissertation's values."""
    checks = [about(ROAD_DLC, {k: r}, given, tol) for k, (r, given) in cases.items()]
    return all_of(*checks)


# -- shared readings ----------------------------------------------------------------------
def _peaks_lower(
    signals: tuple[str, ...], semi: tuple[str, Run], others: Mapping[str, Run]
) -> Check:
    return all_of(*(compare(peak(s), dict([semi]), others, "<") for s in signals))


def _monotone_all(signals: tuple[str, ...], runs: Mapping[str, Run], direction: str) -> Check:
    return all_of(*(monotone(peak(s), runs, direction) for s in signals))


def _insensitive_shock(runs: Mapping[str, Run], keys: tuple[str, ...], limit: float) -> Check:
    return all_of(*(spread(SHOCK[k], runs, limit) for k in keys))


def _dtr_max(group: Mapping[str, Payload], reading: str = "ratio") -> float:
    """Largest DTR of a shock-table group against its nominal (563 kg, 50 km/h) row."""
    nominal = next(v for k, v in group.items() if k.endswith("= 563") or k.endswith("= 50"))
    return max(dtr_of(nominal, v, reading) for v in group.values())


def _dtr_readings(nominal: tuple[str, Run], changed: Mapping[str, tuple[Run, float]]) -> Check:
    """Stated DTRs over the sprung mass under every admissible DTR reading, the kept one
    (the peak tire force ratio, which Tables 5.1 and 6.1 support) first."""
    return readings(
        *((DTR_READINGS[r], dtr_values(nominal, changed, reading=r)) for r in DTR_READINGS)
    )


#: Sliding mode's switching-gain factor beta of (3.33): not given in the seed (default
#: 1.25, the model reference's); the admissible range from no margin (1: K = m_s0 phi) to a
#: margin of twice the nominal mass (2), with 1.335, the smallest covering the studied
#: 422-703 kg (docs/errata.md)
_BETA_DEFAULT = SlidingMode().beta
_BETAS: tuple[float, ...] = (1.0, 1.1, BETA_COVERING, 1.5, 2.0)


def _beta_sensitivity(check: Check) -> Check:
    """A sliding-mode check at the default beta (kept) and over :data:`_BETAS`."""
    return readings(
        (
            f"beta = {_BETA_DEFAULT:g} (the default, the model reference's; the seed gives none)",
            check,
        ),
        *(
            (
                f"beta = {b:g}",
                retabled(check, f"beta {b:g}", "sliding-mode", controller={"beta": b}),
            )
            for b in _BETAS
        ),
    )


#: The ADFG centre (M_p at v_d = 0, share of the way from p to 1): 0.5, (2.3) as the model
#: reference writes it, kept; the admissible readings are the value identified from the
#: dissertation's ACM currents (0.1, docs/errata.md) and section 3.2's "p = 0 ... i_d = 0
#: when v_r = 0" (0)
_ADFG_DEFAULT = HiLo(1, mode="ACM").adfg_centre
_ADFG_READINGS: tuple[tuple[float, str], ...] = (
    (
        ADFG_CENTRE_IDENTIFIED,
        "ADFG centre 0.1 (identified from the dissertation's ACM currents: the errata page)",
    ),
    (0.0, "ADFG centre 0 (section 3.2: p = 0 gives i_d = 0 at v_r = 0)"),
)


def _adfg_sensitivity(check: Check) -> Check:
    """A skyhook hi-lo check at the identified ADFG centre (kept) and its readings."""
    return readings(
        (f"ADFG centre {_ADFG_DEFAULT:g} ((2.3) as the model reference writes it)", check),
        *(
            (name, retabled(check, f"adfg {c:g}", "skyhook-hilo", controller={"adfg_centre": c}))
            for c, name in _ADFG_READINGS
        ),
    )


#: Policy gains of Figs 4.4/4.5 by the rule section 4.3.1 states ("to ensure identical peak
#: value of the drive current about i_H = 0.5 A"): the gain at which each policy's peak i_d
#: reaches 0.49 A at 2.5 cm / 1.5 Hz in our model (docs/errata.md), where the stated 3, 10,
#: 10, 300 reach 0.37, 0.36, 0.29, 0.22 A
_RULE_GAINS: dict[str, float] = {
    "skyhook-hilo": 4.2,
    "policy-ii": 18.0,
    "policy-iii": 26.0,
    "policy-iv": 1100.0,
}


def _rule_gain_sensitivity(check: Check) -> Check:
    """A Figs 4.4/4.5 policy check at the stated gains (kept) and at :data:`_RULE_GAINS`."""
    changed = check
    for law, gain in _RULE_GAINS.items():
        changed = retabled(changed, f"k_c {gain:g}", law, controller={"gain": gain})
    name = "gains by the stated rule (peak i_d 0.49 A: k_c = " + ", ".join(
        f"{g:g}" for g in _RULE_GAINS.values()
    )
    return readings(("stated gains k_c = 3, 10, 10, 300", check), (name + ")", changed))


#: the laws that shape their current with the ADFG multiplier (the ``adfg_centre`` option)
_ADFG_LAWS: tuple[str, ...] = tuple(
    law for law in CONTROLLERS if any(o.name == "adfg_centre" for o in law_options(law))
)


def _identified_sensitivity(check: Check) -> Check:
    """A check at the model reference's defaults (kept) and with the unknowns identified
    from the dissertation's numbers: the ADFG centre 0.1 in every ADFG-shaped law and
    sliding mode's covering beta 1.335 (docs/errata.md, "Control unknowns identified")."""
    changed = check
    for law in _ADFG_LAWS:
        changed = retabled(
            changed, f"adfg {ADFG_CENTRE_IDENTIFIED:g}", law,
            controller={"adfg_centre": ADFG_CENTRE_IDENTIFIED},
        )  # fmt: skip
    changed = retabled(
        changed, f"beta {BETA_COVERING:g}", "sliding-mode", controller={"beta": BETA_COVERING}
    )
    return readings(
        ("the model reference's defaults (ADFG centre 0.5, beta 1.25)", check),
        (
            f"the unknowns identified from the dissertation's numbers (ADFG centre "
            f"{ADFG_CENTRE_IDENTIFIED:g}, beta {BETA_COVERING:g}: the errata page)",
            changed,
        ),
    )


#: The pulse-decay windows: from the pulse's end (onset 0.5 s + 3 pi / (mu omega_0), the
#: duration section 3.5 gives: the oscillations left when the excitation is over), kept;
#: and from 1 s (the reading before)
_PULSE_END = pulse_end(figs("4.10")["passive 0 A"])
_DECAY_WINDOWS: tuple[tuple[str, float], ...] = (
    (
        f"decay read from the pulse's end ({_PULSE_END:.2f} s: onset + 3 pi / (mu omega_0))",
        _PULSE_END,
    ),
    ("decay read from 1 s", 1.0),
)


def _decay(lhs: Mapping[str, Run], rhs: Mapping[str, Run], factor: float = 1.0) -> Check:
    """rms x_s about its final value after the pulse: ``lhs`` below ``factor`` times ``rhs``,
    under each decay window of :data:`_DECAY_WINDOWS` (the first kept)."""
    return readings(
        *((name, compare(residual("x_s", t), lhs, rhs, "<", factor)) for name, t in _DECAY_WINDOWS)
    )


def _speed_change(metric: Any) -> Any:
    def measure(group: Mapping[str, Payload]) -> float:
        a, b = (metric(v) for v in group.values())
        return abs(b / a - 1.0)

    return measure


def _mass_dlc_growth(groups: Mapping[str, tuple[tuple[str, Run], tuple[str, Run], float]]) -> Check:
    """Road DLC of the 703 kg car over the 422 kg car, per controller, near the stated rise,
    with the DLC over each car's own load (kept) and over the nominal load."""

    def growth(metric: Any) -> Check:
        return all_of(
            *(
                ratio(metric, heavy, light, 1 + 0.5 * (given - 1), 1 + 1.5 * (given - 1), given)
                for _name, (heavy, light, given) in groups.items()
            )
        )

    return readings(
        ("DLC read over each car's own static load (3.45)", growth(ROAD_DLC)),
        ("DLC read over the nominal load (m_s0 + m_u) g", growth(ROAD_DLC_NOMINAL)),
    )


def _tracking_by_speed(run: tuple[str, Run]) -> Check:
    """Relative force-tracking error at low speed (|v_r| < 0.1 m/s) above twice that at
    high speed (|v_r| >= 0.3 m/s)."""
    low = relative_tracking(0.0, 0.1)
    high = relative_tracking(0.3, math.inf)

    def fn(p: Mapping[str, Payload]) -> Verdict:
        a, b = low(p[run[0]]), high(p[run[0]])
        ok = a > 2.0 * b
        text = f"{run[0]}: {low.name} {a:.3g}, {high.name} {b:.3g}"
        return Verdict(ok, text, "" if ok else f"low-speed error {a:.3g} not > 2 x {b:.3g}")

    return Check(dict([run]), fn)


def _drift(runs: Mapping[str, Run], larger: str, smaller: str, margin: float) -> Check:
    """|mean x_r| of ``larger`` exceeds that of ``smaller`` by more than ``margin`` mm."""
    metric = mean_of("x_r")

    def fn(p: Mapping[str, Payload]) -> Verdict:
        a, b = metric(p[larger]), metric(p[smaller])
        ok = abs(a) > abs(b) + margin
        text = f"mean x_r: {larger} {metric.text(a)}, {smaller} {metric.text(b)}"
        return Verdict(ok, text, "" if ok else f"{larger}'s drift not {margin:g} mm beyond")

    return Check(dict(runs), fn)


def _band_ratio(
    runs: Mapping[str, Run],
    sig: str,
    band: tuple[float, float],
    ref: tuple[float, float],
    at_least: float,
) -> Check:
    """Spectral amplitude of ``sig`` in ``band`` over that in ``ref``, at least ``at_least``."""
    num, den = band_amplitude(sig, *band), band_amplitude(sig, *ref)

    def fn(p: Mapping[str, Payload]) -> Verdict:
        r = {k: num(v) / den(v) for k, v in p.items()}
        ok = all(v >= at_least for v in r.values())
        text = f"{sig} amplitude {band[0]:g}-{band[1]:g} Hz / {ref[0]:g}-{ref[1]:g} Hz: " + (
            ", ".join(f"{k} {v:.3g}" for k, v in r.items())
        )
        return Verdict(ok, text, "" if ok else f"below {at_least:g}")

    return Check(dict(runs), fn)


def _phase_ratio(run: tuple[str, Run], sig: str, factor: float) -> Check:
    """Peak |sig| in compression below ``factor`` times its peak in rebound."""
    reb, comp = phase_peak(sig, "rebound"), phase_peak(sig, "compression")

    def fn(p: Mapping[str, Payload]) -> Verdict:
        r, c = reb(p[run[0]]), comp(p[run[0]])
        ok = c < factor * r
        text = f"{run[0]} peak |{sig}|: rebound {reb.text(r)}, compression {comp.text(c)}"
        return Verdict(ok, text, "" if ok else f"compression not below {factor:g} x rebound")

    return Check(dict([run]), fn)


def _approaches(a: tuple[str, Run], b: tuple[str, Run], key: str, lo: float, tol: float) -> Check:
    """The curve ``key`` of ``a`` within ``tol`` of ``b``'s at every grid frequency >= lo."""

    def fn(p: Mapping[str, Payload]) -> Verdict:
        f = np.asarray(p[a[0]]["frequency"], dtype=float)
        sel = f >= lo
        r = np.asarray(p[a[0]][key], dtype=float)[sel] / np.asarray(p[b[0]][key])[sel]
        ok = bool(np.max(np.abs(r - 1.0)) <= tol)
        text = f"{key} {a[0]} / {b[0]} above {lo:g} Hz: " + ", ".join(f"{v:.3g}" for v in r)
        return Verdict(ok, text, "" if ok else f"differs by more than {100 * tol:.0f} %")

    return Check(dict([a, b]), fn)


def _dtr_at_most(runs: Mapping[str, Run], nominal: str, limit: float) -> Check:
    """DTR of every run against ``nominal`` at most ``limit``."""

    def fn(p: Mapping[str, Payload]) -> Verdict:
        d = {k: dtr_of(p[nominal], v) for k, v in p.items() if k != nominal}
        ok = max(d.values()) <= limit
        text = "DTR: " + ", ".join(f"{k} {v:.3g}" for k, v in d.items())
        return Verdict(ok, text, "" if ok else f"DTR above {limit:g}")

    return Check(dict(runs), fn)


# ---------------------------------------------------------------------------------------
_CLAIMS: tuple[Claim, ...] = (
    # ---------------------------------------------------------------- 4.2 nonlinearities
    Claim(
        "4.2-hysteresis-passive",
        "4.2",
        "The presence of hysteresis, however, yields slightly larger magnitudes of relative "
        "velocity and acceleration responses.",
        "Passive damper at 0.2 A (Fig 4.1): the hysteretic model gives larger peak |v_r| and "
        "|a_s| than the mean model, by at most 25 %.",
        all_of(
            ratio(
                peak("v_r"),
                ("hysteretic", fig("4.1", "hysteretic model")),
                ("mean", fig("4.1", "mean model")),
                1.0,
                1 + SLIGHT,
            ),
            ratio(
                peak("a_s"),
                ("hysteretic", fig("4.1", "hysteretic model")),
                ("mean", fig("4.1", "mean model")),
                1.0,
                1 + SLIGHT,
            ),
        ),
    ),
    Claim(
        "4.2-light-damping-oscillation",
        "4.2",
        "The magnitude of such oscillations is further amplified under light damping "
        "($i_d=0$), as shown in Figure 4.2.",
        "Passive damper (Fig 4.2): the share of a_u above 5 Hz (the force-limiting "
        "oscillations) is larger at 0 A than at 0.2 A.",
        compare(
            hf_fraction("a_u"),
            {"0 A": fig("4.2", "passive 0 A")},
            {"0.2 A": fig("4.2", "passive 0.2 A")},
            ">",
        ),
        also=("4.6", "8.2"),
    ),
    Claim(
        "4.2-higher-current",
        "4.2",
        "the magnitudes of sprung and unsprung mass accelerations and the oscillations in "
        "a_u due to force-limiting property of the MR-damper can be reduced by selecting "
        "higher drive current",
        "Passive damper (Fig 4.2): peak |a_s| and |a_u| are lower at 0.2 A than at 0 A.",
        all_of(
            *(
                compare(
                    peak(s),
                    {"0.2 A": fig("4.2", "passive 0.2 A")},
                    {"0 A": fig("4.2", "passive 0 A")},
                    "<",
                )
                for s in ("a_s", "a_u")
            )
        ),
    ),
    Claim(
        "4.2-onoff-hysteresis",
        "4.2",
        "The presence of hysteresis causes larger magnitude transient peaks in damping force "
        "and acceleration responses, which occur in the vicinity of current switching",
        "On-off ADFG control (0-0.2 A, Fig 4.3): the hysteretic model gives a larger max "
        "|dF_d/dt| and larger peak |a_s| and |a_u| than the mean model.",
        all_of(
            *(
                compare(
                    m,
                    {"hysteretic": fig("4.3", "hysteretic model")},
                    {"mean": fig("4.3", "mean model")},
                    ">",
                )
                for m in (max_rate("F_d"), peak("a_s"), peak("a_u"))
            )
        ),
    ),
    Claim(
        "4.2-semi-active-hysteresis",
        "4.6",
        "The hysteresis property of the MR-damper would invariably yield transient "
        "oscillations in the damping force, and sprung and unsprung mass acceleration "
        "responses, when the semi-active control scheme is utilized.",
        "Skyhook hi-lo SCM (k_c = 3): the hysteretic damper gives a larger max |dF_d/dt| and "
        "a larger share of a_s and a_u above 5 Hz than the mean damper.",
        all_of(
            *(
                compare(
                    m,
                    {"hysteretic": SKY_H["SCM"]},
                    {"mean": fig("4.6", "SCM", "history", damper={"hysteresis": False})},
                    ">",
                )
                for m in (max_rate("F_d"), hf_fraction("a_s"), hf_fraction("a_u"))
            )
        ),
        also=("8.2",),
    ),
    Claim(
        "4.2-saturation-oscillation",
        "4.6",
        "The force saturation in the post-yield at higher velocities could cause strong "
        "oscillations in the unsprung mass acceleration response, irrespective of the open- "
        "or closed-loop operation of the MR-suspension.",
        "At 2.5 cm / 1.5 Hz, more than 20 % of the rms of a_u lies above 5 Hz with the MR "
        "damper both passive (0 A) and under skyhook hi-lo SCM; a linear damper "
        "(1500 N s/m) has almost none.",
        all_of(
            within(
                hf_fraction("a_u"),
                {"passive 0 A": fig("4.2", "passive 0 A", "history"), "skyhook SCM": SKY_H["SCM"]},
                0.2,
                1.0,
            ),
            within(
                hf_fraction("a_u"),
                {
                    "linear 1500 N s/m": fig(
                        "4.2",
                        "passive 0 A",
                        "history",
                        damper={"model": "linear", "damping": 1500.0},
                    )
                },
                0.0,
                0.05,
            ),
        ),
        also=("8.2",),
    ),
    # ---------------------------------------------------------------- 4.3.1 policies
    Claim(
        "4.3.1-policy-i-resonance",
        "4.3.1",
        'the scheme I based upon "skyhook" modulation of the current yields significantly '
        "lower resonant acceleration responses",
        "Fig 4.5 (SCM): peak T_as of policy I is at most 0.85 times that of II, III and IV.",
        _rule_gain_sensitivity(
            compare(
                fpeak("T_as"), _sub(POL_F, "I"), _sub(POL_F, "II", "III", "IV"), "<", CONSIDERABLY
            )
        ),
    ),
    Claim(
        "4.3.1-policy-i-high-frequency",
        "4.3.1",
        "and better attenuation of sprung mass acceleration in the higher frequency range",
        "Fig 4.5: above 3 Hz, T_as of policy I is below that of II and III at more than 75 % "
        "of the grid frequencies.",
        fraction("T_as", _one(POL_F, "I"), _sub(POL_F, "II", "III"), "<", (3.0, 15.0), 0.75),
    ),
    Claim(
        "4.3.1-policy-iv-highest",
        "4.3.1",
        "The lower damping due to policy IV related to relative displacement response yields "
        "highest resonant response",
        "Fig 4.5: policy IV has the highest peak T_as (0.5-4 Hz) of the four policies.",
        compare(fpeak("T_as"), _sub(POL_F, "IV"), _sub(POL_F, "I", "II", "III"), ">"),
    ),
    Claim(
        "4.3.1-dlc-i-iv",
        "4.3.1",
        "Both the schemes also yield relative small variations in the dynamic tire forces "
        "suggesting better road-holding potential as evident from lower DLC response in "
        "majority of the frequency range.",
        "Fig 4.5: the DLC of policies I and IV is below that of II and III at more than half "
        "of the grid frequencies.",
        _rule_gain_sensitivity(
            all_of(
                fraction("DLC", _one(POL_F, "I"), _sub(POL_F, "II", "III"), "<"),
                fraction("DLC", _one(POL_F, "IV"), _sub(POL_F, "II", "III"), "<"),
            )
        ),
    ),
    Claim(
        "4.3.1-tdr-i-iv-wheel-hop",
        "4.3.1",
        "Both the schemes also yield higher relative displacement response near the unsprung "
        "mass resonant frequency.",
        "Fig 4.5: mean T_dr over 7-15 Hz of policies I and IV is above that of II and III.",
        compare(fmean("T_dr", 7.0, 15.0), _sub(POL_F, "I", "IV"), _sub(POL_F, "II", "III"), ">"),
    ),
    Claim(
        "4.3.1-policy-i-smooth",
        "4.3.1",
        'the modulation scheme I based upon the "skyhook" damping concept [87] yields '
        "relative smooth variations in the drive current and damping force",
        "Fig 4.4 (2.5 cm, 1.5 Hz): policy I has the smallest share of i_d and of F_d above 5 Hz "
        "of the four policies.",
        _rule_gain_sensitivity(
            all_of(
                *(
                    compare(hf_fraction(s), _sub(POL_T, "I"), _sub(POL_T, "II", "III", "IV"), "<")
                    for s in ("i_d", "F_d")
                )
            )
        ),
    ),
    Claim(
        "4.3.1-policy-iv-switching",
        "4.3.1",
        "The control scheme IV based upon modulation of current in proportion to relative "
        "deflection response causes large variations in F_d and i_d near the switching "
        "instants.",
        "Fig 4.4: policy IV has the largest max |di_d/dt| and max |dF_d/dt| of the four policies.",
        _rule_gain_sensitivity(
            all_of(
                *(
                    compare(max_rate(s), _sub(POL_T, "IV"), _sub(POL_T, "I", "II", "III"), ">")
                    for s in ("i_d", "F_d")
                )
            )
        ),
    ),
    Claim(
        "4.3.1-ii-iii-oscillation",
        "4.3.1",
        "but cause high frequency oscillations around the switching, which are more evident "
        "in the unsprung mass acceleration response",
        "Fig 4.4: the share of a_u above 5 Hz is larger with policies II and III than with I.",
        _rule_gain_sensitivity(
            compare(hf_fraction("a_u"), _sub(POL_T, "II", "III"), _sub(POL_T, "I"), ">")
        ),
    ),
    Claim(
        "4.3.1-peak-current",
        "4.3.1",
        "to ensure identical peak value of the drive current about ($i_d=i_H=0.5$ A) under "
        "selected excitation magnitude",
        "Fig 4.4 (2.5 cm, 1.5 Hz): each policy's peak drive current is 0.4-0.5 A.",
        within(peak("i_d"), POL_T, 0.4, 0.5 + 1e-9, 0.5),
    ),
    # ---------------------------------------------------------------- 4.3.2 SCM / ACM
    Claim(
        "4.3.2-gamma",
        "4.3.2",
        "the chosen control parameters could yield asymmetric damping force ratio in the "
        "order of 2.4 in the ACM",
        "Fig 4.6: skyhook hi-lo ACM gives gamma (rebound/compression peak force) of "
        "2.4 +- 25 %, SCM about 1.",
        _adfg_sensitivity(
            all_of(
                about(GAMMA, _sub(SKY_T, "ACM"), 2.4),
                within(GAMMA, _sub(SKY_T, "SCM"), 0.9, 1.1, 1.0),
            )
        ),
        also=("4.6",),
    ),
    Claim(
        "4.3.2-current",
        "4.3.2",
        "The corresponding power consumption is reduced by nearly 50% as observed from "
        "variations in i_d in Figure 4.6",
        "Fig 4.6: the mean drive current in ACM is 0.35-0.65 times that in SCM.",
        _identified_sensitivity(
            ratio(MEAN_CURRENT, _one(SKY_T, "ACM"), _one(SKY_T, "SCM"), 0.35, 0.65, 0.5)
        ),
    ),
    Claim(
        "4.3.2-compression-peaks",
        "4.3.2",
        "the asymmetric damping modulation causes slightly higher magnitudes of the tire force "
        "(F_T), sprung mass deflection and acceleration (x_s and a_s), relative displacement "
        "(x_r) responses during the compression cycle",
        "Fig 4.6: over the compression samples (v_r > 0), ACM's peaks of |F_T|, |x_s|, |a_s| "
        "and |x_r| exceed SCM's by at most 25 %.",
        all_of(
            *(
                ratio(
                    phase_peak(s, "compression"),
                    _one(SKY_T, "ACM"),
                    _one(SKY_T, "SCM"),
                    1.0,
                    1 + SLIGHT,
                )
                for s in ("F_T", "x_s", "a_s", "x_r")
            )
        ),
    ),
    Claim(
        "4.3.2-drift",
        "4.3.2",
        "The light damping in the compression mode also yields asymmetric variations in the "
        "sprung mass displacement and relative displacement responses about their static "
        "equilibria.",
        "Fig 4.6: the mean stroke x_r over whole cycles moves further from equilibrium in ACM "
        "than in SCM (by more than 1 mm).",
        _drift(SKY_H, "ACM", "SCM", 1.0),
    ),
    Claim(
        "4.3.2-wheel-hop-excited",
        "4.3.2",
        "The damping force modulation in both SCM and ACM tend to excite resonant oscillations "
        "of the unsprung mass, even though the excitation frequency is close to the sprung "
        "mass resonance.",
        "Fig 4.6: the a_u spectrum has a component at 8-12 Hz of at least 10 % of its 1.5 Hz "
        "component, in SCM and in ACM.",
        _band_ratio(SKY_H, "a_u", (8.0, 12.0), (1.4, 1.6), 0.1),
    ),
    Claim(
        "4.3.2-acm-resonance-1.5cm",
        "4.3.2",
        "the ACM damping variations cause slightly larger resonant responses in a_s and x_r , "
        "when compared to the SCM",
        "Fig 4.7 (constant 1.5 cm, 0.5-15 Hz): peak T_as and T_dr (0.5-4 Hz) in ACM exceed "
        "SCM's by at most 25 %.",
        all_of(
            *(
                ratio(fpeak(k), _one(SKY_F15, "ACM"), _one(SKY_F15, "SCM"), 1.0, 1 + SLIGHT)
                for k in ("T_as", "T_dr")
            )
        ),
    ),
    Claim(
        "4.3.2-acm-above-resonance",
        "4.3.2",
        "The ACM variations, however, yield lower magnitudes of variations in the dynamic "
        "tire force (DLC) and transmitted accelerations at frequencies above the sprung mass "
        "resonant frequency.",
        "Fig 4.7 (constant 1.5 cm): above 2 Hz, ACM's DLC and T_as are below SCM's at more "
        "than half of the grid frequencies.",
        all_of(
            *(
                fraction(k, _one(SKY_F15, "ACM"), _sub(SKY_F15, "SCM"), "<", (2.0, 15.0))
                for k in ("DLC", "T_as")
            )
        ),
        also=("8.1",),
    ),
    Claim(
        "4.3.2-passive-light",
        "4.3.2",
        "Light constant damping corresponding to $i_d=0$ yields larger magnitudes of a_s , "
        "a_u , x_s , x_r and F_T .",
        "Fig 4.8: peak |a_s|, |a_u|, |x_s|, |x_r| and |F_T| are larger with the passive "
        "damper at 0 A than at 0.1 A.",
        all_of(
            *(
                compare(peak(s), _sub(P4_T, "passive 0 A"), _sub(P4_T, "passive 0.1 A"), ">")
                for s in ("a_s", "a_u", "x_s", "x_r", "F_T")
            )
        ),
    ),
    Claim(
        "4.3.2-passive-current-peak",
        "4.3.2",
        "An increase in the passive mode damping by selecting $i_d=0.1$ A tends to reduce the "
        "peak magnitudes considerably.",
        "Fig 4.9: the peak T_as (0.5-4 Hz) of the passive damper at 0.1 A is at most 0.85 "
        "times that at 0 A.",
        compare(
            fpeak("T_as"), _sub(P4_F, "passive 0.1 A"), _sub(P4_F, "passive 0 A"), "<", CONSIDERABLY
        ),
    ),
    Claim(
        "4.3.2-acm-xs-ft",
        "4.3.2",
        "ACM damping causes lower magnitudes of sprung mass displacement and tire force",
        "Fig 4.8: skyhook hi-lo ACM's peak |x_s| and |F_T| are below both passive modes'.",
        _peaks_lower(
            ("x_s", "F_T"),
            _one(P4_T, "skyhook hi-lo ACM"),
            _sub(P4_T, "passive 0 A", "passive 0.1 A"),
        ),
    ),
    Claim(
        "4.3.2-au-lowest-passive",
        "4.3.2",
        "The peak unsprung mass acceleration response, however, is lowest under higher value "
        "of passive damping ($i_d=0.1$ A).",
        "Fig 4.8: peak |a_u| at passive 0.1 A is below ACM's and passive 0 A's.",
        compare(
            peak("a_u"),
            _sub(P4_T, "passive 0.1 A"),
            _sub(P4_T, "passive 0 A", "skyhook hi-lo ACM"),
            "<",
        ),
    ),
    Claim(
        "4.3.2-acm-rebound-force",
        "4.3.2",
        "which yields considerably higher damping force in rebound. The compression mode "
        "damping force tends to be lower than that observed for the passive mode.",
        "Fig 4.8: ACM's peak |F_d| in rebound is over 1/0.85 times its compression peak, and "
        "its compression peak is below passive 0.1 A's.",
        all_of(
            _phase_ratio(("ACM", P4_T["skyhook hi-lo ACM"]), "F_d", CONSIDERABLY),
            compare(
                phase_peak("F_d", "compression"),
                {"ACM": P4_T["skyhook hi-lo ACM"]},
                _sub(P4_T, "passive 0.1 A"),
                "<",
            ),
        ),
    ),
    Claim(
        "4.3.2-acm-majority",
        "4.3.2",
        "ACM damping yields superior sprung mass acceleration transmissibility (T_{as}) and "
        "variations in the tire force in vast majority of the frequency range",
        "Fig 4.9: skyhook hi-lo ACM's T_as and DLC are below both passive modes' at more than "
        "half of the grid frequencies.",
        all_of(
            *(fraction(k, _one(P4_F, "skyhook hi-lo ACM"), PASSIVE_F, "<") for k in ("T_as", "DLC"))
        ),
    ),
    Claim(
        "4.3.2-passive-resonance",
        "4.3.2",
        "Both the passive modes of damping yield higher resonant values of T_{as} and DLC",
        "Fig 4.9: peak T_as and peak DLC (0.5-4 Hz) of both passive modes exceed ACM's.",
        _adfg_sensitivity(
            all_of(
                *(
                    compare(fpeak(k), PASSIVE_F, _sub(P4_F, "skyhook hi-lo ACM"), ">")
                    for k in ("T_as", "DLC")
                )
            )
        ),
    ),
    Claim(
        "4.3.2-passive-0a-approaches",
        "4.3.2",
        "the responses corresponding to $i_d=0$ approach those of the semi-active damping at "
        "frequencies above 2.5 Hz",
        "Fig 4.9: above 2.5 Hz, T_as at passive 0 A is within 25 % of ACM's at every grid "
        "frequency.",
        _approaches(
            _one(P4_F, "passive 0 A"), _one(P4_F, "skyhook hi-lo ACM"), "T_as", 2.5, SLIGHT
        ),
    ),
    Claim(
        "4.3.2-passive-au-high",
        "4.3.2",
        "A higher value of passive damping, however, is desirable to limit the unsprung mass "
        "acceleration",
        "Fig 4.9: mean T_au over 5-15 Hz is lower at passive 0.1 A than with ACM.",
        compare(
            fmean("T_au", 5.0, 15.0),
            _sub(P4_F, "passive 0.1 A"),
            _sub(P4_F, "skyhook hi-lo ACM"),
            "<",
        ),
    ),
    Claim(
        "4.3.2-pulse-passive",
        "4.3.2",
        "Light passive damping ($i_d=0$), on the other hand, yields lower peak value of a_s , "
        "but higher peak values of x_s and considerably lower rate of decay.",
        "Fig 4.10 (5 cm pulse): passive 0 A has lower peak |a_s|, higher peak |x_s| and an "
        "rms x_s after the pulse (from its end, 0.80 s) over 1/0.85 times that of passive 0.1 A.",
        all_of(
            compare(peak("a_s"), _sub(P4_P, "passive 0 A"), _sub(P4_P, "passive 0.1 A"), "<"),
            compare(peak("x_s"), _sub(P4_P, "passive 0 A"), _sub(P4_P, "passive 0.1 A"), ">"),
            _decay(_sub(P4_P, "passive 0.1 A"), _sub(P4_P, "passive 0 A"), CONSIDERABLY),
        ),
    ),
    Claim(
        "4.3.2-pulse-acm-both",
        "4.3.2",
        "ACM damping variations can help realize the benefits of both the lower and higher "
        "passive mode damping, in limiting the peak responses and rate of decay",
        "Fig 4.10 (5 cm pulse): ACM's peak |a_s| is below passive 0.1 A's, its peak |x_s| and "
        "rms x_s after the pulse below passive 0 A's.",
        all_of(
            compare(peak("a_s"), _sub(P4_P, "skyhook hi-lo ACM"), _sub(P4_P, "passive 0.1 A"), "<"),
            compare(peak("x_s"), _sub(P4_P, "skyhook hi-lo ACM"), _sub(P4_P, "passive 0 A"), "<"),
            _decay(_sub(P4_P, "skyhook hi-lo ACM"), _sub(P4_P, "passive 0 A")),
        ),
    ),
    Claim(
        "4.3.2-road-force",
        "4.3.2",
        "the passive mode damping force is generally considerably higher than the semi-active "
        "damping force in majority of the frequency range",
        "Fig 4.11 (rough road, 50 km/h): the PSD of F_d at passive 0.1 A is above ACM's at "
        "more than half of the 0.5-20 Hz bins.",
        fraction(
            "PSD F_d",
            _one(P4_R, "passive 0.1 A"),
            _sub(P4_R, "skyhook hi-lo ACM"),
            ">",
            (0.5, 20.0),
        ),
        depends_on=(ROAD,),
    ),
    Claim(
        "4.3.2-road-ride",
        "4.3.2",
        "The PSD of sprung mass acceleration in the vicinity of the sprung mass resonance thus "
        "tends to be lower for the passive mode damping, while the response in the ride "
        "frequency range (2-8 Hz) is considerably larger than that of the semi-active",
        "Fig 4.11: mean PSD of a_s over 1-2 Hz is lower at passive 0.1 A than with ACM, and "
        "over 2-8 Hz ACM's is at most 0.85 times passive 0.1 A's.",
        all_of(
            compare(
                psd_mean("a_s", 1.0, 2.0),
                _sub(P4_R, "passive 0.1 A"),
                _sub(P4_R, "skyhook hi-lo ACM"),
                "<",
            ),
            compare(
                psd_mean("a_s", 2.0, 8.0),
                _sub(P4_R, "skyhook hi-lo ACM"),
                _sub(P4_R, "passive 0.1 A"),
                "<",
                CONSIDERABLY,
            ),
        ),
        depends_on=(ROAD,),
    ),
    Claim(
        "4.3.2-road-dlc",
        "4.3.2",
        "the semi-active ACM damping variations yield lower unsprung mass acceleration and "
        "dynamic tire force variations",
        "Fig 4.11 (rough road): skyhook hi-lo ACM gives a lower road DLC than passive 0.1 A.",
        compare(ROAD_DLC, _sub(P4_R, "skyhook hi-lo ACM"), _sub(P4_R, "passive 0.1 A"), "<"),
        depends_on=(ROAD,),
        inconsistent="the same paragraph gives DLC 0.138 for the semi-active ACM damping and "
        "0.111 for the fixed 0.1 A damping, a higher value for ACM; the text's reading "
        "(lower with ACM) is tested.",
    ),
    # ---------------------------------------------------------------- 4.4.1 sprung mass
    Claim(
        "4.4.1-harmonic-insensitive",
        "4.4.1",
        "The peak magnitudes of sprung mass responses (a_s and x_s), however, remain almost "
        "insensitive to variations in m_s .",
        "Fig 4.12 (m_s 422-703 kg): the spread of peak |a_s| and |x_s| is at most 10 %.",
        all_of(spread(peak("a_s"), M4_T), spread(peak("x_s"), M4_T)),
    ),
    Claim(
        "4.4.1-light-rebound-force",
        "4.4.1",
        "For a lighter sprung mass, the current modulation to higher value occurs earlier than "
        "that for the nominal mass, and the magnitude of the corresponding damping force is "
        "relatively smaller, particularly in the rebound mode.",
        "Fig 4.12: peak |F_d| in rebound is lower for 422 kg than for 563 kg.",
        compare(
            phase_peak("F_d", "rebound"),
            _sub(M4_T, "m_s = 422 kg"),
            _sub(M4_T, "m_s = 563 kg"),
            "<",
        ),
    ),
    Claim(
        "4.4.1-tire-force-mass",
        "4.4.1",
        "The mean and amplitude of the tire force increase with increasing sprung mass.",
        "Fig 4.12: peak |F_T| and the amplitude of F_T rise with m_s.",
        all_of(monotone(peak("F_T"), M4_T), monotone(amplitude("F_T"), M4_T)),
    ),
    Claim(
        "4.4.1-tas-tdr-mass",
        "4.4.1",
        "An increase in m_s causes slightly higher magnitudes of T_{as} and T_{dr}",
        "Fig 4.13: peak T_as and T_dr rise with m_s, spread at most 25 %.",
        all_of(
            *(
                all_of(monotone(fpeak(k), M4_F), spread(fpeak(k), M4_F, SLIGHT))
                for k in ("T_as", "T_dr")
            )
        ),
    ),
    Claim(
        "4.4.1-dlc-lighter-peak",
        "4.4.1",
        "Owing to its definition, the DLC increases with decreasing vehicle weight.",
        "Fig 4.13: the peak DLC over 0.5-15 Hz falls as m_s rises.",
        monotone(fpeak("DLC", 0.5, 15.0), M4_F, "decreasing"),
        also=("5.5.1",),
    ),
    Claim(
        "4.4.1-dlc-lighter-everywhere",
        "4.4.1",
        "The lower mass thus yields higher DLC response in the entire frequency range.",
        "Fig 4.13: the 422 kg car's DLC is above the 563 and 703 kg cars' at every grid frequency.",
        fraction(
            "DLC",
            _one(M4_F, "m_s = 422 kg"),
            _sub(M4_F, "m_s = 563 kg", "m_s = 703 kg"),
            ">",
            at_least=1.0,
            strictly_more=False,
        ),
    ),
    Claim(
        "4.4.1-pulse-current",
        "4.4.1",
        "A lower sprung mass causes higher drive current in rebound due to higher sprung mass "
        "velocity, as evident from the sprung mass acceleration response shown in Figure 4.14. "
        "The peak damping force, however, varies only slightly",
        "Fig 4.14 (3.5 cm pulse): the peak drive current falls as m_s rises; the peak |F_d| "
        "varies by at most 25 % ('only slightly').",
        all_of(monotone(peak("i_d"), M4_P, "decreasing"), spread(peak("F_d"), M4_P, SLIGHT)),
    ),
    Claim(
        "4.4.1-table-sar-s",
        "4.4.1",
        "The sprung mass shock acceleration ratio (SAR_s), however, increases by 32% when m_s "
        "is reduced by 25%, and it decreases by 21% when m_s is increased by 25%.",
        "Table 4.1: SAR_s changes by +32 % at 422 kg and -21 % at 703 kg.",
        change(
            SHOCK["SAR_s"],
            _one(T41, "m_s = 563"),
            {"m_s = 422": (T41["m_s = 422"], 0.32), "m_s = 703": (T41["m_s = 703"], -0.21)},
        ),
    ),
    Claim(
        "4.4.1-table-insensitive",
        "4.4.1",
        "the peak suspension travel (RDR), sprung mass displacement ratio (SDR_s) and "
        "unsprung mass acceleration and displacement ratios (SAR_u and SDR_u) remain "
        "insensitive to variations in m_s",
        "Table 4.1: the spread of RDR, SDR_s, SAR_u and SDR_u over m_s is at most 10 %.",
        _insensitive_shock(T41, ("RDR", "SDR_s", "SAR_u", "SDR_u"), INSENSITIVE),
    ),
    Claim(
        "4.4.1-table-dtr",
        "4.4.1",
        "The normalized peak force increases is in the order of 26%, when sprung mass is "
        "decreased by 25%. The peak tire force deviation, however, decreases by 29%",
        "Table 4.1: DTR 0.26 at 422 kg and 0.29 at 703 kg, within 30 %.",
        _dtr_readings(
            _one(T41, "m_s = 563"),
            {"m_s = 422": (T41["m_s = 422"], 0.26), "m_s = 703": (T41["m_s = 703"], 0.29)},
        ),
    ),
    Claim(
        "4.4.1-road-current",
        "4.4.1",
        "The results show higher drive current for the lower mass ($m_s=422$ kg) due to high "
        "sprung mass motion and thus damping force demand",
        "Fig 4.15 (rough road): the mean drive current falls as m_s rises.",
        monotone(MEAN_CURRENT, M4_R, "decreasing"),
        depends_on=(ROAD,),
    ),
    Claim(
        "4.4.1-road-dlc-heavier",
        "4.4.1",
        "The DLC due to tire force tends to be lower for heavier operating mass, which is "
        "attributed to its definition.",
        "Fig 4.15 (rough road): the road DLC falls as m_s rises.",
        monotone(ROAD_DLC, M4_R, "decreasing"),
        depends_on=(ROAD,),
        inconsistent="the next sentence says the DLC 'increases from 0.114 to 0.176, when the "
        "sprung mass is increased by 67%', and section 6.5 repeats the rise (+54 %); the "
        "'lower for heavier' reading is tested here, the rise in 6.5-road-dlc-mass.",
    ),
    # ---------------------------------------------------------------- 4.4.2 speed
    Claim(
        "4.4.2-pulse-speed",
        "4.4.2",
        "The peak sprung mass acceleration response at a speed of 100 km/h is relatively "
        "larger than that at 50 km/h.",
        "Fig 4.16 (3.5 cm pulse): at 100 km/h peak |a_s| is higher, peak |x_s| and the peak "
        "drive current lower than at 50 km/h.",
        all_of(
            compare(peak("a_s"), _sub(V4_P, "V = 100 km/h"), _sub(V4_P, "V = 50 km/h"), ">"),
            compare(peak("x_s"), _sub(V4_P, "V = 100 km/h"), _sub(V4_P, "V = 50 km/h"), "<"),
            compare(peak("i_d"), _sub(V4_P, "V = 100 km/h"), _sub(V4_P, "V = 50 km/h"), "<"),
        ),
    ),
    Claim(
        "4.4.2-table-changes",
        "4.4.2",
        "the sprung mass shock displacement and acceleration ratios (SDR_s and SAR_s) "
        "decrease and increase by 42% and 74%, respectively, and the unsprung mass "
        "acceleration ratio (SAR_u) decreases by 69%",
        "Table 4.2: at 100 km/h SDR_s changes by -42 %, SAR_s by -74 % and SAR_u by -69 %.",
        all_of(
            *(
                change(SHOCK[k], _one(T42, "V = 50"), {"V = 100": (T42["V = 100"], c)})
                for k, c in (("SDR_s", -0.42), ("SAR_s", -0.74), ("SAR_u", -0.69))
            )
        ),
        inconsistent="the text pairs SAR_s with an increase of 74 %, Table 4.2 lists SAR_s "
        "0.19 at 50 km/h and 0.05 at 100 km/h, a decrease of 74 %; the table is tested.",
    ),
    Claim(
        "4.4.2-table-insensitive",
        "4.4.2",
        "the unsprung mass and relative displacement ratios (SDR_u and RDR) remain relatively "
        "insensitive to variations in speed",
        "Table 4.2: SDR_u and RDR differ by at most 10 % between 50 and 100 km/h.",
        _insensitive_shock(T42, ("SDR_u", "RDR"), INSENSITIVE),
    ),
    Claim(
        "4.4.2-table-dtr",
        "4.4.2",
        "The peak force deviation (DTR) is in the order of 42%, when vehicle speed is "
        "increased by 100%",
        "Table 4.2: DTR at 100 km/h 0.42 within 30 %.",
        dtr_values(_one(T42, "V = 50"), {"V = 100": (T42["V = 100"], 0.42)}),
    ),
    Claim(
        "4.4.2-road-dlc",
        "4.4.2",
        "The DLC due to tire force at 100 km/h increases slightly to 0.142 compared to 0.138 "
        "at 50 km/h.",
        "Fig 4.17 (rough road): DLC at 100 km/h is 1.0-1.15 times that at 50 km/h.",
        ratio(
            ROAD_DLC,
            _one(V4_R, "V = 100 km/h"),
            _one(V4_R, "V = 50 km/h"),
            1.0,
            1.15,
            0.142 / 0.138,
        ),
        depends_on=(ROAD,),
    ),
    Claim(
        "4.4.2-road-current",
        "4.4.2",
        "The variation in drive current magnitude thus tends to be higher for the 50 km/h "
        "operation, when compared to that for 100 km/h.",
        "Fig 4.17: the standard deviation of the drive current is higher at 50 km/h.",
        compare(road_current_std(), _sub(V4_R, "V = 50 km/h"), _sub(V4_R, "V = 100 km/h"), ">"),
        depends_on=(ROAD,),
    ),
    # ---------------------------------------------------------------- 4.4.3 excitation
    Claim(
        "4.4.3-harmonic-amplitude",
        "4.4.3",
        "An increase in excitation magnitude causes higher sprung mass displacement and "
        "acceleration response, and thus poses increased demand on the damping force. The "
        "drive current increases considerably",
        "Fig 4.18 (1.5 Hz): peak |x_s| and |a_s| rise with the amplitude (1.5, 2.5, 3.5 cm); "
        "the mean current at 2.5 cm is over 1/0.85 times that at 1.5 cm.",
        all_of(
            _monotone_all(("x_s", "a_s"), A4_T, "increasing"),
            compare(
                MEAN_CURRENT, _sub(A4_T, "a = 1.5 cm"), _sub(A4_T, "a = 2.5 cm"), "<", CONSIDERABLY
            ),
        ),
    ),
    Claim(
        "4.4.3-tas-slight",
        "4.4.3",
        "The peak resonant transmissibility increases only slightly with increasing "
        "excitation magnitude",
        "Fig 4.19: peak T_as rises with the amplitude, spread at most 25 %.",
        all_of(monotone(fpeak("T_as"), A4_F), spread(fpeak("T_as"), A4_F, SLIGHT)),
    ),
    Claim(
        "4.4.3-tau-dlc-tdr",
        "4.4.3",
        "Higher excitation magnitudes, however, cause significantly higher unsprung mass "
        "acceleration and thus the tire force responses",
        "Fig 4.19: peak T_au, DLC and T_dr (0.5-15 Hz) rise with the amplitude.",
        all_of(*(monotone(fpeak(k, 0.5, 15.0), A4_F) for k in ("T_au", "DLC", "T_dr"))),
    ),
    Claim(
        "4.4.3-pulse-height",
        "4.4.3",
        "the drive current increases significantly with increasing pulse displacement",
        "Fig 4.20 (pulse 2, 3.5, 5 cm): peak drive current, peak |x_s|, |a_s| and |F_T| rise "
        "with the pulse height.",
        _monotone_all(("i_d", "x_s", "a_s", "F_T"), A4_P, "increasing"),
    ),
    Claim(
        "4.4.3-table",
        "4.4.3",
        "the sprung mass acceleration ratio (SAR_s) remains insensitive to variation in the "
        "peak excitation magnitude",
        "Table 4.3: SAR_s spread at most 10 % over the pulse heights; SDR_s falls as the "
        "height rises (0.75, 0.71, 0.64).",
        all_of(spread(SHOCK["SAR_s"], T43), monotone(SHOCK["SDR_s"], T43, "decreasing")),
    ),
    Claim(
        "4.4.3-table-dtr",
        "4.4.3",
        "The peak force deviation (DTR) increases and decreases in the order of 29%",
        "Table 4.3: DTR 0.29 at 2 cm and at 5 cm, within 30 %.",
        dtr_values(
            _one(T43, "a_m = 3.5"),
            {"a_m = 2": (T43["a_m = 2"], 0.29), "a_m = 5": (T43["a_m = 5"], 0.29)},
        ),
    ),
    Claim(
        "4.4.3-road-roughness",
        "4.4.3",
        "The DLC due to tire force for the rough road excitation increases significantly to "
        "0.138, compared to 0.045 for medium-rough road excitation.",
        "Fig 4.21: rough/medium-rough road DLC ratio 0.138/0.045 = 3.07, within 25 %.",
        ratio(
            ROAD_DLC,
            _one(R4, "rough"),
            _one(R4, "medium-rough"),
            0.75 * 0.138 / 0.045,
            1.25 * 0.138 / 0.045,
            0.138 / 0.045,
        ),
        depends_on=(ROAD,),
    ),
    Claim(
        "4.4.3-road-ride-comparable",
        "4.4.3",
        "The responses of a_s , a_u and F_T for the rough road excitation are comparable to "
        "those attained under the medium rough road excitation in the ride frequency range "
        "(2-5 Hz).",
        "Fig 4.21: mean PSDs of a_s, a_u and F_T over 2-5 Hz on the rough road are within a "
        "factor 1.5 of the medium-rough road's.",
        all_of(
            *(
                ratio(
                    psd_mean(s, 2.0, 5.0), _one(R4, "rough"), _one(R4, "medium-rough"), 1 / 1.5, 1.5
                )
                for s in ("a_s", "a_u", "F_T")
            )
        ),
        depends_on=(ROAD,),
    ),
    Claim(
        "4.4-road-dlc-levels",
        "4.3.2",
        "The results revealed comparable values of DLC of 0.111 for the fixed higher damping "
        "and 0.138 for the semi-active ACM damping.",
        "Road DLC levels (50 km/h) within 25 %: rough, passive 0.1 A 0.111 and skyhook ACM "
        "0.138; medium-rough, skyhook ACM 0.045.",
        _road_levels(
            {
                "rough passive 0.1 A": (P4_R["passive 0.1 A"], 0.111),
                "rough skyhook ACM": (P4_R["skyhook hi-lo ACM"], 0.138),
                "medium-rough skyhook ACM": (R4["medium-rough"], 0.045),
            }
        ),
        depends_on=(ROAD,),
        also=("4.4.3",),
    ),
    # ---------------------------------------------------------------- 4.5.1 gain
    Claim(
        "4.5.1-gain-current",
        "4.5.1",
        "a lower controller gain yield considerably lower current in accordance with the "
        "formulation in EQ (3.15). The corresponding relative velocity response, however, "
        "increases, which is evident from slightly higher relative displacement response.",
        "Fig 4.22: the mean current rises with k_c (0.5, 1.5, 3); peak |x_r| at k_c = 0.5 "
        "exceeds that at k_c = 3.",
        all_of(
            monotone(MEAN_CURRENT, K4_T),
            compare(peak("x_r"), _sub(K4_T, "k_c = 0.5"), _sub(K4_T, "k_c = 3"), ">"),
        ),
    ),
    Claim(
        "4.5.1-gain-comparable",
        "4.5.1",
        "the different values of controller gain yielded only slight variations in the "
        "resonant response magnitude. This is evident from comparable magnitudes of x_s , a_s "
        ", x_r and F_T .",
        "Fig 4.22: the spread of peak |x_s|, |a_s|, |x_r| and |F_T| over k_c is at most 25 % ('only slight').",
        all_of(*(spread(peak(s), K4_T, SLIGHT) for s in ("x_s", "a_s", "x_r", "F_T"))),
        also=("4.6", "8.2"),
    ),
    Claim(
        "4.5.1-gain-frequency",
        "4.5.1",
        "The results show variations in the control gain variation affect the frequency "
        "characteristics only slightly.",
        "Fig 4.23: the spread of peak T_as, T_au, T_dr and DLC (0.5-15 Hz) over k_c is at "
        "most 25 %.",
        all_of(
            *(spread(fpeak(k, 0.5, 15.0), K4_F, SLIGHT) for k in ("T_as", "T_au", "T_dr", "DLC"))
        ),
    ),
    Claim(
        "4.5.1-table-sdr",
        "4.5.1",
        "The lower compression damping corresponding to lower controller gain ($k_c=0.5$) "
        "causes slightly magnitudes of sprung mass displacement and accelerations",
        "Table 4.4: SDR_s falls as k_c rises (0.88, 0.74, 0.71).",
        monotone(SHOCK["SDR_s"], T44, "decreasing"),
    ),
    Claim(
        "4.5.1-table-insensitive",
        "4.5.1",
        "The relatively high insensitivity of the controller synthesis to variations in the "
        "gain are further evident from the measures of the shock response predicted in Table "
        "4.4.",
        "Table 4.4: the spread of SAR_s, SDR_u, SAR_u and RDR over k_c is at most 10 %.",
        _insensitive_shock(T44, ("SAR_s", "SDR_u", "SAR_u", "RDR"), INSENSITIVE),
        inconsistent="Table 4.4 lists SDR_u 1.71 for k_c = 0.5 and 1.5 but 1.17 for k_c = 3 "
        "(a 46 % change, against 'high insensitivity'); every other chapter-4 table has 1.17 "
        "at the nominal case, so 1.71 looks like a transposed 1.17. The text's reading is "
        "tested.",
    ),
    Claim(
        "4.5.1-pulse-rebound",
        "4.5.1",
        "while the rebound damping force remains insensitive to k_c and i_d",
        "Fig 4.24 (3.5 cm pulse): the peak |F_d| in rebound varies by at most 10 % over k_c.",
        spread(phase_peak("F_d", "rebound"), K4_P),
    ),
    Claim(
        "4.5.1-road-gain",
        "4.5.1",
        "The DLC values due to tire force also remain identical (0.138) for both controller "
        "gains. The lower controller gain, however, yields considerably lower drive current",
        "Fig 4.25 (rough road): DLC at k_c = 1.5 and 3 within 5 %; mean current at k_c = 1.5 "
        "at most 0.85 times that at 3.",
        all_of(
            spread(ROAD_DLC, K4_R, 0.05),
            compare(
                MEAN_CURRENT, _sub(K4_R, "k_c = 1.5"), _sub(K4_R, "k_c = 3"), "<", CONSIDERABLY
            ),
        ),
        depends_on=(ROAD,),
    ),
    # ---------------------------------------------------------------- 4.5.2 order
    Claim(
        "4.5.2-order-current",
        "4.5.2",
        "a low order ($n=1$) controller yields rapid variations and considerable "
        "discontinuities in the drive current",
        "Fig 4.26: max |di_d/dt| falls as the order n rises (1, 2, 3).",
        monotone(max_rate("i_d"), N4_T, "decreasing"),
        also=("4.6", "8.2"),
    ),
    Claim(
        "4.5.2-order-peaks",
        "4.5.2",
        "The peak responses, however, do not show a significant influence of the controller order.",
        "Fig 4.26: the spread of peak |x_s|, |a_s|, |x_r| and |F_T| over n is at most 25 % (no 'significant influence'); "
        "n = 3 gives peaks of |x_s|, |a_s| and |x_r| at least those of n = 2.",
        _identified_sensitivity(
            all_of(
                *(spread(peak(s), N4_T, SLIGHT) for s in ("x_s", "a_s", "x_r", "F_T")),
                *(
                    compare(peak(s), _sub(N4_T, "n = 3"), _sub(N4_T, "n = 2"), ">=")
                    for s in ("x_s", "a_s", "x_r")
                ),
            )
        ),
    ),
    Claim(
        "4.5.2-order-frequency",
        "4.5.2",
        "The associated discontinuity in damping force, however, yields significantly higher "
        "unsprung mass acceleration transmissibility.",
        "Fig 4.27: n = 1 gives a peak T_au (0.5-15 Hz) over 1/0.85 times n = 2's, and lower "
        "peak T_as and T_dr than n = 2.",
        all_of(
            compare(
                fpeak("T_au", 0.5, 15.0),
                _sub(N4_F, "n = 2"),
                _sub(N4_F, "n = 1"),
                "<",
                CONSIDERABLY,
            ),
            *(
                compare(fpeak(k), _sub(N4_F, "n = 1"), _sub(N4_F, "n = 2"), "<")
                for k in ("T_as", "T_dr")
            ),
        ),
    ),
    Claim(
        "4.5.2-order-3-comparable",
        "4.5.2",
        "The frequency response characteristics of the highest order controller ($n=3$) are "
        "generally comparable with those of the second order ($n=2$) controller.",
        "Fig 4.27: peak T_as, T_au, T_dr and DLC (0.5-15 Hz) of n = 3 within 10 % of n = 2.",
        _identified_sensitivity(
            all_of(
                *(
                    spread(fpeak(k, 0.5, 15.0), _sub(N4_F, "n = 2", "n = 3"))
                    for k in ("T_as", "T_au", "T_dr", "DLC")
                )
            )
        ),
    ),
    Claim(
        "4.5.2-table-sdr",
        "4.5.2",
        "The sprung mass displacement ratio (SDR_s), however, decreases and increases by 35% "
        "and 20%, when the order is decreased to 1 or increased to 3, respectively.",
        "Table 4.5 text: SDR_s changes by -35 % at n = 1 and +20 % at n = 3.",
        change(
            SHOCK["SDR_s"],
            _one(T45, "n = 2"),
            {"n = 1": (T45["n = 1"], -0.35), "n = 3": (T45["n = 3"], 0.20)},
        ),
        inconsistent="Table 4.5 lists SDR_s 0.85, 0.71, 0.46 for n = 1, 2, 3: +20 % at n = 1 "
        "and -35 % at n = 3, the reverse of its text (the text agrees with Fig 4.28's: 'The "
        "higher damping [n = 1] yields lower peak displacement'); the text is tested.",
    ),
    Claim(
        "4.5.2-table-insensitive",
        "4.5.2",
        "The peak tire force deviation (DTR), sprung mass acceleration (SAR_s), unsprung "
        "displacement and acceleration (SDR_u and SAR_u) and relative displacement (RDR) "
        "ratios remain insensitive to variations in the controller order.",
        "Table 4.5: the spread of SAR_s, SDR_u, SAR_u and RDR over n at most 10 %; DTR at "
        "most 0.05.",
        all_of(
            _insensitive_shock(T45, ("SAR_s", "SDR_u", "SAR_u", "RDR"), INSENSITIVE),
            _dtr_at_most(T45, "n = 2", 0.05),
        ),
    ),
    Claim(
        "4.5.2-road-order",
        "4.5.2",
        "The responses at frequencies above 2 Hz show negligible effects of the controller "
        "order. The results show that the low order controller ($n=1$) yields considerably "
        "higher variation in i_d",
        "Fig 4.29 (rough road): mean PSD of a_s over 2-20 Hz within 10 % for n = 1 and 2; "
        "the standard deviation of i_d at n = 1 over 1/0.85 times that at n = 2.",
        _identified_sensitivity(
            all_of(
                spread(psd_mean("a_s", 2.0, 20.0), N4_R),
                compare(
                    road_current_std(), _sub(N4_R, "n = 2"), _sub(N4_R, "n = 1"), "<", CONSIDERABLY
                ),
            )
        ),
        depends_on=(ROAD,),
    ),
    # ---------------------------------------------------------------- 4.6 summary
    Claim(
        "4.6-skyhook-best-policy",
        "4.6",
        "offers superior vibration attenuation, tire force and rattle space performance, "
        "when compared to those of other control synthesis formulated in the study",
        "Fig 4.5: policy I has the lowest mean T_as, DLC and T_dr over the grid of the four "
        "policies.",
        _rule_gain_sensitivity(
            all_of(
                *(
                    compare(
                        fmean(k, 0.5, 15.0), _sub(POL_F, "I"), _sub(POL_F, "II", "III", "IV"), "<"
                    )
                    for k in ("T_as", "DLC", "T_dr")
                )
            )
        ),
        also=("4.3.1", "8.2"),
    ),
    Claim(
        "4.6-cm-smooths",
        "4.6",
        "can be effectively reduced by employing the proposed continuous modulation (CM) and "
        "asymmetric damping force generation (ADFG) functions",
        "Skyhook hi-lo at 2.5 cm / 1.5 Hz: CM (xi_c = 10, SCM) against a near switch "
        "(xi_c = 1000), and ADFG (xi = 4.5, ACM) against a near switch (xi = 1000): max "
        "|di_d/dt| and the share of a_u above 5 Hz are lower with the smooth functions.",
        _identified_sensitivity(
            all_of(
                *(
                    compare(
                        m,
                        {"SCM xi_c = 10": SKY_H["SCM"]},
                        {
                            "SCM xi_c = 1000": fig(
                                "4.6", "SCM", "history", controller={"xi_c": 1000.0}
                            )
                        },
                        "<",
                    )
                    for m in (max_rate("i_d"), hf_fraction("a_u"))
                ),
                *(
                    compare(
                        m,
                        {"ACM xi = 4.5": SKY_H["ACM"]},
                        {"ACM xi = 1000": fig("4.6", "ACM", "history", controller={"xi": 1000.0})},
                        "<",
                    )
                    for m in (max_rate("i_d"), hf_fraction("a_u"))
                ),
            )
        ),
        also=("8.2",),
    ),
    Claim(
        "8.2-adfg-tunable",
        "8.2",
        "The ADFG function can be easily tuned to attain desired asymmetry factor for the "
        "MR-damper force.",
        "Skyhook hi-lo (k_c = 3) at 2.5 cm / 1.5 Hz: gamma rises as p falls from 1 to 0.5 to 0.",
        monotone(
            GAMMA,
            {
                "p = 1": SKY_T["SCM"],
                "p = 0.5": fig(
                    "4.6", "SCM", controller={"law": "skyhook-hilo", "gain": 3.0, "p": 0.5}
                ),
                "p = 0": SKY_T["ACM"],
            },
        ),
        also=("4.6",),
    ),
    Claim(
        "4.6-skyhook-robust",
        "4.6",
        "has desirable robust control performance with respect to variations in the "
        "operating parameters, such as load, speed and road roughness",
        "Skyhook hi-lo ACM: peak T_as (0.5-4 Hz) varies by at most 25 % over m_s (422-703 "
        "kg), k_c (0.5-3) and n (1-3).",
        all_of(
            spread(fpeak("T_as"), M4_F, SLIGHT),
            spread(fpeak("T_as"), K4_F, SLIGHT),
            spread(fpeak("T_as"), N4_F, SLIGHT),
        ),
        also=("8.2",),
    ),
    # ---------------------------------------------------------------- 5.2 inverse hi-lo
    Claim(
        "5.2-mixed-inverse-transients",
        "5.2",
        "The presence of high magnitude transients in damping force are mostly caused by the "
        "mean inverse model. Such transients can be partly suppressed when the hysteretic "
        "inverse model is considered",
        "Figs 5.1-5.3 (SCM, k_d = 1): max |dF_d/dt| is largest with the hysteretic damper and "
        "mean inverse, smaller with the hysteretic inverse, smallest with mean damper and "
        "mean inverse.",
        monotone(
            max_rate("F_d"),
            {
                "mean damper + mean inverse": INV_SCM1["mean damper + mean inverse"],
                "hysteretic damper + hysteretic inverse": INV_SCM1[
                    "hysteretic damper + hysteretic inverse"
                ],
                "hysteretic damper + mean inverse": INV_SCM1["hysteretic damper + mean inverse"],
            },
        ),
        also=("5.6",),
    ),
    Claim(
        "5.2-relative-velocity",
        "5.2",
        "The consideration of mean damping and inverse models yields peak steady-state "
        "relative velocity in the order of 0.6 m/s, which is considerably smaller than 0.75 "
        "m/s attained with hysteretic models.",
        "Figs 5.1/5.3: peak |v_r| 0.6 m/s (mean models) and 0.75 m/s (hysteretic), each "
        "within 25 %, the mean one at most 0.85 times the hysteretic one.",
        all_of(
            about(peak("v_r"), _sub(INV_SCM1, "mean damper + mean inverse"), 0.6),
            about(peak("v_r"), _sub(INV_SCM1, "hysteretic damper + hysteretic inverse"), 0.75),
            compare(
                peak("v_r"),
                _sub(INV_SCM1, "mean damper + mean inverse"),
                _sub(INV_SCM1, "hysteretic damper + hysteretic inverse"),
                "<",
                CONSIDERABLY,
            ),
        ),
    ),
    Claim(
        "5.2-tracking-speed",
        "5.2",
        "the proposed controller can yield satisfactory forcing-tracking ability only at "
        "higher velocities, while the forcing-tracking ability at low velocities is severely "
        "limited",
        "Fig 5.3 (hysteretic, SCM, k_d = 1): the relative tracking error while z_c < 0 at "
        "|v_r| < 0.1 m/s is over twice that at |v_r| >= 0.3 m/s.",
        _tracking_by_speed(("inverse hi-lo SCM k_d = 1", INV_H1)),
        also=("5.6", "8.2"),
    ),
    Claim(
        "5.2-acm-gamma",
        "5.2",
        "the chosen control parameters could yield asymmetric damping force ratio in the "
        "order of 2.5 in the ACM",
        "Fig 5.4 (inverse hi-lo, k_d = 1): gamma in ACM 2.5 within 25 %.",
        about(GAMMA, _sub(INV_MODES, "ACM"), 2.5),
    ),
    Claim(
        "5.2-acm-current",
        "5.2",
        "The corresponding power consumption is reduced by nearly 50% as observed from "
        "variations in i_d in Figure 5.4",
        "Fig 5.4: the mean drive current in ACM is 0.35-0.65 times that in SCM.",
        ratio(MEAN_CURRENT, _one(INV_MODES, "ACM"), _one(INV_MODES, "SCM"), 0.35, 0.65, 0.5),
    ),
    Claim(
        "5.2-acm-compression-current",
        "5.2",
        "The results show nonzero current of small peak value ($i_d < 0.1$ A; $F_d > 0$)",
        "Fig 5.4: in ACM the peak drive current in compression is below 0.1 A.",
        _identified_sensitivity(
            within(phase_peak("i_d", "compression"), _sub(INV_MODES, "ACM"), 0.0, 0.1)
        ),
    ),
    Claim(
        "5.2-acm-unsprung",
        "5.2",
        "The peak magnitudes of the unsprung mass oscillations, however, are considerably "
        "lower with asymmetric damping.",
        "Fig 5.4: ACM's peak |a_u| is at most 0.85 times SCM's; its peak |a_s| is higher.",
        all_of(
            compare(peak("a_u"), _sub(INV_MODES, "ACM"), _sub(INV_MODES, "SCM"), "<", CONSIDERABLY),
            compare(peak("a_s"), _sub(INV_MODES, "ACM"), _sub(INV_MODES, "SCM"), ">"),
        ),
    ),
    Claim(
        "5.2-hysteretic-current",
        "5.2",
        "Although the hysteretic models yield significantly higher peak current in rebound, "
        "the corresponding sprung mass acceleration responses for mean as well as hysteretic "
        "models are comparable.",
        "Fig 5.5 (ACM, k_d = 1): peak rebound current of the hysteretic pair over 1/0.85 "
        "times the mean pair's; peak |a_s| within 10 %.",
        all_of(
            compare(
                phase_peak("i_d", "rebound"),
                _sub(INV_MIX, "mean damper + mean inverse"),
                _sub(INV_MIX, "hysteretic damper + hysteretic inverse"),
                "<",
                CONSIDERABLY,
            ),
            spread(
                peak("a_s"),
                _sub(
                    INV_MIX, "mean damper + mean inverse", "hysteretic damper + hysteretic inverse"
                ),
            ),
        ),
    ),
    Claim(
        "5.2-mean-models-smooth",
        "5.6",
        'The "inverse model"-based upon mean damping force characteristics coupled with the '
        "mean force MR-damper model would yield smooth responses, but these deviate "
        "significantly from the practically realizable responses.",
        "Fig 5.5 (ACM, k_d = 1): the mean pair's share of i_d above 5 Hz is at most 0.85 times the hysteretic "
        "pair's, and its peak |v_r| differs from theirs by more than 15 %.",
        all_of(
            compare(
                hf_fraction("i_d"),
                _sub(INV_MIX, "mean damper + mean inverse"),
                _sub(INV_MIX, "hysteretic damper + hysteretic inverse"),
                "<",
                CONSIDERABLY,
            ),
            compare(
                peak("v_r"),
                _sub(INV_MIX, "mean damper + mean inverse"),
                _sub(INV_MIX, "hysteretic damper + hysteretic inverse"),
                "<",
                CONSIDERABLY,
            ),
        ),
        also=("8.2",),
    ),
    # ---------------------------------------------------------------- 5.3 force gain
    Claim(
        "5.3-tracking-kd",
        "5.3",
        "The higher damping force permits reducing the force error between the target spring "
        "force and damping force.",
        "Fig 5.6 (inverse hi-lo, 2.5 cm / 1.5 Hz): rms(|F_d| - |F*|) while z_c < 0 falls as "
        "k_d rises (1, 2, 2.5), in ACM and SCM, by at least 15 % over the range.",
        all_of(
            monotone(TRACKING, INV_KD, "decreasing"),
            monotone(TRACKING, {f"SCM {k}": v for k, v in INV_KD_SCM.items()}, "decreasing"),
            compare(
                TRACKING, _sub(INV_KD, "k_d = 2.5"), _sub(INV_KD, "k_d = 1"), "<", CONSIDERABLY
            ),
        ),
        also=("5.6", "8.2"),
    ),
    Claim(
        "5.3-current-kd",
        "5.3",
        "the magnitude of drive current (i_d) in compression and rebound decreases with "
        "increasing value of k_d",
        "Fig 5.6 (ACM): the mean and the peak drive current fall as k_d rises.",
        all_of(
            monotone(MEAN_CURRENT, INV_KD, "decreasing"),
            monotone(peak("i_d"), INV_KD, "decreasing"),
        ),
    ),
    Claim(
        "5.3-peaks-kd",
        "5.3",
        "The results suggest a higher force gain yields improved suspension performance in "
        "view of a_s, a_u, x_s, x_r and F_T",
        "Fig 5.6 (ACM): peak |a_s|, |a_u|, |x_s|, |x_r| and |F_T| are lower at k_d = 2.5 than "
        "at k_d = 1.",
        _peaks_lower(
            ("a_s", "a_u", "x_s", "x_r", "F_T"), _one(INV_KD, "k_d = 2.5"), _sub(INV_KD, "k_d = 1")
        ),
    ),
    Claim(
        "5.3-frequency-kd",
        "5.3",
        "The peak acceleration and relative displacement transmissibility decrease "
        "significantly with higher force gain",
        "Fig 5.7 (ACM): peak T_as, T_au (0.5-15 Hz) and T_dr at k_d = 2.5 at most 0.85 times "
        "those at k_d = 1.",
        all_of(
            *(
                compare(
                    m, _sub(INV_KD_F, "k_d = 2.5"), _sub(INV_KD_F, "k_d = 1"), "<", CONSIDERABLY
                )
                for m in (fpeak("T_as"), fpeak("T_au", 0.5, 15.0), fpeak("T_dr"))
            )
        ),
    ),
    Claim(
        "5.3-mid-ride-kd",
        "5.3",
        "while the sprung mass acceleration response increases in the mid-ride frequencies region",
        "Fig 5.7 (ACM): mean T_as over 3-7 Hz is higher at k_d = 2.5 than at k_d = 1.",
        compare(
            fmean("T_as", 3.0, 7.0), _sub(INV_KD_F, "k_d = 2.5"), _sub(INV_KD_F, "k_d = 1"), ">"
        ),
        also=("5.6",),
    ),
    Claim(
        "5.3-dlc-kd",
        "5.3",
        "DLC due to tire force increases slightly in the 1.5 to 7.5 frequency range",
        "Fig 5.7 (ACM): DLC at k_d = 2.5 above k_d = 1 at more than half of the grid "
        "frequencies in 1.5-7.5 Hz.",
        fraction("DLC", _one(INV_KD_F, "k_d = 2.5"), _sub(INV_KD_F, "k_d = 1"), ">", (1.5, 7.5)),
    ),
    # ---------------------------------------------------------------- 5.4 response
    Claim(
        "5.4-harmonic-peaks",
        "5.4",
        "The results show that the semi-active ACM damping mode effectively reduces the peak "
        "magnitudes of x_s , a_s , x_r , and F_T , when compared to those attained under "
        "light and higher passive damping modes",
        "Fig 5.8: inverse hi-lo ACM (k_d = 2.5) has lower peak |x_s|, |a_s|, |x_r| and |F_T| "
        "than passive 0 A and 0.1 A.",
        _peaks_lower(
            ("x_s", "a_s", "x_r", "F_T"),
            _one(P5_T, "inverse-model hi-lo ACM"),
            _sub(P5_T, "passive 0 A", "passive 0.1 A"),
        ),
    ),
    Claim(
        "5.4-current-levels",
        "5.4",
        "current modulation is well below 0.1 A in the compression cycle, while the current "
        "approaches 0.35 A in the rebound mode",
        "Fig 5.8: peak drive current below 0.1 A in compression and 0.35 A within 25 % in rebound.",
        _identified_sensitivity(
            all_of(
                within(
                    phase_peak("i_d", "compression"),
                    _sub(P5_T, "inverse-model hi-lo ACM"),
                    0.0,
                    0.1,
                ),
                about(phase_peak("i_d", "rebound"), _sub(P5_T, "inverse-model hi-lo ACM"), 0.35),
            )
        ),
    ),
    Claim(
        "5.4-passive-resonance",
        "5.4",
        "both the passive damping modes yield higher resonant magnitudes of T_{as} , T_{dr} "
        "and DLC",
        "Fig 5.9: peak T_as, T_dr and DLC (0.5-4 Hz) of both passive modes exceed inverse "
        "hi-lo ACM's.",
        all_of(
            *(
                compare(
                    fpeak(k),
                    _sub(P5_F, "passive 0 A", "passive 0.1 A"),
                    _sub(P5_F, "inverse-model hi-lo ACM"),
                    ">",
                )
                for k in ("T_as", "T_dr", "DLC")
            )
        ),
    ),
    Claim(
        "5.4-light-passive-unsprung",
        "5.4",
        "Light passive mode damping yields significantly higher unsprung mass acceleration "
        "near the unsprung mass resonance but slightly lower response near the sprung mass "
        "resonance.",
        "Fig 5.9: mean T_au over 7-15 Hz at passive 0 A over 1/0.85 times inverse hi-lo "
        "ACM's; over 1-2.5 Hz lower than ACM's.",
        all_of(
            compare(
                fmean("T_au", 7.0, 15.0),
                _sub(P5_F, "inverse-model hi-lo ACM"),
                _sub(P5_F, "passive 0 A"),
                "<",
                CONSIDERABLY,
            ),
            compare(
                fmean("T_au", 1.0, 2.5),
                _sub(P5_F, "passive 0 A"),
                _sub(P5_F, "inverse-model hi-lo ACM"),
                "<",
            ),
        ),
    ),
    Claim(
        "5.4-ride-transmission",
        "5.4",
        "yields improved resonance control but slightly higher transmission in the important "
        "ride frequencies",
        "Fig 5.9: mean T_as over 3-7 Hz with inverse hi-lo ACM above passive 0 A's.",
        compare(
            fmean("T_as", 3.0, 7.0),
            _sub(P5_F, "inverse-model hi-lo ACM"),
            _sub(P5_F, "passive 0 A"),
            ">",
        ),
    ),
    Claim(
        "5.4-pulse",
        "5.4",
        "and higher passive damping ($i_d=0.1$ A) yield rapid rate of decay and effectively "
        "reduce the peak amplitudes of x_s and x_r",
        "Fig 5.10 (5 cm pulse): inverse hi-lo ACM and passive 0.1 A have lower peak |x_s|, "
        "|x_r| and rms x_s after the pulse (from its end) than passive 0 A.",
        all_of(
            *(
                compare(
                    m,
                    _sub(P5_P, "inverse-model hi-lo ACM", "passive 0.1 A"),
                    _sub(P5_P, "passive 0 A"),
                    "<",
                )
                for m in (peak("x_s"), peak("x_r"))
            ),
            _decay(
                _sub(P5_P, "inverse-model hi-lo ACM", "passive 0.1 A"), _sub(P5_P, "passive 0 A")
            ),
        ),
    ),
    Claim(
        "5.4-pulse-vs-skyhook",
        "5.4",
        'yields larger peak magnitude of a_s in compression than the "skyhook"-based hi-lo '
        "semi-active controller",
        "Figs 5.10 / 4.10 (5 cm pulse): peak |a_s| in compression is larger with inverse "
        "hi-lo ACM than with skyhook hi-lo ACM.",
        compare(
            phase_peak("a_s", "compression"),
            _sub(P5_P, "inverse-model hi-lo ACM"),
            _sub(P4_P, "skyhook hi-lo ACM"),
            ">",
        ),
    ),
    Claim(
        "5.4-pulse-current",
        "5.4",
        "The drive current exceeds 0.1 A only for short durations in rebound",
        "Figs 5.10 and 6.9 (5 cm pulse): inverse hi-lo and sliding mode ACM spend at most "
        "0.2 s of the 4 s record above 0.1 A.",
        _beta_sensitivity(
            within(
                time_above("i_d", 0.1),
                {
                    "inverse hi-lo": P5_P["inverse-model hi-lo ACM"],
                    "sliding mode": P6_P["sliding mode ACM"],
                },
                0.0,
                0.2,
            )
        ),
        also=("6.3",),
    ),
    Claim(
        "5.4-road-force",
        "5.4",
        "yields significantly higher damping force than the low passive mode damping "
        "($i_d=0$) in the entire frequency range",
        "Figs 5.11 / 6.10 (rough road): the PSD of F_d with inverse hi-lo and sliding mode "
        "ACM is above passive 0 A's at 90 % or more of the 0.5-20 Hz bins.",
        all_of(
            fraction(
                "PSD F_d",
                _one(P5_R, "inverse-model hi-lo ACM"),
                _sub(P5_R, "passive 0 A"),
                ">",
                (0.5, 20.0),
                0.9,
                strictly_more=False,
            ),
            fraction(
                "PSD F_d",
                _one(P6_R, "sliding mode ACM"),
                _sub(P6_R, "passive 0 A"),
                ">",
                (0.5, 20.0),
                0.9,
                strictly_more=False,
            ),
        ),
        depends_on=(ROAD,),
        also=("6.3",),
    ),
    Claim(
        "5.4-road-ride",
        "5.4",
        "The resulting high damping force tends to suppress the sprung mass acceleration near "
        "the resonant frequency but causes considerably higher acceleration responses in the "
        "ride frequency range.",
        "Figs 5.11 / 6.10: mean PSD of a_s over 2-7 Hz with inverse hi-lo and sliding mode "
        "ACM over 1/0.85 times passive 0 A's; over 1-2 Hz lower than passive 0 A's.",
        all_of(
            compare(
                psd_mean("a_s", 2.0, 7.0),
                _sub(P5_R, "passive 0 A"),
                {
                    "inverse hi-lo": P5_R["inverse-model hi-lo ACM"],
                    "sliding mode": P6_R["sliding mode ACM"],
                },
                "<",
                CONSIDERABLY,
            ),
            compare(
                psd_mean("a_s", 1.0, 2.0),
                {
                    "inverse hi-lo": P5_R["inverse-model hi-lo ACM"],
                    "sliding mode": P6_R["sliding mode ACM"],
                },
                _sub(P5_R, "passive 0 A"),
                "<",
            ),
        ),
        depends_on=(ROAD,),
        also=("6.3", "5.6", "8.2"),
    ),
    Claim(
        "5.4-road-dlc",
        "5.4",
        "The DLC value due to dynamic tire force of the semi-active ACM damping mode is in "
        "the order of 0.113, which is slightly lower than 0.139 due to that with the fixed "
        "low passive damping mode.",
        "Fig 5.11 (rough road): inverse hi-lo ACM's DLC is 0.7-0.95 times passive 0 A's "
        "(dissertation 0.81).",
        ratio(
            ROAD_DLC,
            _one(P5_R, "inverse-model hi-lo ACM"),
            _one(P5_R, "passive 0 A"),
            0.7,
            0.95,
            0.113 / 0.139,
        ),
        depends_on=(ROAD,),
    ),
    # ---------------------------------------------------------------- 5.5.1 mass
    Claim(
        "5.5.1-harmonic-mass",
        "5.5.1",
        "The magnitude of the damping force tends to increase with increasing sprung mass.",
        "Fig 5.12 (inverse hi-lo ACM): peak |F_d|, |x_r| and |F_T| rise with m_s.",
        _monotone_all(("F_d", "x_r", "F_T"), M5_T, "increasing"),
    ),
    Claim(
        "5.5.1-frequency-mass",
        "5.5.1",
        "the peak resonant magnitudes of T_{as} and T_{dr} remain insensitive to the sprung "
        "mass variations, while the peak magnitudes of T_{au} and DLC around the sprung mass "
        "natural frequency increase slightly with increasing m_s",
        "Fig 5.13: peak T_as and T_dr spread at most 10 % over m_s; peak T_au and DLC "
        "(0.5-4 Hz) rise with m_s.",
        all_of(
            spread(fpeak("T_as"), M5_F),
            spread(fpeak("T_dr"), M5_F),
            monotone(fpeak("T_au"), M5_F),
            monotone(fpeak("DLC"), M5_F),
        ),
    ),
    Claim(
        "5.5.1-table",
        "5.5.1",
        "The sprung mass shock displacement ratio (SDR_s) and acceleration ratio (SAR_s) "
        "increase with decreasing sprung mass.",
        "Table 5.1: SDR_s and SAR_s fall as m_s rises; SDR_u, SAR_u and RDR spread at most 10 %.",
        all_of(
            monotone(SHOCK["SDR_s"], T51, "decreasing"),
            monotone(SHOCK["SAR_s"], T51, "decreasing"),
            _insensitive_shock(T51, ("SDR_u", "SAR_u", "RDR"), INSENSITIVE),
        ),
    ),
    Claim(
        "5.5.1-table-dtr",
        "5.5.1",
        "The peak force deviations (DTR) decreases and increases by 18% and 14%, when the "
        "sprung mass is decreased and increased by 25%, respectively.",
        "Table 5.1: DTR 0.18 at 422 kg and 0.14 at 703 kg, within 30 %.",
        _dtr_readings(
            _one(T51, "m_s = 563"),
            {"m_s = 422": (T51["m_s = 422"], 0.18), "m_s = 703": (T51["m_s = 703"], 0.14)},
        ),
    ),
    Claim(
        "5.5.1-road-light-ride",
        "5.5.1",
        "The sprung mass acceleration response, however, increases with decreasing mass at "
        "higher frequencies.",
        "Figs 5.15 / 6.14 (rough road): mean PSD of a_s over 4-20 Hz is higher for 422 kg "
        "than for 703 kg, with inverse hi-lo and with sliding mode.",
        all_of(
            compare(
                psd_mean("a_s", 4.0, 20.0),
                {"inverse 422 kg": M5_R["m_s = 422 kg"]},
                {"inverse 703 kg": M5_R["m_s = 703 kg"]},
                ">",
            ),
            compare(
                psd_mean("a_s", 4.0, 20.0),
                {"sliding 422 kg": M6_R["m_s = 422 kg"]},
                {"sliding 703 kg": M6_R["m_s = 703 kg"]},
                ">",
            ),
        ),
        depends_on=(ROAD,),
        also=("6.4.1",),
    ),
    # ---------------------------------------------------------------- 5.5.2 speed
    Claim(
        "5.5.2-pulse-speed",
        "5.5.2",
        "Operation at a higher speed ($V=100$ km/h) results in higher demand on the damping "
        "force, and yields higher peak acceleration but lower sprung mass displacement.",
        "Figs 5.16 / 6.15 (3.5 cm pulse): at 100 km/h peak |F_d| and |a_s| are higher and "
        "peak |x_s| lower than at 50 km/h, with inverse hi-lo and with sliding mode.",
        all_of(
            *(
                all_of(
                    compare(
                        peak("F_d"),
                        {f"{n} 100 km/h": r["V = 100 km/h"]},
                        {f"{n} 50 km/h": r["V = 50 km/h"]},
                        ">",
                    ),
                    compare(
                        peak("a_s"),
                        {f"{n} 100 km/h": r["V = 100 km/h"]},
                        {f"{n} 50 km/h": r["V = 50 km/h"]},
                        ">",
                    ),
                    compare(
                        peak("x_s"),
                        {f"{n} 100 km/h": r["V = 100 km/h"]},
                        {f"{n} 50 km/h": r["V = 50 km/h"]},
                        "<",
                    ),
                )
                for n, r in (("inverse", V5_P), ("sliding", V6_P))
            )
        ),
        also=("6.4.2",),
    ),
    Claim(
        "5.5.2-table-changes",
        "5.5.2",
        "The sprung mass displacement and acceleration ratios (SDR_s and SAR_s) and the "
        "unsprung mass acceleration ratio (SAR_u) decrease by 42%, 76% and 54%, respectively",
        "Table 5.2's rows: at 100 km/h SDR_s changes by -37 %, SAR_s by -76 %, SAR_u by -61 %.",
        all_of(
            *(
                change(SHOCK[k], _one(T52, "V = 50"), {"V = 100": (T52["V = 100"], c)})
                for k, c in (
                    ("SDR_s", 0.57 / 0.91 - 1),
                    ("SAR_s", -0.76),
                    ("SAR_u", 0.48 / 1.24 - 1),
                )
            )
        ),
        inconsistent="the text's 42 % and 54 % do not match Table 5.2's rows (SDR_s 0.91 -> "
        "0.57 is -37 %, SAR_u 1.24 -> 0.48 is -61 %); 42 % is Table 4.2's SDR_s change. The "
        "table is tested.",
    ),
    Claim(
        "5.5.2-table-rest",
        "5.5.2",
        "The results also show that the unsprung mass and relative displacement ratios "
        "(SDR_u and RDR) remain insensitive to variations in speed.",
        "Table 5.2: SDR_u and RDR within 10 % between 50 and 100 km/h; DTR 0.37 within 30 %.",
        all_of(
            _insensitive_shock(T52, ("SDR_u", "RDR"), INSENSITIVE),
            dtr_values(_one(T52, "V = 50"), {"V = 100": (T52["V = 100"], 0.37)}),
        ),
    ),
    Claim(
        "5.5.2-road-dlc",
        "5.5.2",
        "The DLC due to tire force at 100 km/h increases slightly to 0.114, compared to 0.113 "
        "at 50 km/h.",
        "Figs 5.17 / 6.16 (rough road): DLC at 100 km/h is 0.97-1.1 times that at 50 km/h, "
        "with inverse hi-lo and with sliding mode.",
        all_of(
            ratio(
                ROAD_DLC,
                ("inverse 100 km/h", V5_R["V = 100 km/h"]),
                ("inverse 50 km/h", V5_R["V = 50 km/h"]),
                0.97,
                1.1,
                0.114 / 0.113,
            ),
            ratio(
                ROAD_DLC,
                ("sliding 100 km/h", V6_R["V = 100 km/h"]),
                ("sliding 50 km/h", V6_R["V = 50 km/h"]),
                0.97,
                1.1,
                0.114 / 0.112,
            ),
        ),
        depends_on=(ROAD,),
        also=("6.4.2",),
    ),
    # ---------------------------------------------------------------- 5.5.3 excitation
    Claim(
        "5.5.3-harmonic-amplitude",
        "5.5.3",
        "Despite the higher damping force, the amplitudes of sprung mass (x_s and a_s) and "
        "tire force (F_T) responses increase considerably with increasing excitation "
        "amplitude.",
        "Fig 5.18 (1.5 Hz): peak |F_d|, |x_s|, |a_s| and |F_T| rise with the amplitude; the "
        "peak drive current varies by at most 25 %.",
        all_of(
            _monotone_all(("F_d", "x_s", "a_s", "F_T"), A5_T, "increasing"),
            spread(peak("i_d"), A5_T, SLIGHT),
        ),
    ),
    Claim(
        "5.5.3-frequency-amplitude",
        "5.5.3",
        "An increase in the excitation magnitude, however, does not alter the peak unsprung "
        "mass acceleration transmissibility (T_{au}).",
        "Fig 5.19: peak T_au (0.5-15 Hz) spread at most 10 %; peak T_as rises with the "
        "amplitude; peak DLC rises with it.",
        all_of(
            spread(fpeak("T_au", 0.5, 15.0), A5_F),
            monotone(fpeak("T_as"), A5_F),
            monotone(fpeak("DLC", 0.5, 15.0), A5_F),
        ),
    ),
    Claim(
        "5.5.3-pulse-height",
        "5.5.3",
        "An increase in peak excitation displacement yields higher peak damping force in "
        "response to increased target force and thus higher sprung mass acceleration.",
        "Figs 5.20 / 6.19 (pulse 2, 3.5, 5 cm): peak |F_d| and |a_s| rise with the height, "
        "with inverse hi-lo and with sliding mode.",
        all_of(
            *(
                _monotone_all(("F_d", "a_s"), {f"{n} {k}": v for k, v in r.items()}, "increasing")
                for n, r in (("inverse", A5_P), ("sliding", A6_P))
            )
        ),
        also=("6.4.3",),
    ),
    Claim(
        "5.5.3-table",
        "5.5.3",
        "The corresponding unsprung mass shock displacement and acceleration ratios (SDR_u "
        "and SAR_u) and relative displacement ratio (RDR) reveal increases and decreases by "
        "0.9% and 0.9%, 0.8% and 0.8%, and 2.3% and 2.3%.",
        "Table 5.3: SDR_s rises with the pulse height (0.88, 0.91, 0.96); SDR_u, SAR_u and "
        "RDR spread at most 10 %; DTR 0.29 at 2 and 5 cm within 30 %.",
        all_of(
            monotone(SHOCK["SDR_s"], T53),
            _insensitive_shock(T53, ("SDR_u", "SAR_u", "RDR"), INSENSITIVE),
            dtr_values(
                _one(T53, "a_m = 3.5"),
                {"a_m = 2": (T53["a_m = 2"], 0.29), "a_m = 5": (T53["a_m = 5"], 0.29)},
            ),
        ),
    ),
    Claim(
        "5.5.3-road-roughness",
        "5.5.3",
        "The DLC due to tire force for the rough random road excitation is in the order of "
        "0.113, which is considerably higher than 0.056 obtained for the medium-rough road "
        "excitation.",
        "Figs 5.21 / 6.20: rough/medium-rough DLC ratio 2.0 (inverse hi-lo) and 2.1 (sliding "
        "mode), within 25 %.",
        all_of(
            ratio(
                ROAD_DLC,
                ("inverse rough", R5["rough"]),
                ("inverse medium", R5["medium-rough"]),
                0.75 * 0.113 / 0.056,
                1.25 * 0.113 / 0.056,
                0.113 / 0.056,
            ),
            ratio(
                ROAD_DLC,
                ("sliding rough", R6["rough"]),
                ("sliding medium", R6["medium-rough"]),
                0.75 * 0.112 / 0.054,
                1.25 * 0.112 / 0.054,
                0.112 / 0.054,
            ),
        ),
        depends_on=(ROAD,),
        also=("6.4.3",),
    ),
    Claim(
        "5.4-road-dlc-levels",
        "5.4",
        "The DLC value due to dynamic tire force of the semi-active ACM damping mode is in "
        "the order of 0.113",
        "Road DLC levels (50 km/h) within 25 %: rough, passive 0 A 0.139, inverse hi-lo 0.113, "
        "sliding mode 0.112; medium-rough, inverse hi-lo 0.056, sliding mode 0.054.",
        _road_levels(
            {
                "rough passive 0 A": (P5_R["passive 0 A"], 0.139),
                "rough inverse hi-lo": (P5_R["inverse-model hi-lo ACM"], 0.113),
                "rough sliding mode": (P6_R["sliding mode ACM"], 0.112),
                "medium-rough inverse hi-lo": (R5["medium-rough"], 0.056),
                "medium-rough sliding mode": (R6["medium-rough"], 0.054),
            }
        ),
        depends_on=(ROAD,),
        also=("5.5.3", "6.3", "6.4.3"),
    ),
    # ---------------------------------------------------------------- 6.2 sliding mode
    Claim(
        "6.2-mixed-inverse-transients",
        "6.2",
        "exhibit relatively high magnitudes of transient responses near $v_r \\approx 0$",
        "Figs 6.1 / 6.2 (sliding mode SCM, k_d = 1, as section 6.2 states): max |dF_d/dt| "
        "and rms di_d/dt are larger with the mean inverse than with the hysteretic inverse.",
        all_of(
            *(
                compare(
                    m,
                    _sub(SM_MIX_SCM, "hysteretic damper + mean inverse"),
                    _sub(SM_MIX_SCM, "hysteretic damper + hysteretic inverse"),
                    ">",
                )
                for m in (max_rate("F_d"), rms_rate("i_d"))
            )
        ),
        also=("6.6",),
    ),
    Claim(
        "6.2-tracking-speed",
        "6.2",
        "can yield satisfactory forcing-tracking ability only at higher velocities, while the "
        "forcing-tracking ability at low velocities is severely limited due to low pre-yield "
        "damping forces",
        "Sliding mode SCM (k_d = 1): the relative tracking error while z_c < 0 at |v_r| < "
        "0.1 m/s is over twice that at |v_r| >= 0.3 m/s.",
        _tracking_by_speed(("sliding mode SCM k_d = 1", SM_H1)),
        also=("6.6", "8.2"),
    ),
    Claim(
        "6.2-kd-smoother",
        "6.2",
        "The results show more smooth variations and lower magnitude transient oscillations "
        "in the drive current",
        "Figs 6.3 / 6.2 (sliding mode SCM): the share of i_d above 5 Hz and the peak drive "
        "current are lower at k_d = 2.5 than at k_d = 1 (peak current at most 0.85 times).",
        _beta_sensitivity(
            all_of(
                compare(
                    hf_fraction("i_d"),
                    _sub(SM_34, "SCM k_d = 2.5"),
                    _sub(SM_34, "SCM k_d = 1"),
                    "<",
                ),
                compare(
                    peak("i_d"),
                    _sub(SM_34, "SCM k_d = 2.5"),
                    _sub(SM_34, "SCM k_d = 1"),
                    "<",
                    CONSIDERABLY,
                ),
            )
        ),
    ),
    Claim(
        "6.2-tracking-kd",
        "6.2",
        "The force-tracking ability of the controller is also considerably enhanced",
        "Sliding mode (2.5 cm / 1.5 Hz): rms(|F_d| - |F_c|) while z_c < 0 is at most 0.85 "
        "times at k_d = 2.5 what it is at k_d = 1, in SCM (Figs 6.3 / 6.2) and in ACM (Fig "
        "6.4 / ACM at k_d = 1).",
        all_of(
            compare(
                TRACKING,
                _sub(SM_34, "SCM k_d = 2.5"),
                _sub(SM_34, "SCM k_d = 1"),
                "<",
                CONSIDERABLY,
            ),
            compare(
                TRACKING,
                _sub(SM_34, "ACM k_d = 2.5"),
                {"ACM k_d = 1": fig("6.5", "ACM k_d = 2.5", damper={"force_gain": 1.0})},
                "<",
                CONSIDERABLY,
            ),
        ),
        also=("6.6", "8.2"),
    ),
    Claim(
        "6.2-acm-current",
        "6.2",
        "the ACM control can further reduce the power consumption by nearly 50%",
        "Figs 6.4 / 6.3 (sliding mode, k_d = 2.5): mean drive current in ACM 0.35-0.65 times "
        "that in SCM.",
        ratio(
            MEAN_CURRENT,
            _one(SM_34, "ACM k_d = 2.5"),
            _one(SM_34, "SCM k_d = 2.5"),
            0.35,
            0.65,
            0.5,
        ),
    ),
    Claim(
        "6.2-acm-tracking",
        "6.2",
        "The ACM control yields improved force-tracking and transient response suppression "
        "than the SCM",
        "Figs 6.4 / 6.3 (sliding mode, k_d = 2.5): ACM's tracking error and share of i_d above "
        "5 Hz are below SCM's.",
        _beta_sensitivity(
            all_of(
                compare(TRACKING, _sub(SM_34, "ACM k_d = 2.5"), _sub(SM_34, "SCM k_d = 2.5"), "<"),
                compare(
                    hf_fraction("i_d"),
                    _sub(SM_34, "ACM k_d = 2.5"),
                    _sub(SM_34, "SCM k_d = 2.5"),
                    "<",
                ),
            )
        ),
    ),
    Claim(
        "6.2-sm-vs-hilo",
        "6.2",
        "could offer superior force-tracking and hysteresis rejection properties than the "
        "hi-lo semi-active controller",
        "ACM, k_d = 2.5: the relative tracking error (rms(|F_d| - |F*|) / rms(F*) while "
        "z_c < 0) of sliding mode is below inverse hi-lo's.",
        compare(relative_tracking_all(), {"sliding mode": SM_H}, {"inverse hi-lo": INV_H}, "<"),
    ),
    Claim(
        "6.2-acm-vs-nominal-scm",
        "6.2",
        "Peak magnitudes of x_s , x_r and a_u for ACM control ($k_d=2.5$) are considerably lower "
        "than those obtained for the nominal force SCM control ($k_d=1$).",
        "Fig 6.5: peak |x_s|, |x_r| and |a_u| of ACM k_d = 2.5 at most 0.85 times those of "
        "SCM k_d = 1.",
        all_of(
            *(
                compare(
                    peak(s),
                    _sub(SM_G, "ACM k_d = 2.5"),
                    _sub(SM_G, "SCM k_d = 1"),
                    "<",
                    CONSIDERABLY,
                )
                for s in ("x_s", "x_r", "a_u")
            )
        ),
    ),
    Claim(
        "6.2-frequency-kd",
        "6.2",
        "decrease significantly with higher force gain, while T_{as} and DLC response increase "
        "slightly in 1.5 to 8 frequency range",
        "Fig 6.6 (SCM): peak T_as, T_au (0.5-15 Hz) and T_dr at k_d = 2.5 at most 0.85 times "
        "those at k_d = 1; T_as and DLC above k_d = 1's at more than half of the 1.5-8 Hz grid.",
        all_of(
            *(
                compare(
                    m, _sub(SM_G_F, "SCM k_d = 2.5"), _sub(SM_G_F, "SCM k_d = 1"), "<", CONSIDERABLY
                )
                for m in (fpeak("T_as"), fpeak("T_au", 0.5, 15.0), fpeak("T_dr"))
            ),
            *(
                fraction(
                    k, _one(SM_G_F, "SCM k_d = 2.5"), _sub(SM_G_F, "SCM k_d = 1"), ">", (1.5, 8.0)
                )
                for k in ("T_as", "DLC")
            ),
        ),
    ),
    Claim(
        "6.2-acm-tau",
        "6.2",
        "the ACM control could offer superior benefits in attenuating the peak magnitudes of "
        "T_{au} around the sprung mass natural frequency",
        "Fig 6.6 (k_d = 2.5): peak T_au over 0.5-4 Hz lower in ACM than in SCM.",
        compare(fpeak("T_au"), _sub(SM_G_F, "ACM k_d = 2.5"), _sub(SM_G_F, "SCM k_d = 2.5"), "<"),
    ),
    # ---------------------------------------------------------------- 6.3 response
    Claim(
        "6.3-harmonic-peaks",
        "6.3",
        "the semi-active ACM damping mode effectively reduces the peak magnitudes of x_s , a_s "
        ", x_r , and F_T",
        "Fig 6.7: sliding mode ACM (k_d = 2.5) has lower peak |x_s|, |a_s|, |x_r| and |F_T| "
        "than passive 0 A and 0.1 A.",
        _peaks_lower(
            ("x_s", "a_s", "x_r", "F_T"),
            _one(P6_T, "sliding mode ACM"),
            _sub(P6_T, "passive 0 A", "passive 0.1 A"),
        ),
    ),
    Claim(
        "6.3-current-levels",
        "6.3",
        "current modulation is well below 0.06 A in compression, while the current approaches "
        "0.15 A in the rebound mode",
        "Fig 6.7: peak drive current below 0.06 A in compression and 0.15 A within 25 % in "
        "rebound.",
        _beta_sensitivity(
            all_of(
                within(phase_peak("i_d", "compression"), _sub(P6_T, "sliding mode ACM"), 0.0, 0.06),
                about(phase_peak("i_d", "rebound"), _sub(P6_T, "sliding mode ACM"), 0.15),
            )
        ),
    ),
    Claim(
        "6.3-passive-resonance",
        "6.3",
        "Both the passive damping modes yield higher resonant magnitudes of T_{as} , T_{dr} "
        "and DLC, while the light passive mode damping yields significantly higher unsprung "
        "mass acceleration near the unsprung mass resonance",
        "Fig 6.8: peak T_as, T_dr and DLC (0.5-4 Hz) of both passive modes exceed sliding "
        "mode's; mean T_au over 7-15 Hz at passive 0 A over 1/0.85 times sliding mode's.",
        all_of(
            *(
                compare(
                    fpeak(k),
                    _sub(P6_F, "passive 0 A", "passive 0.1 A"),
                    _sub(P6_F, "sliding mode ACM"),
                    ">",
                )
                for k in ("T_as", "T_dr", "DLC")
            ),
            compare(
                fmean("T_au", 7.0, 15.0),
                _sub(P6_F, "sliding mode ACM"),
                _sub(P6_F, "passive 0 A"),
                "<",
                CONSIDERABLY,
            ),
        ),
    ),
    Claim(
        "6.3-ride-rattle",
        "6.3",
        "yields improved resonance control but slightly higher vibration transmission in the "
        "important ride frequencies. The suspension rattle space requirements, however, could "
        "be considerably reduced",
        "Fig 6.8: mean T_as over 3-7 Hz with sliding mode above passive 0 A's; its peak T_dr "
        "at most 0.85 times both passive modes'.",
        _identified_sensitivity(
            all_of(
                compare(
                    fmean("T_as", 3.0, 7.0),
                    _sub(P6_F, "sliding mode ACM"),
                    _sub(P6_F, "passive 0 A"),
                    ">",
                ),
                compare(
                    fpeak("T_dr"),
                    _sub(P6_F, "sliding mode ACM"),
                    _sub(P6_F, "passive 0 A", "passive 0.1 A"),
                    "<",
                    CONSIDERABLY,
                ),
            )
        ),
    ),
    Claim(
        "6.3-pulse",
        "6.3",
        "and higher passive damping ($i_d=0.1$ A) yield rapid rate of decay and effectively "
        "reduce the peak amplitudes of x_s and x_r",
        "Fig 6.9 (5 cm pulse): sliding mode ACM and passive 0.1 A have lower peak |x_s|, "
        "|x_r| and rms x_s after the pulse (from its end) than passive 0 A.",
        all_of(
            *(
                compare(
                    m,
                    _sub(P6_P, "sliding mode ACM", "passive 0.1 A"),
                    _sub(P6_P, "passive 0 A"),
                    "<",
                )
                for m in (peak("x_s"), peak("x_r"))
            ),
            _decay(_sub(P6_P, "sliding mode ACM", "passive 0.1 A"), _sub(P6_P, "passive 0 A")),
        ),
    ),
    Claim(
        "6.3-road-dlc",
        "6.3",
        "which is slightly lower than 0.139 and 0.113 due to those with the fixed passive "
        'damping mode and "inverse model"-based hi-lo semi-active control',
        "Fig 6.10 (rough road): sliding mode's DLC is below passive 0 A's and below inverse "
        "hi-lo's.",
        compare(
            ROAD_DLC,
            _sub(P6_R, "sliding mode ACM"),
            {"passive 0 A": P6_R["passive 0 A"], "inverse hi-lo": P5_R["inverse-model hi-lo ACM"]},
            "<",
        ),
        depends_on=(ROAD,),
    ),
    # ---------------------------------------------------------------- 6.4 operating
    Claim(
        "6.4.1-harmonic-mass",
        "6.4.1",
        "The magnitudes of the drive current (i_d) and the resulting sprung and unsprung "
        "mass accelerations (a_s , a_u) and sprung mass displacement (x_s), decrease "
        "with increasing sprung mass.",
        "Fig 6.11 (sliding mode ACM): peak |F_d|, |x_r| and |F_T| rise with m_s; peak drive "
        "current, |a_s|, |a_u| and |x_s| fall.",
        all_of(
            _monotone_all(("F_d", "x_r", "F_T"), M6_T, "increasing"),
            _monotone_all(("i_d", "a_s", "a_u", "x_s"), M6_T, "decreasing"),
        ),
    ),
    Claim(
        "6.4.1-frequency-mass",
        "6.4.1",
        "The peak magnitudes of T_{as} and T_{dr} increase only slightly with increasing "
        "sprung mass, while the peak magnitudes of T_{au} and DLC decrease.",
        "Fig 6.12: peak T_as and T_dr rise with m_s (spread at most 25 %); peak T_au and DLC "
        "(0.5-15 Hz) fall.",
        all_of(
            monotone(fpeak("T_as"), M6_F),
            monotone(fpeak("T_dr"), M6_F),
            spread(fpeak("T_as"), M6_F, SLIGHT),
            spread(fpeak("T_dr"), M6_F, SLIGHT),
            monotone(fpeak("T_au", 0.5, 15.0), M6_F, "decreasing"),
            monotone(fpeak("DLC", 0.5, 15.0), M6_F, "decreasing"),
        ),
    ),
    Claim(
        "6.4.1-table",
        "6.4.1",
        "The sprung mass shock displacement (SDR_s) and acceleration ratios (SAR_s) increase "
        "with decreasing sprung mass.",
        "Table 6.1: SDR_s and SAR_s fall as m_s rises; SDR_u, SAR_u, RDR spread at most 10 %; "
        "DTR 0.16 at 422 kg and 0.13 at 703 kg within 30 %.",
        all_of(
            monotone(SHOCK["SDR_s"], T61, "decreasing"),
            monotone(SHOCK["SAR_s"], T61, "decreasing"),
            _insensitive_shock(T61, ("SDR_u", "SAR_u", "RDR"), INSENSITIVE),
            _dtr_readings(
                _one(T61, "m_s = 563"),
                {"m_s = 422": (T61["m_s = 422"], 0.16), "m_s = 703": (T61["m_s = 703"], 0.13)},
            ),
        ),
    ),
    Claim(
        "6.4.1-more-robust-than-hilo",
        "6.4.1",
        'The results show relatively superior robustness of "inverse model"-based sliding '
        'mode semi-active control than the "inverse model"-based hi-lo semi-active control, '
        "in view of the sprung mass variations and transient responses.",
        "Tables 6.1 / 5.1: the relative spread of SAR_s over m_s is smaller with sliding mode "
        "than with inverse hi-lo.",
        rank(
            relative_spread(SHOCK["SAR_s"]),
            "relative spread of SAR_s over m_s",
            {"sliding mode": T61, "inverse hi-lo": T51},
            "sliding mode",
        ),
    ),
    Claim(
        "6.4.2-table",
        "6.4.2",
        "The sprung mass displacement and acceleration ratios (SDR_s and SAR_s) and the "
        "unsprung mass acceleration ratio (SAR_u) decrease by 42%, 76% and 58%",
        "Table 6.2's rows: at 100 km/h SDR_s changes by -37 %, SAR_s by -76 %, SAR_u by -58 %; "
        "DTR 0.35 within 30 %.",
        all_of(
            *(
                change(SHOCK[k], _one(T62, "V = 50"), {"V = 100": (T62["V = 100"], c)})
                for k, c in (("SDR_s", 0.57 / 0.91 - 1), ("SAR_s", -0.76), ("SAR_u", -0.58))
            ),
            dtr_values(_one(T62, "V = 50"), {"V = 100": (T62["V = 100"], 0.35)}),
        ),
        inconsistent="the text's 42 % for SDR_s does not match Table 6.2's rows (0.91 -> 0.57 "
        "is -37 %; 42 % is Table 4.2's); the table is tested.",
    ),
    Claim(
        "6.4.3-harmonic-amplitude",
        "6.4.3",
        "an increase in excitation amplitude yields higher magnitudes of the target (spring) "
        "force (F_d), and sprung mass displacement and acceleration (x_s and a_s) and tire "
        "force (F_T) responses",
        "Fig 6.17 (sliding mode, 1.5 Hz): peak |F_c|, |F_d|, |x_s|, |a_s| and |F_T| rise with "
        "the amplitude.",
        _monotone_all(("F*", "F_d", "x_s", "a_s", "F_T"), A6_T, "increasing"),
    ),
    Claim(
        "6.4.3-frequency-amplitude",
        "6.4.3",
        "Lower excitation magnitude yields lower sprung mass acceleration near the sprung mass "
        "resonance due to relatively higher damping force.",
        "Fig 6.18: peak T_as rises with the amplitude; peak T_as and T_dr spread at most 10 % "
        "between 2.5 and 3.5 cm; peak DLC (0.5-15 Hz) rises with the amplitude.",
        all_of(
            monotone(fpeak("T_as"), A6_F),
            spread(fpeak("T_as"), _sub(A6_F, "a = 2.5 cm", "a = 3.5 cm")),
            spread(fpeak("T_dr"), _sub(A6_F, "a = 2.5 cm", "a = 3.5 cm")),
            monotone(fpeak("DLC", 0.5, 15.0), A6_F),
        ),
        also=("5.5.3",),
    ),
    Claim(
        "6.4.3-low-amplitude-tau",
        "6.4.3",
        "The lower excitation magnitude, however, causes undesirable variations in unsprung "
        "mass acceleration response (T_{au}) in the vicinity of sprung mass resonance.",
        "Fig 6.18: peak T_au over 0.5-4 Hz is higher at 1.5 cm than at 2.5 cm.",
        compare(fpeak("T_au"), _sub(A6_F, "a = 1.5 cm"), _sub(A6_F, "a = 2.5 cm"), ">"),
    ),
    Claim(
        "6.4.3-table",
        "6.4.3",
        "The peak force deviation (DTR) increases and decreases in the order of 30% and 29%, "
        "when the peak displacement is increased to 5 cm and decreased to 2 cm",
        "Table 6.3: SDR_s rises with the pulse height (0.90, 0.94, 0.98); DTR 0.29 at 2 cm "
        "and 0.30 at 5 cm within 30 %.",
        all_of(
            monotone(SHOCK["SDR_s"], T63),
            dtr_values(
                _one(T63, "a_m = 3.5"),
                {"a_m = 2": (T63["a_m = 2"], 0.29), "a_m = 5": (T63["a_m = 5"], 0.30)},
            ),
        ),
    ),
    Claim(
        "6.4-nominal-rows",
        "6.4.1",
        "Table 6.1: Influence of sprung masses variations on the transient response measures.",
        "The nominal case (sliding mode ACM, 563 kg, 3.5 cm, 50 km/h) is one run: our SDR_s, "
        "SAR_s, SDR_u, SAR_u and RDR within 25 % of every nominal row the dissertation prints for it "
        "(Tables 6.1, 6.2, 6.3).",
        all_of(
            *(
                about_each(SHOCK[k], ("nominal", T61["m_s = 563"]), values)
                for k, values in (
                    ("SDR_s", (0.89, 0.91, 0.94)),
                    ("SAR_s", (0.27, 0.25, 0.27)),
                    ("SDR_u", (1.13, 1.02, 1.14)),
                    ("SAR_u", (1.29, 1.15, 1.15)),
                    ("RDR", (0.86, 0.86, 0.80)),
                )
            )
        ),
        inconsistent="Tables 6.1, 6.2 and 6.3 print different rows for the same nominal case: "
        "SDR_s 0.89 / 0.91 / 0.94, SAR_s 0.27 / 0.25 / 0.27, SDR_u 1.13 / 1.02 / 1.14, SAR_u "
        "1.29 / 1.15 / 1.15, RDR 0.86 / 0.86 / 0.80 (Table 6.2's SDR_s and SAR_s equal Table "
        "5.2's); every printed value is tested against our one run.",
        depends_on=(SAR,),
        also=("6.4.2", "6.4.3"),
    ),
    # ---------------------------------------------------------------- 6.5 comparison
    Claim(
        "6.5-skyhook-ride",
        "6.5",
        "yield slightly poor vibration attenuation in the important ride frequency range (2-7 Hz)",
        "Figs 4.9 / 5.9 / 6.8 (ACM): mean T_as over 2-7 Hz of skyhook hi-lo below inverse "
        "hi-lo's and sliding mode's (k_d = 2.5).",
        compare(
            fmean("T_as", 2.0, 7.0),
            _sub(CTRL_F, "skyhook hi-lo"),
            _sub(CTRL_F, "inverse hi-lo", "sliding mode"),
            "<",
        ),
        also=("8.2",),
    ),
    Claim(
        "6.5-inverse-resonance",
        "6.5",
        "but superior resonance control",
        "Figs 4.9 / 5.9 / 6.8: peak T_as (0.5-4 Hz) of inverse hi-lo and sliding mode below "
        "skyhook hi-lo's.",
        compare(
            fpeak("T_as"),
            _sub(CTRL_F, "inverse hi-lo", "sliding mode"),
            _sub(CTRL_F, "skyhook hi-lo"),
            "<",
        ),
        inconsistent="the sentence before says the skyhook hi-lo ACM controller 'could offer "
        "both superior resonance control and vibration attenuation in nearly entire frequency "
        "range'; the inverse-model laws' superior resonance control is tested.",
    ),
    Claim(
        "6.5-skyhook-shock",
        "6.5",
        'the "skyhook"-based hi-lo semi-active controller offers superior control of the peak '
        "shock ratio of the sprung mass acceleration, than the other two controllers",
        "Tables 4.1 / 5.1 / 6.1 nominal rows (3.5 cm pulse): SAR_s of skyhook hi-lo below "
        "inverse hi-lo's and sliding mode's.",
        compare(
            SHOCK["SAR_s"],
            {"skyhook hi-lo": T41["m_s = 563"]},
            {"inverse hi-lo": T51["m_s = 563"], "sliding mode": T61["m_s = 563"]},
            "<",
        ),
    ),
    Claim(
        "6.5-road-holding",
        "6.5",
        "offers superior unsprung mass acceleration (T_{au}) response in the vicinity of "
        "sprung mass natural frequency and lower values of DLC in the important ride "
        "frequency range (2-7 Hz) than the other two controllers",
        "Figs 4.9 / 5.9 / 6.8: skyhook hi-lo's mean T_au over 1-2.5 Hz and mean DLC over "
        "2-7 Hz below inverse hi-lo's and sliding mode's.",
        all_of(
            compare(
                fmean("T_au", 1.0, 2.5),
                _sub(CTRL_F, "skyhook hi-lo"),
                _sub(CTRL_F, "inverse hi-lo", "sliding mode"),
                "<",
            ),
            compare(
                fmean("DLC", 2.0, 7.0),
                _sub(CTRL_F, "skyhook hi-lo"),
                _sub(CTRL_F, "inverse hi-lo", "sliding mode"),
                "<",
            ),
        ),
    ),
    Claim(
        "6.5-skyhook-wheel-hop",
        "6.5",
        "This synthesis, however, yields slightly higher unsprung mass response in the "
        "vicinity of the unsprung mass natural frequency.",
        "Figs 4.9 / 5.9 / 6.8: skyhook hi-lo's mean T_au and T_dr over 7-15 Hz above inverse "
        "hi-lo's and sliding mode's.",
        all_of(
            *(
                compare(
                    fmean(k, 7.0, 15.0),
                    _sub(CTRL_F, "skyhook hi-lo"),
                    _sub(CTRL_F, "inverse hi-lo", "sliding mode"),
                    ">",
                )
                for k in ("T_au", "T_dr")
            )
        ),
    ),
    Claim(
        "6.5-rattle-space",
        "6.5",
        "For the suspension rattle space performance, the results suggest that all three "
        "controllers yield superior relative displacement transmissibility (T_{dr}).",
        "Figs 4.9 / 5.9 / 6.8: peak T_dr (0.5-4 Hz) of each controller below both passive modes'.",
        compare(fpeak("T_dr"), CTRL_F, PASSIVE_F, "<"),
    ),
    Claim(
        "6.5-mass-robust",
        "6.5",
        "particularly, yields superior robustness in view of the sprung mass resonance "
        "control than the other two controllers",
        "Figs 4.13 / 5.13 / 6.12: the relative spread of peak T_as over m_s is smallest with "
        "sliding mode.",
        rank(
            relative_spread(fpeak("T_as")),
            "relative spread of peak T_as over m_s",
            {"skyhook hi-lo": M4_F, "inverse hi-lo": M5_F, "sliding mode": M6_F},
            "sliding mode",
        ),
    ),
    Claim(
        "6.5-mass-dtr",
        "6.5",
        "This controller in ACM damping mode reveals relatively small deviations in peak tire "
        "forces, as evident from DTR in Tables 4.1, 5.1 and 6.1.",
        "Tables 4.1 / 5.1 / 6.1: the largest DTR over m_s is smallest with sliding mode.",
        readings(
            *(
                (
                    DTR_READINGS[r],
                    rank(
                        functools.partial(_dtr_max, reading=r),
                        "largest DTR over m_s",
                        {"skyhook hi-lo": T41, "inverse hi-lo": T51, "sliding mode": T61},
                        "sliding mode",
                    ),
                )
                for r in DTR_READINGS
            )
        ),
    ),
    Claim(
        "6.5-road-dlc-mass",
        "6.5",
        'The DLC due to tire force increases by 54%, 61% and 55% for the "skyhook"-based '
        'hi-lo, "inverse model"-based hi-lo and "inverse model"-based sliding mode ACM '
        "controllers, respectively, when m_s is increased from 422 to 703 kg.",
        "Figs 4.15 / 5.15 / 6.14 (rough road): DLC(703 kg) / DLC(422 kg) rises by 54 %, 61 % "
        "and 55 %, each within half to 1.5 times the stated rise.",
        _mass_dlc_growth(
            {
                "skyhook": (
                    ("skyhook 703 kg", M4_R["m_s = 703 kg"]),
                    ("skyhook 422 kg", M4_R["m_s = 422 kg"]),
                    1.54,
                ),
                "inverse": (
                    ("inverse 703 kg", M5_R["m_s = 703 kg"]),
                    ("inverse 422 kg", M5_R["m_s = 422 kg"]),
                    1.61,
                ),
                "sliding": (
                    ("sliding 703 kg", M6_R["m_s = 703 kg"]),
                    ("sliding 422 kg", M6_R["m_s = 422 kg"]),
                    1.55,
                ),
            }
        ),
        depends_on=(ROAD,),
        inconsistent="section 4.4.1 says in one paragraph that the DLC 'tends to be lower for "
        "heavier operating mass, which is attributed to its definition' and that it 'increases "
        "from 0.114 to 0.176' (4.4.1-road-dlc-heavier tests the first); the six printed DLCs "
        "(skyhook 0.114 / 0.176, inverse hi-lo 0.091 / 0.147, sliding mode 0.091 / 0.141 for "
        "422 / 703 kg) are ours with the masses swapped (ours over each car's own load: 0.112 / "
        "0.173, 0.093 / 0.152, 0.094 / 0.157 for 703 / 422 kg, within 2-11 %), which supports "
        "the DLC over each car's own load and a mislabelled rise; over the nominal load the "
        "DLC hardly changes with the mass (ratios 0.93-1.01). Both readings are tested.",
        also=("4.4.1", "5.5.1", "6.4.1"),
    ),
    Claim(
        "6.5-speed-robust",
        "6.5",
        "This is particularly observed in the sprung mass displacement ratio (SDR_s) and the "
        "peak tire force (DTR) responses to a rounded pulse excitation",
        "Tables 4.2 / 5.2 / 6.2: the relative change of SDR_s and the DTR from 50 to 100 "
        "km/h are smallest with sliding mode.",
        all_of(
            rank(
                _speed_change(SHOCK["SDR_s"]),
                "|change of SDR_s| 50 -> 100 km/h",
                {"skyhook hi-lo": T42, "inverse hi-lo": T52, "sliding mode": T62},
                "sliding mode",
            ),
            rank(
                _dtr_max,
                "DTR at 100 km/h",
                {"skyhook hi-lo": T42, "inverse hi-lo": T52, "sliding mode": T62},
                "sliding mode",
            ),
        ),
    ),
    Claim(
        "6.5-amplitude-skyhook",
        "6.5",
        'The "skyhook"-based hi-lo ACM controller yields relatively larger deviations in the '
        "response measures when excitation magnitudes are varied.",
        "Figs 4.19 / 5.19 / 6.18: the relative spread of peak T_as, T_au and T_dr over the "
        "amplitude is largest with skyhook hi-lo.",
        all_of(
            *(
                rank(
                    relative_spread(fpeak(k, 0.5, 15.0)),
                    f"relative spread of peak {k} over the amplitude",
                    {"skyhook hi-lo": A4_F, "inverse hi-lo": A5_F, "sliding mode": A6_F},
                    "skyhook hi-lo",
                    smallest=False,
                )
                for k in ("T_as", "T_au", "T_dr")
            )
        ),
    ),
    Claim(
        "6.6-load-sensitivity",
        "6.6",
        'The "inverse model"-based sliding mode ACM controller exhibits relatively lower '
        "sensitivity to variations in operating load.",
        "Tables 4.1 / 5.1 / 6.1: the relative spread of SAR_s over m_s is smallest with "
        "sliding mode.",
        rank(
            relative_spread(SHOCK["SAR_s"]),
            "relative spread of SAR_s over m_s",
            {"skyhook hi-lo": T41, "inverse hi-lo": T51, "sliding mode": T61},
            "sliding mode",
        ),
        also=("6.1", "8.2"),
    ),
    # ---------------------------------------------------------------- 8.2 conclusions
    Claim(
        "8.2-skyhook-vs-inverse",
        "8.2",
        "offers superior vibration attenuation, tire force and rattle space performance, "
        "when compared to those of other control syntheses formulated in the study",
        "ACM controllers (Figs 4.9 / 5.9 / 6.8): skyhook hi-lo has the lowest mean T_as, DLC "
        "and T_dr over 0.5-15 Hz of the three.",
        all_of(
            *(
                compare(
                    fmean(k, 0.5, 15.0),
                    _sub(CTRL_F, "skyhook hi-lo"),
                    _sub(CTRL_F, "inverse hi-lo", "sliding mode"),
                    "<",
                )
                for k in ("T_as", "DLC", "T_dr")
            )
        ),
        also=("6.5",),
    ),
    Claim(
        "8.2-inverse-robust",
        "8.2",
        'The "inverse model"-based hi-lo and sliding-mode ACM controllers exhibit desirable '
        "robust control performance with respect to variations in some of the operating "
        "parameters, namely, operating load and speed.",
        "Figs 5.13 / 6.12: peak T_as (0.5-4 Hz) varies by at most 25 % over m_s with both "
        "inverse-model laws.",
        all_of(
            spread(fpeak("T_as"), {f"inverse {k}": v for k, v in M5_F.items()}, SLIGHT),
            spread(fpeak("T_as"), {f"sliding {k}": v for k, v in M6_F.items()}, SLIGHT),
        ),
        also=("5.6",),
    ),
    Claim(
        "8.2-high-preyield-degrades",
        "8.2",
        "High pre-yield damping required for improving the force-tracking performance, "
        "however, causes degradation of the vibration transmission performance of both "
        '"inverse model"-based controllers.',
        "ACM frequency responses: mean T_as over 3-7 Hz higher at k_d = 2.5 than at k_d = 1, "
        "for inverse hi-lo (Fig 5.7) and sliding mode.",
        all_of(
            compare(
                fmean("T_as", 3.0, 7.0),
                {"inverse k_d = 2.5": INV_KD_F["k_d = 2.5"]},
                {"inverse k_d = 1": INV_KD_F["k_d = 1"]},
                ">",
            ),
            compare(
                fmean("T_as", 3.0, 7.0),
                {"sliding k_d = 2.5": SM_G_F["ACM k_d = 2.5"]},
                {"sliding k_d = 1": SM_ACM1_F},
                ">",
            ),
        ),
        also=("5.6",),
    ),
)


#: What no quarter-car simulation can test, with the reason: (section, what, why)
SKIPPED: tuple[tuple[str, str, str], ...] = (
    (
        "7.x, 8.2",
        "the HiL measurements: model validity against the rig, agreement of the "
        "'quarter-vehicle' model with the measured data (passive and skyhook hi-lo), the "
        "robustness to the load measured on the rig, deviations ascribed to the servo-hydraulic "
        "bandwidth",
        "hardware (Chapter 7): needs the rig's measurements",
    ),
    (
        "8.2",
        "the controller synthesis can be realized and tuned in a HiL environment",
        "hardware and workflow, not a response",
    ),
    (
        "8.2",
        "MR fluids offer variable damping with high bandwidth and minimal power; active "
        "suspensions are limited by power or bandwidth",
        "general background, not a result",
    ),
    (
        "8.2",
        "the measured F-v properties (low pre-yield damping, post-yield saturation, "
        "hysteresis depending on the field and the excitation)",
        "Chapter 2 measurements",
    ),
    (
        "8.2",
        "the generalized model characterizes the F-v properties accurately; the current "
        "function can be applied to other reported models",
        "model identification against measured data (Chapter 2), not a vehicle simulation",
    ),
    (
        "8.2, 5.6",
        "the hysteretic inverse model facilitates the implementation; the hi-lo "
        "controller is easy to implement with directly measurable variables",
        "implementation merit, not a response",
    ),
    (
        "6.5",
        "the skyhook controller 'poses a challenging task for measuring the sprung mass velocity'",
        "a sensing remark (hardware)",
    ),
    (
        "4.2",
        "hysteresis and force limiting 'may include limit cycle and larger steady-state "
        "error [70-76, 79]'",
        "a statement of the literature",
    ),
    (
        "4.3.1",
        "damping hysteresis 'tends to distort the phase relationship' of x_r and v_r",
        "an explanation of a mechanism, no measurable statement",
    ),
    ("8.3", "recommendations for future work", "not a result"),
)


_ROAD_SPEED = (
    "road presets: with the n^-1 slope of the model reference, section 8(c), the temporal "
    "road PSD is the same at both speeds, yet the model's DLC rises 1.13-1.15x from 50 to "
    "100 km/h (the dissertation: 1.01-1.03); a flatter slope would bring it down (w = 0.8: "
    "1.07)"
)
_SM_GAIN = (
    "not held for any admissible value of the law's unknowns: sliding mode's rebound current "
    "peaks at 0.48 A (the dissertation: 0.15 A) for every beta in 1.0-2.0 (and eps up to 5 "
    "m/s, phi 0): the peak is the inverse model's saturation where the hysteron force F_h "
    "changes sign early in rebound (C = |F_c| / (k_d |F_h|) unbounded as F_h -> 0 while the "
    "skyhook reference still asks for about 1 kN), so i_d = i_max M_p M_c, not the switching "
    "gain K (the errata page)"
)
_DTR_STATIC = (
    "our DTR over the sprung mass is the static-load change alone (141 kg g / 6406 N = "
    "0.216) for every controller: the dynamic peak tire force hardly changes with m_s in our "
    "model, while the dissertation's differ by controller (0.13-0.29)"
)

#: Claims known not to hold in our model (the integration test expects them to fail): id ->
#: suspected cause. Evaluated on main after the cycle-rms estimator and the (2.13) v_h
#: default (b7802c2), quick settings. "reading:" marks a result near our reading's
#: threshold; "road presets:" the random-road claims awaiting the new presets.
KNOWN: dict[str, str] = {
    "4.2-semi-active-hysteresis": "model: with the smooth CM/ADFG hi-lo modulation (xi_c = "
    "10, n = 2) the hysteretic model adds no transients (the share of a_s and a_u above 5 Hz "
    "is even lower); with on-off switching it does (4.2-onoff-hysteresis holds)",
    "4.3.1-policy-i-resonance": "model: policies II and III damp the body mode as well as I "
    "(peak T_as about 1.7-1.8 for I, II, III); the k_c = 10 relative-velocity laws reach "
    "0.29-0.36 A, close to policy I's 0.37 A",
    "4.3.1-dlc-i-iv": "model: policy IV's DLC is below II's and III's at only about a third "
    "of the frequencies (I's holds); IV's current stays low (0.22 A peak)",
    "4.3.1-policy-i-smooth": "model: policy I's current has the largest high-frequency share "
    "(0.22 against 0.10-0.17): with k_c |z_s'|^2 the current follows the body velocity, "
    "which carries the wheel-hop ripple",
    "4.3.1-ii-iii-oscillation": "model: the relative-velocity laws II and III give the "
    "smoothest wheel acceleration (share above 5 Hz 0.13 against I's 0.35)",
    "4.3.1-peak-current": "model: with k_c = 3, 10, 10, 300 the peak currents at 2.5 cm / "
    "1.5 Hz are 0.37, 0.36, 0.29, 0.22 A, not about 0.5 A; the stated rule needs k_c = 4.2, "
    "18, 26, 1100 in our model (about 0.5 A, 0.375 A or more, from 3.0, 11, 16, 710: "
    "the errata page); the other policy claims are checked at those gains too",
    "4.3.2-compression-peaks": "reading: ACM's compression peaks exceed SCM's as stated, but "
    "by 10-44 % (x_r 44 %), more than 'slightly' (25 %)",
    "4.3.2-acm-xs-ft": "model: ACM beats passive 0 A but not passive 0.1 A (x_s 56.9 against "
    "54.4 mm, F_T within 1 %)",
    "4.3.2-acm-majority": "reading: ACM's DLC is below passive 0.1 A's at exactly half of the "
    "grid, short of a majority",
    "4.3.2-road-dlc": "road presets: they are tuned to the DLCs of this very paragraph (ACM "
    "0.138, passive 0.1 A 0.111) and ours follow them (0.136 against 0.114), so the text's "
    "'lower with ACM' fails as the dissertation's own numbers do",
    "4.3.2-pulse-passive": "model: not held for any admissible decay window: the light passive "
    "damper's rms x_s after the pulse is 1.06 times the 0.1 A damper's from the pulse's end "
    "(0.80 s; 'considerably' needs 1/0.85 = 1.18) and 0.84 times it from 1 s (the 0.1 A "
    "damper's yield force leaves a slow creep); its peak |x_s| is only 3 % higher",
    "4.4.1-harmonic-insensitive": "reading: peak |a_s| varies by 12 % over m_s, just above "
    "'almost insensitive' (10 %); peak |x_s| by 9 %",
    "4.4.1-dlc-lighter-everywhere": "model: below the body resonance the heavier car has the "
    "larger DLC (the lighter car's is higher at about two thirds of the grid, from about 2 "
    "Hz up)",
    "4.4.2-road-current": "road presets / model: on the n^-1 presets the temporal road PSD "
    "is the same at both speeds, and skyhook ACM's current on the rough road stays near zero "
    "(std 2.1 mA at 50 km/h, 2.2 mA at 100 km/h), so its variation does not fall with speed",
    "4.4.3-tas-slight": "model: the peak T_as falls with the amplitude (2.41, 2.13, 1.99 for "
    "1.5, 2.5, 3.5 cm; the MR damper's friction-like force is relatively larger at small "
    "amplitude), where the dissertation sees a slight rise",
    "4.4.3-tau-dlc-tdr": "model: peak T_au and DLC rise with the amplitude as stated; peak "
    "T_dr does not (1.89, 1.60, 1.95)",
    "4.4.3-pulse-height": "model: the peak body displacement saturates (21.4 mm at 3.5 cm, "
    "21.2 mm at 5 cm); current, a_s and F_T rise as stated",
    "4.4.3-road-ride-comparable": "road presets: the presets share one spectral shape and "
    "differ only in level, so their PSDs differ by the same factor at every frequency; the "
    "dissertation's measured roads differ in shape",
    "4.5.1-pulse-rebound": "model: the rebound peak force over the pulse rises with k_c "
    "(1.5, 1.9, 2.3 kN for k_c = 0.5, 1.5, 3): the damper is not saturated in rebound at "
    "the 3.5 cm pulse",
    "4.6-skyhook-best-policy": "model: policy I has the lowest mean T_as and DLC but the "
    "policies II and III the lowest mean T_dr (0.77 against I's 0.90): I's wheel-hop stroke "
    "is larger (4.3.1-tdr-i-iv-wheel-hop)",
    "5.2-relative-velocity": "reading: peak |v_r| 0.62 m/s (mean models) and 0.70 m/s "
    "(hysteretic), each near the dissertation's 0.6 / 0.75, but 0.90 times apart, not "
    "'considerably' (0.85)",
    "5.2-tracking-speed": "model: the relative tracking error of inverse hi-lo at low speed "
    "(0.75) is under twice that at high speed (0.39); the high-speed error is larger than the "
    "dissertation suggests (saturation at i_max)",
    "5.2-acm-unsprung": "model: ACM does not lower the peak wheel acceleration of inverse "
    "hi-lo (17.2 against SCM's 16.0 m/s^2)",
    "5.2-hysteretic-current": "model: the hysteretic models' peak rebound current is only 4 % "
    "above the mean models' (0.448 against 0.429 A; both near i_max)",
    "5.2-mean-models-smooth": "model: with the mean damper and inverse the current is hardly "
    "smoother (share above 5 Hz 0.64 against 0.66) and v_r only 11 % lower",
    "5.4-pulse-current": _SM_GAIN + " (sliding mode spends 0.61 s above 0.1 A)",
    "5.5.1-frequency-mass": "model: the body-resonance DLC falls with m_s (0.52, 0.44, 0.37; "
    "DLC divides by the weight) where the dissertation sees a slight rise; T_au rises as "
    "stated",
    "5.5.2-road-dlc": _ROAD_SPEED,
    "5.5.3-frequency-amplitude": "model: peak T_au grows 23 % with the amplitude (not "
    "unaltered) and peak T_as is flat (1.90, 2.00, 1.98) rather than rising",
    "5.5.3-table": "model: SDR_s falls with the pulse height (0.86, 0.80, 0.69) where Table "
    "5.3 has it rising, and SAR_u / RDR vary by 28 % / 16 %, not under 3 %",
    "6.2-kd-smoother": _SM_GAIN + "; at k_d = 2.5 the current is no smoother either (share "
    "above 5 Hz 0.63 against 0.45 at beta = 1.335, 0.72-0.77 against 0.44 at beta 1.0-1.1) "
    "and the peak current stays at 0.5 A",
    "6.2-acm-tracking": "model: not held for any beta in 1.0-2.0: ACM leaves the compression "
    "current low (p = 0) where the sliding-mode target asks for force, so its tracking error "
    "(1.22 kN at beta = 1.335; 0.50-3.2 kN over beta 1.0-2.0) exceeds SCM's (776 N; "
    "418-2210 N); "
    "ACM's current is the smoother, as stated",
    "6.2-acm-vs-nominal-scm": "model: sliding mode SCM at k_d = 1 already has smaller peaks "
    "(x_s 34.9 mm, a_u 8.1 m/s^2) than ACM at k_d = 2.5 (45.2 mm, 12.6 m/s^2)",
    "6.2-frequency-kd": "model: in SCM, k_d = 2.5 lowers peak T_as by 7 % only, leaves T_dr "
    "and raises T_au (3.33 against 2.44); the mid-range rise holds",
    "6.3-current-levels": _SM_GAIN,
    "6.3-road-dlc": "model: on the PSD-level presets both k_d = 2.5 laws are below passive "
    "0 A (0.118 and 0.115 against 0.137) but sliding mode's DLC is 2 % above inverse hi-lo's "
    "(the dissertation's 0.112 is 1 % below its 0.113)",
    "6.4.1-harmonic-mass": _SM_GAIN + "; the current stays at the limit for every mass, so "
    "a_s, a_u, x_s do not fall with m_s",
    "6.4.1-frequency-mass": "model: peak T_as and T_dr are flat over m_s (spread 1-4 %), not "
    "rising, and peak T_au is flat; DLC falls as stated",
    "6.4.1-table": "model: not held for any admissible DTR reading: SDR_s, SAR_s, SDR_u, "
    "SAR_u and RDR hold; the DTR at 422 kg is 0.216 (peak tire force ratio) or 0.218 ((3.44) "
    "as printed) against 0.16 (30 %: at most 0.208); at 703 kg the ratio reading gives 0.139 "
    "against 0.13. The peak tire force is reached in the passive compression phase of the "
    "pulse, the same for both inverse-model laws, so no sliding-mode parameter moves it",
    "6.4.1-more-robust-than-hilo": "model: the peak body accelerations over the pulse are "
    "reached in the passive compression phase, identical for both inverse-model laws, so "
    "their SAR_s spreads tie (0.451)",
    "6.4.3-table": "model: SDR_s falls with the pulse height (0.69, 0.60, 0.55) where Table "
    "6.3 has it rising",
    "6.4-nominal-rows": "the dissertation prints three different rows for one case; ours "
    "also differ in level: SDR_s 0.60 (0.63-0.67x the printed values) and SAR_u 1.82 "
    "(1.4-1.6x; after-onset SAR denominator); SAR_s, SDR_u and RDR agree within 25 %",
    "6.5-rattle-space": "model: skyhook hi-lo ACM's peak T_dr (1.58) exceeds passive 0.1 A's "
    "(1.53); the inverse-model laws' are lower",
    "6.5-mass-dtr": "model: not held for any admissible DTR reading: skyhook hi-lo has the "
    "smallest largest DTR over m_s under each (peak tire force ratio 0.200 against 0.216 for "
    "both inverse-model laws; (3.44) as printed 0.216 against 0.218); the inverse-model laws "
    "tie, their peak tire force being reached in the passive compression phase",
    "6.5-road-dlc-mass": "the dissertation contradicts itself (4.4.1-road-dlc-heavier) and "
    "the claim is not held for either DLC reading: DLC(703 kg) / DLC(422 kg) is 0.60-0.65 over "
    "each car's own load and 0.93-1.01 over the nominal load, against the stated 1.54-1.61",
    "6.5-speed-robust": "model: inverse hi-lo, not sliding mode, has the smallest SDR_s change "
    "(29 % against 36 %); the 100 km/h DTRs of the two inverse-model laws tie (0.348)",
    "6.6-load-sensitivity": "model: the SAR_s spreads of the two inverse-model laws tie "
    "(0.451, peak in the passive compression phase), skyhook's is 0.465",
    "8.2-skyhook-vs-inverse": "model: skyhook hi-lo ACM has the lowest mean DLC, but sliding "
    "mode a marginally lower mean T_as (0.798 against 0.804) and both inverse-model laws a "
    "lower mean T_dr (0.62-0.64 against 0.96: skyhook's wheel-hop stroke)",
}

_unknown = sorted(set(KNOWN) - {c.id for c in _CLAIMS})
if _unknown:  # pragma: no cover - caught by the unit tests at once
    raise ValueError(f"KNOWN names claims that do not exist: {', '.join(_unknown)}")
CLAIMS: tuple[Claim, ...] = tuple(replace(c, known=KNOWN.get(c.id, "")) for c in _CLAIMS)
