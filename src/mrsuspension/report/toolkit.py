"""The report's figure toolkit: what every chapter module shares.

Chapter modules (``ch2`` ... ``ch7``, :mod:`~mrsuspension.report.beyond`) import this
module and :mod:`~mrsuspension.report.families`, never each other. It holds:

- **figures**: :func:`subplots` (the one panel-grid factory, constrained or with fixed
  margins), :class:`FigureRecord` (a numbered figure with its caption and data, saved as
  PNG/SVG) and :func:`save_figure` (lay out, write one PNG and close);
- **HTML and numbers**: :func:`table` (the one HTML table), :func:`format_cell`,
  :func:`format_number`;
- **shared scenarios**: the constants and helpers more than one chapter uses
  (:data:`HARMONIC`, :data:`SKYHOOK_ACM`, :data:`STEADY_FROM`, :data:`TRACK`, the
  frequency-sweep study of :func:`sweep_study`, the inverse-model helpers of Chapters 5
  and 6 such as :func:`error_figure`), and :func:`in_worker`.

It imports no other module of the report (the figure families build on it), and
matplotlib, the engine, the scenario reader and the study runner only inside the
functions that need them, so importing it stays cheap.
"""

from __future__ import annotations

import html
import math
import multiprocessing
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from mrsuspension.errors import ValidationError

if TYPE_CHECKING:
    from mrsuspension.engine.result import SimulationResult
    from mrsuspension.studies import Study, StudyResult

__all__ = [
    "DPI",
    "DURATION",
    "FORCE_GAINS",
    "FREQUENCY_PANELS",
    "HARMONIC",
    "LABEL_OFFSETS",
    "LEGEND",
    "SHOCK",
    "SHOWN",
    "SKYHOOK_ACM",
    "STEADY_FROM",
    "TABLE_MEASURES",
    "TRACK",
    "Chapter",
    "Context",
    "FigureRecord",
    "Jobs",
    "error_figure",
    "family_chapter",
    "family_note",
    "figure_legend",
    "figure_sections",
    "force_tracking_errors",
    "format_cell",
    "format_number",
    "harmonic_runs",
    "in_worker",
    "inverse_model_step",
    "label_outer_x",
    "legend_columns",
    "plot_selections",
    "plot_sweep",
    "reused_subplots",
    "run_sweep",
    "save_figure",
    "share_x",
    "shock_table_html",
    "shown",
    "side_legend",
    "spread_labels",
    "steady",
    "subplots",
    "sweep_study",
    "table",
    "table_sections",
    "tracking_error",
    "write_csv",
    "write_png",
]


# -- figures -------------------------------------------------------------------------------
#: panel-grid layouts of :func:`subplots`
LAYOUTS = ("constrained", "fixed")


def subplots(
    nrows: int,
    ncols: int,
    width: float = 4.2,
    height: float = 3.4,
    *,
    layout: str = "constrained",
    legend_rows: int = 0,
    title_rows: int = 0,
) -> tuple[Any, Any]:
    """A figure with an ``nrows`` x ``ncols`` grid of panels (always a 2-D axes array).

    Parameters
    ----------
    nrows, ncols : int
        Panel rows and columns.
    width, height : float
        Size of one panel [in].
    layout : {"constrained", "fixed"}
        ``"fixed"``: fixed margins and a 0.35 in title strip, for every figure whose texts
        fit them (``--check-layout`` says so); drawing is about a sixth cheaper.
        ``"constrained"``: matplotlib's constrained layout, for figures with texts
        outside the panels' usual margins (a legend beside or below a panel, a twin y
        axis on the right).
    legend_rows : int
        ``"fixed"`` only: rows of a figure legend to leave room for between the title
        and the panels (:func:`figure_legend`), 0.22 in each.
    title_rows : int
        ``"fixed"`` only: lines of panel titles (``ax.set_title``) above the first row
        of panels to leave room for, 0.25 in each.

    Returns
    -------
    tuple
        The matplotlib figure and its axes array.

    Raises
    ------
    ValidationError
        For an unknown ``layout``.

    Examples
    --------
    >>> fig, axes = subplots(2, 3, 3.3, 2.5, layout="fixed")
    >>> axes.shape, [round(float(v), 2) for v in fig.get_size_inches()]
    ((2, 3), [9.9, 5.35])
    >>> import matplotlib.pyplot as plt; plt.close(fig)
    """
    if layout not in LAYOUTS:
        raise ValidationError(f"layout: unknown {layout!r}; valid: {', '.join(LAYOUTS)}")
    import matplotlib

    matplotlib.use("Agg", force=False)
    import matplotlib.pyplot as plt

    if layout == "constrained":
        return plt.subplots(
            nrows,
            ncols,
            figsize=(width * ncols, height * nrows),
            squeeze=False,
            layout="constrained",
        )
    size, margins = _fixed_layout(nrows, ncols, width, height, legend_rows, title_rows)
    fig, axes = plt.subplots(nrows, ncols, figsize=size, squeeze=False)
    fig.subplots_adjust(**margins)
    return fig, axes


def _fixed_layout(
    nrows: int, ncols: int, width: float, height: float, legend_rows: int, title_rows: int
) -> tuple[tuple[float, float], dict[str, float]]:
    """The fixed layout's figure size [in] and ``subplots_adjust`` margins."""
    strip = _LEGEND_ROW * legend_rows + _TITLE_ROW * title_rows
    fig_w, fig_h = width * ncols, height * nrows + 0.35 + strip
    margins = {
        "left": 0.95 / fig_w,
        "right": 1 - 0.15 / fig_w,
        "bottom": 0.5 / fig_h,
        "top": 1 - (0.45 + strip) / fig_h,
        "wspace": 0.5,
        "hspace": 0.42,
    }
    return (fig_w, fig_h), margins


#: the figures of :func:`reused_subplots`, by key (one set per process)
_REUSED: dict[Any, tuple[Any, Any]] = {}


def reused_subplots(
    key: Any,
    nrows: int,
    ncols: int,
    width: float = 4.2,
    height: float = 3.4,
    *,
    legend_rows: int = 0,
    title_rows: int = 0,
) -> tuple[Any, Any]:
    """:func:`subplots` (fixed layout) made once per ``key`` and process, then reused.

    The second call with a ``key`` returns the same figure with its data artists
    (lines, collections, patches, texts, images), legends, titles and axis labels removed,
    data limits reset and colour cycles restarted; what the figure function set besides
    (scales, locators, visibility, shared axes) stays, so ``key`` must name everything
    that sets up a figure differently (the figure family and its panels). Drawing such a
    figure again is about a third cheaper than drawing a new one: matplotlib keeps its
    axes, ticks and renderer (and so the renderer's cache of text sizes).
    :meth:`FigureRecord.save` leaves it open (``plt.close`` does not know it).

    Examples
    --------
    >>> fig, axes = reused_subplots("doc", 1, 2, legend_rows=1)
    >>> _ = axes[0, 0].plot([0, 1], [0, 5], label="a")
    >>> again, axes2 = reused_subplots("doc", 1, 2, legend_rows=1)
    >>> again is fig, len(axes2[0, 0].lines), axes2[0, 0].get_ylabel()
    (True, 0, '')
    >>> from matplotlib.colors import to_hex
    >>> _ = axes2[0, 0].plot([0, 1], [0, 1]); to_hex(axes2[0, 0].get_lines()[0].get_color())
    '#1f77b4'
    """
    hit = _REUSED.get(key)
    if hit is not None:
        fig, axes = hit
        for legend in list(fig.legends):
            legend.remove()
        for ax in axes.flat:
            artists = [*ax.lines, *ax.collections, *ax.patches, *ax.texts, *ax.images]
            for artist in artists:
                artist.remove()
            if ax.get_legend() is not None:
                ax.get_legend().remove()
            for title in (ax.title, ax._left_title, ax._right_title):
                title.set_text("")
            ax.set_xlabel("")
            ax.set_ylabel("")
            ax.set_prop_cycle(None)  # colours from C0 again
            ax.relim()  # no data: limits follow what is plotted next
            ax.set_autoscale_on(True)
        return fig, axes
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    size, margins = _fixed_layout(nrows, ncols, width, height, legend_rows, title_rows)
    fig = Figure(figsize=size, dpi=DPI)  # outside pyplot: plt.close leaves it
    FigureCanvasAgg(fig)
    axes = fig.subplots(nrows, ncols, squeeze=False)
    fig.subplots_adjust(**margins)
    _REUSED[key] = (fig, axes)
    return fig, axes


#: Resolution of the report's PNG figures [dots per inch]
DPI = 110

#: zlib level of the report's PNGs (1-9; Pillow's default is 6). Measured on the quick
#: report's 91 PNGs: level 3 encodes in 0.70 of the time for 8 % larger files.
PNG_COMPRESSION = 3

_MATHTEXT: Any = None


def _mathtext_parser() -> Any:
    """The process's one mathtext parser for Agg renderers (created on first use)."""
    global _MATHTEXT
    if _MATHTEXT is None:
        from matplotlib.mathtext import MathTextParser

        _MATHTEXT = MathTextParser("path")  # what RendererAgg makes for itself
    return _MATHTEXT


def lighten(fig: Any) -> Any:
    """Make ``fig`` cheaper to draw as a PNG at :data:`DPI` without changing what it shows.

    - Its resolution becomes :data:`DPI`, so a legibility check's draw and the PNG's draw
      share one renderer (and its cache of text sizes).
    - That renderer gets the process's one mathtext parser: matplotlib caches parsed math
      (``$a_s$``, log tick labels ``10^{-2}``) per parser and makes a new parser with
      each renderer, i.e. each figure, so the same few labels were parsed again in every
      figure (605 parses of 34 strings for the 70 family figures of the quick report;
      sharing the parser saves about 15 % of their CPU).

    :meth:`FigureRecord.save` calls it; calling it again is harmless.

    Examples
    --------
    >>> fig, axes = subplots(1, 1, layout="fixed")
    >>> _ = axes[0, 0].set_ylabel("$a_s$ [m/s$^2$]")
    >>> lighten(fig).canvas.get_renderer().mathtext_parser is _mathtext_parser()
    True
    >>> import matplotlib.pyplot as plt; plt.close(fig)
    """
    fig.set_dpi(DPI)
    renderer = getattr(fig.canvas, "get_renderer", lambda: None)()
    if renderer is not None and hasattr(renderer, "mathtext_parser"):
        renderer.mathtext_parser = _mathtext_parser()
    return fig


def share_x(axes: Any) -> Any:
    """Let the panels of ``axes`` share the first one's x axis; returns ``axes``.

    Examples
    --------
    >>> fig, axes = subplots(2, 1, layout="fixed")
    >>> _ = share_x(axes.ravel())
    >>> _ = axes[1, 0].set_xlim(2.0, 3.0); [float(v) for v in axes[0, 0].get_xlim()]
    [2.0, 3.0]
    >>> import matplotlib.pyplot as plt; plt.close(fig)
    """
    first, *rest = list(axes)
    shared = first.get_shared_x_axes()
    for ax in rest:
        if not shared.joined(first, ax):  # a reused figure's axes are shared already
            ax.sharex(first)
    return axes


def label_outer_x(axes: Any) -> int:
    """Hide the x tick labels and x label of each panel that has, right below it, a
    visible panel sharing its x axis (:func:`share_x`): the bottom one says it for both.

    Fewer texts to lay out and draw (about a tenth of a stacked figure's CPU), and the
    panels read as one column.

    Parameters
    ----------
    axes : numpy.ndarray
        The figure's 2-D axes array (:func:`subplots`), with x labels and visibility set.

    Returns
    -------
    int
        Panels whose x labels were hidden.

    Examples
    --------
    >>> fig, axes = subplots(2, 2, layout="fixed")
    >>> _ = share_x(axes[:, 0])
    >>> for ax in axes.ravel():
    ...     _ = ax.set_xlabel("time [s]")
    >>> label_outer_x(axes), axes[0, 0].get_xlabel(), axes[0, 1].get_xlabel()
    (1, '', 'time [s]')
    >>> import matplotlib.pyplot as plt; plt.close(fig)
    """
    hidden = 0
    rows, cols = axes.shape
    for r in range(rows - 1):
        for c in range(cols):
            ax, below = axes[r, c], axes[r + 1, c]
            if (
                ax.get_visible()
                and below.get_visible()
                and ax.get_shared_x_axes().joined(ax, below)
            ):
                ax.tick_params(axis="x", labelbottom=False)
                ax.set_xlabel("")
                hidden += 1
    return hidden


def write_png(fig: Any, path: Path, *, drawn: bool = False) -> Path:
    """Write ``fig`` (drawn at :data:`DPI` by :func:`lighten`) as an RGB PNG at ``path``.

    What ``fig.savefig(path, dpi=DPI)`` writes, without its alpha channel (the report's
    figures are opaque: a quarter less to compress, files about a tenth smaller) and at
    zlib level :data:`PNG_COMPRESSION`. ``drawn``: the figure was just drawn (e.g. by
    the layout check), so its pixels are written without drawing it again.

    Examples
    --------
    >>> import tempfile
    >>> from PIL import Image
    >>> fig, axes = subplots(1, 1, layout="fixed")
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     image = Image.open(write_png(lighten(fig), Path(tmp) / "a.png"))
    ...     image.mode, image.size
    ('RGB', (462, 412))
    >>> import matplotlib.pyplot as plt; plt.close(fig)
    """
    from PIL import Image

    canvas = fig.canvas
    if not hasattr(canvas, "buffer_rgba"):  # a figure made outside pyplot, no canvas yet
        from matplotlib.backends.backend_agg import FigureCanvasAgg

        canvas, drawn = FigureCanvasAgg(fig), False
    if not drawn or fig.dpi != DPI:
        fig.set_dpi(DPI)
        canvas.draw()
    rgba = np.asarray(canvas.buffer_rgba())
    Image.fromarray(rgba[..., :3]).save(path, format="png", compress_level=PNG_COMPRESSION)
    return path


#: Height of one row of a figure legend above fixed-layout panels [in]
_LEGEND_ROW = 0.22
#: Height of one line of panel titles above fixed-layout panels [in]
_TITLE_ROW = 0.25


def legend_columns(labels: Sequence[str], width: float, fontsize: float = 7.0) -> int:
    """Columns of a one-line-per-row figure legend of ``labels`` across ``width`` inches.

    An entry is estimated as its handle (0.4 in) plus 0.55 em per character.

    Examples
    --------
    >>> legend_columns(["0 A", "0.1 A", "0.2 A"], 9.9), legend_columns(["x" * 60] * 3, 6.6)
    (3, 1)
    """
    if not labels:
        return 1
    entry = 0.4 + 0.55 * fontsize / 72.0 * max(len(str(t)) for t in labels)
    return max(1, min(len(labels), int((width - 0.3) // entry)))


def figure_legend(fig: Any, ax: Any, *, fontsize: float = 7.0, **options: Any) -> Any:
    """One legend for the whole figure, outside every panel, from the curves of ``ax``.

    With constrained layout it goes below the panels (the layout makes room); with the
    fixed layout into the strip left between the title and the panels
    (:func:`subplots` ``legend_rows``, e.g. from :func:`legend_columns`).

    Examples
    --------
    >>> fig, axes = subplots(1, 2, layout="fixed", legend_rows=1)
    >>> _ = axes[0, 0].plot([0, 1], label="a"); _ = axes[0, 1].plot([1, 0])
    >>> figure_legend(fig, axes[0, 0]).get_texts()[0].get_text()
    'a'
    >>> import matplotlib.pyplot as plt; plt.close(fig)
    """
    handles, labels = ax.get_legend_handles_labels()
    width, height = fig.get_size_inches()
    ncols = options.pop("ncols", legend_columns(labels, width, fontsize))
    if fig.get_layout_engine() is not None:
        return fig.legend(
            handles, labels, loc="outside lower center", ncols=ncols, fontsize=fontsize, **options
        )
    return fig.legend(
        handles,
        labels,
        loc="upper center",
        bbox_to_anchor=(0.5, 1 - 0.33 / height),
        ncols=ncols,
        fontsize=fontsize,
        frameon=False,
        borderaxespad=0.0,
        **options,
    )


def side_legend(ax: Any, **options: Any) -> Any:
    """A legend beside ``ax`` (to its right, top-aligned), off the data.

    Examples
    --------
    >>> fig, axes = subplots(1, 1)
    >>> _ = axes[0, 0].plot([0, 1], label="a")
    >>> side_legend(axes[0, 0], fontsize=8).get_texts()[0].get_text()
    'a'
    >>> import matplotlib.pyplot as plt; plt.close(fig)
    """
    return ax.legend(loc="upper left", bbox_to_anchor=(1.02, 1.0), borderaxespad=0.0, **options)


#: Offsets [pt] tried in turn for a point's label by :func:`spread_labels`
LABEL_OFFSETS: tuple[tuple[float, float], ...] = (
    (3, 3), (3, -9), (-3, 3), (-3, -9), (3, 11), (3, -17), (-3, 11), (-3, -17),
)  # fmt: skip


def spread_labels(fig: Any, offsets: Sequence[tuple[float, float]] = LABEL_OFFSETS) -> int:
    """Move point labels (annotations in offset points, no arrow) so that no two overlap.

    Each label takes the first offset of ``offsets`` (to the right for positive x, to
    the left otherwise) where it overlaps no label placed before it nor the axes' other
    texts; a label that fits nowhere keeps the first offset.

    Returns
    -------
    int
        Labels moved from the first offset.

    Examples
    --------
    >>> fig, axes = subplots(1, 1)
    >>> ax = axes[0, 0]
    >>> for x in (0.0, 0.0001):
    ...     _ = ax.annotate("k_c = 10", (x, 0.0), xytext=(3, 3), textcoords="offset points")
    >>> spread_labels(fig)
    1
    >>> import matplotlib.pyplot as plt; plt.close(fig)
    """
    from matplotlib.text import Annotation

    from mrsuspension.report.legibility import overlap

    fig.canvas.draw()  # resolve the layout: label positions are then final
    renderer = fig.canvas.get_renderer()
    moved = 0
    for ax in fig.axes:
        labels = [
            t
            for t in ax.texts
            if isinstance(t, Annotation)
            and t.anncoords == "offset points"
            and t.arrow_patch is None  # a note with an arrow stays where it points from
            and t.get_visible()
        ]
        placed = [t.get_window_extent(renderer) for t in ax.texts if t not in labels]
        for label in labels:
            for k, (dx, dy) in enumerate([*offsets, offsets[0]]):
                label.xyann = (dx, dy)
                label.set_horizontalalignment("left" if dx >= 0 else "right")
                box = label.get_window_extent(renderer)
                # a 2 px margin: the saved figure is drawn again (at its DPI, with its
                # title), which moves the labels by a pixel or so
                if k == len(offsets) or not any(overlap(box.padded(2), b) for b in placed):
                    break
            moved += k > 0
            placed.append(box)
    return moved


@dataclass
class FigureRecord:
    """A figure with its number, caption, and the numbers behind it.

    Examples
    --------
    >>> fig, _ = subplots(1, 1)
    >>> FigureRecord("4.3b", "A title", "A caption.", fig).slug
    'fig_4_3b'
    >>> import matplotlib.pyplot as plt; plt.close(fig)
    """

    number: str
    title: str
    caption: str
    figure: Any  # matplotlib.figure.Figure
    data: dict[str, Any] = field(default_factory=dict)
    files: list[str] = field(default_factory=list)
    issues: list[str] | None = None

    @property
    def slug(self) -> str:
        """File stem, e.g. ``fig_2_3``."""
        return "fig_" + self.number.replace(".", "_")

    def save(
        self, folder: Path, formats: Sequence[str] = ("png",), *, check: bool = False
    ) -> list[Path]:
        """Title the figure ``Fig. <number>: <title>``, write it in each format and close it.

        Parameters
        ----------
        folder : Path
            Where the files go (created).
        formats : sequence of str
            File formats: PNG by default (SVG costs as much again as drawing the figure).
        check : bool
            Also list what makes the figure hard to read in :attr:`issues`
            (:func:`~mrsuspension.report.legibility.layout_issues`; its draw is the
            PNG's).

        Returns
        -------
        list of Path
            The files written.
        """
        import matplotlib.pyplot as plt

        folder.mkdir(parents=True, exist_ok=True)
        self.figure.suptitle(f"Fig. {self.number}: {self.title}", fontsize=10)
        lighten(self.figure)
        drawn = False
        if check:
            from mrsuspension.report.legibility import layout_issues

            self.issues = layout_issues(self.figure)  # draws the figure at DPI
            drawn = True
        paths = []
        for fmt in formats:
            path = folder / f"{self.slug}.{fmt}"
            if fmt == "png":
                write_png(self.figure, path, drawn=drawn)
            else:
                self.figure.savefig(path, dpi=DPI)
                drawn = False
            paths.append(path)
        plt.close(self.figure)
        self.files = [p.name for p in paths]
        return paths


def save_figure(fig: Any, folder: Path, name: str, dpi: int = 90) -> str:
    """Lay out (tight), write ``folder/name`` and close ``fig``; returns ``name``.

    Examples
    --------
    >>> import tempfile
    >>> import matplotlib.pyplot as plt
    >>> fig = plt.figure()
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     save_figure(fig, Path(tmp), "one.png")
    'one.png'
    """
    import matplotlib.pyplot as plt

    fig.tight_layout()
    fig.savefig(folder / name, dpi=dpi)
    plt.close(fig)
    return name


# -- HTML and numbers ----------------------------------------------------------------------
def format_cell(value: Any, fmt: str = "{:.3g}") -> str:
    """A table cell: ``"-"`` for None, ``fmt`` for floats, ``str`` otherwise.

    Examples
    --------
    >>> format_cell(0.98612), format_cell(None), format_cell(3), format_cell(2.5, "{:g}")
    ('0.986', '-', '3', '2.5')
    """
    if value is None:
        return "-"
    return fmt.format(value) if isinstance(value, float) else str(value)


def format_number(value: Any, percent: bool = False) -> str:
    """A number to 4 digits, or a signed percentage of a ratio; ``"-"`` if missing.

    Examples
    --------
    >>> format_number(1234.567), format_number(-0.01234, percent=True)
    ('1235', '-1.23 %')
    >>> format_number(None), format_number(float("nan"))
    ('-', '-')
    """
    if value is None or (isinstance(value, float) and not math.isfinite(value)):
        return "-"
    return f"{100 * value:+.2f} %" if percent else f"{value:.4g}"


def table(
    rows: Sequence[Mapping[str, Any]] | Sequence[Sequence[Any]],
    header: Sequence[str] | None = None,
    fmt: str = "{:.4g}",
) -> str:
    """An HTML table: floats by ``fmt``, numbers right-aligned, text left (``class="l"``).

    Parameters
    ----------
    rows : sequence of mappings or of sequences
        Mappings: the keys of the first row are the header. Sequences: give ``header``
        (it may repeat a name, e.g. ``"diff"`` after each measure).
    header : sequence of str, optional
        Column names of sequence rows.
    fmt : str
        Format of float cells.

    Returns
    -------
    str
        ``<table>...</table>``; empty without rows and header.

    Examples
    --------
    >>> table([{"name": "k_c", "value": 3.0}])
    '<table><tr><th>name</th><th>value</th></tr><tr><td class="l">k_c</td><td>3</td></tr></table>'
    >>> table([["1.5", 0.25]], header=["f [Hz]", "diff"])
    '<table><tr><th>f [Hz]</th><th>diff</th></tr><tr><td class="l">1.5</td><td>0.25</td></tr></table>'
    """
    if header is None:
        if not rows:
            return ""
        first = rows[0]
        if not isinstance(first, Mapping):
            raise ValidationError("table: rows without names need a header")
        keys = list(first)
        values = [[r[k] for k in keys] for r in rows]  # type: ignore[call-overload]
        header = [str(k) for k in keys]
    else:
        values = [list(r.values()) if isinstance(r, Mapping) else list(r) for r in rows]
    head = "".join(f"<th>{html.escape(str(k))}</th>" for k in header)
    body = []
    for row in values:
        cells = []
        for v in row:
            text = fmt.format(v) if isinstance(v, float) else str(v)
            cls = "" if isinstance(v, int | float) else ' class="l"'
            cells.append(f"<td{cls}>{html.escape(text)}</td>")
        body.append("<tr>" + "".join(cells) + "</tr>")
    return f"<table><tr>{head}</tr>{''.join(body)}</table>"


def _number_key(number: str) -> tuple[int, int, str]:
    """Sort key of a figure number: ``"4.3b"`` -> (4, 3, "b"); non-numeric parts last."""
    chapter, _, rest = number.partition(".")
    digits = "".join(c for c in rest if c.isdigit())
    tail = rest[len(digits) :]
    return (int(chapter) if chapter.isdigit() else 99, int(digits) if digits else 999, tail)


def figure_sections(
    chapter: int, records: Mapping[str, dict[str, Any]], folder: Path
) -> tuple[list[str], list[dict[str, Any]]]:
    """HTML ``<figure>`` elements and manifest records of a chapter's built figures.

    Parameters
    ----------
    chapter : int
        Chapter number (the files are under ``chapter<N>/``).
    records : mapping
        ``"<sub-folder>/<number>"`` -> figure record (``families.Built.figures``); only the
        records under ``folder``'s name are taken.
    folder : Path
        The chapter's output folder.

    Returns
    -------
    tuple
        The HTML of each figure and the records, in figure-number order.

    Examples
    --------
    >>> rec = {"number": "4.10", "title": "T", "caption": "C.", "files": ["fig_4_10.png"]}
    >>> html_parts, recs = figure_sections(4, {"chapter4/4.10": rec}, Path("out/chapter4"))
    >>> html_parts[0][:44]
    '<figure id="fig_4_10"><img src="chapter4/fig'
    """
    prefix = f"{folder.name}/"
    chosen = sorted(
        (rec for key, rec in records.items() if key.startswith(prefix)),
        key=lambda r: _number_key(r["number"]),
    )
    sections = []
    for rec in chosen:
        slug = "fig_" + rec["number"].replace(".", "_")
        svg = (
            f' <a href="chapter{chapter}/{slug}.svg">SVG</a>'
            if f"{slug}.svg" in rec["files"]
            else ""
        )
        sections.append(
            f'<figure id="{slug}"><img src="chapter{chapter}/{slug}.png" '
            f'alt="Fig. {html.escape(rec["number"])}"><figcaption><b>Fig. '
            f"{html.escape(rec['number'])}: {html.escape(rec['title'])}.</b> "
            f"{html.escape(rec['caption'])}{svg}</figcaption></figure>"
        )
    return sections, chosen


#: Shock-response measures of the tables, and with the DTR
SHOCK: tuple[str, ...] = ("SDR_s", "SAR_s", "SDR_u", "SAR_u", "RDR")
TABLE_MEASURES: tuple[str, ...] = (*SHOCK, "DTR")

#: The legend of the shock tables' cell colours (families.AGREEMENT_BANDS)
LEGEND = (
    "<p class='meta'>Each measure: ours | the dissertation's | ours/theirs (DTR: ours - "
    "theirs). <span class='green'>within 10 %</span> <span class='amber'>within 25 %"
    "</span> <span class='red'>beyond 25 %</span>; DTR by the absolute difference: within "
    "0.025, within 0.05, beyond.</p>"
)


def shock_table_html(tab: Mapping[str, Any]) -> str:
    """A shock table (:func:`~mrsuspension.report.families.shock_table`) as HTML.

    One group of three columns per measure, ours | dissertation | ratio (DTR: the
    difference), each group's cells coloured by its ``agreement`` band, then the peak
    tire force; a summary line below gives each measure's share of cells within 25 %
    (DTR: within 0.05).

    Examples
    --------
    >>> row = {"m_s (kg)": 563.0, "SDR_s model": 0.7, "SDR_s dissertation": 0.71,
    ...        "SDR_s ratio": 0.986, "SDR_s agreement": "green"}
    >>> tab = {"rows": [row], "summary": {"SDR_s": {"within": 1, "cells": 1, "share": 1.0}}}
    >>> html_text = shock_table_html(tab)
    >>> '<td class="green">0.986</td>' in html_text, "SDR_s 1/1" in html_text
    (True, True)
    """
    rows = tab["rows"]
    if not rows:
        return ""
    column = next(iter(rows[0]))
    measures = [k for k in TABLE_MEASURES if f"{k} model" in rows[0]]
    last = "DTR difference"
    extra = [
        k
        for k in rows[0]
        if k != column and not any(k.startswith(f"{m} ") for m in measures) and k != last
    ]
    top = f"<th rowspan='2' class='l'>{html.escape(column)}</th>" + "".join(
        f"<th colspan='3'>{html.escape(m)}</th>" for m in measures
    )
    top += "".join(f"<th rowspan='2'>{html.escape(k)}</th>" for k in extra)
    sub = "".join(
        "<th>ours</th><th>diss.</th><th>" + ("diff." if m == "DTR" else "ratio") + "</th>"
        for m in measures
    )
    body = []
    for r in rows:
        cells = [f"<td class='l'>{html.escape(format_cell(r[column], '{:g}'))}</td>"]
        for m in measures:
            band = html.escape(str(r.get(f"{m} agreement", "")))
            third = r.get("DTR difference") if m == "DTR" else r.get(f"{m} ratio")
            for v in (r[f"{m} model"], r[f"{m} dissertation"], third):
                cells.append(f'<td class="{band}">{html.escape(format_cell(v))}</td>')
        cells += [f"<td>{html.escape(format_cell(r[k], '{:.4g}'))}</td>" for k in extra]
        body.append("<tr>" + "".join(cells) + "</tr>")
    summary = tab.get("summary", {})
    line = ", ".join(
        f"{m} {s['within']}/{s['cells']} ({100 * s['share']:.0f} %)" for m, s in summary.items()
    )
    return f"<table><tr>{top}</tr><tr>{sub}</tr>{''.join(body)}</table>" + (
        f"<p class='meta'>Cells within 25 % (DTR: within 0.05): {line}.</p>" if line else ""
    )


def write_csv(path: Path, rows: Sequence[Mapping[str, Any]]) -> None:
    """Write dict rows to ``path`` as CSV (the header: the first row's keys).

    Examples
    --------
    >>> import tempfile
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     write_csv(Path(tmp) / "t.csv", [{"a": 1, "b": 2.5}])
    ...     (Path(tmp) / "t.csv").read_text().splitlines()
    ['a,b', '1,2.5']
    """
    import csv

    with path.open("w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)


def table_sections(
    chapter: int, tables: Sequence[Mapping[str, Any]], folder: Path
) -> tuple[str, list[dict[str, Any]]]:
    """Write each shock table as CSV; the HTML of all of them and their manifest entries.

    Parameters
    ----------
    chapter : int
        Chapter number.
    tables : sequence of mapping
        Built shock tables (:func:`~mrsuspension.report.families.shock_table`).
    folder : Path
        The chapter's output folder (the CSV files go there).

    Returns
    -------
    tuple
        The HTML (the colour legend first) and each table's manifest entry.

    Examples
    --------
    >>> import tempfile
    >>> tab = {"number": "9.1", "title": "T", "caption": "C.", "rows": [{"V": 50.0}]}
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     text, entries = table_sections(9, [tab], Path(tmp))
    >>> text.startswith(LEGEND), entries[0]["file"]
    (True, 'chapter9/table_9_1.csv')
    """
    out = []
    parts = []
    for tab in tables:
        slug = "table_" + tab["number"].replace(".", "_")
        write_csv(folder / f"{slug}.csv", tab["rows"])
        out.append({**tab, "file": f"chapter{chapter}/{slug}.csv"})
        parts.append(
            f"<h3 id='{slug}'>Table {html.escape(tab['number'])}: {html.escape(tab['title'])}"
            f"</h3><p>{html.escape(tab['caption'])} <a href='chapter{chapter}/{slug}.csv'>"
            f"{slug}.csv</a></p>" + shock_table_html(tab)
        )
    return (LEGEND if parts else "") + "".join(parts), out


_FAMILY_NOTE = (
    "<p>Every figure below is a figure family (mrsuspension.report.families): a base "
    "scenario and its variants, run once each and shared between figures and tables. Time "
    "histories: 2.5 cm harmonic at 1.5 Hz (steady state 6-7.4 s); frequency responses: "
    "two-stage swept excitation a = 2.5 cm, f_T = 2.1 Hz, 0.5-15 Hz; transients: rounded "
    "pulse mu = 3, a_m = 3.5 cm, 50 km/h; random responses: the 'rough' preset road at "
    "50 km/h, a stand-in for the dissertation's Canadian roads (which are not available), "
    "defined by its PSD level (G_d(n) = G_d(n0) (n/0.1)^-1, G_d(n0) tuned against the "
    "dissertation's DLCs). "
    "Each record in manifest.json holds the scenario of every curve and the numbers behind "
    "it; each table sets our values beside the dissertation's.{quick}</p>"
)


def family_note(quick: bool) -> str:
    """The paragraph that opens a chapter of figure families (Chapters 4-6).

    Examples
    --------
    >>> "Quick mode" in family_note(True), "Quick mode" in family_note(False)
    (True, False)
    """
    return _FAMILY_NOTE.format(
        quick=" Quick mode: 10 frequencies and a 0.5 ms step (0.25 ms for the inverse-model laws)."
        if quick
        else ""
    )


def family_chapter(
    context: Context, heading: str, tables: Sequence[Any], intro: str = ""
) -> tuple[str, dict[str, Any]]:
    """The HTML and manifest entry of a chapter of figure families and shock tables.

    Parameters
    ----------
    context : Context
        The chapter's build context.
    heading : str
        The chapter's ``<h2>`` text.
    tables : sequence of ShockTable
        The chapter's shock tables (their built rows are in ``context.built.tables``).
    intro : str
        HTML after the family note.

    Returns
    -------
    tuple
        The body HTML and ``{"figures": [...], "tables": [...]}``.

    Examples
    --------
    >>> from types import SimpleNamespace
    >>> built = SimpleNamespace(figures={}, tables={})
    >>> context = Context(9, Path("out/chapter9"), True, built, print)
    >>> body, manifest = family_chapter(context, "Chapter 9: more", [])
    >>> body[:33], manifest
    ("<h2 id='ch9'>Chapter 9: more</h2>", {'figures': [], 'tables': []})
    """
    n = context.number
    sections, records = figure_sections(n, context.built.figures, context.folder)
    tables_html, built_tables = table_sections(
        n, [context.built.tables[t.number] for t in tables], context.folder
    )
    body = (
        f"<h2 id='ch{n}'>{html.escape(heading)}</h2>"
        + family_note(context.quick)
        + intro
        + "".join(sections)
        + tables_html
    )
    return body, {"figures": records, "tables": built_tables}


# -- chapters ------------------------------------------------------------------------------
@dataclass(frozen=True)
class Jobs:
    """What a chapter needs built in the report's process pool.

    The arguments of :func:`~mrsuspension.report.families.build_all`, merged over the
    chosen chapters so that one pool runs them all.

    Parameters
    ----------
    figures : mapping
        Sub-folder (``"chapter4"``) -> figure specs.
    tables : sequence of ShockTable
        Shock tables.
    specials : sequence
        ``(sub-folder, builder, quick or None)``: figure functions that draw themselves.
    calls : mapping
        Name -> ``(function, args)``: other work for the pool (its result under
        ``Built.calls[name]``).

    Examples
    --------
    >>> Jobs(tables=("4.1",)).tables, Jobs().figures
    (('4.1',), {})
    """

    figures: Mapping[str, Sequence[Any]] = field(default_factory=dict)
    tables: Sequence[Any] = ()
    specials: Sequence[tuple[str, Callable[..., Any], bool | None]] = ()
    calls: Mapping[str, tuple[Callable[..., Any], tuple[Any, ...]]] = field(default_factory=dict)


@dataclass(frozen=True)
class Context:
    """What a chapter's ``build`` gets: its number and folder, the mode, the pool's results.

    Parameters
    ----------
    number : int
        Chapter number.
    folder : Path
        Output folder of the chapter (``<report>/chapter<N>``).
    quick : bool
        Quick mode.
    built : families.Built
        What the report's one pool built (figures, tables, call results).
    progress : callable
        Progress messages.

    Examples
    --------
    >>> Context(4, Path("out/chapter4"), True, None, print).folder.name
    'chapter4'
    """

    number: int
    folder: Path
    quick: bool
    built: Any
    progress: Callable[[str], None]


@dataclass(frozen=True)
class Chapter:
    """A chapter of the report: what it needs built, and how it writes its section.

    Each chapter module exposes one ``CHAPTER`` and is named in
    :data:`mrsuspension.report.chapters.CHAPTERS`.

    Parameters
    ----------
    number : int
        Chapter number (``chapter<N>/`` folder, ``#ch<N>`` anchor, manifest key).
    jobs : callable
        ``jobs(quick) -> Jobs``.
    build : callable
        ``build(context) -> (body HTML, manifest entry)``, after the pool ran.
    figures, tables : tuple
        The chapter's figure families and shock tables, for the ``docs/report.md`` index
        (empty for chapters of special figures only).

    Examples
    --------
    >>> ch = Chapter(9, lambda quick: Jobs(), lambda ctx: ("<h2>9</h2>", {}))
    >>> ch.jobs(True).figures, ch.build(None)[0]
    ({}, '<h2>9</h2>')
    """

    number: int
    jobs: Callable[[bool], Jobs]
    build: Callable[[Context], tuple[str, dict[str, Any]]]
    figures: tuple[Any, ...] = ()
    tables: tuple[Any, ...] = ()


# -- shared scenarios ----------------------------------------------------------------------
#: The harmonic input of the time histories: 2.5 cm at 1.5 Hz (Chapters 4-6)
HARMONIC: dict[str, Any] = {"kind": "harmonic", "frequency": 1.5, "amplitude": 0.025}
#: Skyhook hi-lo in ACM with the section 4.4 parameters (n = 2, k_c = 3, p = 0)
SKYHOOK_ACM: dict[str, Any] = {"law": "skyhook-hilo", "mode": "ACM", "gain": 3.0}
#: Length of the Chapter 5-6 time-history runs [s] and the start of their steady window [s]
DURATION = 8.0
STEADY_FROM = 4.0
#: The time window shown in the time-history panels [s]
SHOWN = (6.0, 7.4)
#: The section 5.3 force gains k_d (1 = the nominal damper)
FORCE_GAINS: tuple[float, ...] = (1.0, 1.5, 2.0, 2.5)
#: Force-tracking panels: damper force, its target, current, accelerations, stroke
TRACK = ("F_d", "F*", "i_d", "a_s", "a_u", "x_r")
#: The frequency-response panels of :func:`plot_sweep`: (measure, axis label)
FREQUENCY_PANELS = (
    ("T_as", "$T_{as}$"),
    ("T_au", "$T_{au}$"),
    ("T_dr", "$T_{dr}$"),
    ("DLC", "DLC"),
)


def in_worker() -> bool:
    """True in a child process (a pool worker): nested pools are then avoided.

    Examples
    --------
    >>> in_worker()
    False
    """
    return multiprocessing.parent_process() is not None


def inverse_model_step(quick: bool) -> float:
    """Fixed step [s]: 0.25 ms in quick mode (stable up to k_d = 2.5), else 0.1 ms.

    Examples
    --------
    >>> inverse_model_step(True), inverse_model_step(False)
    (0.00025, 0.0001)
    """
    return 2.5e-4 if quick else 1e-4


def sweep_study(quick: bool, name: str, **tables: Any) -> Study:
    """A two-stage swept study (a = 2.5 cm, f_T = 2.1 Hz) over 0.5-15 Hz.

    Parameters
    ----------
    quick : bool
        10 frequencies and dt = 0.5 ms, else 30 frequencies and dt = 0.1 ms.
    name : str
        Study name.
    **tables
        Further study tables (``controller``, ``grid``, ``cases``, ...).

    Returns
    -------
    Study

    Examples
    --------
    >>> study = sweep_study(True, "demo")
    >>> len(study.frequencies), study.measures
    (10, ('T_as', 'T_au', 'T_dr', 'DLC'))
    """
    from mrsuspension.studies import Study

    data: dict[str, Any] = {
        "study": {"name": name, "measures": [k for k, _ in FREQUENCY_PANELS]},
        "excitation": {
            "kind": "swept",
            "amplitude": 0.025,
            "transition_frequency": 2.1,
            "frequencies": "log:10:0.5:15" if quick else "log:30:0.5:15",
        },
        "simulation": {"dt": 5e-4 if quick else 1e-4},
        **tables,
    }
    return Study.from_dict(data)


def run_sweep(study: Study) -> StudyResult:
    """Run ``study`` quietly and uncached (in this process inside a report worker).

    Examples
    --------
    >>> study = sweep_study(True, "demo", controller={"law": "passive", "current": 0.0})
    >>> result = run_sweep(study)
    >>> result.to_xarray()["T_as"].shape
    (10,)
    """
    from mrsuspension.studies import run_study

    return run_study(study, workers=1 if in_worker() else None, progress=False, cache_dir=False)


def plot_sweep(
    result: StudyResult, dim: str, labels: Mapping[Any, str]
) -> tuple[Any, dict[str, Any]]:
    """Four panels against frequency, one curve per value of ``dim``; data for the record.

    Parameters
    ----------
    result : StudyResult
        A :func:`sweep_study` result.
    dim : str
        The study dimension of the curves.
    labels : mapping
        Value of ``dim`` -> curve label.

    Returns
    -------
    tuple
        The figure and the data for its record (curves, peak T_as and its frequency).

    Examples
    --------
    >>> currents = {f"{i:g} A": {"controller": {"law": "passive", "current": i}}
    ...             for i in (0.0, 0.4)}
    >>> result = run_sweep(sweep_study(True, "demo", cases={"damping": currents}))
    >>> fig, data = plot_sweep(result, "damping", {k: k for k in currents})
    >>> data["peak T_as 0 A"] > data["peak T_as 0.4 A"]
    True
    >>> import matplotlib.pyplot as plt; plt.close(fig)
    """
    return plot_selections(result, {label: {dim: value} for value, label in labels.items()})


def plot_selections(
    result: StudyResult,
    selections: Mapping[str, Mapping[str, Any]],
    *,
    peak_frequency: bool = True,
) -> tuple[Any, dict[str, Any]]:
    """Like :func:`plot_sweep`, but each curve is an ``xarray`` selection over several dims.

    Parameters
    ----------
    result : StudyResult
        The study, as for :func:`plot_sweep`.
    selections : mapping
        Curve label -> ``{dimension: value}`` selecting its runs.
    peak_frequency : bool, optional
        Also record the frequency of each curve's peak T_as (default True).

    Returns
    -------
    tuple
        ``(figure, data)`` as from :func:`plot_sweep`.

    Examples
    --------
    >>> soft = {"controller": {"law": "passive", "current": 0.0}}
    >>> result = run_sweep(sweep_study(True, "demo", cases={"damping": {"0 A": soft}}))
    >>> fig, data = plot_selections(result, {"soft": {"damping": "0 A"}}, peak_frequency=False)
    >>> sorted(k for k in data if k.startswith("peak"))
    ['peak T_as soft']
    >>> import matplotlib.pyplot as plt; plt.close(fig)
    """
    ds = result.to_xarray()
    f = ds["frequency"].values
    fig, axes = subplots(2, 2, layout="fixed")
    data: dict[str, Any] = {"frequency [Hz]": [float(v) for v in f]}
    for label, where in selections.items():
        sel = ds.sel(dict(where))
        for ax, (key, ylabel) in zip(axes.ravel(), FREQUENCY_PANELS, strict=True):
            ax.plot(f, sel[key].values, marker="o", ms=3, label=label)
            ax.set_ylabel(ylabel)
            data[f"{key} {label}"] = [float(v) for v in sel[key].values]
        body = sel["T_as"].sel(frequency=slice(0.5, 4.0))
        data[f"peak T_as {label}"] = float(body.max())
        if peak_frequency:
            data[f"peak T_as frequency {label} [Hz]"] = float(
                body["frequency"].values[int(np.argmax(body.values))]
            )
    for ax in axes.ravel():
        ax.set_xscale("log")
        ax.set_xlabel("frequency [Hz]")
        ax.grid(True, which="both", alpha=0.3)
    axes[0, 0].legend(fontsize=8)
    data["study hash"] = result.content_hash
    data["study run time [s]"] = round(result.run_time, 2)
    return fig, data


def harmonic_runs(
    cases: Sequence[dict[str, Any]], quick: bool, excitation: dict[str, Any] | None = None
) -> list[SimulationResult]:
    """Run scenario tables (``damper``, ``controller``, ``vehicle``) under a harmonic input.

    Parameters
    ----------
    cases : sequence of dict
        Scenario tables of each run, without ``excitation``/``simulation``.
    quick : bool
        Step size choice (see :func:`inverse_model_step`).
    excitation : dict, optional
        Excitation table; default :data:`HARMONIC`.

    Returns
    -------
    list of SimulationResult
        Time histories of :data:`DURATION` s sampled at 1 kHz, in the order given.

    Examples
    --------
    >>> (r,) = harmonic_runs([{"controller": {"law": "passive", "current": 0.0}}], True)
    >>> float(r.time[-1])
    8.0
    """
    from mrsuspension.engine.simulate import run_many
    from mrsuspension.scenario import Scenario

    dt = inverse_model_step(quick)
    sims = []
    for case in cases:
        data = {**case, "excitation": dict(excitation or HARMONIC), "simulation": {"dt": dt}}
        sims.extend(Scenario.from_dict(data).simulations())
    return run_many(
        sims, duration=DURATION, dt=dt, output_rate=1000.0, workers=1 if in_worker() else None
    )


def steady(result: SimulationResult) -> np.ndarray:
    """Mask of the steady window (t >= :data:`STEADY_FROM`).

    Examples
    --------
    >>> from types import SimpleNamespace
    >>> steady(SimpleNamespace(time=np.array([3.0, 4.0, 7.0]))).tolist()
    [False, True, True]
    """
    return np.asarray(result.time >= STEADY_FROM)


def shown(result: SimulationResult) -> np.ndarray:
    """Mask of the window shown in time-history panels (:data:`SHOWN`).

    Examples
    --------
    >>> from types import SimpleNamespace
    >>> shown(SimpleNamespace(time=np.array([5.0, 6.5, 7.5]))).tolist()
    [False, True, False]
    """
    return np.asarray((result.time >= SHOWN[0]) & (result.time <= SHOWN[1]))


def tracking_error(result: SimulationResult) -> float:
    """rms(|F_d| - |F*|) while z_c < 0 over the steady window [N].

    Examples
    --------
    >>> (r,) = harmonic_runs([{"controller": {"law": "inverse-hilo", "mode": "ACM"}}], True)
    >>> tracking_error(r) > 0.0
    True
    """
    from mrsuspension.measures import force_tracking_error

    sel = steady(result)
    return float(force_tracking_error(result.F_d[sel], result.F_target[sel], result.z_c[sel]))


def force_tracking_errors(
    law: str, quick: bool, modes: Sequence[str] = ("ACM", "SCM")
) -> dict[str, list[float]]:
    """Force-tracking error [N] of ``law`` for each k_d of :data:`FORCE_GAINS`, by mode.

    Parameters
    ----------
    law : str
        ``"inverse-hilo"`` or ``"sliding-mode"``.
    quick : bool
        Step size choice (see :func:`inverse_model_step`).
    modes : sequence of str
        Control modes to run.

    Returns
    -------
    dict
        ``{mode: [error at k_d = 1, 1.5, 2, 2.5]}``.

    Examples
    --------
    >>> errors = force_tracking_errors("inverse-hilo", True, modes=("ACM",))
    >>> list(errors), len(errors["ACM"])
    (['ACM'], 4)
    """
    cases = [
        {"damper": {"force_gain": kd}, "controller": {"law": law, "mode": mode}}
        for mode in modes
        for kd in FORCE_GAINS
    ]
    errors = [tracking_error(r) for r in harmonic_runs(cases, quick)]
    n = len(FORCE_GAINS)
    return {mode: errors[k * n : (k + 1) * n] for k, mode in enumerate(modes)}


def error_figure(law: str, quick: bool) -> tuple[Any, dict[str, Any]]:
    """Force-tracking error against k_d (SCM, ACM) and ACM F_d histories per k_d.

    Parameters
    ----------
    law : str
        Inverse-model law.
    quick : bool
        Step size choice.

    Returns
    -------
    tuple
        The figure and the data for its record.

    Examples
    --------
    >>> fig, data = error_figure("sliding-mode", True)
    >>> data["k_d"], len(data["force-tracking error SCM [N]"])
    ([1.0, 1.5, 2.0, 2.5], 4)
    >>> import matplotlib.pyplot as plt; plt.close(fig)
    """
    modes = ("ACM", "SCM")
    every = harmonic_runs(  # each run once: the errors and the ACM histories share them
        [
            {"damper": {"force_gain": kd}, "controller": {"law": law, "mode": mode}}
            for mode in modes
            for kd in FORCE_GAINS
        ],
        quick,
    )
    n = len(FORCE_GAINS)
    errors = {
        mode: [tracking_error(r) for r in every[k * n : (k + 1) * n]]
        for k, mode in enumerate(modes)
    }
    runs = every[:n]
    fig, grid = subplots(1, 3, layout="fixed")
    axes = grid[0]
    data: dict[str, Any] = {"k_d": list(FORCE_GAINS)}
    for mode, values in errors.items():
        axes[0].plot(FORCE_GAINS, values, marker="o", label=mode)
        data[f"force-tracking error {mode} [N]"] = values
    axes[0].set_xlabel("force gain $k_d$")
    axes[0].set_ylabel("rms(|F_d| - |F*|) while $z_c$ < 0 [N]")
    axes[0].legend(fontsize=8)
    axes[0].grid(True, alpha=0.3)
    for kd, r in zip(FORCE_GAINS, runs, strict=True):
        w = shown(r)
        axes[1].plot(r.time[w], r.F_d[w], label=f"$k_d$ = {kd:g}")
        axes[2].plot(r.time[w], r.i_d[w], label=f"$k_d$ = {kd:g}")
        data[f"mean current ACM k_d={kd:g} [A]"] = float(np.mean(r.i_d[steady(r)]))
        data[f"rms body acceleration ACM k_d={kd:g} [m/s^2]"] = float(
            np.sqrt(np.mean(r.z_s_ddot[steady(r)] ** 2))
        )
    axes[1].set_ylabel("$F_d$ [N] (ACM)")
    axes[2].set_ylabel("$i_d$ [A] (ACM)")
    for ax in axes[1:]:
        ax.set_xlabel("time [s]")
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=8)
    return fig, data
