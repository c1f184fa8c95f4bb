"""Notebook conventions shared by the results: :class:`Measures`, HTML summaries, figures.

What a Jupyter user of python-control, xarray or pandas expects of a result:

* :class:`Measures` - a run's measures as a ``dict`` (``m["DLC"]``, float arithmetic,
  JSON) that also carries their units (``m.units``), shows as a table in a notebook
  (``_repr_html_``) and becomes a pandas Series (:meth:`Measures.to_series`);
* :func:`html_table` - the compact ``<table>`` of the results' ``_repr_html_`` summaries;
* :func:`new_figure` - a :class:`matplotlib.figure.Figure` made without pyplot, so a
  notebook shows a returned figure once (pyplot would also show it as the cell's
  open figure);
* :func:`axes_for` - the Axes a ``plot(..., ax=...)`` draws into;
* :func:`with_unit_headers` - a DataFrame whose units are in ``df.attrs["units"]``
  relabelled ``"name [unit]"`` for CSV files.
"""

from __future__ import annotations

import html
import math
from collections.abc import Iterable, Mapping, Sequence
from typing import TYPE_CHECKING, Any, Literal

from mrsuspension.errors import ValidationError

if TYPE_CHECKING:
    import pandas as pd
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

__all__ = ["Measures", "axes_for", "html_table", "new_figure", "unit_of", "with_unit_headers"]


def unit_of(name: str, units: Mapping[str, str]) -> str | None:
    """The unit of ``name`` in ``units``, looking up ``"<measure>.<corner>"`` by its measure.

    Examples
    --------
    >>> unit_of("DLC.front_left", {"DLC": "-"}), unit_of("vdv", {"DLC": "-"})
    ('-', None)
    """
    if name in units:
        return units[name]
    base, dot, _ = name.partition(".")
    return units.get(base) if dot else None


def _number(value: Any) -> str:
    """A value for a summary table: numbers to 4 significant digits."""
    if isinstance(value, bool) or not isinstance(value, int | float):
        return str(value)
    if isinstance(value, int):
        return str(value)
    return f"{value:.4g}" if math.isfinite(value) else str(value)


def html_table(
    rows: Iterable[Sequence[Any]], header: Sequence[str] = (), caption: str | None = None
) -> str:
    """A compact HTML table (cells escaped; floats to 4 significant digits).

    Examples
    --------
    >>> html_table([("dt", "0.1 ms")], caption="run")
    '<table><caption>run</caption><tr><th style="text-align:left">dt</th><td style="text-align:left">0.1 ms</td></tr></table>'
    """
    out = ["<table>"]
    if caption:
        out.append(f"<caption>{html.escape(caption)}</caption>")
    if header:
        cells = "".join(f'<th style="text-align:left">{html.escape(h)}</th>' for h in header)
        out.append(f"<tr>{cells}</tr>")
    for row in rows:
        first, *rest = row
        cells = f'<th style="text-align:left">{html.escape(str(first))}</th>'
        cells += "".join(
            f'<td style="text-align:left">{html.escape(_number(v))}</td>' for v in rest
        )
        out.append(f"<tr>{cells}</tr>")
    out.append("</table>")
    return "".join(out)


class Measures(dict[str, Any]):
    """A run's measures by name: a ``dict`` that carries their units.

    Everything a dict does works as before (``m["DLC"]``, ``m["DLC"] * 2``, ``dict(m)``,
    JSON, equality with a plain dict); besides, :attr:`units` maps each numeric
    measure to its unit (``"-"``: a dimensionless ratio), :meth:`label` gives
    ``"name [unit]"``, :meth:`to_series` a pandas Series with the units in
    ``series.attrs["units"]``, and a notebook shows the measures as a table
    (``_repr_html_``). Non-numeric entries (``road_peak``: how a measure was computed)
    have no unit.

    Parameters
    ----------
    values : mapping or iterable of pairs
        The measures.
    units : mapping, optional
        Unit of each measure; a ``"<measure>.<corner>"`` key takes the unit of
        ``<measure>``.

    Examples
    --------
    >>> m = Measures({"DLC": 0.12, "vdv": 1.5, "road_peak": "onset"},
    ...              units={"DLC": "-", "vdv": "m/s^1.75"})
    >>> m["vdv"] * 2, m.units["vdv"], m.label("vdv")
    (3.0, 'm/s^1.75', 'vdv [m/s^1.75]')
    >>> m == {"DLC": 0.12, "vdv": 1.5, "road_peak": "onset"}, "road_peak" in m.units
    (True, False)
    >>> s = m.to_series()
    >>> s["DLC"], s.attrs["units"]["DLC"]
    (np.float64(0.12), '-')
    """

    units: dict[str, str]

    def __init__(
        self,
        values: Mapping[str, Any] | Iterable[tuple[str, Any]] = (),
        /,
        units: Mapping[str, str] | None = None,
    ) -> None:
        super().__init__(values)
        table = dict(units or {})
        self.units = {
            k: u for k, v in self.items() if _is_number(v) and (u := unit_of(k, table)) is not None
        }

    def label(self, name: str) -> str:
        """``"name [unit]"`` (``name`` alone when it has no unit)."""
        if name not in self:
            from mrsuspension.errors import unknown_name

            raise unknown_name("measure", name, list(self))
        unit = self.units.get(name)
        return name if unit is None else f"{name} [{unit}]"

    def to_series(self) -> pd.Series:
        """The numeric measures as a pandas Series (index ``measure``), units in
        ``series.attrs["units"]`` and the non-numeric entries in ``series.attrs["notes"]``."""
        import pandas as pd

        numbers = {k: float(v) for k, v in self.items() if _is_number(v)}
        series = pd.Series(numbers, dtype=float, name="value")
        series.index.name = "measure"
        series.attrs["units"] = {k: self.units[k] for k in numbers if k in self.units}
        series.attrs["notes"] = {k: v for k, v in self.items() if k not in numbers}
        return series

    def _repr_html_(self) -> str:
        corners = list(dict.fromkeys(k.partition(".")[2] for k in self if "." in k))
        plain = [k for k in self if "." not in k]
        parts = []
        if plain:
            parts.append(
                html_table(
                    ((k, self[k], self.units.get(k, "")) for k in plain),
                    header=("measure", "value", "unit"),
                )
            )
        if corners:  # a vehicle's per-corner measures: one column per corner
            names = list(dict.fromkeys(k.partition(".")[0] for k in self if "." in k))
            rows = [
                (
                    n,
                    *(self.get(f"{n}.{c}", "") for c in corners),
                    next((self.units[f"{n}.{c}"] for c in corners if f"{n}.{c}" in self.units), ""),
                )
                for n in names
            ]
            parts.append(html_table(rows, header=("measure", *corners, "unit")))
        return "".join(parts)

    def __reduce__(self) -> tuple[Any, ...]:
        return (Measures, (dict(self), self.units))


def _is_number(value: Any) -> bool:
    """True for a real number (not a bool nor a string)."""
    import numbers

    return isinstance(value, numbers.Real) and not isinstance(value, bool)


_FIGURE_CLASS: type[Figure] | None = None


def _figure_class() -> type[Figure]:
    """:class:`ResultFigure`, made on first use (matplotlib is imported only then)."""
    global _FIGURE_CLASS
    if _FIGURE_CLASS is None:
        from matplotlib.figure import Figure

        class ResultFigure(Figure):
            """A matplotlib Figure that a notebook shows without pyplot (``_repr_png_``)."""

            def _repr_png_(self) -> bytes:
                import io

                buffer = io.BytesIO()
                self.savefig(buffer, format="png", dpi=100)
                return buffer.getvalue()

        ResultFigure.__module__ = __name__
        ResultFigure.__qualname__ = "ResultFigure"
        _FIGURE_CLASS = ResultFigure
    return _FIGURE_CLASS


def __getattr__(name: str) -> Any:
    if name == "ResultFigure":  # pickle finds the figure class by its name
        return _figure_class()
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def new_figure(
    width: float, height: float, layout: Literal["tight", "constrained"] = "tight"
) -> Figure:
    """A figure of ``width`` x ``height`` inches made without pyplot (``layout``:
    matplotlib's layout engine, ``"tight"`` by default).

    pyplot is not involved, so a notebook shows a returned figure once (as the cell's
    value: its ``_repr_png_``, or the inline backend's renderer when pyplot is in use)
    and ``plt.close`` is not needed; ``fig.savefig`` works as usual.

    Examples
    --------
    >>> fig = new_figure(4.0, 3.0)
    >>> import matplotlib.pyplot as plt
    >>> fig.get_size_inches().tolist(), fig in map(plt.figure, plt.get_fignums())
    ([4.0, 3.0], False)
    >>> fig._repr_png_()[:4]
    b'\x89PNG'
    """
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    fig = _figure_class()(figsize=(width, height), layout=layout)
    FigureCanvasAgg(fig)
    return fig


def axes_for(ax: Any, count: int, what: str = "signals") -> list[Axes]:
    """The Axes of ``plot(..., ax=ax)`` for ``count`` panels: one each, or all in one.

    ``ax`` is one Axes (every panel drawn into it) or a sequence (or array) of
    ``count`` Axes.

    Examples
    --------
    >>> fig = new_figure(4.0, 3.0)
    >>> axes = fig.subplots(2, 1)
    >>> len(axes_for(axes, 2)), len(axes_for(axes[0], 2))
    (2, 2)
    >>> axes_for(list(axes), 3)
    Traceback (most recent call last):
    ...
    mrsuspension.errors.ValidationError: ax: 2 Axes for 3 signals; give one Axes or 3
    """
    from matplotlib.axes import Axes

    if isinstance(ax, Axes):
        return [ax] * count
    try:
        import numpy as np

        many = list(np.ravel(np.asarray(ax, dtype=object)))
    except TypeError:
        many = []
    if not many or not all(isinstance(a, Axes) for a in many):
        raise ValidationError(
            f"ax must be a matplotlib Axes or a sequence of {count}; got {type(ax).__name__}"
        )
    if len(many) != count:
        raise ValidationError(f"ax: {len(many)} Axes for {count} {what}; give one Axes or {count}")
    return many


def with_unit_headers(df: pd.DataFrame) -> pd.DataFrame:
    """A copy of ``df`` with columns (and the index name) relabelled ``"name [unit]"``
    from ``df.attrs["units"]``: the headers of the CSV files. Names without a unit
    keep their label.

    Examples
    --------
    >>> import pandas as pd
    >>> df = pd.DataFrame({"F_d": [1.0], "law": ["passive"]}, index=pd.Index([0.0], name="time"))
    >>> df.attrs["units"] = {"time": "s", "F_d": "N"}
    >>> out = with_unit_headers(df)
    >>> list(out.columns), out.index.name, list(df.columns)
    (['F_d [N]', 'law'], 'time [s]', ['F_d', 'law'])
    """
    units: Mapping[str, str] = df.attrs.get("units", {})

    def label(name: Any) -> Any:
        unit = units.get(str(name)) if name is not None else None
        return name if unit is None else f"{name} [{unit}]"

    out = df.rename(columns=label)
    out.index = out.index.rename(label(df.index.name))
    return out
