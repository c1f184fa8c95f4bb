"""Report section "Beyond the quarter car": the full car with an MR damper at every corner.

Issue 19, item 7. The quarter car of the full car's front-left corner and the full car
(:class:`~mrsuspension.vehicle.FullCar`, its published set) under three controllers:

* passive at 0 A;
* skyhook hi-lo ACM at every corner (:class:`~mrsuspension.control.HiLo` policy I,
  ``mode="ACM"``, on the body's velocity at the corner);
* modal skyhook (:class:`~mrsuspension.control.modal.ModalSkyhook` with the gains of
  per-corner skyhook, ``c_s`` = 6750 N s/m as in the model reference, section 5; hi-lo
  currents per corner);

on two roads: a two-track ISO 8608 class C road (isotropic left/right coherence) at
50 km/h and a 5 cm, 0.5 m rounded bump under the left wheels only (it excites roll).
The quarter car rides the front-left wheel's road. Then the cost of estimated against
ideal velocity feedback: the same skyhook controllers with the body velocity estimated
from each corner's accelerometer (1 kHz) by a leaky integrator or a band-pass observer
set for a 10 degree phase lead at 1 Hz (:mod:`mrsuspension.control.sensing`).

* Fig V.1 / V.2: heave, pitch and roll acceleration PSDs on each road.
* Table V.1: RMS accelerations, ISO 2631-1 seat values at the driver's seat
  (:data:`~mrsuspension.engine.vehicle_result.DRIVER_SEAT`) and per-wheel DLC (also as CSV).
* Table V.2: the estimators' cost, in percent against ideal feedback, beside the
  controller's gain over passive.

Quick mode: 10 s of road, 0.2 ms steps, 500 Hz records; full mode: 20 s, 0.1 ms. All runs
in this process (about 2 s quick, 4 s full, after the kernels' compilation is cached).
"""

from __future__ import annotations

import html
import math
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any

import numpy as np

from mrsuspension._docs import doc
from mrsuspension.control import HiLo, Passive
from mrsuspension.control.modal import ModalSkyhook
from mrsuspension.control.sensing import (
    BandPassObserver,
    LeakyIntegrator,
    Sensing,
    band_pass_corner,
    leaky_integrator_tau,
)
from mrsuspension.dampers import WangSymmetric
from mrsuspension.dampers.wang import VEHICLE_VH_VARIANT
from mrsuspension.engine.simulate import Simulation
from mrsuspension.engine.vehicle import VehicleSimulation
from mrsuspension.engine.vehicle_result import DRIVER_SEAT, VehicleResult
from mrsuspension.errors import ValidationError
from mrsuspension.excitation.wheels import WheelRoads
from mrsuspension.measures.iso2631 import weighted_rms
from mrsuspension.measures.spectral import psd
from mrsuspension.measures.steady import dlc
from mrsuspension.report.toolkit import FigureRecord, subplots, table, write_csv
from mrsuspension.vehicle import FullCar

__all__ = [
    "CONTROLLERS",
    "ESTIMATORS",
    "ROADS",
    "SPEED_KMH",
    "build",
    "compute",
    "roads",
    "simulation",
]

#: vehicle speed on both roads [km/h]
SPEED_KMH = 50.0
#: the controllers compared (labels)
CONTROLLERS = ("passive 0 A", "skyhook hi-lo ACM (per corner)", "modal skyhook")
#: the roads (labels)
ROADS = ("rough road (ISO 8608 C, two-track)", "one-sided bump (left, 5 cm)")
#: the velocity estimators (labels); phase budget: 10 deg at 1 Hz, accelerometer at 1 kHz
ESTIMATORS = ("ideal", "leaky integrator", "band-pass observer")
#: accelerometer rate [Hz], the phase budget [deg] and the frequency it holds at [Hz]
ACC_FS, PHASE_BUDGET, PHASE_FREQ = 1000.0, 10.0, 1.0
_CORNER = "front_left"  # the quarter car's corner


def _settings(quick: bool) -> tuple[float, float, float]:
    """``(dt [s], rough-road duration [s], output rate [Hz])``."""
    return (2e-4, 10.0, 500.0) if quick else (1e-4, 20.0, 500.0)


def roads(car: FullCar, quick: bool) -> dict[str, WheelRoads]:
    """The two roads of :data:`ROADS` under ``car`` at :data:`SPEED_KMH`.

    Examples
    --------
    >>> r = roads(FullCar(), quick=True)
    >>> list(r) == list(ROADS), r[ROADS[1]].right is None
    (True, True)
    """
    geometry = (car.wheelbase, car.front_track)
    _, duration, _ = _settings(quick)
    length = duration * SPEED_KMH / 3.6 + 2.0 * car.wheelbase
    return {
        ROADS[0]: WheelRoads.two_track("C", geometry, SPEED_KMH, length=length, seed=1),
        ROADS[1]: WheelRoads.bump("left", 0.05, 0.5, geometry, SPEED_KMH, position=2.0),
    }


def _sensing(name: str) -> Sensing:
    if name == ESTIMATORS[1]:
        tau = leaky_integrator_tau(PHASE_FREQ, PHASE_BUDGET, fs=ACC_FS)
        return Sensing(LeakyIntegrator(tau, ACC_FS))
    if name == ESTIMATORS[2]:
        corner = band_pass_corner(PHASE_FREQ, PHASE_BUDGET, fs=ACC_FS)
        return Sensing(BandPassObserver(corner, ACC_FS))
    return Sensing()


def simulation(
    car: FullCar, road: WheelRoads, controller: str, estimator: str = "ideal"
) -> VehicleSimulation:
    """The full car on ``road`` with one of :data:`CONTROLLERS` and :data:`ESTIMATORS`.

    Examples
    --------
    >>> car = FullCar()
    >>> sim = simulation(car, roads(car, True)[ROADS[1]], CONTROLLERS[2], ESTIMATORS[1])
    >>> sim.describe()["body_control"]["law"], sim.describe()["sensing"]["velocity"]["kind"]
    ('modal-skyhook', 'leaky-integrator')
    """
    sensing = _sensing(estimator)
    if controller == CONTROLLERS[0]:
        return VehicleSimulation(car, road, controllers=Passive(), sensing=sensing)
    if controller == CONTROLLERS[1]:
        return VehicleSimulation(car, road, controllers=HiLo(1, mode="ACM"), sensing=sensing)
    x, y = car.corner_positions()
    modal = ModalSkyhook.corner_equivalent(x, y, skyhook_damping=6750.0)
    return VehicleSimulation(car, road, body_control=modal, sensing=sensing)


def _duration(road_name: str, quick: bool) -> float:
    _, duration, _ = _settings(quick)
    return duration if road_name == ROADS[0] else 3.0


def _quarter_row(car: FullCar, road: WheelRoads, controller: str, quick: bool,
                 road_name: str) -> tuple[dict[str, Any], dict[str, np.ndarray]]:  # fmt: skip
    dt, _, rate = _settings(quick)
    law = Passive() if controller == CONTROLLERS[0] else HiLo(1, mode="ACM")
    track = road.left
    if track is None:  # the section's roads all have a left track
        raise ValidationError(f"{road_name}: the quarter car needs the left track")
    sim = Simulation(
        track, car.corner_quarter_car(_CORNER), WangSymmetric(vh_variant=VEHICLE_VH_VARIANT),
        law, 0.5,
    )  # fmt: skip
    res = sim.run(_duration(road_name, quick), dt=dt, output_rate=rate)
    acc = np.asarray(res["z_s_ddot"])
    row = {
        "model": "quarter car", "road": road_name, "controller": controller, "sensing": "ideal",
        "heave RMS [m/s^2]": float(np.sqrt(np.mean(acc**2))),
        "pitch RMS [rad/s^2]": math.nan, "roll RMS [rad/s^2]": math.nan,
        "seat Wk RMS [m/s^2]": weighted_rms(acc, rate, weighting="Wk"),
        "seat total [m/s^2]": math.nan,
        **{f"DLC {c}": math.nan for c in car.corners},
    }  # fmt: skip
    row[f"DLC {_CORNER}"] = dlc(np.asarray(res["F_T"]))
    return row, {"heave_ddot": acc}


def _full_row(
    res: VehicleResult, road_name: str, controller: str, estimator: str
) -> dict[str, Any]:
    m = res.vehicle_measures()
    return {
        "model": "full car", "road": road_name, "controller": controller,
        "sensing": estimator,
        "heave RMS [m/s^2]": m["heave_ddot_rms"],
        "pitch RMS [rad/s^2]": m["pitch_ddot_rms"],
        "roll RMS [rad/s^2]": m["roll_ddot_rms"],
        "seat Wk RMS [m/s^2]": m["seat_z"], "seat total [m/s^2]": m["seat_total"],
        **{f"DLC {c}": m[f"DLC.{c}"] for c in res.corners},
    }  # fmt: skip


def compute(quick: bool, progress: Callable[[str], None] | None = None) -> dict[str, Any]:
    """Every run of the section: the table's rows, the PSD records and the estimator costs.

    Returns ``{"rows": [...], "signals": {(model, road, controller): {signal: array}},
    "costs": [...], "fs": rate, "dt": dt}``; ``costs`` rows give, per skyhook controller
    and estimator on the rough road, the percent change of the heave RMS, the Wk seat RMS
    and the mean DLC against ideal feedback, the controller's own changes against
    passive, and the heave cost as a share of the controller's heave gain (NaN when it
    gains nothing).
    """
    say = progress or (lambda _msg: None)
    dt, _, rate = _settings(quick)
    car = FullCar()
    rows: list[dict[str, Any]] = []
    signals: dict[tuple[str, str, str], dict[str, np.ndarray]] = {}
    for road_name, road in roads(car, quick).items():
        say(f"vehicles: {road_name}")
        for controller in CONTROLLERS:
            if controller != CONTROLLERS[2]:
                row, sig = _quarter_row(car, road, controller, quick, road_name)
                rows.append(row)
                signals["quarter car", road_name, controller] = sig
            res = simulation(car, road, controller).run(
                _duration(road_name, quick), dt=dt, output_rate=rate
            )
            rows.append(_full_row(res, road_name, controller, "ideal"))
            signals["full car", road_name, controller] = {
                k: np.asarray(res[k]) for k in ("heave_ddot", "pitch_ddot", "roll_ddot")
            }
    say("vehicles: estimated against ideal velocity feedback")
    road_name = ROADS[0]
    road = roads(car, quick)[road_name]

    def full(controller: str) -> dict[str, Any]:
        return next(
            r for r in rows
            if r["model"] == "full car" and r["road"] == road_name and r["controller"] == controller
        )  # fmt: skip

    def mean_dlc(r: dict[str, Any]) -> float:
        return float(np.mean([r[f"DLC {c}"] for c in car.corners]))

    def change(a: float, b: float) -> float:
        return 100.0 * (a / b - 1.0)

    passive = full(CONTROLLERS[0])
    costs: list[dict[str, Any]] = []
    heave, wk = "heave RMS [m/s^2]", "seat Wk RMS [m/s^2]"
    for controller in CONTROLLERS[1:]:
        ideal = full(controller)
        gain = change(ideal[heave], passive[heave])
        for estimator in ESTIMATORS[1:]:
            res = simulation(car, road, controller, estimator).run(
                _duration(road_name, quick), dt=dt, output_rate=rate
            )
            est = _full_row(res, road_name, controller, estimator)
            rows.append(est)
            cost = change(est[heave], ideal[heave])
            costs.append({
                "controller": controller, "estimator": estimator,
                "heave RMS change vs ideal [%]": cost,
                "seat Wk RMS change vs ideal [%]": change(est[wk], ideal[wk]),
                "mean DLC change vs ideal [%]": change(mean_dlc(est), mean_dlc(ideal)),
                "controller's heave RMS change vs passive [%]": gain,
                "controller's seat Wk RMS change vs passive [%]": change(ideal[wk], passive[wk]),
                "controller's mean DLC change vs passive [%]": change(
                    mean_dlc(ideal), mean_dlc(passive)
                ),
                "cost / gain (heave RMS) [%]": 100.0 * cost / -gain if gain < 0.0 else math.nan,
            })  # fmt: skip
    return {"rows": rows, "signals": signals, "costs": costs, "fs": rate, "dt": dt}


_PANELS = (
    ("heave_ddot", "heave acceleration", "PSD [(m/s^2)^2/Hz]"),
    ("pitch_ddot", "pitch acceleration", "PSD [(rad/s^2)^2/Hz]"),
    ("roll_ddot", "roll acceleration", "PSD [(rad/s^2)^2/Hz]"),
)
_COLOURS = dict(zip(CONTROLLERS, ("tab:blue", "tab:red", "tab:green"), strict=True))


def _psd_figure(data: dict[str, Any], road_name: str, quick: bool) -> tuple[Any, dict[str, Any]]:
    fig, axes = subplots(1, 3, 4.0, 3.4)
    fs = data["fs"]
    nperseg = 512 if road_name == ROADS[1] else (1024 if quick else 2048)
    out: dict[str, Any] = {}
    for (model, road, controller), sig in data["signals"].items():
        if road != road_name:
            continue
        label = f"{model}: {controller}"
        style = "--" if model == "quarter car" else "-"
        for ax, (key, _, _) in zip(axes[0], _PANELS, strict=True):
            if key not in sig:
                continue
            spec = psd(sig[key], fs, fs=fs, nperseg=min(nperseg, sig[key].size), warn=False)
            keep = (spec.frequency > 0.0) & (spec.frequency <= 30.0)
            ax.semilogy(
                spec.frequency[keep], spec.density[keep], style, color=_COLOURS[controller],
                lw=1.0, label=label,
            )  # fmt: skip
            out.setdefault(label, {})[key] = {
                "frequency": spec.frequency[keep].tolist(),
                "density": spec.density[keep].tolist(),
            }
    for ax, (_, title, ylabel) in zip(axes[0], _PANELS, strict=True):
        ax.set_title(title, fontsize=10)
        ax.set_xlabel("frequency [Hz]")
        ax.set_ylabel(ylabel)
        ax.grid(True, which="both", alpha=0.3)
    handles, labels = axes[0, 0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="outside lower center", ncol=3, fontsize="small")
    return fig, out


def _summary(data: dict[str, Any]) -> str:
    """What the table says, in numbers (generated, not written by hand), and why modal
    skyhook loses to passive 0 A (the analysis of docs/vehicles.md, issue 29)."""
    rows = [r for r in data["rows"] if r["model"] == "full car" and r["sensing"] == "ideal"]

    def get(road: str, controller: str, key: str) -> float:
        return float(
            next(r[key] for r in rows if r["road"] == road and r["controller"] == controller)
        )

    heave, wk = "heave RMS [m/s^2]", "seat Wk RMS [m/s^2]"
    parts = []
    for controller in CONTROLLERS[1:]:
        changes = [
            100.0 * (get(ROADS[0], controller, k) / get(ROADS[0], CONTROLLERS[0], k) - 1.0)
            for k in (heave, wk)
        ]
        parts.append(f"{controller}: heave {changes[0]:+.1f} %, seat Wk {changes[1]:+.1f} %")
    roll_bump = get(ROADS[1], CONTROLLERS[0], "roll RMS [rad/s^2]")
    why = doc("vehicles", "why-modal-skyhook-loses-to-passive-0-a-on-the-class-c-road")
    return (
        "<p>Full car on the rough road, against passive 0 A: "
        + "; ".join(parts)
        + f". The one-sided bump excites roll (passive: {roll_bump:.3g} rad/s^2 RMS).</p>"
        "<p>Modal skyhook rides worse than passive 0 A although the law is right: its "
        "signs, distribution and gains match an independent linear reference (a test "
        "checks the engine against that reference's closed-form response). The loss comes "
        "from the MR damper's band under hi-lo switching: hi-lo uses the desired corner "
        "forces only for their signs, so no gain changes the result; when the desired "
        "force is achievable the damper at 0.5 A delivers more than it, and when it is not "
        "the damper still gives its 0 A force, which on this light car is already more "
        "damping than it wants. The measured evidence (a 14-run table): "
        f"<a href='{why}'>vehicles, modal skyhook on the class C road</a>. "
        "After a transient the MR corners can also ring at 30-120 Hz: a limit cycle of "
        "the damper model's hysteresis term, not of the integrator "
        f"(<a href='{doc('damper-models')}'>damper models</a>).</p>"
    )


def build(
    folder: Path,
    quick: bool,
    progress: Callable[[str], None],
    formats: Sequence[str] = ("png",),
    check: bool = False,
) -> tuple[str, dict[str, Any]]:
    """Build the section into ``folder``; returns its HTML and its manifest entry.

    ``formats``: figure formats (PNG; SVG too with ``--svg``); ``check``: record each
    figure's layout issues (:mod:`mrsuspension.report.legibility`) in the manifest.
    """
    folder.mkdir(parents=True, exist_ok=True)
    data = compute(quick, progress)
    rows, costs = data["rows"], data["costs"]
    write_csv(folder / "vehicle_measures.csv", rows)
    write_csv(folder / "estimator_cost.csv", costs)
    figures: list[dict[str, Any]] = []
    sections: list[str] = []
    for number, road_name in (("V.1", ROADS[0]), ("V.2", ROADS[1])):
        fig, fig_data = _psd_figure(data, road_name, quick)
        rec = FigureRecord(
            number=number,
            title=f"Heave, pitch and roll acceleration PSDs: {road_name}",
            caption=(
                f"{SPEED_KMH:g} km/h, dt = {data['dt'] * 1e3:g} ms, Welch PSD of the body's "
                "accelerations at the centre of gravity. Solid: full car; dashed: the quarter "
                f"car of the {_CORNER.replace('_', '-')} corner on that wheel's road (heave "
                "only: it has no pitch or roll)."
            ),
            figure=fig,
            data=fig_data,
        )
        rec.save(folder, formats, check=check)
        entry: dict[str, Any] = {"number": rec.number, "title": rec.title, "files": rec.files}
        if rec.issues is not None:
            entry["layout issues"] = rec.issues
        figures.append(entry)
        sections.append(
            f'<figure id="{rec.slug}"><img src="vehicles/{rec.slug}.png" alt="Fig. {rec.number}">'
            f"<figcaption><b>Fig. {html.escape(rec.number)}: {html.escape(rec.title)}.</b> "
            f"{html.escape(rec.caption)}</figcaption></figure>"
        )
    seat = ", ".join(f"{k} = {v:g} m" for k, v in DRIVER_SEAT.items())
    body = (
        "<h2 id='vehicles'>Beyond the quarter car: the full car with an MR damper at every "
        "corner</h2>"
        "<p>The dissertation's first recommendation (section 8.3): carry the controllers to "
        "a vehicle with roll and pitch, and obtain the body velocity skyhook needs from "
        "measurable acceleration. The quarter car of one corner against the full car "
        f"(<a href='{doc('vehicles')}'>vehicles</a>), passive, skyhook hi-lo ACM at every corner and modal skyhook "
        "(heave, pitch and roll damped to the sky; hi-lo currents per corner), on a "
        "two-track class C road and a one-sided bump.</p>"
        + sections[0]
        + sections[1]
        + "<h3>Table V.1: RMS accelerations, seat values and per-wheel DLC</h3>"
        f"<p>Seat (ISO 2631-1, comfort factors): the driver's, {seat} from the CG. "
        "<a href='vehicles/vehicle_measures.csv'>vehicle_measures.csv</a></p>"
        + table(rows)
        + _summary(data)
        + "<h3>Table V.2: estimated against ideal velocity feedback (rough road)</h3>"
        f"<p>Body velocity from each corner's accelerometer at {ACC_FS:g} Hz, estimators set "
        f"for a {PHASE_BUDGET:g} degree phase lead at {PHASE_FREQ:g} Hz. A positive change is "
        "a loss; cost / gain compares the loss with what the controller gains over passive. "
        "<a href='vehicles/estimator_cost.csv'>estimator_cost.csv</a></p>" + table(costs)
    )
    return body, {
        "figures": figures,
        "tables": [
            {"number": "V.1", "file": "vehicles/vehicle_measures.csv", "rows": len(rows)},
            {"number": "V.2", "file": "vehicles/estimator_cost.csv", "rows": len(costs)},
        ],
        "estimator_cost": costs,
    }
