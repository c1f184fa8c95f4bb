"""Comfort, road holding and rattle space across controllers and gains (beyond the dissertation).

Every controller setting of a grid runs on the same road(s); each gives three measures,
all smaller-is-better:

* comfort: ``wk_rms_body_acceleration``, the ISO 2631-1 Wk-weighted RMS body
  acceleration [m/s^2];
* road holding: ``DLC``, the dynamic load coefficient std(F_T) / static load [-];
* rattle space: ``rms_stroke``, the RMS suspension stroke about its mean [m].

The default grid (:func:`default_grid`): passive currents 0-0.5 A, skyhook hi-lo
(policy I) in SCM and ACM over the gain k_c, inverse-model hi-lo and sliding mode (ACM)
over the force gain k_d, and the ideal skyhook damper as an unreachable reference.
:func:`pareto_front` marks the settings no other setting beats in every measure (the
ideal controllers are left out of the fronts: an MR damper cannot realise them).

Examples
--------
>>> pareto_front([[1.0, 3.0], [2.0, 2.0], [3.0, 1.0], [3.0, 3.0]]).tolist()
[True, True, True, False]
"""

from __future__ import annotations

import copy
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, TypeVar, overload

import numpy as np
import numpy.typing as npt

from mrsuspension._batch import job_of, process_pool, run_jobs
from mrsuspension.errors import ValidationError
from mrsuspension.optimize import Road
from mrsuspension.scenario import Scenario

if TYPE_CHECKING:
    import pandas as pd
    from matplotlib.figure import Figure

_A = TypeVar("_A")  # the Axes a plot(..., ax=...) draws into and returns

__all__ = [
    "TRADEOFF_MEASURES",
    "TradeoffPoint",
    "TradeoffResult",
    "default_grid",
    "pareto_front",
    "tradeoff",
]

#: (comfort, road holding, rattle space), all smaller-is-better
TRADEOFF_MEASURES: tuple[str, str, str] = ("wk_rms_body_acceleration", "DLC", "rms_stroke")
_AXIS_LABELS = {
    "wk_rms_body_acceleration": "Wk-weighted RMS body acceleration [m/s$^2$]",
    "DLC": "dynamic load coefficient DLC [-]",
    "rms_stroke": "RMS suspension stroke [mm]",
}
#: Grid = family -> list of (setting label, scenario tables replacing the base's).
Grid = dict[str, list[tuple[str, dict[str, dict[str, Any]]]]]


def pareto_front(points: npt.ArrayLike) -> npt.NDArray[np.bool_]:
    """Which points no other point dominates (every column minimised).

    A point is dominated when another is no worse in every column and better in one.
    Rows with a NaN are never on the front.

    Parameters
    ----------
    points : array_like, shape (n, k)
        One row per point.

    Returns
    -------
    numpy.ndarray of bool, shape (n,)

    Examples
    --------
    >>> pareto_front([[1.0, 1.0], [1.0, 1.0], [2.0, 0.5], [2.0, 1.0]]).tolist()
    [True, True, True, False]
    """
    p = np.asarray(points, dtype=float)
    if p.ndim != 2:
        raise ValidationError(
            f"points must be a 2-D array (n points x k measures); got shape {p.shape}"
        )
    ok = np.all(np.isfinite(p), axis=1)
    front = ok.copy()
    for i in np.flatnonzero(ok):
        others = p[ok]
        dominated = np.all(others <= p[i], axis=1) & np.any(others < p[i], axis=1)
        front[i] = not bool(np.any(dominated))
    return front


def default_grid(quick: bool = False) -> Grid:
    """The controllers and gains of the trade-off plot.

    Passive currents 0-0.5 A; skyhook hi-lo (n = 2) SCM and ACM over k_c; inverse-model
    hi-lo and sliding mode ACM over the force gain k_d (their Chapter 5-6 gain); the
    ideal skyhook damper (c_s = the vehicle's skyhook damping).

    Examples
    --------
    >>> grid = default_grid(quick=True)
    >>> sorted(grid)[:2], grid["passive"][0]
    (['ideal skyhook', 'inverse hi-lo ACM'], ('0 A', {'controller': {'law': 'passive', 'current': 0.0}}))
    """
    currents = (
        (0.0, 0.05, 0.1, 0.2, 0.3, 0.5) if quick else tuple(np.round(np.arange(0.0, 0.51, 0.05), 2))
    )
    gains = (1.0, 10.0, 100.0, 1000.0) if quick else (1.0, 3.0, 10.0, 30.0, 100.0, 300.0, 1000.0)
    force_gains = (1.0, 2.5) if quick else (1.0, 1.5, 2.0, 2.5)
    grid: Grid = {
        "passive": [
            (f"{c:g} A", {"controller": {"law": "passive", "current": float(c)}}) for c in currents
        ]
    }
    for mode in ("SCM", "ACM"):
        grid[f"skyhook hi-lo {mode}"] = [
            (
                f"k_c = {g:g}",
                {"controller": {"law": "skyhook-hilo", "mode": mode, "gain": g, "order": 2.0}},
            )
            for g in gains
        ]
    for family, law in (
        ("inverse hi-lo ACM", "inverse-hilo"),
        ("sliding mode ACM", "sliding-mode"),
    ):
        grid[family] = [
            (
                f"k_d = {k:g}",
                {"controller": {"law": law, "mode": "ACM"}, "damper": {"force_gain": k}},
            )
            for k in force_gains
        ]
    grid["ideal skyhook"] = [("c_s", {"controller": {"law": "ideal-skyhook"}})]
    return grid


@dataclass(frozen=True)
class TradeoffPoint:
    """One controller setting and its measures (weighted mean over the roads).

    Parameters
    ----------
    family : str
        Controller family (a key of the grid).
    setting : str
        The setting within the family, e.g. ``"k_c = 10"``.
    tables : dict
        Scenario tables that replaced the base's.
    measures : dict
        Measure -> value: the road-weighted mean of every road measure.
    """

    family: str
    setting: str
    tables: dict[str, dict[str, Any]]
    measures: dict[str, float]

    @property
    def realisable(self) -> bool:
        """False for the ideal (force-source) controllers: references, not MR dampers."""
        return not str(self.tables.get("controller", {}).get("law", "")).startswith("ideal")

    @property
    def values(self) -> tuple[float, float, float]:
        """(comfort, road holding, rattle space)."""
        m = self.measures
        return (m[TRADEOFF_MEASURES[0]], m[TRADEOFF_MEASURES[1]], m[TRADEOFF_MEASURES[2]])


@dataclass(frozen=True)
class TradeoffResult:
    """The measures of every grid setting; Pareto fronts and the two trade-off panels.

    Parameters
    ----------
    points : tuple of TradeoffPoint
        In grid order.
    roads : tuple of Road
        The roads the measures are averaged over.
    """

    points: tuple[TradeoffPoint, ...]
    roads: tuple[Road, ...]

    def matrix(self) -> npt.NDArray[np.float64]:
        """(n, 3): comfort, road holding, rattle space of every point."""
        return np.array([p.values for p in self.points], dtype=float)

    def pareto(self, measures: Sequence[str] = TRADEOFF_MEASURES) -> npt.NDArray[np.bool_]:
        """Non-dominated realisable points over ``measures`` (default: all three).

        The ideal controllers are references: never on the front, and they do not push
        the MR-damper settings off it.
        """
        idx = [TRADEOFF_MEASURES.index(m) for m in measures]
        data = self.matrix()[:, idx]
        data[~self._realisable()] = np.nan
        return pareto_front(data)

    def _realisable(self) -> npt.NDArray[np.bool_]:
        return np.array([p.realisable for p in self.points], dtype=bool)

    def rows(self) -> list[dict[str, Any]]:
        """One plain row per point, with its Pareto flags."""
        all3 = self.pareto()
        dlc = self.pareto(TRADEOFF_MEASURES[:2])
        stroke = self.pareto((TRADEOFF_MEASURES[0], TRADEOFF_MEASURES[2]))
        out = []
        for k, p in enumerate(self.points):
            out.append(
                {
                    "controller": p.family,
                    "setting": p.setting,
                    "Wk RMS a_s [m/s^2]": p.measures[TRADEOFF_MEASURES[0]],
                    "DLC": p.measures[TRADEOFF_MEASURES[1]],
                    "RMS stroke [mm]": 1e3 * p.measures[TRADEOFF_MEASURES[2]],
                    "mean current [A]": p.measures.get("mean_current", float("nan")),
                    "Pareto (3 measures)": "yes" if all3[k] else "",
                    "front a_s-DLC": "yes" if dlc[k] else "",
                    "front a_s-stroke": "yes" if stroke[k] else "",
                }
            )
        return out

    def to_pandas(self) -> pd.DataFrame:
        """:meth:`rows` as a DataFrame."""
        import pandas as pd

        return pd.DataFrame(self.rows())

    @overload
    def plot(
        self, extra: Mapping[str, Mapping[str, float]] | None = ..., *, ax: None = None
    ) -> Figure: ...
    @overload
    def plot(self, extra: Mapping[str, Mapping[str, float]] | None = ..., *, ax: _A) -> _A: ...
    def plot(
        self, extra: Mapping[str, Mapping[str, float]] | None = None, *, ax: Any = None
    ) -> Any:
        """Comfort against road holding (left) and against rattle space (right).

        Each panel marks its two-measure Pareto front (a line through the non-dominated
        settings); settings on the three-measure front have a black edge.

        Parameters
        ----------
        extra : mapping, optional
            Label -> measures of further points to mark with a star (e.g. the
            optimiser's best controller).
        ax : sequence of two matplotlib Axes, optional
            Draw the two panels there (the legend in the second) and return ``ax``;
            default: a new Figure made without pyplot (a notebook shows it once).
        """
        from mrsuspension._notebook import axes_for, new_figure

        data = self.matrix()
        all3 = self.pareto()
        families = list(dict.fromkeys(p.family for p in self.points))
        markers = dict(zip(families, "osD^vXPh", strict=False))
        given = ax  # the loop below names each panel ax
        if given is None:
            fig = new_figure(11.0, 5.2, layout="constrained")
            axes = list(fig.subplots(1, 2))
        else:
            axes = axes_for(given, 2, "panels")
        scale = (1.0, 1.0, 1e3)  # stroke in mm
        for ax, j in zip(axes, (1, 2), strict=True):
            x = data[:, 0]
            y = data[:, j] * scale[j]
            for c, fam in enumerate(families):
                sel = np.array([p.family == fam for p in self.points])
                ax.plot(
                    x[sel], y[sel], marker=markers[fam], ls="-" if sel.sum() > 1 else "none",
                    lw=0.8, ms=6, color=f"C{c}", alpha=0.85, label=fam,
                )  # fmt: skip
                edge = sel & all3
                ax.plot(
                    x[edge], y[edge], marker=markers[fam], ls="none", ms=8, mfc="none",
                    mec="k", mew=1.2,
                )  # fmt: skip
            front = self.pareto((TRADEOFF_MEASURES[0], TRADEOFF_MEASURES[j]))
            order = np.argsort(x[front])
            ax.step(
                x[front][order], y[front][order], where="post", color="k", lw=1.2, ls="--",
                label="Pareto front (this panel)",
            )  # fmt: skip
            for k, p in enumerate(self.points):
                ax.annotate(p.setting, (x[k], y[k]), fontsize=6, alpha=0.7,
                            xytext=(3, 3), textcoords="offset points")  # fmt: skip
            for label, m in (extra or {}).items():
                ax.plot(
                    m[TRADEOFF_MEASURES[0]], m[TRADEOFF_MEASURES[j]] * scale[j], marker="*",
                    ms=16, color="gold", mec="k", ls="none", label=label,
                )  # fmt: skip
            self._limit(
                ax, y, extra_y=[m[TRADEOFF_MEASURES[j]] * scale[j] for m in (extra or {}).values()]
            )
            ax.set_xlabel(_AXIS_LABELS[TRADEOFF_MEASURES[0]])
            ax.set_ylabel(_AXIS_LABELS[TRADEOFF_MEASURES[j]])
            ax.grid(True, alpha=0.3)
        axes[0].set_title("comfort vs road holding (down-left is better)", fontsize=9)
        axes[1].set_title("comfort vs rattle space (down-left is better)", fontsize=9)
        handles, labels = axes[1].get_legend_handles_labels()
        if given is not None:
            axes[1].legend(handles, labels, fontsize=7)
            return given
        fig.legend(handles, labels, loc="outside lower center", ncol=4, fontsize=7)
        return fig

    def _limit(self, ax: Any, y: npt.NDArray[np.float64], extra_y: Sequence[float]) -> None:
        """y range of the realisable settings; an ideal one beyond it is noted at the edge."""
        real = self._realisable()
        if not real.any():
            return
        values = np.concatenate([y[real], np.asarray(extra_y, dtype=float)])
        lo, hi = float(np.nanmin(values)), float(np.nanmax(values))
        pad = 0.08 * (hi - lo or abs(hi) or 1.0)
        ax.set_ylim(lo - pad, hi + pad)
        for k, p in enumerate(self.points):
            if real[k] or lo - pad <= y[k] <= hi + pad:
                continue
            edge = hi + pad if y[k] > hi else lo - pad
            ax.annotate(
                f"{p.family} {p.setting}: {y[k]:.3g} (off the plot)",
                (p.values[0], edge), xytext=(0, -14 if y[k] > hi else 14),
                textcoords="offset points", fontsize=7, ha="left",
                arrowprops={"arrowstyle": "->", "lw": 0.8},
            )  # fmt: skip


def tradeoff(
    roads: Sequence[Road],
    *,
    grid: Grid | None = None,
    base: Mapping[str, Mapping[str, Any]] | None = None,
    dt: float = 1e-4,
    workers: int | None = None,
    progress: Callable[[str], None] | None = None,
) -> TradeoffResult:
    """Run every setting of ``grid`` on every road and average the measures over the roads.

    Parameters
    ----------
    roads : sequence of Road
        The roads (weights as in an optimisation problem).
    grid : dict, optional
        Family -> [(setting label, tables)]; default :func:`default_grid`.
    base : mapping, optional
        Scenario tables under every setting (vehicle, damper, ...); a setting's tables
        replace the base's section by section.
    dt : float
        Fixed step [s] (default 1e-4, model reference, section 7).
    workers : int, optional
        Processes (None: one per core; 1: this process).
    progress : callable, optional
        Called with a message before the runs.

    Raises
    ------
    ValidationError
        No road, an empty grid, a setting whose scenario fails its checks (named), or a
        run that diverges.

    Examples
    --------
    >>> road = Road.from_dict({"iso_class": "C", "length": 30.0})
    >>> grid = {"passive": [("0 A", {"controller": {"law": "passive", "current": 0.0}}),
    ...                     ("0.5 A", {"controller": {"law": "passive", "current": 0.5}})]}
    >>> res = tradeoff([road], grid=grid, dt=5e-4, workers=1)
    >>> a, b = res.points  # a harder damper: less stroke, more body acceleration
    >>> b.measures["rms_stroke"] < a.measures["rms_stroke"], b.values[0] > a.values[0]
    (True, True)
    """
    roads = tuple(roads)
    if not roads:
        raise ValidationError("tradeoff needs at least one road")
    grid = default_grid() if grid is None else grid
    settings = [(fam, label, tables) for fam, items in grid.items() for label, tables in items]
    if not settings:
        raise ValidationError("tradeoff grid is empty: give at least one controller setting")
    base_tables = {k: dict(v) for k, v in (base or {}).items()}
    jobs = []
    for fam, label, tables in settings:
        for road in roads:
            data = copy.deepcopy(base_tables)
            data.update(copy.deepcopy(dict(tables)))
            data["excitation"] = road.excitation()
            data.setdefault("simulation", {})["dt"] = dt
            try:
                scenario = Scenario.from_dict(data)
            except ValidationError as err:
                raise ValidationError(
                    f"tradeoff setting {fam} {label} on {road.name}: {err}"
                ) from None
            jobs.append(job_of(scenario))
    if progress:
        progress(f"trade-off: {len(settings)} settings x {len(roads)} roads")
    with process_pool(workers, len(jobs)) as pool:
        rows = run_jobs(jobs, pool)
    weights = np.array([r.weight for r in roads], dtype=float)
    weights = weights / weights.sum()
    points = []
    for k, (fam, label, tables) in enumerate(settings):
        runs = rows[k * len(roads) : (k + 1) * len(roads)]
        if any(r is None for r in runs):
            raise ValidationError(f"tradeoff setting {fam} {label} diverged; reduce dt")
        measures = {
            m: float(sum(w * float(r[m]) for w, r in zip(weights, runs, strict=True) if r))
            for m in (runs[0] or {})
        }
        points.append(TradeoffPoint(fam, label, copy.deepcopy(dict(tables)), measures))
    return TradeoffResult(tuple(points), roads)
