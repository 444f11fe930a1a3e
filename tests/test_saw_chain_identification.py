"""saw_chain: the identification of the authors' unstated choices from the paper's six numbers
(models/saw_chain/identification.py): it recovers the choices of a synthetic paper, its
shortcut for the load maximum is the solver's, and its data are the reported rows'."""
import math
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
import yaml

from mechrepro.models.saw_chain import identification as idf
from mechrepro.models.saw_chain.analysis import pitch_radius_readings
from mechrepro.models.saw_chain.chain import Chain
from mechrepro.models.saw_chain.difference import load_x

ROOT = Path(__file__).resolve().parents[1]
D = idf.Design(8.91e-3, 7.56e-3, 8, 6550 * math.pi / 30, 1.906e-3, 1.296e-3, 32, 32)
SPEEDS = np.linspace(0.95, 1.05, 1001)
STRETCHES = np.linspace(0.0, 0.03, 151)
K = np.arange(2, 39435)


def synthetic_paper(reading, s, e, K_paper):
    """The six numbers a paper would print had its program used ``reading`` at s x 6550 r/min
    and K_paper steps, its tested chain stretched by e: computed by the solver itself (not by
    the shortcuts under test) and rounded to the paper's printed digits."""
    R = pitch_radius_readings(D.p1, D.p2, D.z)[reading]
    u = idf.unit_predictions(D, reading, np.array([K_paper]))

    class Read(Chain):          # the solver with the pitch radius the program read
        @property
        def R(self):
            return R
    ch = Read(D.p1, D.p2, D.z, D.omega * s, D.m_L, D.m_C, D.M, D.N, K_paper)
    F = load_x(ch)
    exact = [s * u["band_min"], s * u["band_max"], s * (1 + e) * u["measured_mean"],
             s * (1 + e) * u["measured_fluctuation"], s**2 * u["load_min"], float(F.max())]
    digits = (2, 2, 1, 1, 1, 1)
    return [round(x, d) for x, d in zip(exact, digits)]


@pytest.mark.parametrize("reading, s, e, K_paper", [("pitch_line", 1.012, 0.008, 150),
                                                     ("pair_chord", 0.99, 0.02, 60)])
def test_recovers_the_choices_of_a_synthetic_paper(reading, s, e, K_paper):
    paper = synthetic_paper(reading, s, e, K_paper)
    fits, joint = idf.analyse(D, paper, idf.PRINTED, idf.INPUTS_HALF, 0.001, SPEEDS, STRETCHES, K)
    w = dict(zip(joint, idf.weights([f.chi2 for f in joint.values()])))
    assert max(w, key=w.get) == reading and w[reading] > 0.95, w
    best = joint[reading]
    s95 = idf.interval(SPEEDS, best.prof_speed, "95")
    e95 = idf.interval(STRETCHES, best.prof_stretch, "95")
    assert s95[0] <= s <= s95[1] and s95[1] - s95[0] < 0.01, s95
    assert e95[0] <= e <= e95[1] and e95[1] - e95[0] < 0.01, e95
    # the profiled K of the load maximum brackets the synthetic paper's within 10 %
    assert abs(best.K - K_paper) <= 0.1 * K_paper, best.K
    # the joint explanation is the best of all, and the rounded numbers are fitted within noise
    assert min(fits, key=lambda f: f.chi2).explanation == "reading + speed + stretch"
    assert best.chi2 < 6.0


def test_as_printed_paper_is_explained_by_no_offset():
    """A paper whose numbers are the model's own, as printed: Eq. (1) (or its 0.01 %-close
    mean-pitch twin) at s = 1, e = 0 fits, and the speed interval contains 1."""
    paper = synthetic_paper("eq1", 1.0, 0.0, 109)
    fits, joint = idf.analyse(D, paper, idf.PRINTED, idf.INPUTS_HALF, 0.001, SPEEDS, STRETCHES, K)
    w = dict(zip(joint, idf.weights([f.chi2 for f in joint.values()])))
    assert w["eq1"] + w["mean_pitch"] > 0.95, w
    printed = next(f for f in fits if f.explanation == "as printed")
    assert printed.chi2 < 6.0 and printed.K == 109
    lo, hi = idf.interval(SPEEDS, joint["eq1"].prof_speed, "95")
    assert lo <= 1.0 <= hi


@pytest.mark.parametrize("reading", ["eq1", "pair_chord", "tie_strap"])
def test_last_sample_load_is_the_solvers_maximum(reading):
    """The load maximum of the difference method is its last sample for K >= 10 (on the
    paper's chain under every reading tried), and three positions give it exactly."""
    R = pitch_radius_readings(D.p1, D.p2, D.z)[reading]

    class Read(Chain):
        @property
        def R(self):
            return R
    ch = Read(D.p1, D.p2, D.z, D.omega, D.m_L, D.m_C, D.M, D.N, 10)
    Ks = np.array([10, 37, 109, 1000, 20000])
    short = idf.last_sample_load(D, R, Ks)
    for k, f in zip(Ks, short):
        F = load_x(replace(ch, K=int(k)))
        assert int(np.argmax(F)) == F.size - 1
        assert f == pytest.approx(F[-1], rel=1e-9)


def test_the_identification_data_are_the_reported_rows():
    raw = yaml.safe_load((ROOT / "config" / "papers" / "saw_chain.yaml").read_text())
    p, rep = raw["parameters"], raw["reported"]
    assert p["identification_velocities"]["value"] == [
        rep["tight_side_velocity_min"]["value"], rep["tight_side_velocity_max"]["value"],
        rep["measured_velocity_mean"]["value"],
        pytest.approx(2 * rep["measured_velocity_mean"]["tolerance"] * rep["measured_velocity_mean"]["value"],
                      abs=1e-4)]
    assert p["identification_loads"]["value"] == [rep["dynamic_load_min"]["value"],
                                                  rep["dynamic_load_max"]["value"]]
