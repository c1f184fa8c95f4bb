"""Time-domain identification end to end (issue 15): file -> CLI -> parameter set.

A record of random displacement with random 0/2.25 V switching goes through the file
reader, the CLI and the fit; bad data gives one line and exit code 2.
"""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from typer.testing import CliRunner

from mrsuspension import parameters
from mrsuspension.cli.identify import app
from mrsuspension.dampers import Bingham, SpencerBoucWen
from mrsuspension.identify import fit_time_domain, synthetic_record
from mrsuspension.identify.timedomain import segment_metrics

runner = CliRunner()
ARGS = ["--time-domain", "--columns", "t,x,v,F,u", "--units", "s,cm,cm/s,N,V"]


@pytest.fixture(scope="module")
def record_file(tmp_path_factory: pytest.TempPathFactory) -> Path:
    rec = synthetic_record(duration=4.0, noise=0.02, seed=9)
    return rec.save(tmp_path_factory.mktemp("td") / "random.csv", units="s,cm,cm/s,N")


def test_recovers_a_perturbed_spencer_damper_from_the_published_start() -> None:
    truth = parameters.get("spencer-1997").replace(
        c0a=2800.0, k0=3000.0, c1a=22000.0, alpha_a=10000.0, alpha_b=90000.0,
        gamma=5e6, beta=2.5e6,
    )  # fmt: skip
    rec = synthetic_record(duration=8.0, parameters=truth, eta=118.0, noise=0.02, seed=5)
    clean = synthetic_record(duration=8.0, parameters=truth, eta=118.0, noise=0.0, seed=5)
    res = fit_time_domain(rec, "spencer")
    val = slice(res.split, None)
    noise = segment_metrics(rec.time[val], rec.force[val], clean.force[val])
    assert res.start_metrics["validation"].nrmse > 2 * noise.nrmse  # the start is off
    assert res.metrics["validation"].nrmse <= 1.1 * noise.nrmse
    assert abs(res.parameters["eta"] / 118.0 - 1.0) < 0.05
    for key in ("c0a", "alpha_a", "alpha_b", "gamma"):
        assert res.parameters[key] == pytest.approx(truth[key], rel=0.1), key


def test_cli_json(record_file: Path, tmp_path: Path) -> None:
    res = runner.invoke(
        app, [str(record_file), *ARGS, "--model", "spencer", "--gain", "0.2222222", "--json",
              "--out", str(tmp_path / "o"), "--no-plots", "--multistart", "1"],
    )  # fmt: skip
    assert res.exit_code == 0, res.stderr
    data = json.loads(res.stdout)
    for key in ("parameters", "train_nrmse", "validation_nrmse", "train_r2", "validation_r2",
                "fit_seconds"):  # fmt: skip
        assert key in data
    assert data["validation_nrmse"] < 0.01
    assert data["validation_r2"] > 0.999
    assert data["parameters"]["volts_per_amp"] == pytest.approx(4.5, rel=1e-6)
    pset = parameters.load(tmp_path / "o" / "parameters.toml")
    assert SpencerBoucWen(pset).values["eta"] == pytest.approx(data["parameters"]["eta"])


def test_cli_text_and_a_current_model(record_file: Path, tmp_path: Path) -> None:
    res = runner.invoke(
        app, [str(record_file), *ARGS, "--model", "bingham", "--gain", "0.2222222",
              "--out", str(tmp_path / "b"), "--no-plots"],
    )  # fmt: skip
    assert res.exit_code == 0, res.stderr
    assert "NRMSE train" in res.stdout
    assert "wrote" in res.stdout
    Bingham(parameters.load(tmp_path / "b" / "parameters.toml"))
    assert "has no coil lag" in res.stdout


def _bad_files(folder: Path, record_file: Path) -> dict[str, Path]:
    table = np.loadtxt(record_file, delimiter=",", skiprows=1)
    out = {}
    nan = table.copy()
    nan[::20, 3] = np.nan
    kn = table.copy()
    kn[:, 3] *= 1e-3
    for name, t in (("nan", nan), ("kn", kn), ("nocoil", table[:, :4])):
        out[name] = folder / f"{name}.csv"
        np.savetxt(out[name], t, delimiter=",", fmt="%.10g")
    return out


@pytest.mark.parametrize(
    ("case", "args", "message"),
    [
        ("nan", ARGS, "hold NaN or empty values"),
        ("kn", ARGS, "is the column in kN?"),
        ("nocoil", ["--time-domain", "--columns", "t,x,v,F", "--units", "s,cm,cm/s,N"],
         "the record has no coil input"),
        ("good", [*ARGS, "--model", "bingham"], "no driver gain was given; pass --gain"),
        ("good", [*ARGS, "--model", "spencr"], "Did you mean 'spencer'"),
        ("good", [*ARGS, "--validation-fraction", "0.95"], "--validation-fraction"),
    ],
)  # fmt: skip
def test_cli_bad_data_one_line_no_traceback(
    record_file: Path, tmp_path: Path, case: str, args: list[str], message: str
) -> None:
    files = _bad_files(tmp_path, record_file)
    path = record_file if case == "good" else files[case]
    model = [] if "--model" in args else ["--model", "spencer"]
    res = runner.invoke(app, [str(path), *args, *model, "--json"])
    assert res.exit_code == 2, res.stdout
    assert res.stderr.startswith("error: ")
    assert message in res.stderr
    assert len(res.stderr.strip().splitlines()) == 1
    assert "Traceback" not in res.stderr


def test_benchmark_smoke() -> None:
    root = Path(__file__).resolve().parents[2]
    done = subprocess.run(
        [sys.executable, str(root / "benchmarks" / "bench_identify_time.py"), "--duration", "2",
         "--repeat", "1", "--ivp-seconds", "0.1", "--json"],
        capture_output=True, text=True, timeout=300,
    )  # fmt: skip
    assert done.returncode == 0, done.stderr
    data = json.loads(done.stdout)
    assert data["samples"] == 6000
    assert data["ratios"]["solve_ivp (RK45)"] > 1


def test_cli_options_of_the_other_path_are_refused(record_file: Path) -> None:
    res = runner.invoke(app, [str(record_file), *ARGS, "--bands", "0.5-5"])
    assert res.exit_code == 2
    assert res.stderr.strip() == (
        "error: --bands applies to periodic campaigns, not with --time-domain"
    )
    res = runner.invoke(app, [str(record_file), "--free", "n"])
    assert res.exit_code == 2
    assert "--free applies to time-domain records only (add --time-domain)" in res.stderr
