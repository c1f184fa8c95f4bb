"""The study cache: keyed by the study and the code, announced, repairable, clearable."""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest
from typer.testing import CliRunner

import mrsuspension
from mrsuspension.cli import app
from mrsuspension.studies import Study, run_study
from mrsuspension.studies.run import StudyCacheWarning, cache_key

TINY: dict[str, Any] = {
    "study": {"name": "tiny", "measures": ["mean_current"]},
    "excitation": {"kind": "harmonic", "frequency": 5.0, "amplitude": 0.01},
    "simulation": {"dt": 5e-4},
    "grid": {"controller.current": [0.0, 0.2]},
}
TINY_TOML = """
[study]
name = "tiny"
measures = ["mean_current"]

[excitation]
kind = "harmonic"
frequency = 5.0
amplitude = 0.01

[simulation]
dt = 5e-4

[grid]
"controller.current" = [0.0, 0.2]
"""

# one run of the tiny study in a fresh interpreter: whether it came from the cache, values
SCRIPT = """
import json
from mrsuspension.studies import Study, run_study
study = Study.from_dict(json.loads({tiny!r}))
res = run_study(study, workers=1, progress=False)
print(json.dumps({{"from_cache": res.from_cache,
                  "values": [float(v) for v in res["mean_current"]],
                  "package": __import__("mrsuspension").__file__}}))
"""


@pytest.fixture
def cache(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    """A private cache root (``$MRSUSPENSION_CACHE``); the studies' folder inside it."""
    monkeypatch.setenv("MRSUSPENSION_CACHE", str(tmp_path / "cache"))
    return tmp_path / "cache" / "studies"


def test_a_code_change_misses_the_cache(tmp_path: Path) -> None:
    """Edit a measure in a copy of the package: the same study is recomputed, not reused.

    Three runs of about 3 s here (the copied ``__pycache__`` spares numba's compile).
    """
    source = Path(mrsuspension.__file__).parent
    copy = tmp_path / "src" / "mrsuspension"
    shutil.copytree(source, copy)  # with __pycache__: numba's compiled kernels are reused
    env = {**os.environ, "PYTHONPATH": str(tmp_path / "src")}
    env["MRSUSPENSION_CACHE"] = str(tmp_path / "cache")
    script = SCRIPT.format(tiny=json.dumps(TINY))

    def run() -> dict[str, Any]:
        done = subprocess.run(
            [sys.executable, "-c", script], env=env, capture_output=True, text=True, timeout=600
        )
        assert done.returncode == 0, done.stderr
        data: dict[str, Any] = json.loads(done.stdout.splitlines()[-1])
        assert Path(data["package"]).parent == copy  # the copy runs, not the worktree
        return data

    first, second = run(), run()
    assert (first["from_cache"], second["from_cache"]) == (False, True)
    assert second["values"] == first["values"] == pytest.approx([0.0, 0.2])

    steady = copy / "measures" / "steady.py"
    text = steady.read_text()
    # the final formulas every path ends in (post-processed and reduced in the kernels)
    old = 'out["mean_current"], out["mean_square_current"] = current'
    assert text.count(old) == 1
    steady.write_text(text.replace(old, old + '\n        out["mean_current"] += 1.0'))
    edited = run()
    assert not edited["from_cache"]  # the old numbers are not returned
    assert edited["values"] == pytest.approx([1.0, 1.2])
    # (that the new result is cached in turn is the first two runs' property)


def test_the_key_covers_study_and_code(monkeypatch: pytest.MonkeyPatch) -> None:
    from mrsuspension.studies import run as R

    study = Study.from_dict(TINY)
    key = cache_key(study)
    assert key == cache_key(Study.from_dict(TINY)) != study.content_hash()
    monkeypatch.setattr(R, "_fingerprint", "0" * 64)  # as if the code had changed
    assert cache_key(study) != key


def test_a_corrupted_cache_file_is_named_and_recomputed(cache: Path) -> None:
    study = Study.from_dict(TINY)
    first = run_study(study, workers=1, progress=False)
    assert first.cache_file is not None
    assert first.cache_file.parent == cache
    first.cache_file.write_bytes(b"not a NetCDF file")
    with pytest.warns(StudyCacheWarning, match=str(first.cache_file)):
        again = run_study(study, workers=1, progress=False)
    assert not again.from_cache
    assert [float(v) for v in again["mean_current"]] == pytest.approx([0.0, 0.2])
    assert run_study(study, workers=1, progress=False).from_cache  # replaced by a good one


def test_cli_says_where_a_result_came_from(tmp_path: Path, cache: Path) -> None:
    path = tmp_path / "tiny.toml"
    path.write_text(TINY_TOML)
    runner = CliRunner()
    args = ["study", str(path), "--workers", "1", "--json"]
    first = runner.invoke(app, args)
    assert first.exit_code == 0, first.stderr
    assert "from cache" not in first.stderr
    files = list(cache.glob("*.nc"))
    assert len(files) == 1
    second = runner.invoke(app, args)
    assert second.exit_code == 0, second.stderr
    assert second.stderr.strip() == f"from cache: {files[0]}"
    assert json.loads(second.stdout) == json.loads(first.stdout)
    # --no-cache: computed, and not announced
    fresh = runner.invoke(app, [*args, "--no-cache"])
    assert fresh.exit_code == 0
    assert "from cache" not in fresh.stderr

    files[0].write_bytes(b"garbage")
    broken = runner.invoke(app, args)
    assert broken.exit_code == 0, broken.stderr
    assert broken.stderr.strip().splitlines() == [
        f"warning: the study cache file {files[0]} is unreadable (ValueError); recomputing "
        "and replacing it (mrsus cache clear empties the cache)"
    ]


def test_no_cache_writes_nothing(tmp_path: Path, cache: Path) -> None:
    path = tmp_path / "tiny.toml"
    path.write_text(TINY_TOML)
    res = CliRunner().invoke(app, ["study", str(path), "--workers", "1", "--no-cache"])
    assert res.exit_code == 0, res.stderr
    assert not cache.exists()


def test_cache_info_and_clear(cache: Path) -> None:
    runner = CliRunner()
    empty = runner.invoke(app, ["cache", "info"])
    assert empty.exit_code == 0
    assert empty.stdout.splitlines() == [
        f"folder: {cache}",
        "files: 0",
        "size: 0.00 MB (0 bytes)",
    ]
    cache.mkdir(parents=True)
    (cache / "a.nc").write_bytes(b"x" * 1000)
    (cache / "b.123.tmp").write_bytes(b"x" * 500)  # left by an interrupted write
    (cache / "notes.txt").write_text("not ours")
    info = runner.invoke(app, ["cache", "info"])
    assert info.stdout.splitlines()[1:] == ["files: 2", "size: 0.00 MB (1500 bytes)"]
    cleared = runner.invoke(app, ["cache", "clear"])
    assert cleared.exit_code == 0
    assert cleared.stdout.strip() == f"removed 2 files (0.00 MB) from {cache}"
    assert [p.name for p in cache.iterdir()] == ["notes.txt"]
