"""The figure-family machinery: specs validate, variants merge, equal scenarios share runs."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from _helpers import raises_validation
from mrsuspension.report import ch4, ch5, ch6
from mrsuspension.report.families import (
    KINDS,
    FigureSpec,
    ShockTable,
    build_all,
    check_finite,
    make_unit,
    passive,
    render,
    run_unit,
    shock_table,
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
    # a heavier body moves less after the same pulse
    assert heavy["SAR_s model"] < nominal["SAR_s model"]
    assert heavy["SDR_s dissertation"] == 0.71
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


def test_docs_report_page_is_generated_from_the_specs() -> None:
    from mrsuspension.report import report_page

    page = Path(__file__).resolve().parents[3] / "docs" / "report.md"
    assert page.read_text() == report_page(), "run: python tools/report_docs.py"
