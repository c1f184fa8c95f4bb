"""Output folders and files: checked before the work, written whole or not at all.

The policy lives in :mod:`mrsuspension._output`; ``study``, ``sweep`` and ``optimize``
use it. Tests may run as root, where ``chmod`` does not stop writes: a path under a
regular file stands for "cannot be written".
"""

from __future__ import annotations

import json
from collections.abc import Callable
from contextlib import AbstractContextManager
from pathlib import Path
from typing import Any

import pytest
from typer.testing import CliRunner

from mrsuspension._output import MARKER, prepare_output, prepare_output_file
from mrsuspension.cli import app
from mrsuspension.errors import ValidationError

ROOT = Path(__file__).resolve().parents[2]
SCENARIO = str(ROOT / "examples" / "scenarios" / "passive-harmonic.toml")
STUDY = """
[excitation]
kind = "harmonic"
frequency = 5.0
amplitude = 0.01

[grid]
"controller.current" = [0.0, 0.2]
"""
PROBLEM = """
[problem]
name = "tiny"
seed = 2
population = 5
max_evaluations = 5

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
weights = { rms_stroke = 1.0 }
"""


class _Computed(Exception):
    """Raised by the stubbed computation: reaching it means the check came too late."""


def _no_computing(*_: Any, **__: Any) -> Any:
    raise _Computed


def _interrupted(
    output: AbstractContextManager[Path | None],
    write: Callable[[Path], object],
    error: BaseException,
) -> None:
    """Write part of an output, then fail (or be interrupted) inside the block."""
    with output as target:
        assert target is not None
        write(target)
        raise error


def _command(name: str, tmp_path: Path, out: Path) -> list[str]:
    if name == "study":
        study = tmp_path / "study.toml"
        study.write_text(STUDY)
        return ["study", str(study), "--no-cache", "--out", str(out)]
    if name == "optimize":
        problem = tmp_path / "problem.toml"
        problem.write_text(PROBLEM)
        return ["optimize", str(problem), "--workers", "1", "--out", str(out)]
    return ["sweep", SCENARIO, "-f", "5", "-j", "1", "--out", str(out)]


@pytest.fixture
def stubbed(monkeypatch: pytest.MonkeyPatch) -> None:
    """The computations of study, sweep and optimize fail loudly if they start."""
    import mrsuspension.engine.simulate as engine
    import mrsuspension.optimize as optimize
    import mrsuspension.studies as studies

    monkeypatch.setattr(studies, "run_study", _no_computing)
    monkeypatch.setattr(engine, "run_many", _no_computing)
    monkeypatch.setattr(optimize, "optimize", _no_computing)


@pytest.mark.usefixtures("stubbed")
@pytest.mark.parametrize("command", ["study", "sweep", "optimize"])
@pytest.mark.parametrize(
    ("where", "message"),
    [
        ("file", "is a file, not a folder"),
        ("under-file", "cannot be created: '{tmp}/blocker' is a file, not a folder"),
        (
            "foreign",
            "holds '{tmp}/mine/notes.txt', not written by mrsus or changed since; mrsus never "
            "deletes files it did not write, even with --force: move them out",
        ),
    ],
)
def test_a_bad_out_is_one_line_before_any_computing(
    tmp_path: Path, command: str, where: str, message: str
) -> None:
    blocker = tmp_path / "blocker"
    blocker.write_text("a regular file")
    name = "r.nc" if command == "study" else "out"
    out = {
        "file": blocker,
        "under-file": blocker / name,
        "foreign": tmp_path / "mine" / ("mine.nc" if command == "study" else ""),
    }[where]
    if where == "foreign":
        (tmp_path / "mine").mkdir()
        (tmp_path / "mine" / "notes.txt").write_text("the user's own file")
        if command == "study":  # a file output replaces its file, it has no folder to own
            out = tmp_path / "mine"
            message = "is a folder; give a file name ending with .nc or .csv"
    elif where == "file" and command == "study":
        message = "must end with .nc or .csv; got 'no suffix'"
    res = CliRunner().invoke(app, _command(command, tmp_path, out))
    assert res.exit_code == 2, (res.stderr, res.exception)
    lines = res.stderr.splitlines()
    assert len(lines) == 1
    assert lines[0].startswith(f"error: --out '{out}'")
    assert message.format(tmp=tmp_path) in lines[0]
    assert sorted(p.name for p in tmp_path.iterdir() if p.name.startswith(".")) == []


@pytest.mark.usefixtures("stubbed")
def test_an_unusable_cache_folder_is_refused_before_computing(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    import mrsuspension.studies as studies
    from mrsuspension.studies.run import run_study

    monkeypatch.setattr(studies, "run_study", run_study)  # the real one, with its check
    monkeypatch.setattr("mrsuspension.studies.run._run_local", _no_computing)
    blocker = tmp_path / "blocker"
    blocker.write_text("x")
    monkeypatch.setenv("MRSUSPENSION_CACHE", str(blocker))
    study = tmp_path / "study.toml"
    study.write_text(STUDY)
    res = CliRunner().invoke(app, ["study", str(study)])
    assert res.exit_code == 2, (res.stderr, res.exception)
    assert res.stderr.splitlines() == [
        f"error: the study cache folder '{blocker}/studies' cannot be created: '{blocker}' is "
        "a file, not a folder; set MRSUSPENSION_CACHE or use --no-cache"
    ]


def test_another_commands_folder_needs_force(tmp_path: Path) -> None:
    out = tmp_path / "out"
    runner = CliRunner()
    sweep = runner.invoke(app, _command("sweep", tmp_path, out))
    assert sweep.exit_code == 0, sweep.stderr
    assert json.loads((out / MARKER).read_text())["command"] == "sweep"
    assert sorted(p.name for p in out.iterdir()) == [MARKER, "sweep.csv", "sweep.png"]

    refused = runner.invoke(app, _command("optimize", tmp_path, out))
    assert refused.exit_code == 2
    assert refused.stderr == (
        f"error: --out '{out}' holds the output of 'mrsus sweep'; give another folder or "
        "--force to replace it\n"
    )
    forced = runner.invoke(app, [*_command("optimize", tmp_path, out), "--force"])
    assert forced.exit_code == 0, forced.stderr
    # replaced, not mixed: no sweep.csv beside the optimisation's files
    assert sorted(p.name for p in out.iterdir()) == [
        MARKER,
        "convergence.png",
        "optimization.json",
    ]
    assert f"wrote {out / 'optimization.json'}" in forced.stdout
    assert sorted(p.name for p in tmp_path.iterdir()) == ["out", "problem.toml"]


def test_the_same_command_replaces_its_folder(tmp_path: Path) -> None:
    out = tmp_path / "out"
    with prepare_output(out, "sweep") as tmp:
        assert tmp is not None
        (tmp / "old.csv").write_text("1\n")
    with prepare_output(out, "sweep") as tmp:
        assert tmp is not None
        (tmp / "new.csv").write_text("2\n")
    assert sorted(p.name for p in out.iterdir()) == [MARKER, "new.csv"]
    assert [p.name for p in tmp_path.iterdir()] == ["out"]  # no temporary siblings left


def test_an_interrupted_run_leaves_nothing(tmp_path: Path) -> None:
    out = tmp_path / "new" / "deeper" / "out"
    with pytest.raises(KeyboardInterrupt):
        _interrupted(
            prepare_output(out, "sweep"),
            lambda tmp: (tmp / "half.csv").write_text("frequency\n1.0,"),
            KeyboardInterrupt(),
        )
    assert list(tmp_path.iterdir()) == []  # nor the parents created for it

    kept = tmp_path / "kept"
    with prepare_output(kept, "sweep") as tmp:
        assert tmp is not None
        (tmp / "sweep.csv").write_text("good\n")
    with pytest.raises(RuntimeError):
        _interrupted(
            prepare_output(kept, "sweep"),
            lambda tmp: (tmp / "sweep.csv").write_text("half"),
            RuntimeError("the run failed"),
        )
    assert (kept / "sweep.csv").read_text() == "good\n"  # the previous result is intact
    assert [p.name for p in tmp_path.iterdir()] == ["kept"]


def test_an_interrupted_file_output_leaves_nothing(tmp_path: Path) -> None:
    out = tmp_path / "sub" / "study.csv"
    with pytest.raises(RuntimeError):
        _interrupted(
            prepare_output_file(out, suffixes=(".csv",)),
            lambda tmp: tmp.write_text("half"),
            RuntimeError(),
        )
    assert list(tmp_path.iterdir()) == []
    with prepare_output_file(out, suffixes=(".csv",)) as tmp:
        assert tmp is not None
        tmp.write_text("a\n")
        tmp.with_suffix(".json").write_text("{}")  # a sidecar moves along
    assert sorted(p.name for p in out.parent.iterdir()) == [
        ".study.csv.mrsus-output.json",  # what mrsus wrote there, so that a rerun replaces it
        "study.csv",
        "study.json",
    ]


def test_force_never_replaces_the_current_or_home_folder(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    work = tmp_path / "work"
    work.mkdir()
    (work / "project.toml").write_text("precious")
    monkeypatch.chdir(work)
    for path in (Path("."), tmp_path):
        with (
            pytest.raises(ValidationError, match="even with --force"),
            prepare_output(path, "sweep", force=True),
        ):
            pass
    assert (work / "project.toml").read_text() == "precious"


def test_a_linked_folder_is_written_through_the_link(tmp_path: Path) -> None:
    target = tmp_path / "target"
    target.mkdir()
    link = tmp_path / "link"
    link.symlink_to(target)
    with prepare_output(link, "sweep") as tmp:
        assert tmp is not None
        (tmp / "sweep.csv").write_text("1\n")
    assert link.is_symlink()
    assert sorted(p.name for p in target.iterdir()) == [MARKER, "sweep.csv"]
