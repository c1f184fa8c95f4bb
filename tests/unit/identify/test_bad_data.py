"""Awkward layouts and bad data: each case is read, or refused with one clear message."""

from __future__ import annotations

import dataclasses
import math
from pathlib import Path

import numpy as np
import pytest

from mrsuspension.dampers import WangSymmetric
from mrsuspension.errors import ValidationError
from mrsuspension.identify import identify, synthetic_campaign
from mrsuspension.identify.preprocess import preprocess
from mrsuspension.identify.readers import RawTest, TestDataError, read_test

DAMPER = WangSymmetric()


def record(f: float = 5.0, a: float = 0.002, fs: float = 200.0, cycles: float = 8.3) -> RawTest:
    t = np.arange(int(cycles / f * fs)) / fs
    w = 2 * math.pi * f
    x = a * np.sin(w * t + 0.4)
    v = a * w * np.cos(w * t + 0.4)
    force = DAMPER.force(x, v, -w * w * x, 0.3, peak_velocity=a * w)
    return RawTest("r", t, x, v, force)


def write(path: Path, text: str) -> Path:
    path.write_text(text)
    return path


def test_quoted_header_and_trailing_empty_columns(tmp_path: Path) -> None:
    p = write(
        tmp_path / "export.csv",
        '"Time [s]","Disp [mm]","Force [kN]",,\n0,0,0,,\n0.001,0.5,0.02,,\n0.002,1,0.03,,\n',
    )
    r = read_test(p)
    assert r.roles == ("time", "displacement", "force")
    assert r.force.tolist() == pytest.approx([0.0, 20.0, 30.0])
    assert "ignored 2 empty trailing columns" in r.notes


@pytest.mark.parametrize(
    ("units", "factors"),
    [("s,cm,cm/s,kN", (1e-2, 1e-2, 1e3)), ("s,mm,mm/s,N", (1e-3, 1e-3, 1.0))],
)
def test_cm_and_kn_units(tmp_path: Path, units: str, factors: tuple[float, ...]) -> None:
    p = write(tmp_path / "r.txt", "0 1 2 3\n0.01 1 2 3\n")
    r = read_test(p, columns="t,x,v,F", units=units)
    assert (r.displacement[0], r.velocity[0], r.force[0]) == pytest.approx(
        (factors[0], 2 * factors[1], 3 * factors[2])
    )
    assert r.units["force"] == units.split(",")[3]


def test_current_in_volts_needs_the_gain(tmp_path: Path) -> None:
    p = write(tmp_path / "r.csv", "Time [s],Disp [mm],Force [N],Current [V]\n0,0,0,2\n0.01,1,5,2\n")
    with pytest.raises(TestDataError, match=r"current column is in V, a voltage; give .* --gain"):
        read_test(p)
    r = read_test(p, current_gain=0.25)
    assert r.current.tolist() == pytest.approx([0.5, 0.5])
    assert any("times the gain 0.25 A/V" in n for n in r.notes)
    with pytest.raises(ValidationError, match="current gain must be a number > 0"):
        read_test(p, current_gain=-1.0)


def test_jittery_time_is_resampled_with_a_note() -> None:
    raw = record()
    rng = np.random.default_rng(0)
    t = np.round(raw.time + rng.uniform(-0.3, 0.3, raw.time.size) / 200.0, 4)
    loop = preprocess(dataclasses.replace(raw, time=t), current=0.3, frequency=5.0, amplitude=0.002)
    note = next(n for n in loop.notes if n.startswith("time steps vary"))
    assert "resampled onto a uniform 4.99" in note
    assert loop.frequency == pytest.approx(5.0, rel=1e-3)
    assert not [n for n in loop.notes if n.startswith("warning")]


def test_a_few_nan_rows_are_dropped_with_a_note() -> None:
    raw = record()
    force = raw.force.copy()
    force[[17, 90, 200]] = np.nan
    loop = preprocess(dataclasses.replace(raw, force=force), current=0.3)
    assert any(
        n.startswith("dropped 3 rows holding NaN or infinite values in force") for n in loop.notes
    )


def test_many_nan_rows_are_refused() -> None:
    raw = record()
    force = raw.force.copy()
    force[::10] = np.nan
    with pytest.raises(TestDataError, match=r"rows \(10\.\d %\) hold NaN .* more than 2 %"):
        preprocess(dataclasses.replace(raw, force=force), current=0.3)


def test_force_in_the_wrong_unit_is_named() -> None:
    raw = record()
    as_kn = dataclasses.replace(raw, force=raw.force * 1e-3, units={"force": "N"})
    with pytest.raises(TestDataError, match=r"implausibly small .* is the force column in kN\?"):
        preprocess(as_kn, current=0.3)
    as_n = dataclasses.replace(raw, force=raw.force * 1e4, units={"force": "kN"})
    with pytest.raises(TestDataError, match=r"implausibly large .* is the force column in N\?"):
        preprocess(as_n, current=0.3)


def test_too_few_samples_per_cycle() -> None:
    raw = record(fs=50.0, cycles=12.0)  # 10 samples per cycle at 5 Hz
    with pytest.raises(TestDataError, match=r"10 samples per cycle .* at least 12 are needed"):
        preprocess(raw, current=0.3)


def test_velocity_column_in_the_wrong_unit_is_flagged() -> None:
    raw = record()
    loop = preprocess(
        dataclasses.replace(raw, velocity=raw.velocity * 10), current=0.3, frequency=5.0,
        amplitude=0.002,
    )  # fmt: skip
    warnings = [n for n in loop.notes if n.startswith("warning")]
    assert warnings[0].startswith("warning: the velocity column's amplitude 0.6283 m/s is +900 %")


def test_cli_gain_reaches_the_reader(tmp_path: Path) -> None:
    manifest = synthetic_campaign(tmp_path, "linear", [(1.0, 0.01, 0.0)])
    with pytest.raises(ValidationError, match="--gain must be a number > 0"):
        identify(manifest, "linear", current_gain=0.0)
