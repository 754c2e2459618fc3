"""The default plan over the grid users meet: each run in a fresh process exactly as the
command line runs it (``fcgrasp plan FILE ... --json OUT``, nothing but the gripper's
options given), timed in CPU seconds and peak memory of that process, beside two
baselines measured in the same invocation:

* **complete**: the same command with ``--time-limit 0`` (no budget: the distinct search
  run to its end, as every run was before the budget), stopped by this script after
  ``--cap`` seconds of wall-clock time (the cell then reads ``>CAP``);
* **ranked**: ``--distinct 0`` (the ranked list, no distinct alternatives);
* **previous** (with ``--previous DIR``, a checkout of an earlier commit): the same
  default command run by that checkout's code (``PYTHONPATH=DIR/src``, its kernels
  compiled first), and whether its plans are the same (the JSON's grasps compared).

The default's column says how many plans it proved and whether its answer is complete;
``time_limit`` and ``max_memory`` stops print their bound.

    python benchmarks/bench_defaults.py [--sizes 1000,10000] [--mu 0.2,0.3,0.5,1.0]
                                        [--grippers 2f,3f,4f,jaw] [--shapes smooth,noisy]
                                        [--files dxf/forms.dxf,gears/teeth-32.dxf]
                                        [--cap 120] [--no-baselines] [--previous DIR]
                                        [--repeat N]

The outlines: ``smooth`` an ellipse with a third harmonic (120 x 70 mm), ``noisy`` a
five-lobed star with 0.5 % radial noise (100 mm across), each with the given number of
equal-angle edges; ``--files`` adds corpus files (``benchmarks/corpus``), read as the
command line reads them.  Prints a Markdown table.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
FCGRASP = Path(sys.executable).with_name("fcgrasp")

GRIPPERS = {
    "2f": [],
    "3f": ["--fingers", "3"],
    "4f": ["--fingers", "4"],
    "jaw": ["--gripper", "jaw", "--stroke", "5,130", "--pad", "8"],
}


def outline(shape: str, n: int) -> dict[str, list[list[float]]]:
    import numpy as np

    a = np.linspace(0, 2 * np.pi, n, endpoint=False)
    if shape == "smooth":
        r = 1 + 0.1 * np.cos(3 * a)
        xy = np.c_[60 * r * np.cos(a), 35 * r * np.sin(a)]
    else:
        rng = np.random.default_rng(0)
        r = 50 * (1 + 0.3 * np.sin(5 * a)) * (1 + 0.005 * rng.standard_normal(n))
        xy = np.c_[r * np.cos(a), r * np.sin(a)]
    return {"vertices": xy.tolist()}


def run(argv: list[str], cap: float | None, src: str | None = None) -> dict[str, object]:
    """One command in a fresh process (``src``: the package's sources to run instead of
    the installed ones): its CPU seconds and peak memory (its own, from ``wait4``), and
    what its JSON report says; None fields where it was stopped."""
    env = None if src is None else dict(os.environ, PYTHONPATH=src)
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "plan.json")
        proc = subprocess.Popen([str(FCGRASP), *argv, "--json", out, "--quiet"],
                                stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, env=env)
        start = time.monotonic()
        while True:
            pid, status, usage = os.wait4(proc.pid, os.WNOHANG)
            if pid:
                break
            if cap is not None and time.monotonic() - start > cap:
                proc.kill()
                proc.wait()
                return {"cpu": None, "mb": None, "capped": True}
            time.sleep(0.01)
        err = proc.stderr.read().decode() if proc.stderr else ""
        proc.stderr and proc.stderr.close()
        if os.waitstatus_to_exitcode(status) != 0:
            return {"cpu": None, "mb": None, "error": err.strip().splitlines()[-1:]}
        report = json.loads(Path(out).read_text())
    return {"cpu": usage.ru_utime + usage.ru_stime, "mb": usage.ru_maxrss / 1024,
            "plans": len(report["grasps"]), "complete": report.get("complete", True),
            "gap": report.get("gap"), "grasps": json.dumps(report["grasps"], sort_keys=True)}


def warm(previous: str | None) -> None:
    """numba's cache compiled once (the previous checkout's package ``previous`` too),
    so that no row pays for it, and both packages' bytecode written, so that neither
    compiles its sources per run."""
    for src in [None] + ([previous] if previous else []):
        env = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}
        if src is not None:
            env["PYTHONPATH"] = src
        subprocess.run([sys.executable, "-c", "import fcgrasp; fcgrasp.compile_kernels()"],
                       check=True, env=env)
        subprocess.run([sys.executable, "-m", "compileall", "-q",
                        src or str(HERE.parent / "src")], check=True, env=env,
                       stdout=subprocess.DEVNULL)


def _least(a: dict[str, object], b: dict[str, object]) -> dict[str, object]:
    """Of two runs of one command, the one with less CPU (a stopped run counts as more)."""
    if a.get("cpu") is None:
        return b
    if b.get("cpu") is None:
        return a
    return a if a["cpu"] <= b["cpu"] else b  # type: ignore[operator]


def cell(r: dict[str, object], cap: float | None) -> str:
    if r.get("capped"):
        return f">{cap:g} s"
    if r.get("error"):
        return f"error: {r['error']}"
    return f"{r['cpu']:.2f} s, {r['mb']:.0f} MB"


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sizes", default="1000,10000")
    ap.add_argument("--mu", default="0.2,0.3,0.5,1.0")
    ap.add_argument("--grippers", default="2f,3f,4f,jaw")
    ap.add_argument("--shapes", default="smooth,noisy")
    ap.add_argument("--files", default="")
    ap.add_argument("--cap", type=float, default=120.0)
    ap.add_argument("--no-baselines", action="store_true")
    ap.add_argument("--repeat", type=int, default=1,
                    help="run the default (and previous) command this many times, "
                         "alternated, and keep the least CPU of each")
    ap.add_argument("--previous", default=None,
                    help="a checkout of an earlier commit: its code's row beside each")
    args = ap.parse_args()
    previous = None if args.previous is None else str(Path(args.previous).resolve() / "src")
    warm(previous)
    parts: list[tuple[str, str]] = []
    with tempfile.TemporaryDirectory() as tmp:
        for shape in filter(None, args.shapes.split(",")):
            for n in map(int, filter(None, args.sizes.split(","))):
                path = os.path.join(tmp, f"{shape}-{n}.json")
                Path(path).write_text(json.dumps(outline(shape, n)))
                parts.append((f"{shape} {n:,}", path))
        for f in filter(None, args.files.split(",")):
            parts.append((f, str(HERE / "corpus" / f)))
        head = ["part", "gripper", "mu", "default (CPU, peak)", "plans", "complete"]
        if not args.no_baselines:
            head += ["complete search", "ratio", "ranked", "ratio"]
        if previous:
            head += ["previous", "ratio", "same plans"]
        print("| " + " | ".join(head) + " |")
        print("|" + " --- |" * len(head))
        for label, path in parts:
            for g in filter(None, args.grippers.split(",")):
                for mu in filter(None, args.mu.split(",")):
                    if g == "4f" and mu != args.mu.split(",")[0]:
                        continue                # frictionless: one row per part
                    argv = ["plan", path, *GRIPPERS[g]]
                    if g != "4f":
                        argv += ["--mu", mu]
                    d = run(argv, None)
                    b_prev = run(argv, args.cap, previous) if previous else {}
                    for _ in range(args.repeat - 1):     # the least of each, alternated
                        d = _least(d, run(argv, None))
                        if previous:
                            b_prev = _least(b_prev, run(argv, args.cap, previous))
                    done = "yes" if d.get("complete") else \
                        f"no: {d['gap']['stopped_by']}, bound {d['gap']['bound']}" \
                        if d.get("gap") else "-"
                    row = [label, g, "-" if g == "4f" else mu, cell(d, None),
                           str(d.get("plans", "-")), done]
                    if not args.no_baselines:
                        for extra in (["--time-limit", "0"], ["--distinct", "0"]):
                            b = run(argv + extra, args.cap)
                            ratio = "-" if b.get("cpu") is None or d.get("cpu") is None \
                                else f"{d['cpu'] / max(b['cpu'], 1e-9):.2f}"
                            row += [cell(b, args.cap), ratio]
                    if previous:
                        b = b_prev
                        ratio = "-" if b.get("cpu") is None or d.get("cpu") is None \
                            else f"{d['cpu'] / max(b['cpu'], 1e-9):.2f}"
                        same = "-" if b.get("grasps") is None else \
                            "yes" if b["grasps"] == d.get("grasps") else "no"
                        row += [cell(b, args.cap), ratio, same]
                    print("| " + " | ".join(row) + " |", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
