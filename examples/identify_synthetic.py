"""Identify the dissertation's damper model from a (synthetic) rig campaign.

A campaign of 10 harmonic tests (5 currents x 2 frequency/amplitude pairs) is generated
from the Table 2.2 (0.5-5 Hz) parameters with 2 % force noise and written to a temporary
folder in four file layouts (CSV in SI, TSV in mm/kN, headerless text, MATLAB .mat) with
a manifest. The model is then fitted from a start 20 % off the truth, compared with the
Bingham model, and the fitted parameter set is loaded back into a damper, exactly as
with real rig data (see docs/identification.md):

    mrsus identify manifest.csv --model wang-symmetric --compare bingham --out fit
"""

import tempfile
from pathlib import Path

import numpy as np

from mrsuspension import parameters
from mrsuspension.dampers import make_damper
from mrsuspension.identify import identify, synthetic_campaign

folder = Path(tempfile.mkdtemp())
tests = [(f, a, i) for f, a in [(1.5, 0.0125), (2.5, 0.0125)] for i in (0.0, 0.1, 0.2, 0.3, 0.4)]
manifest = synthetic_campaign(folder / "rig", "wang-symmetric", tests, noise=0.02, layout="mixed")
print(f"campaign: {len(tests)} tests in {manifest.parent}")
print(manifest.read_text().splitlines()[3])  # a headerless file: columns and units in the row

truth = parameters.get("wang-symmetric-low")
rng = np.random.default_rng(0)
start = truth.replace(**{k: v * (1 + rng.uniform(-0.2, 0.2)) for k, v in truth.items()})

result = identify(manifest, "wang-symmetric", start=start, compare="bingham")
print(result.summary_text())
files = result.save(folder / "fit")
print(f"wrote {len(files)} files, open {folder / 'fit' / 'index.html'}")

# the fitted set drops straight into a damper model (and so into a vehicle scenario)
damper = make_damper("wang-symmetric", folder / "fit" / "parameters.toml")
for name, model in (("published", make_damper("wang-symmetric")), ("fitted", damper)):
    force = float(model.force(0.0, 0.2, -1.0, 0.3, peak_velocity=0.2))
    print(f"{name:9s} F(v=0.2 m/s, i=0.3 A, v_m=0.2 m/s) = {force:7.1f} N")
