"""What an example's comment says it prints is what it prints (issue 31).

Scenario examples state their key results in a ``# Prints: name = value, ...`` comment line;
this runs each such example and compares every named measure with the stated value, to
the digits given (at least 1 % apart fails), so a comment cannot drift from the code.
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from mrsuspension.scenario import Scenario

ROOT = Path(__file__).resolve().parents[2]
PRINTS = re.compile(r"^#\s*Prints:\s*(.+)$", re.MULTILINE)
PAIR = re.compile(r"([A-Za-z_][\w.]*)\s*=\s*([-+0-9.eE]+)")
EXAMPLES = sorted(p for p in (ROOT / "examples").rglob("*.toml") if PRINTS.search(p.read_text()))


def _stated(path: Path) -> dict[str, str]:
    out: dict[str, str] = {}
    for line in PRINTS.findall(path.read_text()):
        out.update(PAIR.findall(line))
    return out


def test_some_examples_state_what_they_print() -> None:
    assert EXAMPLES, "no example carries a '# Prints:' line"


@pytest.mark.parametrize("path", EXAMPLES, ids=[p.name for p in EXAMPLES])
def test_the_stated_values_are_printed(path: Path) -> None:
    stated = _stated(path)
    (result,) = Scenario.load(path).run()
    measures = result.measures()
    for name, text in stated.items():
        assert name in measures, f"{path.name}: the comment names {name!r}, not a measure"
        decimals = len(text.split(".")[1]) if "." in text else 0
        tolerance = max(0.5 * 10.0**-decimals, 0.01 * abs(float(text)))
        got = float(measures[name])
        assert abs(got - float(text)) <= tolerance, f"{path.name}: {name} = {got:.4g}, says {text}"
