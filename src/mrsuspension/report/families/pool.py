"""The pool: :func:`build_all` runs every distinct unit once and draws every figure across
a process pool, longest task first by an estimated cost (:data:`STEP_COST`,
:data:`RENDER_COST`, :data:`TASK_COST`; :func:`unit_cost`, :func:`task_cost`), and
returns what it made as :class:`Built`.

The pool's workers receive :func:`~mrsuspension.report.families.run.run_unit`,
:func:`~mrsuspension.report.families.drawing.render`, ``_build_special`` and ``_call`` by
module path. To change a cost in a test, patch it here (``monkeypatch.setattr(pool,
"TASK_COST", ...)``): rebinding the name the package re-exports leaves this module's own.
"""

from __future__ import annotations

import heapq
import itertools
import math
import time
from collections.abc import Callable, Iterator, Mapping, Sequence
from contextlib import contextmanager
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from mrsuspension._pool import process_pool, worker_count
from mrsuspension.report.families.drawing import _build_special, render
from mrsuspension.report.families.run import run_unit
from mrsuspension.report.families.shock import ShockTable, shock_table
from mrsuspension.report.families.spec import HARMONIC_DURATION, PULSE_DURATION, FigureSpec, Unit
from mrsuspension.report.toolkit import in_worker

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
    >>> from mrsuspension.report.families.spec import make_unit
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
    >>> from mrsuspension.report.families.spec import make_unit
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


def _call(func: Callable[..., Any], args: tuple[Any, ...]) -> tuple[Any, float, float]:
    """``func(*args)``, the CPU time and the wall time it took [s]."""
    cpu, wall = time.process_time(), time.perf_counter()
    value = func(*args)
    return value, time.process_time() - cpu, time.perf_counter() - wall


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
