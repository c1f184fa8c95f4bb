# %% [markdown]
# # (a) Model and fit your damper from rig files
#
# A damper characterisation campaign gives one file per test: stroke, force (and often
# velocity and current) sampled while the rig drives a sine at a fixed current. This
# tutorial fits the dissertation's symmetric MR-damper model to such a campaign, compares
# it with the Bingham model, and drops the fitted parameter set into a damper you can
# simulate with.
#
# The campaign here is the example shipped with the package
# (`mrsuspension.identify.example_campaign()`): eight tests at 0-0.4 A and 1.5-5 Hz, with
# 2 % force noise, in the four file layouts the readers take (CSV in SI units, TSV in
# mm and kN, a headerless text file whose columns are named in the manifest, and a
# MATLAB `.mat` file). Your own campaign needs the same: a `manifest.csv` naming each
# file with its frequency, amplitude and current (`docs/identification.md`).

# %%
from pathlib import Path

from mrsuspension.dampers import make_damper
from mrsuspension.identify import example_campaign, identify
from mrsuspension.identify.manifest import read_manifest

manifest = example_campaign()
entries = read_manifest(manifest).entries
print(f"{len(entries)} tests in {manifest.parent.name}/:")
for e in entries[:4]:
    print(
        f"  {e.file.name:<24} {e.frequency:4.1f} Hz  {e.amplitude * 1e3:5.1f} mm  {e.current:.2f} A"
    )

# %% [markdown]
# ## Fit
#
# `identify` reads every file (any of the layouts, units converted to SI), cuts each
# record to its steady cycles, and fits all tests at once by least squares on the force.
# `compare="bingham"` fits a second model for reference. The summary gives each test's
# normalised RMS error (NRMSE: the force error over the force range).

# %%
result = identify(manifest, "wang-symmetric", compare="bingham")
print(f"mean NRMSE {result.mean_nrmse:.2%}, worst {result.max_nrmse:.2%}")
print(result.verdict())
for name, value in result.parameters.items():
    print(f"  {name:>8} = {value:10.5g} [{result.parameters.units.get(name, '-')}]")

# %% [markdown]
# ## Use the fitted set
#
# The fitted parameters are a parameter set like the published ones: save them
# (`result.save(folder)` writes `parameters.toml`, a report and one plot per test) and
# give the file to a damper model, a scenario's `[damper] parameters`, or `mrsus`.

# %%
out = Path("tutorial-output")
files = result.save(out / "fit", plots=False)
damper = make_damper("wang-symmetric", out / "fit" / "parameters.toml")
published = make_damper("wang-symmetric")
for label, model in (("published", published), ("fitted", damper)):
    force = float(model.force(0.0, 0.2, -1.0, 0.3, peak_velocity=0.2))
    print(f"{label:>9}: F(v = 0.2 m/s, i = 0.3 A, v_m = 0.2 m/s) = {force:7.1f} N")

# %% [markdown]
# ## One test, measured and fitted
#
# The force-velocity loop of the 0.4 A test: the measured samples and the fitted model.

# %%
from matplotlib.figure import Figure  # no pyplot: a notebook shows it once, CI needs no display

test = max(result.fitted_tests(), key=lambda t: t.loop.mean_current)
loop = test.loop
fig = Figure(figsize=(6, 3.5), layout="tight")
ax = fig.add_subplot()
ax.plot(loop.velocity, loop.force, ".", ms=2, color="k", label="measured")
ax.plot(loop.velocity, test.model_force, color="C3", label=f"fitted ({test.nrmse:.1%})")
ax.set_xlabel("velocity $v_d$ [m/s]")
ax.set_ylabel("force $F_d$ [N]")
ax.set_title(f"{test.file}: {loop.mean_current:.2f} A, {loop.frequency:g} Hz")
ax.legend()
fig.savefig(out / "a-fit-loop.png", dpi=80)
print(f"wrote {out / 'a-fit-loop.png'}")
fig  # a notebook shows the figure
