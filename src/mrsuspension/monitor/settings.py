"""Monitor page settings -> a validated :class:`~mrsuspension.scenario.Scenario`.

The page sends a flat dictionary of its form fields; :func:`scenario_from_settings` turns
it into scenario tables and validates them with :meth:`Scenario.from_dict` (and by
building the simulation), so an invalid entry raises
:class:`~mrsuspension.errors.ValidationError` before anything reaches the loop.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from mrsuspension.errors import ValidationError
from mrsuspension.excitation import PRESET_ROADS
from mrsuspension.scenario import Scenario

__all__ = ["CONTROLLERS", "EXCITATIONS", "MonitorSettings", "scenario_from_settings"]

#: controller choices of the page
CONTROLLERS = ("passive-zero", "fixed-current", "skyhook-hilo", "inverse-hilo", "sliding-mode")
#: excitation choices of the page
EXCITATIONS = ("zero", "harmonic", "pulse", "road")
#: drive-current limit of the monitored run [A] (the HiL safety limit)
MAX_CURRENT = 0.3
#: placeholder excitation used to validate a "zero input" run (the road is then held at 0)
_ZERO_PLACEHOLDER = {"kind": "harmonic", "frequency": 1.0, "amplitude": 0.01}


@dataclass(frozen=True)
class MonitorSettings:
    """A validated monitor configuration.

    Attributes
    ----------
    tables : dict
        Scenario tables (as for :meth:`Scenario.from_dict`).
    zero_input : bool
        True when the road is held at zero (the tables then carry a placeholder excitation).
    rate : float
        Loop rate [Hz].
    duration : float
        Longest run [s] (STOP ends it earlier).
    """

    tables: dict[str, dict[str, Any]]
    zero_input: bool
    rate: float
    duration: float

    def scenario(self) -> Scenario:
        """The scenario of these settings."""
        return Scenario.from_dict(self.tables)

    def to_dict(self) -> dict[str, Any]:
        """Plain data (picklable, for the loop process)."""
        return {
            "tables": self.tables,
            "zero_input": self.zero_input,
            "rate": self.rate,
            "duration": self.duration,
        }


def _number(settings: Mapping[str, Any], key: str, default: float, label: str) -> float:
    raw = settings.get(key, default)
    if raw is None or raw == "":
        raw = default
    try:
        value = float(raw)
    except (TypeError, ValueError):
        raise ValidationError(f"{label} must be a number; got {raw!r}") from None
    if not math.isfinite(value):
        raise ValidationError(f"{label} must be finite; got {raw!r}")
    return value


def _choice(settings: Mapping[str, Any], key: str, choices: tuple[str, ...], default: str) -> str:
    value = str(settings.get(key, default))
    if value not in choices:
        raise ValidationError(f"unknown {key} {value!r}; valid: {', '.join(choices)}")
    return value


def scenario_from_settings(settings: Mapping[str, Any]) -> MonitorSettings:
    """Validate the page's settings and build the scenario tables.

    Parameters
    ----------
    settings : mapping
        Form fields: ``controller`` (one of :data:`CONTROLLERS`), ``current``, ``gain``
        (k_c), ``order``, ``lambda``, ``eps``, ``mode`` (``SCM``/``ACM``), ``excitation``
        (one of :data:`EXCITATIONS`), ``frequency``, ``amplitude``, ``height``,
        ``severity``, ``speed``, ``profile``, ``road_speed``, ``scale``, ``sprung_mass``,
        ``rate``, ``duration``.

    Returns
    -------
    MonitorSettings
        The validated configuration.

    Raises
    ------
    ValidationError
        For an unknown choice, a non-number or a value the scenario layer refuses.
    """
    law = _choice(settings, "controller", CONTROLLERS, "skyhook-hilo")
    mode = _choice(settings, "mode", ("SCM", "ACM"), "ACM")
    controller: dict[str, Any]
    if law == "passive-zero":
        controller = {"law": "passive", "current": 0.0}
    elif law == "fixed-current":
        controller = {"law": "passive", "current": _number(settings, "current", 0.1, "current")}
    elif law == "skyhook-hilo":
        controller = {
            "law": "skyhook-hilo",
            "mode": mode,
            "gain": _number(settings, "gain", 3.0, "k_c"),
            "order": _number(settings, "order", 2.0, "order n"),
        }
    elif law == "inverse-hilo":
        controller = {"law": "inverse-hilo", "mode": mode}
    else:
        controller = {
            "law": "sliding-mode",
            "mode": mode,
            "lambda": _number(settings, "lambda", 0.5, "lambda"),
            "eps": _number(settings, "eps", 0.05, "eps"),
        }

    kind = _choice(settings, "excitation", EXCITATIONS, "harmonic")
    excitation: dict[str, Any]
    if kind == "zero":
        excitation = dict(_ZERO_PLACEHOLDER)
    elif kind == "harmonic":
        excitation = {
            "kind": "harmonic",
            "frequency": _number(settings, "frequency", 1.5, "frequency"),
            "amplitude": _number(settings, "amplitude", 0.02, "amplitude"),
        }
    elif kind == "pulse":
        excitation = {
            "kind": "pulse",
            "amplitude": _number(settings, "height", 0.05, "pulse height"),
            "severity": _number(settings, "severity", 1.0, "severity"),
            "speed": _number(settings, "speed", 50.0, "speed"),
        }
    else:
        profile = str(settings.get("profile", "smooth"))
        if profile not in PRESET_ROADS:  # no file paths from the page
            raise ValidationError(
                f"unknown road preset {profile!r}; valid: {', '.join(PRESET_ROADS)}"
            )
        excitation = {
            "kind": "road",
            "profile": profile,
            "speed": _number(settings, "road_speed", 50.0, "road speed"),
            "scale": _number(settings, "scale", 1.0, "scale"),
        }
    tables: dict[str, dict[str, Any]] = {
        "vehicle": {"sprung_mass": _number(settings, "sprung_mass", 563.0, "sprung mass")},
        "damper": {"max_current": MAX_CURRENT},
        "controller": controller,
        "excitation": excitation,
    }
    rate = _number(settings, "rate", 1000.0, "loop rate")
    if not 50.0 <= rate <= 5000.0:
        raise ValidationError(f"loop rate must be in [50, 5000] Hz; got {rate:g} Hz")
    duration = _number(settings, "duration", 60.0, "duration")
    if not 0.0 < duration <= 3600.0:
        raise ValidationError(f"duration must be in (0, 3600] s; got {duration:g} s")
    scenario = Scenario.from_dict(tables)
    scenario.simulations()  # builds the simulation: refuses e.g. a current above i_max
    return MonitorSettings(tables=tables, zero_input=kind == "zero", rate=rate, duration=duration)
