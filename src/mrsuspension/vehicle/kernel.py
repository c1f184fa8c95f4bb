"""The quarter car's compiled equations (model reference, sections 4-5): state, parameter layouts.

The one place the vehicle's equations are written, for the engine's scalar step
(``engine/kernel.py``), its lane kernel (``engine/lanes.py``)
and, through the engine, the HiL loop.

State ``y`` (``NY`` values, indices ``Y_*``)::

    y = [z_s, z_s', z_u, z_u', z_s0, z_s0']

the last two being the single-DOF modified-skyhook reference model (3.18) that the
sliding-mode controller tracks, integrated with the plant (zero otherwise).

Parameters ``vp`` (:meth:`mrsuspension.vehicle.QuarterCar.params`, indices ``V_*``):
``m_s, m_u, k_s, k_t, c_t, c_sky, g, dx_u`` (``dx_u`` the static tire deflection).
"""

from __future__ import annotations

from numba import njit

__all__ = [
    "NY",
    "VP_SIZE",
    "V_CSKY",
    "V_CT",
    "V_DXU",
    "V_G",
    "V_KS",
    "V_KT",
    "V_MS",
    "V_MU",
    "Y_V0",
    "Y_VS",
    "Y_VU",
    "Y_Z0",
    "Y_ZS",
    "Y_ZU",
    "plant_rates",
]

# vehicle parameters (QuarterCar.params): m_s, m_u, k_s, k_t, c_t, c_sky, g, dx_u
V_MS, V_MU, V_KS, V_KT, V_CT, V_CSKY, V_G, V_DXU = range(8)
VP_SIZE = 8

# state: z_s, z_s', z_u, z_u', and the reference model's z_s0, z_s0'
Y_ZS, Y_VS, Y_ZU, Y_VU, Y_Z0, Y_V0 = range(6)
NY = 6


# inlined by numba (not compiled on its own, see mrsuspension._numba_cache.INLINED): the
# lane kernel's vectorised stages apply their fused multiply-adds to it
@njit(cache=True, inline="always")
def plant_rates(
    zs: float,
    vs: float,
    zu: float,
    vu: float,
    z0: float,
    v0: float,
    zr: float,
    zrd: float,
    fd: float,
    ks: float,
    csky: float,
    inv_ms: float,
    inv_mu: float,
    weight: float,
    kt: float,
    ct: float,
    dxu: float,
    reference: bool,
    c0: float,
    cs: float,
    inv_ms0: float,
) -> tuple[float, float, float, float]:
    """``(z_s'', z_u'', z_s0'', F_T)`` given the damper force (model reference, section 4).

    Branch-free (selects), so that a loop over independent cars compiles to vector
    instructions. ``weight = (m_s + m_u) g``; the tire force is zero when the tire has
    lifted off (``delta <= 0``) and never pulls. With ``reference``, ``z_s0''`` is the
    single-DOF modified-skyhook reference (3.18) of mass ``1 / inv_ms0``, passive damping
    ``c0`` and skyhook damping ``cs``, driven by the plant's ``z_u``; else 0.

    Examples
    --------
    A quarter car at rest on a static road: no acceleration, the tire carries the weight.

    >>> from mrsuspension.vehicle import QuarterCar
    >>> car = QuarterCar()
    >>> a_s, a_u, a_0, ft = plant_rates(
    ...     0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, car.suspension_stiffness, 0.0,
    ...     1.0 / car.sprung_mass, 1.0 / car.unsprung_mass, car.static_load,
    ...     car.tire_stiffness, car.tire_damping, car.static_tire_deflection, False, 0.0, 0.0,
    ...     0.0,
    ... )
    >>> abs(a_s) < 1e-12 and abs(a_u) < 1e-9 and round(ft, 6) == round(car.static_load, 6)
    True
    """
    xd = zu - zs
    delta = zr - zu + dxu
    ft = kt * delta + ct * (zrd - vu)
    ft = 0.0 if ft < 0.0 else ft
    ft = ft if delta > 0.0 else 0.0
    spring = ks * xd
    a_s = (spring + fd - csky * vs) * inv_ms
    a_u = (ft - weight - spring - fd) * inv_mu
    # single-DOF modified-skyhook reference (3.18), driven by the plant's z_u
    a_0 = (-c0 * (v0 - vu) - cs * v0 - ks * (z0 - zu)) * inv_ms0 if reference else 0.0
    return a_s, a_u, a_0, ft
