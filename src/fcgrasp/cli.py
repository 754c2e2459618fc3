"""The ``fcgrasp`` command (a leaf: nothing in the core imports it).

Sub-commands: ``plan`` (ranked grasp plans of a part file), ``check`` (the verdict for a
given grasp) and ``demo`` (the main job on built-in parts).  Every error prints one line
on stderr and exits with code 2 (1 for an internal error), never a traceback; output
files are written atomically (temporary file, then rename), so a failed run leaves none.
"""

from __future__ import annotations

import argparse
import os
import sys
from pathlib import Path
from typing import Any, NoReturn

import numpy as np

from . import __version__
from ._atomic import OutputSet
from .grasp import Grasp
from .hand import Hand
from .parts import DEMO_PARTS, demo_part, read_contacts, read_part
from .planning import plan
from .ranking import MEASURES
from .regions import DEFAULT_MARGIN_DEG
from .report import check_report, demo_summary, dumps, plan_report

EXIT_USAGE = 2
EXIT_INTERNAL = 1
UNITS = {"mm": 10.0, "cm": 1.0, "m": 0.01}      # 1 cm in each unit


class CliError(Exception):
    """An error reported as one line on stderr with exit code 2."""


class _Parser(argparse.ArgumentParser):
    def error(self, message: str) -> NoReturn:
        print(f"fcgrasp: error: {message} (see fcgrasp --help)", file=sys.stderr)
        raise SystemExit(EXIT_USAGE)


# ----------------------------------------------------------------------------- helpers


def _floats(text: str, n: int, name: str) -> tuple[float, ...]:
    parts = [t for t in text.replace(" ", "").split(",") if t]
    try:
        vals = tuple(float(t) for t in parts)
    except ValueError:
        raise CliError(f"{name} must be {n} comma-separated numbers, got {text!r}") from None
    if len(vals) != n or not all(np.isfinite(vals)):
        raise CliError(f"{name} must be {n} comma-separated finite numbers, got {text!r}")
    return vals


def _progress(enabled: bool) -> Any:
    if not enabled:
        return None

    def show(done: int, total: int) -> None:
        width = 30
        frac = done / max(total, 1)
        bar = "#" * int(width * frac)
        print(f"\r[{bar:<{width}}] {100 * frac:5.1f}% candidate edge sets", end="",
              file=sys.stderr, flush=True)
        if done >= total:
            print("\r" + " " * (width + 32) + "\r", end="", file=sys.stderr, flush=True)

    return show


def _same_file(a: str, b: str) -> bool:
    try:
        if os.path.exists(a) and os.path.exists(b):
            return os.path.samefile(a, b)
    except OSError:
        pass
    return os.path.realpath(a) == os.path.realpath(b)


def _check_outputs(args: Any, inputs: list[str]) -> None:
    """Validate every output option before any work: extensions, and no output that is
    an input or another output (a run must never overwrite what it reads)."""
    outs = [(f"--{k}", getattr(args, k)) for k in ("json", "plot") if getattr(args, k, None)]
    for opt, path in outs:
        if path == "-" or path.endswith(os.sep) or os.path.isdir(path):
            raise CliError(f"{opt} must be a file name, got {path!r}")
        for src in inputs:
            if not src.startswith("demo:") and _same_file(path, src):
                raise CliError(f"{opt} {path} is an input of this run: refusing to "
                               f"overwrite it")
    if len(outs) == 2 and _same_file(outs[0][1], outs[1][1]):
        raise CliError(f"--json and --plot name the same file {outs[0][1]!r}")
    plot = getattr(args, "plot", None)
    if plot:
        if Path(plot).suffix.lower() not in (".png", ".svg", ".pdf"):
            raise CliError(f"--plot must end in .png, .svg or .pdf, got {plot!r}")
        try:
            import matplotlib  # noqa: F401
        except ImportError:
            raise CliError("--plot needs matplotlib: pip install 'fcgrasp[plot]'") from None


def _write_outputs(polygon: Any, plans: list[Any], report: dict[str, Any], args: Any,
                   title: str) -> None:
    """The JSON and the figure of one run, written as a set (both or neither)."""
    with OutputSet() as out:
        if args.json:
            out.add_text(args.json, dumps(report))
        if args.plot:
            from .plotting import plan_figure

            plan_figure(polygon, plans, args.plot, units=args.units, title=title, outputs=out)


def _print_table(plans: list[Any], units: str, out: Any) -> None:
    if not plans:
        return
    print(f"{'rank':>4}  {'edges':<16} {'min region':>11}  {'regions (' + units + ')':<28} "
          f"{'resistance':>10} {'eps L1':>8}", file=out)
    for k, p in enumerate(plans):
        q = p.quality
        regs = ", ".join(f"{x:.3g}" for x in p.lengths)
        print(f"{k + 1:>4}  {str(list(p.edges)):<16} {p.min_length:>11.4g}  {regs:<28} "
              f"{q['resistance']:>10.4g} {q['epsilon_l1']:>8.4g}", file=out)


def _no_grasp_reason(polygon: Any, fingers: int, mu: float, margin: float,
                     hand: Hand | None) -> str:
    if fingers == 2 and mu == 0:
        return "two fingers need friction: with mu = 0 no two-finger grasp is force closure"
    base = {2: f"no pair of edges admits two fingers with mu = {mu:g}",
            3: "no three edges hold the part against gravity with frictionless fingers",
            4: "no four edges (or three, two fingers on one) admit frictionless fingers"}[fingers]
    extra = f" with a margin of {margin:g} degrees"
    if hand is not None:
        extra += " within the hand's reach"
    return base + extra


# ----------------------------------------------------------------------------- commands


def cmd_plan(args: Any) -> int:
    # every option is checked before any work or output (--flatten and --id by read_part,
    # before it reads anything)
    _check_outputs(args, [args.part])
    if args.mu < 0 or not np.isfinite(args.mu):
        raise CliError(f"--mu must be a finite number >= 0, got {args.mu:g}")
    if not 0 <= args.margin < 90:
        raise CliError(f"--margin is an angle in degrees in [0, 90), got {args.margin:g}")
    if args.top < 1:
        raise CliError(f"--top must be at least 1, got {args.top}")
    hand = ws = None
    if args.workspace is not None or args.finger_radius:
        ws = _floats(args.workspace, 3, "--workspace") if args.workspace else None
        if ws is not None and ws[2] <= 0:
            raise CliError(f"--workspace radius must be > 0, got {ws[2]:g}")
        if not (np.isfinite(args.finger_radius) and args.finger_radius >= 0):
            raise CliError(f"--finger-radius must be a finite number >= 0, got "
                           f"{args.finger_radius:g}")
        hand = Hand(workspace=ws, finger_radius=args.finger_radius)
    polygon = read_part(args.part, args.id, args.flatten)
    if hand is not None:
        reach = hand.feasible_intervals(polygon)
        if not any(reach):
            where = f"workspace {ws}" if ws else f"finger radius {args.finger_radius:g}"
            raise CliError(f"the hand cannot touch the part: no edge is reachable with the "
                           f"{where}")
    show = _progress(sys.stderr.isatty() and not args.quiet)
    plans = plan(polygon, fingers=args.fingers, mu=args.mu, top=args.top, rank_by=args.rank_by,
                 hand=hand, margin=args.margin, disturbance=(UNITS[args.units], 15.0),
                 progress=show)
    params = {"fingers": args.fingers, "mu": args.mu, "top": args.top, "rank_by": args.rank_by,
              "margin_deg": args.margin,
              "workspace": None if hand is None or hand.workspace is None else
              list(hand.workspace),
              "finger_radius": args.finger_radius,
              "disturbance": {"translation": UNITS[args.units], "rotation_deg": 15.0}}
    reason = None if plans else _no_grasp_reason(polygon, args.fingers, args.mu, args.margin,
                                                 hand)
    report = plan_report(polygon, plans, params, args.units, reason)
    _write_outputs(polygon, plans, report, args, f"{args.part}: {args.fingers} fingers")
    if not args.quiet:
        if plans:
            _print_table(plans, args.units, sys.stdout)
        else:
            print(f"no grasp: {reason}")
    return 0


def cmd_check(args: Any) -> int:
    _check_outputs(args, [args.part, args.contacts])
    polygon = read_part(args.part, args.id, args.flatten)
    contacts, described = read_contacts(args.contacts, polygon)
    grasp = Grasp(contacts)
    rep = grasp.explain()
    free = grasp.total_freedom()
    result = check_report(polygon, described, rep, free, args.units)
    with OutputSet() as out:
        if args.json:
            out.add_text(args.json, dumps(result))
        if args.plot:
            from .plotting import grasp_figure

            grasp_figure(polygon, grasp, args.plot, units=args.units, outputs=out)
    if not args.quiet:
        print(str(rep))
        if not rep.force_closure:
            print(f"total freedom: {len(free.lines)} free motion(s), {len(free.rays)} unisense "
                  f"motion(s) (twists (omega, vx, vy))")
            for line in free.lines:
                print(f"  free      {np.round(line, 6).tolist()}")
            for ray in free.rays:
                print(f"  unisense  {np.round(ray, 6).tolist()}")
        else:
            print("total freedom: none (the twist convexe is null)")
    return 0


def cmd_demo(args: Any) -> int:
    out = Path(args.out)
    if out.exists() and not out.is_dir():
        raise CliError(f"--out {out} exists and is not a folder")
    out.mkdir(parents=True, exist_ok=True)
    from .plotting import plan_figure

    jobs = [("blob", 2, 0.3, "figure 1.a: two fingers with friction"),
            ("triangle", 4, 0.0, "figure 1.b: four frictionless fingers on three edges"),
            ("quad", 4, 0.0, "figure 1.c: four frictionless fingers on four edges"),
            ("triangle", 3, 0.0, "three frictionless fingers and gravity"),
            ("washer", 2, 0.2, "two fingers with friction on a part with a hole")]
    entries: list[dict[str, Any]] = []
    for name, fingers, mu, title in jobs:
        polygon = demo_part(name)
        plans = plan(polygon, fingers=fingers, mu=mu, top=6, margin=DEFAULT_MARGIN_DEG)
        params = {"fingers": fingers, "mu": mu, "top": 6, "rank_by": "min_region",
                  "margin_deg": DEFAULT_MARGIN_DEG, "workspace": None, "finger_radius": 0.0,
                  "disturbance": {"translation": 10.0, "rotation_deg": 15.0}}
        reason = None if plans else _no_grasp_reason(polygon, fingers, mu, DEFAULT_MARGIN_DEG,
                                                     None)
        stem = f"{name}-{fingers}f"
        with OutputSet() as files:
            files.add_text(out / f"{stem}.json",
                           dumps(plan_report(polygon, plans, params, "mm", reason)))
            plan_figure(polygon, plans, str(out / f"{stem}.png"), units="mm",
                        title=f"demo:{name} - {title}", outputs=files)
        best = plans[0] if plans else None
        entries.append({"part": f"demo:{name}", "fingers": fingers, "mu": mu,
                                 "json": f"{stem}.json", "figure": f"{stem}.png",
                                 "best_edges": None if best is None else list(best.edges),
                                 "best_min_region": None if best is None else best.min_length})
        if not args.quiet:
            if best is None:
                print(f"demo:{name:9s} {fingers} fingers  no grasp: {reason}")
            else:
                print(f"demo:{name:9s} {fingers} fingers  best edges {list(best.edges)!s:16s} "
                      f"min region {best.min_length:7.3f} mm  -> {out / stem}.png")
    with OutputSet() as files:
        files.add_text(out / "demo.json", dumps(demo_summary(entries, "mm")))
    if not args.quiet:
        print(f"wrote {len(jobs)} plans (JSON and PNG) and {out / 'demo.json'}")
    return 0


# ----------------------------------------------------------------------------- parser


def build_parser() -> argparse.ArgumentParser:
    parser = _Parser(prog="fcgrasp",
                     description="Force-closure grasps of planar parts (Nguyen's synthesis): "
                                 "where to put the fingers, with independent regions of "
                                 "contact.",
                     epilog="examples:\n  fcgrasp demo --out demo-output\n"
                            "  fcgrasp plan part.svg --fingers 2 --mu 0.3 --json plan.json "
                            "--plot plan.png\n  fcgrasp check part.json --contacts grasp.json",
                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--version", action="version", version=f"fcgrasp {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", parser_class=_Parser)

    def part_args(p: argparse.ArgumentParser) -> None:
        p.add_argument("part", metavar="PART",
                       help="part file (.json, .geojson, .wkt, .svg, .dxf, .png) or demo:NAME "
                            f"({', '.join(DEMO_PARTS)})")
        p.add_argument("--id", help="SVG element id, or DXF entity handle or layer")
        p.add_argument("--flatten", type=float, default=None, metavar="TOL",
                       help="curve flattening tolerance (SVG, DXF) or pixels (images)")
        p.add_argument("--units", choices=sorted(UNITS), default="mm",
                       help="units of the coordinates (default mm)")
        p.add_argument("--json", metavar="OUT.json", help="write the result as JSON")
        p.add_argument("--quiet", action="store_true", help="print nothing on success")

    p = sub.add_parser("plan", help="ranked grasp plans of a part",
                       description="Plan force-closure grasps: the best edge sets with their "
                                   "independent regions of contact.",
                       epilog="example:\n  fcgrasp plan demo:blob --fingers 2 --mu 0.3 --top 5 "
                              "--json plan.json --plot plan.png",
                       formatter_class=argparse.RawDescriptionHelpFormatter)
    part_args(p)
    p.add_argument("--fingers", type=int, choices=(2, 3, 4), default=2,
                   help="2: with friction; 4: frictionless; 3: frictionless with gravity")
    p.add_argument("--mu", type=float, default=0.3, help="friction coefficient (default 0.3)")
    p.add_argument("--top", type=int, default=10, help="how many plans (default 10)")
    p.add_argument("--rank-by", choices=tuple(MEASURES), default="min_region",
                   help="ranking measure (see fcgrasp.ranking)")
    p.add_argument("--margin", type=float, default=DEFAULT_MARGIN_DEG, metavar="DEG",
                   help=f"safety margin in degrees (default {DEFAULT_MARGIN_DEG})")
    p.add_argument("--workspace", metavar="CX,CY,R", help="circular workspace of the fingertips")
    p.add_argument("--finger-radius", type=float, default=0.0, metavar="R",
                   help="fingertip radius (default 0)")
    p.add_argument("--plot", metavar="OUT.png|OUT.svg|OUT.pdf", help="write a figure")
    p.set_defaults(func=cmd_plan)

    c = sub.add_parser("check", help="the verdict for a given grasp",
                       description="Is this grasp force closure? If not, why, and how does "
                                   "the part escape?",
                       epilog='example:\n  fcgrasp check demo:rectangle --contacts grasp.json\n'
                              'with grasp.json = {"contacts": [{"point": [0, 15], "mu": 0.3}, '
                              '{"point": [80, 15], "mu": 0.3}]}',
                       formatter_class=argparse.RawDescriptionHelpFormatter)
    part_args(c)
    c.add_argument("--contacts", required=True, metavar="CONTACTS.json",
                   help="contacts: point, and per contact its type and mu")
    c.add_argument("--plot", metavar="OUT.png|OUT.svg|OUT.pdf",
                   help="draw the part, the contact forces and the escape motion")
    c.set_defaults(func=cmd_check)

    d = sub.add_parser("demo", help="plans for the built-in parts, JSON and figures",
                       description="The main job on built-in parts (the paper's figure 1): "
                                   "plans written as JSON and figures into a folder.",
                       epilog="example:\n  fcgrasp demo --out demo-output",
                       formatter_class=argparse.RawDescriptionHelpFormatter)
    d.add_argument("--out", default="demo-output", help="output folder (default demo-output)")
    d.add_argument("--quiet", action="store_true", help="print nothing on success")
    d.set_defaults(func=cmd_demo)
    return parser


def main(argv: list[str] | None = None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    if not getattr(args, "func", None):
        parser.print_help()
        return EXIT_USAGE
    try:
        return int(args.func(args))
    except (CliError, ValueError, TypeError) as exc:
        msg = " ".join(str(exc).split())
        print(f"fcgrasp: error: {msg}", file=sys.stderr)
        return EXIT_USAGE
    except OSError as exc:
        print(f"fcgrasp: error: {exc.filename or ''}: {exc.strerror or exc}".replace(": :", ":"),
              file=sys.stderr)
        return EXIT_USAGE
    except KeyboardInterrupt:
        print("fcgrasp: interrupted", file=sys.stderr)
        return 130
    except Exception as exc:  # noqa: BLE001 - the promise is: never a traceback
        print(f"fcgrasp: internal error: {type(exc).__name__}: {' '.join(str(exc).split())}",
              file=sys.stderr)
        return EXIT_INTERNAL


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
