"""Inverse-model sliding-mode control (3.19)-(3.35): :class:`SlidingMode`."""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar

import numpy as np
import numpy.typing as npt

from mrsuspension.control import kernel as CK
from mrsuspension.control.base import option
from mrsuspension.control.shaped import ADFG_CENTRE, INVERSE_KINDS, Shaped

__all__ = ["BETA", "BETA_COVERING", "SlidingMode"]

#: Default mass-uncertainty bound beta of (3.26)/(3.33), not given in the seed: 1.25, the
#: model reference's (model reference, section 6: "the studied +-25 % load range"). The
#: smallest beta that covers the studied sprung masses 422-703 kg about m_s0 = 563 kg is
#: :data:`BETA_COVERING` (563/422 = 1.3341), a stated reading of the findings scorecard
#: until the reference changes (``docs/errata.md``)
BETA = 1.25
#: the smallest beta covering the studied 422-703 kg (not the default)
BETA_COVERING = 1.335


@dataclass(frozen=True, init=False)
class SlidingMode(Shaped):
    """Inverse-model sliding-mode controller (3.19)-(3.35), up-positive frame.

    Tracks the single-DOF modified-skyhook reference (3.18) of nominal mass ``m_s0``::

        s   = e' + lambda e,  e = z_s - z_s0
        F_d0 = -k_s x_d + m_s0 z_s0'' - m_s0 lambda e'
        K   = m_s0 beta phi + (beta - 1)(|F_d0| + k_s |z_s| + k_s |z_u|)
        F_c = F_d0 - K sat(s / eps)

    then ``i_z`` = inverse(F_c) and ``z_c = -F_h F_c``. Defaults (Chapter 6): lambda 0.5,
    eps 0.05, phi 1.6, beta 1.335 (not given in the seed: the smallest beta whose range
    ``[m_s0/beta, beta m_s0]`` of (3.26) holds the studied 422-703 kg, 563/422 = 1.3341;
    identified in ``docs/errata.md``, "Control unknowns identified"), c_s 6750, c_0 2500,
    m_s0 563 kg, p_c 0, xi_c 150, xi 30, ADFG centre 0.1. ``inverse="mean"`` inverts
    the mean model whatever the damper (Fig. 6.1); see
    :class:`~mrsuspension.control.InverseHiLo`.

    Examples
    --------
    >>> float(SlidingMode(slope=1.0).params(0.5)[CK.P_LAMBDA])
    1.0
    """

    slope: float = option(
        0.5, unit="1/s", low=0.0, high=1e4, low_open=True, symbol="lambda", label="slope (lambda)"
    )
    boundary_layer: float = option(
        0.05, unit="m/s", low=0.0, high=1e3, low_open=True, symbol="eps",
        label="boundary_layer (eps)",
    )  # fmt: skip
    phi: float = option(1.6, unit="m/s^2", low=0.0, high=1e6, symbol="phi")
    beta: float = option(BETA, low=1.0, high=10.0, symbol="beta")
    nominal_mass: float = option(563.0, unit="kg", low=1.0, high=1e5, symbol="m_s0")
    skyhook_damping: float = option(6750.0, unit="N s/m", low=0.0, high=1e7, symbol="c_s")
    passive_damping: float = option(2500.0, unit="N s/m", low=0.0, high=1e7, symbol="c_0")
    inverse: str = option("hysteretic", choices=tuple(INVERSE_KINDS), label="inverse model")
    code: ClassVar[int] = CK.C_SLIDING
    law: ClassVar[str] = "sliding-mode"
    needs_inverse: ClassVar[bool] = True

    def __init__(
        self,
        *,
        slope: float = 0.5,
        boundary_layer: float = 0.05,
        phi: float = 1.6,
        beta: float = BETA,
        nominal_mass: float = 563.0,
        skyhook_damping: float = 6750.0,
        passive_damping: float = 2500.0,
        mode: str | None = None,
        p: float | None = None,
        xi: float = 30.0,
        p_c: float = 0.0,
        xi_c: float = 150.0,
        adfg_centre: float = ADFG_CENTRE,
        inverse: str = "hysteretic",
    ) -> None:
        object.__setattr__(self, "inverse", inverse)
        object.__setattr__(self, "slope", slope)
        object.__setattr__(self, "boundary_layer", boundary_layer)
        object.__setattr__(self, "phi", phi)
        object.__setattr__(self, "beta", beta)
        object.__setattr__(self, "nominal_mass", nominal_mass)
        object.__setattr__(self, "skyhook_damping", skyhook_damping)
        object.__setattr__(self, "passive_damping", passive_damping)
        self._set_shaping(mode, p, xi, p_c, xi_c, adfg_centre)
        self._validate()

    def _fill(self, p: npt.NDArray[np.float64]) -> None:
        self._fill_shaping(p)
        p[CK.P_LAMBDA] = self.slope
        p[CK.P_EPS] = self.boundary_layer
        p[CK.P_PHI] = self.phi
        p[CK.P_BETA] = self.beta
        p[CK.P_MS0] = self.nominal_mass
        p[CK.P_CS] = self.skyhook_damping
        p[CK.P_C0] = self.passive_damping
        p[CK.P_INV_HYST] = INVERSE_KINDS[self.inverse]
