"""Simulation results: named signals with units, exports and plots."""

from __future__ import annotations

import json
from collections.abc import Iterator, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any, TypeVar, overload

import numpy as np
import numpy.typing as npt

from mrsuspension._notebook import Measures, axes_for, html_table, new_figure
from mrsuspension.errors import MRSuspensionError, ValidationError, unknown_name

if TYPE_CHECKING:
    import pandas as pd
    import xarray as xr
    from matplotlib.figure import Figure

    from mrsuspension.measures import RoadPeak

__all__ = [
    "ALIAS_WARN_FRACTION",
    "CLAMP_WARN_FRACTION",
    "CURRENT_MEASURES",
    "MEASURES_BY_KIND",
    "MEASURE_NAMES",
    "MEASURE_NOTES",
    "MEASURE_UNITS",
    "PARQUET_METADATA_KEY",
    "SIGNALS",
    "AliasedRecordWarning",
    "Measures",
    "SimulationDiverged",
    "SimulationResult",
    "VelocityClampWarning",
    "controller_text",
    "describe_run",
    "drop_unused_currents",
    "excitation_text",
    "measure_label",
    "measures_context",
    "pulse_measures",
    "require_pyarrow",
    "road_measures",
    "warn_if_clamped",
]

_A = TypeVar("_A")  # the Axes a plot(..., ax=...) draws into and returns

#: Share of a record with v_m at its upper clamp above which a run warns: beyond it the
#: force model is pinned at the edge of its identified range (model reference, section 2.4).
CLAMP_WARN_FRACTION = 0.05


class VelocityClampWarning(UserWarning):
    """A run spent a large share of its time with v_m at the estimator's upper clamp."""


#: Share of a run's steps whose drive current reverses the previous step's change above
#: which a record that keeps one step in several warns (:func:`warn_if_aliased`)
ALIAS_WARN_FRACTION = 0.05


class AliasedRecordWarning(UserWarning):
    """A run's current alternates at the step rate and its record keeps one step in several."""


#: The numeric measures :meth:`SimulationResult.measures` returns for each measures kind
#: (an excitation class's ``measures_kind``; model reference, section 9);
#: ``vm_clamp_fraction`` is in every kind's. Studies and the optimiser take their measure
#: lists from here.
MEASURES_BY_KIND: dict[str, tuple[str, ...]] = {
    "harmonic": (
        "T_as", "T_au", "T_dr", "T_ds", "T_du", "DLC", "gamma", "mean_current",
        "mean_square_current", "vm_clamp_fraction",
    ),
    "pulse": ("SDR_s", "SAR_s", "SDR_u", "SAR_u", "RDR", "peak_tire_force", "vm_clamp_fraction"),
    "road": (
        "DLC", "rms_body_acceleration", "wk_rms_body_acceleration", "vdv", "rms_stroke",
        "mean_current", "vm_clamp_fraction",
    ),
}  # fmt: skip
#: The measures of the drive current: reported only for a damper that takes one
#: (:func:`~mrsuspension.dampers.takes_current`; a linear damper's runs leave them out).
CURRENT_MEASURES: tuple[str, ...] = ("mean_current", "mean_square_current")
#: Non-numeric entries of :meth:`SimulationResult.measures` by measures kind (how a
#: measure was computed, not a measure).
MEASURE_NOTES: dict[str, tuple[str, ...]] = {"pulse": ("road_peak",)}
#: Unit of every measure in :data:`MEASURES_BY_KIND` ("-": a dimensionless ratio), and of
#: the sweep coordinates ``frequency`` and ``amplitude``; used wherever a measure leaves
#: the program (printouts, ``sweep.csv`` headers, NetCDF ``units``, Parquet metadata).
MEASURE_UNITS: dict[str, str] = {
    "frequency": "Hz",
    "amplitude": "m",
    "T_as": "-",
    "T_au": "-",
    "T_dr": "-",
    "T_ds": "-",
    "T_du": "-",
    "DLC": "-",
    "gamma": "-",
    "mean_current": "A",
    "mean_square_current": "A^2",
    "vm_clamp_fraction": "-",
    "SDR_s": "-",
    "SAR_s": "-",
    "SDR_u": "-",
    "SAR_u": "-",
    "RDR": "-",
    "peak_tire_force": "N",
    "rms_body_acceleration": "m/s^2",
    "wk_rms_body_acceleration": "m/s^2",
    "vdv": "m/s^1.75",
    "rms_stroke": "m",
}
#: What each measure of :data:`MEASURE_UNITS` is, in a few words (the ``long_name`` of
#: a study data set's variables and coordinates; model reference, section 9).
MEASURE_NAMES: dict[str, str] = {
    "frequency": "excitation frequency",
    "amplitude": "excitation amplitude",
    "T_as": "sprung-mass acceleration transmissibility",
    "T_au": "unsprung-mass acceleration transmissibility",
    "T_dr": "stroke over road displacement (rms ratio)",
    "T_ds": "sprung-mass displacement transmissibility",
    "T_du": "unsprung-mass displacement transmissibility",
    "DLC": "dynamic load coefficient (tire force std over load)",
    "gamma": "damper force asymmetry (max rebound over max compression)",
    "mean_current": "mean drive current",
    "mean_square_current": "mean square drive current",
    "vm_clamp_fraction": "share of the record with v_m at its upper clamp",
    "SDR_s": "peak sprung-mass displacement over peak road displacement",
    "SAR_s": "peak sprung-mass acceleration over road acceleration peak",
    "SDR_u": "peak unsprung-mass displacement over peak road displacement",
    "SAR_u": "peak unsprung-mass acceleration over road acceleration peak",
    "RDR": "peak damper stroke over peak road displacement",
    "peak_tire_force": "peak tire force",
    "rms_body_acceleration": "rms body acceleration",
    "wk_rms_body_acceleration": "Wk-weighted rms body acceleration (ISO 2631-1)",
    "vdv": "vibration dose value (ISO 2631-1)",
    "rms_stroke": "rms damper stroke",
}
#: Key of the JSON entry (scenario, ``dt``, units) in a saved Parquet file's schema metadata.
PARQUET_METADATA_KEY = "mrsuspension"


def measure_label(name: str) -> str:
    """``"name [unit]"`` for a measure with a unit in :data:`MEASURE_UNITS`, else ``name``.

    Examples
    --------
    >>> measure_label("vdv"), measure_label("T_as"), measure_label("road_peak")
    ('vdv [m/s^1.75]', 'T_as [-]', 'road_peak')
    """
    unit = MEASURE_UNITS.get(name)
    return name if unit is None else f"{name} [{unit}]"


class SimulationDiverged(MRSuspensionError):
    """A run left the physical range; the message says when and which signal.

    Attributes
    ----------
    time : float
        Simulated time of the first offence [s].
    signal : str
        The signal out of range (``z_s``, ``F_d``, ...).
    value : float
        Its value there.

    Examples
    --------
    >>> err = SimulationDiverged("diverged at t = 1 s", 1.0, "z_s", 11.0)
    >>> err.signal, err.value
    ('z_s', 11.0)
    """

    def __init__(self, message: str, time: float, signal: str, value: float) -> None:
        super().__init__(message)
        self.time = time
        self.signal = signal
        self.value = value


#: Recorded signals: name -> (unit, description).
SIGNALS: dict[str, tuple[str, str]] = {
    "z_s": ("m", "sprung-mass displacement (up)"),
    "z_u": ("m", "unsprung-mass displacement (up)"),
    "z_r": ("m", "road displacement (up)"),
    "z_s_dot": ("m/s", "sprung-mass velocity"),
    "z_u_dot": ("m/s", "unsprung-mass velocity"),
    "z_r_dot": ("m/s", "road velocity"),
    "z_s_ddot": ("m/s^2", "sprung-mass acceleration"),
    "z_u_ddot": ("m/s^2", "unsprung-mass acceleration"),
    "z_r_ddot": ("m/s^2", "road acceleration"),
    "x_d": ("m", "damper stroke z_u - z_s (compression +)"),
    "v_d": ("m/s", "damper velocity (compression +)"),
    "F_d": ("N", "damper force (resists compression +)"),
    "F_T": ("N", "tire force (total, 0 when lifted off)"),
    "i_d": ("A", "drive current"),
    "i_z": ("A", "controller current before shaping"),
    "z_c": ("-", "switching condition (high current when < 0)"),
    "F_target": ("N", "controller target force (NaN if none)"),
    "v_m": ("m/s", "controller peak-velocity estimate"),
    "z_s0": ("m", "sliding-mode reference displacement"),
}


@dataclass(frozen=True)
class SimulationResult(Mapping[str, np.ndarray]):
    """Time histories of one simulation, by signal name (see :data:`SIGNALS`).

    Behaves as a read-only mapping ``name -> array`` and exposes each signal as an
    attribute (``result.z_s``); ``time`` [s] is the common axis. ``scenario`` holds the
    plain-data description of what was simulated.
    """

    time: npt.NDArray[np.float64]
    signals: dict[str, npt.NDArray[np.float64]]
    scenario: dict[str, Any] = field(default_factory=dict)
    dt: float = 0.0

    units: Mapping[str, str] = field(
        default_factory=lambda: {"time": "s", **{k: u for k, (u, _) in SIGNALS.items()}}
    )

    def __getitem__(self, key: str) -> npt.NDArray[np.float64]:
        if key == "time":
            return self.time
        try:
            return self.signals[key]
        except KeyError:
            raise unknown_name("signal", key, ["time", *self.signals]) from None

    def __iter__(self) -> Iterator[str]:
        return iter(["time", *self.signals])

    def __len__(self) -> int:
        return 1 + len(self.signals)

    def __getattr__(self, key: str) -> npt.NDArray[np.float64]:
        signals = self.__dict__.get("signals", {})
        if key in signals:
            return signals[key]
        raise AttributeError(key)

    def __repr__(self) -> str:
        return f"{type(self).__name__}({self._summary_line()})"

    def _summary_line(self) -> str:
        """``"<model>, <controller>, <excitation>: N samples over T s, dt"``."""
        what = ", ".join(
            t for t in (self._model_text(), self._controller_text(),
                        excitation_text(self.scenario)) if t
        )  # fmt: skip
        return f"{what}: {self.time.size} samples over {self._duration():.4g} s, dt {_dt_text(self.dt)}"

    def _duration(self) -> float:
        return float(self.time[-1] - self.time[0]) if self.time.size else 0.0

    def _model_text(self) -> str:
        """The vehicle and the damper, e.g. ``"quarter car, wang-symmetric damper"``."""
        damper = self.scenario.get("damper", {}).get("model")
        return "quarter car" + (f", {damper} damper" if damper else "")

    def _controller_text(self) -> str:
        return controller_text(self.scenario)

    def _summary_rows(self) -> list[tuple[str, str]]:
        """The rows of the HTML summary before the measures."""
        rows = [("model", self._model_text())]
        ctrl = self._controller_text()
        if ctrl:
            rows.append(("controller", ctrl))
        rows.append(("excitation", excitation_text(self.scenario) or "-"))
        rows.append(("duration", f"{self._duration():.4g} s ({self.time.size} samples)"))
        rows.append(("dt", _dt_text(self.dt)))
        return rows

    def _repr_html_(self) -> str:
        """A notebook's view: model, controller, excitation, duration, dt, the measures."""
        head = html_table(self._summary_rows(), caption=type(self).__name__)
        return f"<div>{head}{self._html_measures()}</div>"

    def _html_measures(self) -> str:
        """The measures' table of the HTML summary (or why there is none)."""
        try:
            return self.measures()._repr_html_()
        except Exception as exc:  # a record too short for its measures: say so, still show
            return html_table([("measures", f"not available: {exc}")])

    # -- peak-velocity clamp (model reference, section 2.4) --------------------------------
    @property
    def velocity_clamp_fraction(self) -> float:
        """Share of the record [-] with ``v_m`` at the estimator's upper clamp ``v_max``.

        0 when the estimator has no clamp (``known``) or ``v_m`` was not recorded. A large
        share means the damper model ran at the edge of its identified velocity range
        (model reference, section 2.4); :meth:`Simulation.run` warns above
        :data:`CLAMP_WARN_FRACTION`.
        """
        limit = self.scenario.get("peak_velocity_limit")
        vm = self.signals.get("v_m")
        if limit is None or vm is None or vm.size == 0:
            return 0.0
        return float(np.mean(vm >= float(limit) * (1.0 - 1e-12)))

    @property
    def velocity_clamp_time(self) -> float:
        """Time [s] the record spent with ``v_m`` at the estimator's upper clamp."""
        if self.time.size < 2:
            return 0.0
        return self.velocity_clamp_fraction * float(self.time[-1] - self.time[0])

    # -- measures (model reference, section 9) ---------------------------------------------
    def measures(self, *, road_peak: RoadPeak = "after-onset") -> Measures:
        """The measures suited to the excitation, by their names (model reference, section 9).

        A :class:`~mrsuspension._notebook.Measures`: a ``dict`` whose ``units``
        give each measure's unit (:data:`MEASURE_UNITS`).

        * harmonic: ``T_as``, ``T_au``, ``T_dr``, ``T_ds``, ``T_du``, ``DLC``, ``gamma``,
          ``mean_current``, ``mean_square_current`` (steady window, model reference, section 9);
        * pulse: ``SDR_s``, ``SAR_s``, ``SDR_u``, ``SAR_u``, ``RDR``, ``peak_tire_force``,
          and ``road_peak``, the definition of the road acceleration peak that divides
          ``SAR_s`` and ``SAR_u``;
        * road: ``DLC`` (std/mean tire force), ``rms_body_acceleration``,
          ``wk_rms_body_acceleration`` (ISO 2631-1), ``vdv``, ``rms_stroke``,
          ``mean_current``;

        and, for every kind, ``vm_clamp_fraction``: the share of the record with the
        peak-velocity estimate at its upper clamp (:attr:`velocity_clamp_fraction`). A
        damper that takes no current (the linear one) reports no ``mean_current`` or
        ``mean_square_current`` (:func:`drop_unused_currents`).

        Parameters
        ----------
        road_peak : {"after-onset", "onset"}, optional
            Pulse runs: divide ``SAR_s`` and ``SAR_u`` by the largest ``|z_r''|`` after
            the onset lobe (default; it matches the dissertation's SAR_s) or over the
            whole record, the jump at the pulse's onset (4.854 times larger); see
            :func:`mrsuspension.measures.road_acceleration_peak`. Checked for every
            excitation, used by pulse runs only.

        Examples
        --------
        >>> from mrsuspension.engine.simulate import Simulation
        >>> from mrsuspension.excitation import RoundedPulse
        >>> res = Simulation(RoundedPulse(0.035, 3.0)).run(1.5, dt=5e-4)
        >>> m = res.measures()
        >>> m["road_peak"], round(m["SAR_s"] / res.measures(road_peak="onset")["SAR_s"], 2)
        ('after-onset', 4.85)
        >>> m.units["peak_tire_force"], m.label("SAR_s")
        ('N', 'SAR_s [-]')
        """
        from mrsuspension.measures import check_road_peak

        how = check_road_peak(road_peak)
        kind, exc, static_load = measures_context(self.scenario)
        out: dict[str, Any] = self._kind_measures(kind, exc, static_load, how)
        drop_unused_currents(out, self.scenario)
        out["vm_clamp_fraction"] = self.velocity_clamp_fraction
        return Measures(out, units=MEASURE_UNITS)

    def _kind_measures(
        self, kind: Any, exc: Mapping[str, Any], static_load: float, how: RoadPeak
    ) -> dict[str, Any]:
        from mrsuspension import measures as M

        if kind == "harmonic":
            return M.harmonic_measures(
                self.time,
                float(exc["frequency"]),
                z_s=self.z_s,
                z_u=self.z_u,
                z_r=self.z_r,
                acc_s=self.z_s_ddot,
                acc_u=self.z_u_ddot,
                acc_r=self.z_r_ddot,
                x_d=self.x_d,
                F_d=self.F_d,
                F_T=self.F_T,
                static_load=static_load,
                i_d=self.i_d,
            )
        if kind == "pulse":
            ratios = M.shock_ratios(
                self.z_s,
                self.z_u,
                self.z_r,
                self.z_s_ddot,
                self.z_u_ddot,
                self.z_r_ddot,
                self.x_d,
                road_peak=how,
            )
            return pulse_measures(ratios, float(np.max(self.F_T)), how)
        if kind == "road":
            x_d = self.x_d
            return road_measures(
                tire_force_mean=float(np.mean(self.F_T)),
                tire_force_variance=float(np.var(self.F_T)),
                body_acceleration=self.z_s_ddot,
                fs=1.0 / float(self.time[1] - self.time[0]),
                stroke_variance=float(np.mean((x_d - np.mean(x_d)) ** 2)),
                mean_current=float(np.mean(self.i_d)),
            )
        raise ValidationError(f"no measures defined for excitation kind {kind!r}")

    # -- exports -----------------------------------------------------------------------
    def to_pandas(self) -> pd.DataFrame:
        """The signals as a DataFrame indexed by ``time``, one column per signal by its
        plain name (``df["z_s"]``); the units are in ``df.attrs["units"]`` (name -> unit,
        ``"time"`` included).

        Examples
        --------
        >>> res = SimulationResult(time=np.arange(3.0), signals={"F_d": np.zeros(3)},
        ...     units={"time": "s", "F_d": "N"})
        >>> df = res.to_pandas()
        >>> list(df.columns), df.index.name, df.attrs["units"]
        (['F_d'], 'time', {'time': 's', 'F_d': 'N'})
        """
        import pandas as pd

        df = pd.DataFrame(dict(self.signals), index=pd.Index(self.time, name="time"))
        df.attrs["units"] = {
            "time": self.units.get("time", "s"),
            **{k: self.units.get(k, "") for k in self.signals},
        }
        return df

    def to_xarray(self) -> xr.Dataset:
        """The signals as an xarray Dataset over ``time``, with units and descriptions."""
        import xarray as xr

        ds = xr.Dataset(
            {
                k: ("time", v, {"units": self.units[k], "long_name": SIGNALS.get(k, ("", k))[1]})
                for k, v in self.signals.items()
            },
            coords={"time": ("time", self.time, {"units": "s", "long_name": "time"})},
        )
        ds.attrs["scenario"] = json.dumps(self.scenario, default=str)
        ds.attrs["dt"] = self.dt
        return ds

    def _file_metadata(self) -> dict[str, Any]:
        """Further metadata a saved file keeps (a vehicle: its corners)."""
        return {}

    @classmethod
    def _loaded(cls, meta: Mapping[str, Any], signals: Mapping[str, Any]) -> dict[str, Any]:
        """Further constructor arguments from a loaded file's metadata."""
        return {}

    def save(self, path: str | Path) -> Path:
        """Write to ``.csv`` (with a JSON side file of the scenario), ``.nc`` or ``.parquet``.

        NetCDF keeps the scenario as a JSON attribute and a ``units`` attribute on every
        variable; Parquet (needs pyarrow, the ``data`` extra) holds the :meth:`to_pandas`
        table with the scenario, ``dt`` and units as JSON in the schema metadata (key
        :data:`PARQUET_METADATA_KEY`). :meth:`load` reads either back.
        """
        path = Path(path)
        suffix = path.suffix.lower()
        if suffix not in (".csv", ".nc", ".parquet"):
            raise ValidationError(
                f"cannot save a result as {suffix!r}; use .csv, .nc (NetCDF) or .parquet"
            )
        if suffix == ".parquet":
            require_pyarrow()
        path.parent.mkdir(parents=True, exist_ok=True)
        if suffix == ".csv":
            from mrsuspension._notebook import with_unit_headers

            labelled = with_unit_headers(self.to_pandas())  # "name [unit]" headers
            header = ",".join(map(str, [labelled.index.name, *labelled.columns]))
            table = np.column_stack([self.time, *self.signals.values()])
            np.savetxt(path, table, delimiter=",", header=header, comments="", fmt="%.9g")
            path.with_suffix(".json").write_text(
                json.dumps({"scenario": self.scenario, "dt": self.dt}, indent=2, default=str)
            )
        elif suffix == ".nc":
            self.to_xarray().to_netcdf(path)
        else:
            self._save_parquet(path)
        return path

    def _save_parquet(self, path: Path) -> None:
        """The :meth:`to_pandas` table, with the scenario, ``dt`` and units as metadata."""
        import pyarrow as pa
        import pyarrow.parquet as pq

        df = self.to_pandas()
        df.attrs = {}
        table = pa.Table.from_pandas(df)
        # columns by plain name (files written before name them "name [unit]"): the
        # "columns" entry maps each signal to its column either way
        labels = {"time": "time", **{k: k for k in self.signals}}
        meta = {
            "scenario": self.scenario,
            "dt": self.dt,
            "units": {k: self.units[k] for k in labels},
            "columns": labels,
            **self._file_metadata(),
        }
        entry = {PARQUET_METADATA_KEY.encode(): json.dumps(meta, default=str).encode()}
        pq.write_table(
            table.replace_schema_metadata({**(table.schema.metadata or {}), **entry}), path
        )

    @classmethod
    def load(cls, path: str | Path) -> SimulationResult:
        """Read a result written by :meth:`save` as ``.parquet`` or ``.nc``.

        The scenario, ``dt`` and the units come back from the file's metadata.

        Examples
        --------
        >>> import tempfile
        >>> from mrsuspension.engine.simulate import Simulation
        >>> from mrsuspension.excitation import Harmonic
        >>> res = Simulation(Harmonic(1.5, 0.025)).run(0.2)
        >>> with tempfile.TemporaryDirectory() as d:
        ...     back = SimulationResult.load(res.save(f"{d}/run.parquet"))
        >>> back.units["F_d"], back.scenario == res.scenario, bool((back.F_d == res.F_d).all())
        ('N', True, True)
        """
        path = Path(path)
        suffix = path.suffix.lower()
        if suffix not in (".parquet", ".nc"):
            raise ValidationError(
                f"cannot load a result from {suffix!r}; use .parquet or .nc (NetCDF)"
            )
        if not path.is_file():
            raise ValidationError(f"no result file at {str(path)!r}")
        from mrsuspension._inputs import parse_json

        if suffix == ".parquet":
            data, units, meta = _read_parquet(path)
        else:
            import xarray as xr

            where = f"result file {str(path)!r}"
            with xr.open_dataset(path) as ds:
                data, units = _flat_signals(ds)
                meta = {
                    "scenario": parse_json(str(ds.attrs.get("scenario", "{}")), where),
                    "dt": float(ds.attrs.get("dt", 0.0)),
                }
                if "corner" in ds.coords:
                    meta["corners"] = [str(c) for c in ds["corner"].values]
                if "corner_scenarios" in ds.attrs:
                    meta["corner_scenarios"] = parse_json(str(ds.attrs["corner_scenarios"]), where)
        time = data.pop("time")
        return cls(
            time=time,
            signals=data,
            scenario=dict(meta.get("scenario", {})),
            dt=float(meta.get("dt", 0.0)),
            units={"time": "s", **{k: str(units.get(k, "")) for k in data}},
            **cls._loaded(meta, data),
        )

    @overload
    def plot(
        self, signals: tuple[str, ...] = ..., title: str | None = ..., *, ax: None = None
    ) -> Figure: ...
    @overload
    def plot(self, signals: tuple[str, ...] = ..., title: str | None = ..., *, ax: _A) -> _A: ...
    def plot(
        self,
        signals: tuple[str, ...] = ("z_s_ddot", "x_d", "F_d", "F_T", "i_d"),
        title: str | None = None,
        *,
        ax: Any = None,
    ) -> Any:
        """Time histories of some signals, one panel each, titled with the run.

        Parameters
        ----------
        signals : tuple of str
            Signals to show, one panel each.
        title : str, optional
            Title; default: the controller and the excitation of the run
            (:func:`describe_run`). With ``ax``, set on the first Axes only when given.
        ax : matplotlib Axes or sequence of Axes, optional
            Draw into these instead of a new figure: one Axes per signal, or a single
            Axes for all of them (each line labelled ``"name [unit]"``, with a legend).

        Returns
        -------
        matplotlib.figure.Figure or Axes
            Without ``ax``: a new :class:`~matplotlib.figure.Figure`, made without
            pyplot (a notebook shows it once; no ``plt.close`` needed). With ``ax``:
            ``ax``, as given.

        Examples
        --------
        >>> res = SimulationResult(time=np.arange(3.0), signals={"F_d": np.zeros(3)},
        ...     scenario={"controller": {"law": "passive", "current": 0.1}},
        ...     units={"time": "s", "F_d": "N"})
        >>> fig = res.plot(("F_d",))
        >>> fig._suptitle.get_text()
        'passive (current 0.1)'
        >>> from mrsuspension._notebook import new_figure
        >>> ax = new_figure(4.0, 3.0).subplots()
        >>> res.plot(("F_d", "F_d"), ax=ax) is ax, len(ax.get_lines())
        (True, 2)
        """
        for s in signals:
            self[s]
        if ax is not None:
            axes = axes_for(ax, len(signals))
            shared = len(signals) > 1 and len({id(a) for a in axes}) == 1
            for a, s in zip(axes, signals, strict=True):
                a.plot(self.time, self[s], lw=0.8, label=self._label(s) if shared else None)
                if not shared:
                    a.set_ylabel(self._label(s))
                a.grid(True, alpha=0.3)
            axes[-1].set_xlabel(f"time [{self.units.get('time', 's')}]")
            if shared:
                axes[0].legend(fontsize=8)
            if title is not None:
                axes[0].set_title(title, fontsize=10)
            return ax
        fig = new_figure(8.0, 1.8 * len(signals))
        panels = fig.subplots(len(signals), 1, sharex=True, squeeze=False)[:, 0]
        self.plot(signals, ax=list(panels))
        fig.suptitle(describe_run(self.scenario) if title is None else title, fontsize=10)
        return fig

    def _label(self, name: str) -> str:
        unit = self.units.get(name)
        return f"{name} [{unit}]" if unit else name


def measures_context(scenario: Mapping[str, Any]) -> tuple[Any, Mapping[str, Any], float]:
    """``(measures kind, excitation description, static load [N])`` of a scenario.

    What :meth:`SimulationResult.measures` and the engine's in-kernel reduction
    (:mod:`mrsuspension.engine.reduced`) both start from.

    Examples
    --------
    >>> from mrsuspension.engine import Simulation
    >>> from mrsuspension.excitation import Harmonic
    >>> kind, exc, load = measures_context(Simulation(Harmonic(1.0, 0.01)).describe())
    >>> kind, exc["frequency"], round(load, 2)
    ('harmonic', 1.0, 6405.93)
    """
    from mrsuspension.vehicle import QuarterCar

    exc = scenario.get("excitation", {})
    static_load = QuarterCar(**scenario.get("vehicle", {})).static_load
    return _measures_kind(exc.get("kind")), exc, static_load


def drop_unused_currents(out: dict[str, Any], scenario: Mapping[str, Any]) -> dict[str, Any]:
    """``out`` without :data:`CURRENT_MEASURES` when the run's damper takes no current.

    A linear damper ignores the current its controller commands, so a mean current
    would report a drive that does nothing (:func:`~mrsuspension.dampers.takes_current`).

    Examples
    --------
    >>> drop_unused_currents({"DLC": 0.1, "mean_current": 0.2}, {"damper": {"model": "linear"}})
    {'DLC': 0.1}
    >>> drop_unused_currents({"mean_current": 0.2}, {"damper": {"model": "bingham"}})
    {'mean_current': 0.2}
    """
    from mrsuspension.dampers import takes_current

    if not takes_current(scenario.get("damper")):
        for name in CURRENT_MEASURES:
            out.pop(name, None)
    return out


def pulse_measures(ratios: Mapping[str, float], peak_tire_force: float, how: str) -> dict[str, Any]:
    """The pulse measures: the shock ratios, ``peak_tire_force`` [N] and ``road_peak``.

    Examples
    --------
    >>> pulse_measures({"SDR_s": 0.5}, 9000.0, "onset")
    {'SDR_s': 0.5, 'peak_tire_force': 9000.0, 'road_peak': 'onset'}
    """
    out: dict[str, Any] = dict(ratios)
    out["peak_tire_force"] = peak_tire_force
    out["road_peak"] = how
    return out


def road_measures(
    *,
    tire_force_mean: float,
    tire_force_variance: float,
    body_acceleration: npt.ArrayLike,
    fs: float,
    stroke_variance: float,
    mean_current: float,
) -> dict[str, Any]:
    """The road measures from the record's moments and its body acceleration.

    ``DLC`` is the tire force's std over its mean (:func:`~mrsuspension.measures.dlc`
    without a static load), ``rms_stroke`` the std of ``x_d``; the ISO 2631 measures
    filter the body acceleration ``z_s''`` sampled at ``fs`` [Hz].

    Examples
    --------
    >>> acc = np.sin(np.linspace(0.0, 200.0, 20_000))
    >>> m = road_measures(tire_force_mean=6400.0, tire_force_variance=6400.0**2 * 1e-4,
    ...                   body_acceleration=acc, fs=1000.0, stroke_variance=1e-4,
    ...                   mean_current=0.1)
    >>> round(m["DLC"], 6), round(m["rms_stroke"], 6)
    (0.01, 0.01)
    """
    from mrsuspension import measures as M

    if tire_force_mean <= 0.0:
        raise ValidationError(
            f"mean tire force must be > 0 N to normalise the DLC; got {tire_force_mean:g} N "
            "(give static_load)"
        )
    acc = np.asarray(body_acceleration, dtype=float)
    return {
        "DLC": float(np.sqrt(tire_force_variance)) / tire_force_mean,
        "rms_body_acceleration": float(np.sqrt(np.mean(acc * acc))),
        "wk_rms_body_acceleration": M.weighted_rms(acc, fs),
        "vdv": M.vdv(acc, fs),
        "rms_stroke": float(np.sqrt(stroke_variance)),
        "mean_current": mean_current,
    }


def describe_run(scenario: Mapping[str, Any]) -> str:
    """A one-line title of a run: its controller and its excitation (from ``describe()``).

    Examples
    --------
    >>> describe_run({"controller": {"law": "skyhook-hilo", "mode": "ACM", "gain": 3.0},
    ...               "excitation": {"kind": "harmonic", "frequency": 1.5, "amplitude": 0.025}})
    'skyhook-hilo ACM (gain 3), harmonic 1.5 Hz, 25 mm'
    >>> describe_run({})
    'simulation'
    """
    parts = [controller_text(scenario), excitation_text(scenario)]
    return ", ".join(p for p in parts if p) or "simulation"


def controller_text(scenario: Mapping[str, Any]) -> str:
    """The controller of a run in a few words (``""`` without one).

    Examples
    --------
    >>> controller_text({"controller": {"law": "passive", "current": 0.2}})
    'passive (current 0.2)'
    >>> controller_text({"controller": {"law": "skyhook-hilo", "p": 0.0, "gain": 3.0}})
    'skyhook-hilo ACM (gain 3)'
    """
    ctrl = dict(scenario.get("controller", {}))
    if not ctrl:
        return ""
    law = str(ctrl.pop("law", "controller"))
    mode = ctrl.pop("mode", None)
    if mode is None and ctrl.get("p") in (0.0, 1.0):  # the ADFG asymmetry p of a mode
        mode = "ACM" if ctrl["p"] == 0.0 else "SCM"
    first = f"{law} {mode}" if mode else law
    extra = [f"{k} {v:g}" for k, v in ctrl.items() if k in ("current", "gain")]
    return first + (f" ({', '.join(extra)})" if extra else "")


def excitation_text(scenario: Mapping[str, Any]) -> str:
    """The excitation of a run in a few words (``""`` without one); a vehicle's road
    that wraps one excitation names both.

    Examples
    --------
    >>> harmonic = {"kind": "harmonic", "frequency": 2.0, "amplitude": 0.01}
    >>> excitation_text({"excitation": {"kind": "wheel-roads", "speed_kmh": 72.0,
    ...     "details": {"excitation": harmonic}}})
    'wheel-roads at 72 km/h: harmonic 2 Hz, 10 mm'
    >>> excitation_text({"excitation": {"kind": "wheel-roads", "speed_kmh": None,
    ...     "details": {"excitation": harmonic}}})  # in phase: no speed
    'wheel-roads: harmonic 2 Hz, 10 mm'
    """
    exc = scenario.get("excitation", {})
    if not exc:
        return ""
    kind = str(exc.get("kind", "excitation"))
    if kind == "harmonic" and "frequency" in exc:
        kind += f" {exc['frequency']:g} Hz, {1e3 * float(exc.get('amplitude', 0.0)):g} mm"
    elif exc.get("speed_kmh") is not None:
        kind += f" at {exc['speed_kmh']:g} km/h"
    details = exc.get("details")
    inner = exc.get("excitation") or (
        details.get("excitation") if isinstance(details, Mapping) else None
    )
    if isinstance(inner, Mapping) and inner:
        kind += f": {excitation_text({'excitation': inner})}"
    return kind


def _dt_text(dt: float) -> str:
    """A time step for a summary: ``"0.1 ms"`` (``"-"`` when not recorded)."""
    return f"{dt * 1e3:.4g} ms" if dt > 0.0 else "-"


def require_pyarrow() -> None:
    """Raise a one-line :class:`ValidationError` naming the ``data`` extra without pyarrow.

    Examples
    --------
    >>> require_pyarrow()  # pyarrow is installed here: nothing happens
    """
    from mrsuspension.errors import require_extra

    require_extra("data", "Parquet output", "use .csv / .nc")


def _measures_kind(kind: Any) -> Any:
    """The measures kind of a registered excitation kind (an unregistered one: itself)."""
    from mrsuspension.excitation import EXCITATIONS

    cls = EXCITATIONS.get(kind) if isinstance(kind, str) else None
    return kind if cls is None else cls.measures_kind


def warn_if_clamped(result: SimulationResult) -> None:
    """Warn (:class:`VelocityClampWarning`) when ``v_m`` sat at its clamp for long."""
    share = result.velocity_clamp_fraction
    if share > CLAMP_WARN_FRACTION:
        import warnings

        limit = result.scenario.get("peak_velocity_limit")
        warnings.warn(
            f"the peak-velocity estimate v_m was at its upper clamp ({limit:g} m/s) for "
            f"{100 * share:.1f} % of the run ({result.velocity_clamp_time:.2f} s): the damper "
            "model ran at the edge of its identified velocity range (model reference, "
            "section 2.4); its forces there are an extrapolation",
            VelocityClampWarning,
            stacklevel=3,
        )


def warn_if_aliased(
    reversals: float, steps: int, decimate: int, dt: float, where: str = ""
) -> bool:
    """Warn (:class:`AliasedRecordWarning`) when a decimated record aliases the current.

    ``reversals``: the run's steps whose change of the drive current reversed the step
    before's (the kernels' count, :func:`mrsuspension.engine.kernel.note_current`), out of
    ``steps`` of ``dt`` [s]; the record (or the reduced measures) kept one step in
    ``decimate``. A law that switches at the step rate (a hi-lo decision that flips every
    step) then puts power at half the step rate, which a record at ``1 / (decimate dt)``
    folds onto one phase of the alternation: on the bump at 50 km/h, ``mpc-hilo``'s
    weighted body acceleration read 0.222 m/s^2 from a 1 kHz record and 0.376 m/s^2 from
    every 0.5 ms step. Returns whether it warned.

    Examples
    --------
    >>> import warnings
    >>> with warnings.catch_warnings(record=True) as caught:
    ...     warnings.simplefilter("always")
    ...     warn_if_aliased(900.0, 2000, 10, 1e-4), warn_if_aliased(900.0, 2000, 1, 1e-4)
    (True, False)
    >>> print(caught[0].message)  # doctest: +ELLIPSIS
    the drive current reversed its change at 45 % of the 0.1 ms steps ...
    """
    share = reversals / steps if steps > 0 else 0.0
    if decimate <= 1 or share <= ALIAS_WARN_FRACTION:
        return False
    import warnings

    rate = 1.0 / (decimate * dt)
    warnings.warn(
        f"the drive current reversed its change at {100 * share:.0f} % of the "
        f"{dt * 1e3:g} ms steps{where} (it switches at the step rate); the record keeps one "
        f"step in {decimate} ({rate:g} Hz) and may alias that switching (mpc-hilo on a bump: "
        "weighted body acceleration 0.222 m/s^2 from a 1 kHz record, 0.376 from every "
        f"step). Record every step to be sure: output_rate = 1/dt = {1.0 / dt:g} Hz",
        AliasedRecordWarning,
        stacklevel=3,
    )
    return True


def _flat_signals(
    ds: xr.Dataset,
) -> tuple[dict[str, npt.NDArray[np.float64]], dict[str, str]]:
    """Signals by name and their units from a NetCDF result: a variable over
    ``("time", "corner")`` becomes one ``"<name>.<corner>"`` signal per corner."""
    data = {"time": ds["time"].to_numpy().astype(np.float64)}
    units = {"time": str(ds["time"].attrs.get("units", "s"))}
    for key in ds.data_vars:
        var = ds[key]
        unit = str(var.attrs.get("units", ""))
        if "corner" in var.dims:
            var = var.transpose("time", "corner")
            for c, column in zip(ds["corner"].values, var.to_numpy().T, strict=True):
                data[f"{key}.{c}"] = column.astype(np.float64)
                units[f"{key}.{c}"] = unit
        else:
            data[str(key)] = var.to_numpy().astype(np.float64)
            units[str(key)] = unit
    return data, units


def _read_parquet(
    path: Path,
) -> tuple[dict[str, npt.NDArray[np.float64]], dict[str, str], dict[str, Any]]:
    """Signals by name, units and metadata of a Parquet file written by ``save``."""
    require_pyarrow()
    import pyarrow.parquet as pq

    table = pq.read_table(path)
    raw = (table.schema.metadata or {}).get(PARQUET_METADATA_KEY.encode())
    if raw is None:
        raise ValidationError(
            f"{str(path)!r} was not written by SimulationResult.save: its Parquet metadata "
            f"has no {PARQUET_METADATA_KEY!r} entry"
        )
    from mrsuspension._inputs import parse_json

    meta: dict[str, Any] = parse_json(raw, f"result file {str(path)!r}")
    present = set(table.column_names)
    data = {
        name: table.column(label).to_numpy().astype(np.float64)
        for name, label in meta["columns"].items()
        if label in present
    }
    return data, dict(meta["units"]), meta
