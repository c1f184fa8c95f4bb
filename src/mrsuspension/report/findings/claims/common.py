"""What the chapters' claims share: the runs, named once, and the shared readings
(unknown parameters, windows, measures) of :mod:`mrsuspension.report.findings.claims`."""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import numpy as np

from mrsuspension.control import CONTROLLERS, HiLo, SlidingMode, law_options
from mrsuspension.control.shaped import ADFG_CENTRE_IDENTIFIED
from mrsuspension.control.sliding import BETA_COVERING
from mrsuspension.excitation.road import PRESET_IDENTIFIED
from mrsuspension.report.families import merge_tables
from mrsuspension.report.findings.checks import (
    ABOUT,
    DTR_READINGS,
    ROAD_DLC,
    ROAD_DLC_NOMINAL,
    SHOCK,
    Check,
    Payload,
    Run,
    Verdict,
    about,
    all_of,
    band_amplitude,
    compare,
    dtr_of,
    dtr_values,
    fig,
    figs,
    mean_of,
    monotone,
    peak,
    phase_peak,
    pulse_end,
    ratio,
    readings,
    relative_tracking,
    residual,
    retabled,
    rows,
    spread,
)


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


#: The admissible range of the control unknowns swept for the claims no reading makes hold
#: (issue 30, group 5): the ADFG centre over [0, 0.5] (0.5 the default; 0.1 identified; 0
#: section 3.2's) and sliding mode's beta over 1.0-2.0 (:data:`_BETAS`)
_ADFG_SWEEP: tuple[float, ...] = (0.0, ADFG_CENTRE_IDENTIFIED, 0.25)


def _laws(check: Check) -> set[tuple[str, str]]:
    """(law, mode) of every run of ``check``."""
    out = set()
    for run in check.runs.values():
        controller = run.scenario.get("controller", {})
        out.add((str(controller.get("law", "passive")), str(controller.get("mode", ""))))
    return out


def _swept(check: Check) -> Check:
    """A check at the defaults (kept) and over the admissible range of every control unknown
    its runs involve: the ADFG centre (:data:`_ADFG_SWEEP`, in every ADFG-shaped law, when
    a run is not SCM, where ``p = 1`` makes the centre moot) and sliding mode's beta
    (:data:`_BETAS`). With no unknown involved the check is its only reading: a failure is
    then "not held for any admissible value" (every value it uses is given)."""
    laws = _laws(check)
    cases: list[tuple[str, Check]] = []
    if any(law in _ADFG_LAWS and mode != "SCM" for law, mode in laws):
        for c in _ADFG_SWEEP:
            changed = check
            for law in _ADFG_LAWS:
                changed = retabled(changed, f"adfg {c:g}", law, controller={"adfg_centre": c})
            cases.append((f"ADFG centre {c:g}", changed))
    if any(law == "sliding-mode" for law, _mode in laws):
        cases += [
            (
                f"beta = {b:g}",
                retabled(check, f"beta {b:g}", "sliding-mode", controller={"beta": b}),
            )
            for b in _BETAS
        ]
    kept = (
        "the defaults (ADFG centre 0.5, beta 1.25)"
        if cases
        else "every value the check uses is given (no unknown parameter involved)"
    )
    return readings((kept, check), *cases)


#: The road spectra: the model reference's presets (n^-1 over 0.011-2 cycle/m, differing in
#: level only; section 8(c)), kept; and the spectra identified from the dissertation's road
#: numbers (slope, level and band of each preset fitted jointly to its DLCs at 50 and 100
#: km/h, the rough/medium-rough PSD comparisons and the peak elevations:
#: ``excitation.road.PRESET_IDENTIFIED``, docs/errata.md "Road spectra identified")
_ROAD_READINGS: tuple[str, str] = (
    "the model reference's presets (n^-1, 0.011-2 cycle/m, level only)",
    "the road spectra identified from the dissertation's road numbers ("
    + "; ".join(f"{n} {PRESET_IDENTIFIED[n].spectrum.label()}" for n in ("rough", "medium-rough"))
    + ": the errata page)",
)


#: The other road spectra as good by the count (17 of the 21 random-road claims on one
#: spectrum, as the identified ones): a rough road white in displacement (n^-0, at the
#: edge of the fit's grid) and the medium-rough road's shape at a higher level. It holds
#: 4.4.3-road-ride-comparable and loses 4.4.2-road-dlc (DLC 100/50 km/h 0.89), where the
#: identified spectra do the opposite (docs/errata.md, "Road spectra identified")
ROAD_WHITE_ROUGH: dict[str, dict[str, Any]] = {
    "rough": {"level": 4.15e-6, "waviness": 0.0, "band": [0.011, 1.4]},
    "medium-rough": {"level": 5.4e-6, "waviness": 0.5, "band": [0.05, 0.7]},
}


def on_roads(check: Check, tag: str, spectra: Mapping[str, Mapping[str, Any]]) -> Check:
    """``check`` with each random-road run on its preset's spectrum changed by
    ``spectra[preset]`` (road options: ``spectrum``, ``level``, ``waviness``, ``band``),
    its label tagged ``[tag]`` (as :func:`~mrsuspension.report.findings.checks.retabled`)."""

    def changed(run: Run) -> Run:
        profile = run.unit(quick=True).scenario["excitation"].get("profile")
        if run.kind != "psd" or profile not in spectra:
            return run
        road = {**spectra[profile], "profile": profile}
        return Run.of("psd", merge_tables(run.scenario, {"excitation": road}))

    runs = {f"{k} [{tag}]": changed(r) for k, r in check.runs.items()}

    def fn(p: Mapping[str, Payload]) -> Verdict:
        return check.fn({k: p[f"{k} [{tag}]"] for k in check.runs})

    return Check(runs, fn)


def _road_sensitivity(check: Check, *, white_rough: bool = False) -> Check:
    """A random-road check on the model reference's presets (kept), on the identified
    spectra and (``white_rough``) on :data:`ROAD_WHITE_ROUGH` (the road runs only)."""
    identified = {name: {"spectrum": "identified"} for name in PRESET_IDENTIFIED}
    cases = [
        (_ROAD_READINGS[0], check),
        (_ROAD_READINGS[1], on_roads(check, "identified roads", identified)),
    ]
    if white_rough:
        cases.append(
            (
                "a rough road white in displacement (Gd(n0) 4.15e-06 m^3, n^-0, 0.011-1.4 "
                "cycle/m; medium-rough 5.4e-06 m^3, n^-0.5, 0.05-0.7 cycle/m: as good by the "
                "count as the identified spectra, but its DLC falls with speed, 4.4.2-road-dlc: "
                "the errata page)",
                on_roads(check, "white rough road", ROAD_WHITE_ROUGH),
            )
        )
    return readings(*cases)


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


#: The sensitivity check of the claims of ``claims.SWEPT_IN_FULL`` (frequency responses),
#: whose sweep costs too much for quick mode (58 runs more, 130 s of CPU at the full step):
#: the full build runs it
_SWEPT_IN_FULL = (
    "; the full build checks it over the ADFG centre 0-0.5 and beta 1-2 where its laws "
    "use them (quick mode keeps the default reading): not held for any of them (the errata "
    "page)"
)
_SM_GAIN = (
    "not held for any admissible value of the law's unknowns: sliding mode's rebound current "
    "peaks at 0.48 A (the dissertation: 0.15 A) for every beta in 1.0-2.0 (and eps up to 5 "
    "m/s, phi 0): the peak is the inverse model's saturation where the hysteron force F_h "
    "changes sign early in rebound (C = |F_c| / (k_d |F_h|) unbounded as F_h -> 0 while the "
    "sliding-mode target is 2-3.4 kN), so i_d = i_max M_p M_c, not the switching gain K; "
    "checked term by term against (2.3)-(3.35), and no reading of the inverse (2.17), the "
    "sign of K or the CM units moves it below 0.46 A (the errata page)"
)
_DTR_STATIC = (
    "our DTR over the sprung mass is the static-load change alone (141 kg g / 6406 N = "
    "0.216) for every controller: the dynamic peak tire force hardly changes with m_s in our "
    "model, while the dissertation's differ by controller (0.13-0.29)"
)
