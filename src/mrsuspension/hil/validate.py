"""HiL against offline: the Chapter 7 validation comparisons (``mrsus hil validate``).

The same scenario runs hardware-in-the-loop (:func:`~mrsuspension.hil.loop.run_hil`, no
start-up ramp) and offline (:meth:`~mrsuspension.engine.simulate.Simulation.run`, same
engine step, output at the loop rate), with the controller's current capped at the
safety limit in both, so that they are comparable. The comparison gives RMS measures both
ways with their relative difference, and figures: overlaid time histories of the body
acceleration and the damper force, and the overlaid F-v loop.

A half or full car (:class:`~mrsuspension.engine.vehicle.VehicleSimulation`) runs with one
corner's damper on the rig (:mod:`~mrsuspension.hil.vehicle`) against
:meth:`VehicleSimulation.run <mrsuspension.engine.vehicle.VehicleSimulation.run>` on the
same roads and engine step: the rig corner's measures (:data:`MEASURES`) and the body's
(:data:`BODY_MEASURES`).
"""

from __future__ import annotations

import dataclasses
import json
import math
from pathlib import Path
from typing import Any

import numpy as np

from mrsuspension._jsonsafe import to_jsonable as _clean
from mrsuspension.engine.simulate import DEFAULT_DT, Simulation
from mrsuspension.hil.loop import HilResult, _capped, run_hil
from mrsuspension.hil.rig import Rig
from mrsuspension.hil.safety import SafetyLimits, StartUp
from mrsuspension.hil.vehicle import check_corner, has_corners

__all__ = ["BODY_MEASURES", "MEASURES", "ValidationReport", "validate"]

#: compared RMS measures: (key, label, unit, channel, remove the mean)
MEASURES: tuple[tuple[str, str, str, str, bool], ...] = (
    ("body_acceleration", "body acceleration z_s''", "m/s^2", "z_s_ddot", False),
    ("wheel_acceleration", "wheel acceleration z_u''", "m/s^2", "z_u_ddot", False),
    ("suspension_travel", "suspension stroke x_d", "m", "x_d", False),
    ("stroke_rate", "stroke rate v_d", "m/s", "v_d", False),
    ("damper_force", "damper force F_d", "N", "F_d", False),
    ("dynamic_tire_force", "dynamic tire force F_T - mean", "N", "F_T", True),
    ("drive_current", "drive current demand i_d", "A", "i_d", False),
)
#: the body's RMS measures of a half or full car, as :data:`MEASURES` (a degree of freedom
#: the vehicle does not have, the half car's roll, is left out: both runs give 0)
BODY_MEASURES: tuple[tuple[str, str, str, str, bool], ...] = (
    ("heave", "body heave", "m", "heave", False),
    ("pitch", "body pitch", "rad", "pitch", False),
    ("roll", "body roll", "rad", "roll", False),
    ("heave_acceleration", "heave acceleration", "m/s^2", "heave_ddot", False),
    ("pitch_acceleration", "pitch acceleration", "rad/s^2", "pitch_ddot", False),
    ("roll_acceleration", "roll acceleration", "rad/s^2", "roll_ddot", False),
)


def _rms(x: np.ndarray, detrend: bool) -> float:
    if x.size == 0:
        return math.nan
    if detrend:
        x = x - x.mean()
    return float(np.sqrt(np.mean(x * x)))


@dataclasses.dataclass
class ValidationReport:
    """Outcome of :func:`validate`.

    Attributes
    ----------
    hil : HilResult
        The HiL run.
    time : numpy.ndarray
        Model time of the compared samples [s].
    hil_signals, offline_signals : dict of numpy.ndarray
        The compared channels (:data:`MEASURES`), aligned sample by sample.
    rms : dict
        Per measure: ``{"label", "unit", "hil", "offline", "relative_difference"}``
        (a vehicle's rig-corner labels name the corner).
    figures : list of Path
        PNG files written (empty without an output directory).
    corner : str or None
        A vehicle's rig corner (None: a quarter car).
    """

    hil: HilResult
    time: np.ndarray
    hil_signals: dict[str, np.ndarray]
    offline_signals: dict[str, np.ndarray]
    rms: dict[str, dict[str, Any]]
    figures: list[Path] = dataclasses.field(default_factory=list)
    corner: str | None = None

    def describe(self) -> dict[str, Any]:
        """Plain-data summary (the JSON summary)."""
        out = {
            "reason": self.hil.reason,
            "tripped": self.hil.tripped,
            "samples": int(self.time.size),
            "rms": self.rms,
            "stats": self.hil.stats.describe(),
            "figures": [str(p) for p in self.figures],
        }
        if self.corner is not None:
            out["corner"] = self.corner
        return out


def validate(
    sim: Simulation | Any,
    rig: Rig,
    duration: float = 10.0,
    rate: float = 1000.0,
    out: str | Path | None = None,
    *,
    model_dt: float = DEFAULT_DT,
    limits: SafetyLimits | None = None,
    realtime: bool | str = True,
    corner: str | None = None,
) -> ValidationReport:
    """Run ``sim`` in HiL with ``rig`` and offline; compare them.

    Parameters
    ----------
    sim : Simulation or VehicleSimulation
        The scenario's simulation: a quarter car, or a half or full car with the damper
        of ``corner`` on the rig.
    rig : Rig
        The rig of the HiL run.
    duration : float
        Run time [s].
    rate : float
        Loop rate [Hz]; also the offline output rate.
    out : path, optional
        Directory for the recording (``recording/``), ``summary.json`` and the figures
        (``time_histories.png``, ``fv_loop.png``); nothing is written without it.
    model_dt : float
        Engine step [s] (both runs).
    limits : SafetyLimits, optional
        HiL trip limits; the offline run uses the same current cap.
    realtime : bool or str
        Pacing and scheduling of the HiL loop (see :func:`~mrsuspension.hil.loop.run_hil`;
        ``"unpaced"`` runs a simulated rig as fast as possible).
    corner : str, optional
        A vehicle's rig corner (default: the first); the offline run is
        :meth:`VehicleSimulation.run <mrsuspension.engine.vehicle.VehicleSimulation.run>`
        and the body's measures (:data:`BODY_MEASURES`) are compared too.

    Returns
    -------
    ValidationReport
        RMS comparison, aligned signals and the HiL result.

    Examples
    --------
    >>> from mrsuspension.hil import ideal_rig
    >>> from mrsuspension.hil.loop import _simulation_of
    >>> car = _simulation_of("examples/vehicles/half_car.toml")
    >>> rig = ideal_rig(car.corner_simulation("front").damper)
    >>> rep = validate(car, rig, duration=1.0, realtime="unpaced")
    >>> rep.corner, "roll" in rep.rms, abs(rep.rms["heave_acceleration"]["relative_difference"]) < 0.01
    ('front', False, True)
    """
    limits = limits or SafetyLimits()
    vehicle = has_corners(sim)
    if vehicle:
        corner = check_corner(sim, corner)
    if sim.max_current > limits.current:  # both runs at the loop's current limit
        sim = _capped(sim, limits.current)
    out_dir = Path(out) if out is not None else None
    if out_dir is not None:
        out_dir.mkdir(parents=True, exist_ok=True)
    hil = run_hil(
        sim, rig, duration=duration, rate=rate,
        out=out_dir / "recording" if out_dir is not None else None,
        model_dt=model_dt, limits=limits, startup=StartUp.none(), realtime=realtime,
        cap_current=False, corner=corner,
    )  # fmt: skip
    offline = sim.run(duration, dt=model_dt, output_rate=rate)
    run = hil.running()
    # HiL row k holds the model state at the end of tick k: offline sample k + 1
    n = min(int(run.sum()), offline.time.size - 1)
    time = np.asarray(offline.time[1 : n + 1], dtype=float)
    hil_sig: dict[str, np.ndarray] = {}
    off_sig: dict[str, np.ndarray] = {}
    rms: dict[str, dict[str, Any]] = {}
    measures = [(m, f".{corner}" if vehicle else "") for m in MEASURES]
    measures += [(m, "") for m in (BODY_MEASURES if vehicle else ())]
    for (key, label, unit, channel, detrend), suffix in measures:
        h = np.asarray(hil.recording[channel][run][:n], dtype=float)
        o = np.asarray(offline.signals[channel + suffix][1 : n + 1], dtype=float)
        if not suffix and vehicle and not (np.any(o) or np.any(h)):
            continue  # a degree of freedom this vehicle does not have (a half car's roll)
        hil_sig[channel] = h
        off_sig[channel] = o
        rh, ro = _rms(h, detrend), _rms(o, detrend)
        rel = rh / ro - 1.0 if ro > 0 and math.isfinite(rh) else math.nan
        if suffix:
            label = f"{label} ({corner})"
        rms[key] = {"label": label, "unit": unit, "hil": rh, "offline": ro}
        rms[key]["relative_difference"] = rel
    report = ValidationReport(hil, time, hil_sig, off_sig, rms, corner=corner)
    if out_dir is not None:
        report.figures = _figures(report, out_dir)
        summary = report.describe()
        summary["rig"] = rig.describe()
        summary["duration"] = duration
        summary["rate"] = rate
        (out_dir / "summary.json").write_text(json.dumps(_clean(summary), indent=2) + "\n")
    return report


def _figures(report: ValidationReport, out: Path) -> list[Path]:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    t = report.time
    h, o = report.hil_signals, report.offline_signals
    paths = []
    fig, axes = plt.subplots(2, 1, figsize=(8, 6), sharex=True)
    for ax, ch, ylabel in (
        (axes[0], "z_s_ddot", "z_s'' [m/s^2]"),
        (axes[1], "F_d", "F_d [N]"),
    ):
        ax.plot(t, o[ch], label="offline", lw=1.2)
        ax.plot(t, h[ch], "--", label="HiL", lw=1.0)
        ax.set_ylabel(ylabel)
        ax.grid(True, alpha=0.3)
        ax.legend(loc="upper right")
    axes[1].set_xlabel("time [s]")
    rel = report.rms["body_acceleration"]["relative_difference"]
    axes[0].set_title(f"HiL vs offline (RMS z_s'' difference {100 * rel:+.2f} %)")
    fig.tight_layout()
    p = out / "time_histories.png"
    fig.savefig(p, dpi=100)
    plt.close(fig)
    paths.append(p)

    fig, ax = plt.subplots(figsize=(6, 5))
    ax.plot(o["v_d"], o["F_d"], label="offline", lw=1.2)
    ax.plot(h["v_d"], h["F_d"], "--", label="HiL", lw=1.0)
    ax.set_xlabel("stroke rate v_d [m/s]")
    ax.set_ylabel("damper force F_d [N]")
    ax.set_title("F-v loop")
    ax.grid(True, alpha=0.3)
    ax.legend()
    fig.tight_layout()
    p = out / "fv_loop.png"
    fig.savefig(p, dpi=100)
    plt.close(fig)
    paths.append(p)
    return paths
