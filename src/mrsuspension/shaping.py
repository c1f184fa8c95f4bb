"""Current shaping (model reference, section 3): ADFG and CM multipliers, drive-current composition.

Each law is written once as a scalar function and compiled twice by numba: as a scalar
kernel (``*_kernel``, called by the simulation engine inside its compiled step) and as a
broadcasting ufunc (the public array functions below).

* ADFG multiplier (2.3): ``M_p = c + (2/pi)(S - c)|atan(xi v_d / v_m)|`` with ``S = p``
  in compression (``v_d > 0``), else 1, and the value at ``v_d = 0``
  ``c = p + centre (1 - p)``: ``centre = 0.5`` is (2.3) as printed (``c = (1+p)/2``),
  ``centre = 0`` section 3.2's "p = 0 ... letting i_d = 0 when v_r = 0" (``c = p``); the
  control laws use 0.1, identified from the dissertation's currents (``docs/errata.md``,
  "Control unknowns identified"). It makes a symmetric damper
  act asymmetrically (light compression, ``p = 0``) without switching transients.
* On-off ADFG (2.1): ``i = p i_c`` in compression, ``i_c`` otherwise.
* CM multiplier (3.8): ``M_c = (1+p_c)/2 + (2/pi)(S - (1+p_c)/2)|atan(xi_c z_c)|`` with
  ``S = p_c`` for ``z_c >= 0``, else 1 (high current when the switching condition is
  negative).
* Drive current (3.9)/(3.16): ``i_d = clip(M_p M_c i_z, 0, i_max)``.

Examples
--------
>>> float(adfg_multiplier(0.0, 0.3, p=0.0, xi=2.0))  # half way at zero velocity
0.5
>>> float(drive_current(0.4, velocity=-0.2, peak_velocity=0.3, switching=-1.0,
...                     p=1.0, xi=4.5, p_c=0.0, xi_c=10.0, max_current=0.5))  # doctest: +ELLIPSIS
0.387...
"""

from __future__ import annotations

import math

import numpy as np
import numpy.typing as npt
from numba import njit, vectorize

from mrsuspension._numba_cache import INLINED, invalidate_if_changed
from mrsuspension.errors import ValidationError, check_finite, check_range

# no other module's kernels are called here; registered so that a change of INLINED drops
# the cache
invalidate_if_changed(__file__)

__all__ = [
    "ADFG_CENTRE_PRINTED",
    "adfg_multiplier",
    "cm_multiplier",
    "drive_current",
    "onoff_adfg_current",
]

_TWO_OVER_PI = 2.0 / math.pi
#: ADFG ``centre`` (M_p at v_d = 0 as a share of the way from p to 1) of eq. (2.3) as
#: printed, the default of these functions; the control laws default to the value
#: identified from the dissertation's currents (``mrsuspension.control.shaped.ADFG_CENTRE``,
#: ``docs/errata.md``, "Control unknowns identified")
ADFG_CENTRE_PRINTED = 0.5


def _mp(velocity: float, peak_velocity: float, p: float, xi: float, centre: float) -> float:
    s = p if velocity > 0.0 else 1.0
    # (2.3) as printed, bit for bit, at the default centre
    mid = 0.5 * (1.0 + p) if centre == 0.5 else p + centre * (1.0 - p)
    return mid + _TWO_OVER_PI * (s - mid) * abs(math.atan(xi * velocity / peak_velocity))


def _mc(switching: float, p_c: float, xi_c: float) -> float:
    s = p_c if switching >= 0.0 else 1.0
    mid = 0.5 * (1.0 + p_c)
    return mid + _TWO_OVER_PI * (s - mid) * abs(math.atan(xi_c * switching))


def _onoff(control_current: float, velocity: float, p: float) -> float:
    return p * control_current if velocity > 0.0 else control_current


adfg_kernel = njit(cache=True, **INLINED)(_mp)
cm_kernel = njit(cache=True, **INLINED)(_mc)
onoff_kernel = njit(cache=True, **INLINED)(_onoff)


@njit(cache=True, **INLINED)
def drive_current_kernel(
    i_z: float,
    velocity: float,
    peak_velocity: float,
    switching: float,
    p: float,
    xi: float,
    p_c: float,
    xi_c: float,
    max_current: float,
    centre: float,
) -> float:
    """i_d = clip(M_p M_c i_z, 0, i_max), eqs. (3.9)/(3.16); ``centre`` places M_p(v_d = 0)."""
    if i_z == 0.0:  # M_p, M_c in [0, 1]: no current whatever they are (saves two arctans)
        return 0.0
    mp = 1.0 if p == 1.0 else adfg_kernel(velocity, peak_velocity, p, xi, centre)  # SCM: 1
    i = mp * cm_kernel(switching, p_c, xi_c) * i_z
    if i < 0.0:
        return 0.0
    if i > max_current:
        return max_current
    return i


_adfg_ufunc = vectorize(cache=True)(_mp)
_cm_ufunc = vectorize(cache=True)(_mc)
_onoff_ufunc = vectorize(cache=True)(_onoff)
_drive_ufunc = vectorize(cache=True)(drive_current_kernel.py_func)


def _check_p(name: str, value: float, *, open_high: bool = False) -> float:
    return float(check_range(name, value, 0.0, 1.0, high_inclusive=not open_high))


def _check_centre(value: float) -> float:
    return float(check_range("centre", value, 0.0, 0.5))


def _check_positive(name: str, value: float) -> float:
    return float(check_range(name, value, 0.0, None, low_inclusive=False))


def _check_peak_velocity(value: npt.ArrayLike) -> np.ndarray:
    return check_range("peak_velocity", value, 0.0, None, unit="m/s", low_inclusive=False)


def adfg_multiplier(
    velocity: npt.ArrayLike,
    peak_velocity: npt.ArrayLike,
    p: float,
    xi: float,
    centre: float = ADFG_CENTRE_PRINTED,
) -> np.ndarray:
    """ADFG multiplier M_p of eq. (2.3).

    Parameters
    ----------
    velocity : array_like
        Damper velocity v_d [m/s] (compression positive).
    peak_velocity : array_like
        v_m [m/s], > 0.
    p : float
        Asymmetry factor in [0, 1] (1: symmetric, SCM; 0: no compression current, ACM).
    xi : float
        Smoothing factor > 0 (slope of the arctan).
    centre : float, optional
        Where M_p sits at ``v_d = 0``, as a share of the way from ``p`` to 1, in [0, 0.5]:
        0.5 is (2.3) as printed (``(1+p)/2``), 0 makes it ``p`` (no current at rest in
        ACM); default :data:`ADFG_CENTRE_PRINTED`.

    Examples
    --------
    >>> import numpy as np
    >>> adfg_multiplier(np.array([-1e6, 1e6]), 1.0, p=0.2, xi=2.0).round(6)
    array([1. , 0.2])
    >>> float(adfg_multiplier(0.0, 1.0, p=0.0, xi=2.0, centre=0.5))
    0.5
    """
    v = check_finite("velocity", velocity)
    vm = _check_peak_velocity(peak_velocity)
    return np.asarray(
        _adfg_ufunc(v, vm, _check_p("p", p), _check_positive("xi", xi), _check_centre(centre))
    )


def cm_multiplier(switching: npt.ArrayLike, p_c: float, xi_c: float) -> np.ndarray:
    """CM multiplier M_c of eq. (3.8); 1 for strongly negative ``switching`` (z_c).

    ``p_c`` must be in [0, 1) and ``xi_c`` > 0.

    Examples
    --------
    >>> float(cm_multiplier(0.0, p_c=0.0, xi_c=10.0))  # half way at the switching point
    0.5
    >>> float(cm_multiplier(-1e9, p_c=0.0, xi_c=10.0))  # doctest: +ELLIPSIS
    0.99999...
    """
    z = check_finite("switching", switching)
    return np.asarray(
        _cm_ufunc(z, _check_p("p_c", p_c, open_high=True), _check_positive("xi_c", xi_c))
    )


def onoff_adfg_current(
    control_current: npt.ArrayLike, velocity: npt.ArrayLike, p: float
) -> np.ndarray:
    """On-off ADFG current of eq. (2.1): ``p i_c`` in compression, ``i_c`` otherwise.

    Examples
    --------
    >>> onoff_adfg_current(0.3, [0.1, -0.1], p=0.0)
    array([0. , 0.3])
    """
    i = check_range("control_current", control_current, 0.0, None, unit="A")
    v = check_finite("velocity", velocity)
    return np.asarray(_onoff_ufunc(i, v, _check_p("p", p)))


def drive_current(
    i_z: npt.ArrayLike,
    velocity: npt.ArrayLike,
    peak_velocity: npt.ArrayLike,
    switching: npt.ArrayLike,
    *,
    p: float = 1.0,
    xi: float = 4.5,
    p_c: float = 0.0,
    xi_c: float = 10.0,
    max_current: float = 0.5,
    centre: float = ADFG_CENTRE_PRINTED,
) -> np.ndarray:
    """Drive current ``clip(M_p M_c i_z, 0, i_max)`` of eqs. (3.9)/(3.16).

    Defaults are the Chapter 4 policy defaults (model reference, section 6): SCM (``p = 1``),
    ``xi = 4.5``, ``p_c = 0``, ``xi_c = 10``, ``i_max = 0.5 A``; ``centre`` as in
    :func:`adfg_multiplier`.
    """
    iz = check_finite("i_z", i_z)
    if np.any(iz < 0):
        raise ValidationError(f"i_z must be >= 0 A; got {iz.ravel()[np.argmin(iz.ravel())]:g} A")
    return np.asarray(
        _drive_ufunc(
            iz,
            check_finite("velocity", velocity),
            _check_peak_velocity(peak_velocity),
            check_finite("switching", switching),
            _check_p("p", p),
            _check_positive("xi", xi),
            _check_p("p_c", p_c, open_high=True),
            _check_positive("xi_c", xi_c),
            float(
                check_range("max_current", max_current, 0.0, 10.0, unit="A", low_inclusive=False)
            ),
            _check_centre(centre),
        )
    )
