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
    return stroke.solve_exact(g, cut_points(g, n)[1])
