"""Ideal references through an ideal dissipative damper: skyhook (3.12), on-off (3.13)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar

import numpy as np
import numpy.typing as npt

from mrsuspension.control import kernel as CK
from mrsuspension.control.base import Controller, option

__all__ = ["IdealOnOff", "IdealSkyhook"]


@dataclass(frozen=True)
class IdealSkyhook(Controller):
    """Ideal skyhook (3.12): force ``-c_s z_s'`` when ``z_s' v_d < 0`` (dissipative), else 0.

    Acts through an ideal dissipative damper in place of the MR damper (a reference).

    Examples
    --------
    >>> IdealSkyhook().drives_damper
    False
    """

    skyhook_damping: float = option(6750.0, unit="N s/m", low=0.0, high=1e7, symbol="c_s")
    law: ClassVar[str] = "ideal-skyhook"
    code: ClassVar[int] = CK.C_IDEAL_SKYHOOK
    force_source: ClassVar[int] = CK.F_SKYHOOK

    def _fill(self, p: npt.NDArray[np.float64]) -> None:
        p[CK.P_CS] = self.skyhook_damping


@dataclass(frozen=True)
class IdealOnOff(Controller):
    """Rakheja displacement on-off (3.13): ``c v_d`` when ``x_d v_d < 0``, else 0 (ideal damper).

    Examples
    --------
    >>> float(IdealOnOff(damping=1000.0).params(0.5)[CK.P_CS])
    1000.0
    """

    damping: float = option(6750.0, unit="N s/m", low=0.0, high=1e7, symbol="c_s")
    law: ClassVar[str] = "ideal-onoff"
    code: ClassVar[int] = CK.C_IDEAL_ONOFF
    force_source: ClassVar[int] = CK.F_ONOFF

    def _fill(self, p: npt.NDArray[np.float64]) -> None:
        p[CK.P_CS] = self.damping
