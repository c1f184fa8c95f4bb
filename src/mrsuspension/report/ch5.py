"""Chapter 5: the inverse-model hi-lo controller (law ``"inverse-hilo"``).

:data:`FIGURES` lists Figs 5.1-5.21 as figure families
(:class:`~mrsuspension.report.families.FigureSpec`) and :data:`TABLES` the shock Tables
5.1-5.3 with the dissertation's numbers. Beside them, the special figure 5.6b (below) plots
the force-tracking error against k_d. In our model the inverse model always follows the
damper model unless the controller asks for the mean one (``controller.inverse = "mean"``):
Figs 5.2 and 5.5 use that for the dissertation's mixed case (hysteretic damper, mean
inverse). The helpers:

* :func:`tracking_figure`: F_d against the target F* = k_s x_d, mean and hysteretic model,
  k_d = 1 and 2.5 (ACM, 2.5 cm at 1.5 Hz).
* Fig 5.6b: the force-tracking error rms(|F_d| - |F*|) while z_c < 0 against the force gain
  k_d = 1, 1.5, 2, 2.5 (section 5.3), SCM and ACM, with the ACM time histories.
* :func:`response_figure`: frequency responses of an inverse-model law in SCM and ACM
  (k_d = 2.5) against the passive damper at 0 and 0.1 A (nominal damper, k_d = 1).

The time-history figures run the engine directly (:func:`~mrsuspension.engine.run_many`);
the frequency responses run a :class:`~mrsuspension.studies.Study`. The inverse-model laws
use the default (symmetric hysteretic) damper with its force gain k_d; a gain of 2.5 makes
the pre-yield slope 2.5 times steeper, so the step is 0.25 ms in quick mode (RK4 limit about
0.27 ms) and the default 0.1 ms (model reference, section 7) otherwise.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from mrsuspension.report.families import (
    HARMONIC_AMPS,
    HARMONIC_AMPS_STATED,
    MASSES,
    MASSES_STATED,
    PULSE_AMPS,
    PULSE_AMPS_STATED,
    ROADS,
    ROADS_STATED,
    SPEEDS,
    SPEEDS_STATED,
    FigureSpec,
    ShockTable,
    passive,
    road_note,
    shock_tables,
    spec_factory,
    vary,
)
from mrsuspension.report.toolkit import (
    FORCE_GAINS,
    HARMONIC,
    TRACK,
    Chapter,
    Context,
    FigureRecord,
    Jobs,
    error_figure,
    family_chapter,
    force_tracking_errors,
    harmonic_runs,
    plot_sweep,
    run_sweep,
    shown,
    steady,
    subplots,
    sweep_study,
    tracking_error,
)
from mrsuspension.report.toolkit import inverse_model_step as step

__all__ = [
    "CHAPTER",
    "FIGURES",
    "FORCE_GAINS",
    "HARMONIC",
    "TABLES",
    "error_figure",
    "fig_5_6",
    "force_tracking_errors",
    "harmonic_runs",
    "response_cases",
    "response_figure",
    "step",
    "tracking_error",
    "tracking_figure",
]

# FORCE_GAINS, HARMONIC, DURATION, STEADY_FROM, SHOWN, TRACK and the helpers step
# (inverse_model_step), harmonic_runs, tracking_error, force_tracking_errors and
# error_figure are the toolkit's (Chapter 6 shares them); shock_tables is the families'.


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
    fig, axes = subplots(2, 2, layout="fixed", title_rows=1)
    data: dict[str, Any] = {}
    for ax, (hyst, kd), r in zip(axes.ravel(), grid, results, strict=True):
        w = shown(r)
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
        data[f"peak |F_d| {key} [N]"] = float(np.max(np.abs(r.F_d[steady(r)])))
        data[f"mean current {key} [A]"] = float(np.mean(r.i_d[steady(r)]))
        data[f"time {key} [s]"] = [float(v) for v in t[::10]]
        data[f"F_d {key} [N]"] = [float(v) for v in r.F_d[w][::10]]
        data[f"target {key} [N]"] = [float(v) for v in r.F_target[w][::10]]
    axes[0, 0].legend(fontsize=8)
    return fig, data


def fig_5_6(quick: bool = False) -> FigureRecord:
    """Force-tracking error of inverse-model hi-lo against the force gain k_d."""
    fig, data = error_figure("inverse-hilo", quick)
    return FigureRecord(
        number="5.6b",
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
    return plot_sweep(run_sweep(study), "damping", {k: k for k in cases})


#: The chapter's controller: inverse-model hi-lo ACM with k_d = 2.5 (section 5.3)
BASE: dict[str, Any] = {
    "controller": {"law": "inverse-hilo", "mode": "ACM"},
    "damper": {"force_gain": 2.5},
}
_ACM = "inverse-model hi-lo ACM"
_PASSIVE_ACM = {**passive(0.0, 0.1), _ACM: {}}
_MEAN = {"damper": {"hysteresis": False}}
_HYST: dict[str, Any] = {}
_H = "2.5 cm harmonic excitation at 1.5 Hz (steady state 6-7.4 s shown)"
_SW = "two-stage swept excitation a = 2.5 cm, f_T = 2.1 Hz, 0.5-15 Hz"
_P = "rounded pulse mu = 3, a_m = 3.5 cm, 50 km/h (omega_0 = 10.4 rad/s), 4 s"
_R = (
    f"'rough' preset road at 50 km/h ({road_note()}); PSDs by mrsuspension.measures.psd "
    "(512 Hz, Welch/Hann)"
)
_C = "Inverse-model hi-lo ACM (k_d = 2.5, p = 0, xi = 10, p_c = 0, xi_c = 50)"
#: What the caption fragments above state, as ``FigureSpec.settings`` (checked against the
#: runs and the captions by mrsuspension.report.captions)
_H_S: dict[str, Any] = {"amplitude": 0.025, "frequency": 1.5}
_SW_S: dict[str, Any] = {"amplitude": 0.025}
_P_S: dict[str, Any] = {"amplitude": 0.035, "speed": 50.0}
_R_S: dict[str, Any] = {"profile": "rough", "speed": 50.0}
_C_S: dict[str, Any] = {"law": "inverse-hilo", "mode": "ACM", "force_gain": 2.5}
_PASSIVE_ACM_S: dict[str, Any] = {
    "law": {"passive 0 A": "passive", "passive 0.1 A": "passive", _ACM: "inverse-hilo"},
    "mode": {_ACM: "ACM"},
    "force_gain": {"passive 0 A": 1.0, "passive 0.1 A": 1.0, _ACM: 2.5},
    "current": {"passive 0 A": 0.0, "passive 0.1 A": 0.1},
}
#: hysteretic damper, mean inverse model (Figs 5.2, 5.5; 6.1)
_MIX = {"controller": {"inverse": "mean"}}


_spec = spec_factory(BASE)


_SCM1 = {"controller": {"law": "inverse-hilo", "mode": "SCM"}}
_ACM1 = {"controller": {"law": "inverse-hilo", "mode": "ACM"}}
FIGURES: tuple[FigureSpec, ...] = (
    _spec(
        "5.1", "time", "Mean damper and mean inverse model, inverse-model hi-lo SCM",
        f"Mean damper model (damper.hysteresis = false) with the mean inverse, inverse-model "
        f"hi-lo SCM, k_d = 1; {_H}. F* = k_s x_d is the target force.",
        {"mean damper + mean inverse": _MEAN}, base=_SCM1, signals=TRACK,
        settings={
            **_H_S,
            "law": "inverse-hilo",
            "mode": "SCM",
            "force_gain": 1.0,
            "hysteresis": False,
        },
    ),
    _spec(
        "5.2", "time", "Hysteretic damper and mean inverse model, inverse-model hi-lo SCM",
        f"Hysteretic damper with the mean inverse (controller.inverse = mean), inverse-model "
        f"hi-lo SCM, k_d = 1; {_H}. F* = k_s x_d is the target force.",
        {"hysteretic damper + mean inverse": _MIX}, base=_SCM1, signals=TRACK,
        settings={
            **_H_S,
            "law": "inverse-hilo",
            "mode": "SCM",
            "force_gain": 1.0,
            "inverse": "mean",
        },
    ),
    _spec(
        "5.3", "time", "Hysteretic damper and hysteretic inverse, inverse-model hi-lo SCM",
        f"Hysteretic damper with the hysteretic inverse, inverse-model hi-lo SCM, k_d = 1; {_H}.",
        {"hysteretic damper + hysteretic inverse": _HYST}, base=_SCM1, signals=TRACK,
        settings={**_H_S, "law": "inverse-hilo", "mode": "SCM", "force_gain": 1.0},
    ),
    _spec(
        "5.4", "time", "Inverse-model hi-lo in SCM and ACM",
        f"Inverse-model hi-lo (k_d = 1) in SCM (p = 1) and ACM (p = 0), hysteretic damper; {_H}.",
        {"SCM": {"controller": {"mode": "SCM"}}, "ACM": {}}, base=_ACM1, signals=TRACK,
        settings={
            **_H_S,
            "law": "inverse-hilo",
            "mode": {"SCM": "SCM", "ACM": "ACM"},
            "force_gain": 1.0,
        },
    ),
    _spec(
        "5.5", "time", "Inverse-model hi-lo ACM with mean and hysteretic models",
        f"Inverse-model hi-lo ACM, k_d = 1; {_H}. Mean damper and mean inverse, hysteretic "
        "damper and hysteretic inverse, hysteretic damper and mean inverse.",
        {
            "mean damper + mean inverse": _MEAN,
            "hysteretic damper + hysteretic inverse": _HYST,
            "hysteretic damper + mean inverse": _MIX,
        },
        base=_ACM1, signals=TRACK,
        settings={
            **_H_S,
            "law": "inverse-hilo",
            "mode": "ACM",
            "force_gain": 1.0,
            "hysteresis": {"mean damper + mean inverse": False, "hysteretic damper + hysteretic inverse": True, "hysteretic damper + mean inverse": True},
            "inverse": {"mean damper + mean inverse": "hysteretic", "hysteretic damper + hysteretic inverse": "hysteretic", "hysteretic damper + mean inverse": "mean"},
        },
    ),
    _spec(
        "5.6", "time", "Inverse-model hi-lo ACM with force gains k_d = 1, 2, 2.5",
        f"damper.force_gain k_d = 1, 2, 2.5, inverse-model hi-lo ACM; {_H}. Tracking errors in "
        "the data and in Fig 5.6b.",
        vary("damper", "force_gain", (1.0, 2.0, 2.5), "k_d = {:g}".format), base=_ACM1,
        settings={
            **_H_S,
            "law": "inverse-hilo",
            "mode": "ACM",
            "force_gain": {"k_d = 1": 1.0, "k_d = 2": 2.0, "k_d = 2.5": 2.5},
        },
    ),
    _spec(
        "5.7", "freq", "Inverse-model hi-lo ACM with force gains k_d = 1, 2, 2.5: frequency responses",
        f"damper.force_gain k_d = 1, 2, 2.5, inverse-model hi-lo ACM; {_SW}.",
        vary("damper", "force_gain", (1.0, 2.0, 2.5), "k_d = {:g}".format), base=_ACM1,
        settings={
            **_SW_S,
            "law": "inverse-hilo",
            "mode": "ACM",
            "force_gain": {"k_d = 1": 1.0, "k_d = 2": 2.0, "k_d = 2.5": 2.5},
        },
    ),
    _spec(
        "5.8", "time", "Passive (0, 0.1 A) and inverse-model hi-lo ACM: time histories",
        f"Passive damper (dashed, k_d = 1) at 0 and 0.1 A and {_C}; {_H}.", _PASSIVE_ACM,
        settings={**_PASSIVE_ACM_S, **_H_S},
    ),
    _spec(
        "5.9", "freq", "Frequency responses: passive (0, 0.1 A) and inverse-model hi-lo ACM",
        f"Passive damper (dashed, k_d = 1) at 0 and 0.1 A and {_C}; {_SW}.", _PASSIVE_ACM,
        settings={**_PASSIVE_ACM_S, **_SW_S},
    ),
    _spec(
        "5.10", "pulse", "Rounded-pulse responses: passive (0, 0.1 A) and inverse-model hi-lo ACM",
        f"Passive damper (dashed, k_d = 1) at 0 and 0.1 A and {_C}; rounded pulse mu = 3, a_m = 5 cm, "
        "50 km/h, as the dissertation.",
        _PASSIVE_ACM, base={**BASE, "excitation": {"amplitude": 0.05}},
        settings={**_PASSIVE_ACM_S, "amplitude": 0.05, "speed": 50.0},
    ),
    _spec(
        "5.11", "psd", "Random-road PSDs: passive 0 A and inverse-model hi-lo ACM",
        f"Passive damper at 0 A (dashed, k_d = 1) and {_C}; {_R}. The dissertation gives DLC 0.139 "
        "(passive 0 A) and 0.113 (ACM).",
        {**passive(0.0), _ACM: {}}, given={"passive 0 A": 0.139, _ACM: 0.113},
        settings={
            **_R_S,
            "law": {"passive 0 A": "passive", _ACM: "inverse-hilo"},
            "mode": {_ACM: "ACM"},
            "force_gain": {"passive 0 A": 1.0, _ACM: 2.5},
            "current": {"passive 0 A": 0.0},
        },
    ),
    _spec(
        "5.12", "time", "Sprung-mass variation: harmonic responses",
        f"m_s = 422, 563, 703 kg; {_C}; {_H}.", MASSES,
        settings={**_C_S, **MASSES_STATED, **_H_S},
    ),
    _spec(
        "5.13", "freq", "Sprung-mass variation: frequency responses",
        f"m_s = 422, 563, 703 kg; {_C}; {_SW}.", MASSES,
        settings={**_C_S, **MASSES_STATED, **_SW_S},
    ),
    _spec(
        "5.14", "pulse", "Sprung-mass variation: rounded-pulse responses",
        f"m_s = 422, 563, 703 kg; {_C}; {_P}. Measures in Table 5.1.", MASSES,
        settings={**_C_S, **MASSES_STATED, **_P_S},
    ),
    _spec(
        "5.15", "psd", "Sprung-mass variation: random-road PSDs",
        f"m_s = 422, 563, 703 kg; {_C}; {_R}. The dissertation gives DLC 0.091 and 0.147 for "
        "the extreme masses.",
        MASSES, given={"m_s = 422 kg": 0.091, "m_s = 703 kg": 0.147},
        settings={**_C_S, **MASSES_STATED, **_R_S},
    ),
    _spec(
        "5.16", "pulse", "Vehicle-speed variation: rounded-pulse responses",
        f"V = 50 and 100 km/h (omega_0 scaled with speed, erratum 9); {_C}; a_m = 3.5 cm. "
        "Measures in Table 5.2.",
        SPEEDS,
        settings={**_C_S, **SPEEDS_STATED, "amplitude": 0.035},
    ),
    _spec(
        "5.17", "psd", "Vehicle-speed variation: random-road PSDs",
        f"V = 50 and 100 km/h on the 'rough' preset; {_C}. The dissertation gives DLC 0.113 "
        "(50 km/h) and 0.114 (100 km/h).",
        SPEEDS, given={"V = 50 km/h": 0.113, "V = 100 km/h": 0.114},
        settings={**_C_S, **SPEEDS_STATED, "profile": "rough"},
    ),
    _spec(
        "5.18", "time", "Harmonic amplitude variation (1.5 Hz): time histories",
        f"a = 1.5, 2.5, 3.5 cm at 1.5 Hz; {_C}.", HARMONIC_AMPS,
        settings={**_C_S, **HARMONIC_AMPS_STATED, "frequency": 1.5},
    ),
    _spec(
        "5.19", "freq", "Harmonic amplitude variation: frequency responses",
        f"Two-stage swept excitation with a = 1.5, 2.5, 3.5 cm; {_C}.", HARMONIC_AMPS,
        settings={**_C_S, **HARMONIC_AMPS_STATED},
    ),
    _spec(
        "5.20", "pulse", "Pulse-height variation: rounded-pulse responses",
        f"a_m = 2, 3.5, 5 cm (mu = 3, 50 km/h); {_C}. Measures in Table 5.3.", PULSE_AMPS,
        settings={**_C_S, **PULSE_AMPS_STATED, "speed": 50.0},
    ),
    _spec(
        "5.21", "psd", "Road-roughness variation: random-road PSDs",
        f"'medium-rough' and 'rough' presets at 50 km/h; {_C}. The dissertation gives DLC 0.056 "
        "(medium-rough) and 0.113 (rough).",
        ROADS, given={"medium-rough": 0.056, "rough": 0.113},
        settings={**_C_S, **ROADS_STATED, "speed": 50.0},
    ),
    FigureSpec(
        number="5.6b", kind="special", title="Force-tracking error against k_d",
        caption="", builder=fig_5_6,
    ),
)  # fmt: skip

_WHY = (
    "Known causes: at 100 km/h the pulse keeps omega_0 proportional to speed (erratum 9); "
    "the inverse model is the corrected (2.17) of erratum 6."
)


#: Tables 5.1-5.3 as printed in the dissertation (SDR_s, SAR_s, SDR_u, SAR_u, RDR, DTR)
GIVEN: tuple[dict[float, tuple[float, ...]], ...] = (
    {
        422.0: (1.03, 0.33, 1.16, 1.24, 0.86, 0.18),
        563.0: (0.91, 0.25, 1.14, 1.24, 0.86, 0.0),
        703.0: (0.82, 0.20, 1.14, 1.24, 0.86, 0.14),
    },
    {50.0: (0.91, 0.25, 1.14, 1.24, 0.86, 0.0), 100.0: (0.57, 0.06, 1.13, 0.48, 0.86, 0.37)},
    {
        2.0: (0.88, 0.24, 1.15, 1.23, 0.88, 0.29),
        3.5: (0.91, 0.25, 1.14, 1.24, 0.86, 0.0),
        5.0: (0.96, 0.26, 1.16, 1.25, 0.84, 0.29),
    },
)
TABLES: tuple[ShockTable, ...] = shock_tables(BASE, ("5.1", "5.2", "5.3"), GIVEN, _WHY)


def _jobs(quick: bool) -> Jobs:
    return Jobs(figures={"chapter5": FIGURES}, tables=TABLES)


def _build(context: Context) -> tuple[str, dict[str, Any]]:
    return family_chapter(
        context,
        "Chapter 5: inverse-model hi-lo semi-active damping",
        TABLES,
        intro="<p>The force gain k_d is damper.force_gain.</p>",
    )


#: The chapter's entry in the report (:data:`mrsuspension.report.chapters.CHAPTERS`)
CHAPTER = Chapter(5, _jobs, _build, FIGURES, TABLES)
