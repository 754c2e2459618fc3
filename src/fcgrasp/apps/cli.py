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
import warnings
from pathlib import Path
from typing import Any, NoReturn

from .. import __version__
from ..errors import RequestError as CliError
from ._cli_io import (
    _batch_progress,
    _check_outputs,
    _check_plot,
    _floats,
    _json_out,
    _load,
    _memory,
    _print_jaw_table,
    _print_table,
    _progress,
    _reading,
    _seconds,
    _stderr,
    _write_outputs,
)

EXIT_NOT_CLOSURE = 1
EXIT_USAGE = 2
EXIT_INTERNAL = 3
#: Units a part can be read in (``--units``); see :mod:`fcgrasp.io.units`.
UNIT_CHOICES = ("mm", "cm", "m", "in")


class _Parser(argparse.ArgumentParser):
    def error(self, message: str) -> NoReturn:
        print(f"fcgrasp: error: {message} (see fcgrasp --help)", file=sys.stderr)
        raise SystemExit(EXIT_USAGE)


def plan_options(args: Any) -> dict[str, Any]:
    """The typed planning and reading options of parsed ``plan`` (or ``batch``)
    arguments, as :class:`~fcgrasp.planning.PlanRequest` keywords: ``--stroke 10,50``
    becomes ``stroke=(10.0, 50.0)``, ``--max-memory 2G`` bytes."""
    from ..planning import LOAD_OPTIONS, PLAN_OPTIONS, READING_OPTIONS, SEARCH_OPTIONS

    options: dict[str, Any] = {k: getattr(args, k, None)
                               for k in (*PLAN_OPTIONS, *READING_OPTIONS, *LOAD_OPTIONS,
                                         *SEARCH_OPTIONS)}
    options["soft"] = bool(getattr(args, "soft", False))
    options["repair"] = bool(getattr(args, "repair", False))
    options["mu"], options["mu_high"] = _mu(options["mu"])
    for key, n in (("gravity", 2), ("stroke", 2), ("workspace", 3), ("com", 2),
                   ("accel", 2), ("pose_sigma", 3)):
        if options[key] is not None:
            options[key] = _floats(options[key], n, "--" + key)
    if options["max_memory"] is not None:
        options["max_memory"] = _memory(options["max_memory"])
    if options["max_bytes"] is not None:
        options["max_bytes"] = _memory(options["max_bytes"], "--max-bytes")
    if options["time_limit"] is not None:
        options["time_limit"] = _seconds(options["time_limit"])
    return options


def _mu(text: str | None) -> tuple[float | None, float | None]:
    """``--mu 0.3`` or a range ``--mu 0.3:0.6`` (friction known only to lie in it)."""
    if text is None:
        return None, None
    parts = text.split(":")
    try:
        values = [float(v) for v in parts]
    except ValueError:
        values = []
    if len(values) not in (1, 2) or len(values) != len(parts):
        raise CliError(f"--mu must be a number or a range LOW:HIGH such as 0.3:0.6, got "
                       f"{text!r}")
    return values[0], values[1] if len(values) == 2 else None


def cmd_plan(args: Any) -> int:
    from ..io.report import dumps
    from ..planning import PlanRequest, plan_document

    # every option is checked before any work or output
    request = PlanRequest(part=args.part, json=args.json, plot=args.plot,
                          **plan_options(args))
    _check_plot(args.plot)
    say = None if args.quiet else _stderr
    doc = plan_document(request, progress=_progress(sys.stderr.isatty() and not args.quiet),
                        say=say)

    def figure(out: Any) -> None:
        from ..plotting import document_figure

        document_figure(doc, args.plot, outputs=out)

    _write_outputs([(args.json, dumps(doc.report))] if args.json else [],
                   figure if args.plot else None)
    if not args.quiet and not _json_out(args):
        if not doc.plans:
            print(f"no grasp: {doc.reason}")
        elif request.is_solid():
            _print_solid_table(doc.report, sys.stdout)
        elif args.gripper == "jaw":
            _print_jaw_table(doc.plans, doc.units, sys.stdout)
            _print_load_and_placement(doc.report, sys.stdout)
        else:
            _print_table(doc.plans, doc.units, sys.stdout)
            _print_load_and_placement(doc.report, sys.stdout)
    note = incomplete_note(doc.report)
    if note is not None and not args.quiet:
        print(note, file=sys.stderr if _json_out(args) else sys.stdout)
    return 0


def incomplete_note(report: dict[str, Any]) -> str | None:
    """The line that says a search stopped early (the report's ``gap``), or None.

    >>> print(incomplete_note({"complete": False, "units": "mm", "parameters": {"top": 10},
    ...       "gap": {"stopped_by": "time_limit", "found": 3, "bound": 7.25}}))
    ... # doctest: +NORMALIZE_WHITESPACE
    search stopped at its time limit (--time-limit): 3 of 10 plans proved, exact; every
    further distinct alternative has a smallest region of at most 7.25 mm
    """
    gap = report.get("gap")
    if report.get("complete", True) or gap is None:
        return None
    from ..core.budget import stopped_words

    why = f"at {stopped_words(gap['stopped_by'])}"
    top = report.get("parameters", {}).get("top")
    if not gap.get("exact", True):
        return (f"search stopped {why}: {gap['found']} of {top} plans, each proved to hold; "
                f"a complete search may rank others first")
    rest = "no bound on the rest was proved" if gap["bound"] is None else \
        f"every further distinct alternative has a " \
        f"{gap.get('measure', 'smallest region')} of at most " \
        f"{gap['bound']:.4g} {report.get('units', '')}".rstrip()
    return f"search stopped {why}: {gap['found']} of {top} plans proved, exact; {rest}"


def _print_solid_table(report: dict[str, Any], out: Any) -> None:
    """Two soft fingers, three fingers with friction or a parallel jaw on a solid: one
    line per plan."""
    units = report["units"]
    params = report["parameters"]
    jaw = params.get("contact_type") == "jaw"
    soft = params.get("contact_type") == "soft"
    print(f"rank  facets          radius ({units})" + ("  opening" if jaw else "")
          + ("  radii (leximin)" if soft else "") + "  centres", file=out)
    for g in report["grasps"]:
        centres = "  ".join("(" + ", ".join(f"{v:.4g}" for v in c) + ")"
                            for c in g["centers"])
        facets = " ".join(str(f) for f in g["facets"])
        opening = f"  {g['opening']:>7.4g}" if jaw else ""
        if soft:
            opening = "  " + f"{', '.join(f'{v:.4g}' for v in g['radii']):<16s}"
        print(f"{g['rank']:>4}  {facets:<14s}  {g['radius']:>12.4g}{opening}  {centres}",
              file=out)
    if params.get("contact_type") == "friction":
        how = "every triple of pieces the bound left open" if params["exhaustive"] else \
            f"the first {params['certified_triples']} triples of pieces (not exhaustive)"
        print(f"three fingers: certified regions (a lower bound on the largest), searched "
              f"{how}", file=out)
    elif jaw:
        print("parallel jaw: the closing axis anywhere in the region on the first facet "
              "(radius: its inscribed circle); the pads close flush on both facets", file=out)


def _print_load_and_placement(report: dict[str, Any], out: Any) -> None:
    """With a load: what each plan's regions carry, one line each; with a placement
    error: the probability that each plan holds."""
    curve = report.get("friction_curve")
    if curve is not None:
        lo, hi = report["parameters"]["mu_range"]
        print(f"friction in [{lo:g}, {hi:g}]: every plan holds for each mu of it; the best "
              f"smallest region against mu:", file=out)
        for m, v in zip(curve["mu"], curve["min_region"], strict=True):
            print(f"  mu {m:<6.4g} {v:.4g}", file=out)
    def per_plan(heading: str, line: Any) -> None:
        print(heading, file=out)
        for k, g in enumerate(report["grasps"], 1):
            print(f"  {k:>2}  {line(g)}", file=out)

    sigma = report["parameters"].get("placement_sigma")
    if sigma is not None:
        per_plan(f"placement error {sigma:g} (standard deviation along the boundary): "
                 f"probability that the grasp holds", lambda g: f"{g['probability']:.6f}")
    pose = report["parameters"].get("pose_sigma")
    if pose is not None:
        per_plan(f"pose error x {pose[0]:g}, y {pose[1]:g}, {pose[2]:g} deg (standard "
                 f"deviations{', with the placement error' if sigma is not None else ''}): "
                 f"probability that the grasp holds (quasi-Monte Carlo, 99 % interval)",
                 lambda g: f"{g['pose_probability']['probability']:.4f} +- "
                           f"{g['pose_probability']['error']:.4f}")
    k_n = report["parameters"].get("stiffness")
    if k_n is not None:
        per_plan(f"finger springs {k_n:g} N per {report['units']}, squeezing with "
                 f"{report['parameters']['grip_force_n']:g} N (section 8.2): at the plan's "
                 f"grasp; at the regions' corners",
                 lambda g: f"{g['stability']['reason']}; corners "
                           f"{'all' if g['stability']['corners_stable'] else 'not all'} "
                           f"stable (least {g['stability']['corners_margin']:.4g})")
    bound = report.get("optimality")
    if bound is not None:
        best = max((g["min_region_length"] for g in report["grasps"]), default=0.0)
        if bound["upper_bound"] is None:
            print("optimum: no upper bound proved within the search's budget", file=out)
        else:
            print(f"optimum: no regions of {report['parameters']['fingers']} fingers each "
                  f"{bound['upper_bound']:.4g} {report['units']} long or more hold (proved over "
                  f"{bound['nodes']} boxes of positions); the best plan's {best:.4g} is "
                  f"within {100 * bound['gap']:.1f} % of that", file=out)
    load = report["parameters"].get("load")
    if load is None:
        return
    jaw = report["parameters"].get("gripper") == "parallel_jaw"
    what = "pose" if jaw else "grasp"
    every = "every pose of the box" if jaw else "every grasp of the regions"
    print(f"load {load['mass_kg']:g} kg ({every} carries at least this multiple of it; "
          f"certified):", file=out)
    for k, g in enumerate(report["grasps"], 1):
        p = g["payload"]
        scale = "any" if p["scale"] is None else f"{p['scale']:.3g}x"
        worst = "" if p["worst_grasp_scale"] is None else \
            f" (worst {what} found " \
            f"{p['worst_grasp_scale']:.3g}x, gap {100 * p['gap']:.1f} %)"
        print(f"  {k:>2}  {scale}{worst}", file=out)


def cmd_batch(args: Any) -> int:
    from ..planning import template_request
    from .batch import part_files, run_batch

    if args.workers is not None and args.workers < 1:
        raise CliError(f"--workers must be at least 1, got {args.workers}")
    if args.part_timeout is not None and not args.part_timeout > 0:
        raise CliError(f"--part-timeout must be a number of seconds > 0, got "
                       f"{args.part_timeout:g}")
    # the batch's own outputs are never read as parts (a rerun of a folder that holds
    # its results file or its figures)
    paths = part_files(args.input, outputs=(args.out, args.figures))
    if not paths:
        raise CliError(f"no part files in {args.input!r} (a folder of .json, .svg, .dxf, "
                       f"image, mesh ... files, or a glob pattern)")
    if os.path.isdir(args.out):
        raise CliError(f"--out {args.out} is a folder, not a results file")
    options = plan_options(args)
    template_request(options)   # once, before any work (run_batch checks each part's again)
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
    from ..io.meshes import is_solid_source
    from ..io.parts import choose_part, list_parts
    from ..io.report import dumps, parts_report

    _check_outputs(args, [args.part])
    if is_solid_source(args.part) and not args.part.startswith("demo:"):
        return _solid_parts(args)
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


def _solid_parts(args: Any) -> int:
    """``fcgrasp parts part.stl``: the mesh's connected bodies (the default: the largest
    watertight one)."""
    from ..io.limits import Limits
    from ..io.meshes import read_bodies
    from ..io.report import dumps

    reading = _reading(args)
    bodies, units, note = read_bodies(args.part, args.units, args.file_units,
                                      Limits.given(reading["max_bytes"],
                                                   reading["max_elements"],
                                                   reading["max_vertices"]))
    default = next((b.index for b in bodies if b.watertight), 0)
    if args.json:
        doc = {"source": args.part, "units": units, "units_note": note, "default": default,
               "bodies": [{"index": b.index, "triangles": b.triangles,
                           "watertight": b.watertight, "volume": b.volume,
                           "bounds": b.bounds.tolist()} for b in bodies]}
        _write_outputs([(args.json, dumps(doc))])
    if args.quiet or _json_out(args):
        return 0
    print(f"{args.part}: {len(bodies)} bod{'ies' if len(bodies) != 1 else 'y'} (mesh, units "
          f"{units}: {note}); * = the default (the largest watertight)")
    print(f"  {'index':>5}  {'triangles':>9}  {'watertight':>10}  {'size':>26}  "
          f"{'volume':>11}")
    for b in bodies:
        mark = "*" if b.index == default else " "
        w, h, d = b.bounds[1] - b.bounds[0]
        print(f"{mark} {b.index:>5}  {b.triangles:>9}  {'yes' if b.watertight else 'no':>10}  "
              f"{f'{w:.4g} x {h:.4g} x {d:.4g}':>26}  {b.volume:>11.4g}")
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


def _demo_jobs() -> list[tuple[Any, str, str]]:
    """The demo's plan requests, each with its files' stem and its figure's title."""
    from ..planning import PlanRequest

    fingers = [("blob", 2, 0.3, None, "figure 1.a: two fingers with friction"),
               ("triangle", 4, None, None, "figure 1.b: four frictionless fingers on three "
                                              "edges"),
               ("quad", 4, None, None, "figure 1.c: four frictionless fingers on four edges"),
               ("triangle", 3, None, (0.0, -1.0), "three frictionless fingers and gravity"),
               ("blob", 3, 0.5, None, "three fingers with friction"),
               ("washer", 2, 0.2, None, "two fingers with friction on a part with a hole"),
               ("cam", 2, 0.3, None, "regions along the boundary of a curved part")]
    # the plans distinct alternatives, as by default (the curved part's
    # ranked list is one grasp shifted along the curve, drawn six times)
    jobs = [(PlanRequest(part=f"demo:{name}", fingers=n, mu=mu, gravity=g, top=6),
             f"{name}-{n}f" + ("g" if g is not None else ""), f"demo:{name} - {title}")
            for name, n, mu, g, title in fingers]
    # a parallel-jaw gripper: boxes of jaw poses (closing angle, offset) that hold
    jobs.append((PlanRequest(part="demo:rectangle", gripper="jaw", stroke=(10.0, 50.0),
                             pad=8.0, mu=0.5, top=3), "rectangle-jaw",
                 "demo:rectangle - a parallel jaw (stroke 10-50 mm, 8 mm pads, mu 0.5)"))
    # a solid: two soft fingers' regions on the facets of a mesh
    jobs.append((PlanRequest(part="demo:angle", fingers=2, soft=True, mu=0.5, top=4),
                 "angle-soft", "demo:angle - two soft fingers on a solid (mu 0.5)"))
    jobs.append((PlanRequest(part="demo:prism", fingers=3, mu=0.5, top=3),
                 "prism-3f", "demo:prism - three fingers with friction on a solid (mu 0.5)"))
    jobs.append((PlanRequest(part="demo:angle", gripper="jaw", stroke=(5.0, 50.0), pad=8.0,
                             mu=0.5, top=3), "angle-jaw",
                 "demo:angle - a parallel jaw on a solid (stroke 5-50 mm, 8 mm pads)"))
    return jobs


def _demo_entry(request: Any, doc: Any, stem: str) -> tuple[dict[str, Any], str]:
    """The demo summary's entry for one plan, and the line printed for it."""
    import math

    best = doc.plans[0] if doc.plans else None
    entry: dict[str, Any] = {"part": request.part, "json": f"{stem}.json",
                             "figure": f"{stem}.png"}
    params = doc.report["parameters"]
    if doc.report["part"].get("solid"):
        kind = params["contact_type"]
        who = "jaw" if kind == "jaw" else f"{params['fingers']} {kind}"
        entry.update({"gripper": params.get("gripper", "fingers"),
                      "fingers": params.get("fingers"), "contact_type": kind,
                      "mu": params["mu"],
                      "best_facets": None if best is None else list(best.facets),
                      "best_radius": None if best is None else best.radius})
        if best is None:
            return entry, f"{request.part:14s} {who:10s} no grasp: {doc.reason}"
        shape = "a region" if kind == "jaw" else "octagons"
        return entry, (f"{request.part:14s} {who:10s} best facets {list(best.facets)!s:16s}"
                       f"{shape} of radius {best.radius:.3g} mm")
    if "fingers" not in params:
        entry.update({"gripper": params["gripper"], "mu": params["mu"],
                      "best_theta_deg": None if best is None else
                      [math.degrees(x) for x in best.theta],
                      "best_offset": None if best is None else list(best.offset),
                      "best_measure": None if best is None else best.measure})
        if best is None:
            return entry, f"{request.part:14s} jaw        no grasp: {doc.reason}"
        t0, t1 = (math.degrees(x) for x in best.theta)
        return entry, (f"{request.part:14s} jaw        closing {t0:.1f}-{t1:.1f} deg, "
                       f"offsets {best.offset[0]:.1f}-{best.offset[1]:.1f} mm")
    n = params["fingers"]
    entry.update({"fingers": n, "mu": params["mu"],
                  "best_edges": None if best is None else list(best.edges),
                  "best_min_region": None if best is None else best.min_length})
    if best is None:
        return entry, f"{request.part:14s} {n} fingers  no grasp: {doc.reason}"
    return entry, (f"{request.part:14s} {n} fingers  best edges {list(best.edges)!s:16s} "
                   f"min region {best.min_length:7.3f} mm")


def cmd_demo(args: Any) -> int:
    from ..io.outputs import OutputSet
    from ..io.report import demo_summary, dumps
    from ..planning import plan_document
    from ..plotting import document_figure

    out = Path(args.out)
    if out.exists() and not out.is_dir():
        raise CliError(f"--out {out} exists and is not a folder")
    out.mkdir(parents=True, exist_ok=True)
    entries: list[dict[str, Any]] = []
    for request, stem, title in _demo_jobs():
        doc = plan_document(request)
        with OutputSet() as files:
            files.add_text(out / f"{stem}.json", dumps(doc.report))
            document_figure(doc, str(out / f"{stem}.png"), title=title, outputs=files)
        entry, line = _demo_entry(request, doc, stem)
        entries.append(entry)
        if not args.quiet:
            print(f"{line}  -> {out / stem}.png")
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
                            "id or name; id:NAME for an id made of digits, such as the "
                            "layer id:0); default the largest")
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
        g.add_argument("--repair", action="store_true",
                       help="meshes: merge duplicate vertices, drop degenerate triangles, "
                            "fix the winding (holes in the surface are not closed)")
        g.add_argument("--max-bytes", default=None, metavar="SIZE",
                       help="the largest file read, such as 64M or 1G (default 256M)")
        g.add_argument("--max-elements", type=int, default=None, metavar="N",
                       help="the most elements a drawing may hold once its references are "
                            "expanded (SVG <use>, DXF blocks), and the most parts (default "
                            "20000)")
        g.add_argument("--max-vertices", type=int, default=None, metavar="N",
                       help="the most vertices of a drawing's outlines after flattening, "
                            "and of a mesh's triangles (default 500000)")
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
        p.add_argument("--mu", default=None, metavar="MU|LOW:HIGH",
                       help="friction coefficient (default 0.3; four fingers and --gravity are "
                            "frictionless and take none); a range LOW:HIGH when friction is "
                            "known only to lie in it: plans that hold for every mu of it, "
                            "and the best region against mu")
        p.add_argument("--soft", action="store_true",
                       help="with a solid part (a mesh, or demo:box, demo:cylinder, "
                            "demo:prism, demo:angle) and --fingers 2: two soft fingers, "
                            "regions on two facets (a solid with --fingers 3: three point "
                            "fingers with friction, certified regions on three facets)")
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
        p.add_argument("--distinct", type=float, default=None, metavar="FRACTION",
                       help="keep only distinct alternatives: drop a plan whose regions "
                            "overlap a better plan's by more than FRACTION of the shorter "
                            "(on a solid: whose regions, grown by 1/FRACTION, overlap a "
                            "better plan's; 0.5 is a good choice; 0: every plan, as "
                            "ranked; default 0.5: a plan shifted along the outline by "
                            "an edge, a jaw's mirror and neighbouring boxes, are merged)")
        p.add_argument("--mass", type=float, default=None, metavar="KG",
                       help="a load to carry: the part's mass in kg; each plan then reports "
                            "the scale of the load every grasp of its regions carries "
                            "(certified; gravity along -y)")
        p.add_argument("--com", default=None, metavar="X,Y",
                       help="the load's centre of mass (default: the part's centroid)")
        p.add_argument("--accel", default=None, metavar="AX,AY",
                       help="the load is also carried under every acceleration with "
                            "|a_x| <= AX and |a_y| <= AY (m/s^2), or in their ellipse "
                            "(--accel-shape ellipse)")
        p.add_argument("--accel-shape", default="box", choices=("box", "ellipse"),
                       help="the set of accelerations: the box of --accel (default) or "
                            "the ellipse with those semi-axes (at most so much in any "
                            "direction: AX = AY is a circle)")
        p.add_argument("--force-limit", type=float, default=None, metavar="N",
                       help="largest normal force of each finger, newtons")
        p.add_argument("--total-force", type=float, default=None, metavar="N",
                       help="largest sum of the fingers' normal forces, newtons")
        p.add_argument("--placement-sigma", type=float, default=None, metavar="S",
                       help="two fingers: the probability that each plan holds when each "
                            "finger lands with a Gaussian error of S (the part's units) "
                            "along the boundary around its region's centre (exact)")
        p.add_argument("--stiffness", type=float, default=None, metavar="K",
                       help="point fingers as springs of stiffness K (N per unit of the "
                            "part; fingers with friction stick): whether each plan's grasp "
                            "and its regions' corner grasps are stable (section 8.2)")
        p.add_argument("--grip-force", type=float, default=None, metavar="N",
                       help="with --stiffness: the fingers' total squeeze in newtons "
                            "(default 10)")
        p.add_argument("--pose-sigma", default=None, metavar="SX,SY,DEG",
                       help="point fingers: the probability that each plan holds when the "
                            "part sits with a Gaussian pose error (deviations in x, y and "
                            "degrees about its centroid) and each finger closes along its "
                            "approach line (quasi-Monte Carlo with a 99 %% interval)")
        p.add_argument("--bound", action="store_true",
                       help="three fingers with friction or four frictionless: prove an "
                            "upper bound on the best smallest region any plan could reach "
                            "(regions along the boundary), so the plans' gap is known "
                            "(seconds, up to a minute on a large part)")
        p.add_argument("--max-memory", default=None, metavar="SIZE",
                       help="memory budget of the search, such as 500M or 4G (default 2G); a "
                            "search that cannot fit stops at once and says what would")
        p.add_argument("--time-limit", default=None, metavar="SECONDS",
                       help="wall-clock seconds the search may spend looking for distinct "
                            "alternatives (default 10; 0: no limit); stopped early it "
                            "prints the plans it proved and a bound on the rest")

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

    from ._cli_simulate import add_parser as simulate_parser

    simulate_parser(sub, _Parser)

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
        # a reader's or numpy's runtime warnings on a broken input are not the one line
        # the user reads (its failure is); a command that succeeds has none to say
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)
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
    except ImportError as exc:
        # an optional dependency the command needs (the message names its extra)
        if "pip install" not in str(exc):
            raise
        print(f"fcgrasp: error: {' '.join(str(exc).split())}", file=sys.stderr)
        return EXIT_USAGE
    except Exception as exc:  # noqa: BLE001 - the promise is: never a traceback
        print(f"fcgrasp: internal error: {type(exc).__name__}: {' '.join(str(exc).split())}",
              file=sys.stderr)
        return EXIT_INTERNAL


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
