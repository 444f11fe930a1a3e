"""The notebook runner (mechrepro.notebook, mechrepro.kernel): a notebook run in-process sees
what it would see in a kernel process, its output reaches the executed notebook, and a
failing cell fails the job without leaving an output."""
import json
import os
import subprocess
import sys

import pytest

from conftest import ROOT

# what a cell can see that could change a result
PROBE = '''# %% tags=["parameters"]
out = "state.json"

# %%
import json, os, sys, threading, warnings
import numpy as np
from mechrepro.plotting import plt
import matplotlib
print("printed")
print("to stderr", file=sys.stderr)
state = {
    "warnings": [repr(f[:1] + (f[1] and f[1].pattern,) + f[2:]) for f in warnings.filters],
    "rc": {k: repr(v) for k, v in matplotlib.rcParams.items()},
    "backend": matplotlib.get_backend(),
    "cwd": os.getcwd(),
    "env": {k: v for k, v in os.environ.items() if k != "JPY_PARENT_PID"},
    "path": sys.path,
    "main_thread": threading.current_thread() is threading.main_thread(),
    "errstate": np.geterr(),
    "name": __name__,
}
json.dump(state, open(out, "w"))
1 + 1
'''


def _run(code, tmp_path):
    env = {**os.environ, "PYTHONPATH": str(ROOT / "src")}
    return subprocess.run([sys.executable, "-c", code], cwd=tmp_path, env=env,
                          capture_output=True, text=True)


def test_in_process_kernel_sees_what_a_kernel_process_sees(tmp_path):
    (tmp_path / "probe.py").write_text(PROBE)
    # the reference: papermill's own kernel process (the runner before mechrepro.kernel)
    ref = _run("import os, jupytext, papermill\n"
               "os.environ['MPLBACKEND'] = 'Agg'\n"
               "nb = jupytext.read('probe.py')\n"
               "nb.metadata['kernelspec'] = {'name': 'python3', 'display_name': 'Python 3', "
               "'language': 'python'}\n"
               "papermill.execute_notebook(nb, 'ref.ipynb', parameters={'out': 'ref.json'}, "
               "kernel_name='python3', progress_bar=False)", tmp_path)
    assert ref.returncode == 0, ref.stderr
    new = _run("from mechrepro.notebook import run_notebook\n"
               "run_notebook('probe.py', 'new.ipynb', {'out': 'new.json'}, cwd='.')", tmp_path)
    assert new.returncode == 0, new.stderr
    a, b = (json.loads((tmp_path / f).read_text()) for f in ("ref.json", "new.json"))
    # both can import from the working directory ('' on sys.path): a kernel process after
    # the standard library, `python -c` / `python -m` first
    a["path"], b["path"] = ([p for p in d["path"] if p] for d in (a, b))
    # the runner imports numpy before IPython, so their (disjoint) filters come in another order
    a["warnings"], b["warnings"] = sorted(a["warnings"]), sorted(b["warnings"])
    for key in a:
        assert a[key] == b[key], key
    outputs = [json.loads((tmp_path / f).read_text())["cells"][-1]["outputs"]
               for f in ("ref.ipynb", "new.ipynb")]
    assert [(o["output_type"], o.get("text"), o.get("data")) for o in outputs[0]] == \
        [(o["output_type"], o.get("text"), o.get("data")) for o in outputs[1]]
    assert [o.get("name") for o in outputs[1]] == ["stdout", "stderr", None]


def test_failing_cell_fails_and_leaves_no_output(tmp_path):
    (tmp_path / "bad.py").write_text('# %%\nprint("before")\n\n# %%\nraise ValueError("boom")\n')
    proc = _run("from mechrepro.notebook import run_notebook\n"
                "run_notebook('bad.py', 'bad.ipynb', {}, cwd='.')", tmp_path)
    assert proc.returncode != 0
    assert "boom" in proc.stderr
    assert not list(tmp_path.glob("*.ipynb"))
