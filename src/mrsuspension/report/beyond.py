"""Report section "Beyond the dissertation": the comfort / road-holding / rattle-space
trade-off across controllers and gains, and a controller tuned by the optimiser.

* Fig B.1: Wk-weighted RMS body acceleration against DLC and against RMS stroke for the
  :func:`~mrsuspension.tradeoff.default_grid` settings on an ISO 8608 class C road at
  50 km/h, with each panel's Pareto front and the optimiser's best skyhook hi-lo ACM.
* Fig B.2: the optimiser's convergence.
* A table of every point (also as CSV).

Quick mode: a 100 m road, 0.25 ms steps, the coarse grid and a 10-candidate search of
k_c alone (a few seconds on one core). Full mode: 500 m, 0.1 ms, the full grid and a search
of k_c and n. Inside ``mrsus reproduce`` the section is one task of the report's process
pool, run on one core beside the chapters' runs.
"""

from __future__ import annotations

import csv
import html
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any

from mrsuspension._docs import doc
from mrsuspension.optimize import OptimizationProblem, OptimizationResult, Road, optimize
from mrsuspension.report.toolkit import FigureRecord, table
from mrsuspension.report.toolkit import inverse_model_step as step
from mrsuspension.tradeoff import TradeoffResult, default_grid, tradeoff

__all__ = ["WEIGHTS", "build", "problem", "road"]

#: objective weights of the section's optimiser run (comfort and road holding first)
WEIGHTS = {"wk_rms_body_acceleration": 1.0, "DLC": 1.0, "rms_stroke": 0.5}


def road(quick: bool) -> Road:
    """ISO 8608 class C (seed 1) at 50 km/h: 100 m in quick mode, else 500 m."""
    return Road.from_dict(
        {"iso_class": "C", "seed": 1, "length": 100.0 if quick else 500.0, "speed": 50.0}
    )


def problem(quick: bool) -> OptimizationProblem:
    """Skyhook hi-lo ACM: k_c (log, 1-3000) and, in full mode, n (1-3) on :func:`road`."""
    parameters: list[dict[str, Any]] = [
        {"field": "controller.gain", "lower": 1.0, "upper": 3000.0, "log": True}
    ]
    if not quick:
        parameters.append({"field": "controller.order", "lower": 1, "upper": 3, "integer": True})
    r = road(quick)
    return OptimizationProblem.from_dict(
        {
            "problem": {
                "name": "skyhook hi-lo ACM",
                "seed": 1,
                "population": 5 if quick else 8,
                "max_evaluations": 10 if quick else 48,
                **({"workers": 1} if quick else {}),
            },
            "controller": {"law": "skyhook-hilo", "mode": "ACM"},
            "simulation": {"dt": step(quick)},
            "parameters": parameters,
            "roads": [{"name": r.name, **r.options}],
            "objective": {"weights": dict(WEIGHTS)},
        }
    )


def _best_label(result: OptimizationResult) -> str:
    parts = [f"k_c = {result.best['controller.gain']:.3g}"]
    if "controller.order" in result.best:
        parts.append(f"n = {result.best['controller.order']:g}")
    return f"optimiser best: skyhook hi-lo ACM, {', '.join(parts)} (J = {result.objective:.3f})"


def _spread(fig: Any) -> Any:
    """``fig`` with its point labels moved apart (:func:`~.toolkit.spread_labels`)."""
    from mrsuspension.report.toolkit import spread_labels

    spread_labels(fig)
    return fig


def build(
    folder: Path,
    quick: bool,
    progress: Callable[[str], None],
    *,
    formats: Sequence[str] = ("png",),
    check: bool = False,
    workers: int | None = None,
) -> tuple[str, dict[str, Any]]:
    """Build the section into ``folder``; returns its HTML and its manifest entry.

    Parameters
    ----------
    folder : Path
        The section's folder (created).
    quick : bool
        Quick mode (see the module's docstring).
    progress : callable
        Progress messages.
    formats : sequence of str
        Figure formats (PNG by default; ``("png", "svg")`` with ``--svg``).
    check : bool
        Record each figure's ``layout issues`` in the manifest.
    workers : int, optional
        Processes of the trade-off and the optimiser (default: one in quick mode or in a
        pool worker, where the report runs this section beside the chapters' runs; else
        every core).

    Returns
    -------
    tuple
        The section's HTML and its manifest entry.
    """
    from mrsuspension.report.toolkit import in_worker

    folder.mkdir(parents=True, exist_ok=True)
    the_road = road(quick)
    dt = step(quick)
    if workers is None and (quick or in_worker()):
        workers = 1
    progress("beyond: comfort / road holding / rattle space across controllers")
    trade: TradeoffResult = tradeoff([the_road], grid=default_grid(quick), dt=dt, workers=workers)
    progress("beyond: optimising skyhook hi-lo ACM")
    result = optimize(problem(quick), workers=workers, progress=False)
    best_label = _best_label(result)
    best_measures = result.measures[the_road.name]

    rows = trade.rows()
    with (folder / "tradeoff_points.csv").open("w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    result.save(folder)

    fig_b1 = FigureRecord(
        number="B.1",
        title="Comfort against road holding and rattle space, across controllers and gains",
        caption=(
            f"{the_road.name}, dt = {dt * 1e3:g} ms. Each marker is one controller setting; "
            "lines join a family's settings in gain order. Dashed: the panel's Pareto front "
            "(no realisable setting is better in both measures); black edges: on the "
            "three-measure front. The ideal skyhook damper is a reference an MR damper "
            "cannot realise and is left out of the fronts. Star: the optimiser's best skyhook "
            f"hi-lo ACM for weights {WEIGHTS} normalised by passive 0 A."
        ),
        figure=_spread(trade.plot(extra={best_label: best_measures})),
        data={"points": rows, "optimiser_best": best_measures},
    )
    fig_b2 = FigureRecord(
        number="B.2",
        title="Optimiser convergence (skyhook hi-lo ACM)",
        caption=(
            "Objective J of every candidate (reference passive 0 A: J = 1) and the best so "
            f"far; differential evolution, {result.evaluations} evaluations in "
            f"{result.generations} generations."
        ),
        figure=result.plot(),
        data={"history": result.history},
    )
    figures = []
    sections = []
    for rec in (fig_b1, fig_b2):
        rec.save(folder, formats, check=check)
        entry = {"number": rec.number, "title": rec.title, "files": rec.files, "data": rec.data}
        if rec.issues is not None:
            entry["layout issues"] = rec.issues
        figures.append(entry)
        svg = f' <a href="beyond/{rec.slug}.svg">SVG</a>' if "svg" in formats else ""
        sections.append(
            f'<figure id="{rec.slug}"><img src="beyond/{rec.slug}.png" alt="Fig. {rec.number}">'
            f"<figcaption><b>Fig. {html.escape(rec.number)}: {html.escape(rec.title)}.</b> "
            f"{html.escape(rec.caption)}{svg}</figcaption></figure>"
        )
    best_rows = [
        {
            "measure": m,
            "optimiser best": best_measures[m],
            "passive 0 A": result.reference[the_road.name][m],
            "ratio": best_measures[m] / result.reference[the_road.name][m],
            "weight": WEIGHTS[m],
        }
        for m in WEIGHTS
    ]
    optimiser = {
        "best": result.best,
        "objective": result.objective,
        "evaluations": result.evaluations,
        "generations": result.generations,
        "measures": best_measures,
        "reference": result.reference[the_road.name],
        "files": ["beyond/optimization.json", "beyond/convergence.png"],
    }
    body = (
        "<h2 id='beyond'>Beyond the dissertation: trade-offs and a tuned controller</h2>"
        "<p>The dissertation compares controllers one measure at a time. Here every setting "
        "is placed by three smaller-is-better measures at once: ride comfort (ISO 2631-1 "
        "Wk-weighted RMS body acceleration), road holding (DLC) and rattle space (RMS "
        "stroke). Read a panel from the lower left: a setting on the dashed front cannot be "
        "improved in one measure without losing in the other; settings above or right of "
        "it are beaten by another setting in both. Then the optimiser (mrsus optimize, "
        f"<a href='{doc('optimisation')}'>optimisation</a>) tunes the skyhook hi-lo gain for a weighted objective.</p>"
        + sections[0]
        + "<h3>The points</h3><p><a href='beyond/tradeoff_points.csv'>tradeoff_points.csv</a>"
        "</p>" + table(rows) + f"<h3>Optimiser: {html.escape(best_label)}</h3>"
        f"<p>{result.evaluations} candidates"
        f"{' (quick mode: a tiny budget)' if quick else ''}; "
        "J = sum of weighted measure ratios to passive 0 A over the weights' sum. "
        "<a href='beyond/optimization.json'>optimization.json</a></p>"
        + table(best_rows)
        + sections[1]
    )
    return body, {
        "figures": figures,
        "tables": [{"number": "B.1", "file": "beyond/tradeoff_points.csv", "rows": len(rows)}],
        "optimiser": optimiser,
    }
