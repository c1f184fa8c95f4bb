"""Start-up benchmark: wall time of ``mrsus simulate`` beside its floor, whole processes.

Each command runs in a fresh interpreter (``sys.executable``, this environment), in turn
(A B C ... A B C ...) so that a machine whose speed drifts moves every command alike;
the medians are printed with ratios against ``import numba`` measured in the same run:

* ``python -c pass``: the interpreter alone;
* ``import numba``: the floor of any command that runs the engine;
* ``numba + target``: ``import numba`` and the first load of any compiled function
  (numba imports its typing and lowering registries then, scipy.linalg among them);
* ``mrsus --help``: the CLI without the numerical stack;
* ``mrsus simulate``: a 12 s harmonic scenario (passive, 0.1 A; ~30 ms of engine time),
  issue 16's start-up acceptance (target <= 0.6 s).

The first run of each command is a warm-up (it fills numba's on-disk cache if empty).

Run: ``python benchmarks/bench_startup.py [--runs N] [--json]``.
"""

from __future__ import annotations

import argparse
import json
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

SCENARIO = """\
[controller]
law = "passive"
current = 0.1
[excitation]
kind = "harmonic"
frequency = 2.0
amplitude = 0.02
[simulation]
duration = 12.0
"""

TARGET = (
    "import numba\nfrom numba.core.registry import cpu_target\ncpu_target.target_context.refresh()"
)


def commands(scenario: Path) -> dict[str, list[str]]:
    """The timed commands by label (all run with this interpreter)."""
    py = sys.executable
    return {
        "python -c pass": [py, "-c", "pass"],
        "import numba": [py, "-c", "import numba"],
        "numba + target": [py, "-c", TARGET],
        "mrsus --help": [py, "-m", "mrsuspension", "--help"],
        "mrsus simulate": [py, "-m", "mrsuspension", "simulate", str(scenario)],
    }


def wall(cmd: list[str]) -> float:
    """Wall seconds of one run of ``cmd`` (its output discarded; a failure raises)."""
    t0 = time.perf_counter()
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    return time.perf_counter() - t0


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", type=int, default=7, help="timed runs of each command")
    ap.add_argument("--json", action="store_true", help="print the medians as JSON")
    args = ap.parse_args()
    if args.runs < 1:
        ap.error(f"--runs must be >= 1; got {args.runs}")
    with tempfile.TemporaryDirectory() as tmp:
        scenario = Path(tmp) / "harm12.toml"
        scenario.write_text(SCENARIO)
        cmds = commands(scenario)
        for cmd in cmds.values():  # warm-up (and numba's cache)
            wall(cmd)
        times: dict[str, list[float]] = {label: [] for label in cmds}
        for _ in range(args.runs):
            for label, cmd in cmds.items():
                times[label].append(wall(cmd))
    medians = {label: statistics.median(ts) for label, ts in times.items()}
    floor = medians["import numba"]
    if args.json:
        print(json.dumps({"runs": args.runs, "median_wall_s": medians}))
        return
    print(f"whole-process wall time, median of {args.runs} runs (ratio to 'import numba')")
    for label, m in medians.items():
        spread = f"{min(times[label]):.3f}-{max(times[label]):.3f}"
        print(f"{label:>16}: {m:7.3f} s  x{m / floor:5.2f}  (min-max {spread})")
    extra = medians["mrsus simulate"] - medians["numba + target"]
    print(f"{'above the floor':>16}: {extra:7.3f} s  (simulate minus numba + target)")


if __name__ == "__main__":
    main()
