"""The figure-family machinery: specs validate, variants merge, equal scenarios share runs."""

from __future__ import annotations

import math
import time
from pathlib import Path

import pytest

from _helpers import raises_validation
from mrsuspension.report import ch4, ch5, ch6
from mrsuspension.report.families import (
    AGREEMENT_BANDS,
    KINDS,
    Agreement,
    FigureSpec,
    ShockTable,
    agreement,
    agreement_summary,
    build_all,
    check_finite,
    make_unit,
    passive,
    render,
    run_unit,
    shock_table,
    task_cost,
    unit_cost,
    unit_steps,
    vary,
)

ACM = {"controller": {"law": "skyhook-hilo", "mode": "ACM", "gain": 3.0}}


def _spec(**kw: object) -> FigureSpec:
    data: dict[str, object] = {
        "number": "9.1",
        "kind": "time",
        "title": "t",
        "caption": "c",
        "base": ACM,
        "variants": {"nominal": {}},
    }
    data.update(kw)
    return FigureSpec(**data)  # type: ignore[arg-type]


def test_unknown_kind_fails() -> None:
    raises_validation(lambda: _spec(kind="movie"), "figure 9.1", "'movie'", "time, freq")


def test_empty_variant_list_fails() -> None:
    raises_validation(lambda: _spec(variants={}), "figure 9.1", "variant list is empty")


def test_unknown_signal_and_given_label_fail() -> None:
    raises_validation(lambda: _spec(signals=("F_d", "bogus")), "bogus", "F_T")
    raises_validation(lambda: _spec(given={"other": 0.1}), "'other'", "nominal")


def test_special_needs_a_builder() -> None:
    raises_validation(lambda: _spec(kind="special", variants={}), "needs a builder")


def test_variant_section_must_be_a_table() -> None:
    raises_validation(lambda: _spec(variants={"bad": {"vehicle": 422.0}}), "[vehicle]", "422")


def test_variants_merge_by_section_and_a_law_replaces_the_controller() -> None:
    spec = _spec(
        variants={
            "light": {"vehicle": {"sprung_mass": 422.0}},
            "SCM": {"controller": {"mode": "SCM"}},
            **passive(0.1),
        }
    )
    assert spec.scenario("light")["controller"] == ACM["controller"]
    assert spec.scenario("light")["vehicle"] == {"sprung_mass": 422.0}
    assert spec.scenario("SCM")["controller"] == {**ACM["controller"], "mode": "SCM"}
    assert spec.scenario("passive 0.1 A")["controller"] == {"law": "passive", "current": 0.1}
    # the base is not modified by merging
    assert spec.base == ACM


def test_equal_scenarios_share_one_unit() -> None:
    a = make_unit("pulse", {**ACM, "vehicle": {"sprung_mass": 563}}, quick=True)
    b = make_unit("pulse", {**ACM, "vehicle": {"sprung_mass": 563.0}}, quick=True)
    assert a == b
    # a force gain of 1 is the default damper, so passive runs are shared across chapters
    c = make_unit("time", {"controller": {"law": "passive"}, "damper": {"force_gain": 1.0}}, True)
    d = make_unit("time", {"controller": {"law": "passive"}}, True)
    assert c == d
    assert make_unit("pulse", {**ACM, "excitation": {"speed": 100.0}}, True) != a
    # inverse-model laws get the smaller quick step
    inv = make_unit("time", {"controller": {"law": "inverse-hilo"}}, quick=True)
    assert inv.dt < d.dt
    assert make_unit("time", {}, quick=False).dt == 1e-4
    raises_validation(lambda: make_unit("special", {}, True), "'special'", "time")


def test_vary_leaves_the_nominal_value_unset() -> None:
    v = vary("controller", "order", (1, 2), "n = {}".format, nominal=2)
    assert v == {"n = 1": {"controller": {"order": 1}}, "n = 2": {}}


def test_shock_table_needs_a_nominal_row_and_matching_given_values() -> None:
    raises_validation(
        lambda: ShockTable(
            "9.1", "t", "m", ACM, {1.0: {"vehicle": {"sprung_mass": 1.0}}}, {1.0: ()}
        ),
        "nominal",
    )
    raises_validation(lambda: ShockTable("9.1", "t", "m", ACM, {1.0: {}}, {2.0: ()}), "[2.0]")
    raises_validation(lambda: ShockTable("9.1", "t", "m", ACM, {}, {}), "variant list is empty")


def test_chapter_specs_cover_every_figure_once() -> None:
    expected = {
        ch4: {f"4.{k}" for k in range(1, 30)},
        ch5: {f"5.{k}" for k in range(1, 22)},
        ch6: {f"6.{k}" for k in range(1, 21)},
    }
    for module, numbers in expected.items():
        found = [s.number for s in module.FIGURES]
        assert len(found) == len(set(found)), found
        assert numbers <= set(found), numbers - set(found)
        for spec in module.FIGURES:
            assert spec.kind in KINDS
            assert spec.kind == "special" or spec.caption
    tables = [t.number for m in (ch4, ch5, ch6) for t in m.TABLES]
    assert tables == ["4.1", "4.2", "4.3", "4.4", "4.5", "5.1", "5.2", "5.3", "6.1", "6.2", "6.3"]


def test_run_render_and_table_on_two_pulse_runs(tmp_path: Path) -> None:
    table = ShockTable(
        "9.1",
        "mass",
        "m_s (kg)",
        ACM,
        {563.0: {}, 703.0: {"vehicle": {"sprung_mass": 703.0}}},
        {563.0: (0.71, 0.19, 1.17, 1.92, 1.13, 0.0), 703.0: (0.71, 0.15, 1.17, 1.92, 1.13, 0.29)},
    )
    payloads = {v: run_unit(u) for v, u in table.units(quick=True).items()}
    out = shock_table(table, payloads, quick=True)
    nominal, heavy = out["rows"]
    assert nominal["DTR model"] == 0.0
    assert heavy["DTR model"] > 0.0
    # DTR: the peak tire force ratio, each row over its own static load (Tables 5.1/6.1's
    # reading); (3.44) as printed beside it: the heavier car's static-load change, 0.215
    from mrsuspension.measures import dtr_ratio

    loads = [payloads[m]["static load [N]"] for m in (563.0, 703.0)]
    assert loads == pytest.approx([653.0 * 9.81, 793.0 * 9.81])
    peaks = [payloads[m]["peak_tire_force"] for m in (563.0, 703.0)]
    assert heavy["DTR model"] == pytest.approx(dtr_ratio(*peaks, *loads), abs=1e-3)
    assert heavy["DTR (3.44) model"] == pytest.approx(
        abs(peaks[1] - peaks[0]) / (653.0 * 9.81), abs=1e-3
    )
    assert heavy["DTR (3.44) model"] != pytest.approx(heavy["DTR model"], abs=0.02)
    assert "peak tire force ratio" in out["caption"]
    # a heavier body moves less after the same pulse
    assert heavy["SAR_s model"] < nominal["SAR_s model"]
    assert heavy["SDR_s dissertation"] == 0.71
    # per cell: the ratio and its band; DTR: the difference
    for row in out["rows"]:
        for k in ("SDR_s", "SAR_s", "SDR_u", "SAR_u", "RDR"):
            ratio = row[f"{k} model"] / row[f"{k} dissertation"]
            # the ratio and the model value are each rounded to 3 decimals
            slack = 1e-3 + 5e-4 / row[f"{k} dissertation"]
            assert row[f"{k} ratio"] == pytest.approx(ratio, abs=slack)
            assert row[f"{k} agreement"] in ("green", "amber", "red")
        assert row["DTR difference"] == pytest.approx(
            row["DTR model"] - row["DTR dissertation"], abs=1e-3
        )
        assert "DTR ratio" not in row
    assert out["road_peak"] == "after-onset"
    assert "after-onset" in out["caption"]
    assert out["summary"]["SDR_s"]["cells"] == 2
    assert "differs (>25 %)" not in nominal
    spec = _spec(
        kind="pulse", variants={"563 kg": {}, "703 kg": {"vehicle": {"sprung_mass": 703.0}}}
    )
    units = spec.units(quick=True)
    assert set(units.values()) == set(table.units(quick=True).values())
    rec = render(
        spec, {k: payloads[563.0 if k == "563 kg" else 703.0] for k in units}, tmp_path, ("png",)
    )
    assert rec["files"] == ["fig_9_1.png"]
    assert (tmp_path / "fig_9_1.png").stat().st_size > 5000
    assert not check_finite(rec["data"])
    assert rec["data"]["SAR_s 703 kg"] == pytest.approx(heavy["SAR_s model"], abs=1e-3)
    assert "sprung_mass" in rec["data"]["scenario 703 kg"]


def test_build_all_in_process_shares_runs(tmp_path: Path) -> None:
    specs = [
        _spec(number="9.1", kind="pulse", variants={"a": {}}),
        _spec(number="9.2", kind="pulse", variants={"a": {}, **passive(0.0)}),
    ]
    built = build_all({"x": specs}, [], quick=True, out=tmp_path, workers=1)
    assert len(built.payloads) == 2  # three curves, two distinct runs
    assert set(built.figures) == {"x/9.1", "x/9.2"}
    for rec in built.figures.values():
        assert rec["render time [s]"] > 0.0
        assert all(math.isfinite(v) for v in rec["data"]["F_d a"])


def test_unit_costs_follow_the_simulated_steps() -> None:
    pulse, freq = make_unit("pulse", {}, quick=True), make_unit("freq", {}, quick=True)
    assert unit_steps(pulse) == 4.0 / 5e-4
    assert unit_steps(make_unit("pulse", {}, quick=False)) == 4.0 / 1e-4
    # the quick sweep: 10 harmonic runs of at least 5 s settling and 2 s measuring each
    assert 10 * 7.0 / 5e-4 < unit_steps(freq) < 10 * 30.0 / 5e-4
    road = make_unit("psd", {}, quick=True)
    assert unit_steps(road) == pytest.approx(500.0 / (50.0 / 3.6) / 5e-4)
    assert unit_cost(freq) > unit_cost(road) > unit_cost(pulse) > 0.0
    assert task_cost("beyond", quick=True) < task_cost("beyond", quick=False)
    assert task_cost("no such task", quick=True) > 0.0


def _started(seconds: float) -> float:
    """When this task started (monotonic clock, shared by the processes) after sleeping."""
    start = time.monotonic()
    time.sleep(seconds)
    return start


def test_pool_starts_the_longest_tasks_first_and_counts_idle_time(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    from mrsuspension.report.families import pool

    costs = {"a": (1.0, 1.0), "b": (4.0, 4.0), "c": (2.0, 2.0), "d": (3.0, 3.0)}
    monkeypatch.setattr(pool, "TASK_COST", costs)  # where task_cost reads it
    sleep = {"a": 0.1, "b": 0.3, "c": 0.2, "d": 0.1}  # c starts at 0.1 s, a at 0.3 s
    calls = {name: (_started, (sleep[name],)) for name in costs}  # given in another order
    built = build_all({}, [], quick=True, out=tmp_path, calls=calls, workers=2)
    by_start = sorted(built.calls, key=built.calls.__getitem__)
    assert set(by_start[:2]) == {"b", "d"}
    assert by_start[2:] == ["c", "a"]
    assert built.timing["workers"] == 2
    assert 0.0 <= built.timing["idle worker time [s]"] < built.timing["wall time [s]"]
    assert built.timing["started after [s]"] > 0.0


def test_docs_report_page_is_generated_from_the_specs() -> None:
    from mrsuspension.report import report_page

    page = Path(__file__).resolve().parents[3] / "docs" / "report.md"
    assert page.read_text() == report_page(), "run: python tools/report_docs.py"


@pytest.mark.parametrize(
    ("measure", "model", "given", "ratio", "band"),
    [
        ("SDR_s", 0.71, 0.71, 1.0, "green"),
        ("SDR_s", 0.781, 0.71, 1.1, "green"),  # exactly +10 %: still green
        ("SDR_s", 0.639, 0.71, 0.9, "green"),
        ("SAR_s", 0.21, 0.19, 1.105, "amber"),
        ("SAR_s", 0.2375, 0.19, 1.25, "amber"),  # exactly +25 %: still amber
        ("SAR_s", 0.14, 0.19, 0.737, "red"),
        ("RDR", 0.75, 1.13, 0.664, "red"),
        ("SAR_u", 3.0, 1.92, 1.562, "red"),
        ("DTR", 0.0, 0.0, None, "green"),  # the nominal row
        ("DTR", 0.02, 0.0, None, "green"),
        ("DTR", 0.04, 0.0, None, "amber"),
        ("DTR", 0.217, 0.26, 0.835, "amber"),  # by the difference (-0.043), not the ratio
        ("DTR", 0.37, 0.29, 1.276, "red"),
    ],
)
def test_agreement_bands(
    measure: str, model: float, given: float, ratio: float | None, band: str
) -> None:
    ag = agreement(measure, model, given)
    assert isinstance(ag, Agreement)
    assert ag.ratio == (None if ratio is None else pytest.approx(ratio, abs=1e-3))
    assert ag.difference == pytest.approx(model - given, abs=1e-3)
    assert ag.band == band


def test_agreement_edge_cases_and_summary() -> None:
    assert [b[0] for b in AGREEMENT_BANDS] == ["green", "amber", "red"]
    assert agreement("SAR_s", 0.0, 0.0).band == "green"  # a zero agrees only with a zero
    assert agreement("SAR_s", 0.1, 0.0) == Agreement(None, 0.1, "red")
    raises_validation(lambda: agreement("SAR", 1.0, 1.0), "'SAR'", "SDR_s, SAR_s")
    rows = [
        {"SDR_s agreement": "green", "DTR agreement": "green"},
        {"SDR_s agreement": "amber", "DTR agreement": "red"},
        {"SDR_s agreement": "red", "DTR agreement": "red"},
        {"SDR_s agreement": "amber", "DTR agreement": "amber"},
    ]
    summary = agreement_summary(rows)
    assert summary == {
        "SDR_s": {"within": 3, "cells": 4, "share": 0.75},
        "DTR": {"within": 2, "cells": 4, "share": 0.5},
    }


def test_shock_table_html_colours_cells_and_sums_up() -> None:
    from mrsuspension.report.html import shock_table_html

    table = ShockTable(
        "9.1",
        "mass",
        "m_s (kg)",
        ACM,
        {563.0: {}, 703.0: {"vehicle": {"sprung_mass": 703.0}}},
        {563.0: (0.71, 0.19, 1.17, 1.92, 1.13, 0.0), 703.0: (0.71, 0.15, 1.17, 1.92, 1.13, 0.29)},
    )
    payloads = {
        563.0: {"SDR_s": 0.70, "SAR_s": 0.22, "SDR_u": 1.5, "SAR_u": 1.92, "RDR": 0.75,
                "peak_tire_force": 11000.0, "road_peak": "after-onset"},
        703.0: {"SDR_s": 0.62, "SAR_s": 0.15, "SDR_u": 1.2, "SAR_u": 1.5, "RDR": 0.8,
                "peak_tire_force": (11000.0 / (653 * 9.81) - 0.25) * 793 * 9.81,
                "road_peak": "after-onset"},
    }  # fmt: skip
    # DTR: the peak tire force ratio (each row over its own static load), 0.25 here
    tab = shock_table(table, payloads, quick=True)
    nominal, heavy = tab["rows"]
    assert [nominal[f"{k} agreement"] for k in ("SDR_s", "SAR_s", "SDR_u", "SAR_u", "RDR")] == [
        "green", "amber", "red", "green", "red",
    ]  # fmt: skip
    assert nominal["SAR_s ratio"] == 1.158
    assert heavy["DTR model"] == 0.25
    assert heavy["DTR difference"] == -0.04
    assert heavy["DTR agreement"] == "amber"
    assert tab["summary"]["SDR_s"] == {"within": 2, "cells": 2, "share": 1.0}
    assert tab["summary"]["RDR"] == {"within": 0, "cells": 2, "share": 0.0}
    text = shock_table_html(tab)
    assert text.count("<tr>") == 4  # two header rows, two rows
    assert "<th colspan='3'>SAR_s</th>" in text
    assert '<td class="amber">1.16</td>' in text  # the SAR_s ratio of the nominal row
    assert '<td class="amber">-0.04</td>' in text  # DTR: the difference
    assert "<th>diff.</th>" in text
    assert "SDR_s 2/2 (100 %)" in text
    assert "RDR 0/2 (0 %)" in text
    mixed = {**payloads, 703.0: {**payloads[703.0], "road_peak": "onset"}}
    raises_validation(lambda: shock_table(table, mixed, quick=True), "different road peaks")
