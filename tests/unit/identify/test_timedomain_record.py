"""Time-domain records: reading, coil input, and one clear message per kind of bad data."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from mrsuspension.errors import ValidationError
from mrsuspension.identify import TimeRecord, read_record, synthetic_record
from mrsuspension.identify.readers import TestDataError


@pytest.fixture(scope="module")
def record() -> TimeRecord:
    return synthetic_record(duration=1.0, noise=0.01, seed=2)


def write(path: Path, rec: TimeRecord, force_factor: float = 1.0, coil: bool = True) -> Path:
    cols = [rec.time, rec.displacement * 100, rec.velocity * 100, rec.force * force_factor]
    head = "time,disp,vel,force"
    if coil:
        cols.append(rec.coil)
        head += ",voltage"
    np.savetxt(path, np.column_stack(cols), delimiter=",", header=head, comments="", fmt="%.10g")
    return path


def test_reads_cm_and_volts_and_keeps_the_signals(record: TimeRecord, tmp_path: Path) -> None:
    path = write(tmp_path / "r.csv", record)
    rec = read_record(path, "t,x,v,F,u", "s,cm,cm/s,N,V", gain=0.2)
    assert rec.coil_unit == "V"
    assert rec.gain == 0.2
    assert np.allclose(rec.displacement, record.displacement, rtol=1e-8)
    assert np.allclose(rec.coil_current(), 0.2 * record.coil)
    assert rec.sample_rate == 3000.0
    # named form, millivolts
    rec2 = read_record(path, "t=time,x=disp,v=vel,F=force,u=voltage", "x=cm,v=cm/s,u=V")
    assert np.array_equal(rec2.coil, rec.coil)


def test_velocity_is_derived_when_absent(record: TimeRecord, tmp_path: Path) -> None:
    path = write(tmp_path / "r.csv", record)
    rec = read_record(path, "t,x,_,F,u", "s,cm,N,V")
    err = np.abs(rec.velocity - record.velocity)[50:-50]
    assert float(np.sqrt(np.mean(err**2))) < 0.02 * float(np.std(record.velocity))
    assert any("velocity derived" in n for n in rec.notes)


def test_round_trip_through_save(record: TimeRecord, tmp_path: Path) -> None:
    p = record.save(tmp_path / "s.csv", units="s,mm,mm/s,kN")
    rec = read_record(p, "t,x,v,F,u", "s,mm,mm/s,kN,V")
    assert np.allclose(rec.force, record.force, rtol=1e-8, atol=1e-6)


def test_a_few_nan_rows_are_bridged_with_a_note(record: TimeRecord, tmp_path: Path) -> None:
    path = write(tmp_path / "r.csv", record)
    lines = path.read_text().splitlines()
    lines[100] = "nan,,,,"
    lines[200] = lines[200].rsplit(",", 1)[0] + ",nan"
    path.write_text("\n".join(lines) + "\n")
    rec = read_record(path, "t,x,v,F,u", "s,cm,cm/s,N,V")
    assert len(rec) == len(record)  # bridged back onto the uniform grid
    assert any("2 rows with NaN dropped" in n for n in rec.notes)


def test_many_nan_rows_are_refused(record: TimeRecord, tmp_path: Path) -> None:
    rec = record
    f = rec.force.copy()
    f[::10] = np.nan
    with pytest.raises(TestDataError, match=r"10\.0 %\) hold NaN.*at most 2 %"):
        TimeRecord.from_arrays(rec.time, rec.displacement, f, rec.coil, coil_unit="V")


def test_force_in_the_wrong_unit_suggests_kn(record: TimeRecord, tmp_path: Path) -> None:
    path = write(tmp_path / "r.csv", record, force_factor=1e-3)  # written in kN
    with pytest.raises(TestDataError, match="is the column in kN"):
        read_record(path, "t,x,v,F,u", "s,cm,cm/s,N,V")
    path = write(tmp_path / "r.csv", record, force_factor=1e3)  # written in mN
    with pytest.raises(TestDataError, match="mN"):
        read_record(path, "t,x,v,F,u", "s,cm,cm/s,N,V")


def test_displacement_in_the_wrong_unit(record: TimeRecord) -> None:
    with pytest.raises(TestDataError, match="is the column in mm or cm"):
        TimeRecord.from_arrays(record.time, record.displacement * 1e4, record.force, record.coil)


def test_record_without_coil_input(record: TimeRecord, tmp_path: Path) -> None:
    path = write(tmp_path / "r.csv", record, coil=False)
    with pytest.raises(TestDataError, match=r"no coil input.*--columns t,x,v,F,u"):
        read_record(path, "t,x,v,F", "s,cm,cm/s,N")


def test_voltage_without_gain_for_a_current_model(record: TimeRecord) -> None:
    rec = TimeRecord.from_arrays(
        record.time, record.displacement, record.force, record.coil, coil_unit="V"
    )
    with pytest.raises(ValidationError, match=r"driven by current.*no driver gain.*--gain"):
        rec.coil_current("model 'bingham'")
    assert np.array_equal(rec.coil_voltage(4.5), rec.coil)


def test_time_running_backwards(record: TimeRecord) -> None:
    t = record.time.copy()
    t[500], t[501] = t[501], t[500]
    with pytest.raises(TestDataError, match="time is not increasing at data row 502"):
        TimeRecord.from_arrays(t, record.displacement, record.force, record.coil)


def test_jittered_time_is_resampled(record: TimeRecord) -> None:
    t = record.time + np.random.default_rng(1).uniform(-0.1, 0.1, len(record)) * record.dt
    rec = TimeRecord.from_arrays(t, record.displacement, record.force, record.coil)
    assert any("resampled" in n for n in rec.notes)
    assert np.allclose(np.diff(rec.time), rec.dt)


def test_header_naming_the_coil_needs_no_columns(record: TimeRecord, tmp_path: Path) -> None:
    p = record.save(tmp_path / "s.csv", units="s,mm,mm/s,kN")  # header: ...,coil [V]
    rec = read_record(p)
    assert rec.coil_unit == "V"
    assert np.allclose(rec.force, record.force, rtol=1e-8, atol=1e-6)
    assert np.array_equal(rec.coil, record.coil)
    path = write(tmp_path / "r.csv", record)  # header: time,disp,vel,force,voltage (cm)
    rec = read_record(path, units="s,cm,cm/s,N")
    assert rec.coil_unit == "V"
    assert np.allclose(rec.displacement, record.displacement, rtol=1e-8)
