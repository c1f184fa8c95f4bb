"""Hi-lo policies I-IV (3.15): :class:`HiLo`."""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import ClassVar

import numpy as np
import numpy.typing as npt

from mrsuspension.control import kernel as CK
from mrsuspension.control.base import ControlOption, option
from mrsuspension.control.shaped import ADFG_CENTRE, Shaped
from mrsuspension.errors import ValidationError

__all__ = ["POLICY_GAINS", "POLICY_LAWS", "HiLo"]

#: policy -> law name of the registry
POLICY_LAWS = {1: "skyhook-hilo", 2: "policy-ii", 3: "policy-iii", 4: "policy-iv"}
#: Chapter 4 policy-comparison gains k_c (section 4.3.1): 3, 10, 10, 300.
POLICY_GAINS = {1: 3.0, 2: 10.0, 3: 10.0, 4: 300.0}


@dataclass(frozen=True, init=False)
class HiLo(Shaped):
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
    xi_c = 10 on z_c in SI units, xi = 4.5, ADFG centre 0.5 ((2.3) as printed);
    ``mode="SCM"`` (p = 1, default) or ``"ACM"`` (p = 0). Section 4.3.1's figures read as
    the dissertation describes them with z_c in centimetre units, ``xi_c = 1e5`` here
    (``docs/errata.md``, "The hi-lo policies checked against the equations").

    Examples
    --------
    >>> HiLo(2).gain, HiLo(1, mode="ACM").p
    (10.0, 0.0)
    """

    policy: int = 1
    gain: float = option(3.0, low=0.0, high=1e9, symbol="k_c", label="gain k_c")
    order: float = option(2.0, low=0.0, high=10.0, low_open=True, symbol="n", label="order n")
    code: ClassVar[int] = CK.C_POLICY

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
        adfg_centre: float = ADFG_CENTRE,
    ) -> None:
        if policy not in POLICY_LAWS:
            raise ValidationError(f"policy must be 1, 2, 3 or 4; got {policy!r}")
        object.__setattr__(self, "policy", int(policy))
        object.__setattr__(self, "gain", POLICY_GAINS[policy] if gain is None else gain)
        object.__setattr__(self, "order", order)
        self._set_shaping(mode, p, xi, p_c, xi_c, adfg_centre)
        self._validate()

    @property
    def law(self) -> str:  # type: ignore[override]
        return POLICY_LAWS[self.policy]

    @classmethod
    def describe_options(cls, policy: int = 1) -> list[ControlOption]:
        """The options of policy ``policy`` (its default gain; see :meth:`Controller.describe_options`).

        Examples
        --------
        >>> [o.default for o in HiLo.describe_options(4) if o.name == "gain"]
        [300.0]
        """
        out = super().describe_options()
        gain = POLICY_GAINS[policy]
        return [replace(o, default=gain) if o.name == "gain" else o for o in out]

    def __repr__(self) -> str:
        return (
            f"HiLo(policy={self.policy}, gain={self.gain}, order={self.order}, p={self.p}, "
            f"xi={self.xi}, p_c={self.p_c}, xi_c={self.xi_c}, adfg_centre={self.adfg_centre})"
        )

    def _fill(self, p: npt.NDArray[np.float64]) -> None:
        self._fill_shaping(p)
        p[CK.P_POLICY] = self.policy
        p[CK.P_GAIN] = self.gain
        p[CK.P_ORDER] = self.order
