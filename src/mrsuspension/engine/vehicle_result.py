"""Results of the half and full car: :class:`VehicleResult`, its signals and measures.

The body's heave, pitch and roll and every corner's quarter-car signals (named
``"<signal>.<corner>"``), with units; the record columns of the compiled vehicle step
they come from (:mod:`mrsuspension.engine.vehicle_kernel`); the body and per-corner
measures, and the driver's seat (ISO 2631). :class:`~mrsuspension.engine.vehicle.VehicleSimulation`
produces them.
"""

from __future__ import annotations

import json
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, TypeVar, overload

import numpy as np

from mrsuspension._notebook import Measures, html_table
from mrsuspension.engine import vehicle_kernel as VX
from mrsuspension.engine.result import MEASURE_UNITS, SIGNALS, SimulationResult, controller_text
from mrsuspension.errors import ValidationError, check_range, unknown_name

if TYPE_CHECKING:
    import xarray as xr
    from matplotlib.figure import Figure

    from mrsuspension.measures import RoadPeak

__all__ = [
    "BODY_MEASURES",
    "BODY_SIGNALS",
    "DRIVER_SEAT",
    "SEAT_MEASURES",
    "VEHICLE_CORNER_SIGNALS",
    "VEHICLE_MEASURE_UNITS",
    "VehicleResult",
    "WithSeatMeasures",
]

_A = TypeVar("_A")  # the Axes a plot(..., ax=...) draws into and returns

#: Body signals of a vehicle result: name -> (unit, description).
BODY_SIGNALS: dict[str, tuple[str, str]] = {
    "heave": ("m", "body heave at the centre of gravity (up)"),
    "pitch": ("rad", "body pitch (nose down +, ISO 8855)"),
    "roll": ("rad", "body roll (left side up +, ISO 8855)"),
    "heave_dot": ("m/s", "heave velocity"),
    "pitch_dot": ("rad/s", "pitch rate"),
    "roll_dot": ("rad/s", "roll rate"),
    "heave_ddot": ("m/s^2", "heave acceleration"),
    "pitch_ddot": ("rad/s^2", "pitch acceleration"),
    "roll_ddot": ("rad/s^2", "roll acceleration"),
}
BODY_COLUMNS = {
    "heave": VX.RB_Z, "pitch": VX.RB_PITCH, "roll": VX.RB_ROLL, "heave_dot": VX.RB_VZ,
    "pitch_dot": VX.RB_VPITCH, "roll_dot": VX.RB_VROLL, "heave_ddot": VX.RB_AZ,
    "pitch_ddot": VX.RB_APITCH, "roll_ddot": VX.RB_AROLL,
}  # fmt: skip
#: Per-corner signals (named ``"<signal>.<corner>"``) and their quarter-car names.
CORNER_COLUMNS = {
    "z_s": VX.RC_ZS, "z_s_dot": VX.RC_VS, "z_s_ddot": VX.RC_AS, "z_u": VX.RC_ZU, "z_u_dot": VX.RC_VU,
    "z_u_ddot": VX.RC_AU, "z_r": VX.RC_ZR, "z_r_dot": VX.RC_VR, "F_d": VX.RC_FD, "F_T": VX.RC_FT,
    "i_d": VX.RC_ID, "i_z": VX.RC_IZ, "z_c": VX.RC_ZC, "F_target": VX.RC_TARGET, "v_m": VX.RC_VM,
    "z_s0": VX.RC_Z0,
}  # fmt: skip
#: Body measures of a vehicle result (:meth:`VehicleResult.measures`): name -> (signal,
#: unit); the RMS of the signal over the record (``roll_ddot_rms``: the full car only).
BODY_MEASURES: dict[str, tuple[str, str]] = {
    "heave_ddot_rms": ("heave_ddot", "m/s^2"),
    "pitch_ddot_rms": ("pitch_ddot", "rad/s^2"),
    "roll_ddot_rms": ("roll_ddot", "rad/s^2"),
}


@dataclass(frozen=True, repr=False)  # the short repr of SimulationResult
class VehicleResult(SimulationResult):
    """Time histories of a half- or full-car run: body and per-corner signals with units.

    Body signals are :data:`BODY_SIGNALS` (``heave``, ``pitch``, ``roll`` and their
    rates and accelerations); every corner has the quarter car's signals (``z_s`` the
    body at the corner, ``z_u``, ``z_r``, ``x_d`` the stroke, ``v_d``, ``F_d``, ``F_T``,
    ``i_d``, ...) named ``"<signal>.<corner>"``, e.g. ``result["F_T.rear_left"]``.
    :meth:`corner` gives one corner as a quarter-car
    :class:`~mrsuspension.engine.result.SimulationResult` (with its measures).
    ``to_pandas`` has one column per signal (``df["F_T.rear_left"]``, units in
    ``df.attrs["units"]``); ``to_xarray`` stacks the corners along a ``corner``
    dimension (``ds["F_T"].sel(corner="rear_left")``); ``save`` and ``load`` keep the
    corners.
    """

    corners: tuple[str, ...] = ()
    corner_scenarios: Mapping[str, dict[str, Any]] = field(default_factory=dict)

    def _model_text(self) -> str:
        """The vehicle, its corners and dampers, e.g. ``"full-car (4 corners), wang-symmetric dampers"``."""
        model = str(self.scenario.get("vehicle", {}).get("model", "vehicle"))
        dampers = {
            str(cs.get("damper", {}).get("model"))
            for cs in self.corner_scenarios.values()
            if cs.get("damper", {}).get("model")
        }
        text = f"{model} ({len(self.corners)} corners)"
        return text + (f", {', '.join(sorted(dampers))} dampers" if dampers else "")

    def _html_measures(self) -> str:
        """The measures for the HTML summary; the body's alone when the corners' fail."""
        try:
            return self.measures()._repr_html_()
        except Exception as exc:  # e.g. a harmonic record too short for its steady window
            units = {k: u for k, (_, u) in BODY_MEASURES.items()}
            body = Measures(self._body_measures(), units=units)._repr_html_()
            return body + html_table([("corner measures", f"not available: {exc}")])

    def _body_measures(self) -> dict[str, float]:
        """The RMS of the body accelerations (:data:`BODY_MEASURES`)."""
        out: dict[str, float] = {}
        for name, (signal, _) in BODY_MEASURES.items():
            if signal == "roll_ddot" and len(self.corners) < 4:
                continue  # a half car has no roll
            values = np.asarray(self.signals[signal], dtype=float)
            out[name] = float(np.sqrt(np.mean(values * values)))
        return out

    def _controller_text(self) -> str:
        """The vehicle's controller, or the corners' (one text when they agree)."""
        own = controller_text(self.scenario)
        if own:
            return own
        texts = {c: controller_text(cs) for c, cs in self.corner_scenarios.items()}
        if len(set(texts.values())) == 1:
            return next(iter(texts.values()))
        return "; ".join(f"{c}: {t}" for c, t in texts.items() if t)

    def corner(self, name: str) -> SimulationResult:
        """One corner as a quarter-car result (``z_s`` is the body's motion there).

        Examples
        --------
        >>> from mrsuspension.engine.vehicle import VehicleSimulation
        >>> from mrsuspension.excitation import Harmonic, WheelRoads
        >>> from mrsuspension.vehicle import HalfCar
        >>> sim = VehicleSimulation(HalfCar(), WheelRoads.in_phase(Harmonic(2.0, 0.01), "half-car"))
        >>> front = sim.run(0.5, dt=2e-4).corner("front")
        >>> float(front.time[-1]), "F_T" in front
        (0.5, True)
        """
        if name not in self.corners:
            raise unknown_name("corner", str(name), self.corners)
        signals = {
            k.split(".")[0]: v
            for k, v in self.signals.items()
            if k.endswith(f".{name}") and k.split(".")[0] in SIGNALS
        }
        return SimulationResult(
            time=self.time, signals=signals, scenario=dict(self.corner_scenarios[name]), dt=self.dt
        )

    def to_xarray(self) -> xr.Dataset:
        """The signals as an xarray Dataset over ``time`` and ``corner``, CF-style.

        Body signals have the dimension ``time``; every per-corner signal is one
        variable by its quarter-car name with the dimensions ``("time", "corner")``
        (``ds["F_T"].sel(corner="rear")``). Every variable carries ``units`` and
        ``long_name``; the scenario is a JSON attribute.

        Examples
        --------
        >>> from mrsuspension.engine.vehicle import VehicleSimulation
        >>> from mrsuspension.excitation import Harmonic, WheelRoads
        >>> from mrsuspension.vehicle import HalfCar
        >>> sim = VehicleSimulation(HalfCar(), WheelRoads.in_phase(Harmonic(2.0, 0.01), "half-car"))
        >>> ds = sim.run(0.1).to_xarray()
        >>> ds["F_T"].dims, ds["F_T"].attrs["long_name"], ds["pitch"].attrs["units"]
        (('time', 'corner'), 'tire force (total, 0 when lifted off)', 'rad')
        >>> ds["corner"].values.tolist()
        ['front', 'rear']
        """
        import xarray as xr

        per_corner: dict[str, dict[str, np.ndarray]] = {}
        body: dict[str, np.ndarray] = {}
        for key, values in self.signals.items():
            base, dot, corner = key.partition(".")
            if dot and corner in self.corners:
                per_corner.setdefault(base, {})[corner] = values
            else:
                body[key] = values
        data_vars: dict[str, Any] = {}
        for key, values in body.items():
            attrs = {"units": self.units.get(key, ""), "long_name": _signal_name(key)}
            data_vars[key] = ("time", values, attrs)
        blank = np.full(self.time.size, np.nan)
        for base, by_corner in per_corner.items():
            stack = np.column_stack([by_corner.get(c, blank) for c in self.corners])
            unit = next(self.units[f"{base}.{c}"] for c in by_corner if f"{base}.{c}" in self.units)
            attrs = {"units": unit, "long_name": _signal_name(base)}
            data_vars[base] = (("time", "corner"), stack, attrs)
        coords = {
            "time": ("time", self.time, {"units": "s", "long_name": "time"}),
            "corner": ("corner", list(self.corners), {"long_name": "wheel corner"}),
        }
        ds = xr.Dataset(data_vars, coords=coords)
        ds.attrs["scenario"] = json.dumps(self.scenario, default=str)
        ds.attrs["dt"] = self.dt
        ds.attrs["corner_scenarios"] = json.dumps(self.corner_scenarios, default=str)
        return ds

    @classmethod
    def _loaded(cls, meta: Mapping[str, Any], signals: Mapping[str, Any]) -> dict[str, Any]:
        corners = meta.get("corners")
        if corners is None:  # a file without the list: the corners its signals name
            names = [k.partition(".")[2] for k in signals if "." in k]
            corners = list(dict.fromkeys(names))
        return {
            "corners": tuple(str(c) for c in corners),
            "corner_scenarios": dict(meta.get("corner_scenarios", {})),
        }

    def _file_metadata(self) -> dict[str, Any]:
        return {"corners": list(self.corners), "corner_scenarios": dict(self.corner_scenarios)}

    @overload
    def plot(
        self, signals: tuple[str, ...] = ..., title: str | None = ..., *, ax: None = None
    ) -> Figure: ...
    @overload
    def plot(self, signals: tuple[str, ...] = ..., title: str | None = ..., *, ax: _A) -> _A: ...
    def plot(
        self,
        signals: tuple[str, ...] = ("heave_ddot", "pitch_ddot", "roll_ddot"),
        title: str | None = None,
        *,
        ax: Any = None,
    ) -> Any:
        """Time histories of some signals, one panel each (default: body accelerations).

        As :meth:`SimulationResult.plot <mrsuspension.engine.result.SimulationResult.plot>`:
        a new pyplot-free Figure, or drawn into ``ax`` (one Axes or one per signal) and
        ``ax`` returned.
        """
        return super().plot(signals, title=title, ax=ax)

    def measures(self, **kwargs: Any) -> Measures:
        """The body's RMS accelerations (:data:`BODY_MEASURES`), then every corner's
        quarter-car measures, keyed ``"<measure>.<corner>"``, with their units
        (a :class:`~mrsuspension._notebook.Measures`).

        Takes the keywords of :meth:`SimulationResult.measures
        <mrsuspension.engine.result.SimulationResult.measures>`.

        Examples
        --------
        >>> from mrsuspension.engine.vehicle import VehicleSimulation
        >>> from mrsuspension.excitation import Harmonic, WheelRoads
        >>> from mrsuspension.vehicle import HalfCar
        >>> sim = VehicleSimulation(HalfCar(), WheelRoads.in_phase(Harmonic(5.0, 0.005), "half-car"))
        >>> m = sim.run().measures()  # the harmonic's own duration (steady-state rule)
        >>> list(m)[:3], m.units["pitch_ddot_rms"], m.units["mean_current.rear"]
        (['heave_ddot_rms', 'pitch_ddot_rms', 'T_as.front'], 'rad/s^2', 'A')
        """
        out: dict[str, Any] = self._body_measures()
        for c in self.corners:
            for k, v in self.corner(c).measures(**kwargs).items():
                out[f"{k}.{c}"] = v
        return Measures(
            out, units={**MEASURE_UNITS, **{k: u for k, (_, u) in BODY_MEASURES.items()}}
        )

    def vehicle_measures(
        self,
        *,
        seat: Mapping[str, float] | None = None,
        purpose: str = "comfort",
        resistance: float | None = None,
        start: float = 0.0,
    ) -> Measures:
        """Measures of the whole vehicle, with units in :data:`VEHICLE_MEASURE_UNITS`
        (a :class:`~mrsuspension._notebook.Measures`: ``m.units`` holds them).

        Body: ``heave_ddot_rms`` [m/s^2], ``pitch_ddot_rms`` and ``roll_ddot_rms``
        [rad/s^2] (the full car only); the seat (ISO 2631-1,
        :func:`~mrsuspension.measures.vehicle.seat_vibration`): ``seat_total`` (the
        vibration total value of ``purpose``) and ``seat_<axis>`` per axis
        (``seat_z`` is the Wk-weighted vertical RMS); per corner ``"<name>.<corner>"``:
        ``DLC``, ``lift_off_time`` [s], ``rms_travel`` and ``peak_to_peak_travel`` [m],
        ``coil_energy`` [J] (a corner whose damper takes no current, e.g. a linear one,
        has none); and ``coil_energy`` summed over the corners.

        Parameters
        ----------
        seat : mapping, optional
            ``{"x": ..., "y": ..., "height": ...}`` [m] from the CG (forward, left, up),
            keys left out from :data:`DRIVER_SEAT` (the default: the driver's seat).
        purpose : {"comfort", "health"}
            The ISO 2631-1 axis factors of ``seat_total``.
        resistance : float, optional
            Coil resistance [ohm] (default :data:`~mrsuspension.measures.vehicle.COIL_RESISTANCE`).
        start : float
            Skip the record before this time [s] (a start-up transient).

        Examples
        --------
        >>> from mrsuspension.engine.vehicle import VehicleSimulation
        >>> from mrsuspension.excitation.wheels import WheelRoads
        >>> from mrsuspension.vehicle import FullCar
        >>> car = FullCar()
        >>> road = WheelRoads.bump("left", 0.03, 0.5, (car.wheelbase, car.front_track), position=1.0)
        >>> m = VehicleSimulation(car, road).run(1.0, dt=2e-4).vehicle_measures()
        >>> m["roll_ddot_rms"] > 0.0, m.units["lift_off_time.front_left"]
        (True, 's')
        """
        from mrsuspension.dampers import takes_current
        from mrsuspension.measures import vehicle as MV

        place = dict(DRIVER_SEAT)
        if seat is not None:
            for key in seat:
                if key not in DRIVER_SEAT:
                    raise unknown_name("seat coordinate", str(key), tuple(DRIVER_SEAT))
            place.update({k: float(v) for k, v in seat.items()})
        start = float(check_range("start", start, 0.0, float(self.time[-1]), unit="s",
                                  high_inclusive=False))  # fmt: skip
        keep = self.time >= start - 1e-12
        if np.count_nonzero(keep) < 2:
            raise ValidationError(f"start = {start:g} s leaves fewer than 2 samples")
        fs = 1.0 / float(self.time[1] - self.time[0])

        def sig(name: str) -> np.ndarray:
            return np.asarray(self.signals[name])[keep]

        out: dict[str, float] = {}
        for name in ("heave_ddot", "pitch_ddot", "roll_ddot")[: 3 if len(self.corners) == 4 else 2]:
            out[f"{name}_rms"] = float(np.sqrt(np.mean(sig(name) ** 2)))
        sv = MV.seat_vibration(
            sig("heave_ddot"), sig("pitch_ddot"), sig("roll_ddot"), fs,
            x=place["x"], y=place["y"], height=place["height"], purpose=purpose,
        )  # fmt: skip
        out["seat_total"] = sv.total
        for axis, value in sv.weighted_rms.items():
            out[f"seat_{axis}"] = value
        corners = self.corners
        dlc = MV.wheel_dlc({c: sig(f"F_T.{c}") for c in corners})
        lift = MV.wheel_lift_off_time({c: sig(f"F_T.{c}") for c in corners}, fs)
        travel = MV.wheel_suspension_travel({c: sig(f"x_d.{c}") for c in corners})
        r = MV.COIL_RESISTANCE if resistance is None else resistance
        driven = [c for c in corners if takes_current(self.corner_scenarios[c].get("damper"))]
        energy = MV.wheel_coil_energy({c: sig(f"i_d.{c}") for c in driven}, fs, r) if driven else {}
        for c in corners:
            out[f"DLC.{c}"] = dlc[c]
            out[f"lift_off_time.{c}"] = lift[c]
            out[f"rms_travel.{c}"] = travel[c].rms
            out[f"peak_to_peak_travel.{c}"] = travel[c].peak_to_peak
            if c in energy:  # a damper that takes no current has no coil
                out[f"coil_energy.{c}"] = energy[c]
        out["coil_energy"] = float(sum(energy.values()))
        return Measures(out, units=VEHICLE_MEASURE_UNITS)


#: Per-corner signals of a vehicle only: name -> (unit, description).
VEHICLE_CORNER_SIGNALS: dict[str, tuple[str, str]] = {
    "z_s_dot_sensed": (
        "m/s",
        "body velocity the controller used (true, or estimated; held over the step)",
    ),
}
SENSED_COLUMNS = {"z_s_dot_sensed": VX.RC_VSENSE}

#: Default seat of :meth:`VehicleResult.vehicle_measures`: the driver's, [m] from the
#: CG (ISO 8855: x forward, y left, height above the pitch and roll axes). An assumption,
#: not a measured set: a left-hand-drive passenger car's front seats sit near the CG
#: lengthwise, the driver about half a seat spacing (0.35 m) left of the centre line and
#: 0.5 m above the axes. Give your car's seat where you know it.
DRIVER_SEAT: dict[str, float] = {"x": 0.0, "y": 0.35, "height": 0.5}

#: Units of :meth:`VehicleResult.vehicle_measures` (per-corner names without the corner).
VEHICLE_MEASURE_UNITS: dict[str, str] = {
    "heave_ddot_rms": "m/s^2",
    "pitch_ddot_rms": "rad/s^2",
    "roll_ddot_rms": "rad/s^2",
    "seat_total": "m/s^2",
    "seat_x": "m/s^2",
    "seat_y": "m/s^2",
    "seat_z": "m/s^2",
    "seat_rx": "rad/s^2",
    "seat_ry": "rad/s^2",
    "DLC": "-",
    "lift_off_time": "s",
    "rms_travel": "m",
    "peak_to_peak_travel": "m",
    "coil_energy": "J",
}


def _signal_name(name: str) -> str:
    """The description of a body or quarter-car signal (the name itself when unknown)."""
    for table in (BODY_SIGNALS, SIGNALS, VEHICLE_CORNER_SIGNALS):
        if name in table:
            return table[name][1]
    return name


#: The seat's ISO 2631-1 measures of a half or full car (:meth:`VehicleResult.vehicle_measures`
#: at :data:`DRIVER_SEAT`, purpose "comfort", over the whole record): name -> (unit,
#: description). Studies (``[study] measures``) and the optimiser (``[objective] weights``)
#: report them when asked, not by default: a run that reports them keeps its body's time
#: history (the weighting filters need it), where the other measures are reduced in the
#: kernel.
SEAT_MEASURES: dict[str, tuple[str, str]] = {
    "seat_total": ("m/s^2", "vibration total value at the seat (ISO 2631-1, comfort)"),
    "seat_x": ("m/s^2", "Wd-weighted rms fore-aft seat acceleration (ISO 2631-1)"),
    "seat_y": ("m/s^2", "Wd-weighted rms lateral seat acceleration (ISO 2631-1)"),
    "seat_z": ("m/s^2", "Wk-weighted rms vertical seat acceleration (ISO 2631-1)"),
    "seat_rx": ("rad/s^2", "We-weighted rms seat roll acceleration (ISO 2631-1)"),
    "seat_ry": ("rad/s^2", "We-weighted rms seat pitch acceleration (ISO 2631-1)"),
}


@dataclass(frozen=True)
class WithSeatMeasures:
    """A batch reducer (picklable): a run's measures and its seat's (:data:`SEAT_MEASURES`).

    ``result.measures(road_peak=...)`` plus, for a half or full car, the seat measures of
    :meth:`VehicleResult.vehicle_measures` (the driver's seat, comfort), with their units;
    a run without a seat (the quarter car) gives its measures alone. Given to
    :func:`~mrsuspension.engine.batch.run_batch`, each run keeps its time history.

    Examples
    --------
    >>> from mrsuspension.excitation import RoadProfile, WheelRoads
    >>> from mrsuspension.engine.vehicle import VehicleSimulation
    >>> from mrsuspension.vehicle import HalfCar
    >>> road = RoadProfile.from_options({"iso_class": "C", "length": 12.0})
    >>> res = VehicleSimulation(HalfCar(), WheelRoads.from_excitation(road, HalfCar(), 50.0)).run(0.5)
    >>> m = WithSeatMeasures()(res)
    >>> m["seat_z"] == res.vehicle_measures()["seat_z"], m.units["seat_z"], "DLC.rear" in m
    (True, 'm/s^2', True)
    """

    road_peak: RoadPeak = "after-onset"

    def __call__(self, result: SimulationResult) -> Measures:
        out = result.measures(road_peak=self.road_peak)
        if not isinstance(result, VehicleResult):
            return out
        seat = result.vehicle_measures()
        values = {**out, **{k: seat[k] for k in SEAT_MEASURES}}
        return Measures(
            values, units={**out.units, **{k: u for k, (u, _) in SEAT_MEASURES.items()}}
        )
