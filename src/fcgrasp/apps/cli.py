"""The ``fcgrasp`` command (a leaf: nothing in the core imports it).

Sub-commands: ``plan`` (ranked grasp plans of a part file), ``check`` (the verdict for a
given grasp), ``parts`` (the parts a file holds) and ``demo`` (the main job on built-in
parts).  Exit codes: 0 success; 1 ``check`` found the grasp is not force closure; 2 bad
input or options (one line on stderr, never a traceback); 3 an internal error.  Output
files are written atomically (temporary file, then rename), so a failed run leaves none;
``-`` reads the part from standard input, and ``--json -`` writes the JSON on standard
output.
"""

from __future__ import annotations

import argparse
import os
import sys
from dataclasses import dataclass
from pathlib import Path
from typing import Any, NoReturn

from .. import __version__

EXIT_NOT_CLOSURE = 1
EXIT_USAGE = 2
EXIT_INTERNAL = 3
#: Units a part can be read in (``--units``); see :mod:`fcgrasp.io.units`.
UNIT_CHOICES = ("mm", "cm", "m", "in")


class CliError(Exception):
    """An error reported as one line on stderr with exit code 2."""


class _Parser(argparse.ArgumentParser):
    def error(self, message: str) -> NoReturn:
        print(f"fcgrasp: error: {message} (see fcgrasp --help)", file=sys.stderr)
        raise SystemExit(EXIT_USAGE)


# ----------------------------------------------------------------------------- helpers


def _floats(text: str, n: int, name: str) -> tuple[float, ...]:
    import math

    parts = [t for t in text.replace(" ", "").split(",") if t]
    try:
        vals = tuple(float(t) for t in parts)
    except ValueError:
        raise CliError(f"{name} must be {n} comma-separated numbers, got {text!r}") from None
    if len(vals) != n or not all(math.isfinite(v) for v in vals):
        raise CliError(f"{name} must be {n} comma-separated finite numbers, got {text!r}")
    return vals


_SIZES = {"": 1, "b": 1, "k": 2 ** 10, "kb": 2 ** 10, "m": 2 ** 20, "mb": 2 ** 20,
          "g": 2 ** 30, "gb": 2 ** 30, "t": 2 ** 40, "tb": 2 ** 40}


def _memory(text: str) -> int:
    """A memory size: bytes, or a number with K, M, G or T (powers of 1024)."""
    t = text.strip().lower().replace("i", "")
    num = t.rstrip("kmgtb")
    unit = t[len(num):]
    try:
        value = float(num)
    except ValueError:
        value = float("nan")
    if unit not in _SIZES or not value > 0 or value == float("inf"):
        raise CliError(f"--max-memory must be a size such as 500M or 2G, got {text!r}")
    return int(value * _SIZES[unit])


def _duration(seconds: float) -> str:
    if seconds < 120:
        return f"{seconds:.0f} s"
    if seconds < 7200:
        return f"{seconds / 60:.0f} min"
    if seconds < 2 * 86400:
        return f"{seconds / 3600:.1f} h"
    return f"{seconds / 86400:.0f} days"


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
    if sum(1 for src in inputs if src == "-") > 1:
        raise CliError("only one input can be read from standard input ('-')")
    outs = [(f"--{k}", getattr(args, k)) for k in ("json", "plot") if getattr(args, k, None)]
    for opt, path in outs:
        if path == "-" and opt == "--json":
            continue
        if path == "-" or path.endswith(os.sep) or os.path.isdir(path):
            raise CliError(f"{opt} must be a file name, got {path!r}")
        for src in inputs:
            if not src.startswith("demo:") and src != "-" and _same_file(path, src):
                raise CliError(f"{opt} {path} is an input of this run: refusing to "
                               f"overwrite it")
    if len(outs) == 2 and outs[0][1] != "-" and _same_file(outs[0][1], outs[1][1]):
        raise CliError(f"--json and --plot name the same file {outs[0][1]!r}")
    plot = getattr(args, "plot", None)
    if plot:
        if Path(plot).suffix.lower() not in (".png", ".svg", ".pdf"):
            raise CliError(f"--plot must end in .png, .svg or .pdf, got {plot!r}")
        try:
            import matplotlib  # noqa: F401
        except ImportError:
            raise CliError("--plot needs matplotlib: pip install 'fcgrasp[plot]'") from None


def _reading(args: Any) -> dict[str, Any]:
    """The reading options of the command line, as :func:`fcgrasp.io.parts.list_parts`
    keywords."""
    return {"units": args.units, "file_units": args.file_units, "flatten": args.flatten,
            "layer": args.layer, "gap": args.gap, "pixel_size": args.pixel_size,
            "threshold": args.threshold, "y_down": args.y_down, "clean": not args.no_clean,
            "simplify": args.simplify}


def _load(args: Any, say: Any = "stderr") -> Any:
    """The part asked for; when the file holds several, which one was taken is said with
    ``say`` (default on stderr unless --quiet; None: nowhere)."""
    from ..io.parts import load_part

    part = load_part(args.part, args.select, **_reading(args))
    if say == "stderr":
        say = None if args.quiet else _stderr
    if say is not None:
        if part.count > 1:
            name = f" ({part.id})" if part.id else ""
            say(f"fcgrasp: {part.source}: took part {part.index}{name}, {part.chosen} "
                f"(see fcgrasp parts)")
        for note in part.notes:
            say(f"fcgrasp: {part.source}: {note}")
    return part


def _json_out(args: Any) -> bool:
    return getattr(args, "json", None) == "-"


def _write_outputs(outputs: list[tuple[str, str]], figure: Any = None) -> None:
    """Write text outputs (``-``: standard output) and an optional figure as a set."""
    from ..io._atomic import OutputSet

    stdout = [text for path, text in outputs if path == "-"]
    with OutputSet() as out:
        for path, text in outputs:
            if path != "-":
                out.add_text(path, text)
        if figure is not None:
            figure(out)
    for text in stdout:
        sys.stdout.write(text)
        sys.stdout.flush()


def _print_table(plans: list[Any], units: str, out: Any) -> None:
    if not plans:
        return
    print(f"{'rank':>4}  {'edges':<20} {'min region':>11}  {'regions (' + units + ')':<24} "
          f"{'resistance':>10} {'eps L1':>8}", file=out)
    for k, p in enumerate(plans):
        q = p.quality
        regs = ", ".join(f"{x:.3g}" for x in p.lengths)
        # a region along the boundary shows the edges it covers, first-last
        edges = " ".join(str(r[0]) if len(r) == 1 else f"{r[0]}-{r[-1]}"
                         for r in p.region_edges)
        print(f"{k + 1:>4}  {edges:<20} {p.min_length:>11.4g}  {regs:<24} "
              f"{q['resistance']:>10.4g} {q['epsilon_l1']:>8.4g}", file=out)


def _no_grasp_reason(fingers: int, mu: float, margin: float, hand: Any,
                     gravity: Any = None) -> str:
    if fingers == 2 and mu == 0:
        return "two fingers need friction: with mu = 0 no two-finger grasp is force closure"
    base = {2: f"no pair of edges admits two fingers with mu = {mu:g}",
            3: f"no three edges admit three fingers with mu = {mu:g}" if gravity is None
            else "no three edges hold the part against gravity with frictionless fingers",
            4: "no four edges (or three, two fingers on one) admit frictionless fingers"}[fingers]
    extra = f" with a margin of {margin:g} degrees"
    if hand is not None:
        extra += " within the hand's reach"
    return base + extra


# ----------------------------------------------------------------------------- commands


@dataclass
class PlanDocument:
    """What ``fcgrasp plan`` computes for one part: the report written by ``--json``,
    the plans, the part's polygon and units, and a title for its figure."""

    report: dict[str, Any]
    plans: list[Any]
    polygon: Any
    units: str
    reason: str | None
    title: str


def _finger_options(args: Any) -> tuple[Any, ...]:
    """The point-finger options of ``fcgrasp plan``, checked and resolved:
    ``(fingers, mu, gravity, max_memory, hand, workspace)``."""
    import math

    from ..model.hand import Hand

    for opt, value in (("--stroke", args.stroke), ("--pad", args.pad),
                       ("--certify" if args.certify else "--no-certify", args.certify)):
        if value is not None:
            raise CliError(f"{opt} is an option of --gripper jaw")
    fingers = 2 if args.fingers is None else args.fingers
    gravity = None if args.gravity is None else _floats(args.gravity, 2, "--gravity")
    if gravity is not None and fingers != 3:
        raise CliError(f"--gravity is a contact of three frictionless fingers, not of "
                       f"{fingers} (drop it, or use --fingers 3)")
    frictionless = fingers == 4 or gravity is not None
    mu = args.mu
    if mu is None:
        mu = 0.0 if frictionless else 0.3
    elif frictionless and mu != 0:
        what = "four fingers" if fingers == 4 else "three fingers with --gravity"
        raise CliError(f"--mu {mu:g} would not be used: {what} are planned frictionless "
                       f"(drop --mu)")
    if mu < 0 or not math.isfinite(mu):
        raise CliError(f"--mu must be a finite number >= 0, got {mu:g}")
    _check_margin_top(args)
    budget = None if args.max_memory is None else _memory(args.max_memory)
    hand = ws = None
    if args.workspace is not None or args.finger_radius:
        ws = _floats(args.workspace, 3, "--workspace") if args.workspace else None
        if ws is not None and ws[2] <= 0:
            raise CliError(f"--workspace radius must be > 0, got {ws[2]:g}")
        if not (math.isfinite(args.finger_radius) and args.finger_radius >= 0):
            raise CliError(f"--finger-radius must be a finite number >= 0, got "
                           f"{args.finger_radius:g}")
        hand = Hand(workspace=ws, finger_radius=args.finger_radius)
    return fingers, mu, gravity, budget, hand, ws


def plan_document(args: Any, part: Any = None, progress: Any = None,
                  say: Any = None, map: Any = None) -> PlanDocument:
    """Plan one part as ``fcgrasp plan`` does: ``args`` are its parsed options (see
    :func:`build_parser`), ``part`` a :class:`fcgrasp.io.parts.Part` already read (default:
    read ``args.part``), ``progress(done, total)`` a progress callback and ``say(text)``
    where notes go (default nowhere), ``map`` where candidate batches are solved (see
    :func:`fcgrasp.plan`).  Raises :class:`CliError` (a one-line message) for
    options that do not fit together.  ``fcgrasp batch`` calls it for every part, so a
    batch's results are exactly those of ``plan --json``."""
    from ..io.report import plan_report
    from ..io.units import disturbance_step
    from ..pipeline import check_search, plan_spec
    from ..planning.planner import plan

    if args.gripper == "jaw":
        return _plan_jaw(args, part)
    fingers, mu, gravity, budget, hand, ws = _finger_options(args)
    part = _load(args, say) if part is None else part
    polygon, units = part.polygon, part.units
    if hand is not None:
        reach = hand.feasible_intervals(polygon)
        if not any(reach):
            where = f"workspace {ws}" if ws else f"finger radius {args.finger_radius:g}"
            raise CliError(f"the hand cannot touch the part: no edge is reachable with the "
                           f"{where}")
    step = disturbance_step(units)
    kw: dict[str, Any] = {"along_boundary": not args.single_edge, "gravity": gravity}
    if budget is not None:
        kw["max_memory"] = budget
    spec = plan_spec(fingers=fingers, mu=mu, top=args.top, rank_by=args.rank_by,
                     hand=hand, margin=args.margin, disturbance=(step, 15.0), **kw)
    size = check_search(polygon, spec)          # too large: a one-line error, at once
    # with a top and the smallest region, the exact pruning stops far sooner than
    # solving every candidate (seconds where this estimate says hours)
    pruned = spec.top is not None and spec.rank_by == "min_region"
    if size.seconds > 60 and say is not None and not pruned:
        say(f"fcgrasp: {size.rows:.3g} candidate edge sets on {size.features} edges: about "
            f"{_duration(size.seconds)} (--simplify TOL or fewer fingers is faster)")
    plans = plan(polygon, fingers=fingers, mu=mu, top=args.top, rank_by=args.rank_by,
                 hand=hand, margin=args.margin, disturbance=(step, 15.0), progress=progress,
                 map=map, **kw)
    params = {"fingers": fingers, "mu": mu, "top": args.top, "rank_by": args.rank_by,
              "margin_deg": args.margin, "along_boundary": spec.stretches or spec.grows,
              "gravity": None if gravity is None else list(gravity),
              "workspace": None if hand is None or hand.workspace is None else
              list(hand.workspace),
              "finger_radius": args.finger_radius,
              "disturbance": {"translation": step, "rotation_deg": 15.0}}
    reason = None if plans else _no_grasp_reason(fingers, mu, args.margin, hand, gravity)
    report = plan_report(polygon, plans, params, units, reason, source=part.to_dict())
    return PlanDocument(report, plans, polygon, units, reason,
                        f"{args.part}: {fingers} fingers")


def cmd_plan(args: Any) -> int:
    from ..io.report import dumps

    # every option is checked before any work or output
    _check_outputs(args, [args.part])
    say = None if args.quiet else _stderr
    doc = plan_document(args, progress=_progress(sys.stderr.isatty() and not args.quiet),
                        say=say)

    def figure(out: Any) -> None:
        from ..plotting import plan_figure

        plan_figure(doc.polygon, doc.plans, args.plot, units=doc.units, title=doc.title,
                    outputs=out)

    _write_outputs([(args.json, dumps(doc.report))] if args.json else [],
                   figure if args.plot else None)
    if not args.quiet and not _json_out(args):
        if not doc.plans:
            print(f"no grasp: {doc.reason}")
        elif args.gripper == "jaw":
            _print_jaw_table(doc.plans, doc.units, sys.stdout)
        else:
            _print_table(doc.plans, doc.units, sys.stdout)
    return 0


def _stderr(text: str) -> None:
    print(text, file=sys.stderr)


def _check_margin_top(args: Any) -> None:
    if not 0 <= args.margin < 90:
        raise CliError(f"--margin is an angle in degrees in [0, 90), got {args.margin:g}")
    if args.top < 1:
        raise CliError(f"--top must be at least 1, got {args.top}")


def _jaw_options(args: Any) -> Any:
    """The :class:`~fcgrasp.ParallelJaw` of ``fcgrasp plan --gripper jaw``, its options
    checked (none of the point fingers' given)."""
    import math

    from ..grippers.jaw import ParallelJaw

    for opt, given in (("--fingers", args.fingers is not None),
                       ("--gravity", args.gravity is not None),
                       ("--workspace", args.workspace is not None),
                       ("--finger-radius", bool(args.finger_radius)),
                       ("--rank-by", args.rank_by != "min_region"),
                       ("--single-edge", args.single_edge)):
        if given:
            raise CliError(f"{opt} is an option of point fingers, not of --gripper jaw")
    if args.stroke is None or args.pad is None:
        raise CliError("--gripper jaw needs --stroke MIN,MAX and --pad WIDTH (in the part's "
                       "units)")
    stroke = _floats(args.stroke, 2, "--stroke")
    mu = 0.3 if args.mu is None else args.mu
    if not (math.isfinite(mu) and mu > 0):
        raise CliError(f"--mu of a parallel jaw must be a finite number > 0, got {mu:g}")
    _check_margin_top(args)
    return ParallelJaw(stroke=(stroke[0], stroke[1]), pad_width=args.pad, mu=mu)


def _plan_jaw(args: Any, part: Any = None) -> PlanDocument:
    """``fcgrasp plan --gripper jaw``: boxes of parallel-jaw poses (:mod:`fcgrasp.grippers.jaw`)."""
    from ..grippers.jaw import jaw_plans
    from ..io.report import plan_report

    jaw = _jaw_options(args)
    part = _load(args) if part is None else part
    polygon, units = part.polygon, part.units
    certify = args.certify is not False
    plans = jaw_plans(polygon, jaw, top=args.top, margin=args.margin, certify=certify)
    params = {"gripper": "parallel_jaw", "stroke": list(jaw.stroke),
              "pad_width": jaw.pad_width, "mu": jaw.mu, "top": args.top,
              "margin_deg": args.margin, "certify": certify}
    reason = None if plans else (
        f"no pose of the jaw holds the part (stroke {jaw.stroke[0]:g} to {jaw.stroke[1]:g}, "
        f"pads {jaw.pad_width:g} wide, mu = {jaw.mu:g}, margin {args.margin:g} degrees)")
    report = plan_report(polygon, plans, params, units, reason, source=part.to_dict())
    return PlanDocument(report, plans, polygon, units, reason, f"{args.part}: parallel jaw")


def _print_jaw_table(plans: list[Any], units: str, out: Any) -> None:
    import math

    print(f"{'rank':>4}  {'grip':<9} {'closing (deg)':<16} {'offset (' + units + ')':<20} "
          f"{'opening (' + units + ')':<18} {'contacts':<16} {'measure':>8}", file=out)
    for k, p in enumerate(plans):
        t = [math.degrees(x) for x in p.theta]
        print(f"{k + 1:>4}  {p.mode:<9} {t[0]:6.1f} to {t[1]:<6.1f} "
              f"{p.offset[0]:7.3g} to {p.offset[1]:<7.3g} "
              f"{p.opening[0]:6.3g} to {p.opening[1]:<6.3g} "
              f"{p.kinds[0] + '/' + p.kinds[1]:<16} {p.measure:8.3g}", file=out)


#: The options of ``fcgrasp plan`` that ``fcgrasp batch`` passes on to every part.
PLAN_DESTS = ("gripper", "stroke", "pad", "fingers", "mu", "gravity", "top", "single_edge",
              "rank_by", "margin", "workspace", "finger_radius", "max_memory", "select",
              "units", "file_units", "flatten", "layer", "gap", "pixel_size", "threshold",
              "y_down", "simplify", "no_clean")


def cmd_batch(args: Any) -> int:
    from .batch import part_files, run_batch

    if args.workers is not None and args.workers < 1:
        raise CliError(f"--workers must be at least 1, got {args.workers}")
    if args.part_timeout is not None and not args.part_timeout > 0:
        raise CliError(f"--part-timeout must be a number of seconds > 0, got "
                       f"{args.part_timeout:g}")
    paths = part_files(args.input)
    if not paths:
        raise CliError(f"no part files in {args.input!r} (a folder of .json, .svg, .dxf, "
                       f"image ... files, or a glob pattern)")
    if os.path.isdir(args.out):
        raise CliError(f"--out {args.out} is a folder, not a results file")
    options = {d: getattr(args, d) for d in PLAN_DESTS}
    # the options are checked once, on the first part's terms, before any work
    plan_document_check(options)
    client = None
    workers = args.workers or os.cpu_count() or 1
    if args.scheduler is not None:
        from .batch import cluster

        client = cluster(args.scheduler, workers)
    show = _batch_progress(sys.stderr.isatty() and not args.quiet)
    try:
        summary = run_batch(paths, args.out, workers=workers, client=client,
                            part_timeout=args.part_timeout, figures=args.figures,
                            progress=show, retry_failed=args.retry_failed, **options)
    finally:
        if client is not None:
            client.close()
            cluster_of = getattr(client, "cluster", None)
            if cluster_of is not None:
                cluster_of.close()
    if not args.quiet:
        print(summary.table())
    return 1 if summary.failed or summary.failed_before else 0


def plan_document_check(options: dict[str, Any]) -> None:
    """Check ``fcgrasp plan`` options (as :data:`PLAN_DESTS` keywords) without planning:
    a :class:`CliError` for options that do not fit together."""
    from .batch import plan_options

    args = build_parser().parse_args(["plan", "demo:quad", *plan_options(**options)])
    if args.gripper == "jaw":
        _jaw_options(args)
    else:
        _finger_options(args)


def _batch_progress(enabled: bool) -> Any:
    if not enabled:
        return None
    import time

    t0 = time.perf_counter()

    def show(done: int, total: int) -> None:
        width = 30
        frac = done / max(total, 1)
        el = time.perf_counter() - t0
        rate = done / el if el > 0 else 0.0
        left = (total - done) / rate if rate > 0 else float("nan")
        eta = _duration(left) if left == left else "?"
        print(f"\r[{'#' * int(width * frac):<{width}}] {done}/{total} parts, "
              f"{rate:.2f}/s, {eta} left   ", end="", file=sys.stderr, flush=True)
        if done >= total:
            print("", file=sys.stderr)

    return show


def cmd_check(args: Any) -> int:
    import numpy as np

    from ..core.grasp import Grasp
    from ..io.parts import read_contacts
    from ..io.report import check_report, dumps

    _check_outputs(args, [args.part, args.contacts])
    part = _load(args)
    polygon = part.polygon
    contacts, described = read_contacts(args.contacts, polygon)
    grasp = Grasp(contacts)
    rep = grasp.explain()
    free = grasp.total_freedom()
    result = check_report(polygon, described, rep, free, part.units, source=part.to_dict())

    def figure(out: Any) -> None:
        from ..plotting import grasp_figure

        grasp_figure(polygon, grasp, args.plot, units=part.units, outputs=out)

    _write_outputs([(args.json, dumps(result))] if args.json else [],
                   figure if args.plot else None)
    if not args.quiet and not _json_out(args):
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
    return 0 if rep.force_closure else EXIT_NOT_CLOSURE


def cmd_parts(args: Any) -> int:
    from ..io.parts import choose_part, list_parts
    from ..io.report import dumps, parts_report

    _check_outputs(args, [args.part])
    parts = list_parts(args.part, **_reading(args))
    try:
        default = choose_part(parts).index
    except ValueError:
        default = -1
    if args.json:
        _write_outputs([(args.json, dumps(parts_report(parts, default)))])
    if args.quiet or _json_out(args):
        return 0
    units = parts[0].units if parts else ""
    print(f"{parts[0].source}: {len(parts)} part{'s' * (len(parts) != 1)} ({parts[0].format}, "
          f"units {units}: {parts[0].units_note}); * = the default (the largest)")
    print(f"  {'index':>5}  {'id':<18} {'layer':<10} {'edges':>6} {'holes':>5}  "
          f"{'width x height':>22}  {'area':>11}")
    for p in parts:
        mark = "*" if p.index == default else " "
        ident = (p.id or "-")[:18]
        layer = (p.layer or "-")[:10]
        if p.polygon is None:
            print(f"{mark} {p.index:>5}  {ident:<18} {layer:<10} not usable: {p.error}")
            continue
        w, h = p.polygon.vertices.max(axis=0) - p.polygon.vertices.min(axis=0)
        extra = "  (background)" if p.background else ""
        print(f"{mark} {p.index:>5}  {ident:<18} {layer:<10} {p.polygon.n_edges:>6} "
              f"{len(p.polygon.holes):>5}  {f'{w:.4g} x {h:.4g}':>22}  "
              f"{p.polygon.area:>11.4g}{extra}")
    for note in parts[0].notes if parts else ():
        print(f"note: {note}")
    return 0


def cmd_serve(args: Any) -> int:
    import importlib.util

    missing = [m for m in ("starlette", "uvicorn") if importlib.util.find_spec(m) is None]
    if missing:
        raise CliError(f"fcgrasp serve needs {' and '.join(missing)}: pip install "
                       f"'fcgrasp[serve]'")
    if not 0 <= args.port <= 65535:
        raise CliError(f"--port must be from 0 to 65535, got {args.port}")
    from .serve import serve

    part = _load(args, say=_stderr)
    try:
        serve(part, host=args.host, port=args.port, open_browser=args.open,
              announce=lambda text: print(text, flush=True))
    except OSError as exc:
        raise CliError(f"cannot listen on {args.host}:{args.port}: "
                       f"{exc.strerror or exc}") from None
    return 0


def cmd_demo(args: Any) -> int:
    import math

    from ..io._atomic import OutputSet
    from ..io.parts import demo_part
    from ..io.report import demo_summary, dumps, plan_report
    from ..model.regions import DEFAULT_MARGIN_DEG
    from ..planning.planner import plan
    from ..plotting import plan_figure

    out = Path(args.out)
    if out.exists() and not out.is_dir():
        raise CliError(f"--out {out} exists and is not a folder")
    out.mkdir(parents=True, exist_ok=True)
    jobs = [("blob", 2, 0.3, "figure 1.a: two fingers with friction"),
            ("triangle", 4, 0.0, "figure 1.b: four frictionless fingers on three edges"),
            ("quad", 4, 0.0, "figure 1.c: four frictionless fingers on four edges"),
            ("triangle", 3, 0.0, "three frictionless fingers and gravity"),
            ("blob", 3, 0.5, "three fingers with friction"),
            ("washer", 2, 0.2, "two fingers with friction on a part with a hole"),
            ("cam", 2, 0.3, "regions along the boundary of a curved part")]
    entries: list[dict[str, Any]] = []
    for name, fingers, mu, title in jobs:
        polygon = demo_part(name)
        gravity = (0.0, -1.0) if fingers == 3 and mu == 0 else None
        plans = plan(polygon, fingers=fingers, mu=mu, top=6, margin=DEFAULT_MARGIN_DEG,
                     gravity=gravity)
        params = {"fingers": fingers, "mu": mu, "top": 6, "rank_by": "min_region",
                  "gravity": None if gravity is None else list(gravity),
                  "margin_deg": DEFAULT_MARGIN_DEG, "workspace": None, "finger_radius": 0.0,
                  "disturbance": {"translation": 10.0, "rotation_deg": 15.0}}
        reason = None if plans else _no_grasp_reason(fingers, mu, DEFAULT_MARGIN_DEG, None,
                                                     gravity)
        stem = f"{name}-{fingers}f" + ("g" if gravity is not None else "")
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
    # a parallel-jaw gripper: boxes of jaw poses (closing angle, offset) that hold
    from ..grippers.jaw import ParallelJaw

    jaw = ParallelJaw(stroke=(10.0, 50.0), pad_width=8.0, mu=0.5)
    polygon = demo_part("rectangle")
    boxes = plan(polygon, gripper=jaw, top=3, margin=DEFAULT_MARGIN_DEG)
    params = {"gripper": "parallel_jaw", "stroke": list(jaw.stroke),
              "pad_width": jaw.pad_width, "mu": jaw.mu, "top": 3,
              "margin_deg": DEFAULT_MARGIN_DEG}
    with OutputSet() as files:
        files.add_text(out / "rectangle-jaw.json",
                       dumps(plan_report(polygon, boxes, params, "mm", "no pose holds")))
        plan_figure(polygon, boxes, str(out / "rectangle-jaw.png"), units="mm",
                    title="demo:rectangle - a parallel jaw (stroke 10-50 mm, 8 mm pads, "
                          "mu 0.5)", outputs=files)
    best_box = boxes[0] if boxes else None
    entries.append({"part": "demo:rectangle", "gripper": "parallel_jaw", "mu": jaw.mu,
                    "json": "rectangle-jaw.json", "figure": "rectangle-jaw.png",
                    "best_theta_deg": None if best_box is None else
                    [math.degrees(x) for x in best_box.theta],
                    "best_offset": None if best_box is None else list(best_box.offset),
                    "best_measure": None if best_box is None else best_box.measure})
    if not args.quiet and best_box is not None:
        t0, t1 = (math.degrees(x) for x in best_box.theta)
        print(f"demo:rectangle jaw        closing {t0:.1f}-{t1:.1f} deg, offsets "
              f"{best_box.offset[0]:.1f}-{best_box.offset[1]:.1f} mm  -> "
              f"{out / 'rectangle-jaw'}.png")
    with OutputSet() as files:
        files.add_text(out / "demo.json", dumps(demo_summary(entries, "mm")))
    if not args.quiet:
        print(f"wrote {len(entries)} plans (JSON and PNG) and {out / 'demo.json'}")
    return 0


# ----------------------------------------------------------------------------- parser


def build_parser() -> argparse.ArgumentParser:
    from ..io.parts import DEMO_PARTS
    from ..io.units import FILE_UNITS
    from ..model.ranking import MEASURES
    from ..model.regions import DEFAULT_MARGIN_DEG

    parser = _Parser(prog="fcgrasp",
                     description="Force-closure grasps of planar parts (Nguyen's synthesis): "
                                 "where to put the fingers, with independent regions of "
                                 "contact.",
                     epilog="exit codes: 0 success, 1 check: not force closure, 2 bad input "
                            "or options, 3 internal error\n\nexamples:\n"
                            "  fcgrasp demo --out demo-output\n"
                            "  fcgrasp parts drawing.dxf\n"
                            "  fcgrasp plan part.svg --fingers 2 --mu 0.3 --json plan.json "
                            "--plot plan.png\n  fcgrasp check part.json --contacts grasp.json",
                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--version", action="version", version=f"fcgrasp {__version__}",
                        help="print the version and exit")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", parser_class=_Parser,
                                help="plan, check, parts or demo (fcgrasp COMMAND --help)")

    def reading_args(p: argparse.ArgumentParser, json_help: str | None) -> None:
        if json_help is not None:
            p.add_argument("part", metavar="PART",
                           help="part file (.json, .geojson, .wkt, .svg, .dxf, .png, .gif, "
                                ".jpg, ...), '-' for standard input, or demo:NAME "
                                f"({', '.join(DEMO_PARTS)})")
        g = p.add_argument_group("reading the part")
        g.add_argument("--part", "--id", dest="select", metavar="N|ID",
                       help="which part of the file: its index (see fcgrasp parts) or an id "
                            "(SVG element or group id, DXF handle or layer, GeoJSON feature "
                            "id or name); default the largest")
        g.add_argument("--units", choices=UNIT_CHOICES, default=None,
                       help="units to read the part in (default mm; an image without "
                            "--pixel-size stays in pixels)")
        g.add_argument("--file-units", choices=FILE_UNITS, default=None, metavar="UNIT",
                       help="units the file is in, overriding what it says (JSON, WKT and "
                            "unitless DXF say nothing: taken as --units)")
        g.add_argument("--flatten", type=float, default=None, metavar="TOL",
                       help="curve flattening tolerance (SVG, DXF) or outline simplification "
                            "(images), in --units (default 1/1000 of each element's size; "
                            "1 pixel for images); curves also turn at most 1 degree per edge")
        g.add_argument("--layer", default=None, help="DXF: only the entities of this layer")
        g.add_argument("--gap", type=float, default=None, metavar="TOL",
                       help="DXF: entity ends closer than this meet (in --units; default "
                            "1e-6 of the drawing's extents)")
        g.add_argument("--pixel-size", type=float, default=None, metavar="SIZE",
                       help="images: size of one pixel in --units")
        g.add_argument("--threshold", type=float, default=None, metavar="GREY",
                       help="images: grey level in (0, 1) between part and background "
                            "(default Otsu's)")
        g.add_argument("--y-down", action="store_true",
                       help="the file's y axis points down (screen coordinates): flip it")
        g.add_argument("--simplify", type=float, default=None, metavar="TOL",
                       help="simplify the outline to within TOL (in --units), topology kept")
        g.add_argument("--no-clean", action="store_true",
                       help="keep collinear runs and sub-tolerance edges as drawn")
        if json_help is None:
            return
        p.add_argument("--json", metavar="OUT.json", help=json_help)
        p.add_argument("--quiet", action="store_true",
                       help="print nothing on success (errors still go to stderr)")

    def planning_args(p: argparse.ArgumentParser) -> None:
        p.add_argument("--gripper", choices=("fingers", "jaw"), default="fingers",
                       help="point fingers (default) or a parallel-jaw gripper (--stroke, --pad, "
                            "--mu)")
        p.add_argument("--stroke", metavar="MIN,MAX", default=None,
                       help="with --gripper jaw: the smallest and largest opening")
        p.add_argument("--pad", type=float, default=None, metavar="WIDTH",
                       help="with --gripper jaw: the width of the flat pads")
        p.add_argument("--certify", action=argparse.BooleanOptionalAction, default=None,
                       help="with --gripper jaw: prove that every pose of each box holds "
                            "(fcgrasp.grippers.jaw.certify_box; the default: boxes it cannot prove "
                            "are dropped); --no-certify: boxes verified on a fine grid only")
        p.add_argument("--fingers", type=int, choices=(2, 3, 4), default=None,
                       help="2 or 3: with friction; 4: frictionless; 3 with --gravity: "
                            "frictionless against gravity")
        p.add_argument("--mu", type=float, default=None,
                       help="friction coefficient (default 0.3; four fingers and --gravity are "
                            "frictionless and take none)")
        p.add_argument("--gravity", metavar="GX,GY", default=None,
                       help="with --fingers 3: three frictionless fingers holding the part "
                            "against gravity in this direction, such as 0,-1")
        p.add_argument("--top", type=int, default=10, help="how many plans (default 10)")
        p.add_argument("--single-edge", action="store_true",
                       help="keep each region on one edge, as in the paper (default: regions "
                            "run along the boundary across vertices; exact for two fingers, "
                            "grown from the single-edge plans for three or four)")
        p.add_argument("--rank-by", choices=tuple(MEASURES), default="min_region",
                       help="ranking measure (see fcgrasp.model.ranking)")
        p.add_argument("--margin", type=float, default=DEFAULT_MARGIN_DEG, metavar="DEG",
                       help=f"safety margin in degrees (default {DEFAULT_MARGIN_DEG})")
        p.add_argument("--workspace", metavar="CX,CY,R",
                       help="circular workspace of the fingertips")
        p.add_argument("--finger-radius", type=float, default=0.0, metavar="R",
                       help="fingertip radius (default 0)")
        p.add_argument("--max-memory", default=None, metavar="SIZE",
                       help="memory budget of the search, such as 500M or 4G (default 2G); a "
                            "search that cannot fit stops at once and says what would")

    p = sub.add_parser("plan", help="ranked grasp plans of a part",
                       description="Plan force-closure grasps: the best edge sets with their "
                                   "independent regions of contact.",
                       epilog="example:\n  fcgrasp plan demo:blob --fingers 2 --mu 0.3 --top 5 "
                              "--json plan.json --plot plan.png",
                       formatter_class=argparse.RawDescriptionHelpFormatter)
    reading_args(p, "write the result as JSON ('-': standard output)")
    planning_args(p)
    p.add_argument("--plot", metavar="OUT.png|OUT.svg|OUT.pdf", help="write a figure")
    p.set_defaults(func=cmd_plan)

    c = sub.add_parser("check", help="the verdict for a given grasp (exit 1: not force "
                                     "closure)",
                       description="Is this grasp force closure? If not, why, and how does "
                                   "the part escape? Exit code 0 when it is, 1 when it is not.",
                       epilog='example:\n  fcgrasp check demo:rectangle --contacts grasp.json\n'
                              'with grasp.json = {"contacts": [{"point": [0, 15], "mu": 0.3}, '
                              '{"point": [80, 15], "mu": 0.3}]}',
                       formatter_class=argparse.RawDescriptionHelpFormatter)
    reading_args(c, "write the verdict as JSON ('-': standard output)")
    c.add_argument("--contacts", required=True, metavar="CONTACTS.json",
                   help="contacts: point, and per contact its type and mu ('-': standard "
                        "input)")
    c.add_argument("--plot", metavar="OUT.png|OUT.svg|OUT.pdf",
                   help="draw the part, the contact forces and the escape motion")
    c.set_defaults(func=cmd_check)

    ls = sub.add_parser("parts", help="the parts a file holds (index, id, layer, size, area)",
                        description="List the parts of a file, as fcgrasp plan would read "
                                    "them; --part N|ID picks one, the default is the "
                                    "largest (marked *).",
                        epilog="example:\n  fcgrasp parts drawing.dxf --units in",
                        formatter_class=argparse.RawDescriptionHelpFormatter)
    reading_args(ls, "write the list as JSON ('-': standard output)")
    ls.set_defaults(func=cmd_parts)

    b = sub.add_parser("batch", help="plan every part of a folder or glob into JSON Lines",
                       description="Plan a catalogue: every part file of a folder (or a glob "
                                   "pattern), one JSON line per part appended to --out as it "
                                   "finishes, with the plans exactly as fcgrasp plan --json "
                                   "gives them. Run it again to finish an interrupted batch: "
                                   "parts already planned with the same content and options "
                                   "are skipped. Exit code 1 when a part of the input has a "
                                   "failed result (now or recorded before).",
                       epilog="examples:\n  fcgrasp batch parts/ --out results.jsonl "
                              "--fingers 2 --mu 0.4 --top 5\n"
                              "  fcgrasp batch 'drawings/**/*.dxf' --out r.jsonl --scheduler "
                              "tcp://10.0.0.5:8786",
                       formatter_class=argparse.RawDescriptionHelpFormatter)
    b.add_argument("input", metavar="INPUT_DIR_OR_GLOB",
                   help="a folder (its part files) or a glob pattern (quote it)")
    b.add_argument("--out", required=True, metavar="RESULTS.jsonl",
                   help="JSON Lines results, appended to (created if missing)")
    b.add_argument("--workers", type=int, default=None, metavar="N",
                   help="worker processes (default: one per core; with --scheduler local, "
                        "the local cluster's workers)")
    b.add_argument("--scheduler", default=None, metavar="ADDRESS",
                   help="run on a Dask cluster: tcp://HOST:PORT, or 'local' for a "
                        "LocalCluster here (needs fcgrasp[distributed])")
    b.add_argument("--part-timeout", type=float, default=None, metavar="SECONDS",
                   help="give up on a part after this long (recorded as failed)")
    b.add_argument("--retry-failed", action="store_true",
                   help="plan again the parts whose recorded result is an error")
    b.add_argument("--figures", default=None, metavar="DIR",
                   help="also write a figure of each part's plans into this folder")
    b.add_argument("--quiet", action="store_true",
                   help="print nothing on success (errors still go to stderr)")
    planning_args(b)
    reading_args(b, None)
    b.set_defaults(func=cmd_batch)

    sv = sub.add_parser("serve", help="the grasp explorer in the browser (fcgrasp[serve])",
                        description="Start the grasp explorer, a local web app: edit the part, "
                                    "pick the gripper, read the ranked plans drawn as in "
                                    "figure 1, place fingers by hand and see the verdict and "
                                    "the escape motion. Needs the extra fcgrasp[serve].",
                        epilog="example:\n  fcgrasp serve demo:blob --port 8000   # then open "
                               "http://127.0.0.1:8000/",
                        formatter_class=argparse.RawDescriptionHelpFormatter)
    sv.add_argument("part", metavar="PART", nargs="?", default="demo:blob",
                    help="the part shown first (any file fcgrasp plan reads; default "
                         "demo:blob)")
    sv.add_argument("--host", default="127.0.0.1",
                    help="address to listen on (default 127.0.0.1: this machine only)")
    sv.add_argument("--port", type=int, default=8000,
                    help="port to listen on (default 8000; 0: any free port)")
    sv.add_argument("--open", action="store_true", help="open the page in a web browser")
    reading_args(sv, None)
    sv.set_defaults(func=cmd_serve)

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
    args_list = sys.argv[1:] if argv is None else list(argv)
    if args_list == ["--version"]:          # answered before anything heavy is imported
        print(f"fcgrasp {__version__}")
        return 0
    try:
        parser = build_parser()
        args = parser.parse_args(args_list)
    except SystemExit as exc:
        return int(exc.code or 0)
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
