"""The plateau of a ramped rig test (issue 27): which whole cycles are the steady state.

Hand-made sequences of per-cycle stroke amplitudes [m] and force ranges [N] go through
:func:`find_plateau`; ramped records through :func:`preprocess`.
"""

from __future__ import annotations

import math
import re
from pathlib import Path

import numpy as np
import pytest
from typer.testing import CliRunner

from mrsuspension.dampers import WangSymmetric
from mrsuspension.errors import ValidationError
from mrsuspension.identify.plateau import PlateauRun, consistent_runs, find_plateau
from mrsuspension.identify.preprocess import Loop, PreprocessOptions, preprocess
from mrsuspension.identify.readers import RawTest, TestDataError
from mrsuspension.identify.synthetic import RampEnvelope

pytestmark = pytest.mark.audit("identify plateau")

A = 0.025  # plateau stroke amplitude [m]
RNG = np.random.default_rng(27)


def force_ranges(amps: list[float], noise: float = 0.01) -> np.ndarray:
    """Force ranges of an MR damper, rising less than the stroke, with 1 % scatter."""
    a = np.asarray(amps)
    return 2000.0 * (a / A) ** 0.3 * (1 + RNG.normal(0.0, noise / 3, a.size))


def plateau_of(envelope: list[float], **kw: float) -> tuple[int, int]:
    amps = [A * e * (1 + RNG.normal(0.0, 2e-4)) for e in envelope]
    run = find_plateau(amps, force_ranges(amps), **kw)
    return run.start, run.stop


@pytest.mark.parametrize(
    ("envelope", "expected"),
    [
        pytest.param([0.2, 0.4, 0.6, 0.8, 1, 1, 1, 1, 1], (4, 9), id="ramp-in only"),
        pytest.param([1, 1, 1, 1, 0.8, 0.6, 0.4, 0.2], (0, 4), id="ramp-out only"),
        pytest.param([0.25, 0.5, 0.75, 1, 1, 1, 1, 1, 0.66, 0.33], (3, 8), id="ramp both"),
        pytest.param([0.55, 0.8, 1, 1, 1, 0.7, 0.4], (2, 5), id="cut mid-ramp at start and end"),
        pytest.param([0.9, 0.95, 1, 1, 0.95, 0.9], (2, 4), id="two-cycle plateau, slow ramps"),
        pytest.param([0.91, 0.95, 0.99, 1, 1, 0.97, 0.9], (2, 5), id="ramp top within 1 %"),
        pytest.param(
            [0.2, 0.5, 0.5, 0.5, 0.5, 0.5, 0.5, 0.75, 1, 1, 1, 0.5, 0.2], (1, 7),
            id="two plateaus: the longest wins, though smaller",
        ),
        pytest.param(
            [0.5, 0.5, 0.5, 0.5, 0.75, 1, 1, 1, 1, 0.3], (5, 9),
            id="two plateaus of one length: the larger wins",
        ),
        pytest.param([0, 0, 0.5, 1, 1, 1, 0.5, 0, 0, 0, 0], (3, 6), id="rest is no plateau"),
    ],
)  # fmt: skip
def test_the_plateau_is_found_wherever_it_is(
    envelope: list[float], expected: tuple[int, int]
) -> None:
    assert plateau_of(envelope) == expected


def test_steady_throughout_keeps_every_cycle_despite_noise_and_drift() -> None:
    """2 % force noise scatters the range by ~1 %, a drift moves the force, not its range:
    20 cycles stay one plateau."""
    amps = list(A * (1 + RNG.normal(0.0, 5e-4, 20)))
    run = find_plateau(amps, force_ranges(amps, noise=0.02))
    assert (run.start, run.stop) == (0, 20)
    assert run.range_spread < 0.05


def test_a_first_cycle_transient_is_dropped() -> None:
    """A causal start (Bouc-Wen) leaves the stroke alone and changes the force range."""
    amps = [A] * 6
    ranges = [1500.0, 1980.0, 2000.0, 2010.0, 1995.0, 2005.0]
    run = find_plateau(amps, ranges)
    assert (run.start, run.stop) == (1, 6)


def test_options_set_what_consistent_means() -> None:
    amps = [A * e for e in (0.97, 0.985, 1, 1, 1, 0.985, 0.97)]
    ranges = [2000.0] * 7
    assert find_plateau(amps, ranges).length == 3  # 1 %: 0.985 and 1 differ by 1.5 %
    assert find_plateau(amps, ranges, stroke_tolerance=0.02).length == 5
    assert find_plateau(amps, ranges, stroke_tolerance=0.05).length == 7
    ranges = [2000.0, 2000.0, 1000.0, 2000.0, 2000.0, 2000.0, 2000.0]
    assert find_plateau(amps, ranges, stroke_tolerance=0.05).length == 4
    assert find_plateau(amps, ranges, stroke_tolerance=0.05, range_tolerance=1.0).length == 7


def test_no_two_consistent_cycles_is_refused_with_what_was_found() -> None:
    amps = [A * e for e in (0.2, 0.4, 0.6, 0.8, 1.0, 0.75, 0.5, 0.25)]
    with pytest.raises(TestDataError) as err:
        find_plateau(amps, force_ranges(amps))
    message = str(err.value)
    assert message.startswith("no two consistent cycles: of 8 whole cycles (strokes 5-25 mm")
    assert (
        "no two neighbours agree within 1 % in stroke amplitude and 5 % in force range" in message
    )
    assert re.search(r"; the closest, cycles \d and \d, differ by [+-]\d+ % in stroke and [+-]\d+ % "
                     "in force range. A ramped", message)  # fmt: skip
    assert message.endswith("plateau of at least two whole cycles at constant amplitude")
    assert "\n" not in message


def test_a_cycle_whose_stroke_changes_within_it_is_no_plateau() -> None:
    """Two mirror-image cycles around a one-cycle peak agree with each other; their
    halves (ramp / plateau) do not."""
    amps = [A * 0.6, A * 0.94, A * 0.94, A * 0.6]
    ranges = [1500.0, 1960.0, 1960.0, 1500.0]
    assert find_plateau(amps, ranges).length == 2
    halves = [[0.5 * A, 0.7 * A], [0.88 * A, A], [A, 0.88 * A], [0.7 * A, 0.5 * A]]
    runs = consistent_runs(amps, ranges, halves=halves)
    assert max(r.length for r in runs) == 1


def test_candidate_runs_carry_their_figures() -> None:
    run = find_plateau([A, A * 1.002, A * 0.999], [2000.0, 2010.0, 1990.0])
    assert isinstance(run, PlateauRun)
    assert run.stroke_spread == pytest.approx(1.002 / 0.999 - 1)
    assert run.range_spread == pytest.approx(2010 / 1990 - 1)
    assert run.whole


# ------------------------------------------------------------------------------------
FS = 1000.0
DAMPER = WangSymmetric()


def ramped_record(
    f: float = 2.0,
    ramp_in: int = 3,
    plateau: int = 4,
    ramp_out: int = 3,
    cut_start: float = 0.0,
    cut_end: float = 0.0,
    noise: float = 0.02,
    i: float = 0.2,
    tail: float = 0.3,
) -> tuple[RawTest, RampEnvelope]:
    env = RampEnvelope(f, ramp_in, plateau, ramp_out, cut_start)
    periods = ramp_in + plateau + ramp_out - cut_start - cut_end + (tail if not cut_end else 0)
    t = np.arange(int(periods / f * FS)) / FS
    e, de, dde = env(t)
    w, ph = 2 * math.pi * f, 0.4
    sn, cs = np.sin(w * t + ph), np.cos(w * t + ph)
    x = A * e * sn
    v = A * (de * sn + e * w * cs)
    acc = A * (dde * sn + 2 * de * w * cs - e * w * w * sn)
    force = DAMPER.force(x, v, acc, i, peak_velocity=A * w * e)
    force = force + np.random.default_rng(3).normal(0, noise * np.max(np.abs(force)), t.size)
    return RawTest("ramped", t, x, v, force), env


def test_a_ramped_record_is_fitted_on_its_plateau_only() -> None:
    raw, env = ramped_record(cut_start=1.3, cut_end=1.7)
    loop = preprocess(raw, current=0.2, frequency=2.0, amplitude=A)
    p0, p1 = env.plateau_span
    assert loop.cycles_used == 4
    assert p0 - 0.1 / 2.0 <= loop.span[0]
    assert loop.span[1] <= p1 + 0.1 / 2.0
    assert loop.amplitude == pytest.approx(A, rel=1e-3)
    text = next(n for n in loop.notes if "whole cycles" in n)
    assert "; cycles 2-5 of 6 used (t = " in text
    assert "1 leading cycle dropped as not steady (ramp-in: stroke" in text
    assert "1 trailing cycle dropped as not steady (ramp-out: stroke" in text
    assert not [n for n in loop.notes if n.startswith("warning")]
    assert "v_m = 2 pi f a_m = 0.3142 m/s (manifest)" in loop.notes


def test_a_one_cycle_plateau_is_refused_in_one_line() -> None:
    raw, _ = ramped_record(plateau=1, ramp_in=4, ramp_out=4)
    with pytest.raises(
        TestDataError, match=r"^no two consistent cycles: of 9 whole cycles at 2\.0\d* Hz"
    ):
        preprocess(raw, current=0.2)


def test_a_manifest_amplitude_the_plateau_disagrees_with_is_a_warning_and_v_m_is_measured() -> None:
    raw, _ = ramped_record()
    loop = preprocess(raw, current=0.2, frequency=2.0, amplitude=0.75 * A)
    warnings = [n for n in loop.notes if n.startswith("warning")]
    assert warnings == [
        "warning: stroke amplitude 25 mm (least-squares sine over the 4 cycles fitted) "
        "differs from the manifest's 18.75 mm"
    ]
    assert loop.peak_velocity == pytest.approx(A * 4 * math.pi, rel=2e-3)
    assert any("the manifest's 2 pi f a_m = 0.2356 m/s is -25.0 % off" in n for n in loop.notes)
    # forced nominal: the manifest's value, and the velocity warning says so
    nominal = preprocess(
        raw, PreprocessOptions(peak_velocity="nominal"), current=0.2, frequency=2.0,
        amplitude=0.75 * A,
    )  # fmt: skip
    assert nominal.peak_velocity == pytest.approx(0.75 * A * 4 * math.pi)


def test_a_velocity_column_that_is_not_the_strokes_derivative_is_a_warning() -> None:
    raw, _ = ramped_record()
    flipped = RawTest("r", raw.time, raw.displacement, -raw.velocity, raw.force)
    loop = preprocess(flipped, current=0.2, frequency=2.0, amplitude=A)
    warnings = [n for n in loop.notes if n.startswith("warning")]
    assert len(warnings) == 1
    assert "leads the stroke by -90 degrees, not 90" in warnings[0]
    assert "is its sign flipped? (--columns -v)" in warnings[0]


def test_force_delay_is_compensated_and_validated() -> None:
    raw, _ = ramped_record(noise=0.0)
    delay = 0.003
    late = RawTest("r", raw.time, raw.displacement, raw.velocity,
                   np.interp(raw.time - delay, raw.time, raw.force))  # fmt: skip
    true = preprocess(raw, current=0.2, frequency=2.0, amplitude=A)
    lagged = preprocess(late, current=0.2, frequency=2.0, amplitude=A)
    fixed = preprocess(late, PreprocessOptions(force_delay=delay), current=0.2, frequency=2.0,
                       amplitude=A)  # fmt: skip

    def error(loop: Loop) -> float:
        f = DAMPER.force(loop.stroke, loop.velocity, loop.acceleration, 0.2,
                         peak_velocity=loop.peak_velocity)  # fmt: skip
        return float(np.sqrt(np.mean((f - loop.force) ** 2)) / loop.force_range)

    assert error(true) < 0.002
    assert error(lagged) > 0.01
    assert error(fixed) < 0.004
    assert any(n.startswith("motion delayed by 3 ms") for n in fixed.notes)
    with pytest.raises(ValidationError, match=r"force_delay must be in \[0, 0.1\] s; got 0.5"):
        PreprocessOptions(force_delay=0.5)


def test_cli_plateau_options_are_checked_and_reach_the_settings(tmp_path: Path) -> None:
    from mrsuspension.cli.identify import app
    from mrsuspension.identify import synthetic_campaign

    manifest = synthetic_campaign(tmp_path, "linear", [(1.0, 0.01, 0.0)])
    res = CliRunner().invoke(app, [str(manifest), "--model", "linear", "--force-delay", "2"])
    assert res.exit_code == 2
    assert res.stderr.strip() == "error: --force-delay must be in [0, 0.1] s; got 2.0"
    res = CliRunner().invoke(app, [str(manifest), "--model", "linear", "--stroke-tolerance", "0"])
    assert res.exit_code == 2
    assert res.stderr.strip() == "error: --stroke-tolerance must be in (0, 1]; got 0.0"
    res = CliRunner().invoke(app, [str(manifest), "--model", "linear", "--stroke-tolerance", "0.02",
                                   "--json"])  # fmt: skip
    assert res.exit_code == 0, res.stderr
    assert '"stroke_tolerance": 0.02' in res.stdout
