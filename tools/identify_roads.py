"""Identify the preset roads' spectra from the dissertation's road numbers (issue 30, group 4).

The dissertation's rough and medium-rough roads are measured profiles (section 3.5.2) we do
not have; the model reference (section 8(c)) replaces them by ``n^-1`` spectra that differ
only in level. This tool fits each preset's spectrum, ``Gd(n) = Gd(n0) (n/0.1)^-w`` over
a band ``[n_min, n_max]``, to everything the dissertation reports about the roads, as one
least-squares fit in logs, with the toolkit's own engine computing every target quantity
(the report's ``psd`` units: the scorecard's runs, with the road changed):

* the road DLCs per controller: rough at 50 km/h (passive 0.1 A 0.111, passive 0 A
  0.139, skyhook hi-lo ACM 0.138, inverse hi-lo 0.113, sliding mode 0.112), rough at
  100 km/h (0.142, 0.114, 0.114), medium-rough at 50 km/h (0.045, 0.056, 0.054);
* the PSD comparisons: rough and medium-rough "comparable" in 2-5 Hz (a_s, a_u, F_T of
  skyhook hi-lo, Fig 4.21; "slightly insensitive" for the inverse-model laws, Figs
  5.21 / 6.20): read as within a factor 1.5, a hinge residual ``max(0, |ln r| - ln 1.5)``;
* the peak elevations of section 3.5.2 (about 7.5 and 15 mm; weight 0.5: a peak depends
  on the phases, and the dissertation's are of the filtered data).

For each shape (``w``, band) the level is solved (one Newton step in logs: the DLC scales about as
``sqrt(Gd(n0))``); the shapes are searched on a grid, the two roads by coordinate descent
(the comparison couples them). Printed: the target table (dissertation, reference presets,
fitted), the fitted parameters and, per parameter, the grid range whose cost stays within
10 % of the minimum (the others at their best).

Run (quick settings, a few minutes on 2 cores)::

    PYTHONPATH=src python tools/identify_roads.py [--workers 2] [--full-check]

``--full-check`` re-evaluates the two spectra (reference and fitted) at the full report's
0.1 ms step. The fitted values are ``mrsuspension.excitation.road.PRESET_IDENTIFIED``.
"""

from __future__ import annotations

import argparse
import itertools
import math
import time
from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np

from mrsuspension._pool import pool_map, process_pool
from mrsuspension.excitation.road import PRESET_IDENTIFIED, PRESET_ROADS, PresetRoad
from mrsuspension.report.families.run import run_unit
from mrsuspension.report.families.spec import Unit, make_unit, merge_tables
from mrsuspension.report.findings.checks import Check, fig
from mrsuspension.report.findings.claims import common

#: a road spectrum: (Gd(n0) [m^3], w, n_min [cycle/m], n_max [cycle/m])
Spectrum = tuple[float, float, float, float]

#: DLC targets: name -> (road, figure, variant, speed [km/h], the dissertation's DLC, where)
DLC_TARGETS: dict[str, tuple[str, str, str, float, float, str]] = {
    "rough 50 passive 0.1 A": ("rough", "4.11", "passive 0.1 A", 50.0, 0.111, "4.3.2"),
    "rough 50 passive 0 A": ("rough", "5.11", "passive 0 A", 50.0, 0.139, "5.4, 6.3"),
    "rough 50 skyhook ACM": ("rough", "4.11", "skyhook hi-lo ACM", 50.0, 0.138, "4.3.2, 4.4.2"),
    "rough 50 inverse hi-lo": ("rough", "5.11", "inverse-model hi-lo ACM", 50.0, 0.113, "5.4"),
    "rough 50 sliding mode": ("rough", "6.10", "sliding mode ACM", 50.0, 0.112, "6.4.2"),
    "rough 100 skyhook ACM": ("rough", "4.11", "skyhook hi-lo ACM", 100.0, 0.142, "4.4.2"),
    "rough 100 inverse hi-lo": ("rough", "5.11", "inverse-model hi-lo ACM", 100.0, 0.114, "5.5.2"),
    "rough 100 sliding mode": ("rough", "6.10", "sliding mode ACM", 100.0, 0.114, "6.4.2"),
    "medium 50 skyhook ACM": ("medium-rough", "4.11", "skyhook hi-lo ACM", 50.0, 0.045, "4.4.3"),
    "medium 50 inverse hi-lo": (
        "medium-rough", "5.11", "inverse-model hi-lo ACM", 50.0, 0.056, "5.5.3",
    ),
    "medium 50 sliding mode": ("medium-rough", "6.10", "sliding mode ACM", 50.0, 0.054, "6.4.3"),
}  # fmt: skip
#: PSD comparisons: controller run (as in DLC_TARGETS, without the road) -> signals whose
#: 2-5 Hz mean PSD on the rough road is "comparable" to the medium-rough road's
COMPARABLE: dict[str, tuple[str, ...]] = {
    "skyhook ACM": ("a_s", "a_u", "F_T"),
    "inverse hi-lo": ("a_s", "a_u", "F_T"),
    "sliding mode": ("a_s", "a_u", "F_T"),
}
COMPARABLE_FACTOR = 1.5
#: peak elevations of section 3.5.2 [m] and their weight in the fit
PEAKS = {"rough": 0.015, "medium-rough": 0.0075}
PEAK_WEIGHT = 0.5
#: shape grids: w, n_min, n_max
GRID: dict[str, dict[str, tuple[float, ...]]] = {
    "rough": {
        "w": (0.0, 0.2, 0.4, 0.5, 0.6, 0.7, 0.8, 1.0, 1.2),
        "n_min": (0.011,),
        "n_max": (1.4, 2.0),
    },
    "medium-rough": {
        "w": (0.5, 1.0, 1.5, 2.0),
        "n_min": (0.05, 0.07, 0.1, 0.13),
        "n_max": (0.5, 0.7, 1.0, 1.4),
    },
}


def _reference(name: str) -> Spectrum:
    p = PRESET_ROADS[name]
    return (p.level, p.waviness, *p.band)


def _identified(name: str) -> Spectrum:
    p = PRESET_IDENTIFIED[name]
    return (p.level, p.waviness, *p.band)


def unit(target: str, spectrum: Spectrum, quick: bool) -> Unit:
    """The report's psd unit of a DLC target on a road of ``spectrum``."""
    road, number, variant, speed, _given, _where = DLC_TARGETS[target]
    level, w, lo, hi = spectrum
    excitation = {
        "profile": road,
        "speed": speed,
        "level": level,
        "waviness": w,
        "band": [lo, hi],
    }
    tables = merge_tables(fig(number, variant).scenario, {"excitation": excitation})
    return make_unit("psd", tables, quick)


class Evaluator:
    """Runs psd units once (a pool of ``workers``), keeps their payloads."""

    def __init__(self, quick: bool, pool: Any) -> None:
        self.quick, self.pool = quick, pool
        self.payloads: dict[Unit, dict[str, Any]] = {}
        self.runs = 0
        #: every spectra evaluated, with its results
        self.tried: list[tuple[dict[str, Spectrum], dict[str, Any]]] = []

    def run(self, units: Sequence[Unit]) -> None:
        todo = [u for u in dict.fromkeys(units) if u not in self.payloads]
        if todo:
            done = pool_map(run_unit, todo, workers=1, pool=self.pool)
            self.payloads.update(zip(todo, done, strict=True))
            self.runs += len(todo)

    def results(self, spectra: Mapping[str, Spectrum]) -> dict[str, Any]:
        """Every target quantity for the roads' ``spectra``."""
        units = {t: unit(t, spectra[DLC_TARGETS[t][0]], self.quick) for t in DLC_TARGETS}
        self.run(list(units.values()))
        p = {t: self.payloads[u] for t, u in units.items()}
        out: dict[str, Any] = {"DLC": {t: float(p[t]["DLC"]) for t in DLC_TARGETS}}
        ratios = {}
        for law, signals in COMPARABLE.items():
            rough, medium = p[f"rough 50 {law}"], p[f"medium 50 {law}"]
            for s in signals:
                ratios[f"{law} {s}"] = _band_mean(rough, s) / _band_mean(medium, s)
        out["PSD ratio"] = ratios
        out["peak"] = {name: _peak(name, spectra[name]) for name in PEAKS}
        out["current std"] = {
            t: float(np.std(p[t]["i_d"])) for t in ("rough 50 skyhook ACM", "rough 100 skyhook ACM")
        }
        self.tried.append((dict(spectra), out))
        return out

    def extremes(self) -> str:
        """Over every spectra tried: the ranges that decide the claims no fit reached."""
        rows = {
            "rough/medium 2-5 Hz PSD, skyhook ACM a_s (4.4.3: 1/1.5-1.5)": lambda r: r["PSD ratio"][
                "skyhook ACM a_s"
            ],
            "rough/medium 2-5 Hz PSD, skyhook ACM a_u (4.4.3: 1/1.5-1.5)": lambda r: r["PSD ratio"][
                "skyhook ACM a_u"
            ],
            "rough/medium 2-5 Hz PSD, skyhook ACM F_T (4.4.3: 1/1.5-1.5)": lambda r: r["PSD ratio"][
                "skyhook ACM F_T"
            ],
            "rough 50 DLC sliding / inverse hi-lo (6.3: < 1)": lambda r: (
                r["DLC"]["rough 50 sliding mode"] / r["DLC"]["rough 50 inverse hi-lo"]
            ),
            "rough 50 DLC sliding / passive 0 A (6.3: < 1)": lambda r: (
                r["DLC"]["rough 50 sliding mode"] / r["DLC"]["rough 50 passive 0 A"]
            ),
        }
        # admissible: the road DLCs within 25 % of the dissertation's (the scorecard's "about")
        admissible = [
            r
            for _s, r in self.tried
            if all(
                abs(math.log(r["DLC"][t] / DLC_TARGETS[t][4])) <= math.log(1.25) for t in r["DLC"]
            )
        ]
        lines = [
            f"over the {len(self.tried)} road spectra tried ({len(admissible)} admissible: "
            "every road DLC within 25 % of the dissertation's):"
        ]
        for name, fn in rows.items():
            v = [fn(r) for _s, r in self.tried]
            w = [fn(r) for r in admissible] or [math.nan]
            lines.append(
                f"  {name}: {min(v):.3g}-{max(v):.3g} (admissible {min(w):.3g}-{max(w):.3g})"
            )
        comparable = [
            (spectra, r)
            for spectra, r in self.tried
            if r in admissible
            if all(
                1 / COMPARABLE_FACTOR <= r["PSD ratio"][f"skyhook ACM {k}"] <= COMPARABLE_FACTOR
                for k in ("a_s", "a_u", "F_T")
            )
        ]
        lines.append(
            f"  admissible spectra with a_s, a_u and F_T of skyhook ACM all within 1/1.5-1.5 "
            f"(4.4.3-road-ride-comparable): {len(comparable)}"
        )
        for spectra, r in sorted(comparable, key=lambda sr: cost(sr[1]))[:5]:
            lines.append(
                f"    cost {cost(r):.3f}: "
                + "; ".join(describe(n, spectra[n]) for n in ("rough", "medium-rough"))
            )
        below = [
            r
            for r in admissible
            if r["DLC"]["rough 50 sliding mode"]
            < min(r["DLC"]["rough 50 inverse hi-lo"], r["DLC"]["rough 50 passive 0 A"])
        ]
        lines.append(f"  admissible spectra with 6.3's DLC order (sliding lowest): {len(below)}")
        return "\n".join(lines)


def _band_mean(payload: Mapping[str, Any], sig: str, lo: float = 2.0, hi: float = 5.0) -> float:
    f = np.asarray(payload["frequency"])
    sel = (f >= lo) & (f <= hi)
    return float(np.mean(np.asarray(payload[f"PSD {sig}"])[sel]))


def _preset(name: str, spectrum: Spectrum) -> PresetRoad:
    from dataclasses import replace

    level, w, lo, hi = spectrum
    return replace(PRESET_ROADS[name], level=level, waviness=w, band=(lo, hi))


def _peak(name: str, spectrum: Spectrum) -> float:
    return float(_preset(name, spectrum).profile().peak_elevation)


def residuals(res: Mapping[str, Any]) -> dict[str, float]:
    """Log residuals of every target (hinge for the comparisons, weighted peaks)."""
    r = {t: math.log(res["DLC"][t] / DLC_TARGETS[t][4]) for t in DLC_TARGETS}
    for k, v in res["PSD ratio"].items():
        r[f"2-5 Hz {k}"] = max(0.0, abs(math.log(v)) - math.log(COMPARABLE_FACTOR))
    for name, peak in res["peak"].items():
        r[f"peak {name}"] = PEAK_WEIGHT * math.log(peak / PEAKS[name])
    return r


def cost(res: Mapping[str, Any]) -> float:
    return float(sum(v * v for v in residuals(res).values()))


def solve_level(
    ev: Evaluator, name: str, shape: tuple[float, float, float], spectra: dict[str, Spectrum]
) -> tuple[Spectrum, dict[str, Any]]:
    """The level of ``name`` at ``shape`` (w, n_min, n_max) that centres its DLC targets."""
    mine = [t for t in DLC_TARGETS if DLC_TARGETS[t][0] == name]
    level = spectra[name][0]
    res: dict[str, Any] = {}
    for _ in range(1):
        trial = {**spectra, name: (level, *shape)}
        res = ev.results(trial)
        err = float(np.mean([math.log(res["DLC"][t] / DLC_TARGETS[t][4]) for t in mine]))
        level = float(f"{level * math.exp(-2.0 * err):.3g}")
    spectrum = (level, *shape)
    return spectrum, ev.results({**spectra, name: spectrum})


def search(
    ev: Evaluator, spectra: dict[str, Spectrum], rounds: int = 2
) -> tuple[dict[str, Spectrum], dict[str, dict[tuple[float, float, float], float]]]:
    """Coordinate descent over the roads' shape grids; the cost of every shape tried."""
    costs: dict[str, dict[tuple[float, float, float], float]] = {n: {} for n in GRID}
    best = dict(spectra)
    for _ in range(rounds):
        for name, grid in GRID.items():
            tried = {}
            level = best[name][0]
            for shape in itertools.product(grid["w"], grid["n_min"], grid["n_max"]):
                # start from the last shape's level (neighbouring shapes need similar ones)
                spectrum, res = solve_level(ev, name, shape, {**best, name: (level, *shape)})
                level = spectrum[0]
                tried[shape] = (cost(res), spectrum)
                costs[name][shape] = tried[shape][0]
                print(
                    f"  {name:12s} w {shape[0]:.2f} band {shape[1]:g}-{shape[2]:g} "
                    f"level {spectrum[0]:.3g}: cost {tried[shape][0]:.4f}",
                    flush=True,
                )
            best[name] = min(tried.values())[1]
    return best, costs


def spread(costs: Mapping[tuple[float, float, float], float], best: Spectrum) -> list[str]:
    """Per shape parameter, the grid values whose cost is within 10 % of the minimum."""
    low = min(costs.values())
    out = []
    for i, what in enumerate(("w", "n_min", "n_max")):
        values = sorted(
            {
                s[i]
                for s, c in costs.items()
                if c <= 1.1 * low + 1e-12 and all(s[j] == best[j + 1] for j in range(3) if j != i)
            }
        )
        out.append(f"{what} {', '.join(f'{v:g}' for v in values)}")
    return out


def table(columns: Mapping[str, Mapping[str, Any]]) -> str:
    """The target table: the dissertation's value and each column's."""
    names = list(columns)
    lines = [f"{'target':34s} {'dissertation':>12s} " + " ".join(f"{n:>12s}" for n in names)]
    for t, (_r, _f, _v, _s, given, where) in DLC_TARGETS.items():
        row = " ".join(f"{columns[n]['DLC'][t]:12.3f}" for n in names)
        lines.append(f"{'DLC ' + t + ' (' + where + ')':34s} {given:12.3f} {row}")
    for k in next(iter(columns.values()))["PSD ratio"]:
        row = " ".join(f"{columns[n]['PSD ratio'][k]:12.2f}" for n in names)
        lines.append(f"{'rough/medium 2-5 Hz ' + k:34s} {'1/1.5-1.5':>12s} {row}")
    for k, v in PEAKS.items():
        row = " ".join(f"{1e3 * columns[n]['peak'][k]:12.1f}" for n in names)
        lines.append(f"{'peak elevation ' + k + ' [mm]':34s} {1e3 * v:12.1f} {row}")
    for t in ("rough 50 skyhook ACM", "rough 100 skyhook ACM"):
        row = " ".join(f"{1e3 * columns[n]['current std'][t]:12.2f}" for n in names)
        lines.append(f"{'i_d std [mA] ' + t:34s} {'50 > 100':>12s} {row}")
    for t in ("rough", "medium"):
        sp = [
            columns[n]["DLC"][f"{t} 100 skyhook ACM"] / columns[n]["DLC"][f"{t} 50 skyhook ACM"]
            for n in names
            if f"{t} 100 skyhook ACM" in columns[n]["DLC"]
        ]
        if sp:
            lines.append(
                f"{'DLC 100/50 ' + t + ' skyhook':34s} {0.142 / 0.138:12.3f} "
                + " ".join(f"{v:12.3f}" for v in sp)
            )
    lines.append(
        f"{'cost (sum of squared log residuals)':34s} {'':12s} "
        + " ".join(f"{cost(columns[n]):12.4f}" for n in names)
    )
    return "\n".join(lines)


def on_roads(check: Check, spectra: Mapping[str, Spectrum], tag: str) -> Check:
    """``check`` with every random-road run on the roads of ``spectra`` (by preset name)."""
    options = {
        name: {"level": level, "waviness": w, "band": [lo, hi]}
        for name, (level, w, lo, hi) in spectra.items()
    }
    return common.on_roads(check, tag, options)


def count(
    candidates: Mapping[str, Mapping[str, Spectrum]], quick: bool, workers: int
) -> tuple[str, dict[str, int]]:
    """Every random-road claim of the scorecard on each candidate's roads: held or not."""
    from dataclasses import replace

    from mrsuspension.report.findings import CLAIMS, ROAD, evaluate

    road_claims = [c for c in CLAIMS if ROAD in c.depends_on]
    chosen = [
        replace(c, id=f"{c.id} @{name}", check=on_roads(c.check, spectra, name))
        for name, spectra in candidates.items()
        for c in road_claims
    ]
    card = evaluate(quick=quick, claims=chosen, workers=workers)
    held = {r.claim.id: r.holds for r in card.results}
    names = list(candidates)
    lines = [f"{'random-road claim':30s} " + " ".join(f"{n:>10s}" for n in names)]
    for c in road_claims:
        marks = " ".join(f"{'held' if held[f'{c.id} @{n}'] else 'no':>10s}" for n in names)
        lines.append(f"{c.id:30s} {marks}")
    totals = {n: sum(held[f"{c.id} @{n}"] for c in road_claims) for n in names}
    row = " ".join(f"{totals[n]:>10d}" for n in names)
    lines.append(f"{'held (of ' + str(len(road_claims)) + ')':30s} {row}")
    return "\n".join(lines), totals


def describe(name: str, s: Spectrum) -> str:
    return f"{name}: Gd(n0) {s[0]:.3g} m^3, n^-{s[1]:g}, {s[2]:g}-{s[3]:g} cycle/m"


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--full-check", action="store_true")
    parser.add_argument("--rounds", type=int, default=3)
    args = parser.parse_args(argv)
    with process_pool(args.workers, 64) as pool:
        _fit(args, pool)
    return 0


def _fit(args: argparse.Namespace, pool: Any) -> None:
    start = time.perf_counter()
    ev = Evaluator(quick=True, pool=pool)
    reference = {n: _reference(n) for n in GRID}
    best, costs = search(ev, dict(reference), rounds=args.rounds)
    print("\nleast squares (the cost's minimum on the grid):")
    for name in GRID:
        print("  " + describe(name, best[name]), "| within 10 % of the minimum:", "; ".join(
            spread(costs[name], best[name])
        ))  # fmt: skip
    print("identified in the code:", "; ".join(describe(n, _identified(n)) for n in GRID))
    print()
    # the count decides between fits: the rough road's slope profiled (its level solved, the
    # medium-rough road at its fit), every random-road claim of the scorecard on each
    profile: dict[str, dict[str, Spectrum]] = {}
    costs_w: dict[str, float] = {}
    for w in GRID["rough"]["w"]:
        spectrum, res = solve_level(ev, "rough", (w, *best["rough"][2:]), best)
        profile[f"w {w:g}"] = {**best, "rough": spectrum}
        costs_w[f"w {w:g}"] = cost(res)
        print(f"  rough w {w:g}: level {spectrum[0]:.3g}, cost {cost(res):.4f}")
    text, held = count({"reference": reference, **profile}, quick=True, workers=args.workers)
    print(text)
    top = max(held[k] for k in profile)
    pick = min((k for k in profile if held[k] == top), key=lambda k: costs_w[k])
    chosen = profile[pick]
    print(
        f"\nchosen by the count: rough {pick} ({top} random-road claims held against "
        f"{held['reference']} on the reference presets; ties broken by the cost)"
    )
    for name in GRID:
        print("  " + describe(name, chosen[name]))
    columns = {
        "reference": ev.results(reference),
        "least sq.": ev.results(best),
        "chosen": ev.results(chosen),
    }
    print(ev.extremes())
    print("quick settings (0.5 ms step; 0.25 ms for the inverse-model laws)")
    print(table(columns))
    if args.full_check:
        full = Evaluator(quick=False, pool=pool)
        print("\nfull settings (0.1 ms step)")
        print(table({"reference": full.results(reference), "chosen": full.results(chosen)}))
    print(f"\n{ev.runs} runs, {time.perf_counter() - start:.0f} s")


if __name__ == "__main__":
    raise SystemExit(main())
