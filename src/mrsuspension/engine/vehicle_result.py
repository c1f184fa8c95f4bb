"""Results of the half and full car: :class:`VehicleResult`, its signals and measures.

The body's heave, pitch and roll and every corner's quarter-car signals (named
``"<signal>.<corner>"``), with units; the record columns of the compiled vehicle step
they come from (:mod:`mrsuspension.engine.vehicle_kernel`); the body and per-corner
measures, and the driver's seat (ISO 2631). :class:`~mrsuspension.engine.vehicle.VehicleSimulation`
produces them.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np

from mrsuspension.engine import vehicle_kernel as VX
from mrsuspension.engine.result import SIGNALS, SimulationResult
from mrsuspension.errors import ValidationError, check_range, unknown_name

if TYPE_CHECKING:
    import xarray as xr
    from matplotlib.figure import Figure

__all__ = [
    "BODY_MEASURES",
    "BODY_SIGNALS",
    "DRIVER_SEAT",
    "VEHICLE_CORNER_SIGNALS",
    "VEHICLE_MEASURE_UNITS",
    "VehicleResult",
]

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


@dataclass(frozen=True)
class VehicleResult(SimulationResult):
    """Time histories of a half- or full-car run: body and per-corner signals with units.

    Body signals are :data:`BODY_SIGNALS` (``heave``, ``pitch``, ``roll`` and their
    rates and accelerations); every corner has the quarter car's signals (``z_s`` the
    body at the corner, ``z_u``, ``z_r``, ``x_d`` the stroke, ``v_d``, ``F_d``, ``F_T``,
    ``i_d``, ...) named ``"<signal>.<corner>"``, e.g. ``result["F_T.rear_left"]``.
    :meth:`corner` gives one corner as a quarter-car
    :class:`~mrsuspension.engine.result.SimulationResult` (with its measures). Exports
    (``to_pandas``, ``to_xarray``, ``save``) are the quarter car's.
    """

    corners: tuple[str, ...] = ()
    corner_scenarios: Mapping[str, dict[str, Any]] = field(default_factory=dict)

    def __repr__(self) -> str:
        return f"VehicleResult({self.time.size} samples, {self.time[-1]:.3g} s, corners={self.corners})"

    def corner(self, name: str) -> SimulationResult:
        """One corner as a quarter-car result (``z_s`` is the body's motion there).

        Examples
        --------
        >>> from mrsuspension.engine.vehicle import SameRoadAtEveryWheel, VehicleSimulation
        >>> from mrsuspension.excitation import Harmonic
        >>> from mrsuspension.vehicle import HalfCar
        >>> sim = VehicleSimulation(HalfCar(), SameRoadAtEveryWheel(Harmonic(2.0, 0.01), ("front", "rear")))
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
        """The signals as an xarray Dataset over ``time``, with units and descriptions.

        Examples
        --------
        >>> from mrsuspension.engine.vehicle import SameRoadAtEveryWheel, VehicleSimulation
        >>> from mrsuspension.excitation import Harmonic
        >>> from mrsuspension.vehicle import HalfCar
        >>> sim = VehicleSimulation(HalfCar(), SameRoadAtEveryWheel(Harmonic(2.0, 0.01), ("front", "rear")))
        >>> ds = sim.run(0.1).to_xarray()
        >>> ds["F_T.rear"].attrs["long_name"], ds["pitch"].attrs["units"]
        ('tire force (total, 0 when lifted off) at rear', 'rad')
        """
        ds = super().to_xarray()
        for name in ds.data_vars:
            key = str(name)
            if key in BODY_SIGNALS:
                ds[key].attrs["long_name"] = BODY_SIGNALS[key][1]
            elif "." in key:
                base, corner = key.split(".", 1)
                if base in SIGNALS:
                    ds[key].attrs["long_name"] = f"{SIGNALS[base][1]} at {corner}"
                elif base in VEHICLE_CORNER_SIGNALS:
                    ds[key].attrs["long_name"] = f"{VEHICLE_CORNER_SIGNALS[base][1]} at {corner}"
        return ds

    def plot(
        self,
        signals: tuple[str, ...] = ("heave_ddot", "pitch_ddot", "roll_ddot"),
        title: str | None = None,
    ) -> Figure:
        """Time histories of some signals, one panel each (default: body accelerations)."""
        return super().plot(signals, title=title)

    def measures(self, **kwargs: Any) -> dict[str, Any]:
        """The body's RMS accelerations (:data:`BODY_MEASURES`), then every corner's
        quarter-car measures, keyed ``"<measure>.<corner>"``.

        Takes the keywords of :meth:`SimulationResult.measures
        <mrsuspension.engine.result.SimulationResult.measures>`.

        Examples
        --------
        >>> from mrsuspension.engine.vehicle import SameRoadAtEveryWheel, VehicleSimulation
        >>> from mrsuspension.excitation import Harmonic
        >>> from mrsuspension.vehicle import HalfCar
        >>> sim = VehicleSimulation(HalfCar(), SameRoadAtEveryWheel(Harmonic(5.0, 0.005), ("front", "rear")))
        >>> list(sim.run().measures())[:3]  # the harmonic's own duration (steady-state rule)
        ['heave_ddot_rms', 'pitch_ddot_rms', 'T_as.front']
        """
        out: dict[str, Any] = {}
        for name, (signal, _) in BODY_MEASURES.items():
            if signal == "roll_ddot" and len(self.corners) < 4:
                continue  # a half car has no roll
            values = np.asarray(self.signals[signal], dtype=float)
            out[name] = float(np.sqrt(np.mean(values * values)))
        for c in self.corners:
            for k, v in self.corner(c).measures(**kwargs).items():
                out[f"{k}.{c}"] = v
        return out

    def vehicle_measures(
        self,
        *,
        seat: Mapping[str, float] | None = None,
        purpose: str = "comfort",
        resistance: float | None = None,
        start: float = 0.0,
    ) -> dict[str, float]:
        """Measures of the whole vehicle, with units in :data:`VEHICLE_MEASURE_UNITS`.

        Body: ``heave_ddot_rms`` [m/s^2], ``pitch_ddot_rms`` and ``roll_ddot_rms``
        [rad/s^2] (the full car only); the seat (ISO 2631-1,
        :func:`~mrsuspension.measures.vehicle.seat_vibration`): ``seat_total`` (the
        vibration total value of ``purpose``) and ``seat_<axis>`` per axis
        (``seat_z`` is the Wk-weighted vertical RMS); per corner ``"<name>.<corner>"``:
        ``DLC``, ``lift_off_time`` [s], ``rms_travel`` and ``peak_to_peak_travel`` [m],
        ``coil_energy`` [J]; and ``coil_energy`` summed over the corners.

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
        >>> from mrsuspension.engine.vehicle import SameRoadAtEveryWheel, VehicleSimulation
        >>> from mrsuspension.excitation.wheels import WheelRoads
        >>> from mrsuspension.vehicle import FullCar
        >>> car = FullCar()
        >>> road = WheelRoads.bump("left", 0.03, 0.5, (car.wheelbase, car.front_track), position=1.0)
        >>> m = VehicleSimulation(car, road).run(1.0, dt=2e-4).vehicle_measures()
        >>> m["roll_ddot_rms"] > 0.0, VEHICLE_MEASURE_UNITS["lift_off_time"]
        (True, 's')
        """
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
        energy = MV.wheel_coil_energy({c: sig(f"i_d.{c}") for c in corners}, fs, r)
        for c in corners:
            out[f"DLC.{c}"] = dlc[c]
            out[f"lift_off_time.{c}"] = lift[c]
            out[f"rms_travel.{c}"] = travel[c].rms
            out[f"peak_to_peak_travel.{c}"] = travel[c].peak_to_peak
            out[f"coil_energy.{c}"] = energy[c]
        out["coil_energy"] = float(sum(energy.values()))
        return out


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
