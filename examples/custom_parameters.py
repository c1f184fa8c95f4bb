"""Load your own parameter set from a TOML file and compare it with the published one."""

import tempfile
from pathlib import Path

from mrsuspension import parameters
from mrsuspension.dampers import make_damper

published = parameters.get("wang-symmetric-low")
mine = published.replace(F0=80.0, k2=10.0)  # e.g. a stiffer seal and a stronger coil
path = Path(tempfile.mkdtemp()) / "my-damper.toml"
mine.save(path)
print(f"saved {path.name}: {parameters.load(path)}")

for spec in ("wang-symmetric-low", path):
    damper = make_damper("wang-symmetric", spec)
    force = float(damper.force(0.0, 0.2, 0.0, 0.3, peak_velocity=0.3))
    print(f"{damper.parameters.name:32s} F(v=0.2 m/s, i=0.3 A) = {force:7.1f} N")
