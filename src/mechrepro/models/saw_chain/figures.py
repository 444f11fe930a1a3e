"""saw_chain's figures, each drawn from the results it declares (config ``figures``)."""
from __future__ import annotations

from mechrepro.io import run_attrs
from mechrepro.plotting import plt
from mechrepro.units import from_si

from .analysis import stage_one_end


def fig08(R):
    """Fig. 8: the total tight-side dynamic load over one period, difference method, exact
    derivative and textbook Eq. (23), with the paper's ranges (Sec. 4)."""
    run = R.run("fig07_fig08")
    t_ms, t1_ms = from_si(run["t"], "ms"), from_si(stage_one_end(run), "ms")
    fig, ax = plt.subplots(figsize=(6.5, 4))
    ax.plot(t_ms, run["dynamic_load_x"], "-", label=f"difference method (K={run_attrs(run)['resolution']['K']})")
    ax.plot(t_ms, run["dynamic_load_x_exact"], ":", color="k", label="exact derivative")
    ax.plot(t_ms, run["dynamic_load_x_textbook"], "--", label="textbook, Eq. (23)")
    for q, c in (("dynamic_load_min", "tab:blue"), ("dynamic_load_max", "tab:blue"),
                 ("textbook_load_min", "tab:orange"), ("textbook_load_max", "tab:orange")):
        ax.axhline(R.value(q, "paper_value"), color=c, lw=0.7, ls="-.")
    ax.plot([], [], color="gray", ls="-.", lw=0.7, label="paper's ranges (Sec. 4)")
    ax.axvline(t1_ms, color="gray", lw=0.5)
    ax.set(xlabel="t [ms]", ylabel="dynamic load F_dx [N]", title="Fig. 8")
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    return fig
