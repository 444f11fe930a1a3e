"""What an effect costs the solve: the marginal cost carries the spread of its alternated
rounds, and a difference whose rounds disagree on its sign is marked below noise."""
import netCDF4
import numpy as np
import pytest

from mechrepro import costs


def _run(path, wall, rounds, effect_time=0.001):
    with netCDF4.Dataset(path, "w") as nc:
        nc.solver = "s"
        nc.createDimension("timed_effect", 1)
        nc.createDimension("timing_round", len(rounds))
        nc.createVariable("wall_time", "f8")[...] = wall
        nc.createVariable("core_time", "f8")[...] = wall
        nc.createVariable("effect_time", "f8", ("timed_effect",))[:] = [effect_time]
        v = nc.createVariable("timed_effect", str, ("timed_effect",))
        v[0] = "e"
        nc.createVariable("timing_rounds", "f8", ("timing_round",))[:] = rounds


@pytest.mark.parametrize("without, noise", [([0.9, 0.95, 0.92], False),
                                            ([1.02, 0.98, 1.05], True)])
def test_the_marginal_cost_carries_its_rounds_spread(tmp_path, without, noise):
    runs = tmp_path / "runs"
    runs.mkdir()
    _run(runs / "a.nc", 1.0, [1.0, 1.01, 1.03])
    _run(runs / "a@without-e.nc", min(without), without)
    row, = costs.marginal(tmp_path, {"a@without-e": ("a", "e")})
    d = np.array([1.0, 1.01, 1.03]) - np.array(without)
    assert row["marginal_median_s"] == pytest.approx(np.median(d))
    assert (row["marginal_min_s"], row["marginal_max_s"]) == pytest.approx((d.min(), d.max()))
    assert row["below_noise"] is noise


def test_a_run_counts_how_often_each_effect_and_phase_is_evaluated():
    """Evaluations are a cost no machine changes: every run stores them beside the times."""
    from mechrepro.timing import EFFECT, phase, timed_run, timing_variables

    def work():
        for _ in range(3):
            with phase("model.step"):
                with phase(EFFECT + "drag"):
                    pass
        with phase(EFFECT + "drag"):
            pass

    _, seconds, timer = timed_run(work, min_time=0.0)
    v = timing_variables(seconds, timer, ["drag", "unused"])
    assert v["effect_calls"][1] == [4, 0]
    assert v["timed_phase"][1] == ["model.step"] and v["phase_calls"][1] == [3]
