"""Constant-current laws: :class:`Passive` (3.4) and the on-off ADFG :class:`OnOffADFG` (2.1)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar

import numpy as np
import numpy.typing as npt

from mrsuspension.control import kernel as CK
from mrsuspension.control.base import Controller, option
from mrsuspension.errors import ValidationError

__all__ = ["OnOffADFG", "Passive"]


@dataclass(frozen=True)
class Passive(Controller):
    """Constant drive current (3.4); the dissertation studies 0, 0.05, 0.1 and 0.2 A.

    Examples
    --------
    >>> float(Passive(0.1).params(0.5)[CK.P_CURRENT])
    0.1
    """

    current: float = option(0.0, unit="A", low=0.0, high=10.0, symbol="i")
    law: ClassVar[str] = "passive"
    code: ClassVar[int] = CK.C_PASSIVE

    def _fill(self, p: npt.NDArray[np.float64]) -> None:
        if self.current > p[CK.P_IMAX] + 1e-12:
            raise ValidationError(
                f"passive current {self.current:g} A exceeds max_current {p[CK.P_IMAX]:g} A"
            )
        p[CK.P_CURRENT] = self.current


@dataclass(frozen=True)
class OnOffADFG(Controller):
    """On-off ADFG (2.1): ``p i_H`` in compression, ``i_H`` in rebound (Fig. 4.3).

    Examples
    --------
    >>> OnOffADFG(current=0.4, p=0.5)
    OnOffADFG(current=0.4, p=0.5)
    """

    current: float = option(0.5, unit="A", low=0.0, high=10.0, symbol="i_H")
    p: float = option(0.0, low=0.0, high=1.0, symbol="p")
    law: ClassVar[str] = "onoff-adfg"
    code: ClassVar[int] = CK.C_ONOFF_ADFG

    def _fill(self, p: npt.NDArray[np.float64]) -> None:
        p[CK.P_CURRENT] = self.current
        p[CK.P_P] = self.p
