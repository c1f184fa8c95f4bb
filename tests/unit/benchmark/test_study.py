"""The benchmark of semi-active laws: the spec's checks, a quick run end to end, the
command line and the report section.

One quick benchmark (``BenchmarkSpec.quick()``, one process: about 5 s) serves every
test that needs a result: the command line and the report section are given it in place
of a second run (their own plumbing is what they test).
"""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Any

import pytest
from typer.testing import CliRunner

from mrsuspension.benchmark import study as S
from mrsuspension.benchmark.study import (
    LAW_TABLE,
    BenchmarkRoad,
    BenchmarkSpec,
    TunedOption,
    bound_violations,
    default_laws,
    run_benchmark,
)
from mrsuspension.cli import app
from mrsuspension.control import CONTROLLERS
from mrsuspension.control.registry import VEHICLE_LAWS
from mrsuspension.errors import ValidationError

runner = CliRunner()


@pytest.fixture(scope="module")
def quick() -> S.BenchmarkResult:
    return run_benchmark(BenchmarkSpec.quick(), workers=1)


# -- the spec ---------------------------------------------------------------------------------
def test_an_unknown_law_is_one_line_naming_the_valid_ones() -> None:
    with pytest.raises(ValidationError) as err:
        BenchmarkSpec(laws=("skyhook-hilo", "groundhok"))
    text = str(err.value)
    assert "\n" not in text
    assert "'groundhok'" in text
    assert "Valid:" in text
    assert all(law in text for law in (*CONTROLLERS, *VEHICLE_LAWS))


def test_the_default_set_is_the_table_met_by_the_registry(monkeypatch: pytest.MonkeyPatch) -> None:
    laws = default_laws()
    registered = {*CONTROLLERS, *VEHICLE_LAWS}
    assert laws == tuple(law for law in LAW_TABLE if law in registered)
    # every registered law is benchmarked (issue 29: "every law", the whole-vehicle laws
    # too), each with a valid option
    assert set(laws) == registered, registered - set(laws)
    spec = BenchmarkSpec()
    for law in laws:
        assert spec.tuned_option(law).option is not None
    assert spec.tuned_option("vehicle-lq") == TunedOption("force_weight", 1e-8, 1e-4, log=True)
    assert spec.tuned_option("corner-skyhook").option == "high_current"
    # a law of the table registered later joins the default set, its option found
    monkeypatch.setitem(LAW_TABLE, "my-law", TunedOption(None))
    monkeypatch.setitem(CONTROLLERS, "my-law", CONTROLLERS["ideal-skyhook"])
    assert "my-law" in default_laws()
    spec = BenchmarkSpec()
    assert "my-law" in spec.laws
    opt = spec.tuned_option("my-law")  # no option named in the table: the first positive one
    assert opt.option == "skyhook_damping"
    assert (opt.lower, opt.upper, opt.log) == pytest.approx((675.0, 67500.0, True))


@pytest.mark.parametrize(
    ("changes", "words"),
    [
        ({"laws": ()}, "at least one law"),
        ({"tuning": {"skyhook-hilo": TunedOption("gian", 1.0, 2.0)}}, "no option 'gian'"),
        ({"tuning": {"skyhook-hilo": TunedOption("gain", 2.0, 1.0)}}, "lower < upper"),
        ({"tuning": {"passive": TunedOption("current", 0.0, 0.5, log=True)}}, "lower > 0"),
        ({"vehicles": ("quarter", "bus")}, "unknown vehicle 'bus'"),
        ({"speeds": (50.0, 400.0)}, "5-250 km/h"),
        ({"weights": (1.0, -1.0, 0.0)}, "weights"),
        ({"optimum_dt": 0.01}, "optimum_dt"),
        ({"pareto": (0.5,)}, "at least two"),
    ],
)
def test_bad_specs_are_refused(changes: dict[str, Any], words: str) -> None:
    with pytest.raises(ValidationError, match=words):
        BenchmarkSpec.quick().replace(**changes)


def test_a_whole_vehicle_law_needs_the_full_car() -> None:
    # named with the quarter car alone: one line naming the law and the full car
    with pytest.raises(ValidationError) as err:
        BenchmarkSpec(laws=("passive", "vehicle-lq"), vehicles=("quarter",))
    text = str(err.value)
    assert "\n" not in text
    assert text.startswith("laws: 'vehicle-lq' is a whole-vehicle law")
    assert "needs the full car" in text
    assert "'clipped-lq'" in text  # its per-corner law
    with pytest.raises(ValidationError, match="'modal-skyhook' is a whole-vehicle law"):
        BenchmarkSpec.from_dict({"laws": ["modal-skyhook"], "vehicles": ["quarter"]})
    # the default set on the quarter car alone leaves them out; per-corner laws stay
    quarter = BenchmarkSpec(vehicles=("quarter",)).laws
    assert quarter == tuple(law for law in default_laws() if law not in VEHICLE_LAWS)
    assert "clipped-lq" in quarter
    # the full car alone takes them
    assert BenchmarkSpec(laws=("vehicle-lq",), vehicles=("full",)).laws == ("vehicle-lq",)


def test_which_laws_drive_the_damper() -> None:
    """The ``-active`` whole-vehicle laws are ideal actuators: references, not held to the
    bound nor best law; the others switch the MR damper's current."""
    assert S.drives_damper("vehicle-lq") is True
    assert S.drives_damper("vehicle-lq-active") is False
    for law, cls in VEHICLE_LAWS.items():
        assert S.drives_damper(law) is (not cls.active), law
        assert S.drives_damper(law) is (not law.endswith("-active")), law
    assert S.drives_damper("clipped-lq") is True
    assert S.drives_damper("lq-active") is False


def test_a_spec_from_toml_tables() -> None:
    spec = BenchmarkSpec.from_dict(
        {
            "laws": ["passive", "skyhook-hilo"],
            "tuning": {"skyhook-hilo": {"option": "gain", "lower": 1.0, "upper": 9.0}},
            "training": {"name": "B", "kind": "iso", "iso_class": "B", "speed": 70.0},
            "roads": [{"name": "bump", "kind": "bump", "height": 0.02}],
            "speeds": [60.0],
            "weights": {"rattle": 0.0},
            "band": "envelope",
        }
    )
    assert spec.band == "envelope"
    assert spec.tuned_option("skyhook-hilo") == TunedOption("gain", 1.0, 9.0)
    assert spec.training_speed == 70.0
    assert spec.training.iso_class == "B"
    assert spec.weights == (1.0, 1.0, 0.0)
    assert spec.roads[0].excitation("quarter", 60.0, 1.0)["kind"] == "pulse"
    assert spec.roads[0].excitation("full", 60.0, 1.0)["kind"] == "bump"
    assert BenchmarkSpec.from_dict(spec.to_dict()).to_dict() == spec.to_dict()
    with pytest.raises(ValidationError, match="rods"):
        BenchmarkSpec.from_dict({"rods": []})
    with pytest.raises(ValidationError, match="kind must be iso, preset or bump"):
        BenchmarkRoad("x", "crg")


def test_the_bound_check_reports_a_law_below_the_optimum() -> None:
    row = {"law": "x", "road": "r", "speed": 50.0, "bounded": True, "cost": 1.5}
    assert bound_violations([{**row, "optimum_cost": 1.4}]) == []
    assert len(bound_violations([{**row, "optimum_cost": 1.6}])) == 1
    # an ideal damper is outside the band: not held to it
    assert bound_violations([{**row, "bounded": False, "optimum_cost": 1.6}]) == []
    # within the solver's tolerance (BOUND_TOLERANCE, relative) is not a violation
    tol = S.BOUND_TOLERANCE
    assert bound_violations([{**row, "optimum_cost": 1.5 / (1.0 - 0.5 * tol)}]) == []
    (text,) = bound_violations([{**row, "optimum_cost": 1.5 / (1.0 - 2.0 * tol)}])
    assert text.startswith("x on r at 50 km/h costs 1.5000, below the optimum's 1.50")
    # no optimum (the full car, a failed solve): nothing to hold it to
    assert bound_violations([{**row, "optimum_cost": math.nan}]) == []
    # the row's own tolerance (the record's model gap), never below the solver's
    gap = {**row, "bound_tolerance": 0.05}
    assert bound_violations([{**gap, "optimum_cost": 1.5 / 0.97}]) == []
    (text,) = bound_violations([{**gap, "optimum_cost": 1.5 / 0.94}])
    assert text.endswith("by 6.0 % (tolerance 5.0 %)")
    assert len(bound_violations([{**row, "bound_tolerance": 0.0, "optimum_cost": 1.503}])) == 1
    assert bound_violations([{**row, "bound_tolerance": math.nan, "optimum_cost": 1.501}]) == []


def test_the_optimum_task_model_gap_and_the_envelope_band() -> None:
    """The model gap is the engine's passive car scored on the model's; the envelope
    optimum is scaled by the engine's passive car and bounds the mean band's."""
    road = BenchmarkRoad("bump", "bump", height=0.03, length=0.5, position=1.0)
    exc = road.excitation("quarter", 50.0, 0.4)
    w = (1.0, 1.0, 0.1)
    base = ("bump", 50.0, exc, 0.4, 4e-3, w, (), (1e-3, 0.35))
    from mrsuspension.benchmark import BenchmarkProblem, Weights

    problem = BenchmarkProblem(S._road_object(exc, 0.4), duration=0.4, dt=4e-3, weights=Weights(*w))
    sc = problem.scales
    model = {"comfort": sc[0], "road_holding": sc[1] / problem.linear.static_load, "rattle": sc[2]}
    same = S._optimum_task((*base, "mean", model))
    assert same["model_gap"] == pytest.approx(0.0, abs=1e-12)
    assert same["bound_tolerance"] == S.BOUND_TOLERANCE
    harder = {**model, "comfort": 1.1 * model["comfort"]}
    assert S.model_gap(harder, model, w) == pytest.approx(0.21 / 2.1, rel=1e-9)
    engine = {k: 1.05 * v for k, v in model.items()}
    env = S._optimum_task((*base, "envelope", engine))
    assert env["success"]
    assert env["band"] == "envelope"
    assert env["peak_velocity_range"] == [1e-3, 0.35]
    assert env["bound_tolerance"] == S.BOUND_TOLERANCE
    # scaled by the engine's passive car: 1.05^2 the mean band's cost at the same forces,
    # and the envelope holds the mean band at 0.3 m/s: no more than that
    assert env["cost"] <= same["cost"] / 1.05**2 * (1.0 + 1e-6)
    assert env["comfort_ratio"] ** 2 + env["road_holding_ratio"] ** 2 + 0.1 * env[
        "rattle_ratio"
    ] ** 2 == pytest.approx(env["cost"], rel=1e-9)
    with pytest.raises(ValidationError, match="band: the optimum's band must be mean or envelope"):
        BenchmarkSpec.quick().replace(band="hysteretic")


# -- a quick run end to end -------------------------------------------------------------------
def test_quick_run_numbers_and_the_bound(quick: S.BenchmarkResult) -> None:
    spec = quick.spec
    n_cases = len(spec.roads) * len(spec.speeds)
    corner_laws = [law for law in spec.laws if not S.is_vehicle_law(law)]
    assert len(quick.rows) == (len(corner_laws) * len(spec.vehicles) + 1) * n_cases
    for r in quick.rows:
        for k in ("comfort", "road_holding", "rattle", "coil_power", "cost"):
            assert math.isfinite(r[k]), (r["law"], k)
            assert r[k] >= 0.0, (r["law"], k)
        assert (r["vehicle"] == "quarter") == math.isfinite(r["optimum_cost"])
    # every optimum converged; every law through the MR damper costs at least the optimum
    assert len(quick.optima) == n_cases
    assert all(o["success"] for o in quick.optima)
    for r in quick.rows:
        if r["vehicle"] == "quarter" and r["bounded"]:
            assert r["cost"] >= r["optimum_cost"], r
            assert r["distance"] >= 0.0
    assert quick.violations == []
    # the optimum beats the passive car; the ideal skyhook is not held to the bound
    assert all(o["cost"] < o["passive_cost"] for o in quick.optima)
    assert {r["law"] for r in quick.rows if not r["bounded"]} == {"ideal-skyhook"}
    # a law at 0 A costs the passive car's w_c + w_r + w_s; the skyhook hi-lo draws current
    sky = [r for r in quick.rows if r["law"] == "skyhook-hilo"]
    assert all(r["coil_power"] > 0.0 for r in sky)
    tuned = quick.tuned["skyhook-hilo"]
    assert tuned["option"] == "gain"
    assert 0.3 <= tuned["value"] <= 30.0
    assert tuned["evaluations"] == spec.evaluations
    # each vehicle's rows use the law tuned on that vehicle (issue 29: the full car's own)
    assert set(quick.tuned_full) == set(spec.laws)
    assert set(quick.tuned) == set(corner_laws)
    for r in quick.rows:
        t = (quick.tuned if r["vehicle"] == "quarter" else quick.tuned_full)[r["law"]]
        assert (t["vehicle"], r["option"], r["value"]) == (r["vehicle"], t["option"], t["value"])
    assert quick.tuned_full["skyhook-hilo"]["value"] != tuned["value"]
    # each optimum's tolerance is its record's model gap (at least the solver's), on
    # each of its rows; the damper's v_m is recorded (the envelope band's range)
    for o in quick.optima:
        assert o["band"] == "mean"
        assert o["bound_tolerance"] == max(S.BOUND_TOLERANCE, abs(o["model_gap"]))
        assert 0.0 < abs(o["model_gap"]) < 0.5
        assert o["band_violation"] < 1e-3  # [N]
        mine = [r for r in quick.rows if r["vehicle"] == "quarter" and r["road"] == o["road"]]
        assert {r["bound_tolerance"] for r in mine} == {o["bound_tolerance"]}
        assert all(0.0 < r["peak_velocity_max"] <= 0.75 for r in mine)
    # the front: comfort better as its weight grows, road holding worse
    front = quick.front
    assert front is not None
    assert front["comfort_ratio"] == sorted(front["comfort_ratio"], reverse=True)
    assert front["road_holding_ratio"] == sorted(front["road_holding_ratio"])


def test_a_whole_vehicle_law_on_the_full_car_only(quick: S.BenchmarkResult) -> None:
    """The quick set's ``vehicle-lq`` beside per-corner laws on both vehicles: tuned on the
    full car, scored there only (the quarter car has no row of it, not a NaN row)."""
    spec = quick.spec
    assert "vehicle-lq" in spec.laws
    assert set(spec.vehicles) == {"quarter", "full"}
    mine = [r for r in quick.rows if r["law"] == "vehicle-lq"]
    assert {r["vehicle"] for r in mine} == {"full"}
    assert len(mine) == len(spec.roads) * len(spec.speeds)
    assert "vehicle-lq" not in quick.tuned
    tuned = quick.tuned_full["vehicle-lq"]
    assert (tuned["vehicle"], tuned["option"]) == ("full", "force_weight")
    assert 1e-8 <= tuned["value"] <= 1e-4
    assert tuned["evaluations"] == spec.evaluations
    for r in mine:
        assert (r["option"], r["value"]) == ("force_weight", tuned["value"])
        assert r["bounded"]
        for k in ("comfort", "road_holding", "rattle", "cost"):
            assert math.isfinite(r[k]), (r, k)
            assert r[k] > 0.0, (r, k)
        assert r["coil_power"] > 0.0  # it switches the dampers' current
        assert math.isnan(r["optimum_cost"])  # no optimum on the full car
        # the law acts: not the passive car's numbers
        assert r["cost"] != pytest.approx(sum(spec.weights), rel=1e-6)
    # a per-corner law keeps running on both vehicles
    assert {r["vehicle"] for r in quick.rows if r["law"] == "skyhook-hilo"} == {"quarter", "full"}
    # in the summary's tuned options, the full car's figure and the JSON
    assert "vehicle-lq force_weight" in quick.summary().split("on the full car:")[1]
    # a spec of the full car alone: nothing tuned on the quarter car, no optimum
    alone = S.BenchmarkResult(**{**quick.__dict__, "tuned": {}, "optima": []}).summary()
    assert "50 km/h: on the full car: passive current = " in alone
    assert "no optimum (it is the quarter car's): no law held to the bound" in alone
    labels = quick.figure("full").axes[0].get_legend_handles_labels()[1]
    assert "vehicle-lq" in labels
    data = json.loads(json.dumps(quick.to_dict(), allow_nan=False))
    assert "vehicle-lq" in data["tuned_full"]
    assert "vehicle-lq" not in data["tuned"]
    assert {r["vehicle"] for r in data["rows"] if r["law"] == "vehicle-lq"} == {"full"}


def test_result_table_frame_and_figure(quick: S.BenchmarkResult) -> None:
    df = quick.to_pandas()
    assert {"law", "vehicle", "comfort_ratio", "distance", "coil_power"} <= set(df.columns)
    best = quick.best()
    assert len(best) == len(quick.spec.roads) * len(quick.spec.speeds) * len(quick.spec.vehicles)
    for b in best:  # the lowest cost among the laws through the MR damper
        costs = [
            r["cost"]
            for r in quick.rows
            if r["bounded"]
            and (r["vehicle"], r["road"], r["speed"]) == (b["vehicle"], b["road"], b["speed"])
        ]
        assert b["cost"] == min(costs)
        assert b["best"] != "ideal-skyhook"
    assert "best law" in quick.best_table()
    assert "by more than its record's tolerance" in quick.summary()
    fig = quick.figure("quarter")
    labels = fig.axes[0].get_legend_handles_labels()[1]
    assert "optimum (Pareto front)" in labels
    assert "skyhook-hilo" in labels
    json.dumps(quick.to_dict(), allow_nan=False)


# -- the command line --------------------------------------------------------------------------
def _given(monkeypatch: pytest.MonkeyPatch, result: S.BenchmarkResult) -> list[Any]:
    calls: list[Any] = []

    def fake(spec: BenchmarkSpec, **kw: Any) -> S.BenchmarkResult:
        calls.append((spec, kw))
        return result

    monkeypatch.setattr(S, "run_benchmark", fake)
    return calls


def test_cli_json_and_out(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, quick: S.BenchmarkResult
) -> None:
    calls = _given(monkeypatch, quick)
    out = tmp_path / "bm"
    res = runner.invoke(
        app, ["benchmark", "--quick", "--json", "--out", str(out), "--workers", "1"]
    )
    assert res.exit_code == 0, res.output
    data = json.loads(res.stdout)
    assert len(data["rows"]) == len(quick.rows)
    assert data["violations"] == []
    assert calls[0][0] == BenchmarkSpec.quick()
    assert calls[0][1]["workers"] == 1
    names = sorted(p.name for p in out.iterdir() if not p.name.startswith("."))
    assert names == [
        "benchmark.csv",
        "benchmark.json",
        "best.csv",
        "tradeoff-full.png",
        "tradeoff-quarter.png",
    ]
    assert sorted(Path(f).name for f in data["files"]) == names
    assert (out / "benchmark.csv").read_text().count("\n") == len(quick.rows) + 1
    # plain text: the best-law table
    res = runner.invoke(app, ["benchmark", "--quick"])
    assert res.exit_code == 0
    assert "best law" in res.stdout


def test_cli_spec_file_and_errors(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, quick: S.BenchmarkResult
) -> None:
    calls = _given(monkeypatch, quick)
    spec = tmp_path / "b.toml"
    spec.write_text('laws = ["passive", "skyhook-hilo"]\nspeeds = [80.0]\nvehicles = ["quarter"]\n')
    res = runner.invoke(app, ["benchmark", str(spec), "--json"])
    assert res.exit_code == 0, res.output
    assert calls[-1][0].laws == ("passive", "skyhook-hilo")
    assert calls[-1][0].speeds == (80.0,)
    spec.write_text('laws = ["passive", "skyhook-hi-lo"]\n')
    res = runner.invoke(app, ["benchmark", str(spec)])
    assert res.exit_code == 2
    assert res.stderr.startswith("error: laws: unknown controller law 'skyhook-hi-lo'")
    assert res.stderr.count("\n") == 1
    res = runner.invoke(app, ["benchmark", "--workers", "0"])
    assert res.exit_code == 2
    assert "--workers" in res.stderr
    # a law below the optimum: reported, exit 1
    bad = S.BenchmarkResult(**{**quick.__dict__, "violations": ["x on r costs less"]})
    _given(monkeypatch, bad)
    res = runner.invoke(app, ["benchmark", "--quick"])
    assert res.exit_code == 1
    assert "error: bound violated: x on r costs less" in res.stderr


# -- the report section ------------------------------------------------------------------------
def test_report_section(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, quick: S.BenchmarkResult
) -> None:
    from mrsuspension.report import benchmark as B
    from mrsuspension.report.chapters import SECTIONS
    from mrsuspension.report.html import _TITLES
    from mrsuspension.report.merge import PART_ORDER

    assert "benchmark" in SECTIONS
    assert "benchmark" in PART_ORDER
    assert _TITLES["benchmark"] == "Benchmark of semi-active laws"
    calls = _given(monkeypatch, quick)
    body, info = B.build(tmp_path / "benchmark", True, lambda _msg: None, check=True)
    assert calls[0][0] == B.report_spec(True) == BenchmarkSpec.quick()
    assert "<h2 id='benchmark'>Benchmark of semi-active laws</h2>" in body
    assert [f["number"] for f in info["figures"]] == ["BM.1", "BM.2"]
    for f in info["figures"]:
        assert f["layout issues"] == []
        assert (tmp_path / "benchmark" / f["files"][0]).stat().st_size > 5000
    assert (tmp_path / "benchmark" / "best.csv").is_file()
    # the sentences' numbers are the rows'
    near = min(
        (r for r in quick.rows if r["vehicle"] == "quarter" and r["bounded"]),
        key=lambda r: r["distance"],
    )
    assert f"{100 * near['distance']:.1f} %" in " ".join(info["sentences"])
    assert "the bound holds" in body


def test_runs_are_scored_from_every_step_not_an_aliased_record() -> None:
    """``mpc-hilo`` switches its current from one engine step to the next after the bump;
    a record of one step in two sees only one phase of it, and its Wk rms falls (measured
    on the default 4 s bump at 50 km/h: 0.223 against 0.380 m/s^2, which put the law 36 %
    below the optimum). The benchmark records every step."""
    pytest.importorskip("osqp")
    exc = S.BenchmarkRoad("bump", "bump", height=0.03, length=0.5).excitation("quarter", 50.0, 1.5)
    tables = S._scenario("mpc-hilo", {"w_force": 1.349e-5}, "quarter", exc, 1.5)
    for vehicle, dt in S.ENGINE_DT.items():
        rate = S._scenario("passive", {}, vehicle, exc, 1.5)["simulation"]["output_rate"]
        assert rate == pytest.approx(1.0 / dt)
    full = S._score_task(("quarter", "mpc-hilo", tables))
    half_tables = {**tables, "simulation": {**tables["simulation"], "output_rate": 1000.0}}
    half = S._score_task(("quarter", "mpc-hilo", half_tables))
    assert full is not None
    assert half is not None
    assert half["comfort"] < 0.8 * full["comfort"], (half, full)  # the alias the rate avoids
    assert half["road_holding"] == pytest.approx(full["road_holding"], rel=0.02)


def test_an_optimum_that_did_not_converge_is_named_and_bounds_nothing(
    quick: S.BenchmarkResult,
) -> None:
    """IPOPT at its iteration limit (4 of 14 envelope-band solves of the default set) leaves
    its last iterate: the summary says so and no law is held to it."""
    import dataclasses

    first = quick.optima[0]
    assert first["success"]
    assert all(r["optimum_converged"] for r in quick.rows if r["vehicle"] == "quarter")
    stopped = {**first, "success": False, "status": "Maximum_Iterations_Exceeded"}
    below = [
        {**r, "optimum_converged": False, "optimum_cost": 10.0}
        for r in quick.rows
        if r["vehicle"] == "quarter" and r["bounded"]
    ]
    assert bound_violations([{**r, "optimum_converged": True} for r in below])
    assert bound_violations(below) == []
    result = dataclasses.replace(quick, optima=[stopped, *quick.optima[1:]])
    text = result.summary()
    assert "the optimum did not converge on " + first["road"] in text
    assert "Maximum_Iterations_Exceeded" in text
    assert "not a bound" in text
