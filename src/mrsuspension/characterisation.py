"""The dissertation's laboratory characterisation (section 2.2) on any damper model.

The damper was driven by harmonic stroke ``x_d = a_m sin(2 pi f t)`` at constant current
over the test matrix of Table 2.1 (9 frequencies x 5 amplitudes x 5 currents, the larger
amplitudes only at the lower frequencies: 165 tests). :func:`characterise` runs the same
tests on a model and returns the steady-state F-v and F-x loops.

Examples
--------
>>> from mrsuspension.dampers import WangSymmetric
>>> loop = harmonic_loop(WangSymmetric(), frequency=1.5, amplitude=0.0125, current=0.2)
>>> len(loop.force), round(loop.peak_velocity, 4)
(360, 0.1178)
>>> len(table_2_1())
165
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from mrsuspension.dampers import DamperModel, KnownPeak, WangSymmetric
from mrsuspension.dampers.base import FloatArray
from mrsuspension.errors import ValidationError, check_range

if TYPE_CHECKING:
    import pandas as pd

__all__ = [
    "TABLE_2_1_AMPLITUDES",
    "TABLE_2_1_CURRENTS",
    "TABLE_2_1_FREQUENCIES",
    "CharacterisationResult",
    "HarmonicLoop",
    "TestCondition",
    "characterise",
    "harmonic_loop",
    "table_2_1",
]

#: Table 2.1 excitation frequencies [Hz].
TABLE_2_1_FREQUENCIES: tuple[float, ...] = (0.1, 0.5, 1.5, 2.5, 5.0, 7.5, 10.0, 12.5, 15.0)
#: Table 2.1 displacement amplitudes a_m [m] (2.5 to 75 mm).
TABLE_2_1_AMPLITUDES: tuple[float, ...] = (0.0025, 0.0125, 0.025, 0.05, 0.075)
#: Table 2.1 drive currents [A].
TABLE_2_1_CURRENTS: tuple[float, ...] = (0.0, 0.1, 0.2, 0.3, 0.4)
#: Highest frequency tested at each amplitude (Table 2.1: 9 + 8 + 7 + 5 + 4 = 33
#: frequency/amplitude pairs, x 5 currents = 165 tests).
_HIGHEST_FREQUENCY = {0.0025: 15.0, 0.0125: 12.5, 0.025: 10.0, 0.05: 5.0, 0.075: 2.5}


@dataclass(frozen=True)
class TestCondition:
    """One harmonic test: frequency [Hz], amplitude a_m [m] and drive current [A]."""

    frequency: float
    amplitude: float
    current: float

    __test__ = False  # not a pytest test class

    @property
    def peak_velocity(self) -> float:
        """v_m = 2 pi f a_m [m/s]."""
        return 2.0 * math.pi * self.frequency * self.amplitude

    def label(self) -> str:
        """Short label, e.g. ``"1.5 Hz, 12.5 mm, 0.2 A"``."""
        return f"{self.frequency:g} Hz, {self.amplitude * 1e3:g} mm, {self.current:g} A"


def table_2_1(
    *,
    frequencies: Iterable[float] | None = None,
    amplitudes: Iterable[float] | None = None,
    currents: Iterable[float] | None = None,
) -> list[TestCondition]:
    """The 165 tests of Table 2.1, optionally restricted to some values.

    Examples
    --------
    >>> len(table_2_1(frequencies=[0.5, 1.5, 2.5, 5.0]))  # the low-frequency fit range
    95
    """
    fs = TABLE_2_1_FREQUENCIES if frequencies is None else tuple(frequencies)
    ams = TABLE_2_1_AMPLITUDES if amplitudes is None else tuple(amplitudes)
    cs = TABLE_2_1_CURRENTS if currents is None else tuple(currents)
    return [
        TestCondition(f, a, i)
        for a in TABLE_2_1_AMPLITUDES
        if any(math.isclose(a, b) for b in ams)
        for f in TABLE_2_1_FREQUENCIES
        if f <= _HIGHEST_FREQUENCY[a] and any(math.isclose(f, g) for g in fs)
        for i in TABLE_2_1_CURRENTS
        if any(math.isclose(i, c) for c in cs)
    ]


@dataclass(frozen=True)
class HarmonicLoop:
    """Steady-state cycle of a harmonic test: arrays over one period.

    ``time`` [s] (from the start of the cycle), ``stroke`` [m], ``velocity`` [m/s],
    ``current`` [A], ``force`` [N].
    """

    condition: TestCondition
    time: FloatArray
    stroke: FloatArray
    velocity: FloatArray
    current: FloatArray
    force: FloatArray

    @property
    def peak_velocity(self) -> float:
        """v_m = 2 pi f a_m [m/s]."""
        return self.condition.peak_velocity

    @property
    def max_compression_force(self) -> float:
        """Largest force in compression direction (positive) [N]."""
        return float(self.force.max())

    @property
    def max_rebound_force(self) -> float:
        """Largest force magnitude in rebound direction [N]."""
        return float(-self.force.min())

    def energy_per_cycle(self) -> float:
        """Energy dissipated over the cycle, ``closed integral of F dx`` [J]."""
        x = np.append(self.stroke, self.stroke[0])
        f = np.append(self.force, self.force[0])
        return float(np.sum(0.5 * (f[1:] + f[:-1]) * np.diff(x)))

    def equivalent_damping(self) -> float:
        """Viscous coefficient dissipating the same energy, ``E / (pi omega a_m^2)`` [N s/m]."""
        c = self.condition
        return self.energy_per_cycle() / (math.pi * 2 * math.pi * c.frequency * c.amplitude**2)

    def summary(self) -> dict[str, float]:
        """Condition and scalar measures of the loop."""
        c = self.condition
        return {
            "frequency [Hz]": c.frequency,
            "amplitude [m]": c.amplitude,
            "current [A]": c.current,
            "peak velocity [m/s]": c.peak_velocity,
            "max compression force [N]": self.max_compression_force,
            "max rebound force [N]": self.max_rebound_force,
            "energy per cycle [J]": self.energy_per_cycle(),
            "equivalent damping [N s/m]": self.equivalent_damping(),
        }


def _harmonic_setup(
    model: DamperModel, condition: TestCondition, peak_velocity: str
) -> DamperModel:
    if peak_velocity == "known":
        if isinstance(model, WangSymmetric):
            return model.with_options(estimator=KnownPeak(condition.peak_velocity))
        return model
    if peak_velocity == "model":
        return model
    raise ValidationError(f"peak_velocity must be 'known' or 'model'; got {peak_velocity!r}")


def harmonic_loop(
    model: DamperModel,
    frequency: float,
    amplitude: float,
    current: float = 0.0,
    *,
    points_per_cycle: int = 360,
    cycles: int = 3,
    settle_time: float = 2.0,
    max_dt: float = 1e-4,
    peak_velocity: str = "known",
    current_shaping: Callable[[FloatArray, FloatArray, float], FloatArray] | None = None,
) -> HarmonicLoop:
    """Run one harmonic test and return its last (steady-state) cycle.

    Parameters
    ----------
    model : DamperModel
        Any damper model.
    frequency, amplitude, current : float
        f [Hz], a_m [m] and the constant drive current [A].
    points_per_cycle : int
        Samples of the returned loop (360, as in the dissertation's fits).
    cycles, settle_time : int, float
        A model with memory runs at least ``cycles`` periods and ``settle_time`` seconds
        (so internal states and the 1 s peak-velocity window settle); the last cycle is
        kept. A memoryless model runs one cycle.
    max_dt : float
        Largest internal sampling period [s].
    peak_velocity : {"known", "model"}
        ``"known"`` gives the dissertation's models ``v_m = 2 pi f a_m`` (as in the
        characterisation), ``"model"`` keeps the model's own estimator.
    current_shaping : callable, optional
        ``f(velocity, peak_velocity_array, current) -> drive current`` applied along the
        test, e.g. ADFG (:func:`mrsuspension.shaping.adfg_multiplier`).
    """
    cond = TestCondition(
        float(check_range("frequency", frequency, 0.0, 1000.0, unit="Hz", low_inclusive=False)),
        float(check_range("amplitude", amplitude, 0.0, 1.0, unit="m", low_inclusive=False)),
        float(model.check_current(current)),
    )
    if not (isinstance(points_per_cycle, int) and 8 <= points_per_cycle <= 100_000):
        raise ValidationError(
            f"points_per_cycle must be an integer in [8, 100000]; got {points_per_cycle!r}"
        )
    m = _harmonic_setup(model, cond, peak_velocity)
    period = 1.0 / cond.frequency
    sub = max(1, math.ceil(period / points_per_cycle / max_dt))
    n_cycle = points_per_cycle * sub
    # a memoryless model is periodic from the first sample: one cycle is the steady state
    n_cycles = max(cycles, math.ceil(settle_time / period) + 1) if m.stateful else 1
    dt = period / n_cycle
    t = np.arange(n_cycles * n_cycle) * dt
    w = 2.0 * math.pi * cond.frequency
    x = cond.amplitude * np.sin(w * t)
    v = cond.amplitude * w * np.cos(w * t)
    a = -cond.amplitude * w * w * np.sin(w * t)
    i: FloatArray | float = cond.current
    if current_shaping is not None:
        i = np.clip(
            np.asarray(
                current_shaping(v, np.full_like(v, cond.peak_velocity), cond.current), float
            ),
            0.0,
            m.max_current,
        )
    r = m.response(t, x, v, a, i)
    keep = slice((n_cycles - 1) * n_cycle, None, sub)
    return HarmonicLoop(
        condition=cond,
        time=r.time[keep] - r.time[keep][0],
        stroke=r.stroke[keep],
        velocity=r.velocity[keep],
        current=r.current[keep],
        force=r.force[keep],
    )


@dataclass(frozen=True)
class CharacterisationResult:
    """Loops of a set of harmonic tests on one model."""

    model: dict[str, Any]
    loops: tuple[HarmonicLoop, ...]

    def __len__(self) -> int:
        return len(self.loops)

    def find(self, frequency: float, amplitude: float, current: float) -> HarmonicLoop:
        """The loop of a given condition."""
        for loop in self.loops:
            c = loop.condition
            if (
                math.isclose(c.frequency, frequency)
                and math.isclose(c.amplitude, amplitude)
                and math.isclose(c.current, current, abs_tol=1e-12)
            ):
                return loop
        raise ValidationError(
            f"no test at {frequency:g} Hz, {amplitude * 1e3:g} mm, {current:g} A in this result"
        )

    def summary_rows(self) -> list[dict[str, float]]:
        """One row of scalar measures per test."""
        return [loop.summary() for loop in self.loops]

    def to_pandas(self) -> pd.DataFrame:
        """Scalar measures per test as a DataFrame (needs pandas)."""
        import pandas as pd

        return pd.DataFrame(self.summary_rows())

    def save(self, folder: str | Path) -> list[Path]:
        """Write ``summary.csv`` and ``loops.csv`` (long format) to ``folder``."""
        import csv

        folder = Path(folder)
        folder.mkdir(parents=True, exist_ok=True)
        rows = self.summary_rows()
        summary = folder / "summary.csv"
        with summary.open("w", newline="") as fh:
            w = csv.DictWriter(fh, fieldnames=list(rows[0]))
            w.writeheader()
            w.writerows(rows)
        loops = folder / "loops.csv"
        with loops.open("w", newline="") as fh:
            w2 = csv.writer(fh)
            w2.writerow(
                ["frequency [Hz]", "amplitude [m]", "current [A]", "time [s]", "stroke [m]",
                 "velocity [m/s]", "drive current [A]", "force [N]"]
            )  # fmt: skip
            for loop in self.loops:
                c = loop.condition
                for k in range(loop.time.size):
                    w2.writerow(
                        [c.frequency, c.amplitude, c.current, f"{loop.time[k]:.6g}",
                         f"{loop.stroke[k]:.6g}", f"{loop.velocity[k]:.6g}",
                         f"{loop.current[k]:.6g}", f"{loop.force[k]:.6g}"]
                    )  # fmt: skip
        return [summary, loops]


def characterise(
    model: DamperModel,
    conditions: Sequence[TestCondition] | None = None,
    *,
    progress: bool = False,
    **loop_options: Any,
) -> CharacterisationResult:
    """Run a list of harmonic tests (default: all 165 of Table 2.1) on ``model``.

    Currents above the model's ``max_current`` are rejected before anything runs.
    ``loop_options`` go to :func:`harmonic_loop`.
    """
    conds = list(table_2_1() if conditions is None else conditions)
    if not conds:
        raise ValidationError("no test conditions given")
    for c in conds:
        model.check_current(c.current)
    loops: list[HarmonicLoop] = []
    if progress:
        from rich.progress import track

        iterator: Iterable[TestCondition] = track(conds, description=f"characterising {model.name}")
    else:
        iterator = conds
    for c in iterator:
        loops.append(harmonic_loop(model, c.frequency, c.amplitude, c.current, **loop_options))
    return CharacterisationResult(model=model.describe(), loops=tuple(loops))
