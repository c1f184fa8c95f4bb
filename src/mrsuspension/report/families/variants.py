"""What the controller chapters (4, 5 and 6) share to declare their figures: variant
makers (:func:`vary`, :func:`passive`), the variant sets of sections 4.4, 5.4 and 6.4
(:data:`MASSES`, :data:`SPEEDS`, :data:`ROADS`, :data:`HARMONIC_AMPS`,
:data:`PULSE_AMPS`, each with what a caption varying it states), :func:`spec_factory`,
and two readers of the declared figures: :func:`check_finite` and :func:`markdown_index`
(docs/report.md).
"""

from __future__ import annotations

import json
import math
from collections.abc import Callable, Mapping, Sequence
from typing import Any

from mrsuspension.report.families.shock import ShockTable
from mrsuspension.report.families.spec import FigureSpec, _normalise, make_unit


def vary(
    section: str,
    key: str,
    values: Sequence[Any],
    label: Callable[[Any], str],
    nominal: Any = None,
) -> dict[str, dict[str, Any]]:
    """Variants setting ``[section] key`` to each value (the nominal value: no override).

    Examples
    --------
    >>> vary("vehicle", "sprung_mass", (422.0, 563.0), "m_s = {:g} kg".format, 563.0)
    {'m_s = 422 kg': {'vehicle': {'sprung_mass': 422.0}}, 'm_s = 563 kg': {}}
    """
    return {label(v): ({} if v == nominal else {section: {key: v}}) for v in values}


def passive(*currents: float) -> dict[str, dict[str, Any]]:
    """Passive-damper variants at the given currents (nominal damper, k_d = 1).

    Examples
    --------
    >>> passive(0.0)
    {'passive 0 A': {'controller': {'law': 'passive', 'current': 0.0}, 'damper': {'force_gain': 1.0}}}
    """
    return {
        f"passive {i:g} A": {
            "controller": {"law": "passive", "current": float(i)},
            "damper": {"force_gain": 1.0},
        }
        for i in currents
    }


# -- the variant sets the three controller chapters share (sections 4.4, 5.4, 6.4) -------
#: sprung mass +-25 % (563 kg nominal)
MASSES = vary("vehicle", "sprung_mass", (422.0, 563.0, 703.0), "m_s = {:g} kg".format, 563.0)
#: vehicle speed over a pulse or a road (50 km/h nominal)
SPEEDS = vary("excitation", "speed", (50.0, 100.0), "V = {:g} km/h".format, 50.0)
#: road roughness (the presets standing in for the dissertation's roads)
ROADS: dict[str, dict[str, Any]] = {
    "medium-rough": {"excitation": {"profile": "medium-rough"}},
    "rough": {},
}
#: harmonic amplitude at 1.5 Hz (2.5 cm nominal)
HARMONIC_AMPS = vary(
    "excitation", "amplitude", (0.015, 0.025, 0.035), lambda a: f"a = {a * 100:g} cm", 0.025
)
#: rounded-pulse height (3.5 cm nominal)
PULSE_AMPS = vary(
    "excitation", "amplitude", (0.02, 0.035, 0.05), lambda a: f"a_m = {a * 100:g} cm", 0.035
)
#: What a caption varying these states (``FigureSpec.settings``, checked against the runs by
#: :mod:`mrsuspension.report.captions`): one per variant family above
MASSES_STATED: dict[str, Any] = {
    "sprung_mass": {"m_s = 422 kg": 422.0, "m_s = 563 kg": 563.0, "m_s = 703 kg": 703.0}
}
SPEEDS_STATED: dict[str, Any] = {"speed": {"V = 50 km/h": 50.0, "V = 100 km/h": 100.0}}
ROADS_STATED: dict[str, Any] = {"profile": {"medium-rough": "medium-rough", "rough": "rough"}}
HARMONIC_AMPS_STATED: dict[str, Any] = {
    "amplitude": {"a = 1.5 cm": 0.015, "a = 2.5 cm": 0.025, "a = 3.5 cm": 0.035}
}
PULSE_AMPS_STATED: dict[str, Any] = {
    "amplitude": {"a_m = 2 cm": 0.02, "a_m = 3.5 cm": 0.035, "a_m = 5 cm": 0.05}
}


def spec_factory(base: Mapping[str, Any]) -> Callable[..., FigureSpec]:
    """A :class:`FigureSpec` maker whose ``base`` defaults to a chapter's controller.

    Examples
    --------
    >>> spec = spec_factory({"controller": {"law": "passive"}})
    >>> spec("9.1", "time", "T", "C", {"a": {}}).base["controller"]["law"]
    'passive'
    """

    def spec(
        number: str, kind: str, title: str, caption: str, variants: Any, **kw: Any
    ) -> FigureSpec:
        return FigureSpec(
            number=number,
            kind=kind,
            title=title,
            caption=caption,
            base=kw.pop("base", base),
            variants=variants,
            **kw,
        )

    return spec


def check_finite(data: Mapping[str, Any]) -> list[str]:
    """Keys of ``data`` holding a non-finite number (used by tests and the report).

    Examples
    --------
    >>> check_finite({"a": [1.0, float("nan")], "b": 2.0, "c": "text"})
    ['a']
    """
    bad = []
    for key, value in data.items():
        values = value if isinstance(value, list) else [value]
        if any(isinstance(v, float) and not math.isfinite(v) for v in values):
            bad.append(key)
    return bad


def markdown_index(
    chapters: Mapping[int, tuple[Sequence[FigureSpec], Sequence[ShockTable]]],
) -> str:
    """A Markdown list of every figure family and table with its scenario (docs/report.md).

    Parameters
    ----------
    chapters : mapping
        Chapter number -> (figure specs, shock tables).

    Returns
    -------
    str
        Markdown text: per chapter, a table of figures (number, kind, title, variants) and
        each figure's scenario per variant, then the tables.

    Examples
    --------
    >>> spec = FigureSpec(number="9.1", kind="pulse", title="T", caption="C", variants={"a": {}})
    >>> print(markdown_index({9: ((spec,), ())}).splitlines()[4])
    | 9.1 | pulse | T | a |
    """
    out: list[str] = []
    for chapter, (specs, tables) in chapters.items():
        out += [
            f"## Chapter {chapter}",
            "",
            "| Figure | Kind | Title | Variants |",
            "|---|---|---|---|",
        ]
        for s in specs:
            variants = ", ".join(s.variants) if s.kind != "special" else "(own figure function)"
            extra = " (full report only)" if s.full_only else ""
            out.append(f"| {s.number} | {s.kind} | {s.title}{extra} | {variants} |")
        out.append("")
        for s in specs:
            if s.kind == "special":
                continue
            out.append(f"**Fig. {s.number}** ({s.kind}). {s.caption}")
            out.append("")
            for label in s.variants:
                unit = make_unit(s.kind, s.scenario(label), quick=False)
                out.append(f"- {label}: `{unit.tables}`")
            out.append("")
        for t in tables:
            values = ", ".join(f"{v:g}" for v in t.variants)
            out.append(
                f"**Table {t.number}**: {t.title}. Varies {t.column} over {values}; base "
                f"`{json.dumps(_normalise(t.base), sort_keys=True)}` under the rounded pulse "
                "(mu = 3, a_m = 3.5 cm, 50 km/h unless varied). Our SDR_s, SAR_s, SDR_u, "
                "SAR_u, RDR, DTR beside the dissertation's."
            )
            out.append("")
    return "\n".join(out)
