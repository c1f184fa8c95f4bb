"""What a figure's caption states, as data, and its check against the runs.

Every simulated figure family (:class:`~mrsuspension.report.families.FigureSpec`) declares
beside its caption the settings the caption (and title) states, in ``settings``: a key of
:data:`SETTINGS` -> a value for every variant, or a mapping variant label -> value for
some. :func:`mismatches` compares three things and lists every disagreement:

* **settings against the runs**: each stated value equals the one the variant's scenario
  actually runs (resolved through :class:`~mrsuspension.scenario.Scenario`, so defaults
  count: a variant that does not set ``force_gain`` runs k_d = 1);
* **caption against the settings**: each stated value is mentioned in the title or caption
  (in its notation where it has one, e.g. ``k_d = 2.5``, ``703 kg``, ``2.5 cm``; a current
  or frequency as a number; a law by name; SCM/ACM as the word), and every value
  the caption writes in one of the fixed notations (``k_d = ...``, ``k_c = ...``,
  ``n = ...``, ``SCM``/``ACM``, ``... kg``, ``... km/h``, ``... cm``) is a stated one;
* **completeness**: the law, the mode (hi-lo, inverse-model and sliding-mode laws), the
  current (passive and on-off laws), the excitation of the figure's kind (harmonic: a and
  f; sweep: a; pulse: a_m and V; road: the preset and V), every setting that differs from
  the package default and every setting the variants vary are stated.

``tests/unit/report/test_captions.py`` runs it over every figure of Chapters 4-6.

Examples
--------
>>> from mrsuspension.report.families import FigureSpec
>>> spec = FigureSpec(
...     number="9.1", kind="time", title="Passive damper at 0.1 A",
...     caption="Passive damper at 0.1 A; 2.5 cm harmonic excitation at 1.5 Hz.",
...     base={"controller": {"law": "passive", "current": 0.1}}, variants={"0.1 A": {}},
...     settings={"law": "passive", "current": 0.1, "amplitude": 0.025, "frequency": 1.5},
... )
>>> mismatches(spec)
[]
>>> wrong = FigureSpec(
...     number="9.2", kind="time", title="Passive damper, k_d = 2.5",
...     caption="Passive damper at 0.1 A; 2.5 cm harmonic excitation at 1.5 Hz.",
...     base={"controller": {"law": "passive", "current": 0.1}}, variants={"0.1 A": {}},
...     settings={"law": "passive", "current": 0.1, "amplitude": 0.025, "frequency": 1.5},
... )
>>> mismatches(wrong)
["figure 9.2: the caption writes k_d = 2.5, not a stated value of 'force_gain' (stated: none)"]
"""

from __future__ import annotations

import math
import re
from collections.abc import Mapping
from typing import Any, Protocol


class SpecLike(Protocol):
    """What this module reads of a :class:`~mrsuspension.report.families.FigureSpec` (which
    imports this module: no import back)."""

    @property
    def number(self) -> str: ...
    @property
    def kind(self) -> str: ...
    @property
    def title(self) -> str: ...
    @property
    def caption(self) -> str: ...
    @property
    def variants(self) -> Mapping[str, Mapping[str, Any]]: ...
    @property
    def settings(self) -> Mapping[str, Any]: ...
    def units(self, quick: bool) -> Mapping[str, Any]: ...


__all__ = [
    "DEFAULTS",
    "SETTINGS",
    "mismatches",
    "resolved",
    "stated",
]

#: The settings a caption may state: key -> what it is (value kind, caption form)
SETTINGS: dict[str, str] = {
    "law": "controller law (controller.law), named in the caption",
    "mode": "'SCM' or 'ACM' (the law's p = 1 or 0), written as the word",
    "force_gain": "damper force gain k_d (damper.force_gain), 'k_d = ...'",
    "hysteresis": "hysteretic damper model (damper.hysteresis), 'hysteretic' / 'mean'",
    "inverse": "inverse model of the inverse-model laws, 'mean' or 'hysteretic'",
    "current": "passive or on-off current [A], a number in A",
    "gain": "hi-lo control gain k_c, 'k_c = ...'",
    "order": "hi-lo controller order n, 'n = ...'",
    "sprung_mass": "sprung mass m_s [kg], '... kg'",
    "amplitude": "harmonic, sweep or pulse amplitude [m], written in cm",
    "frequency": "harmonic frequency [Hz], '... Hz'",
    "speed": "vehicle speed over a pulse or road [km/h], '... km/h'",
    "profile": "preset road name, quoted",
}
#: The package defaults: a setting that differs from these must be stated
DEFAULTS: dict[str, Any] = {
    "force_gain": 1.0,
    "hysteresis": True,
    "inverse": "hysteretic",
    "order": 2.0,
    "sprung_mass": 563.0,
}
#: Laws with an SCM/ACM mode (p), and those with a fixed current
_MODE_LAWS = (
    "skyhook-hilo",
    "policy-ii",
    "policy-iii",
    "policy-iv",
    "inverse-hilo",
    "sliding-mode",
)
_CURRENT_LAWS = ("passive", "onoff-adfg")
#: How a caption names each law (lower case; any one will do)
_LAW_NAMES: dict[str, tuple[str, ...]] = {
    "passive": ("passive",),
    "onoff-adfg": ("onoff-adfg", "on-off"),
    "skyhook-hilo": ("skyhook", "policy i", "policies i"),
    "policy-ii": ("policy ii", "policies i-iv"),
    "policy-iii": ("policy iii", "policies i-iv"),
    "policy-iv": ("policy iv", "policies i-iv"),
    "inverse-hilo": ("inverse-model hi-lo",),
    "sliding-mode": ("sliding mode", "sliding-mode"),
}
#: Settings required of each kind of figure (its excitation)
_KIND_KEYS: dict[str, tuple[str, ...]] = {
    "time": ("amplitude", "frequency"),
    "freq": ("amplitude",),
    "pulse": ("amplitude", "speed"),
    "psd": ("profile", "speed"),
}
_NUM = r"\d+(?:\.\d+)?"
_LIST = rf"{_NUM}(?:(?:,? and |, ){_NUM})*"
#: Caption notations read back: key -> pattern whose group 1 is a list of values, scale
#: from the caption's unit to the setting's
_NOTATIONS: dict[str, tuple[str, float]] = {
    "force_gain": (rf"\bk_d = ({_LIST})", 1.0),
    "gain": (rf"\bk_c = ({_LIST})", 1.0),
    "order": (rf"(?<![\w(])n = ({_LIST})", 1.0),
    "sprung_mass": (rf"({_LIST}) kg\b", 1.0),
    "speed": (rf"({_NUM}(?: and {_NUM})*) km/h", 1.0),
    "amplitude": (rf"({_LIST}) cm\b", 0.01),
}
#: Scale from a setting's unit to the caption's (amplitude: m -> cm)
_CAPTION_SCALE = {"amplitude": 100.0}


def stated(spec: SpecLike) -> dict[str, dict[str, Any]]:
    """Variant label -> the settings the figure states for it (``spec.settings`` spread).

    Examples
    --------
    >>> from mrsuspension.report.families import FigureSpec
    >>> spec = FigureSpec(number="9.1", kind="time", title="t", caption="c",
    ...                   variants={"a": {}, "b": {}},
    ...                   settings={"law": "passive", "current": {"a": 0.0, "b": 0.1}})
    >>> stated(spec)["b"]
    {'law': 'passive', 'current': 0.1}
    """
    out: dict[str, dict[str, Any]] = {label: {} for label in spec.variants}
    for key, value in spec.settings.items():
        if isinstance(value, Mapping):
            for label, v in value.items():
                out[label][key] = v
        else:
            for label in out:
                out[label][key] = value
    return out


def resolved(spec: SpecLike, label: str) -> dict[str, Any]:
    """The settings variant ``label`` actually runs (defaults resolved by the scenario).

    Examples
    --------
    >>> from mrsuspension.report.families import FigureSpec
    >>> spec = FigureSpec(number="9.1", kind="pulse", title="t", caption="c",
    ...                   base={"controller": {"law": "sliding-mode", "mode": "SCM"}},
    ...                   variants={"a": {}})
    >>> r = resolved(spec, "a")
    >>> r["law"], r["mode"], r["force_gain"], r["amplitude"], r["speed"]
    ('sliding-mode', 'SCM', 1.0, 0.035, 50.0)
    """
    from mrsuspension.scenario import Scenario

    unit = spec.units(quick=False)[label]
    scenario = Scenario.from_dict(unit.scenario)
    ctrl, damper, exc = scenario.controller, scenario.damper, scenario.excitation
    law = str(unit.scenario.get("controller", {}).get("law", "passive"))
    out: dict[str, Any] = {
        "law": law,
        "force_gain": float(getattr(damper, "force_gain", 1.0)),
        "hysteresis": bool(getattr(damper, "hysteresis", True)),
        "sprung_mass": float(scenario.vehicle.sprung_mass),
    }
    if law in _MODE_LAWS:
        p = float(getattr(ctrl, "p", math.nan))
        out["mode"] = "SCM" if p == 1.0 else "ACM" if p == 0.0 else f"p = {p:g}"
    for key in ("inverse", "current", "gain", "order"):
        if hasattr(ctrl, key):
            value = getattr(ctrl, key)
            out[key] = value if isinstance(value, str) else float(value)
    if hasattr(exc, "amplitude"):
        out["amplitude"] = float(exc.amplitude)
    if hasattr(exc, "frequency"):
        out["frequency"] = float(exc.frequency)
    if spec.kind in ("pulse", "psd"):
        out["speed"] = float(unit.scenario["excitation"]["speed"])
    if spec.kind == "psd":
        out["profile"] = str(unit.scenario["excitation"]["profile"])
    return out


def _same(a: Any, b: Any) -> bool:
    if isinstance(a, bool) or isinstance(b, bool) or isinstance(a, str) or isinstance(b, str):
        return bool(a == b)
    return math.isclose(float(a), float(b), rel_tol=1e-9, abs_tol=1e-12)


def _numbers(text: str) -> list[float]:
    return [float(x) for x in re.findall(_NUM, text)]


def _mentioned(key: str, value: Any, text: str) -> bool:
    """Whether the caption text mentions ``value`` of setting ``key``."""
    low = text.lower()
    if key == "law":
        return any(name in low for name in _LAW_NAMES.get(str(value), (str(value),)))
    if key == "mode":
        return re.search(rf"\b{value}\b", text) is not None
    if key == "hysteresis":
        return ("hysteretic" in low) if value else ("mean" in low or "hysteresis = false" in low)
    if key == "inverse":
        return f"{value} inverse" in low or f"inverse = {value}" in low
    if key == "profile":
        return f"'{value}'" in text
    if key in _NOTATIONS:
        pattern, scale = _NOTATIONS[key]
        written = [n * scale for group in re.findall(pattern, text) for n in _numbers(group)]
        return any(_same(n, value) for n in written)
    scaled = float(value) * _CAPTION_SCALE.get(key, 1.0)
    return any(math.isclose(scaled, n, rel_tol=1e-9, abs_tol=1e-9) for n in _numbers(text))


def _required(spec: SpecLike, runs: Mapping[str, Mapping[str, Any]]) -> set[str]:
    keys = {"law", *_KIND_KEYS[spec.kind]}
    for run in runs.values():
        if "mode" in run:
            keys.add("mode")
        if run["law"] in _CURRENT_LAWS:
            keys.add("current")
        keys.update(k for k, d in DEFAULTS.items() if k in run and not _same(run[k], d))
    labels = list(runs)
    for key in SETTINGS:
        values = [runs[label][key] for label in labels if key in runs[label]]
        if any(not _same(v, values[0]) for v in values):
            keys.add(key)
    return keys


def mismatches(spec: SpecLike) -> list[str]:
    """Every disagreement between a figure's caption, its stated settings and its runs.

    Parameters
    ----------
    spec : FigureSpec
        A simulated figure family (``special`` figures have no runs: always ``[]``).

    Returns
    -------
    list of str
        One line per problem, naming the figure, the variant, the setting and both values.
    """
    if spec.kind == "special":
        return []
    where = f"figure {spec.number}"
    text = f"{spec.title}. {spec.caption}"
    said = stated(spec)
    runs = {label: resolved(spec, label) for label in spec.variants}
    out: list[str] = []
    # 1. settings against the runs
    for label, settings in said.items():
        for key, value in settings.items():
            ran = runs[label].get(key)
            if ran is None or not _same(ran, value):
                out.append(f"{where}, {label!r}: states {key} = {value!r}, the run has {ran!r}")
    # 2. caption against the settings: each stated value mentioned...
    for key in spec.settings:
        distinct = {repr(s[key]): s[key] for s in said.values() if key in s}
        for value in distinct.values():
            if not _mentioned(key, value, text):
                out.append(f"{where}: states {key} = {value!r}, the caption does not mention it")
    # ... and each value written in a fixed notation stated
    for key, (pattern, scale) in _NOTATIONS.items():
        values = [s[key] for s in said.values() if key in s]
        for group in re.findall(pattern, text):
            for number in _numbers(group):
                if not any(_same(number * scale, v) for v in values):
                    shown = ", ".join(f"{v:g}" for v in dict.fromkeys(values)) or "none"
                    out.append(
                        f"{where}: the caption writes {_group_text(key, number)}, not a stated "
                        f"value of {key!r} (stated: {shown})"
                    )
    modes = {s.get("mode") for s in said.values()}
    for word in ("SCM", "ACM"):
        if re.search(rf"\b{word}\b", text) and word not in modes:
            out.append(f"{where}: the caption writes {word}, no variant states mode = {word!r}")
    # 3. completeness
    for key in sorted(_required(spec, runs)):
        missing = [
            label for label in spec.variants if key in runs[label] and key not in said[label]
        ]
        if missing:
            out.append(
                f"{where}: {key} is not stated for {', '.join(repr(m) for m in missing)} "
                f"(runs {', '.join(repr(runs[m][key]) for m in missing)})"
            )
    return out


def _group_text(key: str, number: float) -> str:
    """How the caption wrote one value (for messages), e.g. ``k_d = 2.5``, ``703 kg``."""
    forms = {
        "force_gain": "k_d = {:g}",
        "gain": "k_c = {:g}",
        "order": "n = {:g}",
        "sprung_mass": "{:g} kg",
        "speed": "{:g} km/h",
        "amplitude": "{:g} cm",
    }
    return forms[key].format(number)
