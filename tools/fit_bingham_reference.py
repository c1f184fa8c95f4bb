"""Fit the Bingham peer model to the dissertation's model; writes parameters/data/bingham-wang-low.toml.

The Bingham form ``F = (fc_a + fc_b i) sgn(v) + (c0_a + c0_b i) v + f0`` is linear in its
parameters, so the fit is an ordinary linear least-squares problem over the loops of the
Table 2.1 tests in the 0.5-5 Hz range with peak velocity <= 0.75 m/s (the identified
range), computed with the hysteretic model and the ``wang-symmetric-low`` set.

Run: ``python tools/fit_bingham_reference.py``.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from mrsuspension import parameters
from mrsuspension.characterisation import characterise, table_2_1
from mrsuspension.dampers import WangSymmetric

conds = [c for c in table_2_1(frequencies=[0.5, 1.5, 2.5, 5.0]) if c.peak_velocity <= 0.75]
result = characterise(WangSymmetric("wang-symmetric-low"), conds)
rows, rhs = [], []
for loop in result.loops:
    i = loop.condition.current
    v = loop.velocity
    s = np.sign(v)
    rows.append(np.column_stack([s, i * s, v, i * v, np.ones_like(v)]))
    # normalise each test by its force range, as in the dissertation's cost (2.22)
    rng = np.ptp(loop.force)
    rows[-1] = rows[-1] / rng
    rhs.append(loop.force / rng)
A = np.vstack(rows)
b = np.concatenate(rhs)
coef, *_ = np.linalg.lstsq(A, b, rcond=None)
names = ["fc_a", "fc_b", "c0_a", "c0_b", "f0"]
values = {k: float(f"{c:.6g}") for k, c in zip(names, coef, strict=True)}
values["f0"] = 0.0 if abs(values["f0"]) < 1e-6 else values["f0"]
print(values)
pset = parameters.ParameterSet(
    name="bingham-wang-low",
    model="bingham",
    values=values,
    units={"fc_a": "N", "fc_b": "N/A", "c0_a": "N s/m", "c0_b": "N s/(m A)", "f0": "N"},
    descriptions={
        "fc_a": "yield (Coulomb) force at zero current",
        "fc_b": "current slope of the yield force",
        "c0_a": "post-yield viscous coefficient at zero current",
        "c0_b": "current slope of the viscous coefficient",
        "f0": "force offset (accumulator)",
    },
    source=(
        "mrsuspension: linear least-squares fit (tools/fit_bingham_reference.py) to the "
        "dissertation's symmetric model (Table 2.2, 0.5-5 Hz set, eq. 2.12 variant) over the "
        f"{len(conds)} Table 2.1 tests at 0.5-5 Hz with v_m <= 0.75 m/s, each test normalised "
        "by its force range"
    ),
    table="-",
    description="Bingham plastic peer of the dissertation's damper, for model comparisons.",
    frequency_range=(0.5, 5.0),
    max_current=0.5,
)
out = Path(__file__).parents[1] / "src/mrsuspension/parameters/data/bingham-wang-low.toml"
pset.save(out)
out.write_text(
    "# Bingham peer model fitted to the dissertation's model (see source).\n" + out.read_text()
)
print("wrote", out)
