"""``mrsus simulate`` and ``mrsus sweep`` through typer's test runner."""

from __future__ import annotations

import csv
import json
from pathlib import Path

import pytest
import typer
from typer.testing import CliRunner

from mrsuspension.cli.simulate import parse_frequencies, simulate_command, sweep_command
from mrsuspension.engine.simulate import Simulation, SimulationDiverged
from mrsuspension.errors import ValidationError

ROOT = Path(__file__).resolve().parents[2]
SCENARIOS = ROOT / "examples" / "scenarios"
HARMONIC_KEYS = {"T_as", "T_au", "T_dr", "T_ds", "T_du", "DLC", "gamma", "mean_current"}
PULSE_KEYS = {"SDR_s", "SAR_s", "SDR_u", "SAR_u", "RDR", "peak_tire_force"}
ROAD_KEYS = {"DLC", "rms_body_acceleration", "wk_rms_body_acceleration", "vdv"}

app = typer.Typer(pretty_exceptions_enable=False)
app.command("simulate")(simulate_command)
app.command("sweep")(sweep_command)
runner = CliRunner()


def _invoke(*args: str) -> tuple[int, str, str]:
    res = runner.invoke(app, list(args))
    return res.exit_code, res.stdout, res.stderr


def _scenario(tmp_path: Path, text: str) -> str:
    path = tmp_path / "s.toml"
    path.write_text(text)
    return str(path)


def test_simulate_harmonic_json() -> None:
    code, out, err = _invoke(
        "simulate", str(SCENARIOS / "skyhook-hilo-acm-harmonic.toml"), "--json"
    )
    assert code == 0, err
    m = json.loads(out)
    assert isinstance(m, dict)
    assert set(m) >= HARMONIC_KEYS
    assert m["T_as"] > 0
    assert m["DLC"] > 0
    assert 2.0 < m["gamma"] < 3.5  # ACM policy I at 1.5 Hz / 2.5 cm
    assert 0.0 < m["mean_current"] <= 0.5


def test_simulate_pulse_and_road_json() -> None:
    code, out, err = _invoke("simulate", str(SCENARIOS / "policy-iv-pulse.toml"), "--json")
    assert code == 0, err
    m = json.loads(out)
    assert set(m) >= PULSE_KEYS
    assert m["peak_tire_force"] > 0
    assert m["road_peak"] == "after-onset"  # the default, stated beside the ratios
    code, out, err = _invoke(
        "simulate", str(SCENARIOS / "policy-iv-pulse.toml"), "--json", "--road-peak", "onset"
    )
    assert code == 0, err
    onset = json.loads(out)
    assert onset["road_peak"] == "onset"
    assert onset["SDR_s"] == m["SDR_s"]
    assert m["SAR_s"] / onset["SAR_s"] == pytest.approx(4.854, rel=2e-3)
    code, out, err = _invoke(
        "simulate", str(SCENARIOS / "policy-iv-pulse.toml"), "--road-peak", "first"
    )
    assert code == 2
    assert not out
    assert err.strip() == "error: --road-peak must be one of 'after-onset', 'onset'; got 'first'."
    code, out, err = _invoke(
        "simulate", str(SCENARIOS / "ideal-skyhook-road.toml"), "--json", "--duration", "3"
    )
    assert code == 0, err
    m = json.loads(out)
    assert set(m) >= ROAD_KEYS
    assert m["rms_body_acceleration"] > 0
    assert m["vdv"] > 0


def test_simulate_swept_json_is_a_list() -> None:
    code, out, err = _invoke("simulate", str(SCENARIOS / "reference-model-swept.toml"), "--json")
    assert code == 0, err
    rows = json.loads(out)
    assert [r["frequency"] for r in rows] == [1.0, 1.5, 4.0, 10.0]
    for row in rows:
        assert set(row) >= HARMONIC_KEYS - {"mean_current"}
        assert "mean_current" not in row  # a linear damper takes no current (issue 31)
        assert row["T_as"] > 0
    assert not err.strip(), "no progress bar with --json"


def test_simulate_out_writes_files(tmp_path: Path) -> None:
    out = tmp_path / "run"
    code, stdout, err = _invoke(
        "simulate", str(SCENARIOS / "passive-harmonic.toml"), "--out", str(out)
    )
    assert code == 0, err
    for name in ("result.csv", "result.json", "result.png", "measures.json"):
        assert (out / name).is_file(), name
    assert "T_as" in stdout
    measures = json.loads((out / "measures.json").read_text())
    assert set(measures) >= HARMONIC_KEYS
    header = (out / "result.csv").read_text().splitlines()[0]
    assert header.startswith("time [s],z_s [m]")


def test_simulate_prints_units_and_writes_parquet(tmp_path: Path) -> None:
    pytest.importorskip("pyarrow")
    from mrsuspension.engine.result import SimulationResult

    out = tmp_path / "run"
    scenario = SCENARIOS / "passive-harmonic.toml"
    code, stdout, err = _invoke("simulate", str(scenario), "--out", str(out), "--format", "parquet")
    assert code == 0, err
    lines = {line.split("=")[0].strip(): line for line in stdout.splitlines() if "=" in line}
    assert lines["mean_current"].rstrip().endswith(" [A]")
    assert lines["T_as"].rstrip().endswith(" [-]")
    assert (out / "result.parquet").is_file()
    assert not (out / "result.csv").exists()
    back = SimulationResult.load(out / "result.parquet")
    assert back.units["F_d"] == "N"
    assert back.scenario["excitation"]["kind"] == "harmonic"


@pytest.mark.parametrize(
    ("args", "fragment"),
    [
        (["--format", "xlsx", "--out", "x"], "--format must be a comma list of csv, nc, parquet"),
        (["--format", "parquet"], "needs --out"),
    ],
)
def test_simulate_format_errors(args: list[str], fragment: str) -> None:
    code, _, err = _invoke("simulate", str(SCENARIOS / "passive-harmonic.toml"), *args)
    assert code == 2
    assert fragment in err
    assert "Traceback" not in err


def test_simulate_parquet_without_pyarrow(monkeypatch: pytest.MonkeyPatch, tmp_path: Path) -> None:
    import importlib.util

    real = importlib.util.find_spec
    monkeypatch.setattr(
        importlib.util, "find_spec", lambda name, *a: None if name == "pyarrow" else real(name, *a)
    )
    code, _, err = _invoke(
        "simulate",
        str(SCENARIOS / "passive-harmonic.toml"),
        "--format",
        "parquet",
        "--out",
        str(tmp_path),
    )
    assert code == 2
    assert err.strip().count("\n") == 0
    assert 'pip install "mrsuspension[data]"' in err


@pytest.mark.parametrize(
    "args",
    [["monitor", "--port", "0"], ["hil", "run", str(SCENARIOS / "passive-harmonic.toml"),
                                  "--monitor", "--duration", "1"]],
    ids=["monitor", "hil-run-monitor"],
)  # fmt: skip
def test_the_monitor_without_the_web_extra_is_one_line(
    monkeypatch: pytest.MonkeyPatch, args: list[str]
) -> None:
    """Issue 31: no 40-line ModuleNotFoundError, one line naming the extra."""
    import importlib.util

    from mrsuspension.cli import app

    real = importlib.util.find_spec
    monkeypatch.setattr(
        importlib.util,
        "find_spec",
        lambda name, *a: None if name in ("starlette", "uvicorn") else real(name, *a),
    )
    res = CliRunner().invoke(app, args)
    assert res.exit_code == 2, res.output
    lines = res.stderr.strip().splitlines()
    assert len(lines) == 1, lines
    assert "needs starlette, uvicorn, which are not installed" in lines[0]
    assert 'pip install "mrsuspension[web]"' in lines[0]


def test_sweep_json_and_out(tmp_path: Path) -> None:
    scenario = str(SCENARIOS / "skyhook-hilo-acm-harmonic.toml")
    code, out, err = _invoke("sweep", scenario, "-f", "0.987,1.5,4,12", "--json", "-j", "2")
    assert code == 0, err
    rows = json.loads(out)
    assert [r["frequency"] for r in rows] == [0.987, 1.5, 4.0, 12.0]
    assert all(set(r) >= HARMONIC_KEYS for r in rows)
    assert rows[0]["amplitude"] == 0.025
    assert rows[-1]["amplitude"] < 0.025  # two-stage: constant acceleration above f_T
    assert max(rows, key=lambda r: r["T_as"])["frequency"] == 1.5
    folder = tmp_path / "sweep"
    code, out, err = _invoke(
        "sweep", scenario, "-f", "log:3:1:10", "-a", "0.015", "--out", str(folder)
    )
    assert code == 0, err
    assert (folder / "sweep.png").is_file()
    with (folder / "sweep.csv").open() as fh:
        table = list(csv.DictReader(fh))
    assert len(table) == 3
    assert float(table[0]["amplitude [m]"]) == 0.015
    assert "T_dr [-]" in table[0]
    assert "mean_current [A]" in table[0]
    assert next(iter(table[0])) == "frequency [Hz]"


def test_parse_frequencies() -> None:
    assert parse_frequencies("1, 2.5") == [1.0, 2.5]
    assert len(parse_frequencies("log:30:0.5:15")) == 30
    for bad in ("", "a,b", "log:3", "log:x:1:2", "log:3:5:1"):
        with pytest.raises(ValidationError):
            parse_frequencies(bad)


HARMONIC = '[excitation]\nkind = "harmonic"\nfrequency = 1.5\namplitude = 0.025\n'


@pytest.mark.parametrize(
    ("text", "fragment"),
    [
        ('[controller]\nlaw = "skyhok-hilo"\n' + HARMONIC, "Did you mean 'skyhook-hilo'"),
        ('[damper]\nmodel = "bingam"\n' + HARMONIC, "Did you mean 'bingham'"),
        ("[vehicle]\nsprung_mass = -1.0\n" + HARMONIC, "[vehicle] sprung_mass"),
        ("[vehicle]\nunsprung_mass = 0\n" + HARMONIC, "[vehicle] unsprung_mass"),
        ('[vehicle]\nsprung_mass = "x"\n' + HARMONIC, "[vehicle] sprung_mass"),
        ("[vehicle]\nsprung_mas = 500.0\n" + HARMONIC, "Did you mean 'sprung_mass'"),
        ("[simulation]\ndt = 0.005\n" + HARMONIC, "too large for stability"),
        ("[vehicle\n", "not valid TOML"),
    ],
)
def test_bad_input_exit_2_one_line(tmp_path: Path, text: str, fragment: str) -> None:
    path = _scenario(tmp_path, text)
    for command in ("simulate", "sweep"):
        code, out, err = _invoke(command, path, "--json")
        assert code == 2, (command, out, err)
        assert fragment in err
        assert err.startswith("error: ")
        assert len(err.strip().splitlines()) == 1
        assert "Traceback" not in err


def test_bad_road_file_and_options(tmp_path: Path) -> None:
    (tmp_path / "road.csv").write_text("distance,elevation\n0,0\n1,nan\n2,0\n3,0\n")
    path = _scenario(tmp_path, '[excitation]\nkind = "road"\nprofile = "road.csv"\n')
    code, _, err = _invoke("simulate", path)
    assert code == 2
    assert "error:" in err
    assert len(err.strip().splitlines()) == 1
    code, _, err = _invoke("simulate", str(tmp_path / "missing.toml"))
    assert code == 2
    assert "not found" in err
    code, _, err = _invoke("sweep", str(SCENARIOS / "policy-iv-pulse.toml"), "-f", "1,2")
    assert code == 2
    assert "--amplitude" in err
    code, _, err = _invoke("sweep", str(SCENARIOS / "passive-harmonic.toml"), "-f", "log:2")
    assert code == 2
    assert "log:N:fmin:fmax" in err


def test_diverging_run_is_a_user_error(monkeypatch: pytest.MonkeyPatch) -> None:
    # the stability check keeps scenario files from diverging; force it to see the handling
    def diverge(self: Simulation, *args: object, **kwargs: object) -> None:
        raise SimulationDiverged(
            "simulation diverged at t = 0.6000 s: F_d = 2e+06 N", 0.6, "F_d", 2e6
        )

    monkeypatch.setattr(Simulation, "run", diverge)
    code, out, err = _invoke("simulate", str(SCENARIOS / "policy-iv-pulse.toml"), "--json")
    assert code == 2
    assert not out
    assert err.strip() == "error: simulation diverged at t = 0.6000 s: F_d = 2e+06 N"


def test_a_run_at_the_velocity_clamp_says_so(tmp_path: Path) -> None:
    # policy I ACM at a constant 3.5 cm and 2.3 Hz drives the damper past 0.75 m/s
    scenario = _scenario(
        tmp_path,
        '[controller]\nlaw = "skyhook-hilo"\nmode = "ACM"\n'
        '[excitation]\nkind = "harmonic"\nfrequency = 2.3\namplitude = 0.035\n'
        "[simulation]\ndt = 2e-4\n",
    )
    code, out, err = _invoke("simulate", scenario, "--json")
    assert code == 0, err
    share = json.loads(out)["vm_clamp_fraction"]
    assert share > 0.05
    assert f"upper clamp for {100 * share:.0f} % of the time" in err
    assert "Warning" not in err  # a note, not a Python warning with a file name
    code, out, err = _invoke("sweep", scenario, "-f", "1.5,2.3", "-a", "0.045", "--json", "-j", "1")
    assert code == 0, err
    rows = json.loads(out)
    assert rows[0]["vm_clamp_fraction"] == 0.0
    assert "in 1 of 2 runs" in err
    # within the identified range: no note
    code, out, err = _invoke("simulate", str(SCENARIOS / "skyhook-hilo-acm-harmonic.toml"))
    assert code == 0, err
    assert "clamp" not in err


def test_compile_notice_only_when_the_engine_cache_is_cold(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path
) -> None:
    from mrsuspension.cli.compiling import COMPILE_NOTICE

    scenario = str(SCENARIOS / "passive-harmonic.toml")
    code, _, err = _invoke("simulate", scenario)  # warms the cache if needed
    assert code == 0, err
    code, _, err = _invoke("simulate", scenario)
    assert code == 0, err
    assert COMPILE_NOTICE not in err
    # an empty cache folder looks cold (numba itself read its setting at import)
    monkeypatch.setenv("NUMBA_CACHE_DIR", str(tmp_path))
    code, _, err = _invoke("simulate", scenario)
    assert code == 0, err
    assert err.splitlines()[0] == COMPILE_NOTICE


def test_simulate_warns_in_one_line_when_the_spacing_cuts_an_iso_band(tmp_path: Path) -> None:
    """Issue 27: a user's coarse spacing is told, as a ``warning:`` line (``mrsus`` main)."""
    import subprocess
    import sys

    path = _scenario(
        tmp_path,
        '[controller]\nlaw = "passive"\n[excitation]\nkind = "road"\niso_class = "C"\n'
        "length = 60.0\nspacing = 0.3\n[simulation]\nduration = 0.5\n",
    )
    proc = subprocess.run(
        [sys.executable, "-m", "mrsuspension", "simulate", path, "--json"],
        capture_output=True, text=True, timeout=120, check=False,
    )  # fmt: skip
    assert proc.returncode == 0, proc.stderr
    lines = proc.stderr.strip().splitlines()
    assert len(lines) == 1, lines
    assert lines[0].startswith("warning: ISO 8608 class C at 0.3 m spacing cuts the band")
    assert "road.py" not in proc.stderr
    assert json.loads(proc.stdout)["DLC"] > 0.0
