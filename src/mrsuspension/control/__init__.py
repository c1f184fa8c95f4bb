"""Semi-active controllers (MODEL_SPEC section 6), one interface.

Every controller turns the sampled state into a drive current for the damper (or, for
the ideal references, a force through an ideal dissipative damper) and reports its
switching condition ``z_c`` and, where it has one, its target force.

====================  ================================================  ==============
law                   class                                             seed
====================  ================================================  ==============
``passive``           :class:`Passive` (constant current)               (3.4)
``onoff-adfg``        :class:`OnOffADFG` (2.1)                          Fig. 4.3
``skyhook-hilo``      :class:`HiLo` policy I, ``k_c |z_s'|^n``          (3.15)
``policy-ii``         :class:`HiLo` policy II, ``k_c |v_d|^n``          (3.15)
``policy-iii``        :class:`HiLo` policy III, ``k_c |v_d|^n``         (3.15)
``policy-iv``         :class:`HiLo` policy IV, ``k_c |x_d|^n``          (3.15)
``inverse-hilo``      :class:`InverseHiLo`, inverse(``F* = k_s x_d``)   (3.17)
``sliding-mode``      :class:`SlidingMode`, inverse(``F_c``)            (3.35)
``ideal-skyhook``     :class:`IdealSkyhook` (3.12), ideal damper        (3.12)
``ideal-onoff``       :class:`IdealOnOff` (3.13), ideal damper          (3.13)
====================  ================================================  ==============

Drive current (3.9)/(3.16): ``i_d = clip(M_p(p, xi, v_d) M_c(p_c, xi_c, z_c) i_z, 0, i_max)``;
``mode="SCM"`` sets ``p = 1`` (symmetric), ``mode="ACM"`` sets ``p = 0`` (asymmetric).

Examples
--------
>>> make_controller("skyhook-hilo", mode="ACM")
HiLo(policy=1, gain=3.0, order=2.0, p=0.0, xi=4.5, p_c=0.0, xi_c=10.0)
"""

from __future__ import annotations

import dataclasses
import math
from abc import ABC
from dataclasses import dataclass
from typing import Any, ClassVar

import numpy as np
import numpy.typing as npt

from mrsuspension.engine import kernel as EK
from mrsuspension.errors import ValidationError, unknown_name

__all__ = [
    "CONTROLLERS",
    "Controller",
    "HiLo",
    "IdealOnOff",
    "IdealSkyhook",
    "InverseHiLo",
    "OnOffADFG",
    "Passive",
    "SlidingMode",
    "make_controller",
]

_MODES = {"SCM": 1.0, "ACM": 0.0}


def _check(
    name: str, value: float, lo: float, hi: float, *, lo_open: bool = False, hi_open: bool = False
) -> float:
    if isinstance(value, bool) or not isinstance(value, int | float) or not math.isfinite(value):
        raise ValidationError(f"{name} must be a finite number; got {value!r}")
    if (value < lo or (lo_open and value == lo)) or (value > hi or (hi_open and value == hi)):
        lb = "(" if lo_open else "["
        rb = ")" if hi_open else "]"
        raise ValidationError(f"{name} must be in {lb}{lo:g}, {hi:g}{rb}; got {value:g}")
    return float(value)


@dataclass(frozen=True)
class Controller(ABC):
    """Common interface: a kernel code and a parameter vector."""

    law: ClassVar[str]
    code: ClassVar[int]
    #: force source of the engine (a damper model, or an ideal dissipative damper)
    force_source: ClassVar[int] = EK.F_MODEL
    #: whether the controller needs the inverse of the dissertation's damper model
    needs_inverse: ClassVar[bool] = False

    def params(self, max_current: float) -> npt.NDArray[np.float64]:
        """Parameter vector of the compiled controller (layout ``engine.kernel.P_*``)."""
        p = np.zeros(EK.CP_SIZE)
        p[EK.P_P] = 1.0
        p[EK.P_XI] = 1.0
        p[EK.P_XIC] = 1.0
        p[EK.P_EPS] = 1.0
        p[EK.P_MS0] = 1.0
        p[EK.P_BETA] = 1.0
        p[EK.P_INV_HYST] = 1.0
        p[EK.P_IMAX] = max_current
        self._fill(p)
        return p

    def _fill(self, p: npt.NDArray[np.float64]) -> None:  # noqa: B027 - optional hook
        """Write this controller's fields into the parameter vector (default: nothing)."""

    def describe(self) -> dict[str, Any]:
        """Plain data: the law and every parameter."""
        return {"law": self.law, **dataclasses.asdict(self)}


#: inverse model of the inverse-model controllers -> kernel flag (1: hysteretic, 0: mean)
_INVERSE_KINDS = {"hysteretic": 1.0, "mean": 0.0}


def _inverse_kind(kind: str) -> str:
    if kind not in _INVERSE_KINDS:
        raise unknown_name("inverse model", str(kind), _INVERSE_KINDS)
    return kind


def _mode_p(mode: str | None, p: float | None, default: float) -> float:
    if mode is not None and p is not None:
        raise ValidationError("give either mode ('SCM'/'ACM') or p, not both")
    if mode is not None:
        key = str(mode).upper()
        if key not in _MODES:
            raise unknown_name("control mode", str(mode), _MODES)
        return _MODES[key]
    return _check("p", default if p is None else p, 0.0, 1.0)


@dataclass(frozen=True)
class Passive(Controller):
    """Constant drive current (3.4); the dissertation studies 0, 0.05, 0.1 and 0.2 A."""

    current: float = 0.0
    law: ClassVar[str] = "passive"
    code: ClassVar[int] = EK.C_PASSIVE

    def __post_init__(self) -> None:
        object.__setattr__(self, "current", _check("current", self.current, 0.0, 10.0))

    def _fill(self, p: npt.NDArray[np.float64]) -> None:
        if self.current > p[EK.P_IMAX] + 1e-12:
            raise ValidationError(
                f"passive current {self.current:g} A exceeds max_current {p[EK.P_IMAX]:g} A"
            )
        p[EK.P_CURRENT] = self.current


@dataclass(frozen=True)
class OnOffADFG(Controller):
    """On-off ADFG (2.1): ``p i_H`` in compression, ``i_H`` in rebound (Fig. 4.3)."""

    current: float = 0.5
    p: float = 0.0
    law: ClassVar[str] = "onoff-adfg"
    code: ClassVar[int] = EK.C_ONOFF_ADFG

    def __post_init__(self) -> None:
        object.__setattr__(self, "current", _check("current", self.current, 0.0, 10.0))
        object.__setattr__(self, "p", _check("p", self.p, 0.0, 1.0))

    def _fill(self, p: npt.NDArray[np.float64]) -> None:
        p[EK.P_CURRENT] = self.current
        p[EK.P_P] = self.p


@dataclass(frozen=True, init=False)
class _Shaped(Controller):
    """Controllers whose current goes through the ADFG and CM multipliers."""

    p: float = 1.0
    xi: float = 4.5
    p_c: float = 0.0
    xi_c: float = 10.0

    def _set_shaping(
        self, mode: str | None, p: float | None, xi: float, p_c: float, xi_c: float
    ) -> None:
        """Validate and set the ADFG (mode or p, xi) and CM (p_c, xi_c) factors."""
        object.__setattr__(self, "p", _mode_p(mode, p, 1.0))
        object.__setattr__(self, "xi", xi)
        object.__setattr__(self, "p_c", p_c)
        object.__setattr__(self, "xi_c", xi_c)
        self._check_shaping()

    def _check_shaping(self) -> None:
        object.__setattr__(self, "p", _check("p", self.p, 0.0, 1.0))
        object.__setattr__(self, "xi", _check("xi", self.xi, 0.0, 1e6, lo_open=True))
        object.__setattr__(self, "p_c", _check("p_c", self.p_c, 0.0, 1.0, hi_open=True))
        object.__setattr__(self, "xi_c", _check("xi_c", self.xi_c, 0.0, 1e12, lo_open=True))

    def _fill_shaping(self, p: npt.NDArray[np.float64]) -> None:
        p[EK.P_P] = self.p
        p[EK.P_XI] = self.xi
        p[EK.P_PC] = self.p_c
        p[EK.P_XIC] = self.xi_c


_POLICY_LAWS = {1: "skyhook-hilo", 2: "policy-ii", 3: "policy-iii", 4: "policy-iv"}
#: Chapter 4 policy-comparison gains k_c (section 4.3.1): 3, 10, 10, 300.
POLICY_GAINS = {1: 3.0, 2: 10.0, 3: 10.0, 4: 300.0}


@dataclass(frozen=True, init=False)
class HiLo(_Shaped):
    """Hi-lo policies I-IV (3.15) with gain ``k_c`` and order ``n``.

    ==========  =====================  ===============
    policy      i_z                    z_c
    ==========  =====================  ===============
    I (sky)     ``k_c |z_s'|^n``       ``z_s' v_d``
    II          ``k_c |v_d|^n``        ``z_s' v_d``
    III         ``k_c |v_d|^n``        ``x_d v_d``
    IV          ``k_c |x_d|^n``        ``x_d v_d``
    ==========  =====================  ===============

    Defaults (Chapter 4): n = 2, k_c = 3, 10, 10, 300 for policies I-IV, p_c = 0,
    xi_c = 10, xi = 4.5; ``mode="SCM"`` (p = 1, default) or ``"ACM"`` (p = 0).
    """

    policy: int = 1
    gain: float = 3.0
    order: float = 2.0
    code: ClassVar[int] = EK.C_POLICY

    def __init__(
        self,
        policy: int = 1,
        gain: float | None = None,
        order: float = 2.0,
        *,
        mode: str | None = None,
        p: float | None = None,
        xi: float = 4.5,
        p_c: float = 0.0,
        xi_c: float = 10.0,
    ) -> None:
        if policy not in _POLICY_LAWS:
            raise ValidationError(f"policy must be 1, 2, 3 or 4; got {policy!r}")
        object.__setattr__(self, "policy", int(policy))
        g = POLICY_GAINS[policy] if gain is None else gain
        object.__setattr__(self, "gain", _check("gain k_c", g, 0.0, 1e9))
        object.__setattr__(self, "order", _check("order n", order, 0.0, 10.0, lo_open=True))
        self._set_shaping(mode, p, xi, p_c, xi_c)

    @property
    def law(self) -> str:  # type: ignore[override]
        return _POLICY_LAWS[self.policy]

    def __repr__(self) -> str:
        return (
            f"HiLo(policy={self.policy}, gain={self.gain}, order={self.order}, p={self.p}, "
            f"xi={self.xi}, p_c={self.p_c}, xi_c={self.xi_c})"
        )

    def _fill(self, p: npt.NDArray[np.float64]) -> None:
        self._fill_shaping(p)
        p[EK.P_POLICY] = self.policy
        p[EK.P_GAIN] = self.gain
        p[EK.P_ORDER] = self.order


@dataclass(frozen=True, init=False)
class InverseHiLo(_Shaped):
    """Inverse-model hi-lo (3.17): track ``F* = k_s x_d`` when it opposes the spring force.

    ``i_z`` = inverse(F*), ``z_c = F_h k_s x_d``. Chapter 5 defaults: p_c = 0, xi_c = 50,
    xi = 10 (and the damper's force gain k_d = 2.5). Needs the dissertation's symmetric
    damper model (its inverse, spec section 2.3). ``inverse="mean"`` inverts the mean
    model (``v_h = 0``) whatever the damper, as in Figs 5.2 and 5.5 (hysteretic damper,
    mean inverse); the default ``"hysteretic"`` inverts the damper's own model.

    Examples
    --------
    >>> InverseHiLo(mode="ACM", inverse="mean").inverse
    'mean'
    """

    inverse: str = "hysteretic"
    code: ClassVar[int] = EK.C_INVERSE_HILO
    law: ClassVar[str] = "inverse-hilo"
    needs_inverse: ClassVar[bool] = True

    def __init__(
        self,
        *,
        mode: str | None = None,
        p: float | None = None,
        xi: float = 10.0,
        p_c: float = 0.0,
        xi_c: float = 50.0,
        inverse: str = "hysteretic",
    ) -> None:
        self._set_shaping(mode, p, xi, p_c, xi_c)
        object.__setattr__(self, "inverse", _inverse_kind(inverse))

    def _fill(self, p: npt.NDArray[np.float64]) -> None:
        self._fill_shaping(p)
        p[EK.P_INV_HYST] = _INVERSE_KINDS[self.inverse]


@dataclass(frozen=True, init=False)
class SlidingMode(_Shaped):
    """Inverse-model sliding-mode controller (3.19)-(3.35), up-positive frame.

    Tracks the single-DOF modified-skyhook reference (3.18) of nominal mass ``m_s0``::

        s   = e' + lambda e,  e = z_s - z_s0
        F_d0 = -k_s x_d + m_s0 z_s0'' - m_s0 lambda e'
        K   = m_s0 beta phi + (beta - 1)(|F_d0| + k_s |z_s| + k_s |z_u|)
        F_c = F_d0 - K sat(s / eps)

    then ``i_z`` = inverse(F_c) and ``z_c = -F_h F_c``. Defaults (Chapter 6): lambda 0.5,
    eps 0.05, phi 1.6, beta 1.25 (the studied +-25 % load range; not given in the seed),
    c_s 6750, c_0 2500, m_s0 563 kg, p_c 0, xi_c 150, xi 30. ``inverse="mean"`` inverts
    the mean model whatever the damper (Fig. 6.1); see :class:`InverseHiLo`.
    """

    slope: float = 0.5
    boundary_layer: float = 0.05
    phi: float = 1.6
    beta: float = 1.25
    nominal_mass: float = 563.0
    skyhook_damping: float = 6750.0
    passive_damping: float = 2500.0
    inverse: str = "hysteretic"
    code: ClassVar[int] = EK.C_SLIDING
    law: ClassVar[str] = "sliding-mode"
    needs_inverse: ClassVar[bool] = True

    def __init__(
        self,
        *,
        slope: float = 0.5,
        boundary_layer: float = 0.05,
        phi: float = 1.6,
        beta: float = 1.25,
        nominal_mass: float = 563.0,
        skyhook_damping: float = 6750.0,
        passive_damping: float = 2500.0,
        mode: str | None = None,
        p: float | None = None,
        xi: float = 30.0,
        p_c: float = 0.0,
        xi_c: float = 150.0,
        inverse: str = "hysteretic",
    ) -> None:
        object.__setattr__(self, "inverse", _inverse_kind(inverse))
        object.__setattr__(self, "slope", _check("slope (lambda)", slope, 0.0, 1e4, lo_open=True))
        object.__setattr__(
            self,
            "boundary_layer",
            _check("boundary_layer (eps)", boundary_layer, 0.0, 1e3, lo_open=True),
        )
        object.__setattr__(self, "phi", _check("phi", phi, 0.0, 1e6))
        object.__setattr__(self, "beta", _check("beta", beta, 1.0, 10.0))
        object.__setattr__(self, "nominal_mass", _check("nominal_mass", nominal_mass, 1.0, 1e5))
        object.__setattr__(
            self, "skyhook_damping", _check("skyhook_damping", skyhook_damping, 0.0, 1e7)
        )
        object.__setattr__(
            self, "passive_damping", _check("passive_damping", passive_damping, 0.0, 1e7)
        )
        self._set_shaping(mode, p, xi, p_c, xi_c)

    def _fill(self, p: npt.NDArray[np.float64]) -> None:
        self._fill_shaping(p)
        p[EK.P_LAMBDA] = self.slope
        p[EK.P_EPS] = self.boundary_layer
        p[EK.P_PHI] = self.phi
        p[EK.P_BETA] = self.beta
        p[EK.P_MS0] = self.nominal_mass
        p[EK.P_CS] = self.skyhook_damping
        p[EK.P_C0] = self.passive_damping
        p[EK.P_INV_HYST] = _INVERSE_KINDS[self.inverse]


@dataclass(frozen=True)
class IdealSkyhook(Controller):
    """Ideal skyhook (3.12): force ``-c_s z_s'`` when ``z_s' v_d < 0`` (dissipative), else 0.

    Acts through an ideal dissipative damper in place of the MR damper (a reference).
    """

    skyhook_damping: float = 6750.0
    law: ClassVar[str] = "ideal-skyhook"
    code: ClassVar[int] = EK.C_IDEAL_SKYHOOK
    force_source: ClassVar[int] = EK.F_SKYHOOK

    def __post_init__(self) -> None:
        object.__setattr__(
            self, "skyhook_damping", _check("skyhook_damping", self.skyhook_damping, 0.0, 1e7)
        )

    def _fill(self, p: npt.NDArray[np.float64]) -> None:
        p[EK.P_CS] = self.skyhook_damping


@dataclass(frozen=True)
class IdealOnOff(Controller):
    """Rakheja displacement on-off (3.13): ``c v_d`` when ``x_d v_d < 0``, else 0 (ideal damper)."""

    damping: float = 6750.0
    law: ClassVar[str] = "ideal-onoff"
    code: ClassVar[int] = EK.C_IDEAL_ONOFF
    force_source: ClassVar[int] = EK.F_ONOFF

    def __post_init__(self) -> None:
        object.__setattr__(self, "damping", _check("damping", self.damping, 0.0, 1e7))

    def _fill(self, p: npt.NDArray[np.float64]) -> None:
        p[EK.P_CS] = self.damping


def _hilo(policy: int) -> Any:
    def build(**options: Any) -> HiLo:
        return HiLo(policy, **options)

    return build


#: Controller constructors by law name (the scenario files' ``[controller] law``).
CONTROLLERS: dict[str, Any] = {
    "passive": Passive,
    "onoff-adfg": OnOffADFG,
    "skyhook-hilo": _hilo(1),
    "policy-ii": _hilo(2),
    "policy-iii": _hilo(3),
    "policy-iv": _hilo(4),
    "inverse-hilo": InverseHiLo,
    "sliding-mode": SlidingMode,
    "ideal-skyhook": IdealSkyhook,
    "ideal-onoff": IdealOnOff,
}


def make_controller(law: str, **options: Any) -> Controller:
    """Build a controller by law name with options (did-you-mean on unknown names)."""
    if law not in CONTROLLERS:
        raise unknown_name("controller law", law, CONTROLLERS)
    try:
        return CONTROLLERS[law](**options)
    except TypeError as exc:
        import inspect

        target = CONTROLLERS[law]
        sig_src = HiLo.__init__ if law in _POLICY_LAWS.values() else target.__init__
        names = [n for n in inspect.signature(sig_src).parameters if n not in ("self", "policy")]
        bad = [k for k in options if k not in names]
        if bad:
            raise unknown_name(f"option of controller {law!r}:", bad[0], names) from None
        raise ValidationError(f"controller {law!r}: {exc}") from None
