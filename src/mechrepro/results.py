"""What a paper's notebook sees: its config, its runs and studies, and where outputs go.

Notebooks stay short by going through :class:`PaperResults` for every read and write::

    R = PaperResults(paper, results_dir, config_file, profile)
    ds = R.run("fig07_velocity")          # one run, loaded and closed
    st = R.study("cost_of_accuracy")      # the gathered study
    R.save_figure(fig, "fig07")           # results/<paper>/figures/fig07.png
    R.validation()                        # the table validate_<paper> built, for display
    R.table("cost_of_accuracy")           # the framework's long-form cost of accuracy
"""
from __future__ import annotations

from pathlib import Path

from .config import CACHE_DIR, load_paper
from .io import open_dataset, write_dataset
from .validation import write_csv


class PaperResults:
    def __init__(self, paper: str, results_dir: str, config_file: str, profile: str = "default"):
        self.paper = paper
        self.root = Path(results_dir) / paper
        self.cfg = load_paper(config_file, profile, CACHE_DIR)

    def run(self, name: str):
        return open_dataset(self.root / "runs" / f"{name}.nc")

    def study(self, name: str):
        return open_dataset(self.root / "studies" / f"{name}.nc")

    def study_runs(self, name: str) -> list:
        """The run datasets of a study, in sweep order (what the study file cannot stack:
        variables whose length differs between runs, e.g. adaptively sampled speeds)."""
        return [self.run(r) for r in self.cfg.studies[name]]

    def figure_path(self, name: str) -> Path:
        return self.root / "figures" / f"{name}.png"

    def table_path(self, name: str) -> Path:
        return self.root / "tables" / f"{name}.csv"

    def save_figure(self, fig, name: str) -> Path:
        from .plotting import savefig

        if name not in self.cfg.figures:
            raise KeyError(f"{self.paper}: figure {name!r} not declared in config 'figures'")
        savefig(fig, self.figure_path(name))
        return self.figure_path(name)

    def table(self, name: str) -> list[dict]:
        """A written table as rows of dicts (e.g. the framework's ``cost_of_accuracy``,
        long form: one row per entry, knob value and quantity; see mechrepro.accuracy)."""
        from .validation import read_table

        return read_table(self.table_path(name))

    def validation(self) -> list[dict]:
        """The validation table the framework built (``validate_<paper>``), for display."""
        from .validation import read_table

        return read_table(self.table_path("validation"))

    def write_table(self, name: str, header, rows) -> Path:
        if name not in self.cfg.tables:
            raise KeyError(f"{self.paper}: table {name!r} not declared in config 'tables'")
        return write_csv(self.table_path(name), header, rows)

    def write_dataset(self, ds, name: str) -> Path:
        """A derived dataset of the notebook (e.g. cost_of_accuracy) under tables/."""
        return write_dataset(ds, self.root / "tables" / f"{name}.nc")
