"""Manifests: CSV, TOML and folders; currents from file names; precedence."""

from __future__ import annotations

from pathlib import Path

import pytest

from mrsuspension.errors import ValidationError
from mrsuspension.identify.manifest import (
    parse_current_pattern,
    read_manifest,
    values_from_name,
)


def test_csv_manifest_with_units_directives_and_paths(tmp_path: Path) -> None:
    (tmp_path / "data").mkdir()
    m = tmp_path / "campaign.csv"
    m.write_text(
        "# rig 2, October\n"
        "# columns = t,x,F\n"
        "# units = s,mm,N\n"
        "file,current [mA],frequency,amplitude [mm],notes\n"
        "data/run1.txt,100,1.5,12.5,first\n"
        'data/run2.txt,,2.5,12.5,"no current, on purpose"\n'
    )
    man = read_manifest(m)
    e1, e2 = man.entries
    assert e1.file == tmp_path / "data" / "run1.txt"
    assert (e1.current, e1.frequency, e1.amplitude) == (0.1, 1.5, 0.0125)
    assert e1.columns is not None
    assert e1.columns.positional == ("time", "displacement", "force")
    assert e1.units is not None
    assert e1.units.factors["displacement"] == 1e-3
    assert e2.current is None
    assert e2.error is None
    assert any("notes" in n for n in man.notes)  # an unknown column is reported


def test_cli_settings_override_the_manifest(tmp_path: Path) -> None:
    m = tmp_path / "m.csv"
    m.write_text('file,current,columns\nrun.csv,0.2,"t,x,v,F"\n')
    entry = read_manifest(m, columns="t,_,x,F", units="kN").entries[0]
    assert entry.columns is not None
    assert entry.columns.positional == (
        "time",
        None,
        "displacement",
        "force",
    )
    assert entry.units is not None
    assert entry.units.factors == {"force": 1e3}
    assert read_manifest(m).entries[0].columns.positional == (
        "time",
        "displacement",
        "velocity",
        "force",
    )  # type: ignore[union-attr]


def test_bad_rows_are_kept_with_their_error(tmp_path: Path) -> None:
    m = tmp_path / "m.csv"
    m.write_text("file,current,frequency\na.csv,abc,1\nb.csv,0.1,-2\nc.csv,0.2,1.5\n")
    a, b, c = read_manifest(m).entries
    assert "current 'abc' is not a number" in (a.error or "")
    assert "line 2" in (a.error or "")
    assert "frequency must be > 0" in (b.error or "")
    assert c.error is None


def test_manifest_level_errors_raise(tmp_path: Path) -> None:
    with pytest.raises(ValidationError, match="does not exist"):
        read_manifest(tmp_path / "none.csv")
    m = tmp_path / "m.csv"
    m.write_text("name_of_file,current\na.csv,0.1\n")
    with pytest.raises(ValidationError, match="needs a 'file' column"):
        read_manifest(m)
    m.write_text("file,current [kA]\na.csv,0.1\n")
    with pytest.raises(ValidationError, match=r"unit 'kA' is not accepted for current"):
        read_manifest(m)


def test_toml_manifest(tmp_path: Path) -> None:
    m = tmp_path / "m.toml"
    m.write_text(
        'columns = "t,x,v,F"\nunits = "ms,mm,mm/s,kN"\n'
        '[[test]]\nfile = "a.txt"\ncurrent = 0.2\nfrequency = 1.5\namplitude_mm = 12.5\n'
        '[[test]]\nfile = "b.txt"\ncurrent_mA = 300\ncolumns = "t,x,F"\n'
    )
    a, b = read_manifest(m).entries
    assert (a.current, a.frequency, a.amplitude) == (0.2, 1.5, 0.0125)
    assert a.units is not None
    assert a.units.factors["time"] == 1e-3
    assert b.current == 0.3
    assert b.columns is not None
    assert b.columns.positional == ("time", "displacement", "force")
    m.write_text('[[test]]\nfile = "a.txt"\ncurent = 0.2\n')
    with pytest.raises(ValidationError, match=r"unknown key 'curent'\. Did you mean 'current'"):
        read_manifest(m)
    m.write_text('colums = "t,x,F"\n[[test]]\nfile = "a.txt"\n')
    with pytest.raises(ValidationError, match="unknown top-level key 'colums'"):
        read_manifest(m)


def test_folder_with_current_pattern(tmp_path: Path) -> None:
    for name in ("run_0p1A_f1.5.csv", "run_0p3A_f2.5.csv", "notes.md", "manifest.csv"):
        (tmp_path / name).write_text("t,x,F\n")
    man = read_manifest(
        tmp_path, current_pattern=r"_(?P<current>[0-9p.]+)A_f(?P<frequency>[0-9.]+)"
    )
    assert [(e.label, e.current, e.frequency) for e in man.entries] == [
        ("run_0p1A_f1.5.csv", 0.1, 1.5),
        ("run_0p3A_f2.5.csv", 0.3, 2.5),
    ]
    assert all(e.current_source == "file name" for e in man.entries)


def test_manifest_current_wins_over_the_pattern(tmp_path: Path) -> None:
    m = tmp_path / "m.csv"
    m.write_text("file,current\nrun_200mA.csv,0.25\nrun_300mA.csv,\nodd.csv,\n")
    a, b, c = read_manifest(m, current_pattern=r"_(?P<mA>\d+)mA").entries
    assert (a.current, a.current_source) == (0.25, "manifest")
    assert (b.current, b.current_source) == (0.3, "file name")
    assert c.current is None
    assert any("does not match" in n for n in c.notes)


@pytest.mark.parametrize(
    ("pattern", "name", "expected"),
    [
        (r"_(?P<current>[0-9.]+)A", "test_0.25A.csv", 0.25),
        (r"(\d+)mA", "x_150mA.txt", 150.0),  # first unnamed group, taken in A as written
        (r"i(?P<mA>\d+)", "i050_f1.csv", 0.05),
        (r"_(?P<current>\d+p\d+)", "run_0p35.csv", 0.35),
    ],
)
def test_values_from_name(pattern: str, name: str, expected: float) -> None:
    assert values_from_name(parse_current_pattern(pattern), name)["current"] == pytest.approx(
        expected
    )


def test_pattern_errors() -> None:
    with pytest.raises(ValidationError, match="not a valid regular expression"):
        parse_current_pattern("(")
    with pytest.raises(ValidationError, match="has no group for the current"):
        parse_current_pattern(r"\d+A")
