"""Live hooks of the HiL loop (the browser monitor's): tap, external STOP, live changes.

:class:`LoopHooks` is what :func:`~mrsuspension.hil.loop.run_hil` takes as ``hooks``;
:class:`LiveChange` a new configuration prepared outside the loop, applied between two
ticks. See docs/hil.md (Live hooks).
"""

from __future__ import annotations

import dataclasses
import inspect
import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numba import njit

from mrsuspension.engine.arrays import KernelArrays
from mrsuspension.engine.simulate import DEFAULT_DT, Simulation
from mrsuspension.errors import ValidationError, check_range
from mrsuspension.excitation.base import Excitation
from mrsuspension.hil.safety import SafetySupervisor

__all__ = ["LiveChange", "LoopHooks", "tick_step"]


@dataclass
class LoopHooks:
    """Live hooks of :func:`run_hil` (the monitor's tap, STOP and settings channel).

    All of them are optional and none may block the loop: queues are used with
    ``put_nowait`` / ``get_nowait`` only and a full tap queue drops the message (counted).

    Parameters
    ----------
    tap : queue, optional
        Receives ``("started", dict)`` before the clock starts, ``("data", rows)`` (a
        list of :data:`~mrsuspension.hil.loop.CHANNELS` tuples, every ``tap_every``-th
        tick, one list every ``tap_batch`` ticks), ``("status", dict)`` every
        ``status_every`` ticks, ``("applied", dict)`` / ``("rejected", dict)`` for each
        settings change and a last ``("status", dict)`` when the loop ends.
    tap_every, tap_batch, status_every : int
        Decimation, batch length and status period, in ticks.
    ring : TapRing, optional
        Shared-memory ring (:class:`~mrsuspension.hil.tap.TapRing`) that takes the rows
        and the numeric status instead of ``tap`` (no pickling, no helper thread in the
        loop's process); ``tap`` then only carries the rare messages (changes applied or
        refused, the trip, the end).
    stop : event, optional
        Anything with ``is_set()``; checked every tick. When set, the run stops through
        the safety path (reason ``"STOP pressed"``).
    settings : queue, optional
        New :class:`~mrsuspension.engine.simulate.Simulation` configurations (already
        validated), polled every ``poll_every`` ticks and applied between two ticks.
    poll_every : int
        Ticks between two polls of ``settings``.
    ramp_time : float
        After a controller change the drive-current demand moves by at most
        ``current limit * period / ramp_time`` per tick for ``ramp_time`` seconds; an
        excitation change cross-fades the old road into the new one over the same time
        (the new excitation runs on its own clock from the change: a pulse comes its
        ``delay`` after it).

    Examples
    --------
    >>> import queue
    >>> from mrsuspension.excitation import Harmonic
    >>> from mrsuspension.hil import CHANNELS, ideal_rig, run_hil
    >>> sim = Simulation(Harmonic(1.5, 0.02), max_current=0.3)
    >>> tap = queue.Queue(maxsize=100)
    >>> hooks = LoopHooks(tap=tap, tap_every=10, tap_batch=100)
    >>> result = run_hil(sim, ideal_rig(sim.damper), duration=0.5, realtime=False, hooks=hooks)
    >>> tap.get_nowait()[0]  # sent before the clock starts
    'started'
    >>> kind, rows = tap.get_nowait()
    >>> kind, len(rows), len(rows[0]) == len(CHANNELS)
    ('data', 10, True)
    """

    tap: Any = None
    ring: Any = None
    tap_every: int = 5
    tap_batch: int = 50
    status_every: int = 200
    stop: Any = None
    settings: Any = None
    poll_every: int = 10
    ramp_time: float = 0.2
    dropped: int = 0
    applied: int = 0
    misses: int = 0
    _trip_sent: bool = field(default=False, init=False, repr=False)
    _counted: int = field(default=0, init=False, repr=False)
    #: ramp time of the change being applied [s]
    ramp_now: float = field(default=0.2, init=False, repr=False)

    def __post_init__(self) -> None:
        for name in ("tap_every", "tap_batch", "status_every", "poll_every"):
            value = getattr(self, name)
            if not isinstance(value, int) or value < 1:
                raise ValidationError(f"LoopHooks.{name} must be an integer >= 1; got {value!r}")
        check_range("ramp_time", self.ramp_time, 0.0, 10.0, unit="s", low_inclusive=False)

    def row(self, row: tuple[float, ...], pending: list[tuple[float, ...]]) -> None:
        """A tapped row: into the ring, else into the pending batch."""
        if self.ring is not None:
            self.ring.put(row)
        else:
            pending.append(row)

    def status(self, status: dict[str, Any]) -> None:
        """The loop status: into the ring's status block (the trip also as a message)."""
        first_trip = bool(status.get("tripped")) and not self._trip_sent
        if first_trip:
            self._trip_sent = True
        if self.ring is None:
            self.send("status", status)
            return
        self.ring.put_status(status)
        if first_trip:
            self.send("status", status)

    def send(self, kind: str, payload: Any) -> None:
        """Put a message on the tap without waiting (a full queue drops it)."""
        if self.tap is None:
            return
        try:
            self.tap.put_nowait((kind, payload))
        except Exception:  # queue.Full (or a closed queue): never stall the loop
            self.dropped += 1


def tick_step(rate: float, model_dt: float = DEFAULT_DT) -> float:
    """Engine step [s] of a loop at ``rate`` Hz: the tick split into ``ceil(T / model_dt)``.

    Examples
    --------
    >>> tick_step(1000.0)
    0.0001
    """
    period = 1.0 / rate
    return period / max(1, math.ceil(period / model_dt - 1e-9))


@dataclass(frozen=True)
class LiveChange:
    """A new configuration for a running loop, prepared outside the loop.

    :meth:`prepare` does the work (what changed, the kernel arrays) so that the tick that
    applies it only swaps arrays.

    Attributes
    ----------
    simulation : Simulation
        The new configuration.
    controller, excitation : bool
        Whether the control law (then the current ramps) or the road (then it
        cross-fades) changed.
    dt : float
        Engine step the arrays were prepared for.
    arrays : KernelArrays, optional
        :meth:`Simulation.kernel_arrays <mrsuspension.engine.simulate.Simulation.kernel_arrays>`.
    ramp_time : float, optional
        Ramp (and cross-fade) time of this change [s]; default: the hooks' ``ramp_time``.

    Examples
    --------
    >>> import dataclasses
    >>> from mrsuspension.control import Passive
    >>> from mrsuspension.excitation import Harmonic
    >>> sim = Simulation(Harmonic(1.5, 0.02), max_current=0.3)
    >>> change = LiveChange.prepare(
    ...     dataclasses.replace(sim, controller=Passive(0.2)), sim, rate=1000.0
    ... )
    >>> change.controller, change.excitation, change.dt
    (True, False, 0.0001)
    """

    simulation: Simulation
    controller: bool = True
    excitation: bool = True
    dt: float = 0.0
    arrays: KernelArrays | None = None
    ramp_time: float | None = None

    def __post_init__(self) -> None:
        if self.ramp_time is not None:
            check_range("ramp_time", self.ramp_time, 0.0, 10.0, unit="s", low_inclusive=False)

    @classmethod
    def prepare(
        cls,
        new: Simulation,
        old: Simulation,
        rate: float,
        model_dt: float = DEFAULT_DT,
        ramp_time: float | None = None,
    ) -> LiveChange:
        """Compare ``new`` with the running ``old`` and build the arrays (validated).

        Raises
        ------
        ValidationError
            When the loop's engine step is too large for ``new``.
        """
        dt = tick_step(rate, model_dt)
        return cls(
            simulation=new,
            controller=new.controller.describe() != old.controller.describe(),
            excitation=new.excitation.describe() != old.excitation.describe(),
            dt=dt,
            arrays=new.kernel_arrays(dt),
            ramp_time=ramp_time,
        )


#: half-step points of a block of live road evaluated pointwise (at most): 100 doubles
#: stay under numpy's 1024-byte cache of small buffers
_LIVE_POINTS = 100


def live_chunk(n_sub: int) -> int:
    """Ticks per block of live road evaluated pointwise, for ``n_sub`` engine steps per tick.

    Inside the loop a pointwise evaluation costs about the same for one tick as for a
    few (its numpy calls, cold there), so those excitations are evaluated a few ticks at
    a time (5 at 1 kHz); a compiled grid is cheapest one tick at a time (see
    :class:`_Road`).

    Examples
    --------
    >>> live_chunk(10), live_chunk(2), live_chunk(100)
    (5, 25, 1)
    """
    return max(1, _LIVE_POINTS // (2 * n_sub))


#: excitation classes -> whether they have their own ``sample_grid(n, step, start)``
_GRID_TAKES_START: dict[type, bool] = {}


def _grid_takes_start(cls: type) -> bool:
    """Whether ``cls`` has its own ``sample_grid(n, step, start)`` (a fast exact path)."""
    known = _GRID_TAKES_START.get(cls)
    if known is not None:
        return known
    grid = getattr(cls, "sample_grid", None)
    takes = False
    if grid is not None and grid is not Excitation.sample_grid:  # the default is pointwise
        try:
            takes = "start" in inspect.signature(grid).parameters
        except (TypeError, ValueError):
            takes = False
    _GRID_TAKES_START[cls] = takes
    return takes


def _fast_grid(excitation: Any) -> Any:
    """The excitation's ``sample_grid`` if it fills a grid from any start, else None."""
    return excitation.sample_grid if _grid_takes_start(type(excitation)) else None


@njit(cache=True)
def _cross_fade(
    zr: np.ndarray,
    zrd: np.ndarray,
    zr_old: np.ndarray,
    zrd_old: np.ndarray,
    t0: float,
    step: float,
    start: float,
    fade: float,
    out_zr: np.ndarray,
    out_zrd: np.ndarray,
) -> None:
    """Smoothstep from the old road into the new one, at ``t = t0 + k step``.

    ``s = clip((t - start) / fade, 0, 1)``, ``w = s^2 (3 - 2 s)``,
    ``z = (1 - w) z_old + w z`` and ``z' = (1 - w) z'_old + w z' + w' (z - z_old)``: no
    jump in z_r nor in z_r'.
    """
    for k in range(zr.shape[0]):
        s = min(max(((t0 + k * step) - start) / fade, 0.0), 1.0)
        w = s * s * (3.0 - 2.0 * s)
        dw = 6.0 * s * (1.0 - s) / fade if 0.0 < s < 1.0 else 0.0
        out_zrd[k] = (1.0 - w) * zrd_old[k] + w * zrd[k] + dw * (zr[k] - zr_old[k])
        out_zr[k] = (1.0 - w) * zr_old[k] + w * zr[k]


def _finite(values: list[float]) -> bool:
    """Whether every value is finite (a finite sum says so at once)."""
    return math.isfinite(sum(values)) or all(map(math.isfinite, values))


class _Road:
    """Road values at the half steps of a block of ticks (optionally cross-fading).

    An excitation switched in at time ``t`` runs on its own clock from ``t`` (a pulse
    comes its ``delay`` after the change, a road profile starts at its beginning).
    Excitations with a compiled ``sample_grid(n, step, start)`` fill the blocks through
    it, except for the first one (``k0 = 0``, computed before the clock: the values of
    the whole-run road); other excitations are evaluated pointwise
    (``displacement``/``velocity``).

    ``chunk`` is the number of ticks of the next block. With ``fast_chunk`` (the live
    loop's: 1) it is ``fast_chunk`` while every excitation in use has a compiled grid
    and ``slow_chunk`` otherwise; the loop asks for a new block every ``chunk`` ticks.
    In the loop, where every call runs with cold caches, one compiled tick of road costs
    about 10-30 us every tick, a block of 5 such ticks 40-50 us every 5th, and a
    pointwise block about 100 us however short (docs/hil.md).
    """

    def __init__(
        self, excitation: Any, n_sub: int, dt: float, chunk: int, fast_chunk: int | None = None
    ) -> None:
        self.excitation = excitation
        self.grid = _fast_grid(excitation)
        self.offset = 0.0
        self.old: Any = None
        self.old_grid: Any = None
        self.old_offset = 0.0
        self.fade_start = 0.0
        self.fade = 0.0
        self.n_sub = n_sub
        self.dt = dt
        self.slow_chunk = chunk
        self.fast_chunk = fast_chunk
        self.step = 0.5 * dt
        n = 2 * n_sub * max(chunk, fast_chunk or 1) + 1
        # (for k0 = 0 the same times as the whole-run road of a loop without hooks)
        self.half = np.arange(n) * self.step
        self._faded: tuple[np.ndarray, np.ndarray] | None = None  # cross-fade buffers
        self.chunk = self._chunk()

    def _chunk(self) -> int:
        fast = self.grid is not None and (self.old is None or self.old_grid is not None)
        return self.fast_chunk if fast and self.fast_chunk is not None else self.slow_chunk

    def switch(self, excitation: Any, t: float, fade: float) -> None:
        """Cross-fade from the current excitation to ``excitation`` from time ``t``.

        The next block must start at the tick of ``t``.
        """
        self.old, self.old_grid, self.old_offset = self.excitation, self.grid, self.offset
        self.excitation, self.grid, self.offset = excitation, _fast_grid(excitation), float(t)
        self.fade_start = float(t)
        self.fade = float(fade)
        if self._faded is None:
            self._faded = (np.empty(self.half.size), np.empty(self.half.size))
        self.chunk = self._chunk()

    def warm_up(self) -> None:
        """Compile (or load) the kernels live blocks may call, before the clock starts.

        This excitation's grid from a start after 0 (the first block is pointwise), the
        compiled grids a live change may switch to and the cross-fade: loading one
        inside a tick would take milliseconds.
        """
        from mrsuspension.excitation import Harmonic, RoadProfile, RoundedPulse

        grids = [self.grid, Harmonic(1.0, 0.01).sample_grid, RoundedPulse(0.01, 1.0).sample_grid]
        grids.append(RoadProfile(np.arange(4.0), np.zeros(4)).sample_grid)
        for grid in grids:
            if grid is not None:
                grid(3, self.step, self.n_sub * self.dt)
        z = np.zeros(3)
        _cross_fade(z, z, z, z, 0.0, self.step, 0.0, 1.0, np.empty(3), np.empty(3))

    def _sample(
        self, excitation: Any, grid: Any, offset: float, n: int, k0: int, t0: float
    ) -> tuple[np.ndarray, np.ndarray]:
        if grid is None or k0 == 0:
            t = t0 + self.half[:n] - offset
            zr, zrd = excitation.displacement(t), excitation.velocity(t)
        else:
            zr, zrd = grid(n, self.step, t0 - offset)
        z, zd = np.ascontiguousarray(zr, dtype=float), np.ascontiguousarray(zrd, dtype=float)
        if z.shape != (n,) or zd.shape != (n,):  # (n > 1: a scalar is refused too)
            raise ValidationError(
                f"the excitation gave road values of shape {np.shape(zr)} and "
                f"{np.shape(zrd)} for {n} times"
            )
        return z, zd

    def block(self, k0: int) -> tuple[list[float], list[float]]:
        """Road and road velocity for ticks ``k0 .. k0 + chunk`` (half-step samples).

        ``chunk`` is then the length of this block in ticks.

        Raises
        ------
        ValidationError
            When the excitation gives non-finite values.
        """
        t0 = k0 * self.n_sub * self.dt
        if self.old is not None and t0 >= self.fade_start + self.fade:
            self.old = self.old_grid = None  # the fade is over
        self.chunk = chunk = self._chunk()
        n = 2 * self.n_sub * chunk + 1
        zr, zrd = self._sample(self.excitation, self.grid, self.offset, n, k0, t0)
        if self.old is not None and self._faded is not None:
            zr_old, zrd_old = self._sample(self.old, self.old_grid, self.old_offset, n, k0, t0)
            out_zr, out_zrd = self._faded
            _cross_fade(
                zr, zrd, zr_old, zrd_old, t0, self.step, self.fade_start, self.fade,
                out_zr, out_zrd,
            )  # fmt: skip
            zr, zrd = out_zr[:n], out_zrd[:n]
        zl, zdl = zr.tolist(), zrd.tolist()
        if not (_finite(zl) and _finite(zdl)):
            raise ValidationError("the excitation produced non-finite road values")
        return zl, zdl


def _apply_settings(
    hooks: LoopHooks,
    stepper: Any,
    road_src: _Road | None,
    supervisor: SafetySupervisor,
    t: float,
    period: float,
) -> int:
    """Apply the newest queued configuration between two ticks; ramp length in ticks.

    A run whose model takes no live changes (a half or full car, ``live_changes`` False)
    refuses each one (a ``rejected`` message) and carries on.
    """
    q = hooks.settings
    if q is None:
        return 0
    new: Any = None
    try:
        while True:  # only the newest one matters
            new = q.get_nowait()
    except Exception:  # queue.Empty
        pass
    if new is None:
        return 0
    if road_src is None or not getattr(stepper, "live_changes", True):
        hooks.send(
            "rejected",
            {"time": t, "error": "live changes apply to quarter-car runs; this run is a "
             "half or full car (restart it with the new scenario)"},
        )  # fmt: skip
        return 0
    try:
        if isinstance(new, Simulation):  # not prepared: compare here
            new = LiveChange(new, arrays=None)
            old = stepper.simulation
            new = dataclasses.replace(
                new,
                controller=new.simulation.controller.describe() != old.controller.describe(),
                excitation=new.simulation.excitation.describe() != old.excitation.describe(),
            )
        if not isinstance(new, LiveChange):
            raise ValidationError(
                f"a live change must be a Simulation or a LiveChange; got {type(new).__name__}"
            )
        sim = new.simulation
        arrays = new.arrays if new.dt == stepper.dt else None
        if sim.max_current > supervisor.limits.current:
            sim = dataclasses.replace(sim, max_current=supervisor.limits.current)
            arrays = None
        law_changed = new.controller
        road_changed = new.excitation
        stepper.update(sim, arrays)
    except Exception as exc:  # refused; the loop carries on as it was
        hooks.send("rejected", {"time": t, "error": f"{type(exc).__name__}: {exc}"})
        return 0
    ramp = 0
    ramp_time = new.ramp_time or hooks.ramp_time
    hooks.ramp_now = ramp_time
    if road_changed:
        road_src.switch(sim.excitation, t, ramp_time)
    if law_changed or road_changed:
        ramp = max(1, math.ceil(ramp_time / period))
    hooks.applied += 1
    hooks.send(
        "applied",
        {
            "time": t,
            "count": hooks.applied,
            "controller": law_changed,
            "excitation": road_changed,
            "ramp_ticks": ramp,
        },
    )
    return ramp if law_changed or road_changed else 0


def _live_status(
    hooks: LoopHooks,
    supervisor: SafetySupervisor,
    state: int,
    k: int,
    compute: np.ndarray,
    lateness: np.ndarray,
    period: float,
    i_out: float,
) -> dict[str, Any]:
    w = slice(max(0, k - hooks.status_every), k)
    c = compute[w]
    m = slice(hooks._counted, k)  # misses since the last status (each tick counted once)
    hooks.misses += int(np.count_nonzero(compute[m] + lateness[m] > period))
    hooks._counted = k
    return {
        "state": ("startup", "running", "returning", "tripped")[state],
        "state_code": state,
        "time": k * period,
        "ticks": k,
        "misses": hooks.misses,
        "compute_last": float(c[-1]),
        "compute_mean": float(c.mean()),
        "compute_max": float(c.max()),
        "lateness_max": float(lateness[w].max()),
        "tripped": supervisor.tripped,
        "reason": supervisor.reason,
        "current": i_out,
        "dropped": hooks.dropped,
        "applied": hooks.applied,
        "rate": 1.0 / period,
    }
