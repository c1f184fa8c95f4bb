"""Hardware-in-the-loop platform (dissertation Chapter 7; model reference, section 11).

The quarter car minus its damper runs in real time around a rig carrying the damper: the
measured force closes the loop through the engine's compiled step. Pieces:

- :mod:`~mrsuspension.hil.rig`: the :class:`Rig` interface, :class:`SimulatedRig` and the
  :func:`ideal_rig` preset;
- :mod:`~mrsuspension.hil.driver`: the PI drive-current regulator;
- :mod:`~mrsuspension.hil.safety`: limits, trips and the start-up sequence;
- :mod:`~mrsuspension.hil.recorder`: incremental recording and :func:`load_recording`;
- :mod:`~mrsuspension.hil.loop`: the real-time loop, :func:`run_hil`;
- :mod:`~mrsuspension.hil.vehicle`: a half or full car in that loop, one corner's damper
  on the rig and the rest of the car simulated (:class:`~mrsuspension.hil.vehicle.CornerPlant`);
- :mod:`~mrsuspension.hil.latency`: the machine's latency floor for that loop
  (``measure_latency``, ``mrsus hil latency``);
- :mod:`~mrsuspension.hil.live`: its live hooks (:class:`LoopHooks`,
  :class:`LiveChange`; the monitor's);
- :mod:`~mrsuspension.hil.tap`: :class:`TapRing`, :class:`StopFlag` and
  :class:`ChangeQueue`, the shared-memory tap ring, STOP flag and settings queue that
  the loop uses without locks or system calls;
- :mod:`~mrsuspension.hil.network`: the UDP rig protocol, :class:`UdpRig` and
  :func:`serve_rig`;
- :mod:`~mrsuspension.hil.validate`: HiL against offline (``validate.validate``).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from mrsuspension._lazy import lazy_namespace

if TYPE_CHECKING:
    from mrsuspension.hil.driver import PICurrentDriver
    from mrsuspension.hil.loop import (
        CHANNELS,
        HilResult,
        LiveChange,
        LoopHooks,
        TickStats,
        run_hil,
    )
    from mrsuspension.hil.network import UdpRig, serve_rig
    from mrsuspension.hil.recorder import Recorder, Recording, load_recording
    from mrsuspension.hil.rig import Rig, RigSample, SimulatedRig, ideal_rig
    from mrsuspension.hil.safety import SafetyLimits, SafetySupervisor, StartUp
    from mrsuspension.hil.tap import ChangeQueue, StopFlag, TapRing

# the names load on first use: `import mrsuspension.hil.rigs` (the CLI's help) stays cheap
_MODULES = {
    "mrsuspension.hil.driver": ("PICurrentDriver",),
    "mrsuspension.hil.loop": ("CHANNELS", "HilResult", "LiveChange", "LoopHooks", "TickStats", "run_hil"),
    "mrsuspension.hil.network": ("UdpRig", "serve_rig"),
    "mrsuspension.hil.recorder": ("Recorder", "Recording", "load_recording"),
    "mrsuspension.hil.rig": ("Rig", "RigSample", "SimulatedRig", "ideal_rig"),
    "mrsuspension.hil.safety": ("SafetyLimits", "SafetySupervisor", "StartUp"),
    "mrsuspension.hil.tap": ("ChangeQueue", "StopFlag", "TapRing"),
}  # fmt: skip
__getattr__, __dir__ = lazy_namespace(
    __name__, {n: m for m, names in _MODULES.items() for n in names}, globals()
)

__all__ = [
    "CHANNELS",
    "ChangeQueue",
    "HilResult",
    "LiveChange",
    "LoopHooks",
    "PICurrentDriver",
    "Recorder",
    "Recording",
    "Rig",
    "RigSample",
    "SafetyLimits",
    "SafetySupervisor",
    "SimulatedRig",
    "StartUp",
    "StopFlag",
    "TapRing",
    "TickStats",
    "UdpRig",
    "ideal_rig",
    "load_recording",
    "run_hil",
    "serve_rig",
]
