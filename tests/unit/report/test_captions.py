"""Each figure's caption against the scenario it runs (mrsuspension.report.captions).

Every simulated figure of Chapters 4-6 states its settings as data beside its caption
(``FigureSpec.settings``); the test resolves each variant's scenario (defaults included)
and compares: the stated settings with the run, the caption's text with the stated
settings, and that every setting the run does not take by default is stated. A second test
holds Figs 6.1-6.4 to section 6.2's text; a third reads the dissertation's own figure
captions (SCM/ACM, a_m, f, V, i_d) where the text is available.
"""

from __future__ import annotations

import dataclasses
import os
import re
from pathlib import Path
from typing import Any

import pytest

from mrsuspension import ValidationError
from mrsuspension.report import ch4, ch5, ch6
from mrsuspension.report.captions import mismatches, resolved, stated
from mrsuspension.report.families import FigureSpec

FIGURES = {s.number: s for s in (*ch4.FIGURES, *ch5.FIGURES, *ch6.FIGURES) if s.kind != "special"}

_SEED = Path(
    os.environ.get(
        "MRSUS_DISSERTATION",
        Path(__file__).resolve().parents[4] / "shared" / "seed" / "dissertation.txt",
    )
)


def test_every_figure_caption_matches_its_runs() -> None:
    assert len(FIGURES) == 70
    problems = [line for spec in FIGURES.values() for line in mismatches(spec)]
    assert not problems, "\n".join(problems)
    assert all(spec.settings for spec in FIGURES.values())


# Section 6.2: Figs 6.1/6.2 "sliding mode SCM controller ... letting xi = 30 and p = 1" at the
# nominal force gain; "Subsequent response analyses are thus performed assuming the force
# gain of 2.5" (Figs 6.3 SCM, 6.4 ACM, "when compared with those shown in Figures 6.1 and
# 6.2 for the nominal damping force properties")
SECTION_6_2: dict[str, dict[str, Any]] = {
    "6.1": {"law": "sliding-mode", "mode": "SCM", "force_gain": 1.0, "inverse": "mean"},
    "6.2": {"law": "sliding-mode", "mode": "SCM", "force_gain": 1.0, "inverse": "hysteretic"},
    "6.3": {"law": "sliding-mode", "mode": "SCM", "force_gain": 2.5, "inverse": "hysteretic"},
    "6.4": {"law": "sliding-mode", "mode": "ACM", "force_gain": 2.5, "inverse": "hysteretic"},
}


@pytest.mark.parametrize("number", sorted(SECTION_6_2))
def test_figs_6_1_to_6_4_run_section_6_2s_settings(number: str) -> None:
    spec = FIGURES[number]
    (label,) = spec.variants
    run = resolved(spec, label)
    want = {**SECTION_6_2[number], "amplitude": 0.025, "frequency": 1.5, "hysteresis": True}
    assert {k: run[k] for k in want} == want
    said = stated(spec)[label]
    assert {k: said[k] for k in ("law", "mode", "force_gain") if k in said} == {
        k: want[k] for k in ("law", "mode", "force_gain")
    }


def test_a_run_that_leaves_its_caption_is_caught() -> None:
    fig63 = FIGURES["6.3"]
    at_kd1 = dataclasses.replace(fig63, base={"controller": dict(fig63.base["controller"])})
    problems = mismatches(at_kd1)
    assert any("states force_gain = 2.5, the run has 1.0" in p for p in problems), problems


def test_a_caption_that_leaves_its_settings_is_caught() -> None:
    fig63 = FIGURES["6.3"]
    wrong = dataclasses.replace(
        fig63,
        title=fig63.title.replace("k_d = 2.5", "k_d = 1"),
        caption=fig63.caption.replace("k_d = 2.5", "k_d = 1"),
    )
    problems = mismatches(wrong)
    assert any("caption writes k_d = 1" in p for p in problems), problems
    assert any("force_gain = 2.5, the caption does not mention it" in p for p in problems)
    acm = dataclasses.replace(fig63, caption=fig63.caption.replace("SCM", "ACM"))
    assert any("no variant states mode = 'ACM'" in p for p in mismatches(acm))


def test_an_unstated_setting_is_caught() -> None:
    fig612 = FIGURES["6.12"]
    settings = {k: v for k, v in fig612.settings.items() if k != "sprung_mass"}
    problems = mismatches(dataclasses.replace(fig612, settings=settings))
    assert any("sprung_mass is not stated" in p for p in problems), problems


def test_settings_are_validated() -> None:
    with pytest.raises(ValidationError, match="unknown setting 'k_d'"):
        FigureSpec(number="9.1", kind="time", title="t", caption="c", variants={"a": {}},
                   settings={"k_d": 2.5})  # fmt: skip
    with pytest.raises(ValidationError, match="names variant"):
        FigureSpec(number="9.1", kind="time", title="t", caption="c", variants={"a": {}},
                   settings={"current": {"b": 0.1}})  # fmt: skip


_CAPTION = re.compile(r"^Figure ([456]\.\d+): (.*)$", re.MULTILINE)


@pytest.mark.skipif(not _SEED.exists(), reason=f"dissertation text not found at {_SEED}")
def test_figures_state_what_the_dissertations_captions_state() -> None:
    """SCM/ACM, a_m, f, V, i_d and k_d in the dissertation's own figure captions."""
    text = _SEED.read_text(encoding="utf-8")
    checked, problems = 0, []
    for number, caption in _CAPTION.findall(text):
        spec = FIGURES.get(number)
        if spec is None:
            continue
        said = stated(spec).values()
        ours = {
            k: {s[k] for s in said if k in s}
            for k in ("mode", "amplitude", "frequency", "speed", "current", "force_gain")
        }
        modes = set(re.findall(r"\b(SCM|ACM)\b", caption))
        if modes and modes != ours["mode"]:
            problems.append(f"Fig {number}: dissertation {sorted(modes)}, ours {ours['mode']}")
        for key, pattern, scale in (
            ("amplitude", r"\$a_m=([\d.]+)\$ cm", 0.01),
            ("frequency", r"\$f=([\d.]+)\$ Hz", 1.0),
            ("speed", r"\$V=([\d.]+)\$ km/h", 1.0),
            ("current", r"\$i_d=([\d.]+)\$", 1.0),
            ("force_gain", r"\$k_d=([\d.]+)\$", 1.0),
        ):
            for value in re.findall(pattern, caption):
                if not any(abs(float(value) * scale - v) < 1e-9 for v in ours[key]):
                    problems.append(f"Fig {number}: dissertation {key} {value}, ours {ours[key]}")
        checked += 1
    assert checked >= 60, checked
    assert not problems, "\n".join(problems)
