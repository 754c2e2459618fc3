"""The package ships ``py.typed``: ``mypy src`` must report no error (issue 10)."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


def test_mypy_clean():
    pytest.importorskip("mypy", reason="mypy is installed with the test extras")
    r = subprocess.run([sys.executable, "-m", "mypy", "--no-error-summary", "src"], cwd=ROOT,
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stdout + r.stderr


def test_mypy_strict_on_core_and_model():
    """The two bottom layers type-check with ``--strict`` too."""
    pytest.importorskip("mypy", reason="mypy is installed with the test extras")
    r = subprocess.run([sys.executable, "-m", "mypy", "--no-error-summary", "--strict",
                        "src/fcgrasp/core", "src/fcgrasp/model"], cwd=ROOT,
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stdout + r.stderr
