"""``mrsus simulate``/``sweep`` on half- and full-car scenarios, and their bad input."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pyopencrg
import pytest
from typer.testing import CliRunner

from mrsuspension.cli import app

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = sorted((ROOT / "examples" / "vehicles").glob("*.toml"))
runner = CliRunner()


def _invoke(*args: str) -> tuple[int, str, str]:
    res = runner.invoke(app, list(args))
    return res.exit_code, res.stdout, res.stderr


def test_the_examples_are_there() -> None:
    names = {p.name for p in EXAMPLES}
    assert names >= {"half_car.toml", "full_car_two_track.toml", "full_car_bump.toml"}


@pytest.mark.parametrize("path", EXAMPLES, ids=[p.name for p in EXAMPLES])
def test_simulate_writes_like_the_quarter_car(path: Path, tmp_path: Path) -> None:
    assert path.read_text().startswith("#"), "each example says what it shows"
    out = tmp_path / "out"
    # the harmonic example runs its steady-state length; the others 1 s
    short = [] if "harmonic" in path.read_text() else ["--duration", "1"]
    code, stdout, stderr = _invoke("simulate", str(path), "--out", str(out), *short)
    assert code == 0, stderr
    assert "heave_ddot_rms" in stdout
    assert "[m/s^2]" in stdout
    for name in ("result.csv", "result.json", "result.png", "measures.json"):
        assert (out / name).is_file()
        assert f"wrote {out / name}" in stdout
    header = (out / "result.csv").read_text().splitlines()[0]
    assert "pitch [rad]" in header
    assert "F_T.rear" in header
    measures = json.loads((out / "measures.json").read_text())
    assert measures["pitch_ddot_rms"] > 0.0
    assert any(k.startswith("DLC.") for k in measures)


def test_sweep_over_a_full_car(tmp_path: Path) -> None:
    path = ROOT / "examples" / "vehicles" / "full_car_two_track.toml"  # symmetric corners
    out = tmp_path / "sweep"
    code, stdout, stderr = _invoke(
        "sweep", str(path), "-f", "2,4", "-a", "0.005", "-j", "1", "--json", "--out", str(out)
    )
    assert code == 0, stderr
    rows = json.loads(stdout)
    assert [r["frequency"] for r in rows] == [2.0, 4.0]
    for r in rows:
        assert r["roll_ddot_rms"] < 1e-9 * r["heave_ddot_rms"]  # same road left and right
        assert {"T_as.front_left", "DLC.rear_right"} <= set(r)
    assert (
        (out / "sweep.csv")
        .read_text()
        .startswith("frequency [Hz],amplitude [m],heave_ddot_rms [m/s^2]")
    )


def _bad(tmp_path: Path, text: str) -> tuple[int, str, str]:
    path = tmp_path / "bad.toml"
    path.write_text(text)
    return _invoke("simulate", str(path))


HARMONIC = '[excitation]\nkind = "harmonic"\nfrequency = 1.5\namplitude = 0.01\n'


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ('[vehicle]\nmodel = "full-car"\npitch_inertia = -5.0\n' + HARMONIC,
         "error: [vehicle] pitch_inertia must be in (0, 1e+07] kg m^2; got -5 kg m^2"),
        ('[vehicle]\nmodel = "half-car"\ncg_to_front = -1.2\ncg_to_rear = 1.0\n' + HARMONIC,
         "error: [vehicle] wheelbase cg_to_front + cg_to_rear must be > 0 m"),
        ('[vehicle]\nmodel = "full-car"\n[damper.rear_lft]\nhysteresis = false\n' + HARMONIC,
         "error: unknown corner table [damper.rear_lft]. Did you mean 'rear_left'?"),
        ('[vehicle]\nmodel = "half-car"\n[controller.front_left]\nlaw = "passive"\n' + HARMONIC,
         "error: unknown corner table [controller.front_left]."),
        ('[excitation]\nkind = "pothole"\nside = "left"\ndepth = 0.03\nlength = 0.5\n',
         "error: [excitation] kind 'pothole' gives a road per wheel: it needs [vehicle] model"),
    ],
)  # fmt: skip
def test_bad_input_is_one_line_and_exit_2(tmp_path: Path, text: str, message: str) -> None:
    code, _, stderr = _bad(tmp_path, text)
    assert code == 2
    assert stderr.strip().splitlines() == [stderr.strip()]
    assert stderr.startswith(message), stderr
    assert "Traceback" not in stderr


def test_a_crg_file_with_a_nan(tmp_path: Path) -> None:
    u = np.arange(200) * 0.1
    v = np.linspace(-1.5, 1.5, 31)
    z = np.zeros((u.size, v.size))
    z[50, 21:23] = np.nan  # holes under the left wheels (v = 0.621 m)
    pyopencrg.CrgRoad(z, u_inc=0.1, v=v).save(tmp_path / "hole.crg", fmt="KDBI")
    code, _, stderr = _bad(
        tmp_path, '[vehicle]\nmodel = "full-car"\n[excitation]\nkind = "crg"\nfile = "hole.crg"\n'
    )
    assert code == 2
    assert stderr.startswith(
        "error: [excitation] CRG file 'hole.crg': the elevation grid has no value (NaN)"
    )
    assert len(stderr.strip().splitlines()) == 1


def test_a_law_left_near_zero_current_is_noted() -> None:
    """Issue 31: the quarter car's skyhook gain on a full car leaves the damper near 0 A."""
    car = ROOT / "examples" / "vehicles" / "full_car_two_track.toml"
    code, _stdout, stderr = _invoke("simulate", str(car), "--duration", "2", "--json")
    assert code == 0, stderr
    assert "note: skyhook-hilo drew a mean current of" in stderr
    assert "may suit another vehicle" in stderr
    quarter = ROOT / "examples" / "scenarios" / "skyhook-hilo-acm-harmonic.toml"
    code, _stdout, stderr = _invoke("simulate", str(quarter), "--json")
    assert code == 0, stderr
    assert "mean current" not in stderr  # the dissertation's gain on its own car
