# %% [markdown]
# # (d) Your own control law in Python
#
# A semi-active law is a function of what the controller measures. Here you write one
# as a plain Python function, without editing the package: its parameters without a
# default are **signals**, read by name (`z_s_dot` the body velocity, `v_d` the stroke
# rate `z_u' - z_s'`, `z_s_ddot` the body acceleration, ...: the table in the control
# laws page of the docs), and its parameters with a default are its **options**. It
# returns the drive current [A] (or, with `output="force"`, a target force [N] that the
# damper's inverse model turns into a current).
#
# Decorated with `mrsuspension.control.law` it becomes a controller class: the engine
# compiles it with numba when it can (no Python in the loop) and otherwise calls it back
# into Python, about a microsecond per call. It then runs wherever a built-in law runs:
# `Simulation`, every corner of a `VehicleSimulation`, sweeps, studies, the optimiser
# and the HiL loop.
#
# The example is an acceleration-driven damper (ADD, Savaresi et al. 2005): the damper is
# firm when its force would oppose the body's acceleration, soft otherwise. In this
# toolkit's up-positive frame the damper pushes the body with `c v_d`, so that is when
# `z_s'' v_d < 0` (the paper writes `z_s'' (z_s' - z_u') > 0`: the same rule, with the
# stroke rate of the other sign). We compare it with the built-in skyhook hi-lo and with the passive damper.

# %%
from pathlib import Path

import numpy as np
from matplotlib.figure import Figure

from mrsuspension.control import HiLo, Passive, law
from mrsuspension.engine import Simulation, run_many
from mrsuspension.excitation import iso8608


@law
def add_law(z_s_ddot, v_d, high=0.5, low=0.0):
    """Acceleration-driven damper: ``high`` [A] when z_s'' v_d < 0, else ``low`` [A]."""
    return high if z_s_ddot * v_d < 0.0 else low


print(f"law {add_law.law!r} runs on the {add_law.path()} path")
print("options:", ", ".join(f"{o.name} = {o.default}" for o in add_law.describe_options()))

# %% [markdown]
# ## On a quarter car, beside skyhook and passive
#
# An ISO 8608 class C road at 50 km/h; the same measures as tutorial (b): comfort
# (Wk-weighted body acceleration), road holding (DLC), rattle space (RMS stroke).

# %%
road = iso8608("C", length=70.0, seed=1, speed_kmh=50.0)  # 5 s at 50 km/h
DT = 5e-4  # s
laws = {
    "passive 0 A": Passive(0.0),
    "skyhook hi-lo": HiLo(1, mode="ACM"),
    "ADD (yours)": add_law(high=0.5),
}
measures = {name: Simulation(road, controller=c).run(dt=DT).measures() for name, c in laws.items()}
names = ("wk_rms_body_acceleration", "DLC", "rms_stroke", "mean_current")
for name, m in measures.items():
    print(f"{name:<14}", "  ".join(f"{k} {m[k]:.4g} [{m.units[k]}]" for k in names))

# %% [markdown]
# Check a law's sign before trusting it: with the rule turned round (`z_s'' v_d > 0`)
# the damper would push the body along with its acceleration; try it and compare the
# printout (comfort gets much worse and the current stays high most of the time).
#
# ## Tune an option
#
# The firm current `high` sets how hard the law acts. A scan through `run_many` (in this
# process: `workers=1`; a law defined in a notebook cannot be sent to worker processes,
# a law in a module can):

# %%
highs = [0.05, 0.1, 0.2, 0.3, 0.5]
runs = [Simulation(road, controller=add_law(high=h)) for h in highs]
scan = [r.measures() for r in run_many(runs, dt=DT, workers=1)]
for h, m in zip(highs, scan, strict=True):
    print(f"high = {h:4.2f} A: a_w = {m['wk_rms_body_acceleration']:.3f} m/s^2, "
          f"DLC = {m['DLC']:.4f}")  # fmt: skip

# %% [markdown]
# ## Its cost per call
#
# The numba path costs a few nanoseconds a call; the same function forced onto the
# Python path (`numba=False`) about a microsecond. A 1 kHz HiL loop with ten model steps
# a tick calls the law ten times a millisecond: the loop refuses a law too slow for it
# and says what it measured.


# %%
@law(numba=False)
def add_python(z_s_ddot, v_d, high=0.5, low=0.0):
    """The same law, always called back into Python."""
    return high if z_s_ddot * v_d < 0.0 else low


fast, slow = add_law.cost(), add_python.cost()
print(f"cost per call: numba {fast * 1e9:.0f} ns, Python {slow * 1e9:.0f} ns "
      f"({slow / fast:.0f} times)")  # fmt: skip
same = Simulation(road, controller=add_python(high=0.5)).run(dt=DT).measures()
print(
    "same result on both paths:",
    np.isclose(same["DLC"], measures["ADD (yours)"]["DLC"], rtol=0, atol=1e-12),
)

# %%
fig = Figure(figsize=(6, 3.5), layout="tight")
ax = fig.add_subplot()
ax.plot([m["DLC"] for m in scan], [m["wk_rms_body_acceleration"] for m in scan], "o-",
        label="ADD, high = 0.05 ... 0.5 A")  # fmt: skip
for name in ("passive 0 A", "skyhook hi-lo"):
    m = measures[name]
    ax.plot(m["DLC"], m["wk_rms_body_acceleration"], "s", label=name)
ax.set_xlabel("road holding: DLC [-]")
ax.set_ylabel("comfort: $a_w$ [m/s$^2$]")
ax.legend(fontsize=8)
out = Path("tutorial-output")
out.mkdir(exist_ok=True)
fig.savefig(out / "d-own-law.png", dpi=80)
print(f"wrote {out / 'd-own-law.png'}")
fig  # a notebook shows the figure

# %% [markdown]
# ## Where next
#
# - At every corner of a car: `VehicleSimulation(car, road, controllers=add_law())`.
# - From a scenario file: `[controller] law = "my_laws.py:add_law"` with its options as
#   keys, then `mrsus simulate`, `sweep`, `study`, `optimize` or `hil run`.
# - Gains from the plant (e.g. a Riccati solve): `@law(for_plant=...)`; vector and matrix
#   options: give the default as a list. The control laws page of the docs has both.
