"""The shared input reader (:mod:`mrsuspension._inputs`): depth limits, unreadable files,
and the record of the files read."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from mrsuspension import _inputs
from mrsuspension._inputs import MAX_DEPTH, parse_json, parse_toml, read_bytes, recording
from mrsuspension.errors import ValidationError

DEEP = 400  # "hundreds of levels"


def _deep_toml_arrays(n: int = DEEP) -> str:
    return "a = " + "[" * n + "1" + "]" * n + "\n"


def _deep_toml_tables(n: int = DEEP) -> str:
    """Dotted table headers: tomllib builds them without recursing; the walk refuses them."""
    return "[" + ".".join(["a"] * n) + "]\nx = 1\n"


def _deep_toml_inline(n: int = DEEP) -> str:
    return "a = " + "{b = " * n + "1" + "}" * n + "\n"


@pytest.mark.audit("bounded work")
@pytest.mark.parametrize("text", [_deep_toml_arrays(), _deep_toml_tables(), _deep_toml_inline()])
def test_deep_toml_is_one_validation_error(text: str) -> None:
    with pytest.raises(ValidationError, match=f"more than {MAX_DEPTH} levels deep") as info:
        parse_toml(text, "study file 's.toml'")
    assert "study file 's.toml'" in str(info.value)


@pytest.mark.audit("bounded work")
@pytest.mark.parametrize("n", [40, 900, 100_000])
def test_deep_json_is_one_validation_error(n: int) -> None:
    text = '{"a": ' * n + "1" + "}" * n
    with pytest.raises(ValidationError, match=f"more than {MAX_DEPTH} levels deep"):
        parse_json(text, "request body")
    with pytest.raises(ValidationError, match="more than"):
        parse_json(("[" * n + "]" * n).encode(), "request body")


def test_depth_limit_is_inclusive_and_strings_do_not_count() -> None:
    ok = '{"a": ' * (MAX_DEPTH - 1) + "[1]" + "}" * (MAX_DEPTH - 1)
    assert parse_json(ok, "x") is not None
    assert parse_toml('s = "' + "[" * 300 + '"\n', "x") == {"s": "[" * 300}
    assert json.loads(json.dumps(parse_json('{"k": "{{{{"}', "x"))) == {"k": "{{{{"}


@pytest.mark.audit("bounded work")
def test_unreadable_file_is_one_line(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """PermissionError (tests run as root: raised by a patched read) names the file."""
    f = tmp_path / "scenario.toml"
    f.write_text("[excitation]\n")

    def refuse(self: Path) -> bytes:
        raise PermissionError(13, "Permission denied", str(self))

    monkeypatch.setattr(Path, "read_bytes", refuse)
    with pytest.raises(ValidationError) as info:
        read_bytes(f, "scenario file")
    assert str(info.value) == f"cannot read scenario file {str(f)!r}: Permission denied"


def test_recording_nests_and_resolves(tmp_path: Path) -> None:
    f = tmp_path / "p.json"
    f.write_text("{}")
    with recording() as outer:
        with recording() as inner:
            _inputs.load_json(tmp_path / "." / "p.json", "parameter file")
        _inputs.read_text(f, "parameter file")
    assert list(inner) == [str(f.resolve())] == list(outer)
    _inputs.read_text(f, "parameter file")  # outside any recording: nothing kept
    assert len(outer) == 1
