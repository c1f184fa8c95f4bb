"""Identify Spencer's MR-damper model, coil lag included, from a random-motion record.

Many rigs, and much public MR-damper data, drive the damper with band-limited random
displacement and switch the coil at random: there are no cycles to cut, so the model is
integrated over the whole record. Here a public-style record is generated (3 kHz, 0-50 Hz
displacement, random 0/2.25 V switching, Spencer et al. 1997 with a coil lag of
118 1/s, 2 % force noise), written as CSV in cm, cm/s, N and V, read back and fitted on
its first 70 %; the last 30 % validates. The same from the command line:

    mrsus identify random.csv --time-domain --model spencer --columns t,x,v,F,u \\
        --units s,cm,cm/s,N,V --gain 0.2222 --out fit

(docs/identification.md, "Time-domain records").
"""

import tempfile
from pathlib import Path

import numpy as np

from mrsuspension import parameters
from mrsuspension.dampers import SpencerBoucWen
from mrsuspension.identify import fit_time_domain, read_record, synthetic_record

folder = Path(tempfile.mkdtemp())
path = synthetic_record(duration=8.0, eta=118.0, noise=0.02, seed=1).save(
    folder / "random.csv", units="s,cm,cm/s,N"
)
print(f"record: {path} ({path.read_text().splitlines()[0]})")

# the driver maps 0-2.25 V to 0-0.5 A: Bingham needs that gain, Spencer's damper is voltage driven
record = read_record(path, columns="t,x,v,F,u", units="s,cm,cm/s,N,V", gain=0.5 / 2.25)
print(f"{len(record)} samples at {record.sample_rate:g} Hz; coil input in {record.coil_unit}")

for model in ("spencer", "bingham"):
    res = fit_time_domain(record, model, starts=2)
    m, s = res.metrics, res.start_metrics
    print(
        f"{model:8s} NRMSE train {100 * m['train'].nrmse:.2f} %, validation "
        f"{100 * m['validation'].nrmse:.2f} % (R^2 {m['validation'].r2:.4f}); from its "
        f"start {100 * s['validation'].nrmse:.2f} %; eta {res.parameters['eta']:.1f} "
        f"1/s; {res.fit_seconds:.1f} s"
    )
    if model == "spencer":
        spencer = res
for key, why in spencer.fixed.items():
    print(f"  fixed {key}: {why}")

# the fitted set is the simulator's format: load it and run the damper
files = spencer.save(folder / "fit", plots=False)
pset = parameters.load(folder / "fit" / "parameters.toml")
damper = SpencerBoucWen(pset)
t = np.arange(0.0, 2.0, 1e-4)
loop = damper.response(t, 0.01 * np.sin(2 * np.pi * 2.0 * t), current=0.5)
print(f"saved {[f.name for f in files]}; the fitted damper dissipates "
      f"{loop.dissipated_energy():.1f} J over 2 cycles of 1 cm at 2 Hz, 0.5 A")  # fmt: skip
