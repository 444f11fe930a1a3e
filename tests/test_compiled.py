"""mechrepro.compiled: a cached kernel never runs stale code."""
import os
import subprocess
import sys

import pytest

from mechrepro.compiled import available


@pytest.mark.skipif(not available(), reason="numba not installed")
def test_a_cached_kernel_follows_a_change_in_a_kernel_it_calls(tmp_path):
    """numba keys its disk cache on the kernel's own file; k.py's kernel calls f.py's, so
    without a key over the whole package the edit of f.py went unseen (4.0 after the edit,
    measured with numba's default cache)."""
    pkg = tmp_path / "pk"
    pkg.mkdir()
    (pkg / "__init__.py").write_text("")
    kernel = "from mechrepro.compiled import jit\n@jit\ndef g(x):\n    return x + {}\n"
    (pkg / "f.py").write_text(kernel.format(1.0))
    (pkg / "k.py").write_text("from mechrepro.compiled import jit\nfrom .f import g\n"
                              "@jit\ndef k(x):\n    return g(x) * 2.0\n")
    env = {**os.environ, "PYTHONPATH": os.pathsep.join([str(tmp_path), *sys.path])}

    def k_of_1():
        return subprocess.run([sys.executable, "-c", "from pk.k import k; print(k(1.0))"],
                              cwd=tmp_path, capture_output=True, text=True, env=env,
                              check=True).stdout.strip()

    assert k_of_1() == k_of_1() == "4.0"      # compiled, then read from the cache
    (pkg / "f.py").write_text(kernel.format(10.0))
    assert k_of_1() == "22.0"
