# %% [markdown]
# # (b) Design and compare a controller on a quarter car
#
# The quarter car (sprung mass, unsprung mass, tyre, MR damper) is where a semi-active
# law is first designed. This tutorial drives it over an ISO 8608 class C road at
# 50 km/h with the damper held passive (softest and firmest current) and under the
# skyhook hi-lo law, compares comfort, road holding and rattle space, then scans the
# skyhook gain `k_c` to see the trade-off it sets.
#
# Measures (model reference, section 9): `wk_rms_body_acceleration` is the ISO 2631-1
# Wk-weighted RMS of the body acceleration (comfort), `DLC` the tyre force's standard
# deviation over its mean (road holding), `rms_stroke` the damper stroke's RMS (rattle
# space), `mean_current` the mean drive current.

# %%
from pathlib import Path

from matplotlib.figure import Figure

from mrsuspension.control import HiLo, Passive
from mrsuspension.engine import Simulation, run_many
from mrsuspension.excitation import iso8608

road = iso8608("C", length=70.0, seed=1, speed_kmh=50.0)  # 70 m: 5 s at 50 km/h
DT = 5e-4  # s; the engine refuses a step above the model's stable limit (max_stable_dt)
print(f"road: {road.source}, {road.duration:.1f} s")
print(
    f"largest stable step: {Simulation(road).max_stable_dt() * 1e3:.3f} ms, using {DT * 1e3:g} ms"
)

# %% [markdown]
# ## Three dampers on the same road

# %%
laws = {
    "passive 0 A (soft)": Passive(0.0),
    "passive 0.5 A (firm)": Passive(0.5),
    "skyhook hi-lo (ACM)": HiLo(1, mode="ACM"),
}
results = {name: Simulation(road, controller=law).run(dt=DT) for name, law in laws.items()}
names = ("wk_rms_body_acceleration", "DLC", "rms_stroke", "mean_current")
for name, res in results.items():
    m = res.measures()
    print(f"{name:<22}", "  ".join(f"{k} {m[k]:.4g} [{m.units[k]}]" for k in names))

# %% [markdown]
# The firm damper halves the stroke and costs comfort; skyhook switches between soft and
# firm from the body's absolute velocity and, on this road, improves on the soft damper's
# comfort and road holding at once (the printout above). Its mean current is small: at
# the default gain (`k_c` = 3) it is mostly soft.
#
# ## The gain sets the trade-off
#
# `run_many` runs a batch of simulations (on all cores by default; `workers=1` here, in
# this process) and returns their results in order; `reduce=` would keep only what a
# function of each result returns.

# %%
gains = [1.0, 10.0, 100.0, 1000.0]
runs = [Simulation(road, controller=HiLo(1, gain=k, mode="ACM")) for k in gains]
scan = [r.measures() for r in run_many(runs, dt=DT, workers=1)]
for k, m in zip(gains, scan, strict=True):
    print(f"k_c = {k:6g}: a_w = {m['wk_rms_body_acceleration']:.3f} m/s^2, DLC = {m['DLC']:.4f}")

# %%
fig = Figure(figsize=(6, 3.5), layout="tight")
ax = fig.add_subplot()
ax.plot(
    [m["DLC"] for m in scan],
    [m["wk_rms_body_acceleration"] for m in scan],
    "o-",
    label="skyhook hi-lo, k_c = 1 ... 1000",
)
for name in ("passive 0 A (soft)", "passive 0.5 A (firm)"):
    m = results[name].measures()
    ax.plot(m["DLC"], m["wk_rms_body_acceleration"], "s", label=name)
ax.set_xlabel("road holding: DLC [-]")
ax.set_ylabel("comfort: $a_w$ [m/s$^2$]")
ax.legend(fontsize=8)
out = Path("tutorial-output")
out.mkdir(exist_ok=True)
fig.savefig(out / "b-tradeoff.png", dpi=80)
print(f"wrote {out / 'b-tradeoff.png'}")
fig  # a notebook shows the figure
