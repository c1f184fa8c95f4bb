"""HiL on a half or full car: one corner's damper on the rig, the rest of the car simulated.

:class:`CornerPlant` is what the loop (:func:`~mrsuspension.hil.loop.run_hil`) advances
each tick for a :class:`~mrsuspension.engine.vehicle.VehicleSimulation`: the vehicle's
compiled step (:meth:`VehicleSimulation.stepper
<mrsuspension.engine.vehicle.VehicleSimulation.stepper>` with ``external=corner``, the
physics of ``VehicleSimulation.run``), with the rig corner's damper force taken from the
load cell and every other corner's damper and controller simulated. The loop sees the
rig corner as it sees a quarter car (the same channel names: ``z_s`` is the body at that
corner, ``x_d`` its stroke, ``i_d`` its controller's demand...) and records the body's
heave, pitch and roll besides (:data:`BODY_CHANNELS`).

Examples
--------
>>> from mrsuspension.scenario import Scenario
>>> sim = Scenario.load("examples/vehicles/half_car.toml").vehicle_simulations()[0]
>>> check_corner(sim, None), check_corner(sim, "rear")
('front', 'rear')
>>> check_corner(sim, "back")
Traceback (most recent call last):
...
mrsuspension.errors.ValidationError: corner = 'back' is not a corner of this half car; valid: front, rear
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from mrsuspension.control.user import raise_failure
from mrsuspension.engine.result import SimulationDiverged
from mrsuspension.engine.settings import check_memory
from mrsuspension.errors import ValidationError

__all__ = ["BODY_CHANNELS", "CornerPlant", "check_corner", "has_corners"]

#: body channels recorded after the quarter car's (:data:`~mrsuspension.hil.loop.CHANNELS`)
#: in a vehicle run, with their units
BODY_CHANNELS: tuple[tuple[str, str], ...] = (
    ("heave", "m"),  # body heave at the centre of gravity (up)
    ("pitch", "rad"),  # nose down +
    ("roll", "rad"),  # left side up +
    ("heave_ddot", "m/s^2"),
    ("pitch_ddot", "rad/s^2"),
    ("roll_ddot", "rad/s^2"),
)


def has_corners(sim: Any) -> bool:
    """Whether ``sim`` is a run of a model with corners (a half or full car), not a
    one-damper model such as the quarter car (its :class:`~mrsuspension.engine.plants.Plant`
    says).

    Examples
    --------
    >>> from mrsuspension.engine.simulate import Simulation
    >>> from mrsuspension.excitation import Harmonic
    >>> has_corners(Simulation(Harmonic(1.5, 0.01)))
    False
    """
    from mrsuspension.engine.plants import PLANTS

    model = PLANTS.get(str(getattr(sim, "model_name", "")))  # a run (not a path, a scenario)
    return model is not None and bool(model.corners)


def check_corner(sim: Any, corner: str | None, name: str = "corner") -> str:
    """The rig corner of ``sim``: ``corner``, checked, or the first corner when None.

    Raises
    ------
    ValidationError
        One line naming ``name``, the value and the vehicle's corners.
    """
    corners = tuple(sim.corners)
    if corner is None:
        return corners[0]
    if corner not in corners:
        model = getattr(sim.vehicle, "model_name", "vehicle").replace("-", " ")
        raise ValidationError(
            f"{name} = {corner!r} is not a corner of this {model}; valid: {', '.join(corners)}"
        )
    return str(corner)


class CornerPlant:
    """A half or full car advanced one loop tick at a time, one corner's damper outside.

    Parameters
    ----------
    simulation : VehicleSimulation
        The vehicle, its dampers, controllers and wheel roads.
    corner : str
        The corner whose damper is on the rig (its force is the measured one).
    dt : float
        Engine step [s] (checked for the vehicle's stability).
    n_sub : int
        Engine steps per tick.
    n_ticks : int
        Ticks of the run: every wheel's road for them is computed here, before the
        clock (``2 n_sub n_ticks + 1`` half-step samples per wheel, as
        ``VehicleSimulation.run`` samples them).

    Examples
    --------
    >>> from mrsuspension.scenario import Scenario
    >>> sim = Scenario.load("examples/vehicles/half_car.toml").vehicle_simulations()[0]
    >>> plant = CornerPlant(sim, "front", 1e-4, 10, 5)
    >>> out = plant.tick(0, 100.0, 0.0)
    >>> out["F_d"], sorted(out)[:4]
    (100.0, ['F_T', 'F_d', 'heave', 'heave_ddot'])
    """

    #: the monitor's live changes (a new quarter-car configuration) do not apply
    live_changes = False

    def __init__(self, simulation: Any, corner: str, dt: float, n_sub: int, n_ticks: int) -> None:
        from mrsuspension.hil import _vehicle_kernel as HV

        self.simulation = simulation
        self.corner = check_corner(simulation, corner)
        self.index = simulation.corners.index(self.corner)
        self.dt = float(dt)
        self.n_sub = int(n_sub)
        nc = len(simulation.corners)
        n = 2 * self.n_sub * int(n_ticks) + 1
        duration = n_ticks * n_sub * dt
        check_memory(
            duration,
            2.0 * nc * n,
            hint="shorten the duration or raise the engine step dt",
            subject=f"every wheel's road over {duration:g} s at dt = {dt:g} s",
        )
        grid = getattr(simulation.excitation, "sample_grid", None)
        if grid is not None:
            zr, zrd = grid(n, 0.5 * self.dt)
        else:
            t = np.arange(n) * (0.5 * self.dt)
            zr, zrd = simulation.excitation.displacement(t), simulation.excitation.velocity(t)
        self.zr = np.ascontiguousarray(zr, dtype=float)
        self.zrd = np.ascontiguousarray(zrd, dtype=float)
        if self.zr.shape != (nc, n) or self.zrd.shape != (nc, n):
            raise ValidationError(
                f"the wheel input must return ({nc}, {n}) arrays; got {self.zr.shape} and "
                f"{self.zrd.shape}"
            )
        if not (np.all(np.isfinite(self.zr)) and np.all(np.isfinite(self.zrd))):
            raise ValidationError("the wheel input returned a NaN or infinite road value")
        from mrsuspension._numba_cache import announce_compile

        announce_compile(HV.__file__, "corner_tick")  # a first run says why it waits
        self._kernel = HV.corner_tick
        self._names = HV.OUT_NAMES
        self._out = np.zeros(HV.OUT_SIZE)
        self.stepper = simulation.stepper(self.dt, external=self.corner)
        self.reset()

    def reset(self) -> None:
        """Static equilibrium on the roads at time 0, the internals fresh (a new run)."""
        st = self.stepper
        st.reset(self.zr[:, 0], self.zrd[:, 0])
        self.y = st.y
        self.args = st.arrays.args()
        self._scratch = np.zeros((5, self.y.size))
        self._scratch[1] = st._scratch[1]  # the rates at y (the body's acceleration signals)
        self._work = np.zeros((len(self.simulation.corners) + 1, 8))

    def road_at(self, k: int) -> tuple[float, float]:
        """The rig corner's road and road velocity at the start of tick ``k``."""
        j = 2 * self.n_sub * k
        return float(self.zr[self.index, j]), float(self.zrd[self.index, j])

    def tick(self, k: int, force: float, damping: float = 0.0) -> dict[str, float]:
        """Advance tick ``k`` with the measured ``force`` [N] (plus ``damping`` [N s/m]
        times the corner's stroke rate, the start-up ramp) held over each engine step.

        Returns the rig corner's signals (quarter-car names), its road at the tick's end
        (``z_r``, ``z_r_dot``) and the body's (:data:`BODY_CHANNELS`).

        Raises
        ------
        SimulationDiverged
            When the vehicle's state or a force leaves the physical range.
        ValidationError
            For a force that is not a finite number.
        """
        if not math.isfinite(force + damping):
            raise ValidationError(
                f"the damper force at the rig corner must be finite; got {force!r} N"
            )
        status, idx, value, steps = self._kernel(
            self.y, self.dt, self.n_sub, self.zr, self.zrd, 2 * self.n_sub * k, self.index,
            force, damping, self.args, self._scratch, self._work, self._out,
        )  # fmt: skip
        raise_failure()  # a Python control law that raised during the tick
        if status:
            t = (k * self.n_sub + steps) * self.dt
            named = getattr(self.simulation, "_divergence", None)  # names the state or force
            if named is not None:
                raise named(status, t, idx, value, self.dt)
            raise SimulationDiverged(
                f"vehicle model diverged at t = {t:.4f} s (status {status}, index {idx}: "
                f"{value:.3g})", t, "state", value,
            )  # fmt: skip
        return dict(zip(self._names, self._out.tolist(), strict=True))

    def describe(self) -> dict[str, Any]:
        """The rig corner and the vehicle (plain data, for the recording's metadata)."""
        return {"corner": self.corner, "corners": list(self.simulation.corners)}
