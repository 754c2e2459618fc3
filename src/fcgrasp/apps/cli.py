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
from typing import Any

from .. import __version__
from ..errors import RequestError as CliError
from . import _cli_parser
from ._cli_io import (
    _batch_progress,
    _check_outputs,
    _check_plot,
    _floats,
    _json_out,
    _load,
    _memory,
    _progress,
    _reading,
    _seconds,
    _stderr,
    _write_outputs,
)
from ._cli_parser import EXIT_INTERNAL, EXIT_NOT_CLOSURE, EXIT_USAGE
from ._cli_tables import demo_entry, listing_table, plan_table


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
                   ("accel", 2), ("pose_sigma", 3), ("rest_orientation", 4)):
        if options[key] is not None:
            options[key] = _floats(options[key], n, "--" + key.replace("_", "-"))
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
    if args.moveit:
        _check_moveit(args)
    say = None if args.quiet else _stderr
    doc = plan_document(request, progress=_progress(sys.stderr.isatty() and not args.quiet),
                        say=say)

    def figure(out: Any) -> None:
        from ..plotting import document_figure

        document_figure(doc, args.plot, outputs=out)

    texts = [(args.json, dumps(doc.report))] if args.json else []
    if args.moveit:
        from ..io.moveit import grasps_text, moveit_grasps

        texts.append((args.moveit, grasps_text(moveit_grasps(doc.report), args.moveit)))
    _write_outputs(texts, figure if args.plot else None)
    if not args.quiet and not _json_out(args):
        if not doc.plans:
            print(f"no grasp: {doc.reason}")
        else:
            for line in plan_table(doc.report):
                print(line)
            _print_load_and_placement(doc.report, sys.stdout)
    for note in (incomplete_note(doc.report), fewer_note(doc.report)):
        if note is not None and not args.quiet:
            print(note, file=sys.stderr if _json_out(args) else sys.stdout)
    return 0


def _check_moveit(args: Any) -> None:
    """``--moveit`` before any work: a parallel gripper's plans (a jaw's, or two
    fingers'), a file name that is neither the part nor another output."""
    from ..io.outputs import check_outputs

    if args.gripper != "jaw" and args.fingers not in (None, 2):
        raise CliError("--moveit writes a parallel gripper's grasps (moveit_msgs/Grasp): "
                       "plan with --gripper jaw or two fingers")
    if not args.moveit.lower().endswith((".yaml", ".yml", ".json")):
        raise CliError(f"--moveit must end in .yaml, .yml or .json, got {args.moveit!r}")
    check_outputs(args.moveit, None, [args.part])
    if args.moveit in (args.json, args.plot):
        raise CliError(f"--moveit {args.moveit} is another output too")


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
    at_most = None if gap["bound"] is None else \
        f"{gap.get('measure', 'smallest region')} of at most " \
        f"{gap['bound']:.4g} {report.get('units', '')}".rstrip()
    if not gap.get("exact", True):
        others = "" if at_most is None else f", each with a {at_most}"
        return (f"search stopped {why}: {gap['found']} of {top} plans, each proved to hold; "
                f"a complete search may rank others first{others}")
    rest = "no bound on the rest was proved" if at_most is None else \
        f"every further distinct alternative has a {at_most}"
    return f"search stopped {why}: {gap['found']} of {top} plans proved, exact; {rest}"


def fewer_note(report: dict[str, Any]) -> str | None:
    """The line that says why a complete search gave fewer plans than ``top``, or None:
    with distinct alternatives, every other plan it found is a copy of one given; else
    there are no more.

    >>> print(fewer_note({"complete": True, "grasps": [{}] * 3,
    ...                   "parameters": {"top": 10, "distinct": 0.5}}))
    ... # doctest: +NORMALIZE_WHITESPACE
    3 of 10 plans: every other plan that holds is the same alternative as one of these
    (--distinct 0.5; the JSON's "similar" lists them, --distinct 0 every plan)
    """
    top = report.get("parameters", {}).get("top")
    found = len(report.get("grasps", ()))
    if not report.get("complete", True) or top is None or not 0 < found < top:
        return None
    distinct = report["parameters"].get("distinct")
    if distinct:
        return (f"{found} of {top} plans: every other plan that holds is the same "
                f"alternative as one of these (--distinct {distinct:g}; the JSON's "
                f"\"similar\" lists them, --distinct 0 every plan)")
    return f"{found} of {top} plans: the search found no other plan that holds"


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
    from ..io.report import dumps, part_listing

    _check_outputs(args, [args.part])
    doc = part_listing(args.part, **_reading(args))
    if args.json:
        _write_outputs([(args.json, dumps(doc))])
    if not args.quiet and not _json_out(args):
        for line in listing_table(doc):
            print(line)
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
    """The demo summary's entry for one plan (:func:`~fcgrasp.apps._cli_tables.
    demo_entry`), and the line printed for it."""
    entry, line = demo_entry(request.part, doc.report, doc.reason)
    return {"part": request.part, "json": f"{stem}.json", "figure": f"{stem}.png",
            **entry}, line


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


def build_parser() -> argparse.ArgumentParser:
    """The ``fcgrasp`` parser (:func:`fcgrasp.apps._cli_parser.build_parser`)."""
    return _cli_parser.build_parser({"plan": cmd_plan, "check": cmd_check, "parts": cmd_parts,
                                     "batch": cmd_batch, "serve": cmd_serve, "demo": cmd_demo})


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


def run() -> None:
    """The ``fcgrasp`` command (and ``python -m fcgrasp``): :func:`main` on the process's
    arguments, then the process exits with its code.  The heap is frozen first
    (``gc.freeze``): the interpreter's finalization then skips the collections of every
    object the command made (numba's types and loaded kernels among them): about 0.1 s
    of the 1.1 s of CPU of ``fcgrasp plan`` on a 384-edge icon.  The outputs are written
    and closed by then (each atomically), and exit handlers still run."""
    import gc

    code = main()
    sys.stdout.flush()
    gc.freeze()
    sys.exit(code)


if __name__ == "__main__":  # pragma: no cover
    run()
