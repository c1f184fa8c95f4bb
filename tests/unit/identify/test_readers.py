"""Readers: every supported layout gives the same record in SI units."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import scipy.io

from mrsuspension.errors import ValidationError
from mrsuspension.identify.readers import (
    TestDataError,
    parse_columns,
    parse_units,
    read_test,
    split_name_unit,
)

T = np.arange(0.0, 0.5, 0.01)
X = 0.0125 * np.sin(2 * np.pi * 2.0 * T)  # m
V = 0.0125 * 2 * np.pi * 2.0 * np.cos(2 * np.pi * 2.0 * T)  # m/s
F = 800.0 * np.tanh(V / 0.02)  # N


def check_si(rec, velocity: bool = True) -> None:
    np.testing.assert_allclose(rec.time, T, atol=1e-12)
    np.testing.assert_allclose(rec.displacement, X, rtol=1e-6, atol=1e-12)
    np.testing.assert_allclose(rec.force, F, rtol=1e-6, atol=1e-9)
    if velocity:
        np.testing.assert_allclose(rec.velocity, V, rtol=1e-6, atol=1e-12)
    else:
        assert rec.velocity is None


def write(path: Path, header: str | None, columns, delimiter: str) -> Path:
    np.savetxt(
        path,
        np.column_stack(columns),
        delimiter=delimiter,
        header=header or "",
        comments="",
        fmt="%.10g",
    )
    return path


def test_csv_with_header_in_si(tmp_path: Path) -> None:
    p = write(tmp_path / "a.csv", "time,displacement,velocity,force", [T, X, V, F], ",")
    rec = read_test(p)
    check_si(rec)
    assert rec.roles == ("time", "displacement", "velocity", "force")


def test_header_names_match_case_insensitively_with_units_in_brackets(tmp_path: Path) -> None:
    p = write(
        tmp_path / "a.csv", "TIME (ms),Disp [mm],Vel [mm/s],LOAD [kN],Temp [C]",
        [T * 1e3, X * 1e3, V * 1e3, F / 1e3, np.full_like(T, 25.0)], ",",
    )  # fmt: skip
    rec = read_test(p)
    check_si(rec)
    assert any("Temp" in n for n in rec.notes)  # ignored column is reported, not silent


def test_header_units_as_suffix_and_units_line(tmp_path: Path) -> None:
    p = tmp_path / "b.csv"
    body = "\n".join(
        f"{t:.10g},{x * 1e3:.10g},{f / 1e3:.10g}" for t, x, f in zip(T, X, F, strict=True)
    )
    p.write_text(f"t,stroke_mm,load\ns,mm,kN\n{body}\n")
    check_si(read_test(p), velocity=False)


def test_tsv_in_millimetres(tmp_path: Path) -> None:
    p = write(tmp_path / "a.tsv", "t\tx\tv\tF", [T, X * 1e3, V * 1e3, F], "\t")
    check_si(read_test(p, units="mm,mm/s"))


def test_headerless_whitespace_needs_columns(tmp_path: Path) -> None:
    p = write(tmp_path / "a.txt", None, [T, X * 1e3, F], " ")
    with pytest.raises(TestDataError, match=r"no header.*--columns"):
        read_test(p)
    check_si(read_test(p, columns="t,x,F", units="s,mm,N"), velocity=False)


def test_positional_columns_skip_and_flip(tmp_path: Path) -> None:
    p = write(tmp_path / "a.dat", None, [T, np.zeros_like(T), X, -F], " ")
    rec = read_test(p, columns="t,_,x,-F")
    check_si(rec, velocity=False)
    assert "force sign flipped" in rec.notes


def test_named_columns_by_header_and_number(tmp_path: Path) -> None:
    p = write(tmp_path / "a.csv", "Zeitstempel,Weg,Kraft", [T, X, F], ",")
    check_si(read_test(p, columns="t=Zeitstempel,x=Weg,F=3"), velocity=False)
    with pytest.raises(TestDataError, match=r"no column 'Kraf' for force\. Did you mean 'Kraft'"):
        read_test(p, columns="t=1,x=2,F=Kraf")


def test_semicolon_with_decimal_comma(tmp_path: Path) -> None:
    p = tmp_path / "eu.csv"
    rows = [f"{t:.6f};{x:.8f};{f:.4f}".replace(".", ",") for t, x, f in zip(T, X, F, strict=True)]
    p.write_text("Zeit;Weg;Kraft\n" + "\n".join(rows) + "\n")
    rec = read_test(p, columns="t=Zeit,x=Weg,F=Kraft")
    np.testing.assert_allclose(rec.force, F, atol=1e-4)


def test_mat_named_vectors_and_scalar_current(tmp_path: Path) -> None:
    p = tmp_path / "a.mat"
    scipy.io.savemat(p, {"time": T, "disp_mm": X * 1e3, "velocity": V, "force": F, "current": 0.3})
    rec = read_test(p)
    check_si(rec)
    assert rec.current == 0.3


def test_mat_single_matrix_with_positional_columns(tmp_path: Path) -> None:
    p = tmp_path / "m.mat"
    scipy.io.savemat(p, {"data": np.column_stack([T, X * 1e3, V * 1e3, F / 1e3]).T})  # 4 x n
    with pytest.raises(TestDataError, match=r"one matrix 'data'.*--columns"):
        read_test(p)
    check_si(read_test(p, columns="t,x,v,F", units="s,mm,mm/s,kN"))


def test_mat_struct_fields(tmp_path: Path) -> None:
    p = tmp_path / "s.mat"
    scipy.io.savemat(p, {"test": {"t": T, "x": X, "F": F}})
    check_si(read_test(p), velocity=False)


def test_missing_force_column_is_a_test_error(tmp_path: Path) -> None:
    p = write(tmp_path / "a.csv", "time,displacement", [T, X], ",")
    with pytest.raises(
        TestDataError, match=r"a.csv: no force column \(found: time, displacement\)"
    ):
        read_test(p)


def test_missing_file_and_bad_cells(tmp_path: Path) -> None:
    with pytest.raises(TestDataError, match="file not found"):
        read_test(tmp_path / "nope.csv")
    p = tmp_path / "bad.csv"
    p.write_text("t,x,F\n0,0,0\n0.01,abc,1\n")
    with pytest.raises(TestDataError, match="data row 2, column 2: 'abc' is not a number"):
        read_test(p)
    p.write_text("t,x,F\n0,0,0\n0.01,0.1\n")
    with pytest.raises(TestDataError, match="data row 2 has 2 fields"):
        read_test(p)


def test_empty_fields_become_nan_for_the_preprocessor_to_report(tmp_path: Path) -> None:
    p = tmp_path / "gap.csv"
    p.write_text("t,x,F\n0,0,0\n0.01,,1\n0.02,0.2,nan\n")
    rec = read_test(p)
    assert np.isnan(rec.displacement[1])
    assert np.isnan(rec.force[2])


def test_header_unit_of_the_wrong_dimension(tmp_path: Path) -> None:
    p = write(tmp_path / "a.csv", "t [s],x [N],F [N]", [T, X, F], ",")
    with pytest.raises(TestDataError, match="displacement column is in 'N', a unit of force"):
        read_test(p)


def test_parse_units_by_dimension_and_errors() -> None:
    u = parse_units("kN,mm/s,ms")
    assert dict(u.factors) == {"force": 1e3, "velocity": 1e-3, "time": 1e-3}
    with pytest.raises(ValidationError, match=r"unknown unit 'mmm'\. Did you mean 'mm'"):
        parse_units("mmm")
    with pytest.raises(ValidationError, match="'mm' is a unit of displacement, not of force"):
        parse_units("F=mm")


def test_parse_columns_errors() -> None:
    with pytest.raises(ValidationError, match=r"unknown signal 'forc'\. Did you mean 'force'"):
        parse_columns("t,x,forc")
    with pytest.raises(ValidationError, match="names 'force' twice"):
        parse_columns("t,F,force")
    with pytest.raises(ValidationError, match="mixes positional"):
        parse_columns("t,x=2")


@pytest.mark.parametrize(
    ("header", "expected"),
    [("Force [kN]", ("force", "kN")), ("Time(ms)", ("time", "ms")), ("load_kN", ("load", "kN")),
     ("v_d", ("v_d", None)), ("Disp. (mm)", ("disp", "mm"))],
)  # fmt: skip
def test_split_name_unit(header: str, expected: tuple[str, str | None]) -> None:
    assert split_name_unit(header) == expected


def test_preamble_bom_and_trailing_delimiters(tmp_path: Path) -> None:
    p = tmp_path / "rig.csv"
    rows = "\n".join(f"{t:.10g},{x:.10g},{f:.10g}," for t, x, f in zip(T, X, F, strict=True))
    text = "\ufeffRig: MTS 810\nOperator: ab\ntime,displacement,force,\n" + rows + "\n"
    p.write_text(text, encoding="utf-8")
    rec = read_test(p)
    check_si(rec, velocity=False)
    assert "skipped 2 preamble lines above the table" in rec.notes
    p.write_text("time,displacement,force,extra\n" + rows.replace(",\n", "\n").rstrip(",") + "\n")
    with pytest.raises(TestDataError, match="header line names 4 columns but the rows hold 3"):
        read_test(p)
