# %% [markdown]
# # (c) The full car on an ISO road, tuned with the optimiser
#
# A passenger car (`[vehicle] model = "full-car"`: body heave, pitch and roll over four
# quarter cars, an MR damper at every corner) drives an ISO 8608 class C road at
# 50 km/h, the rear wheels meeting the road a wheelbase later. We tune the skyhook hi-lo
# gain `k_c` of all four corners for the driver's comfort (the ISO 2631-1 vibration total
# value at the seat, `seat_total`) and the rattle space of the left wheels (the RMS of
# their damper stroke, `rms_stroke.<corner>`), against the passive damper at 0 A (the
# softest setting: the most comfortable, with the longest strokes), with `mrsus optimize`'s Python API. The same problem as a TOML
# file runs with `mrsus optimize problem.toml` (`docs/optimisation.md`).
#
# The objective is the weighted mean of each measure divided by the reference
# controller's on the same road: the reference scores J = 1, lower is better.

# %%
from pathlib import Path

from matplotlib.figure import Figure

from mrsuspension.optimize import OptimizationProblem, optimize

problem = OptimizationProblem.from_dict(
    {
        "problem": {"name": "full-car skyhook gain", "seed": 1, "population": 5},
        "vehicle": {"model": "full-car"},
        "controller": {"law": "skyhook-hilo", "mode": "ACM"},
        "simulation": {"duration": 2.0, "dt": 2e-4},  # s; the full car is stable below 0.23 ms
        "parameters": [{"field": "controller.gain", "lower": 0.1, "upper": 300.0, "log": True}],
        "roads": [{"iso_class": "C", "seed": 2, "length": 30.0, "speed": 50.0}],
        "objective": {
            "weights": {
                "seat_total": 1.0,
                "rms_stroke.front_left": 0.5,
                "rms_stroke.rear_left": 0.5,
            },
        },
    }
)
road = problem.roads[0]
print(f"road: {road.name}; tuning {[p.field for p in problem.parameters]}")

# %% [markdown]
# A real tuning run takes a budget of a few hundred evaluations and a longer road; this
# one has a budget of eight, enough to see the search work.

# %%
result = optimize(problem, max_evaluations=8, workers=1, progress=False)
print(
    f"best k_c = {result.best['controller.gain']:.3g}, J = {result.objective:.3f} "
    f"(passive 0 A: J = 1), {len(result.history)} evaluations"
)
units = {"seat_total": "m/s^2", "rms_stroke.front_left": "m", "rms_stroke.rear_left": "m"}
for m, w in problem.weights.items():
    best, ref = result.measures[road.name][m], result.reference[road.name][m]
    print(
        f"  {m:<21} {best:.4g} [{units[m]}] vs passive {ref:.4g} (x{best / ref:.3f}, weight {w:g})"
    )

# %% [markdown]
# ## The tuned car against the passive one
#
# Run both on the road and look at the whole vehicle: the seat's ISO 2631-1 values
# (`vehicle_measures()`, at the driver's seat by default) and each wheel's dynamic load
# coefficient (road holding, not in the objective).

# %%
runs = {
    "passive 0 A": problem.scenario(None, road).run()[0],
    "tuned skyhook": problem.scenario(result.best, road).run()[0],
}
for name, res in runs.items():
    vm = res.vehicle_measures()
    dlc = ", ".join(f"{c} {vm[f'DLC.{c}']:.3f}" for c in res.corners)
    print(
        f"{name:<14} seat a_v = {vm['seat_total']:.3f} {vm.units['seat_total']}, "
        f"seat_z = {vm['seat_z']:.3f} {vm.units['seat_z']}, DLC {dlc}"
    )

# %%
fig = Figure(figsize=(6.5, 3.5), layout="tight")
ax = fig.add_subplot()
for name, res in runs.items():
    ax.plot(res.time, res["heave_ddot"], lw=0.8, label=name)
ax.set_xlabel("time [s]")
ax.set_ylabel("body heave acceleration [m/s$^2$]")
ax.legend(fontsize=8)
out = Path("tutorial-output")
out.mkdir(exist_ok=True)
fig.savefig(out / "c-full-car.png", dpi=80)
print(f"wrote {out / 'c-full-car.png'}")
fig  # a notebook shows the figure
