"""Issue 26 section 4: the study cache is keyed by the content of every file a study reads.

For each kind of file input (a top-level or per-corner parameter file, TOML or JSON, a
CSV road profile, an OpenCRG road, an included base scenario), a small study is run,
run again (from the cache), then the file's content is changed at the same path with
its modification time put back: the rerun must miss the cache and give other numbers.
"""

from __future__ import annotations

import os
from collections.abc import Callable
from pathlib import Path

import numpy as np
import pytest

from mrsuspension.studies import Study, run_study

LINEAR_TOML = 'model = "linear"\n[parameters]\nc = {c}\n'
LINEAR_JSON = '{{"model": "linear", "parameters": {{"c": {c}}}}}'


def _road_csv(height_mm: float) -> str:
    rows = [f"{x:g},{height_mm * np.sin(0.8 * x):.6g}" for x in np.arange(0.0, 12.0, 0.25)]
    return "distance [m],elevation [mm]\n" + "\n".join(rows) + "\n"


def _crg(path: Path, height: float) -> None:
    import pyopencrg

    u = np.arange(0.0, 12.0, 0.05)
    v = np.linspace(-1.5, 1.5, 7)
    z = height * np.sin(0.8 * u)[:, None] * np.ones_like(v)[None, :]
    pyopencrg.CrgRoad(z, u_inc=0.05, v=v).save(str(path), fmt="KDBI")


_HALF_CAR = '[vehicle]\nmodel = "half-car"\n'
_SIM = "[simulation]\nduration = 0.4\ndt = 2e-4\n"
_ROAD = '[excitation]\nkind = "road"\nprofile = "rough"\n'
_BUMP = '[excitation]\nkind = "bump"\nside = "left"\nheight = 0.02\nlength = 0.5\n'

# kind -> (file name, study text, writer of the file's version k = 0 or 1)
CASES: dict[str, tuple[str, str, Callable[[Path, int], None]]] = {
    "damper parameter file (TOML)": (
        "damper.toml",
        '[damper]\nmodel = "linear"\nparameters = "damper.toml"\n' + _ROAD + _SIM,
        lambda p, k: p.write_text(LINEAR_TOML.format(c=(1500.0, 3000.0)[k])),
    ),
    "per-corner parameter file (TOML)": (
        "rear.toml",
        _HALF_CAR + '[damper.rear]\nmodel = "linear"\nparameters = "rear.toml"\n' + _BUMP + _SIM,
        lambda p, k: p.write_text(LINEAR_TOML.format(c=(1500.0, 3000.0)[k])),
    ),
    "per-corner parameter file (JSON)": (
        "front.json",
        _HALF_CAR + '[damper.front]\nmodel = "linear"\nparameters = "front.json"\n' + _BUMP + _SIM,
        lambda p, k: p.write_text(LINEAR_JSON.format(c=(1500.0, 3000.0)[k])),
    ),
    "road profile (CSV)": (
        "road.csv",
        '[excitation]\nkind = "road"\nprofile = "road.csv"\nspeed = 36.0\n' + _SIM,
        lambda p, k: p.write_text(_road_csv((5.0, 40.0)[k])),
    ),
    "OpenCRG road (.crg)": (
        "road.crg",
        _HALF_CAR + '[excitation]\nkind = "crg"\nfile = "road.crg"\nspeed = 36.0\n' + _SIM,
        lambda p, k: _crg(p, (0.005, 0.04)[k]),
    ),
    "included base scenario": (
        "base.toml",
        '[study]\nscenario = "base.toml"\n' + _SIM,
        lambda p, k: p.write_text(
            _ROAD + f'[controller]\nlaw = "passive"\ncurrent = {(0.0, 0.4)[k]}\n'
        ),
    ),
}


def _numbers(result: object) -> np.ndarray:
    ds = result.dataset  # type: ignore[attr-defined]
    return np.concatenate([np.ravel(ds[m].values) for m in sorted(ds.data_vars)])


@pytest.mark.audit("stale cache")
@pytest.mark.parametrize("kind", list(CASES))
def test_changed_input_file_misses_the_cache(kind: str, tmp_path: Path) -> None:
    name, text, write = CASES[kind]
    cache = tmp_path / "cache"
    study_file = tmp_path / "study.toml"
    study_file.write_text(text)
    data = tmp_path / name
    write(data, 0)
    stamp = data.stat()

    first = run_study(Study.load(study_file), workers=1, progress=False, cache_dir=cache)
    assert not first.from_cache
    again = run_study(Study.load(study_file), workers=1, progress=False, cache_dir=cache)
    assert again.from_cache, f"{kind}: an unchanged file must be read from the cache"
    np.testing.assert_array_equal(_numbers(again), _numbers(first))

    write(data, 1)  # same path, other content, modification time put back
    os.utime(data, ns=(stamp.st_atime_ns, stamp.st_mtime_ns))
    assert data.stat().st_mtime_ns == stamp.st_mtime_ns
    changed = run_study(Study.load(study_file), workers=1, progress=False, cache_dir=cache)
    assert not changed.from_cache, f"{kind}: a changed file was answered from the cache"
    assert changed.cache_file != first.cache_file
    a, b = _numbers(first), _numbers(changed)
    assert a.shape == b.shape
    assert not np.allclose(a, b, rtol=1e-3, equal_nan=True), f"{kind}: same numbers"


def test_inputs_are_recorded_relative_to_the_study(tmp_path: Path) -> None:
    """Every file read to build the study is in ``Study.inputs`` (relative, with digest)."""
    name, text, write = CASES["per-corner parameter file (TOML)"]
    write(tmp_path / name, 0)
    (tmp_path / "study.toml").write_text(text)
    study = Study.load(tmp_path / "study.toml")
    assert [p for p, _ in study.inputs] == ["rear.toml"]
    assert len(study.inputs[0][1]) == 64
