"""Figure output shared by all notebooks: Agg backend, atomic PNG writes, no timestamps."""
from __future__ import annotations

import os

os.environ.setdefault("MPLBACKEND", "Agg")
import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from .io import atomic_path  # noqa: E402

plt.rcParams.update({"figure.dpi": 110, "savefig.dpi": 110, "font.size": 9,
                     "axes.grid": True, "grid.alpha": 0.3})


def savefig(fig, path, close: bool = True) -> None:
    """Write ``fig`` atomically as PNG without volatile metadata."""
    with atomic_path(path) as tmp:
        fig.savefig(tmp, format="png", bbox_inches="tight", metadata={"Software": None})
    if close:
        plt.close(fig)
