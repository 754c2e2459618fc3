"""The ``fcgrasp`` command's arguments: the parser of every sub-command (part of
:mod:`fcgrasp.apps.cli`)."""

from __future__ import annotations

import argparse
import sys
from collections.abc import Callable, Mapping
from typing import Any, NoReturn

from .. import __version__

EXIT_NOT_CLOSURE = 1
EXIT_USAGE = 2
EXIT_INTERNAL = 3
#: Units a part can be read in (``--units``); see :mod:`fcgrasp.io.units`.
UNIT_CHOICES = ("mm", "cm", "m", "in")


class _Parser(argparse.ArgumentParser):
    def error(self, message: str) -> NoReturn:
        print(f"fcgrasp: error: {message} (see fcgrasp --help)", file=sys.stderr)
        raise SystemExit(EXIT_USAGE)


def build_parser(commands: Mapping[str, Callable[[Any], int]]) -> argparse.ArgumentParser:
    """The ``fcgrasp`` parser, each sub-command calling its function of ``commands``
    (by name: ``plan``, ``check``, ``parts``, ``batch``, ``serve``, ``demo``)."""
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
        p.add_argument("--hand", metavar="NAME|URDF|PARAMS", default=None,
                       help="with --gripper jaw: a real hand (franka, robotiq_hande, a URDF "
                            "file, or stroke=MIN:MAX,pad=W,height=H,thickness=T), whose "
                            "stroke and pads the jaw takes; point fingers: tip=R[,length=L] "
                            "(vertical finger bodies of radius R); the part is picked from "
                            "above and every plan is collision free, with its pose")
        p.add_argument("--thickness", type=float, default=None, metavar="T",
                       help="with --hand on a planar part: the plate's thickness (default: "
                            "the pad's height; 5 mm for point fingers)")
        p.add_argument("--table", action="store_true", default=False,
                       help="with --hand: the part lies on a table the hand must not touch "
                            "(a solid in its most stable pose)")
        p.add_argument("--in-plane", action="store_true", default=False,
                       help="with --hand: the part held in its plane (default: picked "
                            "from above); point fingers (--hand tip=R[,length=L]) lie in it "
                            "along their contacts' normals, the jaw's hand lies in it with "
                            "its palm on one side of the pads' strip")
        p.add_argument("--rest-orientation", default=None, metavar="QX,QY,QZ,QW",
                       help="with --hand --table on a solid: rest in this orientation (a "
                            "quaternion from the part's frame to the table's), lowered onto "
                            "the table, instead of a stable pose")
        p.add_argument("--rest", type=int, default=None, metavar="K",
                       help="with --hand --table on a solid: rest in its K-th most likely "
                            "stable pose (default 0)")
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
                       help="soft fingers: on a solid part (a mesh, or demo:box, "
                            "demo:cylinder, demo:prism, demo:angle) two fingers are soft "
                            "fingers with or without it (regions on two facets; --fingers 3: "
                            "three point fingers with friction, certified regions on three "
                            "facets); on a planar part it changes nothing (the torsion of a "
                            "soft finger turns about an axis in the plane)")
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
                       help="memory budget of the search, such as 500M or 4G (default 2G; "
                            "on a solid none); a search that cannot fit stops at once and "
                            "says what would, one past it on a solid stops as at its time "
                            "limit")
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
    p.add_argument("--moveit", metavar="OUT.yaml|OUT.json",
                   help="write the plans of a jaw or of two fingers as a parallel gripper's "
                        "moveit_msgs/Grasp messages (metres, the part's frame, the Franka "
                        "Hand's joints; fcgrasp.io.moveit)")
    p.set_defaults(func=commands["plan"])

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
    c.set_defaults(func=commands["check"])

    from ._cli_simulate import add_parser as simulate_parser

    simulate_parser(sub, _Parser)

    ls = sub.add_parser("parts", help="the parts a file holds (index, id, layer, size, area)",
                        description="List the parts of a file, as fcgrasp plan would read "
                                    "them; --part N|ID picks one, the default is the "
                                    "largest (marked *).",
                        epilog="example:\n  fcgrasp parts drawing.dxf --units in",
                        formatter_class=argparse.RawDescriptionHelpFormatter)
    reading_args(ls, "write the list as JSON ('-': standard output)")
    ls.set_defaults(func=commands["parts"])

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
    b.set_defaults(func=commands["batch"])

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
    sv.set_defaults(func=commands["serve"])

    d = sub.add_parser("demo", help="plans for the built-in parts, JSON and figures",
                       description="The main job on built-in parts (the paper's figure 1): "
                                   "plans written as JSON and figures into a folder.",
                       epilog="example:\n  fcgrasp demo --out demo-output",
                       formatter_class=argparse.RawDescriptionHelpFormatter)
    d.add_argument("--out", default="demo-output", help="output folder (default demo-output)")
    d.add_argument("--quiet", action="store_true", help="print nothing on success")
    d.set_defaults(func=commands["demo"])
    return parser
