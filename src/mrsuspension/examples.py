"""The examples of the README, reachable from an installed package (``mrsus examples``).

The repository's ``examples/`` folder (scenario, study and optimisation files, Python
scripts) ships inside the wheel as ``mrsuspension/example_files``, so that a ``pip
install`` user can list them and copy them next to their work: ``mrsus examples copy
all`` writes ``./examples/...``, after which every ``mrsus ... examples/...`` command of
the README runs as in a checkout. A checkout (or an editable install) reads the
repository's own ``examples/``.

Copying never replaces a file: when any target exists, nothing is written and the error
names it.

Examples
--------
>>> names = [name for name, _ in list_examples()]
>>> "scenarios/passive-harmonic.toml" in names and "vehicles/half_car.toml" in names
True
"""

from __future__ import annotations

import shutil
from collections.abc import Sequence
from pathlib import Path

from mrsuspension._output import check_writable_folder
from mrsuspension.errors import ValidationError, did_you_mean

__all__ = ["PACKAGED", "SUFFIXES", "copy_examples", "examples_root", "list_examples"]

#: the examples' folder inside the installed package (pyproject's wheel force-include)
PACKAGED = "example_files"
#: the files that are examples (inputs and scripts; no caches or outputs)
SUFFIXES = (".toml", ".py", ".csv", ".json", ".crg")


def examples_root() -> Path:
    """The examples' folder: the packaged copy, or a checkout's ``examples/``.

    Raises
    ------
    ValidationError
        When neither exists (a broken install).
    """
    here = Path(__file__).resolve().parent
    for folder in (here / PACKAGED, here.parents[1] / "examples"):
        if folder.is_dir():
            return folder
    raise ValidationError(
        "the examples are not installed with this package (no mrsuspension/example_files); "
        "reinstall it, or take them from the source repository's examples/ folder"
    )


def _files(root: Path) -> list[Path]:
    return sorted(
        p
        for p in root.rglob("*")
        if p.is_file() and p.suffix in SUFFIXES and "__pycache__" not in p.parts
    )


def _summary(path: Path) -> str:
    """The file's first comment line (``#`` lines of TOML and scripts, a docstring's)."""
    for line in path.read_text(encoding="utf-8", errors="replace").splitlines()[:12]:
        text = line.strip()
        if text.startswith("#") and not text.startswith("#!"):
            return text.lstrip("#").strip()
        if text.startswith('"""'):
            return text.strip('"').strip() or "(script)"
    return ""


def list_examples() -> list[tuple[str, str]]:
    """Every example as ``(relative path, first comment line)``, sorted by path."""
    root = examples_root()
    return [(p.relative_to(root).as_posix(), _summary(p)) for p in _files(root)]


def copy_examples(names: Sequence[str], dest: str | Path = "examples") -> list[Path]:
    """Copy examples into ``dest`` (created), keeping their folders; return the files written.

    Parameters
    ----------
    names : sequence of str
        Example files (``scenarios/passive-harmonic.toml``), folders (``scenarios``) or
        ``all``.
    dest : str or Path
        Target folder, ``examples`` by default (so the README's paths work from its
        parent).

    Raises
    ------
    ValidationError
        An unknown name (with a suggestion), or a target file that exists already (then
        nothing is written).

    Examples
    --------
    >>> import tempfile
    >>> out = copy_examples(["scenarios/passive-harmonic.toml"], tempfile.mkdtemp())
    >>> out[0].name
    'passive-harmonic.toml'
    """
    root = examples_root()
    files = _files(root)
    relative = [p.relative_to(root).as_posix() for p in files]
    folders = sorted({r.rsplit("/", 1)[0] for r in relative if "/" in r})
    if not names:
        raise ValidationError("name at least one example, a folder or 'all' (mrsus examples list)")
    chosen: list[Path] = []
    for name in names:
        key = str(name).strip().strip("/")
        if key == "all":
            chosen += files
        elif key in folders:
            chosen += [p for p, r in zip(files, relative, strict=True) if r.startswith(key + "/")]
        elif key in relative:
            chosen.append(files[relative.index(key)])
        else:
            raise ValidationError(
                f"unknown example {name!r}.{did_you_mean(key, [*relative, *folders, 'all'])} "
                f"Folders: {', '.join(folders)}, or all (mrsus examples list names every file)."
            )
    target = Path(dest).expanduser()
    check_writable_folder(target, "the examples' target folder")
    pairs = {p: target / p.relative_to(root) for p in dict.fromkeys(chosen)}
    taken = [str(t) for t in pairs.values() if t.exists()]
    if taken:
        which = f"{taken[0]!r} exists" if len(taken) == 1 else (
            f"{taken[0]!r} and {len(taken) - 1} more exist")  # fmt: skip
        raise ValidationError(
            f"{which} already: nothing was copied (examples never replace a file); copy "
            "into another folder with --to, or move the file away"
        )
    written = []
    for source, out in pairs.items():
        out.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(source, out)
        written.append(out)
    return written
