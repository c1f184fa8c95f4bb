"""A pip user has the README's examples: the wheel ships them, ``mrsus examples`` copies them.

Issue 31: ``examples/`` was not in the wheel, so ``mrsus simulate examples/...`` failed
after ``pip install``. The wheel is built here (``pip wheel``, as a user's install
builds it) and its package run straight from the unpacked files.
"""

from __future__ import annotations

import os
import subprocess
import sys
import zipfile
from pathlib import Path

import pytest

from _helpers import raises_validation
from mrsuspension.examples import PACKAGED, SUFFIXES, copy_examples, list_examples

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="module")
def unpacked_wheel(tmp_path_factory: pytest.TempPathFactory) -> Path:
    out = tmp_path_factory.mktemp("wheel")
    subprocess.run(
        [sys.executable, "-m", "pip", "wheel", "--no-deps", "-q", "-w", str(out), str(ROOT)],
        check=True, capture_output=True, timeout=300,
    )  # fmt: skip
    (wheel,) = out.glob("mrsuspension-*.whl")
    site = out / "site"
    with zipfile.ZipFile(wheel) as z:
        z.extractall(site)
    return site


def test_the_wheel_ships_every_example(unpacked_wheel: Path) -> None:
    packaged = unpacked_wheel / "mrsuspension" / PACKAGED
    shipped = sorted(
        p.relative_to(packaged).as_posix()
        for p in packaged.rglob("*")
        if p.is_file() and p.suffix in SUFFIXES and "__pycache__" not in p.parts
    )
    assert [name for name, _ in list_examples()] == shipped  # the checkout's, every one


def test_mrsus_examples_copy_from_the_wheel_gives_the_readme_paths(
    unpacked_wheel: Path, tmp_path: Path
) -> None:
    env = {**os.environ, "PYTHONPATH": str(unpacked_wheel)}
    run = subprocess.run(
        [sys.executable, "-m", "mrsuspension", "examples", "copy", "scenarios", "vehicles"],
        cwd=tmp_path, env=env, capture_output=True, text=True, timeout=120, check=False,
    )  # fmt: skip
    assert run.returncode == 0, run.stderr
    assert (tmp_path / "examples" / "scenarios" / "passive-harmonic.toml").is_file()
    assert (tmp_path / "examples" / "vehicles" / "half_car.toml").is_file()
    listed = subprocess.run(
        [sys.executable, "-m", "mrsuspension", "examples", "list"],
        cwd=tmp_path, env=env, capture_output=True, text=True, timeout=120, check=False,
    )  # fmt: skip
    assert f"mrsuspension/{PACKAGED}" in listed.stdout.splitlines()[0]
    assert "scenarios/passive-harmonic.toml" in listed.stdout


def test_copy_never_replaces_a_file_and_names_what_is_valid(tmp_path: Path) -> None:
    first = copy_examples(["scenarios/passive-harmonic.toml"], tmp_path)
    first[0].write_text("# mine\n")
    raises_validation(
        lambda: copy_examples(["scenarios"], tmp_path),
        "passive-harmonic.toml' exists already",
        "nothing was copied",
    )
    assert first[0].read_text() == "# mine\n"
    assert not (tmp_path / "scenarios" / "linear-swept.toml").exists()  # none of the folder
    raises_validation(
        lambda: copy_examples(["scenarioz"], tmp_path), "Did you mean 'scenarios'?", "all"
    )
