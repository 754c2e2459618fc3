"""``import fcgrasp`` stays light (issue 10): no scipy.optimize, matplotlib or reader
library until used; the version literal matches the package metadata."""

from __future__ import annotations

import subprocess
import sys
import tomllib
from pathlib import Path

HEAVY = ("scipy.optimize", "scipy.spatial", "matplotlib", "svgelements", "ezdxf", "skimage",
         "importlib.metadata")


def test_import_fcgrasp_loads_no_heavy_module():
    code = f"import sys, fcgrasp; print(','.join(m for m in {HEAVY!r} if m in sys.modules))"
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert r.stdout.strip() == "", r.stdout


def test_version_matches_pyproject():
    import fcgrasp

    meta = tomllib.loads((Path(__file__).parents[1] / "pyproject.toml").read_text())
    assert fcgrasp.__version__ == meta["project"]["version"]
