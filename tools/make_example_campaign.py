"""Regenerate the example rig campaign shipped with the package.

``src/mrsuspension/identify/data/example_campaign/``: 8 short harmonic tests of the
dissertation's symmetric model (Table 2.2), 0-0.4 A, 1.5-5 Hz, 2 % force noise, a small
stroke offset, 500 Hz sampling, two cycles each, in the four file layouts the readers
take (CSV in SI, TSV in mm and kN, headerless whitespace text in mm, ``.mat``), with its
``manifest.csv``. Fixed seed: running this again writes the same data (the .mat headers carry a date).

Run: ``python tools/make_example_campaign.py``; then ``mrsus identify`` on the manifest
(``mrsuspension.identify.example_campaign()`` gives its path).
"""

from __future__ import annotations

import shutil
from pathlib import Path

from mrsuspension.identify.synthetic import synthetic_campaign

FOLDER = Path(__file__).resolve().parents[1] / "src/mrsuspension/identify/data/example_campaign"
CONDITIONS = [
    (1.5, 0.0125, 0.0), (1.5, 0.0125, 0.2), (1.5, 0.0125, 0.4),
    (2.5, 0.0125, 0.1), (2.5, 0.0125, 0.3),
    (5.0, 0.005, 0.0), (5.0, 0.005, 0.2), (5.0, 0.005, 0.4),
]  # fmt: skip


def main() -> None:
    if FOLDER.exists():
        shutil.rmtree(FOLDER)
    manifest = synthetic_campaign(
        FOLDER, "wang-symmetric", CONDITIONS, noise=0.02, cycles=2, sample_rate=500.0,
        layout="mixed", seed=15, stroke_offset=0.0005,
    )  # fmt: skip
    size = sum(p.stat().st_size for p in FOLDER.iterdir())
    print(f"wrote {manifest} and {len(CONDITIONS)} tests, {size / 1e3:.0f} kB in all")


if __name__ == "__main__":
    main()
