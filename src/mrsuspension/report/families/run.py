"""Running units: :func:`run_unit` simulates one :class:`~.spec.Unit` and reduces it to a
payload (the arrays and numbers the figures and tables need, keyed as they read them:
:data:`STATIC_LOAD`, :data:`CLAMP_KEY`, ...).

Runs in the report's worker processes (:func:`~mrsuspension.report.families.pool.build_all`
sends it there by module path).
"""

from __future__ import annotations

import time
from collections.abc import Mapping
from typing import Any

import numpy as np

from mrsuspension.errors import ValidationError
from mrsuspension.report.families.spec import (
    FREQ_PANELS,
    HARMONIC_DURATION,
    PSD_SIGNALS,
    PULSE_DURATION,
    SIGNALS,
    Unit,
)
from mrsuspension.report.toolkit import SHOCK, SHOWN, STEADY_FROM


def _simulate(unit: Unit, duration: float | None) -> Any:
    from mrsuspension.engine.simulate import run_many
    from mrsuspension.scenario import Scenario

    data = {**unit.scenario, "simulation": {"dt": unit.dt}}
    scenario = Scenario.from_dict(data)
    length = duration if duration is not None else float(scenario.excitations[0].duration)
    (result,) = run_many(
        scenario.simulations(), duration=length, dt=unit.dt, output_rate=1000.0, workers=1
    )
    return result


def _finite(values: Any) -> list[float]:
    return [float(v) for v in np.asarray(values, dtype=float)]


def _history_payload(r: Any, window: tuple[float, float], every: int) -> dict[str, Any]:
    t = np.asarray(r.time)
    w = (t >= window[0]) & (t <= window[1])
    out: dict[str, Any] = {"time": t[w][::every]}
    for name, (key, _) in SIGNALS.items():
        y = np.asarray(r[key], dtype=float)
        if np.any(np.isnan(y[w])):
            continue
        out[name] = y[w][::every]
        out[f"peak {name}"] = float(np.nanmax(np.abs(y[w])))
    return out


#: Pulse payload key: the run's static tire load (m_s + m_u) g [N], for the DTR
STATIC_LOAD = "static load [N]"


#: payload and figure-data key: the largest share of a run [%] with v_m at its upper clamp
CLAMP_KEY = "time at v_m clamp [%]"


def _static_load(tables: Mapping[str, Any]) -> float:
    from mrsuspension.vehicle import QuarterCar

    return float(QuarterCar(**tables.get("vehicle", {})).static_load)


def run_unit(unit: Unit) -> dict[str, Any]:
    """Run one unit and reduce it to what the figures and tables need.

    Parameters
    ----------
    unit : Unit
        From :func:`make_unit`.

    Returns
    -------
    dict
        Arrays and numbers: ``time`` and the :data:`SIGNALS` traces (time, pulse), PSDs and
        the ``i_d`` history (psd), frequency-response curves (freq), plus measures and
        ``run time [s]``.
    """
    start, cpu = time.perf_counter(), time.process_time()
    out: dict[str, Any]
    if unit.kind == "time":
        from mrsuspension.measures import asymmetry_ratio, force_tracking_error

        r = _simulate(unit, HARMONIC_DURATION)
        out = _history_payload(r, SHOWN, 1)
        steady = np.asarray(r.time >= STEADY_FROM)
        out["mean current [A]"] = float(np.mean(r.i_d[steady]))
        out["gamma"] = float(asymmetry_ratio(r.F_d[steady]))
        out["max |di_d| per ms [A]"] = float(np.max(np.abs(np.diff(r.i_d[steady]))))
        target = np.asarray(r.F_target[steady])
        if not np.any(np.isnan(target)):
            out["force-tracking error [N]"] = float(
                force_tracking_error(r.F_d[steady], target, r.z_c[steady])
            )
    elif unit.kind == "pulse":
        r = _simulate(unit, PULSE_DURATION)
        out = _history_payload(r, (0.0, PULSE_DURATION), 2)
        m = r.measures()  # SAR_s, SAR_u over the after-onset road acceleration peak
        out.update({k: float(m[k]) for k in (*SHOCK, "peak_tire_force")})
        out["road_peak"] = m["road_peak"]
        out[STATIC_LOAD] = _static_load(unit.scenario)
    elif unit.kind == "psd":
        from mrsuspension.measures import psd

        r = _simulate(unit, None)
        fs = 1.0 / float(r.time[1] - r.time[0])
        out = {}
        for name in PSD_SIGNALS:
            f, p = psd(np.asarray(r[SIGNALS[name][0]]), fs, warn=False)
            band = (f > 0) & (f <= 25.0)
            out["frequency"] = np.asarray(f)[band]
            out[f"PSD {name}"] = np.asarray(p)[band]
        out["time"] = np.asarray(r.time)[::20]
        out["i_d"] = np.asarray(r.i_d)[::20]
        m = r.measures()
        out["DLC"] = float(m["DLC"])  # std(F_T) over the mean tire force: the run's own load
        out["std F_T [N]"] = float(np.std(np.asarray(r.F_T)))
        out[STATIC_LOAD] = _static_load(unit.scenario)
        out["rms a_s [m/s^2]"] = float(m["rms_body_acceleration"])
        out["mean current [A]"] = float(m.get("mean_current", np.nan))  # n/a: linear damper
    elif unit.kind == "freq":
        from mrsuspension.studies import Study, run_study

        data = {
            "study": {
                "name": "report",
                "measures": [*(k for k, _ in FREQ_PANELS), "vm_clamp_fraction"],
            },
            **unit.scenario,
            "simulation": {"dt": unit.dt},
        }
        exc = dict(data["excitation"])
        exc.setdefault("frequencies", "log:10:0.5:15" if unit.dt > 1e-4 else "log:30:0.5:15")
        data["excitation"] = exc
        result = run_study(Study.from_dict(data), workers=1, progress=False, cache_dir=False)
        ds = result.to_xarray()
        dims = [d for d in ds["T_as"].dims if d != "frequency"]
        ds = ds.isel({d: 0 for d in dims})
        out = {"frequency": np.asarray(ds["frequency"].values, dtype=float)}
        for key, _ in FREQ_PANELS:
            out[key] = np.asarray(ds[key].values, dtype=float)
    else:
        raise ValidationError(
            f"unit kind {unit.kind!r} is not valid; valid: time, freq, pulse, psd"
        )
    out[CLAMP_KEY] = 100.0 * (
        float(np.nanmax(ds["vm_clamp_fraction"].values))
        if unit.kind == "freq"
        else r.velocity_clamp_fraction
    )
    out["run time [s]"] = time.perf_counter() - start
    out["run cpu time [s]"] = time.process_time() - cpu
    return out
