"""Force bands of the semi-active optimum: the forces a damper can give at a velocity.

A band maps the damper velocity ``v_d`` [m/s] (compression positive, ``v_d = z_u' - z_s'``)
and a *band coordinate* ``u`` (the decision variable of the optimal control problem) to
the damper force ``F`` [N] (positive pushes the body up). For a semi-active band ``u`` runs
over ``[0, 1]`` from the soft edge ``F_min(v_d)`` (the damper at ``i_min``) to the hard
edge ``F_max(v_d)`` (at ``i_max``)::

    F = F_min(v_d) + u (F_max(v_d) - F_min(v_d)),    0 <= u <= 1

Both edges are odd in ``v_d`` with the sign of ``v_d``, so every ``u`` gives a dissipative
force (``F v_d >= 0``) between the edges, and every such force has one ``u``. This is the
"damping coefficient as a variable" way of writing the nonconvex set ``{F : F v_d >= 0,
F_min(|v_d|) <= |F| <= F_max(|v_d|)}`` (a cone with a hole, not convex): the coordinate
``u`` lives in a box, the nonconvexity moves into the smooth equality ``F = ...`` (a
bilinear term), and no complementarity constraint or smoothing of ``sign(v_d)`` is needed.
At ``v_d = 0`` the band is the single force 0 whatever ``u``.

* :class:`MRBand` - the dissertation's MR damper (the mean model of eq. (2.15) at a fixed
  peak velocity) between two currents;
* :class:`MREnvelopeBand` - every force the *hysteretic* damper of the engine can give at
  ``v_d``: the envelope over both hysteresis branches (``sgn(a_d) = +-1``), a range of
  peak velocities ``v_m`` and the currents ``i_min`` to ``i_max`` (not dissipative near
  ``v_d = 0``: the hysteresis loop); the benchmark's bound;
* :class:`LinearBand` - ``c_min v_d <= F <= c_max v_d`` (an ideal variable damper);
* :class:`ActiveBand` - any force of magnitude up to ``max_force`` (not dissipative: an
  active actuator, the linear-quadratic reference).

Examples
--------
>>> band = MRBand()
>>> lo, hi = band.edges(np.array([-0.2, 0.0, 0.2]))
>>> np.round(lo), np.round(hi)
(array([-2020., 0., 481.]), array([-481., 0., 2020.]))
>>> float(band.force(0.2, 1.0)) == float(hi[2])
True
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, ClassVar, Protocol

import numpy as np
import numpy.typing as npt

from mrsuspension.dampers import WangSymmetric
from mrsuspension.errors import ValidationError, check_range

__all__ = [
    "DEFAULT_PEAK_VELOCITY",
    "ActiveBand",
    "ForceBand",
    "LinearBand",
    "MRBand",
    "MREnvelopeBand",
]

#: Peak velocity [m/s] of the default :class:`MRBand`: about sqrt(2) times the rms damper
#: velocity of the passive car (0 A) on an ISO 8608 class C road at 50 km/h (0.23 m/s
#: rms in the engine), the peak of a harmonic test of the same rms velocity.
DEFAULT_PEAK_VELOCITY = 0.3


class ForceBand(Protocol):
    """What the optimum needs of a band (see the module docstring)."""

    #: True when every force of the band is dissipative (``F v_d >= 0``)
    semi_active: ClassVar[bool]

    @property
    def bounds(self) -> tuple[float, float]:
        """Bounds of the band coordinate ``u`` (``-inf``/``inf`` for none)."""
        ...

    @property
    def passive(self) -> float:
        """The coordinate of the passive setting (the reference the costs are scaled by)."""
        ...

    def force(self, v: Any, u: Any, ops: Any = np) -> Any:
        """``F(v_d, u)`` [N] with ``ops`` giving ``tanh`` and ``fabs`` (numpy or casadi)."""
        ...

    def edges(self, v: npt.ArrayLike) -> tuple[np.ndarray, np.ndarray]:
        """``(lowest, highest)`` force [N] of the band at ``v`` [m/s]."""
        ...

    def describe(self) -> dict[str, Any]:
        """Plain-data description."""
        ...


def _abs(ops: Any, x: Any) -> Any:
    return ops.fabs(x) if hasattr(ops, "fabs") else np.abs(x)


def _sorted_edges(band: Any, v: npt.ArrayLike) -> tuple[np.ndarray, np.ndarray]:
    vv = np.asarray(v, dtype=float)
    a = np.asarray(band.force(vv, 0.0), dtype=float)
    b = np.asarray(band.force(vv, 1.0), dtype=float)
    return np.minimum(a, b), np.maximum(a, b)


def _check_symmetric(damper: Any, band: str) -> None:
    """Refuse a damper other than the symmetric model (2.15) the bands are written for."""
    if not isinstance(damper, WangSymmetric) or type(damper).__name__ != "WangSymmetric":
        raise ValidationError(
            f"{band} needs a WangSymmetric damper (the symmetric model (2.15)); got "
            f"{type(damper).__name__}"
        )


@dataclass(frozen=True)
class MRBand:
    """The MR damper's band: the mean model (2.15) at a fixed peak velocity, i_min to i_max.

    The edges are the quasi-static force-velocity curves of the dissertation's symmetric
    model without hysteresis (``hysteresis=False``: ``k4 = 0``, so ``v_h = 0``, the mean
    branch) at the peak velocity ``v_m``::

        F(v_d, i) = k_d C_i(i) F_t(v_m) tanh(alpha(v_m) v_d / 2) (1 + k_1 |v_d| e^(-a_4 v_m))

    Why this form: the model's ``v_m`` comes from a peak-velocity estimator over the last
    cycle (model reference, section 2.4), a function of the record's history rather than
    of the state, and its hysteresis ``v_h`` switches with the sign of the acceleration.
    Fixing ``v_m`` and taking the mean branch makes each edge a smooth, odd, static
    function of ``v_d`` (what a characterisation test at that peak velocity draws), which
    a direct transcription can differentiate. The current enters only through the gain
    ``C_i(i)`` (2.9), so the band is also ``F = C F_min(v_d) / C_i(i_min)`` with
    ``C_i(i_min) <= C <= C_i(i_max)``: the coordinate ``u`` maps one to one to a current
    (:meth:`current`).

    Parameters
    ----------
    damper : WangSymmetric, optional
        The damper whose parameter set and force gain ``k_d`` give the band (default: the
        dissertation's, ``wang-symmetric-low``); its hysteresis setting is not used.
    peak_velocity : float
        ``v_m`` [m/s] (:data:`DEFAULT_PEAK_VELOCITY`).
    min_current, max_current : float
        ``i_min`` and ``i_max`` [A] (0 and 0.5 A, the simulations' drive range).

    Examples
    --------
    >>> band = MRBand(peak_velocity=0.3)
    >>> round(band.gain_ratio, 3)  # C_i(0.5 A) / C_i(0 A)
    4.196
    >>> round(float(band.current(band.force(0.1, 0.5), 0.1)), 3)
    0.123
    """

    damper: WangSymmetric = field(default_factory=lambda: WangSymmetric(hysteresis=False))
    peak_velocity: float = DEFAULT_PEAK_VELOCITY
    min_current: float = 0.0
    max_current: float = 0.5
    semi_active: ClassVar[bool] = True
    #: ``(k_d F_t(v_m), alpha(v_m) / 2, k_1 e^(-a_4 v_m))`` (set from the damper)
    _shape: tuple[float, float, float] = field(init=False, repr=False, compare=False)
    _gains: tuple[float, float] = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        _check_symmetric(self.damper, "MRBand")
        vm = float(check_range("peak_velocity", self.peak_velocity, 1e-3, 0.75, unit="m/s"))
        object.__setattr__(self, "peak_velocity", vm)
        i_top = self.damper.max_current
        i0 = float(check_range("min_current", self.min_current, 0.0, i_top, unit="A"))
        i1 = float(check_range("max_current", self.max_current, 0.0, i_top, unit="A"))
        if i1 <= i0:
            raise ValidationError(f"max_current must be > min_current ({i0:g} A); got {i1:g} A")
        object.__setattr__(self, "min_current", i0)
        object.__setattr__(self, "max_current", i1)
        # the model's constants at v_m, computed once
        p = self.damper.values
        ft = p["F0"] * (1.0 + math.exp(p["a1"] * vm))  # (2.7)
        alpha = p["a0"] / (1.0 + p["k0"] * vm)  # (2.11)
        k1 = p["k1"] * math.exp(-p["a4"] * vm)  # (2.10)
        object.__setattr__(self, "_shape", (self.damper.force_gain * ft, 0.5 * alpha, k1))
        c = self.damper.current_gain(np.array([i0, i1]))
        object.__setattr__(self, "_gains", (float(c[0]), float(c[1])))

    @property
    def gains(self) -> tuple[float, float]:
        """``(C_i(i_min), C_i(i_max))`` of eq. (2.9)."""
        return self._gains

    @property
    def gain_ratio(self) -> float:
        """``C_i(i_max) / C_i(i_min)``: the hard edge over the soft one at any velocity."""
        lo, hi = self.gains
        return hi / lo

    @property
    def bounds(self) -> tuple[float, float]:
        """``(0, 1)``: from ``i_min`` to ``i_max``."""
        return 0.0, 1.0

    @property
    def passive(self) -> float:
        """0: the damper at ``i_min``."""
        return 0.0

    def force(self, v: Any, u: Any, ops: Any = np) -> Any:
        """``F(v_d, u)`` [N] (numpy arrays, or casadi expressions with ``ops=casadi``)."""
        scale, half_alpha, k1 = self._shape
        c_lo, c_hi = self.gains
        base = scale * ops.tanh(half_alpha * v) * (1.0 + k1 * _abs(ops, v))
        return base * (c_lo + u * (c_hi - c_lo))

    def edges(self, v: npt.ArrayLike) -> tuple[np.ndarray, np.ndarray]:
        """``(lowest, highest)`` force [N] at ``v`` [m/s]."""
        return _sorted_edges(self, v)

    def current(self, force: npt.ArrayLike, v: npt.ArrayLike) -> np.ndarray:
        """The drive current [A] that gives ``force`` [N] at ``v`` [m/s] (inverse of (2.9)).

        ``nan`` where ``v`` is 0 (any current gives 0 N there).
        """
        scale, half_alpha, k1 = self._shape
        vv = np.asarray(v, dtype=float)
        base = scale * np.tanh(half_alpha * vv) * (1.0 + k1 * np.abs(vv))
        with np.errstate(divide="ignore", invalid="ignore"):
            c = np.where(base != 0.0, np.asarray(force, dtype=float) / base, np.nan)
        p = self.damper.values
        from scipy.special import expit, logit

        sa2 = float(expit(p["a2"] * p["I0"]))
        lo, hi = self.gains
        y = (np.clip(c, lo, hi) - 1.0) / p["k2"] + sa2
        with np.errstate(divide="ignore", invalid="ignore"):
            i = logit(np.clip(y, 1e-300, 1.0 - 1e-16)) / p["a2"] - p["I0"]
        i = np.where(np.isnan(c), np.nan, np.clip(i, self.min_current, self.max_current))
        return np.asarray(i, dtype=float)

    def describe(self) -> dict[str, Any]:
        """Plain-data description."""
        return {
            "band": "mr",
            "damper": self.damper.describe(),
            "peak_velocity": self.peak_velocity,
            "min_current": self.min_current,
            "max_current": self.max_current,
        }


def _envelope_grid(points: int, top: float) -> np.ndarray:
    """Velocities [m/s] of the envelope's table: 0, and ``points`` each side from 1e-5 m/s
    to ``top`` (geometric: the hysteresis acts at velocities of a few cm/s)."""
    side = np.geomspace(1e-5, top, points)
    return np.concatenate([-side[::-1], [0.0], side])


@dataclass(frozen=True)
class MREnvelopeBand:
    """Every force the hysteretic MR damper can give at ``v_d``: the benchmark's bound.

    The engine's damper is the symmetric model (2.15) *with* hysteresis: its force at
    ``v_d`` depends on the branch ``sgn(a_d)`` (the velocity shift ``v_h = sgn(a_d) k4
    v_m``), on the peak-velocity estimate ``v_m`` (a function of the record's history) and
    on the current. This band is the set of all of them::

        F_lo(v_d) = min F(v_d, i, s, v_m),   F_hi(v_d) = max F(v_d, i, s, v_m)
        over  i in [i_min, i_max],  s = sgn(a_d) in {-1, +1},  v_m in [v_m,lo, v_m,hi]

        F = F_lo(v_d) + u (F_hi(v_d) - F_lo(v_d)),   0 <= u <= 1

    so a force the engine's damper produces at ``v_d`` (any current, either branch, a
    ``v_m`` in the range) is a force of the band, and the optimum over this band is a
    lower bound for every current sequence into that damper whose ``v_m`` stays in the
    range. It is a relaxation: the band lets the optimum pick the branch freely, where the
    damper's branch follows the sign of its acceleration; near ``v_d = 0`` it holds forces
    of either sign (the hysteresis loop: about +-880 N at 0.5 A and v_m up to 0.35 m/s), so the band is not
    dissipative there.

    The edges are increasing in ``v_d``. They are tabulated on a velocity grid
    (``points`` velocities each side of 0, geometric from 1e-5 m/s to ``top``) with the
    extrema over ``v_m`` taken on ``vm_points`` values of the range, and interpolated
    linearly *outward*: the table's lower edge at a grid velocity is the exact edge at the
    grid velocity below it (the upper: above it), so between grid points the band contains
    the exact envelope. Beyond ``+-top`` the edges are held (numpy) or extended linearly
    (CasADi); damper velocities stay far below the default 10 m/s.

    Parameters
    ----------
    peak_velocity_range : (float, float)
        ``(v_m,lo, v_m,hi)`` [m/s]: the estimator's range on the record (the benchmark
        takes its clamp's ``v_min`` and the largest ``v_m`` of the runs it scores).
    damper : WangSymmetric, optional
        The damper (default: the dissertation's, ``wang-symmetric-low``, with hysteresis);
        its ``hysteresis=False`` gives the mean model's envelope over ``v_m`` alone.
    min_current, max_current : float
        ``i_min`` and ``i_max`` [A] (0 and 0.5 A).
    points, vm_points : int
        Grid sizes (see above).
    top : float
        The velocity grid's end [m/s].

    Examples
    --------
    >>> band = MREnvelopeBand((0.001, 0.35))
    >>> lo, hi = band.edges(np.array([-0.2, 0.0, 0.2]))
    >>> np.round(lo), np.round(hi)
    (array([-2376., -884., 372.]), array([-372., 884., 2376.]))
    >>> mean = MRBand()  # the mean model at v_m = 0.3 m/s lies inside
    >>> bool(np.all(band.contains(mean.force(np.linspace(-1, 1, 9), 0.7), np.linspace(-1, 1, 9))))
    True
    """

    peak_velocity_range: tuple[float, float] = (1e-3, DEFAULT_PEAK_VELOCITY)
    damper: WangSymmetric = field(default_factory=WangSymmetric)
    min_current: float = 0.0
    max_current: float = 0.5
    points: int = 1000
    vm_points: int = 241
    top: float = 10.0
    semi_active: ClassVar[bool] = False
    _table: tuple[np.ndarray, np.ndarray, np.ndarray] = field(init=False, repr=False, compare=False)
    _funs: dict[int, Any] = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        _check_symmetric(self.damper, "MREnvelopeBand")
        rng = np.asarray(self.peak_velocity_range, dtype=float)
        if rng.shape != (2,) or not np.all(np.isfinite(rng)):
            raise ValidationError(
                f"peak_velocity_range must be two numbers (v_m,lo, v_m,hi) [m/s]; got "
                f"{self.peak_velocity_range!r}"
            )
        lo_vm = float(check_range("peak_velocity_range low", rng[0], 1e-4, 5.0, unit="m/s"))
        hi_vm = float(check_range("peak_velocity_range high", rng[1], lo_vm, 5.0, unit="m/s"))
        object.__setattr__(self, "peak_velocity_range", (lo_vm, hi_vm))
        i_top = self.damper.max_current
        i0 = float(check_range("min_current", self.min_current, 0.0, i_top, unit="A"))
        i1 = float(check_range("max_current", self.max_current, 0.0, i_top, unit="A"))
        if i1 <= i0:
            raise ValidationError(f"max_current must be > min_current ({i0:g} A); got {i1:g} A")
        object.__setattr__(self, "min_current", i0)
        object.__setattr__(self, "max_current", i1)
        for name, low in (("points", 10), ("vm_points", 2)):
            value = getattr(self, name)
            if not isinstance(value, int) or value < low:
                raise ValidationError(f"{name} must be an integer >= {low}; got {value!r}")
        check_range("top", self.top, 0.1, 100.0, unit="m/s")
        grid = _envelope_grid(self.points, float(self.top))
        vms = np.linspace(lo_vm, hi_vm, self.vm_points)
        lo, hi = self.exact_edges(grid, vms)
        # outward: the exact lower edge one grid point below, the upper one above
        lo_out = np.concatenate([[lo[0]], lo[:-1]])
        hi_out = np.concatenate([hi[1:], [hi[-1]]])
        object.__setattr__(self, "_table", (grid, lo_out, hi_out))
        object.__setattr__(self, "_funs", {})

    def exact_edges(
        self, v: npt.ArrayLike, vms: npt.ArrayLike | None = None
    ) -> tuple[np.ndarray, np.ndarray]:
        """The envelope at ``v`` [m/s] over the branches, the currents and ``vms`` [m/s]
        (default: the range's ends and ``vm_points`` values between), untabulated."""
        vv = np.asarray(v, dtype=float)
        if vms is None:
            vms = np.linspace(*self.peak_velocity_range, self.vm_points)
        vm = np.asarray(vms, dtype=float).reshape((1,) * vv.ndim + (-1,))
        p = self.damper.values
        k4 = p["k4"] if self.damper.hysteresis else 0.0
        ft = self.damper.force_gain * p["F0"] * (1.0 + np.exp(p["a1"] * vm))  # (2.7)
        half_alpha = 0.5 * p["a0"] / (1.0 + p["k0"] * vm)  # (2.11)
        rise = 1.0 + p["k1"] * np.exp(-p["a4"] * vm) * np.abs(vv[..., None])  # (2.10)
        h_lo = np.full(vv.shape, np.inf)
        h_hi = np.full(vv.shape, -np.inf)
        for s in (-1.0, 1.0):  # the branches, v_h = sgn(a_d) k4 v_m (2.13)
            h = ft * np.tanh(half_alpha * (vv[..., None] + s * k4 * vm)) * rise
            h_lo = np.minimum(h_lo, h.min(axis=-1))
            h_hi = np.maximum(h_hi, h.max(axis=-1))
        from scipy.special import expit

        # C_i of (2.9) in numpy (the damper's compiled kernel costs a load here)
        c_lo, c_hi = (
            1.0
            + p["k2"] * (float(expit(p["a2"] * (i + p["I0"]))) - float(expit(p["a2"] * p["I0"])))
            for i in (self.min_current, self.max_current)
        )
        # F = C_i F_h with C_i in [c_lo, c_hi] > 0: the extremes at the ends
        lo = np.minimum(c_lo * h_lo, c_hi * h_lo)
        hi = np.maximum(c_lo * h_hi, c_hi * h_hi)
        return lo, hi

    @property
    def bounds(self) -> tuple[float, float]:
        """``(0, 1)``: from the lowest force to the highest."""
        return 0.0, 1.0

    @property
    def passive(self) -> float:
        """0 (the lowest force; the passive car is :attr:`passive_band`'s)."""
        return 0.0

    @property
    def passive_band(self) -> MRBand:
        """The band whose passive setting is the reference passive car (the scales): the
        mean model at ``i_min`` at :data:`DEFAULT_PEAK_VELOCITY`, as with :class:`MRBand`."""
        mean = WangSymmetric(
            self.damper.parameters, hysteresis=False, force_gain=self.damper.force_gain
        )
        return MRBand(mean, DEFAULT_PEAK_VELOCITY, self.min_current, self.max_current)

    def _casadi_edges(self, n: int, ops: Any) -> tuple[Any, Any]:
        if n not in self._funs:
            grid, lo, hi = self._table
            self._funs[n] = (
                ops.interpolant("band_lo", "linear", [grid], lo).map(n),
                ops.interpolant("band_hi", "linear", [grid], hi).map(n),
            )
        return self._funs[n]

    def force(self, v: Any, u: Any, ops: Any = np) -> Any:
        """``F(v_d, u)`` [N] (numpy arrays, or a casadi column vector with ``ops=casadi``)."""
        if ops is np or not hasattr(ops, "interpolant"):
            lo, hi = self.edges(v)
            return lo + np.asarray(u, dtype=float) * (hi - lo)
        f_lo, f_hi = self._casadi_edges(int(v.shape[0]), ops)
        lo = f_lo(v.T).T
        hi = f_hi(v.T).T
        return lo + u * (hi - lo)

    def edges(self, v: npt.ArrayLike) -> tuple[np.ndarray, np.ndarray]:
        """``(lowest, highest)`` force [N] at ``v`` [m/s] (the outward table)."""
        grid, lo, hi = self._table
        vv = np.asarray(v, dtype=float)
        return np.interp(vv, grid, lo), np.interp(vv, grid, hi)

    def coordinate(self, force: npt.ArrayLike, v: npt.ArrayLike) -> np.ndarray:
        """The band coordinate ``u`` of ``force`` [N] at ``v`` [m/s], clipped to [0, 1]."""
        lo, hi = self.edges(v)
        with np.errstate(divide="ignore", invalid="ignore"):
            u = (np.asarray(force, dtype=float) - lo) / (hi - lo)
        return np.asarray(np.clip(np.nan_to_num(u, nan=0.0), 0.0, 1.0), dtype=float)

    def contains(self, force: npt.ArrayLike, v: npt.ArrayLike, tol: float = 1e-9) -> np.ndarray:
        """Whether each ``force`` [N] at ``v`` [m/s] is in the band (to ``tol`` relative to
        the band's width there)."""
        lo, hi = self.edges(v)
        f = np.asarray(force, dtype=float)
        slack = tol * (hi - lo)
        return np.asarray((f >= lo - slack) & (f <= hi + slack))

    def describe(self) -> dict[str, Any]:
        """Plain-data description."""
        return {
            "band": "mr-envelope",
            "damper": self.damper.describe(),
            "peak_velocity_range": list(self.peak_velocity_range),
            "min_current": self.min_current,
            "max_current": self.max_current,
        }


@dataclass(frozen=True)
class LinearBand:
    """An ideal variable damper: ``F = c v_d`` with ``c_min <= c <= c_max`` [N s/m].

    With ``c_min = c_max`` the band is one passive linear damper.

    Examples
    --------
    >>> LinearBand(1000.0, 4000.0).edges([0.1])
    (array([100.]), array([400.]))
    """

    min_damping: float = 500.0
    max_damping: float = 5000.0
    semi_active: ClassVar[bool] = True

    def __post_init__(self) -> None:
        lo = float(check_range("min_damping", self.min_damping, 0.0, 1e7, unit="N s/m"))
        hi = float(check_range("max_damping", self.max_damping, 0.0, 1e7, unit="N s/m"))
        if hi < lo:
            raise ValidationError(
                f"max_damping must be >= min_damping ({lo:g} N s/m); got {hi:g} N s/m"
            )
        object.__setattr__(self, "min_damping", lo)
        object.__setattr__(self, "max_damping", hi)

    @property
    def bounds(self) -> tuple[float, float]:
        """``(0, 1)``."""
        return 0.0, 1.0

    @property
    def passive(self) -> float:
        """0: ``c_min``."""
        return 0.0

    def force(self, v: Any, u: Any, ops: Any = np) -> Any:
        """``(c_min + u (c_max - c_min)) v_d`` [N]."""
        return (self.min_damping + u * (self.max_damping - self.min_damping)) * v

    def edges(self, v: npt.ArrayLike) -> tuple[np.ndarray, np.ndarray]:
        """``(lowest, highest)`` force [N] at ``v`` [m/s]."""
        return _sorted_edges(self, v)

    def describe(self) -> dict[str, Any]:
        """Plain-data description."""
        return {"band": "linear", "min_damping": self.min_damping, "max_damping": self.max_damping}


@dataclass(frozen=True)
class ActiveBand:
    """Any force ``|F| <= max_force`` [N] (``inf``: unbounded): an active actuator.

    Not dissipative: the reference for which the optimum with a wide enough band is the
    linear-quadratic one. The coordinate ``u`` is the force itself; its passive setting is
    0 N.

    Examples
    --------
    >>> ActiveBand(1000.0).edges([0.0, 1.0])
    (array([-1000., -1000.]), array([1000., 1000.]))
    """

    max_force: float = math.inf
    semi_active: ClassVar[bool] = False

    def __post_init__(self) -> None:
        f = float(self.max_force)
        if math.isnan(f) or f <= 0.0:
            raise ValidationError(f"max_force must be > 0 N (inf: no limit); got {f:g} N")
        object.__setattr__(self, "max_force", f)

    @property
    def bounds(self) -> tuple[float, float]:
        """``(-max_force, max_force)`` [N]."""
        return -self.max_force, self.max_force

    @property
    def passive(self) -> float:
        """0 N."""
        return 0.0

    def force(self, v: Any, u: Any, ops: Any = np) -> Any:
        """``u`` itself [N]."""
        return u + 0.0 * v

    def edges(self, v: npt.ArrayLike) -> tuple[np.ndarray, np.ndarray]:
        """``(-max_force, max_force)`` at every ``v``."""
        vv = np.asarray(v, dtype=float)
        return np.full(vv.shape, -self.max_force), np.full(vv.shape, self.max_force)

    def describe(self) -> dict[str, Any]:
        """Plain-data description."""
        return {"band": "active", "max_force": self.max_force}
