"""Where commands write their results: checked before the work, committed whole, and
nothing a user wrote ever deleted.

One policy for every output folder (``mrsus sweep --out``, ``optimize --out``) and output
file (``mrsus study --out``):

* the path is checked **before any computing**: a file in the way, a parent that is a
  file, a folder that cannot be written are a :class:`~mrsuspension.errors.ValidationError`
  naming the option and the path;
* **only what mrsus wrote is replaced**: an output folder carries a marker
  (:data:`MARKER`) naming the command and listing every file it wrote (relative path,
  size, SHA-256 digest), folder and link. A folder is replaced only when everything in it
  is listed and unchanged; a file or folder that is not listed, or was changed since, is
  refused with one line naming it, **even with** ``force``: mrsus never deletes what it
  did not write (move it out, or give another path). A folder of an earlier version,
  whose marker lists nothing, counts as foreign. Nothing is guessed from file names. A
  folder holding another command's output (all listed, unchanged) is replaced only with
  ``force``. An output file (``x.csv`` and its sidecar ``x.json``) is listed the same way
  in a hidden marker beside it (``.x.csv.mrsus-output.json``) and replaced only if
  listed and unchanged;
* the root, the home folder, a parent of the current folder and the system's top-level
  folders are refused on every path (:func:`dangerous_folder`);
* results are written into a temporary hidden sibling (same file system) and moved into
  place only when the command succeeds, so a failed or interrupted run leaves the previous
  output untouched; a temporary folder left by a killed run (SIGKILL, power loss) is
  removed by the next run writing there (only a folder mrsus tagged as its own staging);
* a folder that cannot be renamed (the current folder, a mount point, a folder whose
  parent cannot be written) is written **in place**: staged inside itself, then its
  previous listed files removed and the new ones moved in one by one, the marker last;
  no ``.old`` folder is left. During that commit the marker lists the old and the new
  files, so a run killed half way leaves only files the next run recognises;
* the previous output is removed only after the new one is in place, by deleting exactly
  the files its marker lists (checked again just before); anything added meanwhile is
  kept, in a visible sibling ``NAME.kept``;
* two runs writing one output never interleave: the first holds a lock (a hidden
  ``.NAME.lock`` beside the output, or the folder itself when its parent cannot be
  written; :func:`fcntl.flock`, released by the system when the process dies, removed
  when the run ends) and the second refuses at once with one line. The lock's file
  descriptor is closed in pool workers (:func:`mrsuspension._pool.close_in_workers`), so
  a worker outliving its parent cannot keep it.

Digests cost one read of every file written: 30-60 ms per check for a full report
(17 MB in 112 files; docs/cli.md). The cache folder of the studies is checked with :func:`check_writable_folder`.
"""

from __future__ import annotations

import errno
import hashlib
import json
import os
import re
import shutil
import sys
import tempfile
from collections.abc import Callable, Iterable, Iterator, Mapping, Sequence
from contextlib import contextmanager, suppress
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from mrsuspension._pool import close_in_workers
from mrsuspension.errors import ValidationError

__all__ = [
    "MARKER",
    "carry_over",
    "check_output_folder",
    "check_writable_folder",
    "dangerous_folder",
    "foreign_files",
    "keep_recovered",
    "marked_command",
    "prepare_output",
    "prepare_output_file",
    "relocate_files",
    "relocated",
    "save_listed",
    "staging_in_use",
]

#: the file naming the command that wrote a folder and listing what it wrote
MARKER = ".mrsus-output.json"

#: a file inside a staging folder while mrsus writes it (so that only a folder bearing it,
#: or an empty one, is removed as a killed run's leftover)
_STAGING_TAG = ".mrsus-staging"

#: the staging folder inside an output written in place: ``.mrsus-staging.XXXXXXXX.tmp``
_IN_PLACE = re.compile(r"\.mrsus-staging\.[a-z0-9_]{8}\.tmp")

#: top-level folders of the system, never an output
_SYSTEM = frozenset(
    Path(p)
    for p in (
        "/bin", "/boot", "/dev", "/etc", "/home", "/lib", "/lib32", "/lib64", "/media",
        "/mnt", "/opt", "/proc", "/root", "/run", "/sbin", "/srv", "/sys", "/tmp", "/usr",
        "/var", "/Applications", "/Library", "/System", "/Users", "/Volumes", "/private",
    )
)  # fmt: skip

#: outputs whose block raised or was interrupted, left as they were (for the message of
#: an interrupted command, :func:`mrsuspension.cli.errors.interrupts`)
discarded: list[Path] = []

_CHUNK = 1 << 20


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

    With ``command``, also the checks :func:`prepare_output` makes on entering (a
    dangerous folder, files mrsus did not write, another command's output without
    ``force``: see the module docstring), for a command that computes before it enters
    :func:`prepare_output`.

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


def dangerous_folder(path: str | Path) -> str | None:
    """What makes ``path`` a folder no output may replace or be written into, or None.

    The root, the home folder and its parents, a parent of the current folder, and the
    system's top-level folders (``/usr``, ``/tmp``, ...), after following links. The
    current folder itself is not among them: it is written in place when it is empty or
    holds only mrsus's own output (:func:`prepare_output`).

    Examples
    --------
    >>> dangerous_folder("/"), dangerous_folder(".."), dangerous_folder("~/x/y/z/new")
    ('the root folder', 'a parent of the current folder', None)
    >>> dangerous_folder(Path.home())
    'the home folder'
    """
    resolved = Path(path).expanduser().resolve()
    if resolved == Path(resolved.anchor):
        return "the root folder"
    home = Path.home().resolve()
    if resolved == home:
        return "the home folder"
    if resolved in home.parents:
        return "a parent of the home folder"
    if resolved in Path.cwd().resolve().parents:
        return "a parent of the current folder"
    if resolved in _SYSTEM:
        return "a system folder"
    return None


def _refuse_dangerous(path: Path, option: str) -> None:
    """Refuse a :func:`dangerous_folder` on every path, with or without ``--force``."""
    what = dangerous_folder(path)
    if what is not None:
        raise ValidationError(
            f"{option} {str(path)!r} is {what}: mrsus never writes its output there, even "
            "with --force; give a new folder"
        )


# -- the marker: what a command wrote --------------------------------------------------------
@dataclass
class _Listing:
    """Files (relative path -> size, digest), folders and links of an output."""

    files: dict[str, tuple[int, str]] = field(default_factory=dict)
    folders: set[str] = field(default_factory=set)
    links: dict[str, str] = field(default_factory=dict)

    def to_json(self) -> dict[str, Any]:
        return {
            "files": {k: {"size": s, "sha256": d} for k, (s, d) in sorted(self.files.items())},
            "folders": sorted(self.folders),
            "links": dict(sorted(self.links.items())),
        }

    @classmethod
    def from_json(cls, data: Any) -> _Listing | None:
        """The listing in a marker's JSON; None when there is none or it is malformed."""
        if not isinstance(data, Mapping) or not isinstance(data.get("files"), Mapping):
            return None
        listing = cls()
        for rel, entry in data["files"].items():
            if not isinstance(entry, Mapping):
                return None
            size, digest = entry.get("size"), entry.get("sha256")
            if not isinstance(size, int) or not isinstance(digest, str):
                return None
            listing.files[str(rel)] = (size, digest)
        folders, links = data.get("folders", []), data.get("links", {})
        if not isinstance(folders, list) or not isinstance(links, Mapping):
            return None
        listing.folders = {str(f) for f in folders}
        listing.links = {str(k): str(v) for k, v in links.items()}
        return listing


def _digest(file: Path) -> str:
    """SHA-256 of a file's content (as ``sha256sum`` prints it)."""
    h = hashlib.sha256()
    with open(file, "rb") as f:
        while chunk := f.read(_CHUNK):
            h.update(chunk)
    return h.hexdigest()


def _read_marker(marker: Path) -> tuple[str | None, list[_Listing] | None]:
    """The command a marker names and its listings (the files it wrote; during an in-place
    commit also the previous ones); listings None: no marker, or one of an earlier
    version that lists nothing (its files count as foreign)."""
    try:
        data = json.loads(marker.read_text())
    except (OSError, ValueError, RecursionError):
        return None, None
    if not isinstance(data, dict):
        return None, None
    command = data.get("command") if isinstance(data.get("command"), str) else None
    listing = _Listing.from_json(data)
    if listing is None:
        return command, None
    previous = _Listing.from_json(data.get("previous"))
    return command, [listing] if previous is None else [listing, previous]


def _marker_text(command: str | None, listing: _Listing, previous: _Listing | None = None) -> str:
    from mrsuspension import __version__

    data: dict[str, Any] = {"command": command, "version": __version__, **listing.to_json()}
    if previous is not None:
        data["previous"] = previous.to_json()
    return json.dumps(data, indent=1) + "\n"


def _is_staging(entry: os.DirEntry[str]) -> bool:
    """An in-place staging folder of mrsus (its name, and tagged or empty)."""
    if not _IN_PLACE.fullmatch(entry.name) or not entry.is_dir(follow_symlinks=False):
        return False
    folder = Path(entry.path)
    return (folder / _STAGING_TAG).is_file() or not any(folder.iterdir())


def _scan(
    root: Path, listings: Sequence[_Listing] | None, skip: Iterable[str] = ()
) -> tuple[list[str], _Listing]:
    """Walk ``root`` (links not followed): the entries no listing has, or whose content
    differs (a foreign folder is named once, with a trailing ``/``), and the entries that
    match (with ``listings`` None: every entry, with its digest).

    ``skip``: top-level names left out (the marker, this run's staging folder); mrsus's
    in-place staging folders are left out too.
    """
    skipped = set(skip)
    foreign: list[str] = []
    ours = _Listing()

    def visit(folder: Path, prefix: str) -> None:
        with os.scandir(folder) as it:
            entries = sorted(it, key=lambda e: e.name)
        for e in entries:
            rel = prefix + e.name
            if not prefix and (e.name in skipped or _is_staging(e)):
                continue
            if e.is_symlink():
                target = os.readlink(e.path)
                if listings is None or any(li.links.get(rel) == target for li in listings):
                    ours.links[rel] = target
                else:
                    foreign.append(rel)
            elif e.is_dir(follow_symlinks=False):
                if listings is None or any(rel in li.folders for li in listings):
                    ours.folders.add(rel)
                    visit(Path(e.path), rel + "/")
                else:
                    foreign.append(rel + "/")
            elif e.is_file(follow_symlinks=False):
                size = e.stat(follow_symlinks=False).st_size
                wanted = (
                    None
                    if listings is None
                    else {
                        li.files[rel][1] for li in listings if li.files.get(rel, (-1,))[0] == size
                    }
                )
                digest = _digest(Path(e.path)) if wanted is None or wanted else ""
                if wanted is None or digest in wanted:
                    ours.files[rel] = (size, digest)
                else:
                    foreign.append(rel)
            else:  # a fifo, a socket, a device
                foreign.append(rel)

    visit(root, "")
    return foreign, ours


def foreign_files(folder: str | Path) -> list[str]:
    """The entries of an output folder that mrsus did not write, or that changed since
    (relative paths; a foreign folder ends with ``/``); all of them when the folder has
    no marker listing its files.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> with tempfile.TemporaryDirectory() as d:
    ...     out = pathlib.Path(d) / "out"
    ...     with prepare_output(out, "sweep") as tmp:
    ...         _ = (tmp / "sweep.csv").write_text("1\\n")
    ...     _ = (out / "notes.txt").write_text("mine")
    ...     _ = (out / "sweep.csv").write_text("2\\n")
    ...     foreign_files(out)
    ['notes.txt', 'sweep.csv']
    """
    folder = Path(folder)
    _, listings = _read_marker(folder / MARKER)
    return _scan(folder, listings or [], skip={MARKER})[0]


def marked_command(folder: str | Path) -> str | None:
    """The command named by an output folder's :data:`MARKER` (None: no marker, unreadable).

    Nothing is guessed from the folder's files: a folder without a marker is no
    command's output.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> with tempfile.TemporaryDirectory() as d:
    ...     print(marked_command(d))
    None
    """
    return _read_marker(Path(folder) / MARKER)[0]


def _names(folder: Path, rels: Sequence[str]) -> str:
    shown = ", ".join(repr(str(folder / r) + "/" * r.endswith("/")) for r in rels[:3])
    return shown + (f" and {len(rels) - 3} more" if len(rels) > 3 else "")


def _foreign_error(option: str, path: Path, foreign: Sequence[str], old: bool) -> ValidationError:
    if old:
        return ValidationError(
            f"{option} {str(path)!r} was written by an earlier mrsus version that did not "
            f"list its files ({_names(path, foreign)}); mrsus never deletes files it cannot "
            f"tell it wrote, even with --force: move them out or give another {option}"
        )
    return ValidationError(
        f"{option} {str(path)!r} holds {_names(path, foreign)}, not written by mrsus or "
        "changed since; mrsus never deletes files it did not write, even with --force: "
        f"move them out or give another {option}"
    )


def _check_folder(path: Path, command: str, force: bool, option: str) -> None:
    if path.exists() and not path.is_dir():
        raise ValidationError(f"{option} {str(path)!r} is a file, not a folder; give a folder")
    _refuse_dangerous(path, option)
    if not path.is_dir():
        check_writable_folder(path.parent, option, shown=path)
        return
    check_writable_folder(path, option)
    owner, listings = _read_marker(path / MARKER)
    try:
        foreign = _scan(path, listings or [], skip={MARKER})[0]
    except OSError as exc:
        raise ValidationError(f"{option} {str(path)!r} cannot be read: {exc}") from None
    if foreign:
        raise _foreign_error(option, path, foreign, old=owner is not None and listings is None)
    if owner is not None and owner != command and not force:
        raise ValidationError(
            f"{option} {str(path)!r} holds the output of 'mrsus {owner}'; give another "
            "folder or --force to replace it"
        )


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


def _parent_writable(path: Path) -> bool:
    return path.parent.is_dir() and os.access(path.parent, os.W_OK | os.X_OK)


def _in_place(real: Path) -> bool:
    """Whether the existing folder ``real`` is written in place rather than replaced by
    a rename: the current folder, a mount point, a folder whose parent is read-only."""
    return real.is_dir() and (
        real == Path.cwd().resolve() or os.path.ismount(real) or not _parent_writable(real)
    )


def _remove_stale(real: Path) -> None:
    """Remove what a killed run writing ``real`` left: its tagged (or empty) staging
    folders beside it (and inside it, for a folder written in place), and a previous
    output moved aside (only the files its marker lists; anything else is kept in a
    visible ``NAME.kept``)."""
    pattern = re.compile(rf"\.{re.escape(real.name)}\.[a-z0-9_]{{8}}\.(tmp|old)")
    places: list[tuple[Path, re.Pattern[str]]] = []
    if _parent_writable(real):
        places.append((real.parent, pattern))
    if real.is_dir():
        places.append((real, _IN_PLACE))
    for place, names in places:
        with suppress(OSError), os.scandir(place) as it:
            stale = [
                Path(e.path)
                for e in it
                if names.fullmatch(e.name) and e.is_dir(follow_symlinks=False)
            ]
        for folder in stale:
            if folder.name.endswith(".old"):
                aside = folder / real.name
                if aside.is_dir() and not aside.is_symlink():
                    _discard(aside, real)
                with suppress(OSError):
                    folder.rmdir()
            elif ((folder / _STAGING_TAG).is_file() or not any(folder.iterdir())) and not (
                _in_use(folder)
            ):
                shutil.rmtree(folder, ignore_errors=True)


def _keep_visible(folder: Path, near: Path, suffix: str) -> Path:
    """Move ``folder`` to the first free ``NAME.SUFFIX`` (``NAME.SUFFIX-2``, ...) beside
    ``near`` (inside it when its parent cannot be written); the new path."""
    base = near.parent if _parent_writable(near) else near
    for k in range(1, 1000):
        target = base / f"{near.name or 'output'}.{suffix}{'' if k == 1 else f'-{k}'}"
        if not (target.exists() or target.is_symlink()):
            try:
                os.replace(folder, target)
            except OSError:
                continue
            return target
    return folder  # pragma: no cover - a thousand of them


def _discard(folder: Path, near: Path) -> None:
    """Delete a previous output moved aside: exactly the files, links and folders its
    marker lists and that are unchanged. Anything else (added while the new output was
    being written) is kept, the folder moved to a visible ``NAME.kept`` beside ``near``."""
    _, listings = _read_marker(folder / MARKER)
    try:
        foreign, ours = _scan(folder, listings or [], skip={MARKER})
    except OSError:
        foreign, ours = ["?"], _Listing()
    _delete(folder, ours)
    with suppress(OSError):
        (folder / MARKER).unlink()
    try:
        folder.rmdir()
    except OSError:
        kept = _keep_visible(folder, near, "kept")
        print(
            f"warning: {str(kept)!r} holds what was added to {str(near)!r} while mrsus wrote "
            f"it ({_names(kept, foreign)}); mrsus did not delete it",
            file=sys.stderr,
        )


def _delete(root: Path, ours: _Listing) -> None:
    """Delete the files and links of ``ours`` under ``root``, then its folders left empty."""
    for rel in [*ours.files, *ours.links]:
        with suppress(FileNotFoundError):
            (root / rel).unlink()
    for rel in sorted(ours.folders, key=lambda r: r.count("/"), reverse=True):
        with suppress(OSError):
            (root / rel).rmdir()


def _move(src: Path, dst: Path) -> None:
    """``os.replace``, or a copy when ``src`` is on another file system."""
    try:
        os.replace(src, dst)
    except OSError as exc:
        if exc.errno != errno.EXDEV:
            raise
        shutil.move(str(src), str(dst))


@contextmanager
def _locked(real: Path, option: str, shown: Path) -> Iterator[None]:
    """Hold the write lock of ``real`` (``.NAME.lock`` beside it; the folder itself when
    its parent cannot be written) for the block.

    A second process refuses at once. The lock's descriptor is closed in pool workers
    (:func:`~mrsuspension._pool.close_in_workers`): a worker outliving its parent never
    holds it. Under the lock, what a killed run left is removed (:func:`_remove_stale`).
    The lock file is removed while still locked; a process that opened the old file
    re-opens the new one (inode check). Without :mod:`fcntl` (Windows) the block runs
    unlocked.
    """
    try:
        import fcntl
    except ImportError:  # pragma: no cover - Windows: no advisory locks, last move wins
        yield
        return
    own_file = _parent_writable(real) or not real.is_dir()
    lock = real.parent / f".{real.name}.lock"
    while True:
        try:
            fd = (
                os.open(lock, os.O_RDWR | os.O_CREAT | os.O_CLOEXEC, 0o644)
                if own_file
                else (os.open(real, os.O_RDONLY | os.O_DIRECTORY | os.O_CLOEXEC))
            )
        except OSError as exc:
            raise ValidationError(f"{option} {str(shown)!r} cannot be written: {exc}") from None
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError:
            os.close(fd)
            raise ValidationError(
                f"{option} {str(shown)!r} is being written by another mrsus run; wait for "
                f"it to finish or give another {option}"
            ) from None
        if not own_file:
            break
        try:
            same = os.fstat(fd).st_ino == os.stat(lock).st_ino
        except OSError:
            same = False
        if same:
            break
        os.close(fd)  # locked a file its holder had just removed: take the new one
    try:
        with close_in_workers(fd):
            _remove_stale(real)
            yield
    finally:
        try:
            if own_file:
                os.unlink(lock)
        finally:
            os.close(fd)


def _staging(real: Path, option: str, shown: Path, in_place: bool) -> Path:
    """A new staging folder, tagged as mrsus's: a hidden sibling of ``real``, or inside
    it when it is written in place; the permissions of a plain ``mkdir`` (``mkdtemp``
    makes it private, 0700, which the moved output would keep)."""
    try:
        if in_place:
            tmp = Path(tempfile.mkdtemp(prefix=".mrsus-staging.", suffix=".tmp", dir=real))
        else:
            tmp = Path(tempfile.mkdtemp(prefix=f".{real.name}.", suffix=".tmp", dir=real.parent))
        (tmp / _STAGING_TAG).touch()
        mask = os.umask(0o022)
        os.umask(mask)
        tmp.chmod(0o777 & ~mask)
        return tmp
    except OSError as exc:
        raise ValidationError(f"{option} {str(shown)!r} cannot be written: {exc}") from None


def _changed_meanwhile(option: str, shown: Path, names: str, kept: Path) -> ValidationError:
    return ValidationError(
        f"{option} {str(shown)!r}: {names} appeared or changed while mrsus ran, not written "
        f"by it; nothing was deleted, the results are in {str(kept)!r}"
    )


def _commit_folder(tmp: Path, real: Path, command: str, option: str, shown: Path) -> None:
    """Put the staged output ``tmp`` in place of ``real`` (see the module docstring)."""
    (tmp / _STAGING_TAG).unlink()
    new = _scan(tmp, None)[1]
    if tmp.parent == real:
        _commit_in_place(tmp, real, command, new, option, shown)
        return
    (tmp / MARKER).write_text(_marker_text(command, new))
    try:
        os.replace(tmp, real)  # real missing or an empty folder
        return
    except OSError:
        if not real.is_dir():
            raise
    aside_parent = Path(tempfile.mkdtemp(prefix=f".{real.name}.", suffix=".old", dir=real.parent))
    aside = aside_parent / real.name
    try:
        os.replace(real, aside)  # atomic: nothing reaches it by its name any more
    except OSError:  # busy (a mount point, a process's root): write in place
        aside_parent.rmdir()
        (tmp / MARKER).unlink()
        inner = _staging(real, option, shown, in_place=True)
        (inner / _STAGING_TAG).unlink()
        for entry in sorted(tmp.iterdir()):
            _move(entry, inner / entry.name)
        tmp.rmdir()
        _commit_in_place(inner, real, command, new, option, shown)
        return
    _, listings = _read_marker(aside / MARKER)
    foreign = _scan(aside, listings or [], skip={MARKER})[0]
    if foreign:  # added since the check: put it back, keep the results beside it
        os.replace(aside, real)
        aside_parent.rmdir()
        kept = _keep_visible(tmp, real, "new")
        raise _changed_meanwhile(option, shown, _names(shown, foreign), kept)
    os.replace(tmp, real)
    _discard(aside, real)
    with suppress(OSError):
        aside_parent.rmdir()


def _commit_in_place(
    tmp: Path, real: Path, command: str, new: _Listing, option: str, shown: Path
) -> None:
    """Move the staged files of ``tmp`` (inside ``real``) into ``real`` one by one, after
    removing the previous output's files; the marker lists both until the end."""
    _, listings = _read_marker(real / MARKER)
    foreign, old = _scan(real, listings or [], skip={MARKER, tmp.name})
    if foreign:
        kept = _keep_visible(tmp, real, "new")
        raise _changed_meanwhile(option, shown, _names(shown, foreign), kept)
    pending = tmp / MARKER
    pending.write_text(_marker_text(command, new, previous=old))
    os.replace(pending, real / MARKER)
    gone = _Listing(
        files={r: v for r, v in old.files.items() if r not in new.files},
        folders={r for r in old.folders if r not in new.folders},
        links={r: v for r, v in old.links.items() if r not in new.links},
    )
    _delete(real, gone)
    for rel in sorted(new.folders, key=lambda r: r.count("/")):
        (real / rel).mkdir(exist_ok=True)
    for rel in [*new.files, *new.links]:
        os.replace(tmp / rel, real / rel)
    pending.write_text(_marker_text(command, new))
    os.replace(pending, real / MARKER)
    shutil.rmtree(tmp, ignore_errors=True)  # its folders, emptied


@contextmanager
def prepare_output(
    path: str | Path | None, command: str, *, force: bool = False, option: str = "--out"
) -> Iterator[Path | None]:
    """Check an output folder, yield a temporary folder, and move it into place on success.

    Enter it **before** the work: the checks (see the module docstring) run on entering.
    Write every output into the yielded folder; when the block ends normally its files
    are listed in the :data:`MARKER` and replace ``path`` (or, for a folder that cannot
    be renamed, are moved into it); when it raises (or is interrupted) the temporary
    folder and any parent created for it are removed and ``path`` is untouched.

    Parameters
    ----------
    path : path or None
        The output folder (None: no output; yields None and does nothing).
    command : str
        The command writing it (``"sweep"``), recorded in the marker.
    force : bool
        Replace a folder holding another command's output. Files mrsus did not write
        are never replaced, with or without it.
    option : str
        The option's name, for messages.

    Yields
    ------
    Path or None
        The temporary folder to write into.

    Raises
    ------
    ValidationError
        The path is a file, cannot be written, is a :func:`dangerous_folder`, holds files
        mrsus did not write (or changed), or another command's output and not ``force``.

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
    real = path.resolve()
    created = [] if real.is_dir() else _make_parents(real.parent, option, path)
    try:
        with _locked(real, option, path):
            _check_folder(path, command, force, option)  # again: another run may have ended
            tmp = _staging(real, option, path, in_place=_in_place(real))
            try:
                yield tmp
                _commit_folder(tmp, real, command, option, path)
            except BaseException:
                shutil.rmtree(tmp, ignore_errors=True)
                raise
    except BaseException:
        _remove_empty(created)
        discarded.append(path)
        raise


def _file_marker(path: Path) -> Path:
    """The hidden marker beside an output file: ``.x.csv.mrsus-output.json``."""
    return path.parent / f".{path.name}{MARKER}"


def _foreign_beside(path: Path, names: Iterable[str]) -> tuple[list[str], _Listing]:
    """Of the files ``names`` beside ``path``, those present that its marker does not list
    (or that changed), and the listing of the ones that match."""
    _, listings = _read_marker(_file_marker(path))
    foreign: list[str] = []
    ours = _Listing()
    for name in names:
        file = path.parent / name
        if not (file.exists() or file.is_symlink()):
            continue
        if file.is_symlink() or not file.is_file():
            foreign.append(name)
            continue
        size = file.stat().st_size
        wanted = {
            li.files[name][1] for li in listings or [] if li.files.get(name, (-1,))[0] == size
        }
        digest = _digest(file) if wanted else ""
        if digest in wanted:
            ours.files[name] = (size, digest)
        else:
            foreign.append(name)
    return foreign, ours


def _file_error(option: str, path: Path, foreign: Sequence[str]) -> ValidationError:
    return ValidationError(
        f"{option} {str(path)!r}: {_names(path.parent, foreign)} not written by mrsus or "
        "changed since; mrsus never replaces files it did not write: move "
        f"{'it' if len(foreign) == 1 else 'them'} or give another {option}"
    )


def save_listed(out: Path, folder: Path, save: Callable[[Path], Iterable[str | Path]]) -> list[str]:
    """Write with ``save(folder)`` into :func:`prepare_output`'s folder; the files as they
    will stand under ``out`` (the ``--out`` the user gave).

    An ``OSError`` while writing (a full disk, a permission) becomes one
    :class:`ValidationError` line naming ``--out``; :func:`prepare_output` then leaves the
    previous output as it was.

    Examples
    --------
    >>> import tempfile
    >>> folder = Path(tempfile.mkdtemp())
    >>> save_listed(Path("res"), folder, lambda f: [f / "a.csv", f / "sub" / "b.png"])
    ['res/a.csv', 'res/sub/b.png']
    """
    try:
        return [str(out / Path(p).relative_to(folder)) for p in save(folder)]
    except OSError as exc:
        raise ValidationError(f"cannot write --out {str(out)!r}: {exc}") from None


@contextmanager
def prepare_output_file(
    path: str | Path | None,
    *,
    suffixes: Sequence[str],
    option: str = "--out",
    sidecars: Mapping[str, Sequence[str]] | None = None,
    command: str | None = None,
) -> Iterator[Path | None]:
    """Check an output file, yield a temporary path, and move it into place on success.

    Like :func:`prepare_output` for a single file (and sidecars written beside it, such
    as ``result.json`` next to ``result.csv``): every file written into the temporary
    path's folder replaces its namesake beside ``path`` when the block ends normally,
    and is listed (size, digest) in a hidden marker beside ``path``
    (``.result.csv.mrsus-output.json``). A file in the way that the marker does not
    list, or that changed since, is refused, naming it: before the work for ``path``
    and its ``sidecars``, and again before the move for every file written.

    Parameters
    ----------
    path : path or None
        The output file (None: no output; yields None).
    suffixes : sequence of str
        The valid suffixes (``(".nc", ".csv")``), checked first.
    option : str
        The option's name, for messages.
    sidecars : mapping, optional
        Suffix of ``path`` -> suffixes of the sidecars written with it
        (``{".csv": (".json",)}``), checked before the work too.
    command : str, optional
        The command writing it, recorded in the marker.

    Yields
    ------
    Path or None
        Where to write the file (same name, in a temporary hidden folder).

    Raises
    ------
    ValidationError
        A wrong suffix, a folder in the way, a folder that cannot be written, or a file
        in the way that mrsus did not write.

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
    extra = (sidecars or {}).get(path.suffix.lower(), ())
    names = [path.name, *(path.with_suffix(s).name for s in extra)]
    foreign = _foreign_beside(path, names)[0]
    if foreign:
        raise _file_error(option, path, foreign)
    created = _make_parents(path.parent, option, path)
    real = path.parent.resolve() / path.name
    try:
        with _locked(real, option, path):
            foreign = _foreign_beside(path, names)[0]
            if foreign:
                raise _file_error(option, path, foreign)
            tmp = _staging(real, option, path, in_place=False)
            try:
                yield tmp / path.name
                _commit_files(tmp, real, command, option, path)
            except BaseException:
                shutil.rmtree(tmp, ignore_errors=True)
                raise
    except BaseException:
        _remove_empty(created)
        discarded.append(path)
        raise


def _commit_files(tmp: Path, real: Path, command: str | None, option: str, shown: Path) -> None:
    """Move the files staged in ``tmp`` beside ``real``, its marker last."""
    (tmp / _STAGING_TAG).unlink()
    written = sorted(p.name for p in tmp.iterdir())
    foreign, _ = _foreign_beside(real, written)
    if foreign:
        kept = _keep_visible(tmp, real, "new")
        raise _changed_meanwhile(option, shown, _names(shown.parent, foreign), kept)
    new = _scan(tmp, None)[1]
    _, listings = _read_marker(_file_marker(real))
    kept_old = [n for n in (listings[0].files if listings else {}) if n not in new.files]
    new.files.update(_foreign_beside(real, kept_old)[1].files)  # earlier files still there
    marker = tmp / _file_marker(real).name
    marker.write_text(_marker_text(command, new))
    for name in written:
        os.replace(tmp / name, real.parent / name)
    os.replace(marker, _file_marker(real))
    tmp.rmdir()


#: a file a live process holds locked in a staging folder it writes (:func:`staging_in_use`)
_BUSY = ".mrsus-busy"


@contextmanager
def staging_in_use(folder: str | Path) -> Iterator[None]:
    """Show that this process writes into ``folder`` (a staging folder) until the block ends.

    For a process other than the command's that writes into its staging folder, e.g. the
    loop process of ``hil run``, which outlives a killed command long enough to stop the
    rig and keep its recording (:func:`keep_recovered`): while the block runs, the next
    run writing the same output does not remove the folder as a killed run's leftover.
    The lock (:func:`fcntl.flock` on a hidden file in the folder) is released by the
    system when the process dies; the file is removed when the block ends.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> with tempfile.TemporaryDirectory() as d:
    ...     with staging_in_use(d):
    ...         busy = _in_use(pathlib.Path(d))
    ...     busy, _in_use(pathlib.Path(d)), any(pathlib.Path(d).iterdir())
    (True, False, False)
    """
    path = Path(folder) / _BUSY
    try:
        import fcntl
    except ImportError:  # pragma: no cover - not on POSIX
        yield
        return
    fd = os.open(path, os.O_RDWR | os.O_CREAT | os.O_CLOEXEC, 0o644)
    try:
        fcntl.flock(fd, fcntl.LOCK_EX)
        yield
    finally:
        with suppress(OSError):  # the folder may have been moved meanwhile
            path.unlink()
        os.close(fd)


def _in_use(folder: Path) -> bool:
    """True when a live process holds ``folder``'s :func:`staging_in_use` lock."""
    try:
        import fcntl

        fd = os.open(folder / _BUSY, os.O_RDONLY | os.O_CLOEXEC)
    except (ImportError, OSError):
        return False
    try:
        fcntl.flock(fd, fcntl.LOCK_SH | fcntl.LOCK_NB)
    except OSError:
        return True
    finally:
        os.close(fd)
    return False


def keep_recovered(staged: str | Path, path: str | Path) -> Path:
    """Keep a staged output that could not be committed as a visible ``NAME.recovered``.

    For ``hil run``'s recording when the run ended in a way its command could not commit
    (a full disk, the command killed while its loop process finished the safe stop): the
    temporary folder of :func:`prepare_output` would be removed as a stale sibling by the
    next run; moved beside ``path`` as ``NAME.recovered`` (``NAME.recovered-2``, ... when
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
    for name in (_STAGING_TAG, _BUSY):  # the user's now: not a staging folder
        with suppress(OSError):
            (staged / name).unlink()
    kept = _keep_visible(staged, path, "recovered")
    if kept == staged:
        raise OSError(f"no free name for {path.name}.recovered beside {str(path.parent)!r}")
    return kept
