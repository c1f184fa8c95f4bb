"""Chapter 5 figures: the inverse-model hi-lo controller (law ``"inverse-hilo"``).

* Fig 5.5: hysteresis and force tracking: time histories of the damper force F_d against
  the target F* = k_s x_d with the mean (``hysteresis = false``) and the hysteretic damper
  model, at the nominal force gain k_d = 1 and at k_d = 2.5 (ACM, 2.5 cm at 1.5 Hz). In our
  model the inverse model always follows the damper model (mean damper with mean inverse,
  hysteretic with hysteretic; the dissertation's mixed case of Fig 5.2 is not offered).
* Fig 5.6: the force-tracking error rms(|F_d| - |F*|) while z_c < 0 against the force gain
  k_d = 1, 1.5, 2, 2.5 (section 5.3), SCM and ACM, with the ACM time histories.
* Fig 5.9: frequency responses of inverse-model hi-lo SCM and ACM (k_d = 2.5) against the
  passive damper at 0 and 0.1 A (nominal damper, k_d = 1).

The time-history figures run the engine directly (:func:`~mrsuspension.engine.run_many`);
the frequency responses run a :class:`~mrsuspension.studies.Study`. The inverse-model laws
use the default (symmetric hysteretic) damper with its force gain k_d; a gain of 2.5 makes
the pre-yield slope 2.5 times steeper, so the step is 0.25 ms in quick mode (RK4 limit about
0.27 ms) and the spec's 0.1 ms otherwise.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import Any

import numpy as np

from mrsuspension.engine.result import SimulationResult
from mrsuspension.engine.simulate import run_many
from mrsuspension.measures import force_tracking_error
from mrsuspension.report.ch2 import _subplots
from mrsuspension.report.ch4 import _plot, _run, sweep_study
from mrsuspension.report.html import FigureRecord
from mrsuspension.scenario import Scenario

__all__ = [
    "CHAPTER_5_FIGURES",
    "FORCE_GAINS",
    "HARMONIC",
    "error_figure",
    "fig_5_5",
    "fig_5_6",
    "fig_5_9",
    "force_tracking_errors",
    "harmonic_runs",
    "response_cases",
    "response_figure",
    "step",
    "tracking_error",
    "tracking_figure",
]

#: The section 5.3 force gains k_d (1 = the nominal damper)
FORCE_GAINS: tuple[float, ...] = (1.0, 1.5, 2.0, 2.5)
#: The chapter's harmonic excitation: 2.5 cm at 1.5 Hz
HARMONIC: dict[str, Any] = {"kind": "harmonic", "frequency": 1.5, "amplitude": 0.025}
#: Length of the time-history runs [s] and the start of the measured (steady) window
DURATION = 8.0
STEADY_FROM = 4.0
#: The time window shown in the time-history panels [s]
SHOWN = (6.0, 7.4)


def step(quick: bool) -> float:
    """Fixed step [s]: 0.25 ms in quick mode (stable up to k_d = 2.5), else 0.1 ms."""
    return 2.5e-4 if quick else 1e-4


def harmonic_runs(
    cases: Sequence[dict[str, Any]], quick: bool, excitation: dict[str, Any] | None = None
) -> list[SimulationResult]:
    """Run scenario tables (``damper``, ``controller``, ``vehicle``) under a harmonic input.

    Parameters
    ----------
    cases : sequence of dict
        Scenario tables of each run, without ``excitation``/``simulation``.
    quick : bool
        Step size choice (see :func:`step`).
    excitation : dict, optional
        Excitation table; default :data:`HARMONIC`.

    Returns
    -------
    list of SimulationResult
        Time histories sampled at 1 kHz, in the order given.
    """
    dt = step(quick)
    sims = []
    for case in cases:
        data = {**case, "excitation": dict(excitation or HARMONIC), "simulation": {"dt": dt}}
        sims.extend(Scenario.from_dict(data).simulations())
    return run_many(sims, duration=DURATION, dt=dt, output_rate=1000.0)


def _steady(result: SimulationResult) -> np.ndarray:
    return np.asarray(result.time >= STEADY_FROM)


def tracking_error(result: SimulationResult) -> float:
    """rms(|F_d| - |F*|) while z_c < 0 over the steady window [N]."""
    sel = _steady(result)
    return float(force_tracking_error(result.F_d[sel], result.F_target[sel], result.z_c[sel]))


def force_tracking_errors(
    law: str, quick: bool, modes: Sequence[str] = ("ACM", "SCM")
) -> dict[str, list[float]]:
    """Force-tracking error [N] of ``law`` for each k_d of :data:`FORCE_GAINS`, by mode.

    Parameters
    ----------
    law : str
        ``"inverse-hilo"`` or ``"sliding-mode"``.
    quick : bool
        Step size choice (see :func:`step`).
    modes : sequence of str
        Control modes to run.

    Returns
    -------
    dict
        ``{mode: [error at k_d = 1, 1.5, 2, 2.5]}``.
    """
    cases = [
        {"damper": {"force_gain": kd}, "controller": {"law": law, "mode": mode}}
        for mode in modes
        for kd in FORCE_GAINS
    ]
    errors = [tracking_error(r) for r in harmonic_runs(cases, quick)]
    n = len(FORCE_GAINS)
    return {mode: errors[k * n : (k + 1) * n] for k, mode in enumerate(modes)}


def _window(result: SimulationResult) -> np.ndarray:
    return np.asarray((result.time >= SHOWN[0]) & (result.time <= SHOWN[1]))


def tracking_figure(law: str, quick: bool, target: str) -> tuple[Any, dict[str, Any]]:
    """2 x 2 panels of F_d and F* (rows: mean / hysteretic model; columns: k_d = 1 / 2.5).

    Parameters
    ----------
    law : str
        Inverse-model law.
    quick : bool
        Step size choice.
    target : str
        Label of the target force (``F*`` or ``F_c``).

    Returns
    -------
    tuple
        The figure and the data for its record.
    """
    grid = [(hyst, kd) for hyst in (False, True) for kd in (1.0, 2.5)]
    cases = [
        {
            "damper": {"hysteresis": hyst, "force_gain": kd},
            "controller": {"law": law, "mode": "ACM"},
        }
        for hyst, kd in grid
    ]
    results = harmonic_runs(cases, quick)
    fig, axes = _subplots(2, 2)
    data: dict[str, Any] = {}
    for ax, (hyst, kd), r in zip(axes.ravel(), grid, results, strict=True):
        w = _window(r)
        t = r.time[w]
        model = "hysteretic" if hyst else "mean"
        ax.plot(t, r.F_d[w], label="$F_d$")
        ax.plot(t, r.F_target[w], "--", label=target)
        high = r.z_c[w] < 0
        ax.fill_between(
            t,
            0,
            1,
            where=high,
            transform=ax.get_xaxis_transform(),
            alpha=0.12,
            color="k",
            label="$z_c < 0$",
        )
        ax.set_title(f"{model} damper + inverse, $k_d$ = {kd:g}", fontsize=9)
        ax.set_xlabel("time [s]")
        ax.set_ylabel("force [N]")
        ax.grid(True, alpha=0.3)
        key = f"{model} k_d={kd:g}"
        data[f"force-tracking error {key} [N]"] = tracking_error(r)
        data[f"peak |F_d| {key} [N]"] = float(np.max(np.abs(r.F_d[_steady(r)])))
        data[f"mean current {key} [A]"] = float(np.mean(r.i_d[_steady(r)]))
        data[f"time {key} [s]"] = [float(v) for v in t[::10]]
        data[f"F_d {key} [N]"] = [float(v) for v in r.F_d[w][::10]]
        data[f"target {key} [N]"] = [float(v) for v in r.F_target[w][::10]]
    axes[0, 0].legend(fontsize=8)
    return fig, data


def fig_5_5(quick: bool = False) -> FigureRecord:
    """Hysteresis effect on force tracking of inverse-model hi-lo (mean vs hysteretic)."""
    fig, data = tracking_figure("inverse-hilo", quick, "$F^* = k_s x_d$")
    return FigureRecord(
        number="5.5",
        title="Force tracking of inverse-model hi-lo ACM, mean and hysteretic models",
        caption=(
            "Damper force F_d against the target F* = k_s x_d (shaded: z_c = F_h k_s x_d < 0, "
            "tracking phase) under 2.5 cm harmonic excitation at 1.5 Hz; inverse-model hi-lo "
            "ACM (p = 0, xi = 10, p_c = 0, xi_c = 50). Top: mean damper model "
            "(damper.hysteresis = false, v_h = 0) with the mean inverse; bottom: hysteretic "
            "damper with the hysteretic inverse (the counterparts of Figs 5.1, 5.3 and 5.5; "
            "the mixed hysteretic-damper/mean-inverse case of Fig 5.2 is not available). "
            "Left k_d = 1 (nominal damper), right k_d = 2.5 (damper.force_gain). Tracking is "
            "poor at low velocity, where the pre-yield force is small, as in the dissertation."
        ),
        figure=fig,
        data=data,
    )


def error_figure(law: str, quick: bool) -> tuple[Any, dict[str, Any]]:
    """Force-tracking error against k_d (SCM, ACM) and ACM F_d histories per k_d.

    Parameters
    ----------
    law : str
        Inverse-model law.
    quick : bool
        Step size choice.

    Returns
    -------
    tuple
        The figure and the data for its record.
    """
    errors = force_tracking_errors(law, quick)
    runs = harmonic_runs(
        [
            {"damper": {"force_gain": kd}, "controller": {"law": law, "mode": "ACM"}}
            for kd in FORCE_GAINS
        ],
        quick,
    )
    fig, grid = _subplots(1, 3)
    axes = grid[0]
    data: dict[str, Any] = {"k_d": list(FORCE_GAINS)}
    for mode, values in errors.items():
        axes[0].plot(FORCE_GAINS, values, marker="o", label=mode)
        data[f"force-tracking error {mode} [N]"] = values
    axes[0].set_xlabel("force gain $k_d$")
    axes[0].set_ylabel("rms(|F_d| - |F*|) while $z_c$ < 0 [N]")
    axes[0].legend(fontsize=8)
    axes[0].grid(True, alpha=0.3)
    for kd, r in zip(FORCE_GAINS, runs, strict=True):
        w = _window(r)
        axes[1].plot(r.time[w], r.F_d[w], label=f"$k_d$ = {kd:g}")
        axes[2].plot(r.time[w], r.i_d[w], label=f"$k_d$ = {kd:g}")
        data[f"mean current ACM k_d={kd:g} [A]"] = float(np.mean(r.i_d[_steady(r)]))
        data[f"rms body acceleration ACM k_d={kd:g} [m/s^2]"] = float(
            np.sqrt(np.mean(r.z_s_ddot[_steady(r)] ** 2))
        )
    axes[1].set_ylabel("$F_d$ [N] (ACM)")
    axes[2].set_ylabel("$i_d$ [A] (ACM)")
    for ax in axes[1:]:
        ax.set_xlabel("time [s]")
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=8)
    return fig, data


def fig_5_6(quick: bool = False) -> FigureRecord:
    """Force-tracking error of inverse-model hi-lo against the force gain k_d."""
    fig, data = error_figure("inverse-hilo", quick)
    return FigureRecord(
        number="5.6",
        title="Inverse-model hi-lo: force-tracking error against the force gain k_d",
        caption=(
            "Left: rms(|F_d| - |F*|) over the samples with z_c < 0 in the steady state "
            "(mrsuspension.measures.force_tracking_error on F_d, F_target, z_c), SCM and ACM, "
            "2.5 cm at 1.5 Hz; middle and right: ACM damper force and drive current. A "
            "larger force gain on the hysteron force (damper.force_gain) lowers the drive "
            "current and the tracking error (section 5.3; the dissertation uses k_d = 1, 2, "
            "2.5, we add 1.5)."
        ),
        figure=fig,
        data=data,
    )


def response_cases(law: str) -> dict[str, dict[str, Any]]:
    """Passive 0 / 0.1 A (k_d = 1) and ``law`` in SCM and ACM (k_d = 2.5), as study cases.

    Parameters
    ----------
    law : str
        Inverse-model law.

    Returns
    -------
    dict
        Study ``[cases]`` values by label.
    """
    cases: dict[str, dict[str, Any]] = {
        f"passive {i:g} A": {"controller": {"law": "passive", "current": i}} for i in (0.0, 0.1)
    }
    for mode in ("SCM", "ACM"):
        cases[f"{law} {mode} k_d=2.5"] = {
            "controller": {"law": law, "mode": mode},
            "damper": {"force_gain": 2.5},
        }
    return cases


def response_figure(law: str, quick: bool, name: str) -> tuple[Any, dict[str, Any]]:
    """Frequency responses (T_as, T_au, T_dr, DLC) of :func:`response_cases`.

    Parameters
    ----------
    law : str
        Inverse-model law.
    quick : bool
        Coarse grid (10 frequencies) and a 0.25 ms step.
    name : str
        Study name.

    Returns
    -------
    tuple
        The figure and the data for its record.
    """
    cases = response_cases(law)
    study = sweep_study(quick, name, simulation={"dt": step(quick)}, cases={"damping": cases})
    return _plot(_run(study), "damping", {k: k for k in cases})


def fig_5_9(quick: bool = False) -> FigureRecord:
    """Frequency responses of inverse-model hi-lo SCM/ACM against passive damping."""
    fig, data = response_figure("inverse-hilo", quick, "fig-5.9-inverse-hilo")
    return FigureRecord(
        number="5.9",
        title="Frequency responses: passive (0, 0.1 A), inverse-model hi-lo SCM/ACM",
        caption=(
            "Two-stage swept excitation a = 2.5 cm, f_T = 2.1 Hz, 0.5-15 Hz. Passive damper at "
            "0 and 0.1 A on the nominal damper (k_d = 1); inverse-model hi-lo (p_c = 0, "
            "xi_c = 50, xi = 10) with damper.force_gain = 2.5 in SCM (p = 1) and ACM (p = 0). "
            "Study: [cases.damping] over controller.law/mode/current and damper.force_gain. "
            "Covers the curves of Figs 5.7 (k_d = 2.5) and 5.9."
        ),
        figure=fig,
        data=data,
    )


#: The chapter's figure builders, in report order (each takes ``quick``).
CHAPTER_5_FIGURES: tuple[Callable[[bool], FigureRecord], ...] = (fig_5_5, fig_5_6, fig_5_9)
