"""HiL browser monitor (dissertation section 7.2.3): a page served by the toolkit.

See ``docs/monitor.md``. :func:`create_app` builds the ASGI app;
:func:`~mrsuspension.monitor.cli.monitor_command` serves it (``mrsus monitor``).
Needs the ``web`` extra (starlette, uvicorn, websockets).
"""

from __future__ import annotations

from mrsuspension.monitor.cli import check_bind, monitor_command
from mrsuspension.monitor.settings import MonitorSettings, scenario_from_settings

__all__ = [
    "MonitorSettings",
    "check_bind",
    "create_app",
    "monitor_command",
    "scenario_from_settings",
]


def __getattr__(name: str) -> object:
    if name == "create_app":  # starlette imported on demand
        from mrsuspension.monitor.app import create_app

        return create_app
    raise AttributeError(name)
