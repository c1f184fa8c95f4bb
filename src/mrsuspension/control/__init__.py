"""Semi-active controllers (model reference, section 6), one interface.

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

The literature's benchmark laws (groundhook, hybrid skyhook-groundhook, ADD, SH-ADD,
PDD, clipped-optimal LQ: ``add``, ``sh-add``, ``clipped-lq``...) are registered too, written
with :func:`law` in :mod:`~mrsuspension.control.literature`, and semi-active MPC with OSQP
(``mpc``, ``mpc-hilo``) in :mod:`~mrsuspension.control.mpc`.

Laws of your own: :func:`law` makes a plain Python function of the measured signals
(:mod:`~mrsuspension.control.signals`) a controller (:mod:`~mrsuspension.control.user`;
``docs/control-laws.md``); a scenario names it ``law = "my_module:my_law"``.

Drive current (3.9)/(3.16): ``i_d = clip(M_p(p, xi, v_d) M_c(p_c, xi_c, z_c) i_z, 0, i_max)``;
``mode="SCM"`` sets ``p = 1`` (symmetric), ``mode="ACM"`` sets ``p = 0`` (asymmetric).

One module per family (:mod:`~mrsuspension.control.passive`,
:mod:`~mrsuspension.control.hilo`, :mod:`~mrsuspension.control.inverse`,
:mod:`~mrsuspension.control.sliding`, :mod:`~mrsuspension.control.ideal`), the interface in
:mod:`~mrsuspension.control.base`, the compiled laws and layouts in
:mod:`~mrsuspension.control.kernel` and the registry in
:mod:`~mrsuspension.control.registry`. Adding a law touches this package only (see
``docs/develop.md``).

Vehicle pieces the engine calls: :mod:`~mrsuspension.control.sensing` (body velocity
from an accelerometer, stroke sensor) and :mod:`~mrsuspension.control.modal` (modal
skyhook for the half and full car, with hi-lo clipping per corner) and
:mod:`~mrsuspension.control.vehicle_lq` (the whole-vehicle LQ and LQG laws).

Examples
--------
>>> make_controller("skyhook-hilo", mode="ACM")
HiLo(policy=1, gain=3.0, order=2.0, p=0.0, xi=4.5, p_c=0.0, xi_c=10.0, adfg_centre=0.5)
"""

from __future__ import annotations

from mrsuspension.control.base import Controller, ControlOption
from mrsuspension.control.hilo import POLICY_GAINS, HiLo
from mrsuspension.control.ideal import IdealOnOff, IdealSkyhook
from mrsuspension.control.inverse import InverseHiLo
from mrsuspension.control.modal import CornerSkyhook, ModalSkyhook, VehicleLaw
from mrsuspension.control.passive import OnOffADFG, Passive
from mrsuspension.control.registry import (
    CONTROLLERS,
    VEHICLE_LAWS,
    controller_class,
    law_options,
    make_controller,
)
from mrsuspension.control.sensing import BandPassObserver, LeakyIntegrator, StrokeSensor
from mrsuspension.control.sliding import SlidingMode
from mrsuspension.control.user import UserLaw, law, load_law
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

__all__ = [
    "CONTROLLERS",
    "POLICY_GAINS",
    "VEHICLE_LAWS",
    "BandPassObserver",
    "ControlOption",
    "Controller",
    "CornerSkyhook",
    "HiLo",
    "IdealOnOff",
    "IdealSkyhook",
    "InverseHiLo",
    "LeakyIntegrator",
    "ModalSkyhook",
    "OnOffADFG",
    "Passive",
    "SlidingMode",
    "StrokeSensor",
    "UserLaw",
    "VehicleLQ",
    "VehicleLQActive",
    "VehicleLQForce",
    "VehicleLQG",
    "VehicleLQGActive",
    "VehicleLQGForce",
    "VehicleLaw",
    "VehicleMPC",
    "VehicleMPCActive",
    "VehicleMPCForce",
    "controller_class",
    "law",
    "law_options",
    "load_law",
    "make_controller",
]
