"""``fcgrasp simulate``: the physics stress test of a plan report's grasps, or of one
grasp given as ``fcgrasp check`` takes it (:mod:`fcgrasp.physics`, MuJoCo)."""

from __future__ import annotations

import argparse
import json
from typing import Any

from ..errors import RequestError as CliError
from ._cli_io import _json_out, _write_outputs

#: The layout version of the stress test's JSON.
SIMULATE_VERSION = 1


def add_parser(sub: Any, parser_class: Any) -> None:
    s = sub.add_parser(
        "simulate", help="shake a plan's grasps in MuJoCo until the part slips (fcgrasp[sim])",
        description="The physics stress test: grasps sampled in each plan's regions (their "
                    "ends and middles first), the part extruded and squeezed by fingers "
                    "that balance the load they measure, seeded disturbance wrenches "
                    "ramped up until it slips; the load at slip beside the certified "
                    "payload. Controls that are not force closure (the same contacts "
                    "without friction, or a finger fewer) must slip.",
        epilog="examples:\n  fcgrasp plan demo:blob --mu 0.5 --top 3 --json plan.json\n"
               "  fcgrasp simulate plan.json --json stress.json --seed 1\n"
               "  fcgrasp simulate demo:rectangle --contacts grasp.json --gif grasp.gif",
        formatter_class=argparse.RawDescriptionHelpFormatter)
    s.add_argument("source", metavar="REPORT.json|PART",
                   help="a plan report (fcgrasp plan --json) or, with --contacts, a part")
    s.add_argument("--contacts", metavar="CONTACTS.json",
                   help="one grasp, as fcgrasp check takes it (point fingers)")
    s.add_argument("--json", metavar="OUT", help="write the results as JSON ('-': stdout)")
    s.add_argument("--gif", metavar="OUT.gif",
                   help="an animation of the first grasp's stress test")
    s.add_argument("--grip-force", type=float, default=10.0, metavar="N",
                   help="the largest finger's squeeze, newtons (default 10)")
    s.add_argument("--samples", type=int, default=20, metavar="K",
                   help="grasps sampled in each plan's regions (default 20)")
    s.add_argument("--directions", type=int, default=2, metavar="D",
                   help="seeded disturbance directions per grasp (default 2)")
    s.add_argument("--control", choices=("balance", "servo"), default="balance",
                   help="how a planar part's fingers push: 'balance', the forces that "
                        "balance the load they measure, each up to twice its squeeze "
                        "(default), or 'servo', stiff position servos that share the load "
                        "as their stiffness does")
    s.add_argument("--sensitivity", action="store_true",
                   help="run the same grasps again under each varied setting (softer "
                        "contacts, finer steps, pyramidal cones, no noslip solver) and "
                        "print how the answer moves")
    s.add_argument("--seed", type=int, default=0, help="the sampling seed (default 0)")
    s.add_argument("--workers", type=int, default=None,
                   help="processes (default: every core)")
    s.add_argument("--quiet", action="store_true", help="print nothing but errors")
    s.set_defaults(func=cmd_simulate)


def _read_report(path: str) -> dict[str, Any] | None:
    """The plan report at ``path``, or None where the file is not one (a part)."""
    from ..io.report import migrate_report

    if not path.lower().endswith(".json") or path == "-":
        return None
    try:
        with open(path, encoding="utf-8") as fh:
            doc = json.load(fh)
    except (OSError, ValueError):
        return None
    if not isinstance(doc, dict) or "grasps" not in doc or "format_version" not in doc:
        return None
    try:
        report = migrate_report(doc)
    except ValueError as exc:
        raise CliError(f"{path}: {exc}", "source") from None
    from ..io.schema import validate

    try:
        validate(report)                    # every field named where one does not fit
    except ValueError as exc:
        raise CliError(f"{path}: {exc}", "source") from None
    return report


def _plans_of(args: Any) -> tuple[Any, list[Any], str]:
    """The part's polygon, the plans (a report's grasps, or the one grasp of
    --contacts) and the units."""
    import numpy as np


    report = _read_report(args.source)
    if report is not None:
        if args.contacts:
            raise CliError("--contacts goes with a part, not with a plan report", "contacts")
        from ..io.report import report_part

        shape, units = report_part(report)
        grasps = report["grasps"]
        for g in grasps:
            if g.get("gripper") != "parallel_jaw" and ("regions" not in g
                                                        or "normals" not in g):
                raise CliError("the stress test runs point fingers and the parallel jaw: "
                               "the report's grasps are neither", "source")
        return shape, grasps, units
    if not args.contacts:
        raise CliError(f"{args.source} is not a plan report: give a report of fcgrasp plan "
                       "--json, or a part with --contacts", "source")
    from ..io.parts import load_part, read_contacts

    loaded = load_part(args.source)
    if loaded.polygon is None:
        raise CliError(f"{args.source}: {loaded.error}", "source")
    contacts, _ = read_contacts(args.contacts, loaded.polygon)
    mus = {float(getattr(c, "mu", 0.0)) for c in contacts}
    if len(mus) != 1 or any(not hasattr(c, "point") for c in contacts):
        raise CliError("the stress test takes point fingers of one friction coefficient",
                       "contacts")
    pts = np.array([c.point for c in contacts], float)
    nrm = np.array([c.normal for c in contacts], float)
    grasp = {"regions": [np.array([p, p]) for p in pts], "normals": nrm,
             "mu": mus.pop(), "contacts": pts}
    return loaded.polygon, [grasp], loaded.units


def _tip_radius(source: str) -> float | None:
    """The fingertips' radius of a report planned with ``--hand tip=R`` (its units), or
    None (the stress test's own)."""
    report = _read_report(source)
    hand = (report or {}).get("hand")
    if isinstance(hand, dict) and hand.get("kind") == "fingertips":
        return float(hand["tip_radius"])
    return None


def cmd_simulate(args: Any) -> int:
    import numpy as np

    from .. import __version__
    from ..io.report import dumps
    from ..physics import (
        SLIP_DISPLACEMENT,
        SLIP_ROTATION_DEG,
        VARIANTS,
        control_runs,
        simulate,
    )

    for name, value, low in (("--samples", args.samples, 1), ("--directions",
                                                               args.directions, 1)):
        if value < low:
            raise CliError(f"{name} must be at least {low}, got {value}", name[2:])
    if not args.grip_force > 0 or not np.isfinite(args.grip_force):
        raise CliError(f"--grip-force must be a positive number of newtons, got "
                       f"{args.grip_force}", "grip_force")
    polygon, plans, units = _plans_of(args)
    if not plans:
        raise CliError(f"{args.source}: the report has no plan to simulate", "source")
    tip = _tip_radius(args.source)
    results = simulate(polygon, plans, grip_force=args.grip_force, samples=args.samples,
                       directions=args.directions, seed=args.seed, units=units,
                       workers=args.workers, control=args.control, tip_radius=tip)
    controls = control_runs(polygon, plans, grip_force=args.grip_force, seed=args.seed + 1,
                            units=units, tip_radius=tip)
    doc = {"fcgrasp": __version__, "kind": "stress_test", "version": SIMULATE_VERSION,
           "units": units, "seed": args.seed, "grip_force_n": args.grip_force,
           "settings": {"control": args.control, "tip_radius": tip,
                        "slip_displacement": SLIP_DISPLACEMENT,
                        "slip_rotation_deg": SLIP_ROTATION_DEG, "engine": "mujoco"},
           "plans": results, "controls": controls}
    if args.sensitivity:
        from ..physics import sensitivity

        doc["sensitivity"] = sensitivity(
            polygon, plans, variants=[v for v in VARIANTS if v != "default"],
            grip_force=args.grip_force, samples=args.samples, directions=args.directions,
            seed=args.seed, units=units, workers=args.workers, control=args.control,
            tip_radius=tip)

    def gif(out: Any) -> None:
        from ..physics import recorded_run

        first: dict[str, Any] = results[0]["grasps"][0]["wrench_direction"]
        run = recorded_run(polygon, plans[0], first, grip_force=args.grip_force, units=units)
        if run is not None:
            out.add(args.gif, run[1])

    _write_outputs([(args.json, dumps(doc))] if args.json else [],
                   gif if args.gif else None)
    if not args.quiet and not _json_out(args):
        print("rank  runs  held to the certified payload  slip / certified (least)")
        for row in results:
            worst = "-" if row["worst_ratio"] is None else f"{row['worst_ratio']:.2f}"
            print(f"{row['rank']:>4}  {row['runs']:>4}  {row['held']:>29}  {worst:>24}")
        slipped = sum(c["slipped"] for c in controls)
        print(f"controls (not force closure): {slipped} of {len(controls)} slipped")
        if args.sensitivity:
            print("\nsetting varied     held  slip / certified (least, median)  "
                  "controls slipped")
            for v in doc["sensitivity"]:
                least = "-" if v["least_ratio"] is None else f"{v['least_ratio']:.2f}"
                med = "-" if v["median_ratio"] is None else f"{v['median_ratio']:.2f}"
                print(f"{v['variant']:<16} {v['held']:>4}/{v['runs']:<4} {least:>17}, "
                      f"{med:<15} {v['slipped']} of {v['controls']}")
    return 0
