"""Declarative figure families for Chapters 4-6, and a process pool that builds them.

The three simulation chapters repeat the same analyses per controller (harmonic time
histories, frequency responses, rounded-pulse transients, random-road PSDs), each over a
set of variants. A :class:`FigureSpec` states one figure as data: its number, its
**kind**, the base scenario tables, the variants (label -> table overrides) and the
caption. Each variant of a spec becomes a :class:`Unit` (one scenario under one kind of
analysis); equal units are run once and shared by every figure and table that needs them
(the nominal controller appears in most figures of a chapter).

Kinds and their default excitation:

========  ===================================================================  ==========
kind      analysis                                                             panels
========  ===================================================================  ==========
time      harmonic 2.5 cm at 1.5 Hz, 8 s, steady window 6-7.4 s shown          signals
freq      two-stage swept excitation a = 2.5 cm, f_T = 2.1 Hz, 0.5-15 Hz       T_as, T_au,
                                                                               T_dr, DLC
pulse     rounded pulse mu = 3, a_m = 3.5 cm, 50 km/h (omega_0 = 10.4 rad/s)   signals
psd       'rough' preset road at 50 km/h                                       PSDs + i_d
special   a function ``builder(quick) -> FigureRecord``                        its own
========  ===================================================================  ==========

A variant's tables update the base section by section (``{"vehicle": {"sprung_mass":
422.0}}`` keeps the base controller); a variant ``controller`` table that names a ``law``
replaces the base controller table instead, so ``{"controller": {"law": "passive",
"current": 0.1}}`` does not inherit the base's ``mode`` or ``gain``.

Step sizes: quick mode uses 0.5 ms, or 0.25 ms for the inverse-model laws and any damper
force gain above 1 (a steeper pre-yield slope; RK4 limit about 0.27 ms at k_d = 2.5); the
full report uses the default 0.1 ms (model reference, section 7) throughout.

Examples
--------
>>> spec = FigureSpec(
...     number="4.12",
...     kind="time",
...     title="Sprung-mass variation",
...     caption="Skyhook hi-lo ACM.",
...     base={"controller": {"law": "skyhook-hilo", "mode": "ACM", "gain": 3.0}},
...     variants={"m_s = 422 kg": {"vehicle": {"sprung_mass": 422.0}}, "m_s = 563 kg": {}},
... )
>>> [u.kind for u in spec.units(quick=True).values()]
['time', 'time']
>>> spec.scenario("m_s = 422 kg")["vehicle"]
{'sprung_mass': 422.0}
>>> FigureSpec(number="4.99", kind="movie", title="t", caption="c", variants={"a": {}})
Traceback (most recent call last):
...
mrsuspension.errors.ValidationError: figure 4.99: kind 'movie' is not valid; valid kinds: time, freq, pulse, psd, special
"""

from __future__ import annotations

import copy
import heapq
import itertools
import json
import math
import time
from collections.abc import Callable, Iterator, Mapping, Sequence
from contextlib import contextmanager
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, NamedTuple

import numpy as np

from mrsuspension._pool import process_pool, worker_count
from mrsuspension.errors import ValidationError
from mrsuspension.report.toolkit import (
    FREQUENCY_PANELS,
    HARMONIC,
    SHOCK,
    SHOWN,
    STEADY_FROM,
    TABLE_MEASURES,
    FigureRecord,
    figure_legend,
    in_worker,
    label_outer_x,
    legend_columns,
    reused_subplots,
    share_x,
)

__all__ = [
    "AGREEMENT_BANDS",
    "HARMONIC_AMPS",
    "HARMONIC_AMPS_STATED",
    "KINDS",
    "MASSES",
    "MASSES_STATED",
    "PULSE_AMPS",
    "PULSE_AMPS_STATED",
    "ROADS",
    "ROADS_STATED",
    "SPEEDS",
    "SPEEDS_STATED",
    "STATIC_LOAD",
    "TABLE_MEASURES",
    "Agreement",
    "FigureSpec",
    "ShockTable",
    "Unit",
    "agreement",
    "agreement_summary",
    "build_all",
    "check_finite",
    "in_worker",
    "make_unit",
    "markdown_index",
    "merge_tables",
    "passive",
    "render",
    "road_note",
    "run_unit",
    "shock_table",
    "shock_tables",
    "spec_factory",
    "vary",
]

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


# -- running units -------------------------------------------------------------------------
def _simulate(unit: Unit, duration: float | None) -> Any:
    from mrsuspension.engine.simulate import run_many
    from mrsuspension.scenario import Scenario

    data = {**unit.scenario, "simulation": {"dt": unit.dt}}
    scenario = Scenario.from_dict(data)
    length = duration if duration is not None else float(scenario.excitations[0].duration)
    (result,) = run_many(
        scenario.simulations(), duration=length, dt=unit.dt, output_rate=1000.0, workers=1
    )
    return result


def _finite(values: Any) -> list[float]:
    return [float(v) for v in np.asarray(values, dtype=float)]


def _history_payload(r: Any, window: tuple[float, float], every: int) -> dict[str, Any]:
    t = np.asarray(r.time)
    w = (t >= window[0]) & (t <= window[1])
    out: dict[str, Any] = {"time": t[w][::every]}
    for name, (key, _) in SIGNALS.items():
        y = np.asarray(r[key], dtype=float)
        if np.any(np.isnan(y[w])):
            continue
        out[name] = y[w][::every]
        out[f"peak {name}"] = float(np.nanmax(np.abs(y[w])))
    return out


#: Pulse payload key: the run's static tire load (m_s + m_u) g [N], for the DTR
STATIC_LOAD = "static load [N]"


def _static_load(tables: Mapping[str, Any]) -> float:
    from mrsuspension.vehicle import QuarterCar

    return float(QuarterCar(**tables.get("vehicle", {})).static_load)


def run_unit(unit: Unit) -> dict[str, Any]:
    """Run one unit and reduce it to what the figures and tables need.

    Parameters
    ----------
    unit : Unit
        From :func:`make_unit`.

    Returns
    -------
    dict
        Arrays and numbers: ``time`` and the :data:`SIGNALS` traces (time, pulse), PSDs and
        the ``i_d`` history (psd), frequency-response curves (freq), plus measures and
        ``run time [s]``.
    """
    start, cpu = time.perf_counter(), time.process_time()
    out: dict[str, Any]
    if unit.kind == "time":
        from mrsuspension.measures import asymmetry_ratio, force_tracking_error

        r = _simulate(unit, HARMONIC_DURATION)
        out = _history_payload(r, SHOWN, 1)
        steady = np.asarray(r.time >= STEADY_FROM)
        out["mean current [A]"] = float(np.mean(r.i_d[steady]))
        out["gamma"] = float(asymmetry_ratio(r.F_d[steady]))
        out["max |di_d| per ms [A]"] = float(np.max(np.abs(np.diff(r.i_d[steady]))))
        target = np.asarray(r.F_target[steady])
        if not np.any(np.isnan(target)):
            out["force-tracking error [N]"] = float(
                force_tracking_error(r.F_d[steady], target, r.z_c[steady])
            )
    elif unit.kind == "pulse":
        r = _simulate(unit, PULSE_DURATION)
        out = _history_payload(r, (0.0, PULSE_DURATION), 2)
        m = r.measures()  # SAR_s, SAR_u over the after-onset road acceleration peak
        out.update({k: float(m[k]) for k in (*SHOCK, "peak_tire_force")})
        out["road_peak"] = m["road_peak"]
        out[STATIC_LOAD] = _static_load(unit.scenario)
    elif unit.kind == "psd":
        from mrsuspension.measures import psd

        r = _simulate(unit, None)
        fs = 1.0 / float(r.time[1] - r.time[0])
        out = {}
        for name in PSD_SIGNALS:
            f, p = psd(np.asarray(r[SIGNALS[name][0]]), fs, warn=False)
            band = (f > 0) & (f <= 25.0)
            out["frequency"] = np.asarray(f)[band]
            out[f"PSD {name}"] = np.asarray(p)[band]
        out["time"] = np.asarray(r.time)[::20]
        out["i_d"] = np.asarray(r.i_d)[::20]
        m = r.measures()
        out["DLC"] = float(m["DLC"])  # std(F_T) over the mean tire force: the run's own load
        out["std F_T [N]"] = float(np.std(np.asarray(r.F_T)))
        out[STATIC_LOAD] = _static_load(unit.scenario)
        out["rms a_s [m/s^2]"] = float(m["rms_body_acceleration"])
        out["mean current [A]"] = float(m["mean_current"])
    elif unit.kind == "freq":
        from mrsuspension.studies import Study, run_study

        data = {
            "study": {
                "name": "report",
                "measures": [*(k for k, _ in FREQ_PANELS), "vm_clamp_fraction"],
            },
            **unit.scenario,
            "simulation": {"dt": unit.dt},
        }
        exc = dict(data["excitation"])
        exc.setdefault("frequencies", "log:10:0.5:15" if unit.dt > 1e-4 else "log:30:0.5:15")
        data["excitation"] = exc
        result = run_study(Study.from_dict(data), workers=1, progress=False, cache_dir=False)
        ds = result.to_xarray()
        dims = [d for d in ds["T_as"].dims if d != "frequency"]
        ds = ds.isel({d: 0 for d in dims})
        out = {"frequency": np.asarray(ds["frequency"].values, dtype=float)}
        for key, _ in FREQ_PANELS:
            out[key] = np.asarray(ds[key].values, dtype=float)
    else:
        raise ValidationError(
            f"unit kind {unit.kind!r} is not valid; valid: time, freq, pulse, psd"
        )
    out[CLAMP_KEY] = 100.0 * (
        float(np.nanmax(ds["vm_clamp_fraction"].values))
        if unit.kind == "freq"
        else r.velocity_clamp_fraction
    )
    out["run time [s]"] = time.perf_counter() - start
    out["run cpu time [s]"] = time.process_time() - cpu
    return out


# -- rendering ----------------------------------------------------------------------------
def _subplots(rows: int, cols: int, labels: Sequence[str], key: Any) -> tuple[Any, Any]:
    """The family figures' panel grid: 3.3 x 2.5 in panels with fixed margins, and a strip
    for the legend of ``labels`` between the title and the panels (off the data); one
    figure per ``key`` (the family and its panels) and shape, reused
    (:func:`~mrsuspension.report.toolkit.reused_subplots`)."""
    per_row = legend_columns(labels, 3.3 * cols)
    legend_rows = -(-len(labels) // per_row)
    return reused_subplots(
        (key, rows, cols, legend_rows), rows, cols, 3.3, 2.5, legend_rows=legend_rows
    )


def _grid(n: int) -> tuple[int, int]:
    if n <= 3:
        return 1, n
    if n == 4:
        return 2, 2
    return 2, (n + 1) // 2


def _style(label: str) -> str:
    return "--" if label.startswith("passive") else "-"


def _render_histories(
    spec: FigureSpec, payloads: Mapping[str, dict[str, Any]]
) -> tuple[Any, dict[str, Any]]:
    rows, cols = _grid(len(spec.signals))
    fig, axes = _subplots(rows, cols, list(payloads), ("histories", len(spec.signals)))
    flat = axes.ravel()
    share_x(flat[: len(spec.signals)])
    data: dict[str, Any] = {}
    every = 10
    for label, p in payloads.items():
        t = p["time"]
        data[f"time {label} [s]"] = [round(float(v), 4) for v in t[::every]]
        for ax, name in zip(flat, spec.signals, strict=False):
            ax.set_ylabel(SIGNALS[name][1])
            if name not in p:
                continue
            ax.plot(t, p[name], _style(label), lw=1, label=label)
            data[f"peak |{name}| {label}"] = p[f"peak {name}"]
            data[f"{name} {label}"] = _finite(p[name][::every])
        if spec.kind == "time":
            data[f"mean current {label} [A]"] = p["mean current [A]"]
            data[f"gamma (rebound/compression peak force) {label}"] = p["gamma"]
            data[f"max |di_d| per ms {label} [A]"] = p["max |di_d| per ms [A]"]
            if "force-tracking error [N]" in p:
                data[f"force-tracking error {label} [N]"] = p["force-tracking error [N]"]
        else:
            for k in (*SHOCK, "peak_tire_force"):
                data[f"{k} {label}"] = p[k]
            data["road_peak (SAR_s, SAR_u denominator)"] = p.get("road_peak", "after-onset")
    for ax in flat[len(spec.signals) :]:
        ax.set_visible(False)
    for ax in flat[: len(spec.signals)]:
        ax.set_xlabel("time [s]")
        ax.grid(True, alpha=0.3)
    label_outer_x(axes)
    figure_legend(fig, flat[0])
    return fig, data


def _render_freq(
    spec: FigureSpec, payloads: Mapping[str, dict[str, Any]]
) -> tuple[Any, dict[str, Any]]:
    fig, axes = _subplots(2, 2, list(payloads), "freq")
    share_x(axes.ravel())
    data: dict[str, Any] = {}
    for label, p in payloads.items():
        f = p["frequency"]
        data.setdefault("frequency [Hz]", _finite(f))
        for ax, (key, ylabel) in zip(axes.ravel(), FREQ_PANELS, strict=True):
            ax.plot(f, p[key], _style(label), marker="o", ms=3, label=label)
            ax.set_ylabel(ylabel)
            data[f"{key} {label}"] = _finite(p[key])
        body = (f >= 0.5) & (f <= 4.0)
        k = int(np.argmax(np.where(body, p["T_as"], -np.inf)))
        data[f"peak T_as {label}"] = float(p["T_as"][k])
        data[f"peak T_as frequency {label} [Hz]"] = float(f[k])
    from matplotlib.ticker import FixedLocator, FormatStrFormatter, NullLocator

    for ax in axes.ravel():
        ax.set_xscale("log")
        # labelled ticks at 0.5-10 Hz, no minor ticks (cheaper to draw, easier to read)
        ax.xaxis.set_major_locator(FixedLocator([0.5, 1, 2, 5, 10]))
        ax.xaxis.set_major_formatter(FormatStrFormatter("%g"))
        ax.xaxis.set_minor_locator(NullLocator())
        ax.set_xlabel("frequency [Hz]")
        ax.grid(True, alpha=0.3)
    label_outer_x(axes)
    figure_legend(fig, axes[0, 0])
    return fig, data


def _render_psd(
    spec: FigureSpec, payloads: Mapping[str, dict[str, Any]]
) -> tuple[Any, dict[str, Any]]:
    fig, axes = _subplots(2, 3, list(payloads), "psd")
    flat = axes.ravel()
    share_x(flat[:5])
    data: dict[str, Any] = {}
    for label, p in payloads.items():
        f = p["frequency"]
        keep = f <= 20.0
        data.setdefault("PSD frequency [Hz]", _finite(f[keep][::4]))
        for ax, name in zip(flat, PSD_SIGNALS, strict=False):
            ax.loglog(f, p[f"PSD {name}"], _style(label), lw=1, label=label)
            symbol, unit = SIGNALS[name][1].rstrip("]").split(" [")
            ax.set_ylabel(f"PSD {symbol} [({unit})$^2$/Hz]")
            data[f"PSD {name} {label}"] = _finite(p[f"PSD {name}"][keep][::4])
        flat[5].plot(p["time"], p["i_d"], lw=0.6, label=label)
        data[f"road DLC model {label}"] = p["DLC"]
        data[f"road DLC dissertation {label}"] = spec.given.get(label, "not given")
        data[f"rms a_s {label} [m/s^2]"] = p["rms a_s [m/s^2]"]
        data[f"mean current {label} [A]"] = p["mean current [A]"]
        ride = (f >= 2.0) & (f <= 8.0)
        data[f"mean PSD a_s 2-8 Hz {label} [(m/s^2)^2/Hz]"] = float(np.mean(p["PSD a_s"][ride]))
    from matplotlib.ticker import LogLocator, NullLocator

    for ax in flat[:5]:
        ax.set_xlabel("frequency [Hz]")
        # PSDs span many decades: hundreds of minor ticks would cost seconds to draw
        ax.yaxis.set_major_locator(LogLocator(numticks=5))
        ax.yaxis.set_minor_locator(NullLocator())
        ax.xaxis.set_minor_locator(NullLocator())
        ax.grid(True, alpha=0.3)
    flat[5].set_xlabel("time [s]")
    flat[5].set_ylabel("$i_d$ [A]")
    label_outer_x(axes)
    figure_legend(fig, flat[0])
    return fig, data


_RENDERERS = {"time": _render_histories, "pulse": _render_histories, "freq": _render_freq}


#: payload and figure-data key: the largest share of a run [%] with v_m at its upper clamp
CLAMP_KEY = "time at v_m clamp [%]"


def clamp_note(payloads: Mapping[str, Mapping[str, Any]], data: dict[str, Any]) -> str:
    """Record each variant's time at the v_m clamp in ``data``; a caption note when large.

    Model reference, section 2.4: beyond its identified velocity range the damper model is an
    extrapolation, and a figure that goes there says so.
    """
    from mrsuspension.engine.result import CLAMP_WARN_FRACTION

    hit = {}
    for label, payload in payloads.items():
        share = float(payload.get(CLAMP_KEY, 0.0))
        data[f"{CLAMP_KEY} {label}"] = round(share, 2)
        if share > 100.0 * CLAMP_WARN_FRACTION:
            hit[label] = share
    if not hit:
        return ""
    where = ", ".join(f"{k} {v:.0f} %" for k, v in hit.items())
    return (
        f" Note: the peak-velocity estimate v_m sat at its upper clamp (the identified range, "
        f"0.75 m/s) for part of a run ({where}; largest share per run): there the damper "
        "model is an extrapolation."
    )


def render(
    spec: FigureSpec,
    payloads: Mapping[str, dict[str, Any]],
    folder: Path,
    formats: Sequence[str],
    check: bool = False,
) -> dict[str, Any]:
    """Draw ``spec`` from its units' payloads, save it and return its manifest record.

    Parameters
    ----------
    spec : FigureSpec
        A non-special figure.
    payloads : mapping
        Variant label -> :func:`run_unit` output.
    folder : Path
        Where the files go.
    formats : sequence of str
        ``("png",)`` or ``("png", "svg")``.
    check : bool
        Also record the figure's ``layout issues``
        (:func:`~mrsuspension.report.legibility.layout_issues`).

    Returns
    -------
    dict
        ``number``, ``title``, ``caption``, ``files``, ``data`` (with the scenario of each
        variant under ``scenario <label>``) and ``render time [s]``.
    """
    start, cpu = time.perf_counter(), time.process_time()
    draw = _RENDERERS.get(spec.kind, _render_psd)
    fig, data = draw(spec, payloads)
    for label in spec.variants:
        data[f"scenario {label}"] = json.dumps(spec.scenario(label), sort_keys=True)
    rec = FigureRecord(
        spec.number, spec.title, spec.caption + clamp_note(payloads, data), fig, data
    )
    simulated = sum(p["run time [s]"] for p in payloads.values())
    return _saved(rec, folder, formats, start, cpu, round(simulated, 3), check)


def _build_special(
    builder: Callable[..., Any],
    quick: bool | None,
    folder: Path,
    formats: Sequence[str],
    check: bool = False,
) -> dict[str, Any]:
    """Run a figure function (``builder(quick)``, or ``builder()`` if quick is None) and save."""
    start, cpu = time.perf_counter(), time.process_time()
    rec = builder() if quick is None else builder(quick)
    return _saved(rec, folder, formats, start, cpu, 0.0, check)


def _saved(
    rec: FigureRecord,
    folder: Path,
    formats: Sequence[str],
    start: float,
    cpu: float,
    simulated: float,
    check: bool = False,
) -> dict[str, Any]:
    """Save ``rec`` and return its manifest entry, timed from ``start`` (wall) and ``cpu``."""
    rec.save(folder, formats, check=check)
    extra = {} if rec.issues is None else {"layout issues": rec.issues}
    return {
        "number": rec.number,
        "title": rec.title,
        "caption": rec.caption,
        "files": rec.files,
        "data": rec.data,
        "render time [s]": round(time.perf_counter() - start, 3),
        "render cpu time [s]": round(time.process_time() - cpu, 3),
        "simulation time [s]": simulated,
        **extra,
    }


def _call(func: Callable[..., Any], args: tuple[Any, ...]) -> tuple[Any, float, float]:
    """``func(*args)``, the CPU time and the wall time it took [s]."""
    cpu, wall = time.process_time(), time.perf_counter()
    value = func(*args)
    return value, time.process_time() - cpu, time.perf_counter() - wall


# -- shock tables --------------------------------------------------------------------------
@dataclass(frozen=True)
class ShockTable:
    """A table of shock-response measures over one varied parameter, with the
    dissertation's values.

    Parameters
    ----------
    number, title : str
        Table number and title.
    column : str
        Header of the varied parameter (e.g. ``"m_s (kg)"``).
    base : mapping
        Scenario tables of the nominal case (pulse defaults: 3.5 cm, 50 km/h).
    variants : mapping
        Shown parameter value -> table overrides (the nominal row has ``{}``).
    given : mapping
        Shown parameter value -> the dissertation's SDR_s, SAR_s, SDR_u, SAR_u, RDR, DTR.
    why : str
        Known causes of differences (appended to the caption).
    """

    number: str
    title: str
    column: str
    base: Mapping[str, Any]
    variants: Mapping[float, Mapping[str, Any]]
    given: Mapping[float, tuple[float, ...]]
    why: str = ""

    def __post_init__(self) -> None:
        if not self.variants:
            raise ValidationError(f"table {self.number}: the variant list is empty")
        if set(self.given) != set(self.variants):
            raise ValidationError(
                f"table {self.number}: dissertation values given for {sorted(self.given)}, "
                f"variants are {sorted(self.variants)}"
            )
        if {} not in [dict(v) for v in self.variants.values()]:
            raise ValidationError(
                f"table {self.number}: one variant must be the nominal case ({{}}), the DTR "
                "reference"
            )

    def units(self, quick: bool) -> dict[float, Unit]:
        """Parameter value -> pulse unit."""
        return {
            v: make_unit("pulse", _merge(self.base, o), quick) for v, o in self.variants.items()
        }


# The measures of a shock table, in column order (DTR last: it needs the nominal row):
# the toolkit's TABLE_MEASURES
#: Agreement bands of a shock-table cell, best first: (name, limit on
#: ``|model/dissertation - 1|``, limit on ``|model - dissertation|`` for DTR, which the
#: dissertation often gives as 0). The report colours the cells green, amber and red.
AGREEMENT_BANDS: tuple[tuple[str, float, float], ...] = (
    ("green", 0.10, 0.025),
    ("amber", 0.25, 0.05),
    ("red", math.inf, math.inf),
)


class Agreement(NamedTuple):
    """One shock-table cell compared with the dissertation.

    ``ratio`` is model/dissertation (None where the dissertation gives 0),
    ``difference`` model - dissertation, ``band`` a name of :data:`AGREEMENT_BANDS`.
    """

    ratio: float | None
    difference: float
    band: str


def agreement(measure: str, model: float, dissertation: float) -> Agreement:
    """Compare one cell: the ratio, the difference and the agreement band.

    The band is the first of :data:`AGREEMENT_BANDS` whose limit holds: on the relative
    deviation ``|model/dissertation - 1|`` (green within 10 %, amber within 25 %, red
    beyond), or for ``measure == "DTR"`` on the absolute difference (green within 0.025,
    amber within 0.05), since the dissertation's DTR is 0 in every nominal row. A zero
    dissertation value of another measure agrees only with a zero.

    Parameters
    ----------
    measure : str
        ``"SDR_s"``, ``"SAR_s"``, ``"SDR_u"``, ``"SAR_u"``, ``"RDR"`` or ``"DTR"``.
    model, dissertation : float
        Our value and the dissertation's.

    Returns
    -------
    Agreement

    Examples
    --------
    >>> agreement("SDR_s", 0.70, 0.71)
    Agreement(ratio=0.986, difference=-0.01, band='green')
    >>> agreement("SAR_s", 0.23, 0.19).band, agreement("RDR", 0.75, 1.13).band
    ('amber', 'red')
    >>> agreement("DTR", 0.03, 0.0)
    Agreement(ratio=None, difference=0.03, band='amber')
    """
    if measure not in TABLE_MEASURES:
        raise ValidationError(
            f"measure {measure!r} is not a shock-table measure; valid: {', '.join(TABLE_MEASURES)}"
        )
    ours, theirs = float(model), float(dissertation)
    ratio = None if theirs == 0.0 else round(ours / theirs, 3)
    if measure == "DTR":
        off = abs(ours - theirs)
    else:
        off = abs(ours / theirs - 1.0) if theirs != 0.0 else (0.0 if ours == 0.0 else math.inf)
    band = next(
        name
        for name, relative, absolute in AGREEMENT_BANDS
        if off <= (absolute if measure == "DTR" else relative) + 1e-12
    )
    return Agreement(ratio, round(ours - theirs, 3), band)


def agreement_summary(rows: Sequence[Mapping[str, Any]]) -> dict[str, dict[str, Any]]:
    """Per measure: how many of a table's cells agree within 25 % (DTR: within 0.05).

    Parameters
    ----------
    rows : sequence of mapping
        :func:`shock_table` rows (``"<measure> agreement"`` keys).

    Returns
    -------
    dict
        Measure -> ``{"within": n, "cells": m, "share": n/m}`` (green and amber cells
        agree).

    Examples
    --------
    >>> rows = [{"SDR_s agreement": "green"}, {"SDR_s agreement": "red"}]
    >>> agreement_summary(rows)["SDR_s"]
    {'within': 1, 'cells': 2, 'share': 0.5}
    """
    out: dict[str, dict[str, Any]] = {}
    for k in TABLE_MEASURES:
        bands = [r[f"{k} agreement"] for r in rows if f"{k} agreement" in r]
        if bands:
            n = sum(b != "red" for b in bands)
            out[k] = {"within": n, "cells": len(bands), "share": round(n / len(bands), 3)}
    return out


def shock_table(
    table: ShockTable, payloads: Mapping[float, dict[str, Any]], quick: bool
) -> dict[str, Any]:
    """Rows of our shock measures beside the dissertation's, with per-cell ratios.

    DTR (3.44) against the row without overrides, read as the deviation in the peak tire
    force *ratio* (:func:`~mrsuspension.measures.dtr_ratio`: each run's peak over its own
    static load, the reading Tables 5.1 and 6.1 support; equal to (3.44) as printed,
    :func:`~mrsuspension.measures.dtr`, between rows of one mass, which each row also
    carries as ``DTR (3.44) model``). Each measure ``k`` of a row has ``k model``, ``k dissertation``,
    ``k ratio`` (model/dissertation; for DTR ``DTR difference``, model - dissertation)
    and ``k agreement``, the :func:`agreement` band. ``SAR_s`` and ``SAR_u`` divide by the
    road acceleration peak of the payloads' ``road_peak`` (``"after-onset"`` from
    :func:`run_unit`). The result's ``summary`` is :func:`agreement_summary` of the rows.
    """
    from mrsuspension.measures import dtr, dtr_ratio
    from mrsuspension.vehicle import QuarterCar

    car = QuarterCar()
    nominal = next(v for v, o in table.variants.items() if not o)
    reference = payloads[nominal]["peak_tire_force"]
    loads = {v: _static_load(_merge(table.base, o)) for v, o in table.variants.items()}
    road_peaks = {payloads[v].get("road_peak", "after-onset") for v in table.variants}
    if len(road_peaks) != 1:
        raise ValidationError(
            f"table {table.number}: the rows use different road peaks {sorted(road_peaks)}"
        )
    (road_peak,) = road_peaks
    rows = []
    for value in table.variants:
        p = payloads[value]
        row: dict[str, Any] = {table.column: value}
        peak = p["peak_tire_force"]
        model = [*(p[k] for k in SHOCK), dtr_ratio(reference, peak, loads[nominal], loads[value])]
        for k, ours, theirs in zip(TABLE_MEASURES, model, table.given[value], strict=True):
            ag = agreement(k, ours, theirs)
            row[f"{k} model"] = round(float(ours), 3)
            row[f"{k} dissertation"] = float(theirs)
            if k == "DTR":
                row["DTR difference"] = ag.difference
            else:
                row[f"{k} ratio"] = ag.ratio
            row[f"{k} agreement"] = ag.band
        row["DTR (3.44) model"] = round(float(dtr(reference, peak, car.total_mass)), 3)
        row["peak F_T model [N]"] = round(float(peak), 1)
        rows.append(row)
    ratios = []
    for k in SHOCK:
        r = [row[f"{k} ratio"] for row in rows]
        ratios.append(f"{k} {min(r):.2f}-{max(r):.2f}")
    step = _step(table.base, quick) * 1e3
    sar = (
        "SAR_s and SAR_u divide by the road acceleration peak after the pulse's onset jump "
        "(road_peak 'after-onset': 0.412 c (mu omega_0)^2, c = 0.25 a_m e^2; the dissertation "
        "does not define it and this reading matches its SAR_s; the onset jump, 'onset', "
        "is 4.85x larger)"
        if road_peak == "after-onset"
        else "SAR_s and SAR_u divide by the largest road acceleration, the jump at the "
        "pulse's onset (road_peak 'onset': 2 c (mu omega_0)^2, 4.85x the after-onset peak)"
    )
    return {
        "number": table.number,
        "title": table.title,
        "caption": (
            f"Rounded pulse (mu = 3, a_m = 3.5 cm, 50 km/h, omega_0 = 10.4 rad/s unless varied), "
            f"varying {table.column}; ratios of peaks over a {PULSE_DURATION:g} s record, step "
            f"{step:g} ms. Scenario: {json.dumps(_normalise(table.base), sort_keys=True)}. "
            f"{sar}. DTR against the nominal row, as the deviation in the peak tire force "
            "ratio (each row's peak over its own static load (m_s + m_u) g; the reading Tables "
            "5.1 and 6.1 support: (3.44) as printed divides both peaks by the nominal "
            f"{car.static_load:.0f} N and gives the static-load change, 0.216, for every "
            "controller at 422 and 703 kg; the rows carry it as 'DTR (3.44) model'). Each cell: ours, the dissertation's and their ratio (DTR: "
            "the difference), coloured green within 10 %, amber within 25 %, red beyond (DTR: "
            "within 0.025, 0.05). Model/dissertation ratio over the rows: "
            f"{', '.join(ratios)} (a range that is narrow but far from 1: the trend agrees, "
            "the level does not). " + table.why
        ),
        "road_peak": road_peak,
        "rows": rows,
        "summary": agreement_summary(rows),
    }


def shock_tables(
    base: dict[str, Any],
    numbers: tuple[str, str, str],
    given: Sequence[dict[float, tuple[float, ...]]],
    why: str,
) -> tuple[ShockTable, ...]:
    """The three shock tables of Chapters 5 and 6: sprung mass, speed, pulse height.

    Parameters
    ----------
    base : dict
        The controller's scenario tables.
    numbers : tuple of str
        Table numbers (mass, speed, pulse height).
    given : tuple of dict
        The dissertation's rows of each table (value -> SDR_s, SAR_s, SDR_u, SAR_u, RDR, DTR).
    why : str
        Known causes of differences.

    Returns
    -------
    tuple of ShockTable

    Examples
    --------
    >>> row = (1.0, 0.3, 1.1, 1.2, 0.9, 0.0)
    >>> tabs = shock_tables({}, ("9.1", "9.2", "9.3"),
    ...                     ({563.0: row}, {50.0: row}, {3.5: row}), "")
    >>> [t.column for t in tabs]
    ['m_s (kg)', 'V (km/h)', 'a_m (cm)']
    """
    mass, speed, height = given
    return (
        ShockTable(
            numbers[0],
            "Influence of sprung mass variations on the transient response measures",
            "m_s (kg)",
            base,
            {m: ({} if m == 563.0 else {"vehicle": {"sprung_mass": m}}) for m in mass},
            mass,
            why,
        ),
        ShockTable(
            numbers[1],
            "Influence of vehicle speed variations on the transient response measures",
            "V (km/h)",
            base,
            {v: ({} if v == 50.0 else {"excitation": {"speed": v}}) for v in speed},
            speed,
            why,
        ),
        ShockTable(
            numbers[2],
            "Influence of variations in peak pulse displacement on the transient response "
            "measures (the dissertation's caption says 'road roughness'; its rows vary a_m)",
            "a_m (cm)",
            base,
            {a: ({} if a == 3.5 else {"excitation": {"amplitude": a / 100}}) for a in height},
            height,
            why,
        ),
    )


# -- the pool's packing: estimated costs ----------------------------------------------------
#: CPU seconds per simulated step of a unit, by kind, and a fixed cost per unit (scenario,
#: measures, PSDs, pickling). Measured on the quick and full reports' units (single core,
#: warm numba cache, 2026-11-24): a frequency unit's steps are the sum of its runs'
#: durations over dt (lanes that skip their idle steps, as the lane kernel does).
STEP_COST = {"time": 2.8e-7, "pulse": 3.2e-7, "psd": 4.0e-7, "freq": 1.6e-7}
UNIT_COST = 0.005
#: CPU seconds of drawing and saving one figure from its payloads, by kind (PNG; SVG costs
#: about as much again), measured on the quick report
RENDER_COST = {"time": 0.22, "pulse": 0.24, "psd": 0.22, "freq": 0.14}
#: CPU seconds of the report's calls and figure functions, by name (``module.function``
#: or the call's name in the report): ``(quick, full)``, measured on a quiet machine with
#: a warm cache; others count :data:`DEFAULT_TASK_COST`
TASK_COST: dict[str, tuple[float, float]] = {
    "beyond": (1.74, 7.23),
    "vehicles": (2.09, 3.06),
    "comparison 6.5": (0.22, 0.36),
    "findings history": (0.07, 0.16),
    "table 2.1": (0.05, 0.05),
}
DEFAULT_TASK_COST = 0.3


def _harmonic_seconds(frequency: float) -> float:
    """A harmonic run's length [s]: settling plus measuring window (model reference, section 9)."""
    from mrsuspension.excitation.deterministic import MIN_CYCLES, MIN_MEASURE_TIME, SETTLE_TIME

    start = max(SETTLE_TIME, MIN_CYCLES / frequency)
    return start + max(MIN_CYCLES, math.ceil(MIN_MEASURE_TIME * frequency - 1e-9)) / frequency


def unit_steps(unit: Unit) -> float:
    """Simulated steps of ``unit`` (a frequency unit: summed over its runs).

    Examples
    --------
    >>> unit_steps(make_unit("pulse", {}, quick=True))
    8000.0
    """
    exc = unit.scenario["excitation"]
    if unit.kind == "freq":
        from mrsuspension.studies import expand_frequencies

        grid = exc.get("frequencies", "log:10:0.5:15" if unit.dt > 1e-4 else "log:30:0.5:15")
        seconds = sum(_harmonic_seconds(float(f)) for f in expand_frequencies(grid))
    elif unit.kind == "psd":
        from mrsuspension.excitation.road import PRESET_LENGTH

        seconds = float(exc.get("length", PRESET_LENGTH)) / (float(exc["speed"]) / 3.6)
    else:
        seconds = HARMONIC_DURATION if unit.kind == "time" else PULSE_DURATION
    return seconds / unit.dt


def unit_cost(unit: Unit) -> float:
    """Estimated CPU seconds of :func:`run_unit` on ``unit`` (:data:`STEP_COST`).

    Examples
    --------
    >>> unit_cost(make_unit("freq", {}, quick=True)) > unit_cost(make_unit("pulse", {}, True))
    True
    """
    return UNIT_COST + STEP_COST[unit.kind] * unit_steps(unit)


def task_cost(name: str, quick: bool | None) -> float:
    """Estimated CPU seconds of a call or figure function named ``name`` (:data:`TASK_COST`).

    Examples
    --------
    >>> task_cost("beyond", quick=False)
    7.23
    """
    cost = TASK_COST.get(name)
    return DEFAULT_TASK_COST if cost is None else cost[0 if quick else 1]


def process_age() -> float | None:
    """Seconds since this process started (Linux ``/proc``; None elsewhere).

    Examples
    --------
    >>> age = process_age()
    >>> age is None or age >= 0.0
    True
    """
    import os

    try:
        with open("/proc/self/stat") as f:
            started = int(f.read().rsplit(")", 1)[1].split()[19])
        with open("/proc/uptime") as f:
            uptime = float(f.read().split()[0])
    except (OSError, ValueError, IndexError):
        return None
    return max(0.0, uptime - started / os.sysconf("SC_CLK_TCK"))


@contextmanager
def _frozen_heap(active: bool = True) -> Iterator[None]:
    """Keep the objects alive now out of the garbage collector's passes (``gc.freeze``)
    while the block runs, as Python's ``gc`` documentation advises before forking.

    The pool's workers fork from this process: without it every full collection in a
    worker walks (and so copies, page by page) the parent's whole heap of modules, numba
    and scipy included.
    """
    import gc

    if not active:
        yield
        return
    gc.freeze()
    try:
        yield
    finally:
        gc.unfreeze()


#: A call of the report's pool: ``(function, args)``
Call = tuple[Callable[..., Any], tuple[Any, ...]]


def _function_name(func: Callable[..., Any]) -> str:
    return f"{getattr(func, '__module__', '')}.{getattr(func, '__qualname__', repr(func))}"


# -- the pool ----------------------------------------------------------------------------
@dataclass
class Built:
    """What :func:`build_all` made: figure records by number, tables, call results."""

    figures: dict[str, dict[str, Any]] = field(default_factory=dict)
    tables: dict[str, dict[str, Any]] = field(default_factory=dict)
    calls: dict[str, Any] = field(default_factory=dict)
    payloads: dict[Unit, dict[str, Any]] = field(default_factory=dict)
    call_times: dict[str, float] = field(default_factory=dict)
    wall_time: float = 0.0
    timing: dict[str, Any] = field(default_factory=dict)


def build_all(
    figures: Mapping[str, Sequence[FigureSpec]],
    tables: Sequence[ShockTable],
    quick: bool,
    out: Path,
    *,
    specials: Sequence[tuple[str, Callable[..., Any], bool | None]] = (),
    calls: Mapping[str, Call] | None = None,
    units: Sequence[Unit] = (),
    later: Callable[[], tuple[Sequence[Unit], Mapping[str, Call]]] | None = None,
    workers: int | None = None,
    progress: Callable[[str], None] | None = None,
    formats: Sequence[str] | None = None,
    check: bool = False,
) -> Built:
    """Run every distinct unit once and draw every figure, across a process pool.

    Parameters
    ----------
    figures : mapping
        Sub-folder (e.g. ``"chapter4"``) -> figure specs to draw there.
    tables : sequence of ShockTable
        Shock tables (their pulse units are shared with the figures').
    quick : bool
        Coarse grids and steps.
    out : Path
        Report folder.
    specials : sequence
        ``(sub-folder, builder, quick or None)``: figure functions that simulate and draw
        themselves (``builder()`` when the third item is None).
    calls : mapping, optional
        Name -> ``(function, args)`` run in the pool too (their results under ``calls``).
    units : sequence of Unit, optional
        Further units to run (e.g. the findings scorecard's); their payloads join
        ``Built.payloads``, shared with the figures' equal units.
    later : callable, optional
        ``later() -> (units, calls)``: further units and calls that take the parent a
        while to list (the findings scorecard's claims); called once the pool has its
        first tasks, so that the listing overlaps them.
    workers : int, optional
        Pool size (default: the CPU count, at most one per job); 1 runs everything in
        this process.
    progress : callable, optional
        Called with a message as jobs finish.
    formats : sequence of str, optional
        Figure file formats (default PNG only; ``("png", "svg")`` for both).
    check : bool
        Record each figure's ``layout issues``
        (:func:`~mrsuspension.report.legibility.layout_issues`).

    Returns
    -------
    Built
        Each figure record also holds ``done at [s]``: when it was saved, counted from
        the start of the pool.
    """
    from concurrent.futures import FIRST_COMPLETED, Future, wait

    say = progress or (lambda _m: None)
    formats = tuple(formats or ("png",))
    start = time.perf_counter()
    age = process_age()
    built = Built()
    todo: list[tuple[str, FigureSpec]] = [
        (sub, s)
        for sub, specs in figures.items()
        for s in specs
        if not (s.full_only and quick) and s.kind != "special"
    ]
    special_jobs = list(specials) + [
        (sub, s.builder, quick)
        for sub, specs in figures.items()
        for s in specs
        if s.kind == "special" and s.builder is not None and not (s.full_only and quick)
    ]
    need: dict[str, dict[str, Unit]] = {f"{sub}/{s.number}": s.units(quick) for sub, s in todo}
    table_units = {t.number: t.units(quick) for t in tables}
    distinct: list[Unit] = []
    for u in [u for g in need.values() for u in g.values()] + [
        u for g in table_units.values() for u in g.values()
    ]:
        if u not in distinct:
            distinct.append(u)
    seen = set(distinct)
    distinct += [u for u in dict.fromkeys(units) if u not in seen]
    units = distinct
    seen = set(units)
    calls_all: dict[str, Call] = dict(calls or {})
    # by kind (the pool below orders its tasks by estimated cost)
    order = {"freq": 0, "psd": 1, "time": 2, "pulse": 3}
    units.sort(key=lambda u: order[u.kind])
    total = len(units) + len(todo) + len(special_jobs) + len(calls_all)
    n_workers = 1 if in_worker() else worker_count(workers, total + (later is not None))
    call_cpu: dict[str, float] = {}
    done = 0

    def add_later() -> tuple[list[Unit], list[str]]:
        """Add ``later()``'s units (those not known yet) and calls; return them."""
        nonlocal total
        if later is None:
            return [], []
        more_units, more_calls = later()
        new = [u for u in dict.fromkeys(more_units) if u not in seen]
        seen.update(new)
        units.extend(new)
        calls_all.update(more_calls)
        total += len(new) + len(more_calls)
        return new, list(more_calls)

    def tick(what: str) -> None:
        nonlocal done
        done += 1
        say(f"report: {done}/{total} {what}")

    def done_at(record: dict[str, Any]) -> dict[str, Any]:
        record["done at [s]"] = round(time.perf_counter() - start, 2)
        return record

    pending_figs = dict(
        todo_item for todo_item in ((f"{sub}/{s.number}", (sub, s)) for sub, s in todo)
    )

    busy = 0.0  # seconds the workers spent in tasks
    queued: set[str] = set()
    with _frozen_heap(n_workers > 1), process_pool(n_workers, total) as pool:
        if pool is None:
            add_later()
            for name, (func, args) in calls_all.items():
                built.calls[name], call_cpu[name], built.call_times[name] = _call(func, args)
                tick(name)
            for u in units:
                built.payloads[u] = run_unit(u)
                tick(f"{u.kind} run")
            for key, (sub, s) in pending_figs.items():
                pl = {label: built.payloads[u] for label, u in need[key].items()}
                built.figures[key] = done_at(render(s, pl, out / sub, formats, check))
                tick(f"Fig. {s.number}")
            for sub, builder, q in special_jobs:
                rec = done_at(_build_special(builder, q, out / sub, formats, check))
                built.figures[f"{sub}/{rec['number']}"] = rec
                tick(f"Fig. {rec['number']}")
        else:
            # longest first across calls, units and figure functions (list scheduling by
            # estimated cost); figures join the queue as their units finish. Only one
            # task at a time waits in the pool's queue, so the order is decided here.
            queue: list[tuple[float, int, str, Any]] = []
            seq = itertools.count()

            def push(cost: float, what: str, ref: Any) -> None:
                heapq.heappush(queue, (-cost, next(seq), what, ref))

            for name in calls_all:
                push(task_cost(name, quick), "call", name)
            for u in units:
                push(unit_cost(u), "unit", u)
            for sub, builder, q in special_jobs:
                push(task_cost(_function_name(builder), quick), "special", (sub, builder, q))
            futures: dict[Future[Any], tuple[str, Any]] = {}
            executor = pool

            def submit() -> None:
                while queue and len(futures) <= n_workers:
                    _, _, what, ref = heapq.heappop(queue)
                    if what == "call":
                        func, args = calls_all[ref]
                        futures[executor.submit(_call, func, args)] = (what, ref)
                    elif what == "unit":
                        futures[executor.submit(run_unit, ref)] = (what, ref)
                    elif what == "special":
                        sub, builder, q = ref
                        job = executor.submit(_build_special, builder, q, out / sub, formats, check)
                        futures[job] = (what, sub)
                    else:
                        sub, s = pending_figs.pop(ref)
                        pl = {label: built.payloads[u] for label, u in need[ref].items()}
                        futures[executor.submit(render, s, pl, out / sub, formats, check)] = (
                            what,
                            ref,
                        )

            submit()
            new_units, new_calls = add_later()
            for name in new_calls:
                push(task_cost(name, quick), "call", name)
            for u in new_units:
                push(unit_cost(u), "unit", u)
            submit()
            while futures:
                finished, _ = wait(list(futures), return_when=FIRST_COMPLETED)
                for fut in finished:
                    what, ref = futures.pop(fut)
                    value = fut.result()
                    if what == "unit":
                        built.payloads[ref] = value
                        busy += value["run time [s]"]
                        tick(f"{ref.kind} run")
                        for key in [k for k in need if k in pending_figs and k not in queued]:
                            if all(u in built.payloads for u in need[key].values()):
                                queued.add(key)
                                push(RENDER_COST[pending_figs[key][1].kind], "figure", key)
                    elif what == "figure":
                        built.figures[ref] = done_at(value)
                        busy += value["render time [s]"]
                        tick(f"Fig. {value['number']}")
                    elif what == "special":
                        built.figures[f"{ref}/{value['number']}"] = done_at(value)
                        busy += value["render time [s]"]
                        tick(f"Fig. {value['number']}")
                    else:
                        built.calls[ref], call_cpu[ref], built.call_times[ref] = value
                        busy += built.call_times[ref]
                        tick(ref)
                submit()
    pool_wall = time.perf_counter() - start
    for t in tables:
        rows_in: dict[float, dict[str, Any]] = {
            v: built.payloads[u] for v, u in table_units[t.number].items()
        }
        built.tables[t.number] = shock_table(t, rows_in, quick)
    built.wall_time = time.perf_counter() - start
    built.timing = {
        "workers": n_workers,
        "distinct runs": len(units),
        "figures": len(built.figures),
        "run cpu time [s]": round(sum(p["run cpu time [s]"] for p in built.payloads.values()), 2),
        "figure cpu time [s]": round(
            sum(r.get("render cpu time [s]", 0.0) for r in built.figures.values()), 2
        ),
        "other cpu time [s]": {k: round(v, 2) for k, v in call_cpu.items()},
        "wall time [s]": round(built.wall_time, 2),
    }
    if n_workers > 1:
        built.timing["idle worker time [s]"] = round(n_workers * pool_wall - busy, 2)
    if age is not None:
        built.timing["started after [s]"] = round(age, 2)
    return built


def vary(
    section: str,
    key: str,
    values: Sequence[Any],
    label: Callable[[Any], str],
    nominal: Any = None,
) -> dict[str, dict[str, Any]]:
    """Variants setting ``[section] key`` to each value (the nominal value: no override).

    Examples
    --------
    >>> vary("vehicle", "sprung_mass", (422.0, 563.0), "m_s = {:g} kg".format, 563.0)
    {'m_s = 422 kg': {'vehicle': {'sprung_mass': 422.0}}, 'm_s = 563 kg': {}}
    """
    return {label(v): ({} if v == nominal else {section: {key: v}}) for v in values}


def passive(*currents: float) -> dict[str, dict[str, Any]]:
    """Passive-damper variants at the given currents (nominal damper, k_d = 1).

    Examples
    --------
    >>> passive(0.0)
    {'passive 0 A': {'controller': {'law': 'passive', 'current': 0.0}, 'damper': {'force_gain': 1.0}}}
    """
    return {
        f"passive {i:g} A": {
            "controller": {"law": "passive", "current": float(i)},
            "damper": {"force_gain": 1.0},
        }
        for i in currents
    }


# -- the variant sets the three controller chapters share (sections 4.4, 5.4, 6.4) -------
#: sprung mass +-25 % (563 kg nominal)
MASSES = vary("vehicle", "sprung_mass", (422.0, 563.0, 703.0), "m_s = {:g} kg".format, 563.0)
#: vehicle speed over a pulse or a road (50 km/h nominal)
SPEEDS = vary("excitation", "speed", (50.0, 100.0), "V = {:g} km/h".format, 50.0)
#: road roughness (the presets standing in for the dissertation's roads)
ROADS: dict[str, dict[str, Any]] = {
    "medium-rough": {"excitation": {"profile": "medium-rough"}},
    "rough": {},
}
#: harmonic amplitude at 1.5 Hz (2.5 cm nominal)
HARMONIC_AMPS = vary(
    "excitation", "amplitude", (0.015, 0.025, 0.035), lambda a: f"a = {a * 100:g} cm", 0.025
)
#: rounded-pulse height (3.5 cm nominal)
PULSE_AMPS = vary(
    "excitation", "amplitude", (0.02, 0.035, 0.05), lambda a: f"a_m = {a * 100:g} cm", 0.035
)
#: What a caption varying these states (``FigureSpec.settings``, checked against the runs by
#: :mod:`mrsuspension.report.captions`): one per variant family above
MASSES_STATED: dict[str, Any] = {
    "sprung_mass": {"m_s = 422 kg": 422.0, "m_s = 563 kg": 563.0, "m_s = 703 kg": 703.0}
}
SPEEDS_STATED: dict[str, Any] = {"speed": {"V = 50 km/h": 50.0, "V = 100 km/h": 100.0}}
ROADS_STATED: dict[str, Any] = {"profile": {"medium-rough": "medium-rough", "rough": "rough"}}
HARMONIC_AMPS_STATED: dict[str, Any] = {
    "amplitude": {"a = 1.5 cm": 0.015, "a = 2.5 cm": 0.025, "a = 3.5 cm": 0.035}
}
PULSE_AMPS_STATED: dict[str, Any] = {
    "amplitude": {"a_m = 2 cm": 0.02, "a_m = 3.5 cm": 0.035, "a_m = 5 cm": 0.05}
}


def spec_factory(base: Mapping[str, Any]) -> Callable[..., FigureSpec]:
    """A :class:`FigureSpec` maker whose ``base`` defaults to a chapter's controller.

    Examples
    --------
    >>> spec = spec_factory({"controller": {"law": "passive"}})
    >>> spec("9.1", "time", "T", "C", {"a": {}}).base["controller"]["law"]
    'passive'
    """

    def spec(
        number: str, kind: str, title: str, caption: str, variants: Any, **kw: Any
    ) -> FigureSpec:
        return FigureSpec(
            number=number,
            kind=kind,
            title=title,
            caption=caption,
            base=kw.pop("base", base),
            variants=variants,
            **kw,
        )

    return spec


def check_finite(data: Mapping[str, Any]) -> list[str]:
    """Keys of ``data`` holding a non-finite number (used by tests and the report).

    Examples
    --------
    >>> check_finite({"a": [1.0, float("nan")], "b": 2.0, "c": "text"})
    ['a']
    """
    bad = []
    for key, value in data.items():
        values = value if isinstance(value, list) else [value]
        if any(isinstance(v, float) and not math.isfinite(v) for v in values):
            bad.append(key)
    return bad


def markdown_index(
    chapters: Mapping[int, tuple[Sequence[FigureSpec], Sequence[ShockTable]]],
) -> str:
    """A Markdown list of every figure family and table with its scenario (docs/report.md).

    Parameters
    ----------
    chapters : mapping
        Chapter number -> (figure specs, shock tables).

    Returns
    -------
    str
        Markdown text: per chapter, a table of figures (number, kind, title, variants) and
        each figure's scenario per variant, then the tables.

    Examples
    --------
    >>> spec = FigureSpec(number="9.1", kind="pulse", title="T", caption="C", variants={"a": {}})
    >>> print(markdown_index({9: ((spec,), ())}).splitlines()[4])
    | 9.1 | pulse | T | a |
    """
    out: list[str] = []
    for chapter, (specs, tables) in chapters.items():
        out += [
            f"## Chapter {chapter}",
            "",
            "| Figure | Kind | Title | Variants |",
            "|---|---|---|---|",
        ]
        for s in specs:
            variants = ", ".join(s.variants) if s.kind != "special" else "(own figure function)"
            extra = " (full report only)" if s.full_only else ""
            out.append(f"| {s.number} | {s.kind} | {s.title}{extra} | {variants} |")
        out.append("")
        for s in specs:
            if s.kind == "special":
                continue
            out.append(f"**Fig. {s.number}** ({s.kind}). {s.caption}")
            out.append("")
            for label in s.variants:
                unit = make_unit(s.kind, s.scenario(label), quick=False)
                out.append(f"- {label}: `{unit.tables}`")
            out.append("")
        for t in tables:
            values = ", ".join(f"{v:g}" for v in t.variants)
            out.append(
                f"**Table {t.number}**: {t.title}. Varies {t.column} over {values}; base "
                f"`{json.dumps(_normalise(t.base), sort_keys=True)}` under the rounded pulse "
                "(mu = 3, a_m = 3.5 cm, 50 km/h unless varied). Our SDR_s, SAR_s, SDR_u, "
                "SAR_u, RDR, DTR beside the dissertation's."
            )
            out.append("")
    return "\n".join(out)
