"""Stale numba caches of modules that inline other modules' kernels are removed."""

from __future__ import annotations

from pathlib import Path

from mrsuspension._numba_cache import invalidate_if_changed


def test_cache_removed_only_when_a_dependency_changes(tmp_path: Path) -> None:
    module = tmp_path / "kernel.py"
    dep = tmp_path / "dep.py"
    module.write_text("x = 1\n")
    dep.write_text("y = 1\n")
    cache = tmp_path / "__pycache__"
    cache.mkdir()

    def fake_cache() -> list[Path]:
        files = [cache / "kernel.run-1.py311.nbi", cache / "kernel.run-1.py311.1.nbc"]
        for f in files:
            f.write_text("compiled")
        return files

    files = fake_cache()
    invalidate_if_changed(str(module), str(dep))  # first sight: no stamp, cache dropped
    assert not any(f.exists() for f in files)
    files = fake_cache()
    invalidate_if_changed(str(module), str(dep))  # unchanged: kept
    assert all(f.exists() for f in files)
    dep.write_text("y = 2\n")
    invalidate_if_changed(str(module), str(dep))  # changed: dropped
    assert not any(f.exists() for f in files)
    other = cache / "other.run-1.py311.nbi"
    other.write_text("compiled")
    invalidate_if_changed(str(module), str(dep))
    assert other.exists()  # other modules' caches are left alone
