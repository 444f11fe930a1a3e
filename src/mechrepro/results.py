"""What a paper's notebook sees: its config, its runs and studies, and where outputs go.

Notebooks stay short by going through :class:`PaperResults` for every read and write::

    R = PaperResults(paper, results_dir, config_file, profile)
    ds = R.run("fig07_velocity")          # one run, loaded and closed
    st = R.study("cost_of_accuracy")      # the gathered study
    R.figure("fig07")                     # drawn as config figures.fig07 declares, saved
                                          # as results/<paper>/figures/fig07.png
    R.tabulate("table2")                  # made as config tables.table2 declares, written
                                          # as results/<paper>/tables/table2.csv
    R.validation()                        # the table validate_<paper> built, for display
    R.table("cost_of_accuracy")           # a written table, e.g. the framework's long-form
                                          # cost of accuracy
"""
from __future__ import annotations

from pathlib import Path

from .config import CACHE_DIR, MAKER, load_paper
from .io import open_dataset, write_dataset
from .validation import write_csv


class PaperResults:
    def __init__(self, paper: str, results_dir: str, config_file: str, profile: str = "default"):
        self.paper = paper
        self.root = Path(results_dir) / paper
        self.cfg = load_paper(config_file, profile, CACHE_DIR)
        self._reads = None     # while a figure draws or a table is made: what it declared it reads
        self._rows = None      # the validation table by quantity, read once

    def _may_read(self, name: str) -> None:
        # a declared run or study covers its verdict variants (<name>@coarser, ...), which
        # differ between profiles
        if self._reads is not None and name.split("@")[0] not in self._reads[1]:
            raise KeyError(f"{self.paper}: {self._reads[0]} reads {name!r}, which its declaration "
                           f"(config {self._reads[0]}.reads) does not name")

    def run(self, name: str):
        self._may_read(name)
        return open_dataset(self.root / "runs" / f"{name}.nc")

    def study(self, name: str):
        self._may_read(name)
        return open_dataset(self.root / "studies" / f"{name}.nc")

    def study_runs(self, name: str) -> list:
        """The run datasets of a study, in sweep order (what the study file cannot stack:
        variables whose length differs between runs, e.g. adaptively sampled speeds)."""
        self._may_read(name)
        return [open_dataset(self.root / "runs" / f"{r}.nc") for r in self.cfg.studies[name]]

    def _make(self, kind: str, name: str):
        """What the function of figure or table ``name`` returns, called as its declaration
        says (config ``<kind>.<name>``: ``draw`` or ``make``, a ``module.function`` of
        models/<paper>/ or a function of the package), given this object, opening only the runs
        and studies of its ``reads`` and their verdict variants."""
        import importlib

        if name not in self.cfg.raw.get(kind, {}):
            raise KeyError(f"{self.paper}: {kind[:-1]} {name!r} not declared in config {kind!r}")
        spec = getattr(self.cfg, kind[:-1])(name)
        module, _, function = spec[MAKER[kind]].rpartition(".")
        package = f"mechrepro.models.{self.paper}"
        make = getattr(importlib.import_module(f"{package}.{module}" if module else package), function)
        self._reads = (f"{kind}.{name}", set(spec["reads"]))
        try:
            return make(self)
        finally:
            self._reads = None

    def draw(self, name: str):
        """Figure ``name`` drawn as its declaration says (config ``figures.<name>``)."""
        return self._make("figures", name)

    def figure(self, name: str) -> None:
        """Draw declared figure ``name`` (:meth:`draw`) and save it, linted, as
        ``figures/<name>.png`` (:func:`mechrepro.plotting.savefig`)."""
        from .plotting import savefig

        savefig(self.draw(name), self.root / "figures" / f"{name}.png")

    def make(self, name: str) -> tuple[list, list]:
        """Table ``name``'s (header, rows) made as its declaration says (config
        ``tables.<name>``)."""
        return self._make("tables", name)

    def tabulate(self, name: str) -> None:
        """Make declared table ``name`` (:meth:`make`) and write it as ``tables/<name>.csv``."""
        write_csv(self.table_path(name), *self.make(name))

    def table_path(self, name: str) -> Path:
        return self.root / "tables" / f"{name}.csv"

    def table(self, name: str) -> list[dict]:
        """A written table as rows of dicts (e.g. the framework's ``cost_of_accuracy``,
        long form: one row per entry, knob value and quantity; see mechrepro.accuracy)."""
        from .validation import read_table

        return read_table(self.table_path(name))

    def validation(self) -> list[dict]:
        """The validation table the framework built (``validate_<paper>``), for display."""
        from .validation import read_table

        return read_table(self.table_path("validation"))

    def row(self, quantity: str) -> dict:
        """The validation table's row of ``quantity``."""
        if self._rows is None:
            self._rows = {r["quantity"]: r for r in self.validation()}
        return self._rows[quantity]

    def value(self, quantity: str, column: str = "reproduced_value") -> float:
        """A number of the validation table's row ``quantity`` (in the row's unit)."""
        return float(self.row(quantity)[column])

    def write_dataset(self, ds, name: str) -> Path:
        """A derived dataset of the notebook (e.g. cost_of_accuracy) under tables/."""
        return write_dataset(ds, self.root / "tables" / f"{name}.nc")
