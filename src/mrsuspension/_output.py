"""Where commands write their results: checked before the work, committed whole.

One policy for every output folder (``mrsus sweep --out``, ``optimize --out``) and output
file (``mrsus study --out``):

* the path is checked **before any computing**: a file in the way, a parent that is a
  file, a folder that cannot be written are a :class:`~mrsuspension.errors.ValidationError`
  naming the option and the path;
* results are written into a temporary hidden sibling (same file system) and moved into
  place only when the command succeeds, so a failed or interrupted run leaves the previous
  folder untouched and no temporary folder behind; a temporary folder left by a killed run
  (SIGKILL, power loss) is removed by the next run writing there;
* two runs writing one output never interleave: the first holds a lock (a hidden
  ``.NAME.lock`` beside the output, :func:`fcntl.flock`, released by the system when the
  process dies, removed when the run ends) and the second refuses at once with one line;
* a folder carries a marker (:data:`MARKER`, the command's name): a folder holding
  another command's output, or files not written by ``mrsus``, is refused unless
  ``force`` (which replaces it); the same command's folder is replaced.

The cache folder of the studies is checked with :func:`check_writable_folder`.
"""

from __future__ import annotations

import errno
import json
import os
import re
import shutil
import tempfile
from collections.abc import Iterable, Iterator, Sequence
from contextlib import contextmanager
from pathlib import Path
from typing import Any

from mrsuspension.errors import ValidationError

__all__ = [
    "MARKER",
    "carry_over",
    "check_output_folder",
    "check_writable_folder",
    "keep_recovered",
    "marked_command",
    "prepare_output",
    "prepare_output_file",
    "relocate_files",
    "relocated",
]

#: the file naming the command that wrote a folder
MARKER = ".mrsus-output.json"

#: outputs whose block raised or was interrupted, left as they were (for the message of
#: an interrupted command, :func:`mrsuspension.cli.errors.interrupts`)
discarded: list[Path] = []


def _first_existing(path: Path) -> Path:
    """``path`` or its nearest existing ancestor."""
    for candidate in (path, *path.parents):
        if candidate.exists() or candidate.is_symlink():
            return candidate
    return Path(path.anchor or ".")  # pragma: no cover - the root always exists


def check_output_folder(
    what: str, path: str | Path, command: str | None = None, *, force: bool = False
) -> Path:
    """``path`` as a :class:`~pathlib.Path` that is, or can be created as, a writable
    folder (:func:`check_writable_folder`), checked before a long run writes into it.

    With ``command``, also the checks :func:`prepare_output` makes on entering (a folder
    holding another command's output or foreign files is refused unless ``force``), for
    a command that computes before it enters :func:`prepare_output`.

    Examples
    --------
    >>> check_output_folder("--out", "results/new")
    PosixPath('results/new')
    >>> check_output_folder("--out", "results/new", "sweep")
    PosixPath('results/new')
    """
    path = Path(path)
    check_writable_folder(path, what)
    if command is not None:
        _check_folder(path, command, force, what)
    return path


def check_writable_folder(
    folder: str | Path, what: str, *, hint: str = "", shown: str | Path | None = None
) -> None:
    """Raise unless ``folder`` is, or can be created as, a folder this process can write.

    Nothing is created. ``what`` names the folder in the message (an option such as
    ``"--out"``, or ``"the study cache folder"``); ``hint`` is appended to it.

    Parameters
    ----------
    folder : path
        The folder to check.
    what : str
        What the folder is, for the message.
    hint : str, optional
        How to fix it, appended to the message.
    shown : path, optional
        The path the user gave, named in the message (default: ``folder``); e.g. the
        output file whose folder this is.

    Raises
    ------
    ValidationError
        ``folder`` is a file, a parent of it is a file, or the nearest existing folder is
        not writable.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> with tempfile.TemporaryDirectory() as d:
    ...     _ = (pathlib.Path(d) / "f").write_text("x")
    ...     check_writable_folder(pathlib.Path(d) / "new" / "folder", "--out")
    ...     try:
    ...         check_writable_folder(pathlib.Path(d) / "f" / "sub", "--out")
    ...     except ValidationError as exc:
    ...         print(str(exc).endswith("is a file, not a folder"))
    True
    """
    folder = Path(folder)
    name = str(folder if shown is None else shown)
    tail = f"; {hint}" if hint else ""
    existing = _first_existing(folder)
    if not existing.is_dir():
        if existing == folder and shown is None:
            raise ValidationError(f"{what} {name!r} is a file, not a folder{tail}")
        raise ValidationError(
            f"{what} {name!r} cannot be created: {str(existing)!r} is a file, not a folder{tail}"
        )
    if not os.access(existing, os.W_OK | os.X_OK):
        raise ValidationError(
            f"{what} {name!r} cannot be written: {str(existing)!r} is read-only{tail}"
        )


def _refuse_dangerous(path: Path, option: str) -> None:
    """``--force`` never replaces the root, the home folder or a folder holding the cwd."""
    resolved = path.resolve()
    cwd = Path.cwd().resolve()
    if resolved == cwd or resolved in cwd.parents or resolved == Path.home().resolve():
        raise ValidationError(
            f"{option} {str(path)!r} is the current folder, a parent of it or the home "
            "folder: refusing to replace it even with --force; give a new folder"
        )


def marked_command(folder: str | Path) -> str | None:
    """The command named by an output folder's :data:`MARKER` (None: no marker, unreadable).

    Examples
    --------
    >>> import tempfile, pathlib
    >>> with tempfile.TemporaryDirectory() as d:
    ...     print(marked_command(d))
    None
    """
    folder = Path(folder)
    try:
        data = json.loads((folder / MARKER).read_text())
    except (OSError, ValueError):
        return _unmarked_report(folder)
    command = data.get("command") if isinstance(data, dict) else None
    return command if isinstance(command, str) else None


def _unmarked_report(folder: Path) -> str | None:
    """``"reproduce"`` for a report written before folders carried the marker (an
    ``index.html`` beside a ``manifest.json`` listing chapters), so that ``make report``
    replaces, and ``--chapters`` updates, a report of an older version."""
    try:
        manifest = json.loads((folder / "manifest.json").read_text())
    except (OSError, ValueError):
        return None
    report = isinstance(manifest, dict) and "chapters" in manifest
    return "reproduce" if report and (folder / "index.html").is_file() else None


def _check_folder(path: Path, command: str, force: bool, option: str) -> None:
    if path.exists() and not path.is_dir():
        raise ValidationError(f"{option} {str(path)!r} is a file, not a folder; give a folder")
    if path.is_dir() and any(path.iterdir()):
        owner = marked_command(path)
        if owner != command and not force:
            held = (
                f"holds the output of 'mrsus {owner}'"
                if owner
                else "is not empty and was not written by mrsus"
            )
            raise ValidationError(
                f"{option} {str(path)!r} {held}; give another folder or --force to replace it"
            )
        if owner != command:
            _refuse_dangerous(path, option)
    check_writable_folder(path.parent, option, shown=path)


def _make_parents(folder: Path, option: str, shown: Path) -> list[Path]:
    """Create ``folder`` and its missing parents; the created ones, deepest first."""
    created = [p for p in (folder, *folder.parents) if not p.exists()]
    try:
        folder.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise ValidationError(f"{option} {str(shown)!r} cannot be created: {exc}") from None
    return created


def _remove_empty(folders: Sequence[Path]) -> None:
    for folder in folders:
        try:
            folder.rmdir()
        except OSError:
            break


def _stale_siblings(path: Path) -> list[Path]:
    """Temporary siblings of ``path`` (``.NAME.*.tmp`` / ``.old``) left by a killed run."""
    pattern = re.compile(rf"\.{re.escape(path.name)}\.[a-z0-9_]{{8}}\.(tmp|old)")
    return [
        p
        for p in path.parent.iterdir()
        if pattern.fullmatch(p.name) and p.is_dir() and not p.is_symlink()
    ]


@contextmanager
def _locked(path: Path, option: str) -> Iterator[None]:
    """Hold the write lock of ``path`` (``.NAME.lock`` beside it) for the block.

    A second process refuses at once. Under the lock, temporary siblings left by a killed
    run are removed (only the lock holder creates them). The lock file is removed while
    still locked; a process that opened the old file re-opens the new one (inode check).
    Without :mod:`fcntl` (Windows) the block runs unlocked.
    """
    try:
        import fcntl
    except ImportError:  # pragma: no cover - Windows: no advisory locks, last move wins
        yield
        return
    lock = path.parent / f".{path.name}.lock"
    while True:
        try:
            fd = os.open(lock, os.O_RDWR | os.O_CREAT, 0o644)
        except OSError as exc:
            raise ValidationError(f"{option} {str(path)!r} cannot be written: {exc}") from None
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError:
            os.close(fd)
            raise ValidationError(
                f"{option} {str(path)!r} is being written by another mrsus run; wait for it "
                f"to finish or give another {option}"
            ) from None
        try:
            same = os.fstat(fd).st_ino == os.stat(lock).st_ino
        except OSError:
            same = False
        if same:
            break
        os.close(fd)  # locked a file its holder had just removed: take the new one
    try:
        for stale in _stale_siblings(path):
            shutil.rmtree(stale, ignore_errors=True)
        yield
    finally:
        try:
            os.unlink(lock)
        finally:
            os.close(fd)


def carry_over(old: str | Path, new: str | Path, *, skip: Iterable[str] = ()) -> list[str]:
    """Copy the entries of folder ``old`` into ``new``, except the names in ``skip``.

    For a command that updates part of its previous output (``mrsus reproduce
    --chapters``): the previous folder stays untouched until the new one replaces it.
    Files are copied, not hard-linked: a writer that truncates a file in place (as
    ``savefig`` does) must never reach the previous folder. The marker is never carried
    over.

    Returns
    -------
    list of str
        The names carried over, sorted.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> with tempfile.TemporaryDirectory() as d:
    ...     old, new = pathlib.Path(d, "old"), pathlib.Path(d, "new")
    ...     (old / "chapter2").mkdir(parents=True)
    ...     _ = (old / "chapter2" / "fig.png").write_text("png")
    ...     _ = (old / "index.html").write_text("<html>")
    ...     new.mkdir()
    ...     carry_over(old, new, skip={"index.html"})
    ['chapter2']
    """
    old, new = Path(old), Path(new)
    names = sorted(p.name for p in old.iterdir() if p.name not in {*skip, MARKER})
    for name in names:
        src = old / name
        if src.is_dir() and not src.is_symlink():
            shutil.copytree(src, new / name, symlinks=True)
        else:
            shutil.copy2(src, new / name, follow_symlinks=False)
    return names


def relocated(value: Any, tmp: str | Path, path: str | Path) -> Any:
    """``value`` with every string naming ``tmp`` (or a file in it) naming ``path`` instead.

    For what a command prints or records about files it wrote into the temporary folder
    of :func:`prepare_output`: the paths the user sees name the final folder. Walks
    dicts, lists and tuples; other values are returned as they are.

    Examples
    --------
    >>> relocated({"out": "r/.x.ab12cd34.tmp/rec", "n": 3}, "r/.x.ab12cd34.tmp", "r/x")
    {'out': 'r/x/rec', 'n': 3}
    """
    old, new = str(tmp), str(path)
    if isinstance(value, str):
        if value == old or value.startswith(old + os.sep):
            return new + value[len(old) :]
        return value
    if isinstance(value, dict):
        return {k: relocated(v, old, new) for k, v in value.items()}
    if isinstance(value, list | tuple):
        return type(value)(relocated(v, old, new) for v in value)
    return value


def relocate_files(tmp: str | Path, path: str | Path, pattern: str = "**/*.json") -> None:
    """Rewrite the paths naming ``tmp`` inside the JSON files written into it (before the
    move), so that they name ``path``, where the files end up.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> with tempfile.TemporaryDirectory() as d:
    ...     tmp = pathlib.Path(d, ".out.ab12cd34.tmp")
    ...     tmp.mkdir()
    ...     _ = (tmp / "meta.json").write_text(json.dumps({"out": str(tmp / "rec")}))
    ...     relocate_files(tmp, pathlib.Path(d, "out"))
    ...     json.loads((tmp / "meta.json").read_text())["out"] == str(pathlib.Path(d, "out", "rec"))
    True
    """
    old, new = json.dumps(str(tmp))[1:-1], json.dumps(str(path))[1:-1]
    for file in Path(tmp).glob(pattern):
        if file.is_file() and not file.is_symlink():
            text = file.read_text(encoding="utf-8", errors="surrogateescape")
            if old in text:  # a new file moved over the old: never edit a shared inode
                fresh = file.with_name(file.name + ".relocating")
                fresh.write_text(text.replace(old, new), encoding="utf-8", errors="surrogateescape")
                os.replace(fresh, file)


def _temporary_sibling(path: Path, option: str) -> Path:
    """A new hidden folder beside ``path``, with the permissions of a plain ``mkdir``
    (``mkdtemp`` makes it private, 0700, which the moved output would keep)."""
    try:
        tmp = Path(tempfile.mkdtemp(prefix=f".{path.name}.", suffix=".tmp", dir=path.parent))
        mask = os.umask(0o022)
        os.umask(mask)
        tmp.chmod(0o777 & ~mask)
        return tmp
    except OSError as exc:
        raise ValidationError(f"{option} {str(path)!r} cannot be written: {exc}") from None


def _commit_folder(tmp: Path, path: Path) -> None:
    """Move ``tmp`` to ``path``, replacing what was there (moved aside first)."""
    try:
        os.replace(tmp, path)  # path missing or an empty folder
        return
    except OSError:
        if not path.exists():
            raise
    old = Path(tempfile.mkdtemp(prefix=f".{path.name}.", suffix=".old", dir=path.parent))
    os.replace(path, old / path.name)
    os.replace(tmp, path)
    shutil.rmtree(old, ignore_errors=True)


@contextmanager
def prepare_output(
    path: str | Path | None, command: str, *, force: bool = False, option: str = "--out"
) -> Iterator[Path | None]:
    """Check an output folder, yield a temporary folder, and move it into place on success.

    Enter it **before** the work: the checks (see the module docstring) run on entering.
    Write every output into the yielded folder; when the block ends normally it gets the
    :data:`MARKER` and replaces ``path``; when it raises (or is interrupted) the temporary
    folder and any parent created for it are removed and ``path`` is untouched.

    Parameters
    ----------
    path : path or None
        The output folder (None: no output; yields None and does nothing).
    command : str
        The command writing it (``"sweep"``), recorded in the marker.
    force : bool
        Replace a folder holding another command's output or files not written by mrsus.
    option : str
        The option's name, for messages.

    Yields
    ------
    Path or None
        The temporary folder to write into.

    Raises
    ------
    ValidationError
        The path is a file, cannot be written, or holds something else and not ``force``.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> with tempfile.TemporaryDirectory() as d:
    ...     out = pathlib.Path(d) / "results"
    ...     with prepare_output(out, "sweep") as tmp:
    ...         _ = (tmp / "sweep.csv").write_text("frequency\\n1.0\\n")
    ...     sorted(p.name for p in out.iterdir())
    ['.mrsus-output.json', 'sweep.csv']
    """
    if path is None:
        yield None
        return
    path = Path(path)
    if path.is_symlink() and path.is_dir():  # write where the link points, keep the link
        path = path.resolve()
    _check_folder(path, command, force, option)
    created = _make_parents(path.parent, option, path)
    try:
        with _locked(path, option):
            _check_folder(path, command, force, option)  # again: another run may have ended
            tmp = _temporary_sibling(path, option)
            try:
                yield tmp
                from mrsuspension import __version__

                marker = {"command": command, "version": __version__}
                (tmp / MARKER).write_text(json.dumps(marker) + "\n")
                _commit_folder(tmp, path)
            except BaseException:
                shutil.rmtree(tmp, ignore_errors=True)
                raise
    except BaseException:
        _remove_empty(created)
        discarded.append(path)
        raise


@contextmanager
def prepare_output_file(
    path: str | Path | None, *, suffixes: Sequence[str], option: str = "--out"
) -> Iterator[Path | None]:
    """Check an output file, yield a temporary path, and move it into place on success.

    Like :func:`prepare_output` for a single file (and sidecars written beside it, such
    as ``result.json`` next to ``result.csv``): every file written into the temporary
    path's folder replaces its namesake beside ``path`` when the block ends normally.

    Parameters
    ----------
    path : path or None
        The output file (None: no output; yields None).
    suffixes : sequence of str
        The valid suffixes (``(".nc", ".csv")``), checked first.
    option : str
        The option's name, for messages.

    Yields
    ------
    Path or None
        Where to write the file (same name, in a temporary hidden folder).

    Raises
    ------
    ValidationError
        A wrong suffix, a folder in the way, or a folder that cannot be written.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> with tempfile.TemporaryDirectory() as d:
    ...     out = pathlib.Path(d) / "study.csv"
    ...     with prepare_output_file(out, suffixes=(".nc", ".csv")) as tmp:
    ...         _ = tmp.write_text("a\\n1\\n")
    ...     out.read_text()
    'a\\n1\\n'
    """
    if path is None:
        yield None
        return
    path = Path(path)
    if path.is_dir():
        raise ValidationError(
            f"{option} {str(path)!r} is a folder; give a file name ending with "
            f"{' or '.join(suffixes)}"
        )
    if path.suffix.lower() not in suffixes:
        raise ValidationError(
            f"{option} {str(path)!r} must end with {' or '.join(suffixes)}; got "
            f"{path.suffix or 'no suffix'!r}"
        )
    check_writable_folder(path.parent, option, shown=path)
    created = _make_parents(path.parent, option, path)
    try:
        with _locked(path, option):
            tmp = _temporary_sibling(path, option)
            try:
                yield tmp / path.name
                for written in sorted(tmp.iterdir()):
                    os.replace(written, path.parent / written.name)
                tmp.rmdir()
            except BaseException:
                shutil.rmtree(tmp, ignore_errors=True)
                raise
    except BaseException:
        _remove_empty(created)
        discarded.append(path)
        raise


def keep_recovered(staged: str | Path, path: str | Path) -> Path:
    """Keep a staged output that could not be committed as a visible ``NAME.recovered``.

    For ``hil run``'s recording when the run ended in a way its command could not commit
    (a full disk, the command killed while its loop process finished the safe stop): the
    temporary folder of :func:`prepare_output` would be removed as a stale sibling by the
    next run; moved beside ``path`` as ``NAME.recovered`` (``NAME.recovered.2``, ... when
    taken) it is the user's, and no later run removes it. The move stays on the file
    system (a rename: it needs no free space).

    Returns
    -------
    Path
        Where the folder is now.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> with tempfile.TemporaryDirectory() as d:
    ...     staged = pathlib.Path(d, ".rec.ab12cd34.tmp")
    ...     staged.mkdir()
    ...     keep_recovered(staged, pathlib.Path(d, "rec")).name
    'rec.recovered'
    """
    staged, path = Path(staged), Path(path)
    for n in range(1, 1000):
        dest = path.with_name(f"{path.name}.recovered" + (f".{n}" if n > 1 else ""))
        if dest.exists() or dest.is_symlink():
            continue
        try:
            os.rename(staged, dest)  # never over an existing folder
        except FileExistsError:
            continue
        except OSError as exc:
            if exc.errno in (errno.EEXIST, errno.ENOTEMPTY):
                continue
            raise
        return dest
    raise OSError(f"no free name for {path.name}.recovered beside {str(path.parent)!r}")
