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

The package, by concern (each name below is importable from the package itself):

==================  ====================================================================
module              what lives there
==================  ====================================================================
:mod:`.spec`        declaring figures: :data:`KINDS`, default excitations, :class:`Unit`,
                    :func:`make_unit`, :func:`merge_tables`, :class:`FigureSpec`, signals
:mod:`.run`         running units: :func:`run_unit`, its payload keys, the static load
:mod:`.drawing`     rendering: :func:`render`, one renderer per kind, the clamp note
:mod:`.shock`       the shock tables: :class:`ShockTable`, :func:`agreement`,
                    :func:`shock_table`, :func:`shock_tables`
:mod:`.pool`        the pool: its cost model (:func:`unit_cost`, :func:`task_cost`),
                    :class:`Built`, :func:`build_all`
:mod:`.variants`    what the controller chapters share: :func:`vary`, :func:`passive`,
                    :data:`MASSES` ... :func:`spec_factory`, :func:`check_finite`,
                    :func:`markdown_index`
==================  ====================================================================

Each module imports only those above it in this table (the pool sends
:func:`~.run.run_unit` and :func:`~.drawing.render` to its workers by module path).

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

from mrsuspension.report.families.drawing import (
    clamp_note,
    render,
)
from mrsuspension.report.families.pool import (
    DEFAULT_TASK_COST,
    RENDER_COST,
    STEP_COST,
    TASK_COST,
    UNIT_COST,
    Built,
    Call,
    build_all,
    process_age,
    task_cost,
    unit_cost,
    unit_steps,
)
from mrsuspension.report.families.run import (
    CLAMP_KEY,
    STATIC_LOAD,
    run_unit,
)
from mrsuspension.report.families.shock import (
    AGREEMENT_BANDS,
    Agreement,
    ShockTable,
    agreement,
    agreement_summary,
    shock_table,
    shock_tables,
)
from mrsuspension.report.families.spec import (
    DEFAULT_SIGNALS,
    FREQ_PANELS,
    HARMONIC_DURATION,
    INVERSE_LAWS,
    KINDS,
    PSD_SIGNALS,
    PULSE,
    PULSE_DURATION,
    ROAD,
    SIGNALS,
    SWEPT,
    FigureSpec,
    Unit,
    make_unit,
    merge_tables,
    road_note,
)
from mrsuspension.report.families.variants import (
    HARMONIC_AMPS,
    HARMONIC_AMPS_STATED,
    MASSES,
    MASSES_STATED,
    PULSE_AMPS,
    PULSE_AMPS_STATED,
    ROADS,
    ROADS_STATED,
    SPEEDS,
    SPEEDS_STATED,
    check_finite,
    markdown_index,
    passive,
    spec_factory,
    vary,
)
from mrsuspension.report.toolkit import TABLE_MEASURES, in_worker

__all__ = [
    "AGREEMENT_BANDS",
    "CLAMP_KEY",
    "DEFAULT_SIGNALS",
    "DEFAULT_TASK_COST",
    "FREQ_PANELS",
    "HARMONIC_AMPS",
    "HARMONIC_AMPS_STATED",
    "HARMONIC_DURATION",
    "INVERSE_LAWS",
    "KINDS",
    "MASSES",
    "MASSES_STATED",
    "PSD_SIGNALS",
    "PULSE",
    "PULSE_AMPS",
    "PULSE_AMPS_STATED",
    "PULSE_DURATION",
    "RENDER_COST",
    "ROAD",
    "ROADS",
    "ROADS_STATED",
    "SIGNALS",
    "SPEEDS",
    "SPEEDS_STATED",
    "STATIC_LOAD",
    "STEP_COST",
    "SWEPT",
    "TABLE_MEASURES",
    "TASK_COST",
    "UNIT_COST",
    "Agreement",
    "Built",
    "Call",
    "FigureSpec",
    "ShockTable",
    "Unit",
    "agreement",
    "agreement_summary",
    "build_all",
    "check_finite",
    "clamp_note",
    "in_worker",
    "make_unit",
    "markdown_index",
    "merge_tables",
    "passive",
    "process_age",
    "render",
    "road_note",
    "run_unit",
    "shock_table",
    "shock_tables",
    "spec_factory",
    "task_cost",
    "unit_cost",
    "unit_steps",
    "vary",
]
