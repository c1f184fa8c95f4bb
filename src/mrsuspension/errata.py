"""The dissertation's errata (model reference, section 12) and the choice the code makes for each.

This list is the single source: the report prints it and ``docs/errata.md`` explains it
(a test checks the two agree).
"""

from __future__ import annotations

from dataclasses import dataclass

__all__ = ["ERRATA", "Erratum"]


@dataclass(frozen=True)
class Erratum:
    """One deviation from the dissertation."""

    number: int
    location: str
    printed: str
    correction: str
    code: str


ERRATA: tuple[Erratum, ...] = (
    Erratum(
        1,
        "eq. (3.1)",
        "unsprung equation carries the gravity term (m_s + m_u) g",
        "m_u g, so the model is in equilibrium at rest (model reference, section 4)",
        "mrsuspension.vehicle.kernel.plant_rates",
    ),
    Erratum(
        2,
        "eq. (3.37)",
        "constant-acceleration stage scales the amplitude by f_T/f",
        "(f_T/f)^2, which keeps the road acceleration constant above f_T",
        "mrsuspension.excitation.two_stage_amplitude",
    ),
    Erratum(
        3,
        "eqs. (3.47)/(3.48)",
        "T_dr garbled",
        "T_dr = rms(x_d) / rms(z_r), dimensionless",
        "mrsuspension.measures.T_dr",
    ),
    Erratum(
        4,
        "eqs. (3.24)/(3.34)",
        "sign of the switching term",
        "-K sat(s/eps) with the force acting up on the sprung mass; the seed's own (3.22) frame would need +K",
        "mrsuspension.control.kernel.control (SlidingMode)",
    ),
    Erratum(
        5,
        "eq. (3.34)",
        "sat(s/eps) undefined",
        "sat(y) = clip(y, -1, 1)",
        "mrsuspension.control.kernel.control (SlidingMode)",
    ),
    Erratum(
        6,
        "eq. (2.17)",
        "printed closed form of the inverse model is garbled",
        "invert C_i of (2.9) directly: i = -I0 - ln(1/y - 1)/a2, y = (C - 1)/k2 + sigma(a2 I0)",
        "mrsuspension.dampers.kernels.wang_inverse",
    ),
    Erratum(
        7,
        "eq. (2.14)",
        "peak-velocity estimate sqrt(v^2 - a x) used in closed loop",
        "runs away in closed loop, and so does a windowed peak of |v_d| (1.2-2.4x too high, "
        "positive feedback through F_t); the default is the cycle average of (2.14), "
        "sqrt(2 mean(v_d^2)) over 1 s ('cycle-rms'), clamped to the set's identified range "
        "(1e-3 to 0.75 m/s)",
        "mrsuspension.dampers.peak_velocity.CycleRms",
    ),
    Erratum(
        8,
        "section 4.2",
        "calls v_r < 0 compression once",
        "compression is v_d > 0 everywhere",
        "sign convention of every model and of the ADFG (S = p for v_d > 0)",
    ),
    Erratum(
        9,
        "eq. (3.38), pulse speed scaling",
        "0.64 s / 4.5 m pulse description does not reproduce w0",
        "w0 = 10.4 rad/s at 50 km/h, scaled linearly with speed",
        "mrsuspension.excitation.RoundedPulse",
    ),
)
