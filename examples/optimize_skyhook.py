"""Tune the skyhook hi-lo gain k_c for comfort, road holding and rattle space.

A small version of ``examples/optimize/skyhook-gain.toml`` (``mrsus optimize`` runs the
file): the same problem with a short road and a small budget, run in this process, then
the best gain placed on the comfort / road-holding trade-off of a few passive currents.
Runs in a few seconds.
"""

from __future__ import annotations

from mrsuspension.optimize import OptimizationProblem, optimize
from mrsuspension.tradeoff import tradeoff

problem = OptimizationProblem.from_dict(
    {
        "problem": {"name": "skyhook gain (small)", "seed": 1, "population": 6},
        "controller": {"law": "skyhook-hilo", "mode": "ACM"},
        "simulation": {"dt": 5e-4},
        "parameters": [{"field": "controller.gain", "lower": 1.0, "upper": 3000.0, "log": True}],
        "roads": [{"iso_class": "C", "seed": 1, "length": 60.0, "speed": 50.0}],
        "objective": {"weights": {"wk_rms_body_acceleration": 1.0, "DLC": 1.0, "rms_stroke": 0.5}},
    }
)
result = optimize(problem, max_evaluations=24, workers=1, progress=False)
road = problem.roads[0].name
print(
    f"best k_c = {result.best['controller.gain']:.3g}, J = {result.objective:.4f} (passive 0 A = 1)"
)
for m, w in problem.weights.items():
    best, ref = result.measures[road][m], result.reference[road][m]
    print(f"  {m:26} {best:9.4g} vs {ref:9.4g} (x{best / ref:.3f}, weight {w:g})")

grid = {
    "passive": [
        (f"{c:g} A", {"controller": {"law": "passive", "current": c}}) for c in (0.0, 0.1, 0.3, 0.5)
    ]
}
points = tradeoff(problem.roads, grid=grid, dt=5e-4, workers=1)
front = points.pareto(("wk_rms_body_acceleration", "DLC"))
for p, on in zip(points.points, front, strict=True):
    print(
        f"passive {p.setting:6} a_w = {p.values[0]:.3f} m/s2  DLC = {p.values[1]:.4f}"
        f"{'  (front)' if on else ''}"
    )
fig = points.plot(extra={"optimiser best": result.measures[road]})
fig.savefig("optimize_skyhook.png", dpi=90)
print("wrote optimize_skyhook.png")
