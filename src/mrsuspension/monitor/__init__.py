"""HiL browser monitor (dissertation section 7.2.3): a page served by the toolkit.

See ``docs/monitor.md``. Each run is :func:`~mrsuspension.hil.run_hil` with a rig in the
loop, in its own process, connected through the loop's live hooks (tap, STOP, settings
applied between ticks). :func:`create_app` builds the ASGI app;
:func:`~mrsuspension.monitor.server.serve` serves it (``mrsus monitor``, and
``mrsus hil run ... --monitor``). Needs the ``web`` extra (starlette, uvicorn,
websockets).
"""

from __future__ import annotations

from mrsuspension.monitor.server import check_bind, serve
from mrsuspension.monitor.settings import MonitorSettings, scenario_from_settings

__all__ = [
    "MonitorSettings",
    "check_bind",
    "create_app",
    "scenario_from_settings",
    "serve",
]


def __getattr__(name: str) -> object:
    if name == "create_app":  # starlette imported on demand
        from mrsuspension.monitor.app import create_app

        return create_app
    raise AttributeError(name)
