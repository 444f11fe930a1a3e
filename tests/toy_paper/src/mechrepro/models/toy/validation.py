"""Reproduced values of the toy paper (what it reports is in config/papers/toy.yaml)."""
from __future__ import annotations

import numpy as np

from mechrepro.validation import Quantities, Reproduced

Q = Quantities("toy")


@Q.register("natural_frequency")
def natural_frequency(R):
    """The frequency from the mean spacing of the upward zero crossings, linearly
    interpolated (their own error is far below a step, so none is added)."""
    ds = R.run("response")
    t, x = ds["t"].values, ds["displacement"].values
    i = np.flatnonzero((x[:-1] < 0) & (x[1:] >= 0))
    up = t[i] - x[i] * (t[i + 1] - t[i]) / (x[i + 1] - x[i])
    return Reproduced(float(1.0 / np.mean(np.diff(up))), f"{up.size} upward zero crossings")
