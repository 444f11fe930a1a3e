import shutil
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "src"))


@pytest.fixture
def config_copy(tmp_path):
    """A writable copy of config/ (schemas + paper files) for mutation tests."""
    dst = tmp_path / "config"
    shutil.copytree(ROOT / "config", dst)
    return dst
