"""Running the quarter car: :class:`Simulation` (offline), :class:`Stepper` (tick by tick)
and :func:`run_many` (batches across processes)."""

from __future__ import annotations

import math
import warnings
from collections.abc import Callable, Sequence
from concurrent.futures import Executor
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Protocol

import numpy as np
import numpy.typing as npt

from mrsuspension._numba_cache import announce_compile
from mrsuspension.control import Controller, Passive
from mrsuspension.control.kernel import EST_SHARED, F_EXTERNAL, F_MODEL, P_CS, P_USER_FN
from mrsuspension.control.user import UserLaw, raise_failure
from mrsuspension.dampers import CycleRms, DamperModel, PeakVelocityEstimator, WangSymmetric
from mrsuspension.dampers import kernels as DK
from mrsuspension.dampers.wang import VEHICLE_VH_VARIANT
from mrsuspension.engine import kernel as EK
from mrsuspension.engine import lanes as LN
from mrsuspension.engine.arrays import KernelArrays
from mrsuspension.engine.contract import RunModel
from mrsuspension.engine.result import (
    SimulationDiverged,
    SimulationResult,
    VelocityClampWarning,
    warn_if_aliased,
    warn_if_clamped,
)
from mrsuspension.engine.settings import (
    DEFAULT_DT,
    RK4_LIMIT,
    RunPlan,
    RunSettings,
    check_memory,
    check_step,
    run_settings,
)
from mrsuspension.errors import ValidationError, check_range
from mrsuspension.vehicle import QuarterCar

__all__ = [
    "DEFAULT_DT",
    "KernelArrays",
    "MeasuresOf",
    "RoadInput",
    "Simulation",
    "SimulationDiverged",
    "Stepper",
    "check_inverse_damper",
    "measure_many",
    "measures_of",
    "run_many",
]

if TYPE_CHECKING:
    from mrsuspension.measures import RoadPeak


class RoadInput(Protocol):
    """What the engine needs from an excitation (see :mod:`mrsuspension.excitation`)."""

    def displacement(self, t: npt.ArrayLike) -> np.ndarray: ...
    def velocity(self, t: npt.ArrayLike) -> np.ndarray: ...
    def acceleration(self, t: npt.ArrayLike) -> np.ndarray: ...
    def describe(self) -> dict[str, Any]: ...

    @property
    def duration(self) -> float: ...


def road_grid(
    excitation: RoadInput, n: int, step: float, start: float = 0.0
) -> tuple[np.ndarray, np.ndarray]:
    """The road (z_r, z_r') at ``start + k * step``, ``k < n``: the excitation's fast grid
    if it has one."""
    grid = getattr(excitation, "sample_grid", None)
    if grid is not None:
        zr, zrd = grid(n, step, start=start) if start else grid(n, step)
    else:  # any object with displacement() and velocity() will do
        t = start + np.arange(n) * step if start else np.arange(n) * step
        zr, zrd = excitation.displacement(t), excitation.velocity(t)
    return np.ascontiguousarray(zr, dtype=float), np.ascontiguousarray(zrd, dtype=float)


_STATE_NAMES = ("z_s", "z_s_dot", "z_u", "z_u_dot", "z_s0", "z_s0_dot")
_STATE_UNITS = ("m", "m/s", "m", "m/s", "m", "m/s")


def check_inverse_damper(law: str, damper: DamperModel, where: str = "") -> None:
    """Refuse a damper the inverse model does not describe, for law ``law`` that uses it.

    The inverse model (model reference, section 2.3) is the dissertation's symmetric
    damper's: ``wang-symmetric`` without the asymmetric terms (``k5 = k6 = 0``).
    ``where`` (e.g. ``" at corner fl"``) follows the damper's name in the message.

    Examples
    --------
    >>> from mrsuspension.dampers import make_damper
    >>> check_inverse_damper("inverse-hilo", make_damper("linear"))
    Traceback (most recent call last):
    ...
    mrsuspension.errors.ValidationError: controller 'inverse-hilo' uses the inverse model (model reference, section 2.3) and needs the 'wang-symmetric' damper model; got 'linear'
    """
    symmetric_wang = isinstance(damper, WangSymmetric) and (
        damper.values.get("k5", 0.0) == 0.0 and damper.values.get("k6", 0.0) == 0.0
    )
    if not symmetric_wang:
        raise ValidationError(
            f"controller {law!r} uses the inverse model (model reference, "
            "section 2.3) and needs the 'wang-symmetric' damper model; "
            f"got {damper.name!r}{where}"
        )


@dataclass(frozen=True)
class Simulation:
    """A quarter car with a damper, a controller and a road input.

    Parameters
    ----------
    excitation : RoadInput
        Road displacement ``z_r(t)`` (up positive) with exact velocity/acceleration.
    vehicle : QuarterCar
        Vehicle parameters (nominal by default).
    damper : DamperModel
        Damper model (default: the dissertation's symmetric hysteretic model with the
        vehicle default ``vh_variant="2.13"``, see
        :data:`~mrsuspension.dampers.wang.VEHICLE_VH_VARIANT`).
    controller : Controller
        Control law (default: passive at 0 A).
    max_current : float
        Drive-current limit i_max [A] (0.5 A in simulations, 0.3 A in HiL).
    estimator : PeakVelocityEstimator, optional
        The controller's peak-velocity estimator (for the ADFG multiplier and the inverse
        model); default: the damper's own, else the 1 s ``cycle-rms`` (model reference,
        section 2.4).

    Examples
    --------
    >>> from mrsuspension.excitation import Harmonic
    >>> from mrsuspension.control import HiLo
    >>> sim = Simulation(Harmonic(1.5, 0.025), controller=HiLo(1, mode="ACM"))
    >>> result = sim.run(duration=2.0)
    >>> float(result.time[-1]), bool(result.i_d.max() <= 0.5)
    (2.0, True)
    """

    excitation: RoadInput
    vehicle: QuarterCar = field(default_factory=QuarterCar)
    damper: DamperModel = field(
        default_factory=lambda: WangSymmetric(vh_variant=VEHICLE_VH_VARIANT)
    )
    controller: Controller = field(default_factory=Passive)
    max_current: float = 0.5
    estimator: PeakVelocityEstimator | None = None

    def __post_init__(self) -> None:
        self._check_types()
        # the law attached to this plant (e.g. gains from its masses and stiffnesses)
        attached = self.controller.for_plant(self.vehicle)
        if not isinstance(attached, Controller):
            raise ValidationError(
                f"controller {self.controller.law!r}: for_plant must return a Controller; "
                f"got {attached!r}"
            )
        object.__setattr__(self, "controller", attached)
        check_range("max_current", self.max_current, 0.0, self.damper.max_current, unit="A")
        if self.controller.needs_inverse:
            check_inverse_damper(self.controller.law, self.damper)

    def _check_types(self) -> None:
        """Each argument is the object it names (a name string points to its factory)."""
        from mrsuspension.control.registry import CONTROLLERS
        from mrsuspension.dampers import DAMPERS
        from mrsuspension.errors import did_you_mean

        road = ("displacement", "velocity", "acceleration", "describe", "duration")
        if not all(hasattr(self.excitation, a) for a in road):
            raise ValidationError(
                "excitation must be a road input (e.g. Harmonic(1.5, 0.025), RoundedPulse, "
                f"IsoRoad from mrsuspension.excitation); got {self.excitation!r}"
            )
        for arg, kind, names, factory in (
            ("controller", Controller, CONTROLLERS, "mrsuspension.control.make_controller"),
            ("damper", DamperModel, DAMPERS, "mrsuspension.dampers.make_damper"),
            ("vehicle", QuarterCar, None, "mrsuspension.vehicle.QuarterCar"),
        ):
            value = getattr(self, arg)
            if isinstance(value, kind):
                continue
            hint = f"build one with {factory}(...)"
            if isinstance(value, str) and names is not None:
                hint = (
                    f"build one by name with {factory}(name);{did_you_mean(value, names)} "
                    f"Valid names: {', '.join(sorted(names))}"
                )
            raise ValidationError(f"{arg} must be a {kind.__name__} object; got {value!r}: {hint}")

    # -- helpers ---------------------------------------------------------------------
    @property
    def model_name(self) -> str:
        """``"quarter-car"``: the :class:`~mrsuspension.engine.plants.Plant` of this run."""
        return "quarter-car"

    @property
    def controller_estimator(self) -> PeakVelocityEstimator:
        """The estimator giving the controller its v_m."""
        if self.estimator is not None:
            return self.estimator
        return getattr(self.damper, "estimator", None) or CycleRms()

    def stiffness_rate(self) -> float:
        """Largest decay rate of the linearised model [1/s] (for the step-size check)."""
        car = self.vehicle
        rate = self._slope() * (1.0 / car.unsprung_mass + 1.0 / car.sprung_mass)
        rate += car.tire_damping / car.unsprung_mass + car.skyhook_damping / car.sprung_mass
        omega = math.sqrt((car.suspension_stiffness + car.tire_stiffness) / car.unsprung_mass)
        return max(rate, omega)

    def max_stable_dt(self) -> float:
        """Largest fixed step [s] that keeps RK4 stable (with a margin)."""
        return RK4_LIMIT / self.stiffness_rate()

    def check_dt(self, dt: float) -> float:
        """Validate ``dt`` (positive, at most 10 ms, and stable for this model)."""
        dt = check_step(dt)
        limit = self.max_stable_dt()
        if dt > limit:
            raise ValidationError(
                f"dt = {dt:g} s is too large for stability: the stiffest mode of this model "
                f"(damper slope up to {self._slope():.3g} N s/m on the {self.vehicle.unsprung_mass:g} kg "
                f"wheel) needs dt <= {limit:.3g} s"
            )
        return dt

    def _slope(self) -> float:
        """Largest damper (or ideal-damper) slope dF/dv [N s/m] up to max_current."""
        if self.controller.force_source == F_MODEL:
            return self.damper.max_damping_rate(self.max_current)
        return float(self.controller.params(self.max_current)[P_CS])

    def describe(self) -> dict[str, Any]:
        """Plain-data description of the scenario."""
        return {
            "vehicle": self.vehicle.describe(),
            "damper": self.damper.describe(),
            "controller": self.controller.describe(),
            "excitation": self.excitation.describe(),
            "max_current": self.max_current,
            "estimator": repr(self.controller_estimator),
            "peak_velocity_limit": getattr(self.controller_estimator, "v_max", None),
        }

    def kernel_arrays(self, dt: float, *, check_stability: bool = True) -> KernelArrays:
        """The compiled step's parameter and state arrays at step ``dt``, by name.

        Fresh states (the damper's, the estimators' and the step memory) each call. For
        :meth:`Stepper.update`, the lane kernel and benchmarks.

        Parameters
        ----------
        dt : float
            Fixed step [s].
        check_stability : bool
            Refuse a ``dt`` above the RK4 stability limit of this model (default).

        Raises
        ------
        ValidationError
            When ``dt`` is not positive, above 10 ms or (with ``check_stability``) too
            large for this model.

        Examples
        --------
        >>> from mrsuspension.excitation import Harmonic
        >>> a = Simulation(Harmonic(1.0, 0.01)).kernel_arrays(1e-4)
        >>> a.controller_params.size, a.memory.size
        (18, 44)
        """
        dt = self.check_dt(dt) if check_stability else check_step(dt)
        kern = self.damper.kernel(dt)
        est = self.controller_estimator
        shared = self.estimator is None and kern.kind == DK.WANG
        return KernelArrays(
            vehicle=self.vehicle.params(),
            force_source=self.controller.force_source,
            damper_kind=kern.kind,
            damper_params=kern.params,
            damper_state=kern.state,
            damper_estimator_kind=kern.estimator_code,
            damper_estimator_params=kern.estimator_params,
            damper_estimator_state=kern.estimator_state,
            controller_kind=self.controller.code,
            controller_params=self.controller.params(self.max_current),
            controller_estimator_kind=EST_SHARED if shared else est.code,
            controller_estimator_params=est.params_for(dt),
            controller_estimator_state=est.buffer(dt),
            memory=np.zeros(EK.MEM_SIZE),
        )

    # -- running ---------------------------------------------------------------------
    def run(
        self,
        duration: float | None = None,
        *,
        dt: float | None = None,
        output_rate: float | None = None,
        settings: RunSettings | None = None,
        check_stability: bool = True,
    ) -> SimulationResult:
        """Simulate for ``duration`` seconds (default: the excitation's own duration).

        Parameters
        ----------
        duration : float, optional
            Simulated time [s].
        dt : float, optional
            Fixed RK4 step [s] (default 1e-4, model reference, section 7); checked for stability.
        output_rate : float, optional
            Samples per second kept in the result (default 1 kHz; at most 1/dt).
        settings : RunSettings, optional
            ``duration``, ``dt`` and ``output_rate`` in one object (instead of the three
            keywords above; giving both is an error).
        check_stability : bool
            Refuse a ``dt`` above the RK4 stability limit of the stiffest mode (default).

        Raises
        ------
        ValidationError
            Settings out of range, ``settings`` given with any of ``duration``, ``dt``,
            ``output_rate``, or a ``dt`` too large for this model.
        SimulationDiverged
            When a state, the damper force or the tire force leaves the physical range:
            the message says when and which signal.

        Examples
        --------
        >>> from mrsuspension.excitation import RoundedPulse
        >>> sim = Simulation(RoundedPulse(0.02, 1.0))
        >>> a = sim.run(settings=RunSettings(dt=5e-4, duration=1.0))
        >>> b = sim.run(1.0, dt=5e-4)
        >>> bool((a.z_s == b.z_s).all()), a.time.size
        (True, 1001)
        """
        settings = run_settings(settings, duration=duration, dt=dt, output_rate=output_rate)
        settings.check_for(self.excitation)
        plan = settings.plan(self, check_stability=check_stability)
        announce_compile(EK.__file__, "run")  # a first run says why it waits
        dt, n, decimate = plan
        zr, zrd = self.road_samples(n, dt)
        a = self.kernel_arrays(dt, check_stability=False)  # dt is checked by plan()
        y = np.array([zr[0], 0.0, zr[0], 0.0, zr[0], 0.0])
        rec = np.zeros((plan.rows, EK.N_REC))
        status, k, idx, value = EK.run(
            y, n, dt, zr, zrd, *a.args(), decimate, EK.LIMITS, np.zeros(EK.SCRATCH_SIZE),
            *EK.recording(rec),
        )  # fmt: skip
        raise_failure()  # a Python control law that raised (its run stopped there)
        if status != EK.D_OK:
            raise self.divergence(status, k * dt, idx, value, dt)
        result = self.result_from_record(plan.time(), rec, dt)
        warn_if_clamped(result)
        warn_if_aliased(a.memory[EK.M_NREV], n, decimate, dt)
        return result

    def record_values(self, plan: RunPlan) -> float:
        """Floats a run of ``plan`` allocates: the record and the road at every half step.

        Examples
        --------
        >>> from mrsuspension.excitation import Harmonic
        >>> Simulation(Harmonic(1.0, 0.01)).record_values(RunPlan(1e-4, 100, 10))
        578.0
        """
        return float(plan.rows * EK.N_REC + 2 * (2 * plan.steps + 1))

    def road_samples(self, n: int, dt: float, *, start: int = 0) -> tuple[np.ndarray, np.ndarray]:
        """The road ``(z_r, z_r')`` at every half step of ``n`` steps from step ``start``
        (checked finite).

        Raises
        ------
        ValidationError
            When the excitation gives non-finite values.

        Examples
        --------
        >>> from mrsuspension.excitation import Harmonic
        >>> zr, zrd = Simulation(Harmonic(1.0, 0.01)).road_samples(2, 1e-4)
        >>> zr.shape
        (5,)
        """
        zr, zrd = road_grid(self.excitation, 2 * n + 1, 0.5 * dt, start * dt)
        if not (np.all(np.isfinite(zr)) and np.all(np.isfinite(zrd))):
            raise ValidationError("the excitation produced non-finite road values")
        return zr, zrd

    def divergence(
        self, status: int, t: float, idx: int, value: float, dt: float
    ) -> SimulationDiverged:
        """The error for a run's divergence as the kernels report it (``D_*``, index, value).

        Examples
        --------
        >>> from mrsuspension.engine import kernel as EK
        >>> from mrsuspension.excitation import Harmonic
        >>> err = Simulation(Harmonic(1.0, 0.01)).divergence(EK.D_FORCE, 0.5, 0, 2e6, 1e-4)
        >>> err.signal, err.time
        ('F_d', 0.5)
        """
        limits = EK.LIMITS
        if status == EK.D_STATE:
            name, unit = _STATE_NAMES[idx], _STATE_UNITS[idx]
            limit = limits[0] if idx % 2 == 0 else limits[1]
        elif status == EK.D_FORCE:
            name, unit, limit = "F_d", "N", limits[2]
        else:
            name, unit, limit = "F_T", "N", limits[3]
        what = "is not finite" if not math.isfinite(value) else f"exceeds {limit:g} {unit}"
        return SimulationDiverged(
            f"simulation diverged at t = {t:.4f} s: {name} = {value:.3g} {unit} {what}. "
            f"Check dt (= {dt:g} s; stable limit {self.max_stable_dt():.3g} s), the damper's "
            "peak-velocity estimator (the 'cycle-rms' default cannot run away) and the inputs.",
            t,
            name,
            value,
        )

    def result_from_record(
        self, time: np.ndarray, record: np.ndarray, dt: float
    ) -> SimulationResult:
        """The result of this simulation from the kernels' record (rows: ``R_*`` columns).

        Examples
        --------
        >>> import numpy as np
        >>> from mrsuspension.engine import kernel as EK
        >>> from mrsuspension.excitation import Harmonic
        >>> sim = Simulation(Harmonic(1.0, 0.01))
        >>> sim.result_from_record(np.zeros(1), np.zeros((1, EK.N_REC)), 1e-4).z_s.tolist()
        [0.0]
        """
        R = EK
        rec = np.ascontiguousarray(record.T)  # one pass; each signal is then contiguous
        signals = {
            "z_s": rec[R.R_ZS],
            "z_u": rec[R.R_ZU],
            "z_r": rec[R.R_ZR],
            "z_s_dot": rec[R.R_VS],
            "z_u_dot": rec[R.R_VU],
            "z_r_dot": rec[R.R_VR],
            "z_s_ddot": rec[R.R_AS],
            "z_u_ddot": rec[R.R_AU],
            "z_r_ddot": np.asarray(self.excitation.acceleration(time), dtype=float),
            "x_d": rec[R.R_ZU] - rec[R.R_ZS],
            "v_d": rec[R.R_VU] - rec[R.R_VS],
            "F_d": rec[R.R_FD],
            "F_T": rec[R.R_FT],
            "i_d": rec[R.R_ID],
            "i_z": rec[R.R_IZ],
            "z_c": rec[R.R_ZC],
            "F_target": rec[R.R_TARGET],
            "v_m": rec[R.R_VM],
            "z_s0": rec[R.R_ZS0],
        }
        return SimulationResult(time=time, signals=signals, scenario=self.describe(), dt=dt)

    def stepper(self, dt: float = DEFAULT_DT, *, external_force: bool = False) -> Stepper:
        """Tick-by-tick access to the same compiled step (for a real-time loop)."""
        return Stepper(self, dt, external_force=external_force)


class Stepper:
    """The engine's compiled step, one tick at a time (the HiL loop's physics).

    The road values at the start, middle and end of the tick are given by the caller
    (a real-time loop knows them; pass the same value three times for a held road).
    With ``external_force=True`` the damper force is not computed by a model but given
    at each tick (the measured force of a real damper), held over the tick.

    Examples
    --------
    >>> from mrsuspension.excitation import Harmonic
    >>> stepper = Simulation(Harmonic(1.0, 0.01)).stepper(1e-4)
    >>> out = stepper.step(0.0, 0.0628)
    >>> sorted(out)[:4]
    ['F_T', 'F_d', 'F_target', 'i_d']
    """

    def __init__(self, simulation: Simulation, dt: float, *, external_force: bool = False) -> None:
        self.simulation = simulation
        self.dt = simulation.check_dt(dt)
        self.external_force = external_force
        self.reset()

    def reset(self, road: float = 0.0, road_velocity: float = 0.0) -> None:
        """Back to static equilibrium on a road at height ``road``; fresh internals."""
        a = self.simulation.kernel_arrays(self.dt, check_stability=False)  # checked in init
        self._use(a.replace(force_source=F_EXTERNAL) if self.external_force else a)
        self._scratch = np.zeros(EK.SCRATCH_SIZE)
        self.y = np.array([road, 0.0, road, 0.0, road, 0.0])
        self.time = 0.0
        EK.start(self.y, road, road_velocity, *self._args, self._scratch)

    def _use(self, arrays: KernelArrays) -> None:
        """Step with ``arrays`` (their positional form is kept for the hot path)."""
        self._a = arrays
        self._args = arrays.args()

    @property
    def arrays(self) -> KernelArrays:
        """The arrays being stepped (their states change in place each step)."""
        return self._a

    def update(self, simulation: Simulation, arrays: KernelArrays | None = None) -> None:
        """Swap in another simulation's vehicle, controller and damper between two steps.

        The vehicle state, the held drive current and the other step memory are kept (a
        live change, e.g. from the HiL monitor); the damper's and the controller
        estimator's internal states are kept when their model is unchanged. The
        excitation is not part of the stepper (the caller gives the road).

        Parameters
        ----------
        simulation : Simulation
            The new configuration (checked for stability at this stepper's ``dt``).
        arrays : KernelArrays, optional
            ``simulation.kernel_arrays(dt)`` computed beforehand (e.g. by another process,
            so that the tick that applies the change stays short).

        Raises
        ------
        ValidationError
            When ``dt`` is too large for the new configuration.

        Examples
        --------
        >>> from mrsuspension.excitation import Harmonic
        >>> from mrsuspension.vehicle import QuarterCar
        >>> stepper = Simulation(Harmonic(1.0, 0.01)).stepper(1e-4)
        >>> _ = stepper.step(0.0, 0.0628)
        >>> heavier = Simulation(Harmonic(1.0, 0.01), vehicle=QuarterCar(sprung_mass=700.0))
        >>> stepper.update(heavier)
        >>> stepper.simulation.vehicle.sprung_mass
        700.0
        """
        new = arrays if arrays is not None else simulation.kernel_arrays(self.dt)
        if isinstance(simulation.controller, UserLaw):  # its entry in this process
            params = new.controller_params.copy()
            params[P_USER_FN] = float(type(simulation.controller).entry().address)
            new = new.replace(controller_params=params)
        a = self._a
        old = self.simulation
        changes: dict[str, Any] = {
            "vehicle": new.vehicle,
            "controller_kind": new.controller_kind,
            "controller_params": new.controller_params,
            "controller_estimator_kind": new.controller_estimator_kind,
            "controller_estimator_params": new.controller_estimator_params,
        }
        if (
            new.controller_estimator_state.shape != a.controller_estimator_state.shape
            or new.controller_estimator_kind != a.controller_estimator_kind
        ):
            changes["controller_estimator_state"] = new.controller_estimator_state
        if not self.external_force:
            changes["force_source"] = new.force_source
        if simulation.damper.describe() != old.damper.describe():
            for key in (
                "damper_kind",
                "damper_params",
                "damper_state",
                "damper_estimator_kind",
                "damper_estimator_params",
                "damper_estimator_state",
            ):
                changes[key] = getattr(new, key)
            a.memory[EK.M_PH + DK.PH_FT] = 0.0  # the control law's memo was of the old damper
        self._use(a.replace(**changes))
        self.simulation = simulation

    def step(
        self,
        road: float,
        road_velocity: float,
        *,
        road_mid: tuple[float, float] | None = None,
        road_end: tuple[float, float] | None = None,
        damper_force: float | None = None,
    ) -> dict[str, float]:
        """Advance one tick; returns the new state and outputs by signal name."""
        if self.external_force:
            if damper_force is None or not math.isfinite(damper_force):
                raise ValidationError(
                    f"external_force stepper needs a finite damper_force each tick; got {damper_force!r}"
                )
            self._a.memory[EK.M_FEXT] = damper_force
        elif damper_force is not None:
            raise ValidationError("damper_force is only accepted with external_force=True")
        zr1, zrd1 = road_mid if road_mid is not None else (road, road_velocity)
        zr2, zrd2 = road_end if road_end is not None else (zr1, zrd1)
        EK.step(
            self.y, self.dt, road, road_velocity, zr1, zrd1, zr2, zrd2, *self._args, self._scratch
        )
        raise_failure()  # a Python control law that raised in this step
        self.time += self.dt
        y, mem = self.y, self._a.memory
        out = {
            "time": self.time,
            "z_s": y[0], "z_s_dot": y[1], "z_u": y[2], "z_u_dot": y[3],
            "z_s_ddot": mem[EK.M_AS], "z_u_ddot": mem[EK.M_AU],
            "x_d": y[2] - y[0], "v_d": y[3] - y[1],
            "F_d": mem[EK.M_FD], "F_T": mem[EK.M_FT], "i_d": mem[EK.M_ID],
            "i_z": mem[EK.M_IZ], "z_c": mem[EK.M_ZC], "F_target": mem[EK.M_TARGET],
            "v_m": mem[EK.M_VM],
        }  # fmt: skip
        if not all(math.isfinite(y[q]) for q in range(4)):
            raise SimulationDiverged(
                f"stepper diverged at t = {self.time:.4f} s: state is not finite",
                self.time,
                "state",
                math.nan,
            )
        return out


def measures_of(result: SimulationResult) -> dict[str, Any]:
    """``result.measures()``: a picklable reducer for :func:`run_many` (sweeps).

    :func:`run_many` recognises it (and :class:`MeasuresOf`) and then reduces each run to
    its measures inside the kernel, without writing its time history
    (:mod:`~mrsuspension.engine.reduced`).
    """
    return result.measures()


@dataclass(frozen=True)
class MeasuresOf:
    """``result.measures(road_peak=...)`` as a :func:`run_many` reducer (picklable).

    Like :func:`measures_of` with a choice of ``road_peak``; :func:`run_many` reduces
    runs given it inside the kernel.

    Examples
    --------
    >>> from mrsuspension.excitation import RoundedPulse
    >>> sims = [Simulation(RoundedPulse(0.02, 1.0))]
    >>> (m,) = run_many(sims, dt=5e-4, workers=1, reduce=MeasuresOf("onset"))
    >>> m["road_peak"]
    'onset'
    """

    road_peak: RoadPeak = "after-onset"

    def __call__(self, result: SimulationResult) -> dict[str, Any]:
        return result.measures(road_peak=self.road_peak)


Reducer = Callable[[SimulationResult], Any]


def _in_kernel(reduce: Reducer | None) -> MeasuresOf | None:
    """The measures a reducer asks for, when the kernels can reduce to them (else None)."""
    if reduce is measures_of:
        return MeasuresOf()
    return reduce if isinstance(reduce, MeasuresOf) else None


def _run_one(args: tuple[Simulation, RunSettings, Reducer | None]) -> Any:
    sim, settings, reduce = args
    wanted = _in_kernel(reduce)
    if wanted is not None:
        from mrsuspension.engine.reduced import run_measures

        return run_measures(sim, settings, road_peak=wanted.road_peak)
    result = run_quietly(sim, settings)
    return result if reduce is None else reduce(result)


def run_quietly(sim: RunModel, settings: RunSettings) -> Any:
    """:meth:`Simulation.run` without the clamp warning, for batch runners: the result
    carries its time at the clamp (``vm_clamp_fraction``) for the caller to report."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", VelocityClampWarning)
        return sim.run(settings=settings)


def _run_batch(args: tuple[list[Simulation], RunSettings, Reducer | None]) -> list[Any]:
    """A lane batch (:func:`~mrsuspension.engine.lanes.run_lanes`), reduced; raises the
    first divergence, as a run on its own would."""
    results = _lane_batch(args)
    for r in results:
        if isinstance(r, SimulationDiverged):
            raise r
    return results


def _lane_batch(args: tuple[list[Simulation], RunSettings, Reducer | None]) -> list[Any]:
    """A lane batch's values, a :class:`SimulationDiverged` in place of each diverged run."""
    sims, settings, reduce = args
    wanted = _in_kernel(reduce)
    results = LN.run_lanes(
        sims,
        settings=settings,
        measures=wanted is not None,
        road_peak=wanted.road_peak if wanted is not None else "after-onset",
    )
    if reduce is None or wanted is not None:
        return results
    return [r if isinstance(r, SimulationDiverged) else reduce(r) for r in results]


def _run_task(args: tuple[bool, Any]) -> list[Any]:
    """One task of :func:`run_many`: a single run (as a one-item list) or a lane batch."""
    lanes, arg = args
    return _run_batch(arg) if lanes else [_run_one(arg)]


def _run_task_keep(args: tuple[bool, Any]) -> list[Any]:
    """:func:`_run_task` giving a :class:`SimulationDiverged` in place of a diverged run."""
    lanes, arg = args
    if lanes:
        return _lane_batch(arg)
    try:
        return [_run_one(arg)]
    except SimulationDiverged as err:
        return [err]


_LANES_WARM = False


def _warm_lanes(simulation: Simulation, dt: float) -> None:
    """Load the lane kernel in this process once, before forking workers.

    Forked workers inherit it; otherwise every worker of every pool loads it from numba's
    cache again, which measured slower than the lanes gain on a short sweep.
    """
    global _LANES_WARM
    if _LANES_WARM:
        return
    LN.run_lanes([simulation, simulation], duration=dt, dt=dt, output_rate=1.0 / dt)
    _LANES_WARM = True


def run_many(
    simulations: Sequence[Simulation],
    *,
    duration: float | None = None,
    dt: float | None = None,
    output_rate: float | None = None,
    settings: RunSettings | None = None,
    workers: int | None = None,
    progress: Callable[[int, int], None] | None = None,
    reduce: Reducer | None = None,
    lanes: bool = True,
) -> list[Any]:
    """Run many simulations, across processes (default: one per CPU core).

    Results come back in the order given. ``progress(done, total)`` is called as runs
    finish. ``workers=1`` runs in this process. ``reduce`` (a module-level function, so
    it can be sent to the workers) maps each result before it is returned, e.g.
    :func:`measures_of` for sweeps, which keeps the traffic between processes small.
    Given :func:`measures_of` (or a :class:`MeasuresOf`), the kernels reduce each run to
    its measures while stepping and write no time history
    (:mod:`~mrsuspension.engine.reduced`; equal to the post-processed measures to
    round-off). Runs do not warn about time at the peak-velocity clamp; each result (and
    its measures) carries it as ``vm_clamp_fraction`` for the caller to report. Every run
    uses the same ``settings`` (a :class:`~mrsuspension.engine.settings.RunSettings`),
    or the ``duration``, ``dt`` and ``output_rate`` keywords (not both).

    Runs that differ only in their excitation (a sweep) and use the dissertation's damper
    model are stepped together in vector instructions
    (:mod:`mrsuspension.engine.lanes`), at least
    :data:`~mrsuspension.engine.lanes.MIN_GROUP` at a time; ``lanes=False`` runs each on
    its own. Lane results agree with :meth:`Simulation.run` to round-off (the lanes
    compute exp differently), not bit for bit. Progress is then reported per batch. The
    batches go to the workers costliest first
    (:func:`~mrsuspension.engine.lanes.batch_cost`), so that the workers end together.

    Examples
    --------
    >>> from mrsuspension.excitation import Harmonic
    >>> sims = [Simulation(Harmonic(f, 0.01)) for f in (1.0, 2.0)]
    >>> [round(float(r.time[-1]), 1) for r in run_many(sims, duration=0.5, workers=1)]
    [0.5, 0.5]
    >>> plan = RunSettings(dt=2e-4, duration=0.5, output_rate=100.0)
    >>> [r.time.size for r in run_many(sims, settings=plan, workers=1)]
    [51, 51]
    """
    from mrsuspension._pool import pool_map, worker_count

    plan = run_settings(settings, duration=duration, dt=dt, output_rate=output_rate)
    sims = list(simulations)
    if not sims:
        return []
    n_workers = worker_count(workers, len(sims))
    tasks, batches = _tasks(sims, plan, reduce, lanes, n_workers)
    announce_compile(EK.__file__, "run")  # the workers compile quietly: say it here
    values = pool_map(
        _run_task,
        tasks,
        workers=n_workers,
        progress=progress,
        weights=[len(b) for b in batches],
    )
    return _in_order(len(sims), batches, values)


def _tasks(
    sims: list[Simulation], plan: RunSettings, reduce: Reducer | None, lanes: bool, parts: int
) -> tuple[list[tuple[bool, Any]], list[list[int]]]:
    """The tasks of a batch of runs with equal settings, and the runs of each task.

    Costliest first (:func:`~mrsuspension.engine.lanes.batch_cost`): a pool takes them in
    that order, so the longest starts first and the workers end together.
    """
    for sim in sims:  # before any work: a record that would alias the excitation
        plan.check_for(sim.excitation)
    if reduce is None and len(sims) > 1:  # every record is kept: together they must fit
        _check_records_memory(sims, plan)
    if lanes:
        batches = LN.plan_batches(sims, plan.dt, plan.duration, parts)
    else:
        cost = [LN.batch_cost(sims, [j], plan.dt, plan.duration) for j in range(len(sims))]
        batches = [[j] for j in sorted(range(len(sims)), key=lambda j: -cost[j])]
    tasks = [
        (False, (sims[b[0]], plan, reduce))
        if len(b) == 1
        else (True, ([sims[j] for j in b], plan, reduce))
        for b in batches
    ]
    if parts > 1 and any(len(b) > 1 for b in batches):
        _warm_lanes(sims[next(b for b in batches if len(b) > 1)[0]], plan.dt)
    return tasks, batches


def _check_records_memory(sims: Sequence[Simulation], plan: RunSettings) -> None:
    """Refuse, before any run, a batch whose records together exceed the memory limit."""
    rows = sum(plan.plan(sim, check_stability=False).rows for sim in sims)
    check_memory(
        plan.duration or 0.0,
        float(rows) * EK.N_REC,
        subject=f"keeping the records of {len(sims)} runs",
        hint="run fewer (e.g. fewer sweep frequencies), shorten the duration or lower output_rate",
    )


def _in_order(n: int, batches: list[list[int]], values: list[list[Any]]) -> list[Any]:
    results: list[Any] = [None] * n
    for batch, value in zip(batches, values, strict=True):
        for j, v in zip(batch, value, strict=True):
            results[j] = v
    return results


def measure_many(
    simulations: Sequence[Simulation],
    settings: Sequence[RunSettings],
    *,
    pool: Executor | None = None,
    road_peak: RoadPeak = "after-onset",
) -> list[dict[str, Any] | SimulationDiverged]:
    """The measures of each run (its own settings), reduced in the kernels, lanes first.

    Runs with equal settings share lane batches (:func:`run_many`); a diverged run gives
    its :class:`SimulationDiverged` in its place. ``pool``: an open process pool (e.g.
    :func:`mrsuspension._pool.process_pool`) to run on; None: this process. The batches
    of all settings go to the pool costliest first
    (:func:`~mrsuspension.engine.lanes.batch_cost`).

    Examples
    --------
    >>> from mrsuspension.excitation import RoundedPulse
    >>> sims = [Simulation(RoundedPulse(0.02, mu)) for mu in (1.0, 2.0)]
    >>> plan = RunSettings(dt=5e-4)
    >>> [round(m["SDR_s"], 3) for m in measure_many(sims, [plan, plan])]
    [1.443, 1.123]
    """
    from mrsuspension._pool import pool_map

    groups: dict[RunSettings, list[int]] = {}
    for j, plan in enumerate(settings):
        groups.setdefault(plan, []).append(j)
    # a ProcessPoolExecutor's size (how many parts plan_batches should split groups into)
    parts = getattr(pool, "_max_workers", 1) if pool is not None else 1
    tasks: list[tuple[bool, Any]] = []
    where: list[list[int]] = []
    cost: list[float] = []
    for plan, idx in groups.items():
        own = [simulations[j] for j in idx]
        t, batches = _tasks(own, plan, MeasuresOf(road_peak), True, parts)
        tasks.extend(t)
        where.extend([idx[k] for k in b] for b in batches)
        cost.extend(LN.batch_cost(own, b, plan.dt, plan.duration) for b in batches)
    order = sorted(range(len(tasks)), key=lambda k: -cost[k])  # costliest first, all groups
    values = pool_map(_run_task_keep, [tasks[k] for k in order], pool=pool, workers=1)
    return _in_order(len(simulations), [where[k] for k in order], values)
