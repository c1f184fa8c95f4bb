"""``mrsus optimize`` through typer's test runner and the real ``mrsus`` app."""

from __future__ import annotations

import json
from pathlib import Path

from typer.testing import CliRunner

from mrsuspension.cli import app

runner = CliRunner()

PROBLEM = """
[problem]
name = "tiny"
seed = 2
population = 5
max_evaluations = 10

[controller]
law = "passive"

[simulation]
dt = 5e-4

[[parameters]]
field = "controller.current"
lower = 0.0
upper = 0.5

[[roads]]
iso_class = "C"
length = 30.0

[objective]
weights = { rms_stroke = 1.0, wk_rms_body_acceleration = 1.0 }
"""


def _write(tmp_path: Path, text: str) -> str:
    path = tmp_path / "p.toml"
    path.write_text(text)
    return str(path)


def test_json_output_and_files(tmp_path: Path) -> None:
    out = tmp_path / "out"
    res = runner.invoke(
        app,
        ["optimize", _write(tmp_path, PROBLEM), "--json", "--out", str(out), "--workers", "1",
         "--max-evaluations", "5"],
    )  # fmt: skip
    assert res.exit_code == 0, res.stderr
    data = json.loads(res.stdout)
    assert data["problem"] == "tiny"
    assert data["evaluations"] <= 5
    assert data["generations"] == 1
    assert set(data["best"]) == {"controller.current"}
    assert 0.0 <= data["best"]["controller.current"] <= 0.5
    road = "ISO 8608 C, seed 0, 30 m, 50 km/h"
    assert set(data["measures"]) == {road}
    assert data["objective"] == min(h["objective"] for h in data["history"])
    ratio = (
        data["measures"][road]["rms_stroke"] / data["reference"][road]["rms_stroke"]
        + data["measures"][road]["wk_rms_body_acceleration"]
        / data["reference"][road]["wk_rms_body_acceleration"]
    ) / 2.0
    assert abs(ratio - data["objective"]) < 1e-9
    assert sorted(Path(f).name for f in data["files"]) == ["convergence.png", "optimization.json"]
    assert json.loads((out / "optimization.json").read_text())["best"] == data["best"]


def test_text_output(tmp_path: Path) -> None:
    res = runner.invoke(app, ["optimize", _write(tmp_path, PROBLEM), "--workers", "1"])
    assert res.exit_code == 0, res.stderr
    assert "best objective J =" in res.stdout
    assert "controller.current =" in res.stdout
    assert "rms_stroke" in res.stdout


def test_bad_file_exits_2(tmp_path: Path) -> None:
    bad = PROBLEM.replace("upper = 0.5", "upper = -0.5")
    res = runner.invoke(app, ["optimize", _write(tmp_path, bad)])
    assert res.exit_code == 2
    assert res.stderr.startswith("error: ")
    assert "lower = 0 must be below upper = -0.5" in res.stderr
    res = runner.invoke(app, ["optimize", str(tmp_path / "missing.toml")])
    assert res.exit_code == 2
    assert "not found" in res.stderr


def test_budget_below_a_population_exits_2(tmp_path: Path) -> None:
    res = runner.invoke(app, ["optimize", _write(tmp_path, PROBLEM), "--max-evaluations", "3"])
    assert res.exit_code == 2
    assert "below one population (5 candidates)" in res.stderr
