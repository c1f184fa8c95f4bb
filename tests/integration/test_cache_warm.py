"""``mrsus cache warm`` compiles every entry point ahead of time; the notice says so."""

from __future__ import annotations

import io
from pathlib import Path

import pytest
from typer.testing import CliRunner

from mrsuspension.cli import app
from mrsuspension.cli.compiling import (
    COMPILE_NOTICE,
    WARM_STEPS,
    engine_cache_cold,
    notify_if_compiling,
)


def test_cache_warm_compiles_every_entry_point_with_progress() -> None:
    result = CliRunner().invoke(app, ["cache", "warm"])
    assert result.exit_code == 0, result.stderr
    n = len(WARM_STEPS)
    assert f"compiled kernels ready: {n} entry points in" in result.stdout
    for i, (what, _) in enumerate(WARM_STEPS, 1):
        assert f"[{i}/{n}] {what}: " in result.stderr  # each step said with its time
    assert not engine_cache_cold("run", "step")


def test_the_notice_names_each_cold_entry_point_and_an_estimate(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setenv("NUMBA_CACHE_DIR", str(tmp_path))  # an empty cache: all cold
    log = io.StringIO()
    assert notify_if_compiling(log, "run", "step")
    assert log.getvalue() == COMPILE_NOTICE + "\n"
    assert "5-10 s" in COMPILE_NOTICE
    assert "mrsus cache warm" in COMPILE_NOTICE
    (tmp_path / "kernel.run-1.py311.nbi").write_text("")
    assert engine_cache_cold("run", "step")  # step still cold
    assert not engine_cache_cold("run")
