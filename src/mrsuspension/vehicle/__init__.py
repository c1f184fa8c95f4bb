"""The quarter-vehicle model and the skyhook reference models (model reference, sections 4-5).

Coordinates are positive **up**, measured from static equilibrium: sprung mass ``z_s``,
unsprung mass ``z_u``, road ``z_r``. The damper stroke is ``x_d = z_u - z_s`` (compression
positive) and a positive damper force pushes the sprung mass up::

    m_s z_s'' =  k_s x_d + F_d - c_sky z_s'
    m_u z_u'' =  F_T - (m_s + m_u) g - k_s x_d - F_d
    F_T = max(0, k_t delta + c_t (z_r' - z_u'))  if delta = z_r - z_u + dx_u > 0, else 0

(erratum 1: the unsprung gravity term is consistent with equilibrium at rest). ``c_sky`` is
zero for a real vehicle and the skyhook coefficient ``c_s`` for the modified-skyhook
reference model of section 5.

Examples
--------
>>> car = QuarterCar()
>>> round(car.static_suspension_deflection * 100, 2), round(car.static_tire_deflection * 100, 2)
(9.69, 2.25)
>>> round(car.body_frequency(), 2)
1.46
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass, replace
from typing import TYPE_CHECKING, Any

import numpy as np
import numpy.typing as npt

from mrsuspension._lazy import lazy_namespace
from mrsuspension.errors import ValidationError, check_finite

if TYPE_CHECKING:
    from mrsuspension.vehicle.body import CORNERS_FULL, CORNERS_HALF, FullCar, HalfCar

__all__ = [
    "CORNERS_FULL",
    "CORNERS_HALF",
    "GRAVITY",
    "FullCar",
    "HalfCar",
    "QuarterCar",
    "linear_frequency_response",
]

# the half and full cars (vehicle/body.py) load on first use
__getattr__, __dir__ = lazy_namespace(
    __name__,
    dict.fromkeys(
        ("CORNERS_FULL", "CORNERS_HALF", "FullCar", "HalfCar"), "mrsuspension.vehicle.body"
    ),
    globals(),
)

#: Gravitational acceleration [m/s^2] (model reference, section 1).
GRAVITY = 9.81

_LIMITS = {
    "sprung_mass": (1.0, 1e5, "kg"),
    "unsprung_mass": (0.1, 1e4, "kg"),
    "suspension_stiffness": (1.0, 1e8, "N/m"),
    "tire_stiffness": (1.0, 1e9, "N/m"),
    "tire_damping": (0.0, 1e6, "N s/m"),
    "skyhook_damping": (0.0, 1e7, "N s/m"),
}


@dataclass(frozen=True)
class QuarterCar:
    """Two-degree-of-freedom quarter vehicle (nominal values: model reference, section 4).

    Parameters
    ----------
    sprung_mass : float
        m_s [kg] (563).
    unsprung_mass : float
        m_u [kg] (90).
    suspension_stiffness : float
        k_s [N/m] (57 000).
    tire_stiffness : float
        k_t [N/m] (285 000).
    tire_damping : float
        c_t [N s/m] (100).
    skyhook_damping : float
        c_sky [N s/m] of a damper from the sprung mass to the inertial frame (0; the
        modified-skyhook reference model of section 5 uses 6750).
    """

    sprung_mass: float = 563.0
    unsprung_mass: float = 90.0
    suspension_stiffness: float = 57_000.0
    tire_stiffness: float = 285_000.0
    tire_damping: float = 100.0
    skyhook_damping: float = 0.0

    def __post_init__(self) -> None:
        for name, (lo, hi, unit) in _LIMITS.items():
            value = getattr(self, name)
            if isinstance(value, bool) or not isinstance(value, int | float):
                raise ValidationError(f"{name} must be a number in {unit}; got {value!r}")
            if not (math.isfinite(value) and lo <= value <= hi):
                raise ValidationError(
                    f"{name} must be in [{lo:g}, {hi:g}] {unit}; got {value:g} {unit}"
                )
            object.__setattr__(self, name, float(value))

    @classmethod
    def reference(cls, **overrides: float) -> QuarterCar:
        """Modified-skyhook reference vehicle (section 5): c_sky = c_s = 6750 N s/m.

        Pair it with a ``LinearViscous(damping=2500.0)`` damper (c_0) and no control.
        """
        return cls(**{"skyhook_damping": 6750.0, **overrides})

    def with_(self, **changes: float) -> QuarterCar:
        """A copy with some parameters changed (validated)."""
        for key in changes:
            if key not in _LIMITS:
                from mrsuspension.errors import unknown_name

                raise unknown_name("vehicle parameter", key, _LIMITS)
        return replace(self, **changes)

    @property
    def total_mass(self) -> float:
        """m_s + m_u [kg]."""
        return self.sprung_mass + self.unsprung_mass

    @property
    def static_load(self) -> float:
        """Static tire load (m_s + m_u) g [N]."""
        return self.total_mass * GRAVITY

    @property
    def static_suspension_deflection(self) -> float:
        """m_s g / k_s [m] (9.69 cm nominal)."""
        return self.sprung_mass * GRAVITY / self.suspension_stiffness

    @property
    def static_tire_deflection(self) -> float:
        """(m_s + m_u) g / k_t [m] (2.25 cm nominal)."""
        return self.static_load / self.tire_stiffness

    def body_frequency(self) -> float:
        """Sprung-mass natural frequency with the series stiffness k_s k_t/(k_s+k_t) [Hz].

        The dissertation reports about 1.3 / 1.5 / 1.7 Hz for m_s = 703 / 563 / 422 kg.
        """
        k = (
            self.suspension_stiffness
            * self.tire_stiffness
            / (self.suspension_stiffness + self.tire_stiffness)
        )
        return math.sqrt(k / self.sprung_mass) / (2.0 * math.pi)

    def wheel_hop_frequency(self) -> float:
        """Unsprung-mass natural frequency sqrt((k_s + k_t)/m_u) / 2 pi [Hz] (~10 Hz)."""
        return math.sqrt((self.suspension_stiffness + self.tire_stiffness) / self.unsprung_mass) / (
            2.0 * math.pi
        )

    def undamped_frequencies(self) -> tuple[float, float]:
        """Exact undamped natural frequencies of the 2-DOF model [Hz] (low, high)."""
        ms, mu, ks, kt = (
            self.sprung_mass,
            self.unsprung_mass,
            self.suspension_stiffness,
            self.tire_stiffness,
        )
        m = np.diag([ms, mu])
        k = np.array([[ks, -ks], [-ks, ks + kt]])
        w2 = np.sort(np.linalg.eigvals(np.linalg.solve(m, k)).real)
        return float(np.sqrt(w2[0]) / (2 * math.pi)), float(np.sqrt(w2[1]) / (2 * math.pi))

    def params(self) -> npt.NDArray[np.float64]:
        """Parameter vector of the compiled engine (layout: ``engine.kernel.V_*``)."""
        return np.array(
            [
                self.sprung_mass,
                self.unsprung_mass,
                self.suspension_stiffness,
                self.tire_stiffness,
                self.tire_damping,
                self.skyhook_damping,
                GRAVITY,
                self.static_tire_deflection,
            ]
        )

    def describe(self) -> dict[str, Any]:
        """Plain-data description."""
        return asdict(self)


def linear_frequency_response(
    car: QuarterCar, damping: float, frequency: npt.ArrayLike
) -> dict[str, np.ndarray]:
    """Exact steady-state response of the linear quarter car to ``z_r = sin(2 pi f t)``.

    With a linear damper ``F_d = c v_d`` and no tire lift-off the model is linear; the
    complex amplitudes follow from ``(-w^2 M + i w C + K) Z = F``. Returns the
    dimensionless ratios (model reference, section 9) for a harmonic road:
    ``T_as = |z_s''| / |z_r''| = |Z_s|``, ``T_au = |Z_u|``, ``T_dr = |Z_u - Z_s|``, and
    ``DLC`` per metre of road amplitude: ``|F_T| / sqrt(2) / ((m_s + m_u) g)`` (multiply by
    the road amplitude).

    Examples
    --------
    >>> r = linear_frequency_response(QuarterCar(), 2500.0, [0.01, 1.46])
    >>> bool(abs(r["T_as"][0] - 1) < 1e-3 and r["T_as"][1] > 2)
    True
    """
    f = check_finite("frequency", frequency)
    if np.any(f <= 0):
        raise ValidationError("frequency must be > 0 Hz")
    w = 2.0 * np.pi * np.asarray(f, dtype=float)
    ms, mu = car.sprung_mass, car.unsprung_mass
    ks, kt, ct, csky = (
        car.suspension_stiffness,
        car.tire_stiffness,
        car.tire_damping,
        car.skyhook_damping,
    )
    c = float(damping)
    out: dict[str, list[float]] = {
        "T_as": [],
        "T_au": [],
        "T_dr": [],
        "DLC": [],
        "T_ds": [],
        "T_du": [],
    }
    for wk in np.atleast_1d(w):
        j = 1j * wk
        a = np.array(
            [
                [-(wk**2) * ms + j * (c + csky) + ks, -(j * c + ks)],
                [-(j * c + ks), -(wk**2) * mu + j * (c + ct) + ks + kt],
            ]
        )
        rhs = np.array([0.0, kt + j * ct])
        zs, zu = np.linalg.solve(a, rhs)
        ft = (kt + j * ct) * (1.0 - zu)
        out["T_as"].append(abs(zs))
        out["T_au"].append(abs(zu))
        out["T_dr"].append(abs(zu - zs))
        out["T_ds"].append(abs(zs))
        out["T_du"].append(abs(zu))
        out["DLC"].append(abs(ft) / math.sqrt(2.0) / car.static_load)
    return {k: np.asarray(v).reshape(np.shape(w)) for k, v in out.items()}
