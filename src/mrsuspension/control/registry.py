"""The controller registry: laws by name (:data:`CONTROLLERS`), built by :func:`make_controller`."""

from __future__ import annotations

import inspect
from collections.abc import Callable
from typing import Any

from mrsuspension.control.base import Controller, ControlOption
from mrsuspension.control.hilo import POLICY_LAWS, HiLo
from mrsuspension.control.ideal import IdealOnOff, IdealSkyhook
from mrsuspension.control.inverse import InverseHiLo
from mrsuspension.control.literature import LAWS as LITERATURE_LAWS
from mrsuspension.control.modal import CornerSkyhook, ModalSkyhook, VehicleLaw
from mrsuspension.control.mpc import LAWS as MPC_LAWS
from mrsuspension.control.passive import OnOffADFG, Passive
from mrsuspension.control.sliding import SlidingMode
from mrsuspension.control.vehicle_lq import (
    VehicleLQ,
    VehicleLQActive,
    VehicleLQForce,
    VehicleLQG,
    VehicleLQGActive,
    VehicleLQGForce,
    VehicleMPC,
    VehicleMPCActive,
    VehicleMPCForce,
)
from mrsuspension.errors import ValidationError, unknown_name

__all__ = ["CONTROLLERS", "VEHICLE_LAWS", "controller_class", "law_options", "make_controller"]


def _hilo(policy: int) -> Callable[..., HiLo]:
    """The builder of one hi-lo policy (its law name fixes the policy)."""

    def build(**options: Any) -> HiLo:
        given = options.pop("policy", policy)
        if given != policy:
            raise ValidationError(
                f"policy {given!r} does not match law {POLICY_LAWS[policy]!r} (policy {policy})"
            )
        return HiLo(policy, **options)

    build.__qualname__ = build.__name__ = f"HiLo_{policy}"
    build.controller_class = HiLo  # type: ignore[attr-defined]
    build.policy = policy  # type: ignore[attr-defined]
    return build


#: Controller constructors by law name (the scenario files' ``[controller] law``).
#: Registering a law here is all the rest of the package needs (the scenario keys, the
#: monitor's form and the contract tests derive from it).
CONTROLLERS: dict[str, Any] = {
    "passive": Passive,
    "onoff-adfg": OnOffADFG,
    **{law: _hilo(policy) for policy, law in POLICY_LAWS.items()},
    "inverse-hilo": InverseHiLo,
    "sliding-mode": SlidingMode,
    "ideal-skyhook": IdealSkyhook,
    "ideal-onoff": IdealOnOff,
    **LITERATURE_LAWS,  # the literature's benchmark laws (control/literature.py)
    **MPC_LAWS,  # semi-active MPC with OSQP (control/mpc.py)
}


#: Whole-vehicle laws by name (:class:`~mrsuspension.control.modal.VehicleLaw`
#: plug-ins: a half or full car's ``[controller] law``; their fields are its keys).
#: Registering one here is all the scenarios, the engine and the monitor's form need.
VEHICLE_LAWS: dict[str, type[VehicleLaw]] = {
    cls.law: cls
    for cls in (
        ModalSkyhook,
        CornerSkyhook,
        VehicleLQ,
        VehicleLQActive,
        VehicleLQForce,
        VehicleLQG,
        VehicleLQGActive,
        VehicleLQGForce,
        VehicleMPC,
        VehicleMPCActive,
        VehicleMPCForce,
    )
}


def controller_class(law: str) -> type[Controller]:
    """The :class:`Controller` subclass behind law ``law``.

    Examples
    --------
    >>> controller_class("policy-iii").__name__, controller_class("passive").__name__
    ('HiLo', 'Passive')
    """
    if law not in CONTROLLERS:
        raise unknown_name("controller law", law, CONTROLLERS)
    target = CONTROLLERS[law]
    cls: type[Controller] = getattr(target, "controller_class", target)
    return cls


def law_options(law: str) -> list[ControlOption]:
    """The options of law ``law`` (name, default, unit, valid values), as its constructor takes them.

    Examples
    --------
    >>> [(o.name, o.default) for o in law_options("policy-iv")][:2]
    [('gain', 300.0), ('order', 2.0)]
    """
    cls = controller_class(law)
    policy = getattr(CONTROLLERS[law], "policy", None)
    if policy is not None:
        return HiLo.describe_options(policy)
    return cls.describe_options()


def make_controller(law: str, **options: Any) -> Controller:
    """Build a controller by law name with options (did-you-mean on unknown names).

    Examples
    --------
    >>> make_controller("passive", current=0.1)
    Passive(current=0.1)
    >>> make_controller(**make_controller("policy-ii", mode="ACM").describe()).law
    'policy-ii'
    """
    if law not in CONTROLLERS:
        raise unknown_name("controller law", law, CONTROLLERS)
    try:
        built: Controller = CONTROLLERS[law](**options)
        return built
    except TypeError as exc:
        cls = controller_class(law)
        init = cls.__init__ if cls is HiLo else cls
        names = [n for n in inspect.signature(init).parameters if n not in ("self", "policy")]
        bad = [k for k in options if k not in names and k != "policy"]
        if bad:
            raise unknown_name(f"option of controller {law!r}:", bad[0], names) from None
        raise ValidationError(f"controller {law!r}: {exc}") from None
