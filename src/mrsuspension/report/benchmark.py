"""Report section "Benchmark of semi-active laws" (issue 29).

Every law of the benchmark (:mod:`mrsuspension.benchmark.study`) tuned by the optimiser
on a training road and scored on other roads, speeds, the quarter and the full car:
comfort, road holding, rattle space as ratios to the passive car (0 A), coil power, the
benchmark cost and, on the quarter car, its distance to the semi-active optimum of the
same road record.

* Fig. BM.1: comfort against road holding per law on the first road, with the optimum's
  Pareto front (quarter car); Fig. BM.2: the same on the full car.
* Table BM.1: the best law per vehicle, road and speed; Table BM.2: every row (also CSV).
* A few sentences whose numbers are computed from the rows.

Quick mode: :meth:`BenchmarkSpec.quick` (about 5 s of CPU); full mode: :func:`report_spec`
(the default laws and roads at 50 km/h, 2 s records). Needs the ``optimal`` extra
(CasADi); without it the section says so in one line.
"""

from __future__ import annotations

import html
import math
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any

from mrsuspension._docs import doc
from mrsuspension.report.toolkit import FigureRecord, table, write_csv

__all__ = ["build", "report_spec", "sentences"]


def report_spec(quick: bool) -> Any:
    """The set the report runs: the quick set, or the default laws and roads at 50 km/h
    on 2 s records (the whole default set is ``mrsus benchmark``'s)."""
    from mrsuspension.benchmark.study import BenchmarkSpec

    if quick:
        return BenchmarkSpec.quick()
    return BenchmarkSpec(speeds=(50.0,), duration=2.0, evaluations=12, optimum_dt=4e-3)


def _pct(x: float) -> str:
    return f"{100.0 * x:+.1f} %"


def sentences(result: Any) -> list[str]:
    """What the table says, in sentences whose numbers come from ``result``'s rows.

    Examples
    --------
    >>> from types import SimpleNamespace
    >>> rows = [
    ...     {"law": "a", "vehicle": "quarter", "road": "r", "speed": 50.0, "bounded": True,
    ...      "cost": 1.5, "distance": 0.25, "comfort_ratio": 0.9, "road_holding_ratio": 0.95},
    ...     {"law": "b", "vehicle": "quarter", "road": "r", "speed": 50.0, "bounded": True,
    ...      "cost": 1.8, "distance": 0.5, "comfort_ratio": 1.0, "road_holding_ratio": 1.0},
    ... ]
    >>> best = [{"vehicle": "quarter", "road": "r", "speed": 50.0, "best": "a", "cost": 1.5,
    ...          "passive_cost": 2.1}]
    >>> r = SimpleNamespace(rows=rows, best=lambda: best, violations=[], optima=[{"cost": 1.2}])
    >>> print(sentences(r)[0])
    On the quarter car a is the best law on 1 of 1 road and speed cases.
    """
    out: list[str] = []
    best = result.best()
    for vehicle, name in (("quarter", "quarter car"), ("full", "full car")):
        cases = [b for b in best if b["vehicle"] == vehicle]
        if not cases:
            continue
        counts: dict[str, int] = {}
        for b in cases:
            counts[b["best"]] = counts.get(b["best"], 0) + 1
        ranked = sorted(counts.items(), key=lambda kv: -kv[1])
        text = ", ".join(f"{law} on {n}" for law, n in ranked)
        lead = ranked[0][0]
        worse = [b for b in cases if b["cost"] >= b["passive_cost"]]
        tail = (
            f" On {len(worse)} of them no law costs less than the passive car at 0 A."
            if worse
            else ""
        )
        if len(ranked) == 1:
            out.append(
                f"On the {name} {lead} is the best law on {ranked[0][1]} of {len(cases)} "
                "road and speed cases." + tail
            )
        else:
            out.append(
                f"On the {name} the best law by case: {text} (of {len(cases)} cases)." + tail
            )
    quarter = [
        r
        for r in result.rows
        if r["vehicle"] == "quarter" and r["bounded"] and math.isfinite(r["distance"])
    ]
    if quarter:
        near = min(quarter, key=lambda r: r["distance"])
        far = max(quarter, key=lambda r: r["distance"])
        out.append(
            f"The laws that drive the MR damper cost from {100 * near['distance']:+.1f} % to "
            f"{100 * far['distance']:+.1f} % against the optimum of the same road record: the "
            f"nearest is {near['law']} on {near['road']} at {near['speed']:g} km/h, the "
            f"farthest {far['law']} on {far['road']} at {far['speed']:g} km/h."
        )
        gains = [r for r in quarter if r["comfort_ratio"] < 1.0 and r["road_holding_ratio"] < 1.0]
        out.append(
            f"{len(gains)} of {len(quarter)} quarter-car rows improve both comfort and road "
            "holding on the passive car at 0 A."
        )
    if result.violations:
        out.append("The bound is violated, an error to look at: " + "; ".join(result.violations))
    else:
        out.append(
            "No law that drives the MR damper beats the optimum by more than its record's "
            "model gap (the bound holds within the difference between the engine's damper "
            "and the band's model)."
        )
    ideal = [r for r in result.rows if not r["bounded"] and math.isfinite(r["distance"])]
    below = [r for r in ideal if r["distance"] < 0.0]
    if ideal:
        out.append(
            f"The laws through an ideal damper ({', '.join(sorted({r['law'] for r in ideal}))}) "
            f"are outside the MR band and not held to it; they fall below the optimum on "
            f"{len(below)} of {len(ideal)} quarter-car cases."
        )
    return out


def _figure(result: Any, vehicle: str, number: str, folder: Path, formats: Sequence[str],
            check: bool) -> tuple[dict[str, Any], str]:  # fmt: skip
    spec = result.spec
    road, speed = spec.roads[0].name, spec.speeds[0]
    points = {
        r["law"]: [r["road_holding_ratio"], r["comfort_ratio"]]
        for r in result.rows
        if r["vehicle"] == vehicle and r["road"] == road and r["speed"] == speed
    }
    comfort = (
        "the seat's ISO 2631-1 total value" if vehicle == "full" else "Wk rms body acceleration"
    )
    caption = (
        f"{road} at {speed:g} km/h, {spec.duration:g} s. Comfort ({comfort}) against road "
        "holding (DLC), each over the passive car's at 0 A, of every law with its option "
        f"tuned on {spec.training.name}. Circles: laws through the MR damper; crosses: "
        "ideal dampers."
        + (
            " Dashed: the semi-active optimum's Pareto front on the same record (comfort "
            f"weights {', '.join(f'{x:g}' for x in spec.pareto)}, road holding one less, no "
            "rattle weight); star: the optimum for the benchmark's weights."
            if vehicle == "quarter" and result.front is not None
            else ""
        )
    )
    fig = result.figure(vehicle)
    fig.axes[0].set_title("")  # the record titles it "Fig. <number>: <title>"
    rec = FigureRecord(
        number=number,
        title=f"Comfort against road holding per law, {vehicle} car",
        caption=caption,
        figure=fig,
        data={"points": points, "front": result.front if vehicle == "quarter" else None},
    )
    rec.save(folder, formats, check=check)
    entry: dict[str, Any] = {"number": rec.number, "title": rec.title, "files": rec.files}
    if rec.issues is not None:
        entry["layout issues"] = rec.issues
    body = (
        f'<figure id="{rec.slug}"><img src="benchmark/{rec.slug}.png" alt="Fig. {rec.number}">'
        f"<figcaption><b>Fig. {html.escape(rec.number)}: {html.escape(rec.title)}.</b> "
        f"{html.escape(rec.caption)}</figcaption></figure>"
    )
    return entry, body


def build(
    folder: Path,
    quick: bool,
    progress: Callable[[str], None],
    formats: Sequence[str] = ("png",),
    check: bool = False,
) -> tuple[str, dict[str, Any]]:
    """Build the section into ``folder``; returns its HTML and its manifest entry."""
    from mrsuspension.benchmark.study import run_benchmark
    from mrsuspension.errors import ValidationError
    from mrsuspension.report.toolkit import in_worker

    folder.mkdir(parents=True, exist_ok=True)
    head = "<h2 id='benchmark'>Benchmark of semi-active laws</h2>"
    spec = report_spec(quick)
    progress("benchmark: tuning and scoring the semi-active laws")
    try:
        result = run_benchmark(spec, workers=1 if (quick or in_worker()) else None)
    except ValidationError as exc:  # e.g. CasADi not installed
        return head + f"<p>Not built: {html.escape(str(exc))}</p>", {
            "figures": [],
            "tables": [],
            "skipped": str(exc),
        }
    rows = [  # the tuned value to 4 digits (an LQ law's force weight is about 1e-6)
        {
            k: (float(f"{v:.4g}") if k == "value" else round(v, 4)) if isinstance(v, float) else v
            for k, v in r.items()
        }
        for r in result.rows
    ]
    best = result.best()
    write_csv(folder / "benchmark.csv", rows)
    write_csv(folder / "best.csv", best)
    figures, bodies = [], []
    for vehicle, number in (("quarter", "BM.1"), ("full", "BM.2")):
        if vehicle in spec.vehicles:
            entry, body = _figure(result, vehicle, number, folder, formats, check)
            figures.append(entry)
            bodies.append(body)
    tuned = ", ".join(f"{law}: {t['option']} = {t['value']:.4g}" for law, t in result.tuned.items())
    tuned_full = getattr(result, "tuned_full", {})
    if tuned_full:
        tuned = f"on the quarter car {tuned}; on the full car " + ", ".join(
            f"{law}: {t['option']} = {t['value']:.4g}" for law, t in tuned_full.items()
        )
    best_rows = [
        {
            "vehicle": b["vehicle"],
            "road": b["road"],
            "km/h": f"{b['speed']:g}",
            "best law": b["best"],
            "cost": b["cost"],
            "passive 0 A": b["passive_cost"],
            "comfort / passive": b["comfort_ratio"],
            "DLC / passive": b["road_holding_ratio"],
            "to the optimum": _pct(b["distance"]) if math.isfinite(b["distance"]) else "-",
            "runner-up": b["runner_up"],
        }
        for b in best
    ]
    w = spec.weights
    text = sentences(result)
    body = (
        head + "<p>Every law tuned by the optimiser (one option each, "
        f"{spec.evaluations} candidates) on {html.escape(spec.training.name)} at "
        f"{spec.training_speed:g} km/h on each vehicle, then scored on "
        f"{len(spec.roads)} roads at {', '.join(f'{s:g}' for s in spec.speeds)} km/h on the "
        "quarter car and the full car (the law at every corner; the whole-vehicle laws, "
        "from the body's heave, pitch and roll, on the full car only). The cost is "
        f"J = {w[0]:g} r_c<sup>2</sup> + {w[1]:g} r_r<sup>2</sup> + {w[2]:g} r_s<sup>2</sup> "
        "of the ratios to the passive car at 0 A (comfort, DLC, rms stroke; the passive car "
        f"costs {sum(w):g}), the objective of the semi-active optimum "
        f"(<a href='{doc('benchmark')}'>benchmark</a>) over the MR damper's force band "
        + (
            "(every force the engine's hysteretic damper can give), which bounds it from "
            "below on the quarter car"
            if spec.band == "envelope"
            else "(the damper model at a fixed peak velocity of 0.3 m/s), a bound of that "
            "model held within each record's measured model gap (the engine's passive car "
            "against the model's)"
        )
        + '. Tuned ("passive": the damper at the best constant current): '
        f"{html.escape(tuned)}.</p>"
        + "<p>"
        + " ".join(html.escape(s) for s in text)
        + "</p>"
        + "".join(bodies)
        + "<h3>Table BM.1: the best law per vehicle, road and speed</h3>"
        + "<p>Among the laws that drive the MR damper. "
        "<a href='benchmark/best.csv'>best.csv</a></p>"
        + table(best_rows, fmt="{:.3f}")
        + "<h3>Table BM.2: every law, road, speed and vehicle</h3>"
        + "<p>Coil power R&lt;i<sup>2</sup>&gt; [W] summed over the dampers. "
        "<a href='benchmark/benchmark.csv'>benchmark.csv</a></p>"
        + table(
            [
                {
                    "law": r["law"],
                    "vehicle": r["vehicle"],
                    "road": r["road"],
                    "km/h": f"{r['speed']:g}",
                    "comfort": r["comfort_ratio"],
                    "DLC": r["road_holding_ratio"],
                    "stroke": r["rattle_ratio"],
                    "coil [W]": r["coil_power"],
                    "cost": r["cost"],
                    "to optimum": _pct(r["distance"]) if math.isfinite(r["distance"]) else "-",
                }
                for r in result.rows
            ],
            fmt="{:.3f}",
        )
        + f"<p class='meta'>{len(result.rows)} scored runs, {len(result.optima)} optima, "
        f"{result.run_time:.1f} s.</p>"
    )
    return body, {
        "figures": figures,
        "tables": [
            {"number": "BM.1", "file": "benchmark/best.csv", "rows": len(best)},
            {"number": "BM.2", "file": "benchmark/benchmark.csv", "rows": len(rows)},
        ],
        "sentences": text,
        "violations": result.violations,
        "best": best,
        "optima": [{k: v for k, v in o.items() if k != "front"} for o in result.optima],
        "run_time": round(result.run_time, 2),
    }
