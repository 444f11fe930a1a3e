"""chain_drive: a march under an external load measures over whole excitation periods (the
load repeats every n1 / r tooth periods, Eq. 2-5), so a slow modulation is neither read as
growth nor cut short in the amplitude (Fig. 8)."""
import copy
from pathlib import Path

import numpy as np
import pytest

from mechrepro.config import load_paper
from mechrepro.models.chain_drive import geometry, span

CONFIG = Path(__file__).resolve().parents[1] / "config" / "papers" / "chain_drive.yaml"


@pytest.mark.parametrize("ratio, q", [(1.0, 24), (2.0, 12), (4.0, 6), (1.5, 16)])
def test_excitation_period_in_tooth_periods(ratio, q):
    run = copy.deepcopy(load_paper(CONFIG, "ci").runs["fig08_external"])
    prm = dict(run["parameters"], external_frequency_ratio=ratio)
    assert span.excitation_tooth_periods(prm, run) == q
    assert span.excitation_tooth_periods(dict(prm, external_load_ratio=0.0), run) == 1


def test_each_growth_block_holds_an_excitation_period():
    run = copy.deepcopy(load_paper(CONFIG, "ci").runs["fig08_external"])
    prm, res = run["parameters"], run["resolution"]
    w = np.array([prm["speed_min"], prm["speed_max"]])
    a = span.assemble(run, prm, w, res)
    tau_max = float(geometry.tooth_period(w[0], int(prm["n1"])))
    window = (a["n_steps"] - a["measure_from"]) * a["dt"]
    assert window >= span.GROWTH_BLOCKS * 24 * tau_max * (1 - 1e-9)
