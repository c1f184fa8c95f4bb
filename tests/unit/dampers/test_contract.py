"""The contract every damper model passes, and the parameter-set registry.

``TestDamperContract`` runs once per entry of :data:`mrsuspension.dampers.DAMPERS`, built
with its defaults (``make_damper(name)``): a new model is covered by registering it.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from _helpers import raises_validation as _raises
from mrsuspension import parameters
from mrsuspension.dampers import (
    DAMPERS,
    Bingham,
    KnownPeak,
    LinearViscous,
    SpencerBoucWen,
    WangAsymmetric,
    WangSymmetric,
    make_damper,
)
from mrsuspension.dampers import kernels as K
from mrsuspension.parameters import ParameterSet


@pytest.fixture(scope="module", params=sorted(DAMPERS))
def model(request):
    return make_damper(request.param)


class TestDamperContract:
    # -- shapes and values -------------------------------------------------------------
    def test_scalar_inputs_give_a_scalar(self, model):
        f = model.force(0.01, 0.2, -3.0, 0.1)
        assert type(f) is float  # scalar in, scalar out: round(f), f"{f:.1f}" work
        assert np.isfinite(f)
        assert round(f) == round(float(model.force([0.01], 0.2, -3.0, 0.1)[0]))

    def test_one_dimensional_inputs(self, model):
        v = np.linspace(-1.0, 1.0, 11)
        assert model.force(0.0, v).shape == (11,)
        assert model.force(np.zeros(11), v, np.ones(11), np.full(11, 0.2)).shape == (11,)
        assert model.force(0.0, 0.3, 0.0, np.linspace(0.0, 0.5, 4)).shape == (4,)

    def test_two_dimensional_broadcast(self, model):
        v = np.linspace(-1.0, 1.0, 5).reshape(5, 1)
        i = np.linspace(0.0, model.max_current, 3).reshape(1, 3)
        f = model.force(0.0, v, 0.0, i)
        assert f.shape == (5, 3)
        # each element is the force of its own inputs
        for r in range(5):
            for c in range(3):
                single = float(model.force(0.0, float(v[r, 0]), 0.0, float(i[0, c])))
                assert f[r, c] == pytest.approx(single, rel=1e-12, abs=1e-9)
        x = np.linspace(-0.02, 0.02, 12).reshape(3, 4)
        assert model.force(x, 0.1, 0.0, 0.0).shape == (3, 4)
        assert model.force(x, v[:3], 0.0, 0.0).shape == (3, 4)

    def test_shapes_that_do_not_broadcast_are_rejected(self, model):
        _raises(lambda: model.force(np.zeros(3), np.zeros(4)), "broadcast", "(3,)", "(4,)")

    def test_finite_over_a_grid(self, model):
        x, v, a, i = np.meshgrid(
            np.linspace(-0.05, 0.05, 5),
            np.linspace(-1.5, 1.5, 31),
            np.array([-200.0, -1.0, 0.0, 1.0, 200.0]),
            np.linspace(0.0, model.max_current, 5),
            indexing="ij",
        )
        f = model.force(x, v, a, i)
        assert f.shape == x.shape
        assert np.all(np.isfinite(f))

    @pytest.mark.parametrize("fraction", [0.0, 0.5])
    def test_sign_convention(self, model, fraction):
        # model reference, section 1: positive velocity is compression, a positive force resists it
        i = fraction * model.max_current
        assert float(model.force(0.0, 0.5, 0.0, i)) > 0.0
        assert float(model.force(0.0, -0.5, 0.0, i)) < 0.0

    @pytest.mark.parametrize("fraction", [0.0, 0.5, 1.0])
    def test_force_is_continuous_in_velocity_away_from_zero(self, model, fraction):
        i = fraction * model.max_current
        for lo, hi in ((0.05, 1.0), (-1.0, -0.05)):
            v = np.linspace(lo, hi, 2001)
            f = model.force(0.0, v, 0.0, i)
            scale = np.abs(f).max()
            assert scale > 0
            # step dv = 4.75e-4 m/s: a smooth force changes by well under 1 % of its range
            assert np.abs(np.diff(f)).max() < 0.01 * scale

    def test_harmonic_response_dissipates_energy(self, model):
        # 1.5 Hz, 12.5 mm, three cycles, exact derivatives
        w = 2.0 * math.pi * 1.5
        t = np.arange(0.0, 2.0, 1e-4)
        x = 0.0125 * np.sin(w * t)
        for current in (0.0, 0.5 * model.max_current):
            r = model.response(
                t, x, 0.0125 * w * np.cos(w * t), -0.0125 * w * w * np.sin(w * t), current
            )
            assert r.force.shape == t.shape
            assert np.all(np.isfinite(r.force))
            assert r.dissipated_energy() > 0.0
            # velocity and acceleration derived from the stroke when not given
            r2 = model.response(t, x, current=current)
            assert r2.dissipated_energy() > 0.0

    def test_kernel_arrays(self, model):
        kern = model.kernel(1e-3)
        assert kern.kind == model.kind
        assert kern.kind in (K.LINEAR, K.BINGHAM, K.WANG, K.SPENCER)
        assert isinstance(kern.estimator_code, int)
        for arr in (kern.params, kern.state, kern.estimator_params, kern.estimator_state):
            assert isinstance(arr, np.ndarray)
            assert arr.dtype == np.float64
            assert arr.ndim == 1
        assert kern.state.shape == (K.STATE_SIZE,)
        assert np.all(kern.state == 0.0)  # a fresh state
        assert kern.max_current == model.max_current
        # each kernel view owns its state
        other = model.kernel(1e-3)
        assert not np.shares_memory(kern.state, other.state)
        assert not np.shares_memory(kern.params, other.params)

    def test_kernel_stepping_reproduces_response(self, model):
        # the engine's path (sample, force, advance per step) is the response() path
        dt = 1e-4
        w = 2.0 * math.pi * 2.0
        t = np.arange(0.0, 0.3, dt)
        x, v, a = 0.01 * np.sin(w * t), 0.01 * w * np.cos(w * t), -0.01 * w * w * np.sin(w * t)
        i = 0.2 * model.max_current * (1.0 + np.sin(3.0 * t))
        expected = model.response(t, x, v, a, i).force
        kern = model.kernel(dt)
        got = np.empty_like(t)
        for k in range(t.size):
            K.damper_sample(
                kern.kind, kern.params, kern.state, kern.estimator_code, kern.estimator_params,
                kern.estimator_state, x[k], v[k], a[k], i[k],
            )  # fmt: skip
            got[k] = K.damper_force(kern.kind, kern.params, kern.state, x[k], v[k], i[k])
            K.damper_advance(kern.kind, kern.params, kern.state, x[k], v[k], i[k], dt)
        np.testing.assert_allclose(got, expected, rtol=1e-12, atol=1e-9)

    def test_response_and_force_agree(self, model):
        # force() is the force of a freshly reset damper: the first sample of response();
        # without memory, every sample of response() is force() at that sample
        rng = np.random.default_rng(9)
        n = 400
        t = np.arange(n) * 1e-3
        x, v = rng.uniform(-0.03, 0.03, n), rng.uniform(-1.2, 1.2, n)
        a, i = rng.uniform(-40, 40, n), rng.uniform(0.0, model.max_current, n)
        first = model.response(t, x, v, a, i).force[0]
        assert first == pytest.approx(float(model.force(x[0], v[0], a[0], i[0])), rel=1e-12)
        memoryless = model
        if isinstance(model, WangSymmetric):
            memoryless = model.with_options(estimator=KnownPeak(0.4))
        if not memoryless.stateful:
            np.testing.assert_allclose(
                memoryless.response(t, x, v, a, i).force,
                memoryless.force(x, v, a, i),
                rtol=1e-12,
                atol=1e-9,
            )

    # -- bad inputs --------------------------------------------------------------------
    @pytest.mark.parametrize("field", ["stroke", "velocity", "acceleration"])
    @pytest.mark.parametrize("bad", [math.nan, math.inf, -math.inf])
    def test_non_finite_motion_is_rejected(self, model, field, bad):
        args = {"stroke": 0.0, "velocity": 0.1, "acceleration": 0.0}
        args[field] = np.array([0.0, bad])
        message = _raises(lambda: model.force(**args), field, "finite", "index 1")
        assert str(bad) in message

    @pytest.mark.parametrize("bad", [math.nan, math.inf, -0.1, 0.51, 5.0])
    def test_bad_current_is_rejected(self, model, bad):
        rng = f"[0, {model.max_current:g}]"
        message = _raises(lambda: model.force(0.0, 0.1, 0.0, bad), "drive current", rng, "A")
        assert f"{bad:g}" in message
        # and in response(), as a series
        t = np.arange(5) * 1e-3
        _raises(
            lambda: model.response(t, 0.0, 0.1, 0.0, [0.0, 0.1, bad, 0.2, 0.3]),
            "drive current",
            rng,
        )

    def test_max_current_option(self, model):
        m = type(model)(max_current=0.3)
        assert m.max_current == 0.3
        _raises(lambda: m.force(0.0, 0.1, 0.0, 0.4), "drive current", "[0, 0.3]", "0.4")
        _raises(lambda: type(model)(max_current=0.0), "max_current", "(0, 10]")

    @pytest.mark.parametrize(
        ("time", "fragments"),
        [
            ([0.0, 0.1, 0.3, 0.4], ["uniformly sampled"]),
            ([0.0, 0.1, 0.1, 0.2], ["uniformly sampled"]),
            ([0.3, 0.2, 0.1, 0.0], ["increasing"]),
            ([0.0, math.nan, 0.2, 0.3], ["time", "finite", "nan"]),
            ([0.0, 0.1, 0.2, math.inf], ["time", "finite", "inf"]),
            ([0.0], ["time", "at least 2"]),
            ([[0.0, 0.1], [0.2, 0.3]], ["time", "1-D"]),
        ],
    )
    def test_bad_time_is_rejected(self, model, time, fragments):
        _raises(lambda: model.response(time, 0.0, 0.1), *fragments)

    def test_series_of_the_wrong_length_is_rejected(self, model):
        t = np.arange(10) * 1e-3
        _raises(lambda: model.response(t, np.zeros(9)), "stroke", "(10,)", "(9,)")
        _raises(lambda: model.response(t, np.zeros(10), np.zeros(3)), "velocity", "(10,)")


# ----------------------------------------------------------------------------------
# peer models: hand values from their published sets (model reference, section 2.5)
def test_linear_hand_value():
    assert float(make_damper("linear").force(0.0, 0.3)) == 2500.0 * 0.3
    assert float(LinearViscous(damping=1234.0).force(0.02, -0.5, 9.0, 0.4)) == -617.0


@pytest.mark.parametrize(("v", "i"), [(0.3, 0.0), (0.3, 0.2), (-0.3, 0.2), (-0.05, 0.5)])
def test_bingham_hand_value(v, i):
    # F = (fc_a + fc_b i) sgn(v) + (c0_a + c0_b i) v + f0, set "bingham-wang-low"
    fc_a, fc_b, c0_a, c0_b, f0 = 109.684, 798.235, 2043.48, 17138.8, -0.208535
    expected = (fc_a + fc_b * i) * math.copysign(1.0, v) + (c0_a + c0_b * i) * v + f0
    model = Bingham()
    assert float(model.force(0.0, v, 0.0, i)) == pytest.approx(expected, rel=1e-12)
    t = np.arange(3) * 1e-3
    r = model.response(t, 0.0, v, 0.0, i)
    np.testing.assert_allclose(r.force, expected, rtol=1e-12)


@pytest.mark.parametrize(("x", "v", "i"), [(0.0, 0.3, 0.0), (0.01, -0.2, 0.25), (-0.02, 0.5, 0.5)])
def test_spencer_fresh_damper_hand_value(x, v, i):
    # fresh damper: y = x, z = 0, u = 4.5 V/A * i settled, so
    # F = c1 y' + k1 (x - x0) with y' = c0 v / (c0 + c1)
    u = 4.5 * i
    c0, c1 = 2100.0 + 350.0 * u, 28300.0 + 295.0 * u
    expected = c1 * c0 * v / (c0 + c1) + 500.0 * (x - 0.143)
    assert float(SpencerBoucWen().force(x, v, 0.0, i)) == pytest.approx(expected, rel=1e-12)


# ----------------------------------------------------------------------------------
# model registry
def test_registry_holds_every_model():
    expected = {
        "wang-symmetric": WangSymmetric,
        "wang-asymmetric": WangAsymmetric,
        "bingham": Bingham,
        "spencer": SpencerBoucWen,
        "linear": LinearViscous,
    }
    assert dict(DAMPERS) == expected


def test_make_damper_errors():
    _raises(lambda: make_damper("wang-symetric"), "wang-symetric", "Did you mean 'wang-symmetric'?")
    _raises(lambda: make_damper("wang-symmetric", hysterisis=False), "hysterisis")
    _raises(lambda: make_damper("linear", dampin=1.0), "'linear'", "dampin")
    _raises(
        lambda: make_damper("wang-symmetric", "wang-symetric-low"),
        "Did you mean 'wang-symmetric-low'?",
    )


# ----------------------------------------------------------------------------------
# parameter registry
PUBLISHED = [
    "bingham-wang-low",
    "linear-2500",
    "spencer-1997",
    "wang-asymmetric",
    "wang-symmetric-high",
    "wang-symmetric-low",
]


def test_available_lists_the_six_published_sets():
    assert parameters.available() == PUBLISHED


def test_get_with_a_typo_suggests_the_name():
    _raises(
        lambda: parameters.get("wang-symetric-low"),
        "unknown parameter set 'wang-symetric-low'",
        "Did you mean 'wang-symmetric-low'?",
    )
    _raises(lambda: parameters.get("spencer1997"), "Did you mean 'spencer-1997'?")


@pytest.mark.parametrize("name", PUBLISHED)
def test_every_published_set_has_provenance_and_units(name):
    pset = parameters.get(name)
    assert pset.name == name
    assert pset.source.strip()
    assert pset.table.strip()
    assert pset.description.strip()
    assert len(pset) > 0
    for key in pset:
        assert pset.units.get(key, "").strip(), f"{name}: no unit for {key!r}"
        assert pset.descriptions.get(key, "").strip(), f"{name}: no description for {key!r}"
        assert math.isfinite(pset[key])


@pytest.mark.parametrize("name", PUBLISHED)
def test_every_published_set_builds_its_model(name):
    pset = parameters.get(name)
    model = make_damper(pset.model, name)
    assert model.parameters.name == name
    assert np.isfinite(model.force(0.0, 0.3, 0.0, 0.1))


def test_wang_set_provenance_names_its_table():
    assert parameters.get("wang-symmetric-low").table == "2.2"
    assert parameters.get("wang-symmetric-high").table == "2.2"
    assert parameters.get("wang-asymmetric").table == "2.3"
    assert parameters.get("wang-symmetric-low").frequency_range == (0.5, 5.0)
    assert parameters.get("wang-symmetric-high").frequency_range == (5.0, 15.0)


def test_load_user_toml(tmp_path):
    path = tmp_path / "my-damper.toml"
    path.write_text(
        'model = "linear"\nsource = "bench test 3"\n'
        '[parameters]\nc = { value = 1800.0, unit = "N s/m", description = "slope" }\n'
    )
    pset = parameters.load(path)
    assert pset.name == "my-damper"
    assert pset.model == "linear"
    assert pset["c"] == 1800.0
    assert pset.units["c"] == "N s/m"
    assert pset.source == "bench test 3"
    model = LinearViscous(path)
    assert float(model.force(0.0, 0.5)) == 900.0
    # a path given as a string works wherever a set name does
    assert float(make_damper("linear", str(path)).force(0.0, -0.5)) == -900.0


def test_load_user_json(tmp_path):
    path = tmp_path / "bench.json"
    values = dict(parameters.get("wang-symmetric-low").values)
    values["F0"] = 100.0
    path.write_text(json.dumps({"name": "bench", "model": "wang-symmetric", "parameters": values}))
    pset = parameters.load(path)
    assert pset.name == "bench"
    assert pset["F0"] == 100.0
    model = WangSymmetric(str(path), hysteresis=False)
    # F0 enters linearly: the force scales with it (eq. 2.7)
    ref = WangSymmetric("wang-symmetric-low", hysteresis=False)
    ratio = float(model.force(0.0, 0.2, 0.0, 0.1, peak_velocity=0.3)) / float(
        ref.force(0.0, 0.2, 0.0, 0.1, peak_velocity=0.3)
    )
    assert ratio == pytest.approx(100.0 / 68.506, rel=1e-12)


@pytest.mark.parametrize(
    ("filename", "content", "fragments"),
    [
        ("bad.toml", 'model = "linear"\n[parameters\nc = 1.0\n', ["not valid TOML"]),
        ("bad.json", '{"model": "linear", "parameters": {"c": 1.0}', ["not valid JSON"]),
        ("noparams.toml", 'model = "linear"\n', ["missing required key 'parameters'"]),
        ("nomodel.toml", "[parameters]\nc = 1.0\n", ["missing required key 'model'"]),
        ("empty.toml", 'model = "linear"\n[parameters]\n', ["'parameters' must be a non-empty"]),
        (
            "text.toml",
            'model = "linear"\n[parameters]\nc = "fast"\n',
            ["'c'", "must be a number", "fast"],
        ),
        (
            "bool.json",
            '{"model": "linear", "parameters": {"c": true}}',
            ["'c'", "must be a number"],
        ),
        ("nan.json", '{"model": "linear", "parameters": {"c": NaN}}', ["'c'", "finite", "nan"]),
        ("inf.toml", 'model = "linear"\n[parameters]\nc = inf\n', ["'c'", "finite", "inf"]),
        (
            "novalue.toml",
            'model = "linear"\n[parameters]\nc = { unit = "N s/m" }\n',
            ["'c'", "no 'value'"],
        ),
        (
            "extra.toml",
            'model = "linear"\nsoruce = "x"\n[parameters]\nc = 1.0\n',
            ["soruce", "Did you mean 'source'?"],
        ),
        ("list.json", "[1, 2, 3]", ["table"]),
        (
            "range.toml",
            'model = "linear"\nfrequency_range = [5.0, 1.0]\n[parameters]\nc = 1.0\n',
            ["frequency_range"],
        ),
        (
            "imax.toml",
            'model = "linear"\nmax_current = -1.0\n[parameters]\nc = 1.0\n',
            ["max_current", "(0, 10]"],
        ),
        ("params.yaml", "model: linear\n", ["unsupported extension", ".yaml"]),
    ],
)
def test_malformed_files_are_reported_with_the_file_and_the_problem(
    tmp_path, filename, content, fragments
):
    path = tmp_path / filename
    path.write_text(content)
    _raises(lambda: parameters.load(path), str(path), *fragments)


def test_missing_file_is_reported(tmp_path):
    path = tmp_path / "nowhere.toml"
    _raises(lambda: parameters.load(path), str(path), "does not exist")
    _raises(lambda: WangSymmetric(str(path)), str(path), "does not exist")


def test_a_set_of_another_family_is_rejected():
    _raises(lambda: WangSymmetric("linear-2500"), "'linear-2500'", "'linear'", "wang-symmetric")
    _raises(lambda: WangSymmetric("wang-asymmetric"), "'wang-asymmetric'", "accepts")
    _raises(lambda: LinearViscous("wang-symmetric-low"), "'wang-symmetric-low'", "'linear'")
    _raises(lambda: SpencerBoucWen("bingham-wang-low"), "'bingham-wang-low'", "spencer")
    _raises(lambda: Bingham("spencer-1997"), "'spencer-1997'", "bingham")


def test_a_missing_parameter_is_reported_by_name():
    values = {k: v for k, v in parameters.get("wang-symmetric-low").items() if k != "k4"}
    _raises(lambda: WangSymmetric(values), "'k4'", "lacks")
    asym = {k: v for k, v in parameters.get("wang-asymmetric").items() if k != "k1e"}
    _raises(lambda: WangAsymmetric(asym), "'k1e'", "lacks")
    _raises(lambda: LinearViscous({"d": 1.0}), "'d'")


def test_an_unknown_or_invalid_parameter_is_reported_by_name():
    values = dict(parameters.get("wang-symmetric-low").values)
    values["k44"] = 1.0
    _raises(lambda: WangSymmetric(values), "'k44'", "Did you mean 'k4'?")
    _raises(lambda: LinearViscous({"c": -5.0}), "'c'", ">= 0", "-5")
    bad_f0 = dict(parameters.get("wang-symmetric-low").values, F0=0.0)
    _raises(lambda: WangSymmetric(bad_f0), "'F0'", "> 0")
    _raises(
        lambda: parameters.get("wang-symmetric-low").replace(k44=1.0), "'k44'", "Did you mean 'k4'?"
    )


@pytest.mark.parametrize("name", PUBLISHED)
@pytest.mark.parametrize("suffix", [".toml", ".json"])
def test_save_round_trips(tmp_path, name, suffix):
    pset = parameters.get(name)
    path = pset.save(tmp_path / f"copy{suffix}")
    assert path.is_file()
    again = parameters.load(path)
    assert again.to_dict() == pset.to_dict()
    assert dict(again.values) == dict(pset.values)
    assert again.frequency_range == pset.frequency_range


def test_save_round_trips_a_modified_set(tmp_path):
    pset = parameters.get("wang-asymmetric").replace(k5=0.0, F0=81.5)
    for suffix in (".toml", ".json"):
        again = parameters.load(pset.save(tmp_path / f"mod{suffix}"))
        assert again.to_dict() == pset.to_dict()
        assert again["F0"] == 81.5
        assert "modified" in again.source


def test_save_rejects_an_unknown_format(tmp_path):
    _raises(lambda: parameters.get("linear-2500").save(tmp_path / "x.yaml"), "'.yaml'", ".toml")


def test_parameter_set_is_immutable_and_validated():
    pset = ParameterSet(name="mine", model="linear", values={"c": 1.0})
    with pytest.raises(TypeError):
        pset.values["c"] = 2.0  # type: ignore[index]
    _raises(lambda: ParameterSet(name="x", model="linear", values={}), "no parameters")
    _raises(lambda: ParameterSet(name="x", model="linear", values={"c": math.nan}), "'c'", "finite")
    _raises(lambda: ParameterSet(name="", model="linear", values={"c": 1.0}), "name")
