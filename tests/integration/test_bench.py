"""``mrsus bench --quick --json``: the benchmark runs and reports the agreed keys."""

from __future__ import annotations

import json

from typer.testing import CliRunner

from mrsuspension.cli import app


def test_bench_quick_json() -> None:
    result = CliRunner().invoke(app, ["bench", "--quick", "--json"])
    assert result.exit_code == 0, result.stderr
    data = json.loads(result.stdout)
    for key in (
        "single_run_s",
        "scipy_baseline_s",
        "speedup_vs_scipy",
        "sweep_s",
        "compile_s",
        "sweep_lanes_s",
        "lanes_speedup",
        "sweep_ns_per_run_step",
        "sweep_run_by_run_s",
    ):
        assert key in data
    assert data["sweep_measures_max_relative_difference"] <= 1e-9
    # the plain-Python RK4 is the engine's algorithm written independently: same numbers
    assert data["python_rk4_max_difference_m"] < 1e-12
    assert data["scipy_relative_rms_difference"] < 0.05
    assert data["sweep_runs"] == 24
