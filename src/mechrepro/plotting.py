"""Figure output shared by all notebooks: Agg backend, atomic PNG writes, no timestamps."""
from __future__ import annotations

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


def content_crop(fig, pad_inches: float | None = None):
    """Draw ``fig`` once and return its RGBA pixels cropped to the drawn content plus
    ``pad_inches`` (savefig.pad_inches), or None when content may lie outside the canvas
    (drawn content touching its edge, or a legend, figure text or axes text beyond it).

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


def savefig(fig, path, close: bool = True) -> None:
    """Write ``fig`` atomically as PNG without volatile metadata, cropped to its content.

    One drawing pass, cropped on its pixels (:func:`content_crop`); when content may lie
    outside the canvas, matplotlib's own tight bbox (one layout pass, then the drawing
    pass at that bbox: the crop of ``bbox_inches="tight"`` without its extra draw).
    """
    crop = content_crop(fig)
    with atomic_path(path) as tmp:
        if crop is not None:
            matplotlib.image.imsave(tmp, crop, format="png", dpi=fig.dpi,
                                    metadata={"Software": None})
        else:
            bbox = fig.get_tightbbox(fig.canvas.get_renderer()).padded(
                plt.rcParams["savefig.pad_inches"])
            fig.savefig(tmp, format="png", bbox_inches=bbox, metadata={"Software": None})
    if close:
        plt.close(fig)
