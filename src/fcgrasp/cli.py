"""The ``fcgrasp`` command (a leaf: nothing in the core imports it).

``fcgrasp demo [--out DIR]`` runs the main job on built-in examples and writes a
JSON result and a figure into ``DIR``.  Errors print one line on stderr and exit
with code 2; output files are written atomically.
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path
from typing import Any

import numpy as np

from . import __version__
from ._atomic import atomic_write_text
from .contacts import (
    FrictionEdge,
    FrictionlessEdge,
    FrictionlessPoint,
    FrictionPoint,
    Gravity,
    SoftFinger,
)
from .grasp import Grasp

EXIT_USAGE = 2


class CliError(Exception):
    """An error reported as one line on stderr with exit code 2."""


def _round(x: Any) -> Any:
    return np.round(np.asarray(x, dtype=float), 9).tolist()


def _cone_json(cone: Any) -> dict[str, Any]:
    m = cone.minimal()
    return {"rays": _round(m.rays + 0.0), "lines": _round(m.lines + 0.0)}


def demo_contacts() -> dict[str, Any]:
    """The primitive contacts of figure 4 with their wrench and twist convexes."""
    corner = np.sqrt(0.5)
    return {
        "frictionless point (4.a)": FrictionlessPoint([0, 0], [0, 1]),
        "point with friction (4.b)": FrictionPoint([0, 0], [0, 1], 0.3),
        "frictionless edge (4.c)": FrictionlessEdge([-1, 0], [1, 0], [0, 1]),
        "edge with friction (4.d)": FrictionEdge([-1, 0], [1, 0], [0, 1], 0.3),
        "soft finger around a corner (4.e)": SoftFinger.corner(
            [-1, 0], [0, 0], [corner, -corner], [0, 1], [corner, corner], 0.3),
        "gravity (3.1)": Gravity([0, 0.5]),
    }


def demo_grasps() -> dict[str, tuple[Grasp, list[list[float]]]]:
    """A few grasps on a unit square with their verdicts."""
    square = [[0, 0], [1, 0], [1, 1], [0, 1]]
    return {
        "two fingers with friction": (Grasp([FrictionPoint([0, 0.5], [-1, 0], 0.3),
                                             FrictionPoint([1, 0.6], [1, 0], 0.3)]), square),
        "two frictionless fingers": (Grasp([FrictionlessPoint([0, 0.5], [-1, 0]),
                                            FrictionlessPoint([1, 0.5], [1, 0])]), square),
        "four frictionless fingers": (Grasp([FrictionlessPoint([0, 0.3], [-1, 0]),
                                             FrictionlessPoint([0.4, 0], [0, -1]),
                                             FrictionlessPoint([1, 0.7], [1, 0]),
                                             FrictionlessPoint([0.6, 1], [0, 1])]), square),
        "four fingers, lines concurrent": (Grasp([FrictionlessPoint([0, 0.5], [-1, 0]),
                                                  FrictionlessPoint([0.5, 0], [0, -1]),
                                                  FrictionlessPoint([1, 0.5], [1, 0]),
                                                  FrictionlessPoint([0.5, 1], [0, 1])]), square),
    }


def run_demo(out: Path, quiet: bool = False) -> dict[str, Any]:
    """Compute the demo, write ``demo.json`` and ``demo.png`` into ``out``."""
    result: dict[str, Any] = {"fcgrasp": __version__, "format": 1, "contacts": {}, "grasps": {}}
    for name, c in demo_contacts().items():
        result["contacts"][name] = {
            "wrenches": _round(c.wrenches),
            "wrench_cone": _cone_json(c.wrench_cone()),
            "total_freedom": _cone_json(c.twist_cone()),
        }
    for name, (g, _) in demo_grasps().items():
        rep = g.explain()
        result["grasps"][name] = {
            "force_closure": rep.force_closure,
            "failed": rep.failed,
            "escape_twist": None if rep.escape_twist is None else _round(rep.escape_twist),
            "escape": rep.escape_description,
        }
    out.mkdir(parents=True, exist_ok=True)
    atomic_write_text(out / "demo.json", json.dumps(result, indent=2, sort_keys=True) + "\n")
    _demo_figure(out / "demo.png")
    if not quiet:
        for name, g in result["grasps"].items():
            verdict = "force closure" if g["force_closure"] else f"not: {g['failed']}"
            print(f"{name:34s} {verdict:28s} escape: {g['escape']}")
        print(f"wrote {out / 'demo.json'} and {out / 'demo.png'}")
    return result


def _demo_figure(path: Path) -> None:
    from .plotting import _pyplot, draw_grasp, save_figure

    plt = _pyplot()
    grasps = demo_grasps()
    fig, axes = plt.subplots(1, len(grasps), figsize=(3 * len(grasps), 3))
    for ax, (name, (g, outline)) in zip(np.atleast_1d(axes), grasps.items(), strict=True):
        rep = g.explain()
        draw_grasp(ax, g, outline, title=f"{name}\n{'FC' if rep.force_closure else rep.failed}")
    save_figure(fig, str(path))
    plt.close(fig)


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="fcgrasp",
        description="Force-closure grasps of planar objects (Nguyen's synthesis).",
        epilog="example: fcgrasp demo --out demo-output")
    parser.add_argument("--version", action="version", version=f"fcgrasp {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")
    demo = sub.add_parser("demo", help="run the built-in examples, write JSON and a figure",
                          description="Run the built-in examples and write demo.json and "
                                      "demo.png into a folder.",
                          epilog="example: fcgrasp demo --out demo-output")
    demo.add_argument("--out", default="demo-output", help="output folder (default: %(default)s)")
    demo.add_argument("--quiet", action="store_true", help="print nothing on success")
    return parser


def main(argv: list[str] | None = None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        if args.command == "demo":
            run_demo(Path(args.out), quiet=args.quiet)
            return 0
        parser.print_help()
        return EXIT_USAGE
    except (CliError, ValueError, TypeError, OSError) as exc:
        print(f"fcgrasp: error: {exc}", file=sys.stderr)
        return EXIT_USAGE


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
