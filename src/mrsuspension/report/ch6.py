"""Chapter 6 figures: the inverse-model sliding-mode controller (law ``"sliding-mode"``),
and the section 6.5 comparison of the controllers as a table.

* Fig 6.2: force tracking of F_d against the target F_c with the mean and the hysteretic
  damper model, k_d = 1 and 2.5 (ACM, 2.5 cm at 1.5 Hz; counterparts of Figs 6.1-6.4).
* Fig 6.5: force-tracking error against k_d = 1, 1.5, 2, 2.5 (SCM, ACM), ACM histories.
* Fig 6.8: frequency responses of sliding mode SCM and ACM (k_d = 2.5) against passive
  damping at 0 and 0.1 A (also the k_d = 2.5 curves of Fig 6.6).
* Fig 6.12: robustness to the sprung mass (422, 563, 703 kg), sliding mode ACM, k_d = 2.5.
* :func:`comparison_table`: passive 0 A, skyhook hi-lo ACM, inverse-model hi-lo ACM and
  sliding mode ACM under a 1.5 Hz / 2.5 cm harmonic, a 3.5 cm rounded pulse and the
  ``rough`` road preset.

Settings and step sizes as in :mod:`mrsuspension.report.ch5`.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np

from mrsuspension.engine.result import SimulationResult
from mrsuspension.engine.simulate import run_many
from mrsuspension.report.ch4 import SKYHOOK_ACM, _plot, _run, sweep_study
from mrsuspension.report.ch5 import (
    HARMONIC,
    STEADY_FROM,
    error_figure,
    response_figure,
    step,
    tracking_figure,
)
from mrsuspension.report.html import FigureRecord
from mrsuspension.scenario import Scenario

__all__ = [
    "CHAPTER_6_FIGURES",
    "COMPARISON_CONTROLLERS",
    "COMPARISON_EXCITATIONS",
    "comparison_table",
    "fig_6_2",
    "fig_6_5",
    "fig_6_8",
    "fig_6_12",
]

#: Section 6.5 controllers (ACM; the inverse-model laws with k_d = 2.5)
COMPARISON_CONTROLLERS: dict[str, dict[str, Any]] = {
    "passive 0 A": {"controller": {"law": "passive", "current": 0.0}},
    "skyhook hi-lo ACM (k_c = 3)": {"controller": dict(SKYHOOK_ACM)},
    "inverse-model hi-lo ACM (k_d = 2.5)": {
        "controller": {"law": "inverse-hilo", "mode": "ACM"},
        "damper": {"force_gain": 2.5},
    },
    "sliding mode ACM (k_d = 2.5)": {
        "controller": {"law": "sliding-mode", "mode": "ACM"},
        "damper": {"force_gain": 2.5},
    },
}
#: Section 6.5 excitations with the run length [s] and the start of the measured window [s]
COMPARISON_EXCITATIONS: dict[str, tuple[dict[str, Any], float, float]] = {
    "harmonic 1.5 Hz, 2.5 cm": (dict(HARMONIC), 8.0, STEADY_FROM),
    "rounded pulse 3.5 cm (mu = 3, 50 km/h)": (
        {"kind": "pulse", "amplitude": 0.035, "severity": 3.0, "speed": 50.0},
        3.0,
        0.0,
    ),
    "rough road, 50 km/h": ({"kind": "road", "profile": "rough", "speed": 50.0}, 0.0, 0.0),
}


def fig_6_2(quick: bool = False) -> FigureRecord:
    """Hysteresis effect on force tracking of sliding mode (mean vs hysteretic)."""
    fig, data = tracking_figure("sliding-mode", quick, "$F_c$")
    return FigureRecord(
        number="6.2",
        title="Force tracking of sliding mode ACM, mean and hysteretic models",
        caption=(
            "Damper force F_d against the sliding-mode target F_c (shaded: z_c = -F_h F_c < 0, "
            "tracking phase), 2.5 cm harmonic excitation at 1.5 Hz; sliding mode ACM "
            "(lambda = 0.5, eps = 0.05, phi = 1.6, beta = 1.25, c_s = 6750, c_0 = 2500, "
            "p_c = 0, xi_c = 150, xi = 30). Top: mean damper model with the mean inverse; "
            "bottom: hysteretic damper with the hysteretic inverse (counterparts of Figs "
            "6.1-6.4; the dissertation's hysteretic-damper/mean-inverse case is not "
            "available). Left k_d = 1, right k_d = 2.5."
        ),
        figure=fig,
        data=data,
    )


def fig_6_5(quick: bool = False) -> FigureRecord:
    """Force-tracking error of sliding mode against the force gain k_d."""
    fig, data = error_figure("sliding-mode", quick)
    return FigureRecord(
        number="6.5",
        title="Sliding mode: force-tracking error against the force gain k_d",
        caption=(
            "Left: rms(|F_d| - |F_c|) over the samples with z_c < 0 in the steady state, "
            "SCM and ACM, 2.5 cm at 1.5 Hz; middle and right: ACM damper force and drive "
            "current. The dissertation compares ACM k_d = 2.5 with SCM k_d = 1 and 2.5."
        ),
        figure=fig,
        data=data,
    )


def fig_6_8(quick: bool = False) -> FigureRecord:
    """Frequency responses of sliding mode SCM/ACM against passive damping."""
    fig, data = response_figure("sliding-mode", quick, "fig-6.8-sliding-mode")
    return FigureRecord(
        number="6.8",
        title="Frequency responses: passive (0, 0.1 A), sliding mode SCM/ACM",
        caption=(
            "Two-stage swept excitation a = 2.5 cm, f_T = 2.1 Hz, 0.5-15 Hz. Passive damper at "
            "0 and 0.1 A on the nominal damper (k_d = 1); sliding mode with "
            "damper.force_gain = 2.5 in SCM (p = 1) and ACM (p = 0). Covers the k_d = 2.5 "
            "curves of Fig 6.6 and Fig 6.8."
        ),
        figure=fig,
        data=data,
    )


def fig_6_12(quick: bool = False) -> FigureRecord:
    """Sprung-mass variation (422, 563, 703 kg) with sliding mode ACM."""
    masses = (422.0, 563.0, 703.0)
    study = sweep_study(
        quick,
        "fig-6.12-sprung-mass",
        simulation={"dt": step(quick)},
        controller={"law": "sliding-mode", "mode": "ACM"},
        damper={"force_gain": 2.5},
        grid={"vehicle.sprung_mass": list(masses)},
    )
    result = _run(study)
    fig, data = _plot(result, "vehicle.sprung_mass", {m: f"m_s = {m:g} kg" for m in masses})
    peaks = [data[f"peak T_as m_s = {m:g} kg"] for m in masses]
    data["spread of peak T_as over the masses [%]"] = 100.0 * (max(peaks) - min(peaks)) / peaks[1]
    return FigureRecord(
        number="6.12",
        title="Sprung-mass variation, sliding mode ACM (frequency responses)",
        caption=(
            "m_s = 422, 563, 703 kg (nominal +-25 %) with the controller's nominal mass "
            "m_s0 = 563 kg and beta = 1.25; sliding mode ACM, k_d = 2.5; two-stage swept "
            "excitation a = 2.5 cm. The record gives the spread of the body-resonance peak of "
            "T_as over the three masses (section 6.5: the sliding-mode controller is the "
            "most robust to the load)."
        ),
        figure=fig,
        data=data,
    )


def _row_measures(result: SimulationResult, start: float) -> dict[str, float]:
    sel = np.asarray(result.time >= start)
    acc = result.z_s_ddot[sel]
    stroke = result.x_d[sel]
    veh = result.scenario.get("vehicle", {})
    load = (veh.get("sprung_mass", 563.0) + veh.get("unsprung_mass", 90.0)) * 9.81
    return {
        "RMS a_s [m/s^2]": float(np.sqrt(np.mean(acc**2))),
        "peak |a_s| [m/s^2]": float(np.max(np.abs(acc))),
        "DLC": float(np.std(result.F_T[sel]) / load),
        "RMS stroke [mm]": 1e3 * float(np.sqrt(np.mean((stroke - np.mean(stroke)) ** 2))),
        "peak |stroke| [mm]": 1e3 * float(np.max(np.abs(stroke))),
        "mean current [A]": float(np.mean(result.i_d[sel])),
    }


def comparison_table(quick: bool = False) -> list[dict[str, Any]]:
    """Section 6.5: the controllers compared under harmonic, pulse and road excitation.

    Parameters
    ----------
    quick : bool
        0.25 ms step, else 0.1 ms.

    Returns
    -------
    list of dict
        One row per excitation and controller: RMS and peak body acceleration, DLC
        (std of the tire force over the static load), RMS and peak stroke, mean current.
        Harmonic rows are measured over the steady state (t >= 4 s), pulse and road rows
        over the whole record.
    """
    dt = step(quick)
    sims = []
    runs: list[tuple[str, str, float, float]] = []
    for exc_name, (exc, duration, start) in COMPARISON_EXCITATIONS.items():
        for ctrl_name, tables in COMPARISON_CONTROLLERS.items():
            data = {**tables, "excitation": dict(exc), "simulation": {"dt": dt}}
            scenario = Scenario.from_dict(data)
            sims.extend(scenario.simulations())
            length = duration or float(scenario.excitations[0].duration)
            runs.append((exc_name, ctrl_name, length, start))
    results = []
    # run_many takes one duration per call: group by excitation
    for exc_name in COMPARISON_EXCITATIONS:
        idx = [k for k, r in enumerate(runs) if r[0] == exc_name]
        results.extend(
            run_many([sims[k] for k in idx], duration=runs[idx[0]][2], dt=dt, output_rate=1000.0)
        )
    rows = []
    for (exc_name, ctrl_name, _length, start), result in zip(runs, results, strict=True):
        rows.append(
            {"excitation": exc_name, "controller": ctrl_name, **_row_measures(result, start)}
        )
    return rows


#: The chapter's figure builders, in report order (each takes ``quick``).
CHAPTER_6_FIGURES: tuple[Callable[[bool], FigureRecord], ...] = (
    fig_6_2,
    fig_6_5,
    fig_6_8,
    fig_6_12,
)
