"""The one notebook runner: a jupytext ``py:percent`` notebook executed by papermill.

Notebooks live in git as ``notebooks/<paper>.py`` (reviewable text) and are executed as
parameterised notebooks, in this process (:mod:`mechrepro.kernel`: no kernel process to
start, and the notebook's imports are not paid twice); the executed ``.ipynb`` is written
atomically, once at the end (papermill's save after every cell is skipped).  Executed
notebooks carry timestamps: compare the data they write, never their bytes.
"""
from __future__ import annotations

import os
import sys
import warnings
from pathlib import Path

from .io import atomic_path


def run_notebook(source: str | Path, output: str | Path, parameters: dict,
                 cwd: str | Path = ".") -> Path:
    # the runner's own imports must not leave warnings filters a kernel process has not
    # (requests adds one for urllib3)
    with warnings.catch_warnings():
        import jupytext
        import papermill

    from .kernel import KernelManager

    os.environ["MPLBACKEND"] = "Agg"  # seen by the kernel: no display needed
    nb = jupytext.read(source)
    nb.metadata["kernelspec"] = {"name": "python3", "display_name": "Python 3",
                                 "language": "python"}
    with atomic_path(output) as tmp:
        papermill.execute_notebook(nb, str(tmp), parameters=parameters,
                                   kernel_name="python3", cwd=str(cwd),
                                   progress_bar=False, log_output=False,
                                   request_save_on_cell_execute=False,
                                   kernel_manager_class=KernelManager)
    return Path(output)


def main(argv: list[str]) -> None:
    paper, source, output, results, config_file, profile = argv
    run_notebook(source, output, {"paper": paper, "results_dir": results,
                                  "config_file": config_file, "profile": profile},
                 cwd=Path(config_file).resolve().parent.parent.parent)
    print(f"[{paper}] notebook executed -> {output}", flush=True)


if __name__ == "__main__":
    main(sys.argv[1:])
