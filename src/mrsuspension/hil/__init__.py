"""Hardware-in-the-loop platform (dissertation Chapter 7, spec section 11).

The quarter car minus its damper runs in real time around a rig carrying the damper: the
measured force closes the loop through the engine's compiled step. Pieces:

- :mod:`~mrsuspension.hil.rig`: the :class:`Rig` interface, :class:`SimulatedRig` and the
  :func:`ideal_rig` preset;
- :mod:`~mrsuspension.hil.driver`: the PI drive-current regulator;
- :mod:`~mrsuspension.hil.safety`: limits, trips and the start-up sequence;
- :mod:`~mrsuspension.hil.recorder`: incremental recording and :func:`load_recording`;
- :mod:`~mrsuspension.hil.loop`: the real-time loop, :func:`run_hil`;
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

from mrsuspension.hil.driver import PICurrentDriver
from mrsuspension.hil.loop import CHANNELS, HilResult, LiveChange, LoopHooks, TickStats, run_hil
from mrsuspension.hil.network import UdpRig, serve_rig
from mrsuspension.hil.recorder import Recorder, Recording, load_recording
from mrsuspension.hil.rig import Rig, RigSample, SimulatedRig, ideal_rig
from mrsuspension.hil.safety import SafetyLimits, SafetySupervisor, StartUp
from mrsuspension.hil.tap import ChangeQueue, StopFlag, TapRing

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
