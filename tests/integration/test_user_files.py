"""Issue 26, section 3: a file a user wrote is never deleted.

Each data-loss case of the issue, run the way a user meets it: the user's files survive,
or the command refuses with one line naming them. The policy lives in
:mod:`mrsuspension._output` (the marker lists every file a command wrote, with its
digest); the pool part in :mod:`mrsuspension._pool` (workers close the ``--out`` lock and
die with their parent). Commands run in-process (typer's ``CliRunner``); a subprocess
only where a process boundary and a signal matter. The case ``monitor --workdir`` is the
monitor's (tests/integration/test_monitor.py).
"""

from __future__ import annotations

import contextlib
import hashlib
import json
import os
import shutil
import signal
import subprocess
import sys
import time
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import psutil
import pytest
from typer.testing import CliRunner

from mrsuspension._output import (
    MARKER,
    foreign_files,
    prepare_output,
    prepare_output_file,
    staging_in_use,
)
from mrsuspension.cli import app
from mrsuspension.errors import ValidationError

ROOT = Path(__file__).resolve().parents[2]
SCENARIO = ROOT / "examples" / "scenarios" / "passive-harmonic.toml"
STUDY = """
[excitation]
kind = "harmonic"
frequency = 5.0
amplitude = 0.01

[grid]
"controller.current" = [0.0, 0.2]
"""

pytestmark = pytest.mark.audit("user files")


class _Computed(Exception):
    """Raised by the stubbed computation: reaching it means the check came too late."""


def _no_computing(*_: Any, **__: Any) -> Any:
    raise _Computed


@pytest.fixture
def stubbed(monkeypatch: pytest.MonkeyPatch) -> None:
    """The computations of study, sweep and reproduce fail loudly if they start."""
    import mrsuspension.engine.simulate as engine
    import mrsuspension.report as report
    import mrsuspension.studies as studies

    monkeypatch.setattr(studies, "run_study", _no_computing)
    monkeypatch.setattr(engine, "run_many", _no_computing)
    monkeypatch.setattr(report, "build_report", _no_computing)


def _refused(args: list[str], *names: str) -> str:
    """Run ``mrsus ARGS``: exit 2, one ``error:`` line naming every one of ``names``."""
    res = CliRunner().invoke(app, [str(a) for a in args])
    assert res.exit_code == 2, (res.exit_code, res.stderr, res.exception)
    lines = res.stderr.splitlines()
    assert len(lines) == 1, res.stderr
    assert lines[0].startswith("error: "), lines[0]
    for name in names:
        assert name in lines[0], (name, lines[0])
    return lines[0]


def _sweep_output(out: Path) -> None:
    """An earlier ``mrsus sweep --out OUT`` (what the command writes, without the runs)."""
    with prepare_output(out, "sweep") as tmp:
        assert tmp is not None
        (tmp / "sweep.csv").write_text("frequency [Hz]\n1.0\n")
        (tmp / "plots").mkdir()
        (tmp / "plots" / "sweep.png").write_bytes(b"\x89PNG")


def _tree(folder: Path) -> dict[str, bytes]:
    return {
        str(p.relative_to(folder)): p.read_bytes()
        for p in sorted(folder.rglob("*"))
        if p.is_file() and not p.is_symlink()
    }


def _leftovers(folder: Path) -> list[str]:
    """Temporary or moved-aside folders of mrsus in ``folder``."""
    return sorted(p.name for p in folder.iterdir() if p.name.endswith((".tmp", ".old", ".lock")))


# -- re-running into a folder the command wrote before -----------------------------------
@pytest.mark.usefixtures("stubbed")
def test_a_rerun_never_deletes_what_the_user_added(tmp_path: Path) -> None:
    out = tmp_path / "out"
    _sweep_output(out)
    shutil.copy(SCENARIO, out / "scenario.toml")  # the input scenario, kept with its results
    (out / "notes").mkdir()
    (out / "notes" / "todo.txt").write_text("check 12 Hz")
    before = _tree(out)
    for extra in ([], ["--force"]):
        line = _refused(
            ["sweep", SCENARIO, "-f", "5", "-j", "1", "--out", out, *extra],
            f"'{out}/notes/'",
            f"'{out}/scenario.toml'",
            "never deletes files it did not write, even with --force",
        )
        assert "move them out or give another --out" in line
    assert _tree(out) == before

    shutil.rmtree(out / "notes")
    (out / "scenario.toml").unlink()
    (out / "sweep.csv").write_text("frequency [Hz]\n2.0\n")  # the user edited a result
    _refused(["sweep", SCENARIO, "-f", "5", "--out", out, "--force"], f"'{out}/sweep.csv'")
    assert (out / "sweep.csv").read_text() == "frequency [Hz]\n2.0\n"
    assert foreign_files(out) == ["sweep.csv"]


def test_only_listed_files_are_replaced_and_the_marker_lists_them(tmp_path: Path) -> None:
    out = tmp_path / "out"
    _sweep_output(out)
    marker = json.loads((out / MARKER).read_text())
    assert marker["command"] == "sweep"
    assert sorted(marker["files"]) == ["plots/sweep.png", "sweep.csv"]
    assert marker["files"]["sweep.csv"]["size"] == len("frequency [Hz]\n1.0\n")
    digest = hashlib.sha256(b"frequency [Hz]\n1.0\n").hexdigest()
    assert marker["files"]["sweep.csv"]["sha256"] == digest  # as sha256sum prints it
    assert marker["folders"] == ["plots"]
    (out / "plots" / "sweep.png").unlink()  # a user may delete mrsus's files
    with prepare_output(out, "sweep") as tmp:
        assert tmp is not None
        (tmp / "new.csv").write_text("2\n")
    assert sorted(_tree(out)) == [MARKER, "new.csv"]
    assert _leftovers(tmp_path) == []


def test_an_earlier_versions_folder_is_foreign_even_with_force(tmp_path: Path) -> None:
    out = tmp_path / "out"
    out.mkdir()
    (out / MARKER).write_text('{"command": "sweep", "version": "0.9.0"}\n')  # lists nothing
    (out / "sweep.csv").write_text("1\n")
    for force in (False, True):
        with (
            pytest.raises(ValidationError, match="earlier mrsus version that did not list"),
            prepare_output(out, "sweep", force=force),
        ):
            pass
    assert (out / "sweep.csv").read_text() == "1\n"


# -- the dangerous folders: on every path, not only with --force -----------------------------
def test_a_marker_copied_into_home_lets_nothing_replace_it(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    home = tmp_path / "home"
    _sweep_output(home)  # a marker listing exactly what is there: still the home folder
    monkeypatch.setenv("HOME", str(home))
    work = home / "projects" / "car"
    work.mkdir(parents=True)
    monkeypatch.chdir(work)
    before = _tree(home)
    cases = [(home, "the home folder"), (Path(".."), "a parent of the current folder")]
    cases += [(Path("/"), "the root folder"), (Path("/usr"), "a system folder")]
    for path, what in cases:
        for force in (False, True):
            line = _refused(
                ["sweep", SCENARIO, "-f", "5", "--out", path, *(["--force"] * force)],
                f"--out '{path}' is {what}: mrsus never writes its output there, even with --force",
            )
            assert line.endswith("give a new folder")
    assert _tree(home) == before


# -- nothing guessed from file names ---------------------------------------------------------
@pytest.mark.usefixtures("stubbed")
def test_a_static_site_is_not_taken_for_a_report(tmp_path: Path) -> None:
    site = tmp_path / "book"
    site.mkdir()
    (site / "index.html").write_text("<html>my e-book</html>")
    (site / "manifest.json").write_text('{"chapters": ["intro", "methods"]}')
    before = _tree(site)
    for extra in ([], ["--chapters", "2"], ["--force"]):
        _refused(["reproduce", "--quick", "--out", site, *extra], f"'{site}/index.html'")
    assert _tree(site) == before


# -- file outputs: study --out x.csv and its sidecar x.json ---------------------------------
@pytest.mark.usefixtures("stubbed")
@pytest.mark.parametrize("owned", ["results.csv", "results.json"])
def test_study_never_overwrites_the_users_csv_or_json(tmp_path: Path, owned: str) -> None:
    study = tmp_path / "study.toml"
    study.write_text(STUDY)
    out = tmp_path / "results.csv"
    (tmp_path / owned).write_text("the user's own table\n")
    _refused(
        ["study", study, "--no-cache", "--out", out],
        f"--out '{out}': '{tmp_path / owned}' not written by mrsus",
        "move it or give another --out",
    )
    assert (tmp_path / owned).read_text() == "the user's own table\n"
    assert sorted(p.name for p in tmp_path.iterdir()) == [owned, "study.toml"]


def test_study_replaces_its_own_csv_and_json_but_not_an_edited_one(tmp_path: Path) -> None:
    out = tmp_path / "results.csv"
    sidecars = {".csv": (".json",)}

    def write(text: str) -> None:
        with prepare_output_file(
            out, suffixes=(".csv",), sidecars=sidecars, command="study"
        ) as tmp:
            assert tmp is not None
            tmp.write_text(text)
            tmp.with_suffix(".json").write_text(json.dumps({"run": text}))

    write("a\n1\n")
    write("a\n2\n")  # mrsus wrote both: replaced
    assert out.read_text() == "a\n2\n"
    marker = json.loads((tmp_path / f".results.csv{MARKER}").read_text())
    assert sorted(marker["files"]) == ["results.csv", "results.json"]
    (tmp_path / "results.json").write_text('{"my": "notes"}')  # the user took the sidecar
    with pytest.raises(ValidationError, match=r"results\.json' not written by mrsus"):
        write("a\n3\n")
    assert (tmp_path / "results.json").read_text() == '{"my": "notes"}'
    assert out.read_text() == "a\n2\n"


# -- files added while the command runs, and a killed run's leftovers ------------------------
def test_files_added_during_the_run_survive_and_the_results_are_kept(tmp_path: Path) -> None:
    out = tmp_path / "out"
    _sweep_output(out)

    def run() -> None:
        with prepare_output(out, "sweep") as tmp:
            assert tmp is not None
            (tmp / "sweep.csv").write_text("new\n")
            (out / "draft.txt").write_text("written while the sweep ran")

    with pytest.raises(ValidationError, match="appeared or changed while mrsus ran") as err:
        run()
    assert f"the results are in '{tmp_path / 'out.new'}'" in str(err.value)
    assert (out / "draft.txt").read_text() == "written while the sweep ran"
    assert (out / "sweep.csv").read_text() == "frequency [Hz]\n1.0\n"  # left as it was
    assert (tmp_path / "out.new" / "sweep.csv").read_text() == "new\n"
    assert _leftovers(tmp_path) == []


def test_a_killed_runs_leftovers_lose_no_user_file(tmp_path: Path) -> None:
    out = tmp_path / "out"
    _sweep_output(out)
    aside = tmp_path / ".out.abcd1234.old"  # killed between moving aside and cleaning up
    aside.mkdir()
    out.rename(aside / "out")
    (aside / "out" / "late.txt").write_text("the user's")
    recovered = tmp_path / "out.recovered"  # a HiL recording kept for the user
    recovered.mkdir()
    (recovered / "recording.csv").write_text("t,x\n")
    with prepare_output(out, "sweep") as tmp:
        assert tmp is not None
        (tmp / "sweep.csv").write_text("new\n")
    assert (tmp_path / "out.kept" / "late.txt").read_text() == "the user's"
    assert not (tmp_path / "out.kept" / "sweep.csv").exists()  # mrsus's own files: removed
    assert (recovered / "recording.csv").read_text() == "t,x\n"
    assert _leftovers(tmp_path) == []


@pytest.mark.audit("user files")
def test_a_staging_folder_in_use_is_not_a_leftover(tmp_path: Path) -> None:
    """The loop process of a killed ``hil run`` still writes its staging folder (it stops the
    rig, then keeps the recording as ``NAME.recovered``): a run started meanwhile leaves the
    folder alone; once no process holds it, it is a killed run's leftover."""
    out = tmp_path / "rec"
    staged = tmp_path / ".rec.abcd1234.tmp"
    staged.mkdir()
    (staged / ".mrsus-staging").touch()
    (staged / "recording.bin").write_text("rows")
    with staging_in_use(staged):
        with prepare_output(out, "hil run") as tmp:
            assert tmp is not None
        assert (staged / "recording.bin").read_text() == "rows"
    assert not (staged / ".mrsus-busy").exists()
    with prepare_output(out, "hil run") as tmp:
        assert tmp is not None
    assert not staged.exists()


# -- folders that cannot be renamed: the current folder, a mount point -----------------------
def test_out_dot_writes_into_the_current_folder(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    work = tmp_path / "work"
    work.mkdir()
    monkeypatch.chdir(work)
    for _ in range(2):  # a new empty folder, then its own output: replaced in place
        res = CliRunner().invoke(app, ["sweep", str(SCENARIO), "-f", "5", "-j", "1", "--out", "."])
        assert res.exit_code == 0, (res.stderr, res.exception)
        assert sorted(p.name for p in work.iterdir()) == [MARKER, "sweep.csv", "sweep.png"]
        assert _leftovers(tmp_path) == []
    assert Path.cwd() == work.resolve()  # not renamed under the user
    assert work.is_dir()
    (work / "scenario.toml").write_text("mine")
    _refused(["sweep", SCENARIO, "-f", "5", "--out", "."], "holds 'scenario.toml'")
    assert (work / "scenario.toml").read_text() == "mine"


@pytest.fixture
def mount_point(tmp_path: Path) -> Iterator[Path]:
    """An empty tmpfs mounted at ``tmp_path/mnt`` (skipped where mount is not allowed)."""
    mnt = tmp_path / "mnt"
    mnt.mkdir()
    mount = shutil.which("mount")
    if mount is None:
        pytest.skip("no mount command")
    res = subprocess.run(
        [mount, "-t", "tmpfs", "-o", "size=8m", "tmpfs", str(mnt)], capture_output=True
    )
    if res.returncode != 0:
        pytest.skip(f"cannot mount a tmpfs here: {res.stderr.decode().strip()}")
    try:
        yield mnt
    finally:
        subprocess.run(["umount", "-l", str(mnt)], check=False)


def test_a_mount_point_is_written_in_place(
    tmp_path: Path, mount_point: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    assert os.path.ismount(mount_point)
    for text in ("1\n", "2\n"):
        _sweep_output(mount_point)
        with prepare_output(mount_point, "sweep") as tmp:
            assert tmp is not None
            (tmp / "sweep.csv").write_text(text)
        assert sorted(_tree(mount_point)) == [MARKER, "sweep.csv"]
        assert (mount_point / "sweep.csv").read_text() == text
        assert _leftovers(tmp_path) == []
        assert _leftovers(mount_point) == []
    assert os.path.ismount(mount_point)
    monkeypatch.setattr("mrsuspension._output._in_place", lambda _real: False)  # not seen
    with prepare_output(mount_point, "sweep") as tmp:  # staged beside, on another disk
        assert tmp is not None
        assert tmp.parent == tmp_path
        (tmp / "sweep.csv").write_text("3\n")
    assert sorted(_tree(mount_point)) == [MARKER, "sweep.csv"]  # the rename failed: in place
    assert (mount_point / "sweep.csv").read_text() == "3\n"
    assert _leftovers(tmp_path) == []
    assert os.path.ismount(mount_point)
    (mount_point / "mine.txt").write_text("mine")
    with pytest.raises(ValidationError, match=r"mine\.txt'"), prepare_output(mount_point, "sweep"):
        pass
    assert (mount_point / "mine.txt").read_text() == "mine"


# -- pool workers: no lock kept, no worker outliving its parent ------------------------------
_PARENT = """
import sys, time
from mrsuspension._output import prepare_output
from mrsuspension._pool import pool_map
with prepare_output(sys.argv[1], "sweep") as tmp:
    pool_map(time.sleep, [600.0, 600.0], workers=2)
"""


@pytest.mark.parametrize("signum", [signal.SIGKILL, signal.SIGHUP], ids=["kill-9", "hangup"])
def test_workers_die_with_their_parent_and_keep_no_lock(tmp_path: Path, signum: int) -> None:
    out = tmp_path / "out"
    parent = subprocess.Popen(
        [sys.executable, "-c", _PARENT, str(out)], start_new_session=True,
        stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
    )  # fmt: skip
    try:
        deadline = time.monotonic() + 60
        workers: list[psutil.Process] = []
        while len(workers) < 2:
            assert parent.poll() is None, "the parent ended early"
            assert time.monotonic() < deadline, "the workers did not start"
            time.sleep(0.02)
            workers = psutil.Process(parent.pid).children()
        lock = str(tmp_path / ".out.lock")
        assert lock in [f.path for f in psutil.Process(parent.pid).open_files()]
        # the lock is the parent's alone: each worker closes it as it starts (its
        # initializer runs just after the fork, so a worker seen at once may hold it still)
        deadline = time.monotonic() + 10
        while any(lock in [f.path for f in w.open_files()] for w in workers):
            assert time.monotonic() < deadline, "a worker kept the --out lock"
            time.sleep(0.02)
        os.kill(parent.pid, signum)  # the parent only, not its process group
        parent.wait(10)
        deadline = time.monotonic() + 5
        alive = workers
        while alive and time.monotonic() < deadline:
            time.sleep(0.02)
            alive = [w for w in alive if w.is_running() and w.status() != psutil.STATUS_ZOMBIE]
        assert alive == [], f"workers alive 5 s after the parent's death: {alive}"
    finally:
        with contextlib.suppress(ProcessLookupError):
            os.killpg(parent.pid, signal.SIGKILL)
        parent.wait()
    with prepare_output(out, "sweep") as tmp:  # a rerun: not refused as "being written"
        assert tmp is not None
        (tmp / "sweep.csv").write_text("1\n")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["out"]  # the killed run's temp: gone
