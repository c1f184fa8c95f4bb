"""The ``mrsus`` command: outputs agree with the library, bad input gives exit code 2."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from typer.testing import CliRunner

from mrsuspension.cli import app
from mrsuspension.dampers import WangSymmetric, make_damper

runner = CliRunner()


def run(*args: str) -> tuple[int, str, str]:
    result = runner.invoke(app, list(args))
    return result.exit_code, result.stdout, result.stderr


def test_force_json_matches_library() -> None:
    code, out, _ = run(
        "damper",
        "force",
        "-v",
        "0.1,-0.2",
        "-a",
        "-1,1",
        "-i",
        "0.2",
        "--peak-velocity",
        "0.3",
        "--json",
    )
    assert code == 0
    data = json.loads(out)
    expected = WangSymmetric().force(0.0, [0.1, -0.2], [-1.0, 1.0], 0.2, peak_velocity=0.3)
    np.testing.assert_allclose(data["force"], expected, rtol=1e-12)
    assert data["model"]["parameter_set"] == "wang-symmetric-low"


def test_force_for_a_peer_model_and_table_output() -> None:
    code, out, _ = run("damper", "force", "-m", "linear", "-v", "0.2")
    assert code == 0
    assert "500" in out  # 2500 N s/m * 0.2 m/s


def test_inverse_recovers_current() -> None:
    m = WangSymmetric(vh_variant="2.13")
    f = float(m.force(0.0, 0.1, -1.0, 0.27, peak_velocity=0.2))
    code, out, _ = run(
        "damper",
        "inverse",
        "-f",
        str(f),
        "-v",
        "0.1",
        "-a",
        "-1",
        "--peak-velocity",
        "0.2",
        "--json",
    )
    assert code == 0
    assert json.loads(out)["current"][0] == pytest.approx(0.27, abs=1e-9)


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (
            ("damper", "force", "-v", "0.1", "-i", "0.7"),
            "--current must be in [0, 0.5] A; got 0.7",
        ),
        (
            ("damper", "force", "-v", "0.1", "-i", "-0.1"),
            "--current must be in [0, 0.5] A; got -0.1",
        ),
        (("damper", "force", "-v", "nan"), "velocity must be finite"),
        (("damper", "force", "-v", "abc"), "--velocity must be a number"),
        (("damper", "force", "-v", "0.1", "-m", "linar"), "Did you mean 'linear'?"),
        (
            ("damper", "force", "-v", "0.1", "-p", "wang-symetric-low"),
            "Did you mean 'wang-symmetric-low'?",
        ),
        (
            ("damper", "force", "-v", "0.1", "-m", "bingham", "--mean"),
            "applies to the dissertation's models",
        ),
        (("damper", "force", "-v", "0.1", "--estimator", "windw"), "Did you mean 'window'?"),
        (("damper", "force", "-v", "0.1,0.2", "-i", "0.1,0.2,0.3"), "equal lengths"),
        (
            ("damper", "force", "-v", "0.1", "--peak-velocity", "9"),
            "--peak-velocity must be in [0, 5] m/s",
        ),
        (("damper", "force", "-v", "0.1", "-p", "missing.toml"), "does not exist"),
        (("damper", "sets", "nope"), "unknown parameter set 'nope'"),
        (("reproduce", "--chapters", "9"), "unknown chapter '9'"),
    ],
)
def test_bad_input_exit_code_2_with_message(args: tuple[str, ...], message: str) -> None:
    code, out, err = run(*args)
    assert code == 2, out + err
    assert message in err
    assert "Traceback" not in out + err


def test_malformed_parameter_file(tmp_path: Path) -> None:
    bad = tmp_path / "bad.toml"
    bad.write_text('model = "wang-symmetric"\n[parameters]\na0 = "fast"\n')
    code, _, err = run("damper", "force", "-v", "0.1", "-p", str(bad))
    assert code == 2
    assert "a0" in err
    assert "must be a number" in err


def test_loops_and_matrix_write_files(tmp_path: Path) -> None:
    code, out, _ = run(
        "damper", "loops", "--currents", "0,0.2", "--out", str(tmp_path / "loops"), "--json"
    )
    assert code == 0
    data = json.loads(out)
    assert len(data["tests"]) == 2
    assert (tmp_path / "loops" / "loops.png").stat().st_size > 1000
    assert (tmp_path / "loops" / "summary.csv").exists()
    code, out, _ = run("damper", "matrix", "-m", "bingham", "--json")
    assert code == 0
    tests = json.loads(out)["tests"]
    assert len(tests) == 165
    assert all(t["energy per cycle [J]"] > 0 for t in tests)


def test_sets_listing_and_detail() -> None:
    code, out, _ = run("damper", "sets", "--json")
    assert code == 0
    names = {s["name"] for s in json.loads(out)}
    assert {"wang-symmetric-low", "wang-symmetric-high", "wang-asymmetric", "spencer-1997"} <= names
    code, out, _ = run("damper", "sets", "wang-asymmetric")
    assert code == 0
    assert "k1c" in out
    assert "Table 2.3" in out


def test_installed_entry_point_runs() -> None:
    """The console script itself (not only the Typer app) works and reports errors."""
    exe = Path(sys.executable).with_name("mrsus")
    ok = subprocess.run(
        [exe, "damper", "force", "-v", "0.1", "--json"], capture_output=True, text=True
    )
    assert ok.returncode == 0, ok.stderr
    assert json.loads(ok.stdout)["force"][0] == pytest.approx(
        float(make_damper("wang-symmetric").force(0.0, 0.1)), rel=1e-12
    )
    bad = subprocess.run(
        [exe, "damper", "force", "-v", "0.1", "-i", "2"], capture_output=True, text=True
    )
    assert bad.returncode == 2
    assert bad.stderr.startswith("error: --current")


def test_study_command_runs_the_example_study(tmp_path: Path) -> None:
    root = Path(__file__).resolve().parents[2]
    code, out, err = run(
        "study", str(root / "examples/studies/passive-current.toml"), "--no-cache", "--json",
        "--out", str(tmp_path / "study.nc"),
    )  # fmt: skip
    assert code == 0, err
    rows = json.loads(out)
    assert len(rows) == 18
    assert (tmp_path / "study.nc").exists()
    peak = {c: max(r["T_as"] for r in rows if r["controller_current"] == c) for c in (0.0, 0.1)}
    assert peak[0.1] < peak[0.0]  # section 4.3.2: passive current lowers the T_as peak


def test_study_command_rejects_a_bad_study(tmp_path: Path) -> None:
    bad = tmp_path / "bad.toml"
    bad.write_text(
        '[controller]\nlaw = "passive"\n[excitation]\nkind = "harmonic"\nfrequency = 1.5\n'
        'amplitude = 0.02\n[grid]\n"vehicle.sprung_mas" = [400.0]\n'
    )
    code, _, err = run("study", str(bad))
    assert code == 2
    assert "sprung_mass" in err


def test_damper_tables_show_units_without_truncation() -> None:
    code, out, err = run("damper", "loops", "--currents", "0,0.4")
    assert code == 0, err
    names, units = out.splitlines()[:2]
    assert "max compression force" in names
    assert "equivalent damping" in names
    assert units.split() == ["[Hz]", "[m]", "[A]", "[m/s]", "[N]", "[N]", "[J]", "[N", "s/m]"]


def test_damper_sets_wraps_sources_at_words() -> None:
    from mrsuspension import parameters

    code, out, _ = run("damper", "sets")
    assert code == 0
    words = out.split()
    for name in parameters.available():
        for word in parameters.get(name).source.split():
            assert word in words, word  # no word cut in two
    assert max(len(line) for line in out.splitlines()) <= 22 + 1 + 16 + 1 + 60


def test_reproduce_prints_plain_progress_lines_in_a_log(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path
) -> None:
    import mrsuspension.report as report

    def fake_build_report(out: Path, *, progress, **_: object) -> Path:  # type: ignore[no-untyped-def]
        progress("report: 1/2 chapter 2")
        progress("report: 2/2 chapter 3")  # within PLAIN_EVERY of the first: not written
        return Path(out) / "index.html"

    monkeypatch.setattr(report, "build_report", fake_build_report)
    code, out, err = run("reproduce", "--out", str(tmp_path), "--quick")
    assert code == 0, err
    assert "0 s  report: 1/2 chapter 2" in err.splitlines()
    assert "\r" not in err
    assert "report written to" in out


def test_loops_that_cannot_be_written_give_one_line_and_keep_the_old_output(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """A full disk while writing --out: one ``error: cannot write --out`` line, exit 2, and
    the previous output left as it was."""
    from mrsuspension import characterisation

    out = tmp_path / "loops"
    assert run("damper", "loops", "--currents", "0", "--out", str(out), "--json")[0] == 0
    before = sorted(p.name for p in out.iterdir())

    def full(*args: object, **kwargs: object) -> list[Path]:
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(characterisation.CharacterisationResult, "save", full)
    code, _, err = run("damper", "loops", "--currents", "0", "--out", str(out), "--force")
    assert code == 2
    assert "cannot write --out" in err
    assert "No space left on device" in err
    assert "Traceback" not in err
    assert sorted(p.name for p in out.iterdir()) == before
