"""The figure writer (mechrepro.plotting.savefig): cropped to what is drawn, like
``bbox_inches="tight"``, and nothing outside the canvas is ever cut off."""
import numpy as np
from PIL import Image

from mechrepro.plotting import content_crop, lint, lint_record, plt, savefig


def _figure(**legend):
    fig, ax = plt.subplots(figsize=(5, 3.5))
    ax.plot([0, 1, 2], [0, 1, 0], label="a line")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.set_title("title")
    if legend:
        fig.legend(**legend)
    else:
        ax.legend()
    fig.tight_layout()
    return fig


def _png(path):
    return np.asarray(Image.open(path))


def test_a_figure_inside_its_canvas_is_cropped_to_its_pixels_as_tight_would(tmp_path):
    fig = _figure()
    crop = content_crop(fig)
    assert crop is not None
    pad = round(plt.rcParams["savefig.pad_inches"] * fig.dpi)
    # the padding is background, the content starts right after it
    background = crop[0, 0]
    drawn = np.any(crop != background, axis=2)
    rows, cols = np.flatnonzero(drawn.any(axis=1)), np.flatnonzero(drawn.any(axis=0))
    assert (rows[0], cols[0]) == (pad, pad)
    assert (crop.shape[0] - 1 - rows[-1], crop.shape[1] - 1 - cols[-1]) == (pad, pad)
    savefig(fig, tmp_path / "new.png", close=False)
    fig.savefig(tmp_path / "tight.png", bbox_inches="tight")
    new, tight = _png(tmp_path / "new.png"), _png(tmp_path / "tight.png")
    assert np.array_equal(new, crop)
    # "tight" measures text boxes (with the font's line spacing), the crop drawn pixels:
    # a few pixels apart at most
    assert np.all(np.abs(np.array(new.shape[:2]) - tight.shape[:2]) <= 10)
    plt.close(fig)


def test_a_legend_below_the_canvas_is_kept(tmp_path):
    # as disk_tension's Figs. 6 and 8: a figure legend anchored below the axes
    fig = _figure(loc="lower center", bbox_to_anchor=(0.5, -0.15), ncol=2)
    assert content_crop(fig) is None
    height = fig.canvas.get_width_height()[1]
    savefig(fig, tmp_path / "fig.png", close=False)
    assert _png(tmp_path / "fig.png").shape[0] > height
    plt.close(fig)


def test_content_cut_by_the_canvas_edge_is_kept(tmp_path):
    # no tight_layout: the x label of a short figure reaches below the canvas
    fig, ax = plt.subplots(figsize=(5, 1.2))
    ax.plot([0, 1], [0, 1])
    ax.set_xlabel("a label below the canvas")
    assert content_crop(fig) is None
    savefig(fig, tmp_path / "fig.png", close=False)
    fig.savefig(tmp_path / "tight.png", bbox_inches="tight")
    assert _png(tmp_path / "fig.png").shape == _png(tmp_path / "tight.png").shape
    plt.close(fig)


def test_an_annotation_wholly_below_the_canvas_is_kept(tmp_path):
    # as accuracy.plot's NOT CONVERGED note under the x label: no pixel of it on the canvas,
    # so no drawn content at the edge to say it is there
    fig = _figure()
    ax = fig.axes[0]
    ax.annotate("a note far below", xy=(0.0, 0.0), xycoords="axes fraction", xytext=(0, -200),
                textcoords="offset points", va="top")
    assert content_crop(fig) is None
    height = fig.canvas.get_width_height()[1]
    savefig(fig, tmp_path / "fig.png", close=False)
    assert _png(tmp_path / "fig.png").shape[0] > height + 100
    plt.close(fig)


# --- the figure lint (mechrepro.plotting.lint), recorded in every PNG savefig writes ---

def _clean():
    fig, ax = plt.subplots(figsize=(5, 3.5))
    ax.plot([0, 1, 2], [0, 1, 0], label="a line")
    ax.set(xlabel="x [m]", ylabel="y [m]", title="title")
    ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.2))
    return fig, ax


def test_a_clean_figure_has_no_lint_and_records_that(tmp_path):
    fig, _ = _clean()
    assert lint(fig) == []
    savefig(fig, tmp_path / "f.png")
    assert lint_record(tmp_path / "f.png") == []


def test_the_lint_finds_what_a_reader_must_not_see(tmp_path):
    fig, ax = _clean()
    ax.set_ylabel("y")                                        # a number axis without a unit
    ax.text(0.5, 1.0, "over the title", transform=ax.transAxes, ha="center", va="bottom",
            fontsize=14)                                      # two texts overlap
    ax.plot([0, 2], [0.5, 0.5], alpha=0.0, label="invisible")  # a series not seen
    ax.legend(loc="center")                                   # a legend over the data
    savefig(fig, tmp_path / "f.png")
    found = " | ".join(lint_record(tmp_path / "f.png"))
    for what in ("y axis", "overlapping texts", "'invisible'", "legend over data"):
        assert what in found, (what, found)


def test_a_legend_proxy_and_a_grid_labelled_at_its_edge_are_no_lint():
    fig, ax = plt.subplots(2, 1, figsize=(5, 5))
    for a in ax:
        a.plot([0, 1, 2], [0, 1, 0])
        a.set_ylabel("y [m]")
    ax[1].set_xlabel("x [m]")                                 # the column's label
    ax[0].plot([], [], "k--", label="style key")              # a proxy: no data
    ax[0].legend(loc="upper center", bbox_to_anchor=(0.5, 1.4))
    fig.subplots_adjust(hspace=0.4, top=0.75)
    assert lint(fig) == []
