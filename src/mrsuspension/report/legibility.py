"""Can a reader read a figure? Colliding text and legends over the data, measured.

:func:`layout_issues` draws a matplotlib figure once and lists what would make it hard to
read: two text boxes (tick labels, axis labels, titles, annotations, legends, the
suptitle) that overlap, a text box cut off by the figure's edge, a legend that hides more than a small share of an axes' data
points, and a figure without a title. ``mrsus reproduce`` records the issues of every
figure in ``manifest.json`` when asked (``build_report(..., check_layout=True)``), and the
report's tests require the list to be empty for every figure of the quick report.

matplotlib is imported only by the figures passed in, so importing this module is cheap.
"""

from __future__ import annotations

from typing import Any

import numpy as np

__all__ = ["COVER_LIMIT", "layout_issues", "legend_cover", "overlap", "text_boxes"]

#: the largest share of an axes' data points a legend may hide
COVER_LIMIT = 0.01

#: boxes may touch by this much [px] before they count as overlapping (anti-aliasing)
_SLACK = 1.0


def _visible_text(artist: Any) -> bool:
    return bool(artist.get_visible() and artist.get_text().strip())


def text_boxes(fig: Any) -> list[tuple[str, Any]]:
    """Every visible text of ``fig`` with its window extent (pixels), after one draw.

    Returns
    -------
    list of (str, Bbox)
        A name (``"axes 0 xtick '0.05'"``, ``"legend of axes 1"``, ``"suptitle"``) and its
        box.

    Examples
    --------
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> import matplotlib.pyplot as plt
    >>> fig, ax = plt.subplots()
    >>> _ = ax.set_title("A title")
    >>> "axes 0 title 'A title'" in [name for name, _ in text_boxes(fig)]
    True
    >>> plt.close(fig)
    """
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    boxes: list[tuple[str, Any]] = []

    def add(name: str, artist: Any) -> None:
        if _visible_text(artist):
            boxes.append((f"{name} {artist.get_text()!r}", artist.get_window_extent(renderer)))

    for k, ax in enumerate(a for a in fig.axes if a.get_visible()):
        where = f"axes {k}"
        for which, axis in (("xtick", ax.xaxis), ("ytick", ax.yaxis)):
            lo, hi = sorted(axis.get_view_interval())
            for tick in axis.get_major_ticks() + axis.get_minor_ticks():
                if not lo - 1e-12 * abs(hi - lo) <= tick.get_loc() <= hi + 1e-12 * abs(hi - lo):
                    continue  # outside the view: not drawn
                for label in (tick.label1, tick.label2):
                    add(f"{where} {which}", label)
        add(f"{where} xlabel", ax.xaxis.label)
        add(f"{where} ylabel", ax.yaxis.label)
        for title in (ax.title, ax._left_title, ax._right_title):
            add(f"{where} title", title)
        for text in ax.texts:
            add(f"{where} text", text)
        legend = ax.get_legend()
        if legend is not None and legend.get_visible():
            boxes.append((f"legend of {where}", legend.get_window_extent(renderer)))
    for text in fig.texts:
        if text is not fig._suptitle:
            add("figure text", text)
    if fig._suptitle is not None:
        add("suptitle", fig._suptitle)
    for k, legend in enumerate(fig.legends):
        boxes.append((f"figure legend {k}", legend.get_window_extent(renderer)))
    return boxes


def overlap(a: Any, b: Any) -> bool:
    """Whether two boxes (pixels) overlap by more than a pixel both ways.

    Examples
    --------
    >>> from matplotlib.transforms import Bbox
    >>> overlap(Bbox([[0, 0], [10, 10]]), Bbox([[5, 5], [20, 20]]))
    True
    >>> overlap(Bbox([[0, 0], [10, 10]]), Bbox([[10, 0], [20, 10]]))
    False
    """
    return bool(
        min(a.x1, b.x1) - max(a.x0, b.x0) > _SLACK and min(a.y1, b.y1) - max(a.y0, b.y0) > _SLACK
    )


def legend_cover(ax: Any) -> float:
    """The share of ``ax``'s data points (line vertices, scatter offsets) under its legend.

    Call after the figure was drawn (:func:`text_boxes` draws it). 0 without a legend.

    Examples
    --------
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> import matplotlib.pyplot as plt
    >>> fig, ax = plt.subplots()
    >>> _ = ax.plot([0, 1, 2], [0, 1, 0], label="a")
    >>> _ = ax.legend(loc="upper left", bbox_to_anchor=(1.02, 1.0))
    >>> fig.canvas.draw(); legend_cover(ax)
    0.0
    >>> plt.close(fig)
    """
    legend = ax.get_legend()
    if legend is None or not legend.get_visible():
        return 0.0
    box = legend.get_window_extent(ax.figure.canvas.get_renderer())
    points = []
    for line in ax.get_lines():
        if line.get_visible() and line.get_label() and not line.get_label().startswith("_"):
            xy = np.column_stack([line.get_xdata(orig=False), line.get_ydata(orig=False)])
            points.append(line.get_transform().transform(np.asarray(xy, dtype=float)))
    for coll in ax.collections:
        offsets = np.asarray(coll.get_offsets(), dtype=float)
        if coll.get_visible() and offsets.size:
            points.append(coll.get_offset_transform().transform(offsets))
    if not points:
        return 0.0
    xy = np.concatenate(points)
    xy = xy[np.all(np.isfinite(xy), axis=1)]
    if not len(xy):
        return 0.0
    inside = (
        (xy[:, 0] >= box.x0) & (xy[:, 0] <= box.x1) & (xy[:, 1] >= box.y0) & (xy[:, 1] <= box.y1)
    )
    return float(np.mean(inside))


def layout_issues(fig: Any, *, cover_limit: float = COVER_LIMIT) -> list[str]:
    """What makes ``fig`` hard to read: overlapping or cut-off texts, legends over data,
    no title.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        A figure (drawn once here).
    cover_limit : float
        The largest share of an axes' data points its legend may cover.

    Returns
    -------
    list of str
        One line per issue; empty for a legible figure.

    Examples
    --------
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> import matplotlib.pyplot as plt
    >>> fig, ax = plt.subplots(figsize=(2, 2))
    >>> fig.subplots_adjust(left=0.25, bottom=0.15)
    >>> _ = ax.set_xticks([0.0, 0.01], ["-0.0750", "-0.0500"])
    >>> _ = fig.suptitle("Two ticks")
    >>> layout_issues(fig)
    ["axes 0 xtick '-0.0750' overlaps axes 0 xtick '-0.0500'"]
    >>> _ = ax.legend(["a curve"], loc="upper left", bbox_to_anchor=(1.5, 1.0))
    >>> layout_issues(fig)[-1]
    'legend of axes 0 is cut off by the figure edge'
    >>> plt.close(fig)
    """
    boxes = text_boxes(fig)
    issues = [
        f"{na} overlaps {nb}"
        for i, (na, a) in enumerate(boxes)
        for nb, b in boxes[i + 1 :]
        if overlap(a, b)
    ]
    page = fig.bbox
    issues += [
        f"{name} is cut off by the figure edge"
        for name, box in boxes
        if box.x0 < page.x0 - _SLACK
        or box.y0 < page.y0 - _SLACK
        or box.x1 > page.x1 + _SLACK
        or box.y1 > page.y1 + _SLACK
    ]
    for k, ax in enumerate(a for a in fig.axes if a.get_visible()):
        share = legend_cover(ax)
        if share > cover_limit:
            issues.append(f"legend of axes {k} covers {100 * share:.1f} % of its data points")
    if fig._suptitle is None or not fig._suptitle.get_text().strip():
        issues.append("no figure title")
    return issues
