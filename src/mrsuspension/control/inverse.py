"""Inverse-model hi-lo (3.17): :class:`InverseHiLo`."""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar

import numpy as np
import numpy.typing as npt

from mrsuspension.control import kernel as CK
from mrsuspension.control.base import option
from mrsuspension.control.shaped import ADFG_CENTRE, INVERSE_KINDS, Shaped

__all__ = ["InverseHiLo"]


@dataclass(frozen=True, init=False)
class InverseHiLo(Shaped):
    """Inverse-model hi-lo (3.17): track ``F* = k_s x_d`` when it opposes the spring force.

    ``i_z`` = inverse(F*), ``z_c = F_h k_s x_d``. Chapter 5 defaults: p_c = 0, xi_c = 50,
    xi = 10, ADFG centre 0.1 (and the damper's force gain k_d = 2.5). Needs the dissertation's symmetric
    damper model (its inverse: model reference, section 2.3). ``inverse="mean"`` inverts the mean
    model (``v_h = 0``) whatever the damper, as in Figs 5.2 and 5.5 (hysteretic damper,
    mean inverse); the default ``"hysteretic"`` inverts the damper's own model.

    Examples
    --------
    >>> InverseHiLo(mode="ACM", inverse="mean").inverse
    'mean'
    """

    inverse: str = option("hysteretic", choices=tuple(INVERSE_KINDS), label="inverse model")
    code: ClassVar[int] = CK.C_INVERSE_HILO
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
        adfg_centre: float = ADFG_CENTRE,
        inverse: str = "hysteretic",
    ) -> None:
        self._set_shaping(mode, p, xi, p_c, xi_c, adfg_centre)
        object.__setattr__(self, "inverse", inverse)
        self._validate()

    def _fill(self, p: npt.NDArray[np.float64]) -> None:
        self._fill_shaping(p)
        p[CK.P_INV_HYST] = INVERSE_KINDS[self.inverse]
