"""The shock tables: :class:`ShockTable` (shock-response measures over one varied
parameter, beside the dissertation's values), :func:`shock_tables` (the three tables of
Chapters 5 and 6), :func:`shock_table` (its rows from the pulse payloads) and the per-cell
comparison (:func:`agreement`, :data:`AGREEMENT_BANDS`, :func:`agreement_summary`).
"""

from __future__ import annotations

import json
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any, NamedTuple

from mrsuspension.errors import ValidationError
from mrsuspension.report.families.run import _static_load
from mrsuspension.report.families.spec import (
    PULSE_DURATION,
    Unit,
    _merge,
    _normalise,
    _step,
    make_unit,
)
from mrsuspension.report.toolkit import SHOCK, TABLE_MEASURES


@dataclass(frozen=True)
class ShockTable:
    """A table of shock-response measures over one varied parameter, with the
    dissertation's values.

    Parameters
    ----------
    number, title : str
        Table number and title.
    column : str
        Header of the varied parameter (e.g. ``"m_s (kg)"``).
    base : mapping
        Scenario tables of the nominal case (pulse defaults: 3.5 cm, 50 km/h).
    variants : mapping
        Shown parameter value -> table overrides (the nominal row has ``{}``).
    given : mapping
        Shown parameter value -> the dissertation's SDR_s, SAR_s, SDR_u, SAR_u, RDR, DTR.
    why : str
        Known causes of differences (appended to the caption).
    """

    number: str
    title: str
    column: str
    base: Mapping[str, Any]
    variants: Mapping[float, Mapping[str, Any]]
    given: Mapping[float, tuple[float, ...]]
    why: str = ""

    def __post_init__(self) -> None:
        if not self.variants:
            raise ValidationError(f"table {self.number}: the variant list is empty")
        if set(self.given) != set(self.variants):
            raise ValidationError(
                f"table {self.number}: dissertation values given for {sorted(self.given)}, "
                f"variants are {sorted(self.variants)}"
            )
        if {} not in [dict(v) for v in self.variants.values()]:
            raise ValidationError(
                f"table {self.number}: one variant must be the nominal case ({{}}), the DTR "
                "reference"
            )

    def units(self, quick: bool) -> dict[float, Unit]:
        """Parameter value -> pulse unit."""
        return {
            v: make_unit("pulse", _merge(self.base, o), quick) for v, o in self.variants.items()
        }


# The measures of a shock table, in column order (DTR last: it needs the nominal row):
# the toolkit's TABLE_MEASURES
#: Agreement bands of a shock-table cell, best first: (name, limit on
#: ``|model/dissertation - 1|``, limit on ``|model - dissertation|`` for DTR, which the
#: dissertation often gives as 0). The report colours the cells green, amber and red.
AGREEMENT_BANDS: tuple[tuple[str, float, float], ...] = (
    ("green", 0.10, 0.025),
    ("amber", 0.25, 0.05),
    ("red", math.inf, math.inf),
)


class Agreement(NamedTuple):
    """One shock-table cell compared with the dissertation.

    ``ratio`` is model/dissertation (None where the dissertation gives 0),
    ``difference`` model - dissertation, ``band`` a name of :data:`AGREEMENT_BANDS`.
    """

    ratio: float | None
    difference: float
    band: str


def agreement(measure: str, model: float, dissertation: float) -> Agreement:
    """Compare one cell: the ratio, the difference and the agreement band.

    The band is the first of :data:`AGREEMENT_BANDS` whose limit holds: on the relative
    deviation ``|model/dissertation - 1|`` (green within 10 %, amber within 25 %, red
    beyond), or for ``measure == "DTR"`` on the absolute difference (green within 0.025,
    amber within 0.05), since the dissertation's DTR is 0 in every nominal row. A zero
    dissertation value of another measure agrees only with a zero.

    Parameters
    ----------
    measure : str
        ``"SDR_s"``, ``"SAR_s"``, ``"SDR_u"``, ``"SAR_u"``, ``"RDR"`` or ``"DTR"``.
    model, dissertation : float
        Our value and the dissertation's.

    Returns
    -------
    Agreement

    Examples
    --------
    >>> agreement("SDR_s", 0.70, 0.71)
    Agreement(ratio=0.986, difference=-0.01, band='green')
    >>> agreement("SAR_s", 0.23, 0.19).band, agreement("RDR", 0.75, 1.13).band
    ('amber', 'red')
    >>> agreement("DTR", 0.03, 0.0)
    Agreement(ratio=None, difference=0.03, band='amber')
    """
    if measure not in TABLE_MEASURES:
        raise ValidationError(
            f"measure {measure!r} is not a shock-table measure; valid: {', '.join(TABLE_MEASURES)}"
        )
    ours, theirs = float(model), float(dissertation)
    ratio = None if theirs == 0.0 else round(ours / theirs, 3)
    if measure == "DTR":
        off = abs(ours - theirs)
    else:
        off = abs(ours / theirs - 1.0) if theirs != 0.0 else (0.0 if ours == 0.0 else math.inf)
    band = next(
        name
        for name, relative, absolute in AGREEMENT_BANDS
        if off <= (absolute if measure == "DTR" else relative) + 1e-12
    )
    return Agreement(ratio, round(ours - theirs, 3), band)


def agreement_summary(rows: Sequence[Mapping[str, Any]]) -> dict[str, dict[str, Any]]:
    """Per measure: how many of a table's cells agree within 25 % (DTR: within 0.05).

    Parameters
    ----------
    rows : sequence of mapping
        :func:`shock_table` rows (``"<measure> agreement"`` keys).

    Returns
    -------
    dict
        Measure -> ``{"within": n, "cells": m, "share": n/m}`` (green and amber cells
        agree).

    Examples
    --------
    >>> rows = [{"SDR_s agreement": "green"}, {"SDR_s agreement": "red"}]
    >>> agreement_summary(rows)["SDR_s"]
    {'within': 1, 'cells': 2, 'share': 0.5}
    """
    out: dict[str, dict[str, Any]] = {}
    for k in TABLE_MEASURES:
        bands = [r[f"{k} agreement"] for r in rows if f"{k} agreement" in r]
        if bands:
            n = sum(b != "red" for b in bands)
            out[k] = {"within": n, "cells": len(bands), "share": round(n / len(bands), 3)}
    return out


def shock_table(
    table: ShockTable, payloads: Mapping[float, dict[str, Any]], quick: bool
) -> dict[str, Any]:
    """Rows of our shock measures beside the dissertation's, with per-cell ratios.

    DTR (3.44) against the row without overrides, read as the deviation in the peak tire
    force *ratio* (:func:`~mrsuspension.measures.dtr_ratio`: each run's peak over its own
    static load, the reading Tables 5.1 and 6.1 support; equal to (3.44) as printed,
    :func:`~mrsuspension.measures.dtr`, between rows of one mass, which each row also
    carries as ``DTR (3.44) model``). Each measure ``k`` of a row has ``k model``, ``k dissertation``,
    ``k ratio`` (model/dissertation; for DTR ``DTR difference``, model - dissertation)
    and ``k agreement``, the :func:`agreement` band. ``SAR_s`` and ``SAR_u`` divide by the
    road acceleration peak of the payloads' ``road_peak`` (``"after-onset"`` from
    :func:`run_unit`). The result's ``summary`` is :func:`agreement_summary` of the rows.
    """
    from mrsuspension.measures import dtr, dtr_ratio
    from mrsuspension.vehicle import QuarterCar

    car = QuarterCar()
    nominal = next(v for v, o in table.variants.items() if not o)
    reference = payloads[nominal]["peak_tire_force"]
    loads = {v: _static_load(_merge(table.base, o)) for v, o in table.variants.items()}
    road_peaks = {payloads[v].get("road_peak", "after-onset") for v in table.variants}
    if len(road_peaks) != 1:
        raise ValidationError(
            f"table {table.number}: the rows use different road peaks {sorted(road_peaks)}"
        )
    (road_peak,) = road_peaks
    rows = []
    for value in table.variants:
        p = payloads[value]
        row: dict[str, Any] = {table.column: value}
        peak = p["peak_tire_force"]
        model = [*(p[k] for k in SHOCK), dtr_ratio(reference, peak, loads[nominal], loads[value])]
        for k, ours, theirs in zip(TABLE_MEASURES, model, table.given[value], strict=True):
            ag = agreement(k, ours, theirs)
            row[f"{k} model"] = round(float(ours), 3)
            row[f"{k} dissertation"] = float(theirs)
            if k == "DTR":
                row["DTR difference"] = ag.difference
            else:
                row[f"{k} ratio"] = ag.ratio
            row[f"{k} agreement"] = ag.band
        row["DTR (3.44) model"] = round(float(dtr(reference, peak, car.total_mass)), 3)
        row["peak F_T model [N]"] = round(float(peak), 1)
        rows.append(row)
    ratios = []
    for k in SHOCK:
        r = [row[f"{k} ratio"] for row in rows]
        ratios.append(f"{k} {min(r):.2f}-{max(r):.2f}")
    step = _step(table.base, quick) * 1e3
    sar = (
        "SAR_s and SAR_u divide by the road acceleration peak after the pulse's onset jump "
        "(road_peak 'after-onset': 0.412 c (mu omega_0)^2, c = 0.25 a_m e^2; the dissertation "
        "does not define it and this reading matches its SAR_s; the onset jump, 'onset', "
        "is 4.85x larger)"
        if road_peak == "after-onset"
        else "SAR_s and SAR_u divide by the largest road acceleration, the jump at the "
        "pulse's onset (road_peak 'onset': 2 c (mu omega_0)^2, 4.85x the after-onset peak)"
    )
    return {
        "number": table.number,
        "title": table.title,
        "caption": (
            f"Rounded pulse (mu = 3, a_m = 3.5 cm, 50 km/h, omega_0 = 10.4 rad/s unless varied), "
            f"varying {table.column}; ratios of peaks over a {PULSE_DURATION:g} s record, step "
            f"{step:g} ms. Scenario: {json.dumps(_normalise(table.base), sort_keys=True)}. "
            f"{sar}. DTR against the nominal row, as the deviation in the peak tire force "
            "ratio (each row's peak over its own static load (m_s + m_u) g; the reading Tables "
            "5.1 and 6.1 support: (3.44) as printed divides both peaks by the nominal "
            f"{car.static_load:.0f} N and gives the static-load change, 0.216, for every "
            "controller at 422 and 703 kg; the rows carry it as 'DTR (3.44) model'). Each cell: ours, the dissertation's and their ratio (DTR: "
            "the difference), coloured green within 10 %, amber within 25 %, red beyond (DTR: "
            "within 0.025, 0.05). Model/dissertation ratio over the rows: "
            f"{', '.join(ratios)} (a range that is narrow but far from 1: the trend agrees, "
            "the level does not). " + table.why
        ),
        "road_peak": road_peak,
        "rows": rows,
        "summary": agreement_summary(rows),
    }


def shock_tables(
    base: dict[str, Any],
    numbers: tuple[str, str, str],
    given: Sequence[dict[float, tuple[float, ...]]],
    why: str,
) -> tuple[ShockTable, ...]:
    """The three shock tables of Chapters 5 and 6: sprung mass, speed, pulse height.

    Parameters
    ----------
    base : dict
        The controller's scenario tables.
    numbers : tuple of str
        Table numbers (mass, speed, pulse height).
    given : tuple of dict
        The dissertation's rows of each table (value -> SDR_s, SAR_s, SDR_u, SAR_u, RDR, DTR).
    why : str
        Known causes of differences.

    Returns
    -------
    tuple of ShockTable

    Examples
    --------
    >>> row = (1.0, 0.3, 1.1, 1.2, 0.9, 0.0)
    >>> tabs = shock_tables({}, ("9.1", "9.2", "9.3"),
    ...                     ({563.0: row}, {50.0: row}, {3.5: row}), "")
    >>> [t.column for t in tabs]
    ['m_s (kg)', 'V (km/h)', 'a_m (cm)']
    """
    mass, speed, height = given
    return (
        ShockTable(
            numbers[0],
            "Influence of sprung mass variations on the transient response measures",
            "m_s (kg)",
            base,
            {m: ({} if m == 563.0 else {"vehicle": {"sprung_mass": m}}) for m in mass},
            mass,
            why,
        ),
        ShockTable(
            numbers[1],
            "Influence of vehicle speed variations on the transient response measures",
            "V (km/h)",
            base,
            {v: ({} if v == 50.0 else {"excitation": {"speed": v}}) for v in speed},
            speed,
            why,
        ),
        ShockTable(
            numbers[2],
            "Influence of variations in peak pulse displacement on the transient response "
            "measures (the dissertation's caption says 'road roughness'; its rows vary a_m)",
            "a_m (cm)",
            base,
            {a: ({} if a == 3.5 else {"excitation": {"amplitude": a / 100}}) for a in height},
            height,
            why,
        ),
    )
