#!/usr/bin/env python3
"""The project's two commands, needing nothing but python3 (and PyPI).

    python3 tasks.py demo    # set up .venv if needed, run the demo plan into demo-output/
    python3 tasks.py test    # set up .venv (and Debian's chromium) if needed, run every test,
                             # then build the documentation (warnings are errors)
    python3 tasks.py docs    # set up .venv if needed, build the documentation into docs/_build
    python3 tasks.py bench   # set up .venv if needed, run the benchmark scripts

Extra arguments after the command are passed on (to ``fcgrasp demo`` or to pytest; the
tests run on every core unless ``-n 0`` is given).
"""

from __future__ import annotations

import hashlib
import os
import shutil
import subprocess
import sys
import tempfile
import venv
from pathlib import Path

ROOT = Path(__file__).resolve().parent
VENV = ROOT / ".venv"
BIN = VENV / ("Scripts" if os.name == "nt" else "bin")
PY = BIN / "python"
STAMP = VENV / ".fcgrasp-installed"
EXTRAS = "test,all"


def _fingerprint() -> str:
    data = (ROOT / "pyproject.toml").read_bytes() + EXTRAS.encode()
    return hashlib.sha256(data).hexdigest()


def ensure_venv() -> None:
    """Create .venv and install the package with its extras, once per pyproject change."""
    if not PY.exists():
        print("creating .venv ...", flush=True)
        venv.EnvBuilder(with_pip=True).create(VENV)
    if STAMP.exists() and STAMP.read_text() == _fingerprint():
        return
    print("installing fcgrasp and its dependencies into .venv ...", flush=True)
    pip = [str(PY), "-m", "pip", "--disable-pip-version-check", "-q"]
    subprocess.run(pip + ["install", "--upgrade", "pip"], check=True)
    subprocess.run(pip + ["install", "-e", f".[{EXTRAS}]"], check=True, cwd=ROOT)
    STAMP.write_text(_fingerprint())


def ensure_browser() -> None:
    """Debian's Chromium and ChromeDriver, for the explorer's browser tests
    (tests/test_explorer.py), installed with apt-get when missing; nothing downloads a
    browser build of its own.  Where apt-get cannot run (not Debian, not root) the tests
    that need a browser are skipped and say why."""
    if shutil.which("chromium") and shutil.which("chromedriver"):
        return
    if not shutil.which("apt-get") or not hasattr(os, "geteuid") or os.geteuid() != 0:
        print("note: chromium and chromedriver are missing and apt-get cannot install them "
              "here (needs Debian and root): the browser tests will be skipped", flush=True)
        return
    print("installing Debian's chromium and chromium-driver for the browser tests ...",
          flush=True)
    env = dict(os.environ, DEBIAN_FRONTEND="noninteractive")
    subprocess.run(["apt-get", "update", "-qq"], check=True, env=env)
    subprocess.run(["apt-get", "install", "-y", "-qq", "--no-install-recommends", "chromium",
                    "chromium-driver", "fonts-liberation"], check=True, env=env,
                   stdout=subprocess.DEVNULL)


def compile_kernels(env: dict[str, str]) -> None:
    """numba's kernels compiled once, before the demo or the suite (fcgrasp.compile_kernels:
    two to three minutes the first time, the cache beside the sources after that), so
    that no test worker compiles them again."""
    print("numba kernels: compiling or loading the cache ...", flush=True)
    subprocess.run([str(PY), "-c", "import fcgrasp; fcgrasp.compile_kernels()"], cwd=ROOT,
                   env=env, check=True)


def warm_caches(env: dict[str, str]) -> None:
    """The bytecode of the package and the tests, and matplotlib's font cache, made once
    before the suite: a fresh clone would otherwise make them in every test worker and in
    every command the tests start."""
    subprocess.run([str(PY), "-m", "compileall", "-q", "src", "tests", "benchmarks"],
                   cwd=ROOT, env=env, check=True, stdout=subprocess.DEVNULL)
    subprocess.run([str(PY), "-c", "import matplotlib.font_manager"], cwd=ROOT, env=env,
                   check=True)


def start_type_check(env: dict[str, str]) -> subprocess.Popen[bytes] | None:
    """``mypy src`` started in the background (its verdict is the suite's to give; this
    run only fills mypy's cache in ``.mypy_cache``); None where mypy is not installed."""
    if subprocess.run([str(PY), "-c", "import mypy"], cwd=ROOT, env=env,
                      stderr=subprocess.DEVNULL).returncode:
        return None
    return subprocess.Popen([str(PY), "-m", "mypy", "--no-error-summary", "src"], cwd=ROOT,
                            env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)


def build_docs(out: str, env: dict[str, str], quiet: bool = True) -> int:
    """The documentation (docs/: the guide, the API reference from the docstrings, the
    design notes, the gallery) built with Sphinx into ``out``, every warning an error."""
    return subprocess.run([str(BIN / "sphinx-build"), "-W", "--keep-going", "-E",
                           *(["-q"] if quiet else []), "-b", "html", "docs", out],
                          cwd=ROOT, env=env).returncode


def main(argv: list[str]) -> int:
    if not argv or argv[0] not in {"demo", "test", "docs", "bench"}:
        print(__doc__)
        return 2
    ensure_venv()
    cmd, rest = argv[0], argv[1:]
    env = dict(os.environ, MPLBACKEND="Agg")
    # bytecode cached beside the sources: the suite starts the command line in dozens of
    # processes, each of which would otherwise compile the package again
    env.pop("PYTHONDONTWRITEBYTECODE", None)
    # mypy's cache made beside the kernels' compilation and the bytecode (one core each):
    # the suite's type check (tests/test_typing.py) then reads it instead of parsing
    # numpy's stubs again on one of the suite's cores
    typing = start_type_check(env) if cmd == "test" else None
    if cmd in ("demo", "test"):
        compile_kernels(env)
    if cmd == "demo":
        args = rest or ["--out", "demo-output"]
        return subprocess.run([str(BIN / "fcgrasp"), "demo", *args], cwd=ROOT, env=env).returncode
    if cmd == "test":
        ensure_browser()
        warm_caches(env)
        if typing is not None:
            typing.wait()
        # a compiled loop that fails fails the suite (it would run by numpy, unseen)
        env["FCGRASP_REQUIRE_JIT"] = "1"
        # the suite runs on every core (pytest-xdist) unless told otherwise (-n 0)
        # (work stealing: a worker left idle takes queued tests from the other)
        par = [] if any(a == "-n" or a.startswith(("-n", "--numprocesses")) for a in rest) \
            else ["-n", "auto", "--dist", "worksteal"]
        code = subprocess.run([str(PY), "-m", "pytest", *par, *rest], cwd=ROOT,
                              env=env).returncode
        with tempfile.TemporaryDirectory() as out:
            docs = build_docs(out, env)
        if docs:
            print("the documentation does not build (see above): sphinx-build exit "
                  f"{docs}", flush=True)
        return code or docs
    if cmd == "docs":
        return build_docs(str(ROOT / "docs" / "_build" / "html"), env, quiet=False)
    code = 0
    for script in sorted((ROOT / "benchmarks").glob("bench_*.py")):
        print(f"== {script.name}", flush=True)
        code |= subprocess.run([str(PY), str(script), *rest], cwd=ROOT, env=env).returncode
    return code


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
