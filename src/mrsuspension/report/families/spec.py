"""Declaring figures: the kinds, their default excitations and what a figure family is.

A :class:`FigureSpec` states one figure as data (number, kind, base scenario, variants,
caption); each variant becomes a :class:`Unit` (:func:`make_unit`: one scenario under one
kind of analysis, with the kind's default excitation and step size filled in), the key
under which a run is shared. Here too: :data:`KINDS`, the default excitations
(:data:`PULSE`, :data:`ROAD`, :data:`SWEPT`; the harmonic one is the toolkit's), the run
lengths, the panels (:data:`SIGNALS`, :data:`DEFAULT_SIGNALS`, :data:`PSD_SIGNALS`,
:data:`FREQ_PANELS`), :func:`merge_tables` and :func:`road_note`. The package docstring
(:mod:`mrsuspension.report.families`) describes the kinds and step sizes.

Examples
--------
>>> make_unit("time", {}, quick=True).dt
0.0005
"""

from __future__ import annotations

import copy
import json
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import Any, NamedTuple

from mrsuspension.errors import ValidationError
from mrsuspension.report.toolkit import FREQUENCY_PANELS, HARMONIC

#: The kinds of figure family
KINDS: tuple[str, ...] = ("time", "freq", "pulse", "psd", "special")

#: Default excitation of each simulated kind (HARMONIC: the toolkit's)
PULSE: dict[str, Any] = {"kind": "pulse", "amplitude": 0.035, "severity": 3.0, "speed": 50.0}
ROAD: dict[str, Any] = {"kind": "road", "profile": "rough", "speed": 50.0}


def road_note(name: str = "rough") -> str:
    """Caption text for a preset road: a stand-in, and the PSD that defines it.

    Examples
    --------
    >>> road_note()
    "stand-in for the dissertation's Canadian road, defined by its PSD G_d(n) = 2.7e-05 (n/0.1)^-1 m^3 over 0.011-2 cycle/m"
    """
    from mrsuspension.excitation import PRESET_ROADS

    p = PRESET_ROADS[name]
    return (
        f"stand-in for the dissertation's Canadian road, defined by its PSD G_d(n) = "
        f"{p.level:.2g} (n/0.1)^-{p.waviness:g} m^3 over {p.band[0]:g}-{p.band[1]:g} cycle/m"
    )


SWEPT: dict[str, Any] = {"kind": "swept", "amplitude": 0.025, "transition_frequency": 2.1}
#: Run lengths [s]: harmonic, pulse (the road runs its own length)
HARMONIC_DURATION = 8.0
PULSE_DURATION = 4.0
# The window shown for harmonic runs and the start of their steady state [s]: the
# toolkit's SHOWN and STEADY_FROM
#: The laws that use the inverse damper model (smaller step in quick mode)
INVERSE_LAWS = ("inverse-hilo", "sliding-mode")

#: Time-history signals: name -> (result key, axis label)
SIGNALS: dict[str, tuple[str, str]] = {
    "F_d": ("F_d", "$F_d$ [N]"),
    "F*": ("F_target", "target force $F^*$ / $F_c$ [N]"),
    "i_d": ("i_d", "$i_d$ [A]"),
    "a_s": ("z_s_ddot", "$a_s$ [m/s$^2$]"),
    "a_u": ("z_u_ddot", "$a_u$ [m/s$^2$]"),
    "x_s": ("z_s", "$x_s$ [m]"),
    "x_u": ("z_u", "$x_u$ [m]"),
    "x_r": ("x_d", "$x_r$ [m]"),
    "v_r": ("v_d", "$v_r$ [m/s]"),
    "F_T": ("F_T", "$F_T$ [N]"),
}
#: Default panels of the time and pulse figures (Figs 4.8, 4.10 show these responses)
DEFAULT_SIGNALS: tuple[str, ...] = ("F_d", "i_d", "a_s", "a_u", "x_s", "x_u", "x_r", "F_T")
#: PSD panels (the dissertation's random-response figures), then the i_d history
PSD_SIGNALS: tuple[str, ...] = ("F_d", "a_s", "a_u", "x_r", "F_T")
#: Frequency-response panels
FREQ_PANELS: tuple[tuple[str, str], ...] = FREQUENCY_PANELS


def merge_tables(base: Mapping[str, Any], variant: Mapping[str, Any]) -> dict[str, Any]:
    """Base tables updated section by section; a variant controller with a law replaces.

    Examples
    --------
    >>> base = {"controller": {"law": "skyhook-hilo", "mode": "ACM"}}
    >>> merge_tables(base, {"controller": {"gain": 1.5}})["controller"]
    {'law': 'skyhook-hilo', 'mode': 'ACM', 'gain': 1.5}
    >>> merge_tables(base, {"controller": {"law": "passive"}})["controller"]
    {'law': 'passive'}
    """
    out = copy.deepcopy(dict(base))
    for section, table in variant.items():
        if not isinstance(table, Mapping):
            raise ValidationError(
                f"variant section [{section}] must be a table of keys, got {table!r}"
            )
        if section == "controller" and "law" in table:
            out[section] = dict(table)
        else:
            out[section] = {**out.get(section, {}), **table}
    return out


_merge = merge_tables


class Unit(NamedTuple):
    """One scenario under one kind of analysis: what is run once and shared.

    ``tables`` is the canonical JSON of the scenario tables (``excitation`` included).
    """

    kind: str
    tables: str
    dt: float

    @property
    def scenario(self) -> dict[str, Any]:
        """The scenario tables as a dict."""
        data: dict[str, Any] = json.loads(self.tables)
        return data


def _step(tables: Mapping[str, Any], quick: bool) -> float:
    if not quick:
        return 1e-4
    law = tables.get("controller", {}).get("law")
    gain = float(tables.get("damper", {}).get("force_gain", 1.0))
    return 2.5e-4 if law in INVERSE_LAWS or gain > 1.0 else 5e-4


_DEFAULT_EXCITATION = {"time": HARMONIC, "pulse": PULSE, "psd": ROAD, "freq": SWEPT}


def make_unit(kind: str, tables: Mapping[str, Any], quick: bool) -> Unit:
    """The :class:`Unit` of ``tables`` under ``kind`` (default excitation filled in).

    Parameters
    ----------
    kind : str
        ``"time"``, ``"freq"``, ``"pulse"`` or ``"psd"``.
    tables : mapping
        Scenario tables; an ``excitation`` table updates the kind's default excitation.
    quick : bool
        Quick-mode step sizes.

    Returns
    -------
    Unit

    Examples
    --------
    >>> make_unit("pulse", {"excitation": {"speed": 100.0}}, quick=True).scenario["excitation"]
    {'amplitude': 0.035, 'kind': 'pulse', 'severity': 3.0, 'speed': 100.0}
    """
    if kind not in _DEFAULT_EXCITATION:
        raise ValidationError(
            f"kind {kind!r} has no simulation unit; valid: {', '.join(_DEFAULT_EXCITATION)}"
        )
    full = copy.deepcopy(dict(tables))
    damper = full.get("damper", {})
    if float(damper.get("force_gain", 2.0)) == 1.0:  # the default: drop, so runs are shared
        damper = {k: v for k, v in damper.items() if k != "force_gain"}
        full["damper"] = damper
    if not full.get("damper", True):
        del full["damper"]
    full["excitation"] = {**_DEFAULT_EXCITATION[kind], **full.get("excitation", {})}
    canon = json.dumps(_normalise(full), sort_keys=True)
    return Unit(kind, canon, _step(full, quick))


def _normalise(value: Any, kind: str = "") -> Any:
    """Numbers as the scenario's key kinds (``number`` keys become floats, ``integer`` keys
    ints), so equal scenarios written as ``563`` and ``563.0`` share one key."""
    if isinstance(value, Mapping):
        from mrsuspension.scenario import SCENARIO_KEYS

        out = {}
        for k, v in value.items():
            keys = SCENARIO_KEYS.get(str(k))
            if keys is not None and isinstance(v, Mapping):
                out[str(k)] = {
                    str(kk): _normalise(vv, keys.get(str(kk), "")) for kk, vv in v.items()
                }
            else:
                out[str(k)] = _normalise(v)
        return out
    if isinstance(value, list | tuple):
        return [_normalise(v) for v in value]
    if isinstance(value, bool | str) or value is None:
        return value
    if kind == "integer" or (isinstance(value, int) and kind != "number"):
        return int(value)
    return float(value)


@dataclass(frozen=True)
class FigureSpec:
    """One figure as data: number, kind, base scenario, variants and caption.

    Parameters
    ----------
    number : str
        Figure number, e.g. ``"4.12"``.
    kind : str
        One of :data:`KINDS`.
    title : str
        Short title.
    caption : str
        The caption: what was run (controller, excitation, variants) and what to read.
    base : mapping
        Scenario tables common to every variant (``vehicle``, ``damper``, ``controller``,
        ``excitation``).
    variants : mapping
        Curve label -> table overrides (see the module docstring); at least one.
    signals : tuple of str
        Panels of time and pulse figures (keys of :data:`SIGNALS`); default
        :data:`DEFAULT_SIGNALS`.
    given : mapping
        The dissertation's numbers per variant label (psd: the DLC), shown beside ours.
    builder : callable, optional
        ``builder(quick) -> FigureRecord`` for ``kind="special"``.
    full_only : bool
        Built only in the full report.
    settings : mapping
        What the caption states, as data (:mod:`mrsuspension.report.captions`): a key of
        :data:`~mrsuspension.report.captions.SETTINGS` -> a value for every variant, or a
        mapping variant label -> value; checked against the runs and the caption by
        ``tests/unit/report/test_captions.py``.
    """

    number: str
    kind: str
    title: str
    caption: str
    base: Mapping[str, Any] = field(default_factory=dict)
    variants: Mapping[str, Mapping[str, Any]] = field(default_factory=dict)
    signals: tuple[str, ...] = DEFAULT_SIGNALS
    given: Mapping[str, float] = field(default_factory=dict)
    builder: Callable[[bool], Any] | None = None
    full_only: bool = False
    settings: Mapping[str, Any] = field(default_factory=dict)

    def __post_init__(self) -> None:
        where = f"figure {self.number}"
        from mrsuspension.report.captions import SETTINGS

        for key, value in self.settings.items():
            if key not in SETTINGS:
                raise ValidationError(
                    f"{where}: unknown setting {key!r}; valid: {', '.join(SETTINGS)}"
                )
            if isinstance(value, Mapping):
                bad = [label for label in value if label not in self.variants]
                if bad:
                    raise ValidationError(
                        f"{where}: setting {key!r} names variant(s) {', '.join(map(repr, bad))}, "
                        f"not among {', '.join(self.variants)}"
                    )
        if self.kind not in KINDS:
            raise ValidationError(
                f"{where}: kind {self.kind!r} is not valid; valid kinds: {', '.join(KINDS)}"
            )
        if self.kind == "special":
            if self.builder is None:
                raise ValidationError(f"{where}: kind 'special' needs a builder function")
            return
        if not self.variants:
            raise ValidationError(
                f"{where}: the variant list is empty; give at least one label -> overrides"
            )
        unknown = [s for s in self.signals if s not in SIGNALS]
        if unknown:
            raise ValidationError(
                f"{where}: unknown signal(s) {', '.join(unknown)}; valid: {', '.join(SIGNALS)}"
            )
        for label in self.given:
            if label not in self.variants:
                raise ValidationError(
                    f"{where}: 'given' names variant {label!r}, not one of "
                    f"{', '.join(self.variants)}"
                )
        for label in self.variants:
            self.scenario(label)  # validates the override tables

    @property
    def slug(self) -> str:
        """File stem, e.g. ``fig_4_12``."""
        return "fig_" + self.number.replace(".", "_")

    def scenario(self, label: str) -> dict[str, Any]:
        """The scenario tables of one variant (base updated by its overrides)."""
        return _merge(self.base, self.variants[label])

    def units(self, quick: bool) -> dict[str, Unit]:
        """Variant label -> the :class:`Unit` it needs (none for ``special``)."""
        if self.kind == "special":
            return {}
        return {label: make_unit(self.kind, self.scenario(label), quick) for label in self.variants}

    def describe(self) -> str:
        """One line per variant: its label and scenario tables (for docs and records)."""
        if self.kind == "special":
            doc = (self.builder.__doc__ or "").strip().splitlines() if self.builder else []
            return doc[0] if doc else "special"
        lines = []
        for label in self.variants:
            unit = make_unit(self.kind, self.scenario(label), quick=False)
            lines.append(f"{label}: {unit.tables}")
        return "\n".join(lines)
