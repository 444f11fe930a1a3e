"""Figure output shared by all notebooks: Agg backend, atomic PNG writes, no timestamps, a lint."""
from __future__ import annotations

import json
import os

os.environ.setdefault("MPLBACKEND", "Agg")
import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.image  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from .io import atomic_path  # noqa: E402

plt.rcParams.update({"figure.dpi": 110, "savefig.dpi": 110, "font.size": 9,
                     # room for the x label below the axes (0.11 leaves ~0.4 in: on the figures
                     # 3.6-4 in high the label crossed the canvas edge, and a figure whose content
                     # crosses it is drawn twice, see content_crop)
                     "figure.subplot.bottom": 0.14,
                     "axes.grid": True, "grid.alpha": 0.3})


def _figure_level_extents(fig, renderer):
    """Window extents of the artists that may sit outside the canvas on purpose (figure
    and axes legends, figure texts): cheap once the figure is drawn."""
    artists = [*fig.legends, *fig.texts,
               *(a for a in (getattr(fig, n, None) for n in ("_suptitle", "_supxlabel",
                                                             "_supylabel")) if a is not None),
               *(ax.get_legend() for ax in fig.axes if ax.get_legend() is not None)]
    return [a.get_window_extent(renderer) for a in artists if a.get_visible()]


def content_crop(fig, pad_inches: float | None = None, drawn: bool = False):
    """Draw ``fig`` once (``drawn``: read the canvas as its last draw left it) and return
    its RGBA pixels cropped to the drawn content plus ``pad_inches`` (savefig.pad_inches),
    or None when content may lie outside the canvas (drawn content touching its edge, or a
    legend, figure text or axes text beyond it).

    This is ``bbox_inches="tight"`` measured on the pixels already drawn: matplotlib's
    tight bbox needs a layout pass over every tick label before the drawing pass (~40 %
    of a save), the pixels need none.  Its crop is the bounding box of the drawn pixels,
    where "tight" takes the artists' extents (text boxes include the font's line
    spacing): on the ci figures 0-9 px tighter in height, up to 3 px wider.
    """
    pad_inches = plt.rcParams["savefig.pad_inches"] if pad_inches is None else pad_inches
    renderer = fig.canvas.get_renderer()
    w, h = renderer.get_canvas_width_height()
    for bb in _figure_level_extents(fig, renderer):
        if bb.x0 < 0 or bb.y0 < 0 or bb.x1 > w or bb.y1 > h:
            return None
    if not drawn:
        fig.canvas.draw()
    # an axes' text wholly outside the canvas leaves no pixel at its edge (accuracy.plot's
    # NOT CONVERGED note under an axis label was cut off so): found by its extent, read
    # after the draw has placed it
    for ax in fig.axes:
        for t in ax.texts:
            if t.get_visible() and t.get_text():
                bb = t.get_window_extent(renderer)
                if bb.x0 < 0 or bb.y0 < 0 or bb.x1 > w or bb.y1 > h:
                    return None
    img = np.asarray(fig.canvas.buffer_rgba())
    h, w = img.shape[:2]
    background = img[0, 0]
    drawn = np.any(img != background, axis=2)
    rows, cols = np.flatnonzero(drawn.any(axis=1)), np.flatnonzero(drawn.any(axis=0))
    if rows.size == 0 or rows[0] == 0 or cols[0] == 0 or rows[-1] == h - 1 or cols[-1] == w - 1:
        return None
    pad = int(round(pad_inches * fig.dpi))
    # a copy: the canvas's buffer is drawn over by the next draw
    return img[max(rows[0] - pad, 0):rows[-1] + pad + 1,
               max(cols[0] - pad, 0):cols[-1] + pad + 1].copy()


def log_ticks(axis) -> None:
    """Label a log ``axis`` where labels cannot collide: at 1, 2 and 5 x 10^k over at most
    two decades, at whole decades beyond; never at matplotlib's minor ticks, whose labels
    on a short log axis crowd into each other.  Call after the data are drawn."""
    from matplotlib.ticker import FuncFormatter, LogLocator, MaxNLocator, NullFormatter

    lo, hi = sorted(axis.get_view_interval())
    if lo > 0 and np.log10(hi / lo) <= 2:
        axis.set_major_locator(LogLocator(subs=(1.0, 2.0, 5.0)))
    if lo > 0 and np.log10(hi / lo) < 1:
        # within a decade matplotlib falls back to dense linear ticks, which its log
        # formatter writes as 2.75x10^0: a few plain numbers there
        axis.set_major_locator(MaxNLocator(nbins=4, steps=[1, 2, 2.5, 5, 10]))
        axis.set_major_formatter(FuncFormatter(lambda v, _: f"{v:.3g}"))
    axis.set_minor_formatter(NullFormatter())


# --- the figure lint: what a reader must never see (tests/test_figures.py reads its record) ---
LINT_KEY = "mechrepro-lint"
SERIES_MIN_PIXELS = 20    # a series whose removal changes fewer pixels is not visible


def _drawn_ticklabels(axis):
    """The tick labels matplotlib draws: those of ticks inside the view (``get_ticklabels``
    also returns those of the ticks just outside it)."""
    lo, hi = sorted(axis.get_view_interval())
    tol = 1e-10 * (hi - lo)
    ticks = [t for t in axis.get_major_ticks() + axis.get_minor_ticks()
             if lo - tol <= t.get_loc() <= hi + tol]
    return [lab for t in ticks for lab in (t.label1, t.label2) if lab.get_visible()]


def _texts(fig):
    """(name, artist, axes or None, is_tick) of every visible non-empty text of ``fig``."""
    out = []
    for ax in fig.axes:
        if not ax.get_visible():
            continue
        for name in ("title", "_left_title", "_right_title"):
            t = getattr(ax, name, None)
            if t is not None:
                out.append((f"title {t.get_text()!r}", t, ax, False))
        out += [(f"x label {ax.xaxis.label.get_text()!r}", ax.xaxis.label, ax, False),
                (f"y label {ax.yaxis.label.get_text()!r}", ax.yaxis.label, ax, False),
                *((f"text {t.get_text()!r}", t, ax, False) for t in ax.texts)]
        for axis in (ax.xaxis, ax.yaxis):
            out += [(f"tick label {t.get_text()!r}", t, axis, True) for t in _drawn_ticklabels(axis)]
    out += [(f"figure text {t.get_text()!r}", t, None, False) for t in fig.texts]
    seen = set()    # the suptitle is one of fig.texts too
    return [x for x in out if x[1].get_visible() and x[1].get_text().strip()
            and not (id(x[1]) in seen or seen.add(id(x[1])))]


def _overlap(a, b, px: float = 1.0) -> bool:
    return min(a.x1, b.x1) - max(a.x0, b.x0) > px and min(a.y1, b.y1) - max(a.y0, b.y0) > px


def _data_points(ax):
    """Display coordinates of the drawn data of ``ax``: line vertices and the points between
    them (a segment crossing a legend is data under it) and scatter offsets."""
    pts = []
    for line in ax.lines:
        if not line.get_visible() or line.get_linestyle() in ("None", "none", "", " ") and \
                line.get_marker() in ("None", "none", "", " ", None):
            continue
        xy = line.get_transform().transform(np.asarray(line.get_xydata(), float))
        xy = xy[np.all(np.isfinite(xy), axis=1)]
        if len(xy) > 1 and line.get_linestyle() not in ("None", "none", "", " "):
            s = np.linspace(0.0, 1.0, 9)[:, None, None]
            xy = (xy[:-1] + s * (xy[1:] - xy[:-1])).reshape(-1, 2)
        pts.append(xy)
    for c in ax.collections:
        if c.get_visible() and hasattr(c, "get_offsets") and len(c.get_offsets()) and \
                type(c).__name__ == "PathCollection":
            pts.append(c.get_offset_transform().transform(np.asarray(c.get_offsets(), float)))
    if not pts:
        return np.empty((0, 2))
    p, bb = np.concatenate(pts), ax.bbox    # what is clipped to the axes is not drawn beyond
    return p[(p[:, 0] >= bb.x0) & (p[:, 0] <= bb.x1) & (p[:, 1] >= bb.y0) & (p[:, 1] <= bb.y1)]


def _empty(artist) -> bool:
    if hasattr(artist, "get_xydata"):
        return len(artist.get_xydata()) == 0
    if type(artist).__name__ == "PathCollection":    # a scatter: its points are the offsets
        return len(artist.get_offsets()) == 0
    if hasattr(artist, "get_paths"):
        return not any(len(q.vertices) for q in artist.get_paths())
    return False


def _has_unit(label: str) -> bool:
    return "[" in label and "]" in label


def _unit_missing(fig, ax, name: str) -> bool:
    """An axis with numeric tick labels shown and no ``[unit]`` in its label; an unlabelled
    one takes the label of an axes of the same column (x) or row (y): a grid labels its
    outer axes."""
    axis = ax.xaxis if name == "x" else ax.yaxis
    ticks = [t.get_text() for t in _drawn_ticklabels(axis) if t.get_text()]
    if not any(t.replace("\\mathdefault", "").lstrip("$\u2212-{")[:1].isdigit() for t in ticks):
        return False
    if axis.label.get_text().strip():
        return not _has_unit(axis.label.get_text())
    span = (lambda a: a.get_position().intervalx) if name == "x" else \
        (lambda a: a.get_position().intervaly)
    return not any(_has_unit((o.xaxis if name == "x" else o.yaxis).label.get_text())
                   for o in fig.axes if o is not ax and np.allclose(span(o), span(ax)))


def _legends(fig):
    """(axes or None for a figure legend, legend) of every visible legend."""
    out = [(ax, ax.get_legend()) for ax in fig.axes if ax.get_legend() is not None]
    return [(ax, leg) for ax, leg in out + [(None, leg) for leg in fig.legends]
            if leg.get_visible()]


def _overlapping_texts(fig, r) -> list[str]:
    boxes = [(n, t.get_window_extent(r), ax, tick) for n, t, ax, tick in _texts(fig)]
    boxes += [(f"legend of {'figure' if ax is None else repr(ax.get_title())}",
               leg.get_window_extent(r), ax, False) for ax, leg in _legends(fig)]
    out = []
    for i, (n1, b1, ax1, tick1) in enumerate(boxes):
        for n2, b2, ax2, tick2 in boxes[i + 1:]:
            # tick labels of two axes (x and y too) meet only at corners
            if not (tick1 and tick2 and ax1 is not ax2) and _overlap(b1, b2):
                out.append(f"overlapping texts: {n1} and {n2}")
    return out


def _legends_over_data(fig, r) -> list[str]:
    out = []
    for ax, leg in _legends(fig):
        bb = leg.get_window_extent(r)
        for other in (fig.axes if ax is None else [ax]):
            p = _data_points(other)
            inside = ((p[:, 0] > bb.x0 + 1) & (p[:, 0] < bb.x1 - 1)
                      & (p[:, 1] > bb.y0 + 1) & (p[:, 1] < bb.y1 - 1))
            if inside.any():
                out.append(f"legend over data in axes {other.get_title()!r} "
                           f"({int(inside.sum())} points under it)")
    return out


def _axes_without_units(fig) -> list[str]:
    return [f"{name} axis of {ax.get_title()!r} without a [unit] (dimensionless: [1]): "
            f"label {getattr(ax, f'get_{name}label')()!r}"
            for ax in fig.axes
            if ax.get_visible() and ax.axison and (ax.lines or ax.collections or ax.images
                                                   or ax.patches)
            for name in ("x", "y") if _unit_missing(fig, ax, name)]


def _invisible_series(fig) -> list[str]:
    """Labelled series whose hiding changes fewer than :data:`SERIES_MIN_PIXELS` pixels:
    the figure drawn once without them, then per axes each series' absence composed on
    that background by blitting (its axes' series drawn again, all but one)."""
    series = []
    for ax in fig.axes:
        # a bar chart or histogram is one series: its container's patches
        groups = [(c.get_label(), list(c)) for c in ax.containers if hasattr(c, "patches")]
        grouped = {id(a) for _, g in groups for a in g}
        groups += [(a.get_label(), [a]) for a in [*ax.lines, *ax.collections, *ax.patches,
                                                 *ax.images] if id(a) not in grouped]
        series += [(ax, label, shown) for label, group in groups
                   if label and not label.startswith("_")
                   and (shown := [a for a in group if a.get_visible()])
                   and not all(_empty(a) for a in group)]   # a legend's proxy is no series
    if not series:
        return []
    for _, _, shown in series:
        for a in shown:
            a.set_visible(False)
    fig.canvas.draw()
    height = fig.canvas.get_width_height()[1]
    out = []
    for ax in dict.fromkeys(ax for ax, _, _ in series):
        bg = fig.canvas.copy_from_bbox(ax.bbox)
        mine = [(label, shown) for a, label, shown in series if a is ax]
        arts = sorted((a for _, shown in mine for a in shown), key=lambda a: a.get_zorder())
        x0, x1 = int(ax.bbox.x0), int(np.ceil(ax.bbox.x1))
        y0, y1 = height - int(np.ceil(ax.bbox.y1)), height - int(ax.bbox.y0)

        def drawn(skip=()):
            fig.canvas.restore_region(bg)
            for a in arts:
                if not any(a is s for s in skip):
                    a.set_visible(True)
                    ax.draw_artist(a)
                    a.set_visible(False)
            return np.asarray(fig.canvas.buffer_rgba())[y0:y1, x0:x1].copy()

        full = drawn()
        for label, shown in mine:
            changed = int(np.any(drawn(shown) != full, axis=2).sum())
            if changed < SERIES_MIN_PIXELS:
                out.append(f"series {label!r} in axes {ax.get_title()!r} not visible "
                           f"({changed} pixels)")
    for _, _, shown in series:
        for a in shown:
            a.set_visible(True)
    return out


def lint(fig, drawn: bool = False) -> list[str]:
    """What is wrong with ``fig`` as a reader sees it: two texts that overlap, a legend over
    data, an axis with numbers and no unit, a labelled series that draws nothing visible.
    ``drawn``: the canvas holds the figure's last draw, as it stands.  Leaves every artist
    of ``fig`` as it was, not its canvas (drawn again without the series)."""
    if not drawn:
        fig.canvas.draw()
    r = fig.canvas.get_renderer()
    return (_overlapping_texts(fig, r) + _legends_over_data(fig, r)
            + _axes_without_units(fig) + _invisible_series(fig))


def lint_record(path) -> list[str] | None:
    """The lint problems a PNG written by :func:`savefig` records (None: no record)."""
    from PIL import Image

    with Image.open(path) as im:
        text = im.text.get(LINT_KEY)
    return None if text is None else json.loads(text)


def savefig(fig, path, close: bool = True) -> None:
    """Write ``fig`` atomically as PNG without volatile metadata, cropped to its content,
    with what :func:`lint` finds wrong in it recorded in the PNG (:func:`lint_record`).

    One drawing pass, cropped on its pixels (:func:`content_crop`) and read by the lint,
    whose series check draws once more; when content may lie outside the canvas,
    matplotlib's own tight bbox (one layout pass, then the drawing pass at that bbox: the
    crop of ``bbox_inches="tight"`` without its extra draw).
    """
    fig.canvas.draw()
    crop = content_crop(fig, drawn=True)
    problems = lint(fig, drawn=True)
    for p in problems:
        print(f"figure lint: {path}: {p}")
    meta = {"Software": None, LINT_KEY: json.dumps(problems)}
    with atomic_path(path) as tmp:
        if crop is not None:
            matplotlib.image.imsave(tmp, crop, format="png", dpi=fig.dpi, metadata=meta)
        else:
            bbox = fig.get_tightbbox(fig.canvas.get_renderer()).padded(
                plt.rcParams["savefig.pad_inches"])
            fig.savefig(tmp, format="png", bbox_inches=bbox, metadata=meta)
    if close:
        plt.close(fig)
