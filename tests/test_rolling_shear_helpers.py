"""Shared helpers of the rolling_shear tests (not a test module)."""
from functools import lru_cache
from pathlib import Path

from mechrepro.config import load_paper
from mechrepro.models.rolling_shear import stroke
from mechrepro.models.rolling_shear.geometry import cut_points, from_parameters

CONFIG = Path(__file__).resolve().parent.parent / "config" / "papers" / "rolling_shear.yaml"


@lru_cache(maxsize=None)
def config(profile="default"):
    return load_paper(CONFIG, profile)


def run(scene="original", profile="default"):
    import copy

    return copy.deepcopy(config(profile).runs[scene])


def geometry():
    return from_parameters(run()["parameters"])


def stroke_exact(g, n):
    """The closed-form stroke at n cut points (``.theta``, n x 6)."""
    from types import SimpleNamespace

    return SimpleNamespace(theta=stroke.exact_theta(g, cut_points(g, n)[1]))


def grid(**columns):
    """A family-grid dataset (scene ``family``'s variables) of the members given by
    ``columns`` (name -> values; the rest: one calibrated member far from every constraint
    whose Table II levers assemble and give +10 %), for the extraction's re-checks."""
    import numpy as np
    import xarray as xr

    n = len(next(iter(columns.values()))) if columns else 1
    base = {"tilt": 0.05, "H_levers": 1.4341 * 1.1, "assembles": 1.0, "buildable": 1.0,
            "rod_gap": 500.0, "joint_height": 200.0, "mu_min": 80.0, "mu_max": 120.0,
            "rise": 40.0, "open_mu": 80.0, "levers_buildable": 1.0, "blade_offset": -650.0, "R": 70000.0, "width": 2350.0,
            "y_joint": 250.0, "eq8_reading": "rotation", "carrier_constants": "frozen"}
    data = {k: np.asarray(columns.get(k, [v] * n)) for k, v in base.items()}
    data["reduction"] = columns.get("reduction", 100.0 * (data["H_levers"] / 1.4341 - 1.0))
    ds = xr.Dataset({f"family_member_{k}": ("member", np.asarray(v)) for k, v in data.items()})
    return ds.assign_coords(cut=np.arange(33))


class Results:
    """What an extraction reads (mechrepro.validation.ValidationInputs), for given datasets:
    ``run(name)`` the dataset passed for it (the family grid: :func:`grid`'s default), the
    parameters of run record ``r``, the paper's config."""

    def __init__(self, r, profile="default", **datasets):
        self.r, self.cfg = r, config(profile)
        self.datasets = {"family": grid(), **datasets}

    def run(self, name):
        return self.datasets[name]

    def parameter(self, name):
        return self.r["parameters"][name]

    def reported(self, quantity):
        return self.cfg.reported[quantity]
