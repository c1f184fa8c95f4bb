"""The Chapter 7 comparisons of ``mrsus hil validate``: HiL against offline, figure by figure.

Dissertation Figs 7.7-7.21 compare the rig (HiL) with the model (offline) under three
kinds of excitation; :func:`validate_chapter7` runs each in HiL
(:func:`~mrsuspension.hil.loop.run_hil`, no start-up ramp) and offline
(:meth:`~mrsuspension.engine.simulate.Simulation.run`, same engine step, output at the
loop rate), aligned sample by sample (HiL row k = offline sample k + 1), for one or more
controller cases:

- ``time``: the scenario's own excitation: time histories and F-v loops
  (:func:`~mrsuspension.hil.validate.validate`; Figs 7.7, 7.8, 7.12-7.14);
- ``frequency``: harmonic runs over a frequency list at the two-stage amplitude of the
  HiL rig (``a`` up to 2 Hz, ``a (2/f)^2`` above), ``T_as``, ``T_au``, ``T_dr`` and
  ``DLC`` over the steady window (model reference, section 9; Figs 7.9, 7.15, 7.16);
- ``pulse``: a rounded pulse (mu = 3, w0 = 10.4 rad/s, 2 cm): time histories and the
  shock ratios (Figs 7.10, 7.17, 7.18);
- ``road``: the preset rough road at 50 km/h with its elevations halved (as on the rig):
  PSDs of a_s, x_s, a_u, x_u overlaid and their band RMS (0.5-20 Hz) (Figs 7.11,
  7.19-7.21).

Controller cases (``cases=``): ``scenario`` (the scenario's controller), ``passive-0``,
``passive-0.1`` (0 and 0.1 A), ``skyhook-scm`` and ``skyhook-acm`` (hi-lo, n = 2,
k_c = 3, as in section 7.3.2).

Sprung masses (``masses=``, default the scenario's own): every comparison runs for each
mass, the vehicle of both runs changed to it (Chapter 7 uses 563 and 703 kg: Figs 7.14,
7.16, 7.18, 7.21). With several masses, the entries are keyed ``<case>@<mass>kg`` and the
pulse and road figures get one overlay of the masses per case.

A rig simulated in the same process may run unpaced (``realtime="unpaced"``: as fast as
possible, not real time; the outputs say so), so a sweep validates in seconds; a
network rig always runs paced.

The output folder gets ``validation.json`` (every number) and the ``time`` comparison's
files; the figures of the other comparisons and ``index.html`` come from a renderer passed
in (``render=``): :func:`mrsuspension.report.ch7.validate_chapter7` passes the report's,
:func:`mrsuspension.report.ch7.render` (``hil`` does not import the report).

A half or full car (:class:`~mrsuspension.engine.vehicle.VehicleSimulation`) is compared
on ``time`` only, with one corner's damper on the rig (``corner=``), against
``VehicleSimulation.run``: the rig corner's measures and the body's
(:func:`~mrsuspension.hil.validate.validate`). The other comparisons, the controller
cases and the sprung masses are the quarter car's (Chapter 7's rig) and are refused.
"""

from __future__ import annotations

import dataclasses
import json
import math
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any

import numpy as np

from mrsuspension._jsonsafe import to_jsonable as _clean
from mrsuspension.engine.simulate import DEFAULT_DT, Simulation
from mrsuspension.errors import ValidationError, did_you_mean
from mrsuspension.excitation import Excitation
from mrsuspension.excitation.deterministic import (
    HIL_FREQUENCIES,
    HIL_TRANSITION_FREQUENCY,
    OMEGA0_REFERENCE,
    Harmonic,
    RoundedPulse,
    two_stage_amplitude,
)
from mrsuspension.excitation.road import RoadProfile, preset_road
from mrsuspension.hil.loop import run_hil
from mrsuspension.hil.realtime import normalise_mode
from mrsuspension.hil.rig import Rig, SimulatedRig
from mrsuspension.hil.safety import SafetyLimits, StartUp
from mrsuspension.hil.vehicle import check_corner, has_corners

__all__ = [
    "CASES",
    "WHAT",
    "Renderer",
    "mass_tag",
    "parse_cases",
    "parse_frequencies",
    "parse_masses",
    "parse_what",
    "run_pair",
    "validate_chapter7",
]

#: comparisons ``validate_chapter7`` can make
WHAT = ("time", "frequency", "pulse", "road")
#: controller cases: name -> (law, options); None: the scenario's own controller
CASES: dict[str, tuple[str, dict[str, Any]] | None] = {
    "scenario": None,
    "passive-0": ("passive", {"current": 0.0}),
    "passive-0.1": ("passive", {"current": 0.1}),
    "skyhook-scm": ("skyhook-hilo", {"mode": "SCM", "gain": 3.0, "order": 2}),
    "skyhook-acm": ("skyhook-hilo", {"mode": "ACM", "gain": 3.0, "order": 2}),
}
#: frequency-response measures compared
FREQUENCY_MEASURES = ("T_as", "T_au", "T_dr", "DLC")
#: PSD channels compared under the random road: (channel, label, unit)
PSD_CHANNELS = (
    ("z_s_ddot", "a_s", "m/s^2"),
    ("z_s", "x_s", "m"),
    ("z_u_ddot", "a_u", "m/s^2"),
    ("z_u", "x_u", "m"),
)
#: band of the PSD comparison [Hz]
PSD_BAND = (0.5, 20.0)
#: most sprung masses one validation compares
MAX_MASSES = 6
#: ``render(data, pulses, out)``: draws the comparison figures into ``out``, writes its
#: ``index.html`` and returns the new figures' file names by comparison
#: (:func:`mrsuspension.report.ch7.render`); ``data["figures"]`` holds those made so far
Renderer = Callable[[dict[str, Any], dict[str, Any], Path], dict[str, list[str]]]
_CHANNELS = ("z_r", "z_s", "z_u", "z_s_ddot", "z_u_ddot", "x_d", "v_d", "F_d", "F_T", "i_d")


def _names(text: str | Sequence[str], valid: Sequence[str], option: str) -> tuple[str, ...]:
    items = text.split(",") if isinstance(text, str) else list(text)
    out: list[str] = []
    for raw in items:
        name = str(raw).strip().lower()
        if not name:
            continue
        if name not in valid:
            raise ValidationError(
                f"{option}: unknown {name!r}.{did_you_mean(name, valid)} Valid: {', '.join(valid)}"
            )
        if name not in out:
            out.append(name)
    if not out:
        raise ValidationError(f"{option}: give at least one of {', '.join(valid)}; got {text!r}")
    return tuple(out)


def parse_what(text: str | Sequence[str]) -> tuple[str, ...]:
    """The comparisons of a ``--what`` list (``all`` for every one).

    Examples
    --------
    >>> parse_what("time, frequency")
    ('time', 'frequency')
    >>> parse_what("all")
    ('time', 'frequency', 'pulse', 'road')
    """
    if isinstance(text, str) and text.strip().lower() == "all":
        return WHAT
    return _names(text, WHAT, "--what")


def parse_cases(text: str | Sequence[str]) -> tuple[str, ...]:
    """The controller cases of a ``--cases`` list (``all`` for every one).

    Examples
    --------
    >>> parse_cases("passive-0.1,skyhook-acm")
    ('passive-0.1', 'skyhook-acm')
    """
    if isinstance(text, str) and text.strip().lower() == "all":
        return tuple(CASES)
    return _names(text, tuple(CASES), "--cases")


def parse_frequencies(text: str | Sequence[float] | None) -> tuple[float, ...]:
    """Frequencies [Hz] of a ``--frequencies`` list (default: the 14 of the HiL rig).

    Examples
    --------
    >>> parse_frequencies("1.5, 4,10")
    (1.5, 4.0, 10.0)
    >>> len(parse_frequencies(None))
    14
    """
    if text is None or (isinstance(text, str) and not text.strip()):
        return tuple(HIL_FREQUENCIES)
    items = text.split(",") if isinstance(text, str) else list(text)
    out: list[float] = []
    for raw in items:
        try:
            f = float(raw)
        except (TypeError, ValueError):
            raise ValidationError(
                f"--frequencies: {str(raw).strip()!r} is not a number; "
                "give frequencies in Hz separated by commas, e.g. 1,1.5,4"
            ) from None
        if not (math.isfinite(f) and 0.0 < f <= 50.0):
            raise ValidationError(f"--frequencies: each must be in (0, 50] Hz; got {f:g}")
        if f in out:
            raise ValidationError(f"--frequencies: {f:g} Hz is given twice")
        out.append(f)
    return tuple(out)


def parse_masses(text: str | Sequence[float] | None) -> tuple[float, ...]:
    """Sprung masses [kg] of a ``--masses`` list (empty: the scenario's own mass).

    Examples
    --------
    >>> parse_masses("563, 703")
    (563.0, 703.0)
    >>> parse_masses(None)
    ()
    >>> parse_masses("563,563")
    Traceback (most recent call last):
    ...
    mrsuspension.errors.ValidationError: --masses: 563 kg is given twice
    """
    if text is None or (isinstance(text, str) and not text.strip()):
        return ()
    items = text.split(",") if isinstance(text, str) else list(text)
    out: list[float] = []
    for raw in items:
        try:
            if isinstance(raw, bool):
                raise TypeError
            m = float(raw)
        except (TypeError, ValueError):
            raise ValidationError(
                f"--masses: {str(raw).strip()!r} is not a number; "
                "give sprung masses in kg separated by commas, e.g. 563,703"
            ) from None
        if not (math.isfinite(m) and m > 0.0):
            raise ValidationError(
                f"--masses: each sprung mass must be finite and > 0 kg; got {m:g}"
            )
        if m in out:
            raise ValidationError(f"--masses: {m:g} kg is given twice")
        out.append(m)
    if len(out) > MAX_MASSES:
        raise ValidationError(
            f"--masses: at most {MAX_MASSES} sprung masses; got {len(out)} "
            f"({', '.join(f'{m:g}' for m in out)})"
        )
    return tuple(out)


def mass_tag(mass: float) -> str:
    """The file and folder tag of a sprung mass (several masses: ``m703/``, ``_m703.png``).

    Examples
    --------
    >>> mass_tag(703.0)
    'm703'
    """
    return f"m{mass:g}"


def _entry_key(case: str, mass: float, several: bool) -> str:
    return f"{case}@{mass:g}kg" if several else case


def case_simulation(sim: Simulation, case: str) -> Simulation:
    """``sim`` with the controller of a case (:data:`CASES`)."""
    from mrsuspension.control import make_controller

    spec = CASES[case]
    if spec is None:
        return sim
    law, options = spec
    return dataclasses.replace(sim, controller=make_controller(law, **options))


def run_pair(
    sim: Simulation,
    rig: Rig,
    duration: float,
    rate: float,
    *,
    model_dt: float = DEFAULT_DT,
    limits: SafetyLimits | None = None,
    realtime: bool | str = "unpaced",
) -> dict[str, Any]:
    """Run ``sim`` in HiL and offline; the aligned channels and the HiL outcome.

    Returns
    -------
    dict
        ``time`` (model time [s]), ``hil`` and ``offline`` (channel -> array, with the
        road acceleration ``z_r_ddot``), ``reason``, ``tripped``, ``stats``.
    """
    limits = limits or SafetyLimits()
    if sim.max_current > limits.current:
        sim = dataclasses.replace(sim, max_current=limits.current)
    hil = run_hil(
        sim, rig, duration=duration, rate=rate, model_dt=model_dt, limits=limits,
        startup=StartUp.none(), realtime=realtime, cap_current=False,
    )  # fmt: skip
    offline = sim.run(duration, dt=model_dt, output_rate=rate)
    run = hil.running()
    n = min(int(run.sum()), offline.time.size - 1)
    time = np.asarray(offline.time[1 : n + 1], dtype=float)
    h = {c: np.asarray(hil.recording[c][run][:n], dtype=float) for c in _CHANNELS}
    o = {c: np.asarray(offline.signals[c][1 : n + 1], dtype=float) for c in _CHANNELS}
    # the recording holds z_r and its rate; the road acceleration is the excitation's
    h["z_r_ddot"] = np.asarray(sim.excitation.acceleration(time), dtype=float)
    o["z_r_ddot"] = np.asarray(offline.signals["z_r_ddot"][1 : n + 1], dtype=float)
    return {
        "time": time,
        "hil": h,
        "offline": o,
        "reason": hil.reason,
        "tripped": hil.tripped,
        "stats": hil.stats,
    }


def _static_load(sim: Simulation) -> float:
    return sim.vehicle.static_load


def _rel(h: float, o: float) -> float | None:
    if o is None or h is None or not (math.isfinite(h) and math.isfinite(o)) or o == 0.0:
        return None
    return h / o - 1.0


def _harmonic(pair: dict[str, Any], f: float, side: str, static_load: float) -> dict[str, float]:
    from mrsuspension.measures import harmonic_measures

    s = pair[side]
    m = harmonic_measures(
        pair["time"], f, z_s=s["z_s"], z_u=s["z_u"], z_r=s["z_r"], acc_s=s["z_s_ddot"],
        acc_u=s["z_u_ddot"], acc_r=s["z_r_ddot"], x_d=s["x_d"], F_d=s["F_d"], F_T=s["F_T"],
        static_load=static_load,
    )  # fmt: skip
    return {k: float(m[k]) for k in FREQUENCY_MEASURES}


def frequency_response(
    sim: Simulation,
    rig: Rig,
    frequencies: Sequence[float],
    amplitude: float,
    rate: float,
    **kw: Any,
) -> dict[str, Any]:
    """``T_as``, ``T_au``, ``T_dr``, ``DLC`` HiL and offline at each frequency."""
    freqs = tuple(float(f) for f in frequencies)
    amps = np.atleast_1d(two_stage_amplitude(freqs, amplitude, HIL_TRANSITION_FREQUENCY))
    load = _static_load(sim)
    out: dict[str, Any] = {"frequency": list(freqs), "amplitude": [float(a) for a in amps]}
    hil = {k: [] for k in FREQUENCY_MEASURES}  # type: dict[str, list[float]]
    off = {k: [] for k in FREQUENCY_MEASURES}  # type: dict[str, list[float]]
    reasons = []
    for f, a in zip(freqs, amps, strict=True):
        exc = Harmonic(f, float(a))
        # two ticks more: the aligned record starts one tick in (HiL row 0 = offline 1)
        length = exc.duration + 2.0 / rate
        pair = run_pair(dataclasses.replace(sim, excitation=exc), rig, length, rate, **kw)
        reasons.append(pair["reason"])
        if pair["tripped"]:
            for k in FREQUENCY_MEASURES:
                hil[k].append(math.nan)
                off[k].append(math.nan)
            continue
        mh = _harmonic(pair, f, "hil", load)
        mo = _harmonic(pair, f, "offline", load)
        for k in FREQUENCY_MEASURES:
            hil[k].append(mh[k])
            off[k].append(mo[k])
    out["hil"] = hil
    out["offline"] = off
    out["relative_difference"] = {
        k: [_rel(h, o) for h, o in zip(hil[k], off[k], strict=True)] for k in FREQUENCY_MEASURES
    }
    out["max_abs_relative_difference"] = {
        k: max((abs(r) for r in out["relative_difference"][k] if r is not None), default=None)
        for k in FREQUENCY_MEASURES
    }
    out["reasons"] = reasons
    return out


def default_pulse() -> RoundedPulse:
    """The Chapter 7 rounded pulse: mu = 3, w0 = 10.4 rad/s, 2 cm."""
    return RoundedPulse(0.02, 3.0, omega0=OMEGA0_REFERENCE)


def default_road(duration: float | None = None) -> RoadProfile:
    """The Chapter 7 random road: the preset rough road at 50 km/h, elevations halved."""
    base = preset_road("rough", 50.0)
    road = RoadProfile(
        base.distance, 0.5 * base.elevation, 50.0, source=f"{base.source}, elevations x 0.5"
    )
    if duration is not None and duration < road.duration:
        keep = base.distance <= duration * 50.0 / 3.6 + 2 * (base.distance[1] - base.distance[0])
        road = RoadProfile(
            base.distance[keep], 0.5 * base.elevation[keep], 50.0,
            source=f"{base.source}, elevations x 0.5, first {duration:g} s",
        )  # fmt: skip
    return road


def pulse_response(
    sim: Simulation, rig: Rig, rate: float, pulse: Excitation | None = None, **kw: Any
) -> dict[str, Any]:
    """Transient response under a rounded pulse: shock ratios and peaks, both ways."""
    from mrsuspension.measures import shock_ratios

    exc = pulse or default_pulse()
    pair = run_pair(dataclasses.replace(sim, excitation=exc), rig, exc.duration, rate, **kw)
    res: dict[str, Any] = {"excitation": exc.describe(), "reason": pair["reason"]}
    for side in ("hil", "offline"):
        s = pair[side]
        m = dict(
            shock_ratios(
                s["z_s"], s["z_u"], s["z_r"], s["z_s_ddot"], s["z_u_ddot"], s["z_r_ddot"],
                s["x_d"],
            )
        )  # fmt: skip
        m["peak_F_d"] = float(np.max(np.abs(s["F_d"])))
        m["peak_F_T"] = float(np.max(s["F_T"]))
        res[side] = {k: float(v) for k, v in m.items()}
    res["relative_difference"] = {k: _rel(res["hil"][k], res["offline"][k]) for k in res["hil"]}
    res["_pair"] = pair
    return res


def road_response(
    sim: Simulation,
    rig: Rig,
    rate: float,
    road: Excitation | None = None,
    **kw: Any,
) -> dict[str, Any]:
    """PSDs of a_s, x_s, a_u, x_u under the random road, both ways, and their band RMS."""
    from mrsuspension.measures import psd

    exc = road or default_road()
    pair = run_pair(dataclasses.replace(sim, excitation=exc), rig, exc.duration, rate, **kw)
    res: dict[str, Any] = {"excitation": exc.describe(), "reason": pair["reason"]}
    lo, hi = PSD_BAND
    spectra: dict[str, Any] = {}
    band_rms: dict[str, dict[str, Any]] = {}
    for ch, label, unit in PSD_CHANNELS:
        ph = psd(pair["hil"][ch], rate, warn=False)
        po = psd(pair["offline"][ch], rate, warn=False)
        f = ph.frequency
        band = (f >= lo) & (f <= hi)
        df = float(f[1] - f[0])
        rh = float(np.sqrt(np.sum(ph.density[band]) * df))
        ro = float(np.sqrt(np.sum(po.density[band]) * df))
        # pointwise, where the spectrum carries energy (above 1e-3 of its peak in the band)
        sig = band & (po.density > 1e-3 * float(np.max(po.density[band])))
        pointwise = np.abs(ph.density[sig] / po.density[sig] - 1.0)
        band_rms[label] = {
            "unit": unit,
            "hil": rh,
            "offline": ro,
            "relative_difference": _rel(rh, ro),
            "max_pointwise_relative_difference": float(pointwise.max()) if pointwise.size else None,
        }
        spectra[label] = {
            "frequency": f[band].tolist(),
            "hil": ph.density[band].tolist(),
            "offline": po.density[band].tolist(),
            "short_record": bool(ph.short_record),
        }
    res["band"] = list(PSD_BAND)
    res["band_rms"] = band_rms
    res["psd"] = spectra
    return res


def validate_chapter7(
    sim: Simulation,
    rig: Rig,
    out: str | Path | None = None,
    *,
    what: Sequence[str] = WHAT,
    cases: Sequence[str] = ("scenario",),
    frequencies: Sequence[float] = HIL_FREQUENCIES,
    amplitude: float = 0.015,
    duration: float = 10.0,
    road_duration: float | None = None,
    rate: float = 1000.0,
    model_dt: float = DEFAULT_DT,
    limits: SafetyLimits | None = None,
    realtime: bool | str | None = None,
    masses: Sequence[float] | None = None,
    render: Renderer | None = None,
    corner: str | None = None,
) -> dict[str, Any]:
    """The Chapter 7 comparisons of HiL against offline (see the module docstring).

    Parameters
    ----------
    sim : Simulation
        The scenario (vehicle, damper, controller, excitation for ``time``).
    rig : Rig
        The rig (reset before every run).
    out : path, optional
        Output folder (``validation.json``, the ``time`` recording and figures, and what
        ``render`` writes); nothing is written without it.
    what : sequence of str
        Comparisons (:data:`WHAT`).
    cases : sequence of str
        Controller cases (:data:`CASES`) for ``frequency``, ``pulse`` and ``road``.
    frequencies : sequence of float
        Frequency list [Hz] (default: the 14 of the HiL rig, 0.75-15 Hz).
    amplitude : float
        Low-frequency amplitude [m] of the sweep (1.5 cm as on the rig).
    duration : float
        Run time [s] of the ``time`` comparison.
    road_duration : float, optional
        Length [s] of the random road (default: the whole 500 m, 36 s).
    rate : float
        Loop rate [Hz] (also the offline output rate).
    model_dt : float
        Engine step [s] (both sides).
    limits : SafetyLimits, optional
        HiL trip limits (the offline runs use the same current cap).
    realtime : bool or str, optional
        Pacing (:mod:`~mrsuspension.hil.realtime`); default ``"unpaced"`` for a
        :class:`~mrsuspension.hil.rig.SimulatedRig`, ``"auto"`` for any other rig.
    masses : sequence of float, optional
        Sprung masses [kg] (at most :data:`MAX_MASSES`); each comparison runs for each,
        with the vehicle of both runs changed to it. Default: the scenario's own. With
        one mass the entries are keyed as without (``data["pulse"][case]``, one
        ``time`` report); with several, ``data[what]["<case>@<mass>kg"]`` (``time``:
        ``"scenario@<mass>kg"``, its files in ``m<mass>/``). Every entry has its
        ``sprung_mass``.
    render : Renderer, optional
        With ``out``: draws the other figures and writes ``index.html``
        (:func:`mrsuspension.report.ch7.render`, which
        :func:`mrsuspension.report.ch7.validate_chapter7` passes). Without it only the
        numbers and the ``time`` files are written.
    corner : str, optional
        A half or full car's rig corner (default: the first). A vehicle is compared on
        ``time`` only: ``what`` must be every comparison (the default: read as those
        that apply) or ``time``, ``cases`` the scenario's and ``masses`` its own.

    Returns
    -------
    dict
        Every number (as written to ``validation.json``).

    Raises
    ------
    ValidationError
        For an unknown comparison or case, a bad frequency or mass, or an unpaced
        network rig.

    Examples
    --------
    >>> from mrsuspension.excitation import Harmonic
    >>> from mrsuspension.hil import ideal_rig
    >>> sim = Simulation(Harmonic(1.5, 0.02))
    >>> data = validate_chapter7(
    ...     sim, ideal_rig(sim.damper), what=["pulse"], masses=[563, 703], rate=500.0
    ... )
    >>> sorted(data["pulse"]), data["pulse"]["scenario@703kg"]["sprung_mass"]
    (['scenario@563kg', 'scenario@703kg'], 703.0)
    """
    what = parse_what(list(what))
    cases = parse_cases(list(cases))
    frequencies = parse_frequencies(list(frequencies))
    mass_list = parse_masses(None if masses is None else list(masses))
    if has_corners(sim):
        return _validate_vehicle(
            sim, rig, out, what=what, cases=cases, masses=mass_list, duration=duration,
            rate=rate, model_dt=model_dt, limits=limits, realtime=realtime, render=render,
            corner=corner,
        )  # fmt: skip
    if corner is not None:
        raise ValidationError(
            f"--corner {corner!r}: a quarter-car scenario has no corners (half and full cars do)"
        )
    mass_list = mass_list or (sim.vehicle.sprung_mass,)
    several = len(mass_list) > 1
    # the vehicles first: a mass the vehicle refuses fails before any run
    vehicles = {m: sim.vehicle.with_(sprung_mass=m) for m in mass_list}
    if not (isinstance(amplitude, int | float) and 0.0 < amplitude <= 0.1):
        raise ValidationError(f"amplitude must be in (0, 0.1] m; got {amplitude!r}")
    mode, pacing = _pacing(rig, realtime, rate)
    out_dir = Path(out) if out is not None else None
    if out_dir is not None:
        out_dir.mkdir(parents=True, exist_ok=True)
    kw: dict[str, Any] = {"model_dt": model_dt, "limits": limits, "realtime": mode}
    data: dict[str, Any] = {
        "pacing": pacing,
        "realtime": mode,
        "rate": rate,
        "rig": _clean(rig.describe()),
        "scenario": sim.describe(),
        "what": list(what),
        "cases": list(cases),
        "masses": list(mass_list),
    }
    figures: dict[str, list[str]] = {}
    pulses: dict[str, Any] = {}
    roads: dict[str, Any] = {}

    def entries() -> list[tuple[str, str, float, Simulation]]:
        """(key, case, mass, simulation) of every (case, mass) pair."""
        return [
            (_entry_key(c, m, several), c, m,
             case_simulation(dataclasses.replace(sim, vehicle=vehicles[m]), c))
            for c in cases
            for m in mass_list
        ]  # fmt: skip

    if "time" in what:
        from mrsuspension.hil.validate import validate

        reports: dict[str, Any] = {}
        figures["time"] = []
        for m in mass_list:
            where = out_dir / mass_tag(m) if out_dir is not None and several else out_dir
            report = validate(
                dataclasses.replace(sim, vehicle=vehicles[m]), rig, duration=duration,
                rate=rate, out=where, model_dt=model_dt, limits=limits, realtime=mode,
            )  # fmt: skip
            reports[_entry_key("scenario", m, several)] = {
                **report.describe(),
                "sprung_mass": m,
            }
            if out_dir is not None:
                figures["time"] += [p.relative_to(out_dir).as_posix() for p in report.figures]
        data["time"] = reports if several else next(iter(reports.values()))
    if "frequency" in what:
        data["frequency"] = {
            key: {
                "case": c,
                "sprung_mass": m,
                **frequency_response(s, rig, frequencies, amplitude, rate, **kw),
            }
            for key, c, m, s in entries()
        }
    if "pulse" in what:
        for key, c, m, s in entries():
            pulses[key] = {"case": c, "sprung_mass": m, **pulse_response(s, rig, rate, **kw)}
        data["pulse"] = {c: {k: v for k, v in r.items() if k != "_pair"} for c, r in pulses.items()}
    if "road" in what:
        road = default_road(road_duration)
        for key, c, m, s in entries():
            roads[key] = {"case": c, "sprung_mass": m, **road_response(s, rig, rate, road, **kw)}
        data["road"] = roads
    if out_dir is not None:
        data["figures"] = figures
        if render is not None:
            figures.update(render(data, pulses, out_dir))
        (out_dir / "validation.json").write_text(json.dumps(_clean(data), indent=1) + "\n")
    return data


def _pacing(rig: Rig, realtime: bool | str | None, rate: float) -> tuple[str, str]:
    """The loop's scheduling mode (unpaced by default for a rig in this process) and the
    line every output starts with."""
    if realtime is None:
        realtime = "unpaced" if isinstance(rig, SimulatedRig) else "auto"
    mode = normalise_mode(realtime)
    if mode == "unpaced" and not isinstance(rig, SimulatedRig):
        raise ValidationError(
            f"realtime='unpaced' needs a rig simulated in this process; a "
            f"{type(rig).__name__} always runs paced (auto, fifo or off)"
        )
    pacing = (
        "UNPACED: as fast as possible, not real time (simulated rig)"
        if mode == "unpaced"
        else f"paced in real time at {rate:g} Hz (realtime={mode})"
    )
    return mode, pacing


def _validate_vehicle(
    sim: Any,
    rig: Rig,
    out: str | Path | None,
    *,
    what: Sequence[str],
    cases: Sequence[str],
    masses: Sequence[float],
    duration: float,
    rate: float,
    model_dt: float,
    limits: SafetyLimits | None,
    realtime: bool | str | None,
    render: Renderer | None,
    corner: str | None,
) -> dict[str, Any]:
    """:func:`validate_chapter7` of a half or full car: ``time`` only, one rig corner."""
    model = str(getattr(sim.vehicle, "model_name", "vehicle"))
    if tuple(what) != WHAT and set(what) - {"time"}:
        others = ", ".join(w for w in what if w != "time")
        raise ValidationError(
            f"--what {others}: a {model} scenario is validated on 'time' only (the "
            "frequency, pulse and road comparisons are the quarter car's, Chapter 7)"
        )
    if tuple(cases) != ("scenario",):
        raise ValidationError(
            f"--cases {','.join(cases)}: a {model} scenario is validated with its own "
            "controllers only (--cases scenario)"
        )
    if masses:
        raise ValidationError(
            f"--masses: a {model} scenario is validated at its own masses (the sprung-mass "
            "cases are the quarter car's)"
        )
    corner = check_corner(sim, corner, "--corner")
    mode, pacing = _pacing(rig, realtime, rate)
    out_dir = Path(out) if out is not None else None
    if out_dir is not None:
        out_dir.mkdir(parents=True, exist_ok=True)
    from mrsuspension.hil.validate import validate

    report = validate(
        sim, rig, duration=duration, rate=rate, out=out_dir, model_dt=model_dt,
        limits=limits, realtime=mode, corner=corner,
    )  # fmt: skip
    data: dict[str, Any] = {
        "pacing": pacing,
        "realtime": mode,
        "rate": rate,
        "rig": _clean(rig.describe()),
        "scenario": sim.describe(),
        "corner": corner,
        "what": ["time"],
        "cases": ["scenario"],
        "masses": [],
        "time": report.describe(),
    }
    if out_dir is not None:
        data["figures"] = {"time": [p.relative_to(out_dir).as_posix() for p in report.figures]}
        if render is not None:
            data["figures"].update(render(data, {}, out_dir))
        (out_dir / "validation.json").write_text(json.dumps(_clean(data), indent=1) + "\n")
    return data
