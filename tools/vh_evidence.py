"""Evidence behind two defaults of vehicle runs (issue 14, docs/errata.md, docs/damper-models.md).

Prints, for a peak-velocity estimator and each v_h variant, (2.12) and (2.13), the
dissertation's findings that decide them: the runaway scenarios (Fig 4.5's setting and
policy I at a constant 3.5 cm over 2.0-2.6 Hz: T_as, DLC, peak |F_d| against the HiL load
cell's 8.8 kN, time at the v_m clamp), Fig 4.4's peak currents, Fig 4.6's gamma and
current ratio, and Table 4.1's nominal row (SAR with the after-onset road peak).

Usage::

    python tools/vh_evidence.py [--estimator cycle-rms|window] [--dt 5e-4]
"""

from __future__ import annotations

import argparse
import time
import warnings
from typing import Any

import numpy as np

from mrsuspension.control import HiLo, make_controller
from mrsuspension.dampers import WangSymmetric
from mrsuspension.engine import Simulation
from mrsuspension.engine.result import SimulationResult, VelocityClampWarning
from mrsuspension.engine.simulate import run_many
from mrsuspension.excitation import Harmonic, RoundedPulse
from mrsuspension.excitation.deterministic import two_stage_amplitude

#: Section 4.3.1: policies I-IV and their gains (n = 2)
GAINS = {1: 3.0, 2: 10.0, 3: 10.0, 4: 300.0}


def reduce(r: SimulationResult) -> dict[str, Any]:
    """Measures plus peak |F_d| and the steady peak current."""
    steady = r.time >= r.time[-1] / 2
    return {
        **r.measures(),
        "F_max": float(np.max(np.abs(r.F_d))),
        "i_max": float(np.max(r.i_d[steady])),
    }


def harmonic(cases: list[tuple[float, float, int, str]], damper: dict[str, Any], dt: float) -> list:
    sims = [
        Simulation(
            Harmonic(f, a),
            damper=WangSymmetric(**damper),
            controller=HiLo(p, mode=mode, gain=GAINS[p]),
        )
        for f, a, p, mode in cases
    ]
    return run_many(sims, dt=dt, reduce=reduce, lanes=True)


def report(estimator: str, vh: str, dt: float) -> None:
    damper = {"estimator": estimator, "vh_variant": vh}
    print(f"\n=== estimator {estimator!r}, v_h ({vh}), dt {dt:g} s")
    freqs = sorted(
        {round(float(f), 3) for f in np.geomspace(0.5, 15.0, 24)} | {2.0, 2.2, 2.3, 2.4, 2.6}
    )
    print("Fig 4.5 setting (SCM, k_c 3/10/10/300, n = 2, two-stage 2.5 cm, 0.5-15 Hz):")
    for p in GAINS:
        out = harmonic(
            [(f, float(two_stage_amplitude(f, 0.025)), p, "SCM") for f in freqs], damper, dt
        )
        k = int(np.argmax([o["T_as"] for o in out]))
        print(
            f"  policy {p}: peak T_as {out[k]['T_as']:.3f} at {freqs[k]:g} Hz, "
            f"max DLC {max(o['DLC'] for o in out):.3f}, "
            f"max |F_d| {max(o['F_max'] for o in out) / 1e3:.2f} kN, "
            f"max time at clamp {100 * max(o['vm_clamp_fraction'] for o in out):.0f} %"
        )
    print("Policy I at a constant 3.5 cm, 2.0-2.6 Hz:")
    for mode in ("SCM", "ACM"):
        out = harmonic(
            [(f, 0.035, 1, mode) for f in (2.0, 2.1, 2.2, 2.3, 2.4, 2.5, 2.6)], damper, dt
        )
        print(
            f"  {mode}: max T_as {max(o['T_as'] for o in out):.3f}, "
            f"max DLC {max(o['DLC'] for o in out):.3f}, "
            f"max |F_d| {max(o['F_max'] for o in out) / 1e3:.2f} kN (load cell 8.8 kN), "
            f"max time at clamp {100 * max(o['vm_clamp_fraction'] for o in out):.0f} %"
        )
    out = harmonic([(1.5, 0.025, p, "SCM") for p in GAINS], damper, dt)
    print(
        "Fig 4.4 (SCM, 1.5 Hz, 2.5 cm): peak i_d I-IV "
        + " / ".join(f"{o['i_max']:.3f}" for o in out)
        + " A (dissertation: about 0.5 A each)"
    )
    scm, acm = harmonic([(1.5, 0.025, 1, "SCM"), (1.5, 0.025, 1, "ACM")], damper, dt)
    print(
        f"Fig 4.6: gamma ACM {acm['gamma']:.2f} (about 2.4), mean i_d ACM/SCM "
        f"{acm['mean_current'] / scm['mean_current']:.2f} (about 0.5), "
        f"T_as SCM {scm['T_as']:.2f} ACM {acm['T_as']:.2f}"
    )
    modes = [
        Simulation(
            Harmonic(1.5, 0.025),
            damper=WangSymmetric(**damper),
            controller=make_controller("inverse-hilo", mode=mode),
        )
        for mode in ("SCM", "ACM")
    ]
    scm, acm = run_many(modes, dt=dt, reduce=reduce, workers=1)
    print(
        f"Fig 5.4 (inverse-model hi-lo, k_d = 1): gamma ACM {acm['gamma']:.2f} (about 2.5), "
        f"mean i_d ACM/SCM {acm['mean_current'] / scm['mean_current']:.2f} (about 0.5)"
    )
    pulse = RoundedPulse(0.035, 3.0, speed_kmh=50.0)
    r = Simulation(pulse, damper=WangSymmetric(**damper), controller=HiLo(1, mode="ACM")).run(4.0)
    road = pulse.after_onset_peak_acceleration  # the SAR denominator of the report

    def peak(x: np.ndarray) -> float:
        return float(np.max(np.abs(x)))

    print(
        f"Table 4.1 nominal: SDR_s {peak(r.z_s) / 0.035:.2f} (0.71), "
        f"SAR_s {peak(r.z_s_ddot) / road:.2f} (0.19), SDR_u {peak(r.z_u) / 0.035:.2f} (1.17), "
        f"SAR_u {peak(r.z_u_ddot) / road:.2f} (1.92), RDR {peak(r.x_d) / 0.035:.2f} (1.13), "
        f"peak |F_d| {peak(r.F_d) / 1e3:.2f} kN"
    )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--estimator", default="cycle-rms", choices=["cycle-rms", "window"])
    parser.add_argument("--dt", type=float, default=5e-4, help="RK4 step [s] (default 5e-4)")
    args = parser.parse_args()
    warnings.simplefilter("ignore", VelocityClampWarning)
    start = time.perf_counter()
    for vh in ("2.12", "2.13"):
        report(args.estimator, vh, args.dt)
    print(f"\n[{time.perf_counter() - start:.0f} s]")


if __name__ == "__main__":
    main()
