"""A real hand's pick against the bare jaw: how many of the bare jaw's plans the hand
would hit the part or the table with, and what planning with the hand costs.

    .venv/bin/python benchmarks/bench_hands.py [--hand franka] [--thickness 6]
                                               [--files dxf/forms.dxf,...]
                                               [--tips 3 [--fingers 3]]
                                               [--in-plane]

For each part (the built-in planar parts and the corpus files given), two runs of
``fcgrasp plan`` in fresh processes, as the CLI runs them (CPU seconds with the process's
start, from ``wait4``):

* **bare**: the jaw of the hand's stroke and pad width (``--stroke``, ``--pad``), internal
  grips included;
* **hand**: ``--hand HAND --table --thickness T``.

With ``--tips R`` the same for point fingers (``--fingers 2``, or ``--fingers`` given):
**bare** plans against ``--hand tip=R,length=L --table --thickness T``, each plan's
fingers (vertical cylinders of radius ``R`` over the representative contacts, from
1 mm above the table) checked against the plate and the table by python-fcl, the
hand's plans included (none may collide).

With ``--in-plane`` the jaw's hand holds the plate in its plane (``--hand HAND
--in-plane``, the plate as thick as the pad is wide, no table) against the bare jaw of the
hand's stroke and pad height: each bare plan's centre pose is checked with the hand's
boxes lying in the plane, its palm on either side of the pads' strip (colliding: on both
sides), each hand plan's on its own side (none may collide).

Then each bare plan's centre pose is checked with an independent collision library
(python-fcl through trimesh) as a pick from above with the hand's boxes: the plate of
thickness ``T`` on a table, the tool frame at the height that centres the pad on the
plate's side (what a user of the bare jaw would do), an internal grip's fingers inside
the hole. The table gives the share of the bare plans that collide (they are what the
hand's model leaves out or moves up) and the ratio of the two runs' times.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
FCGRASP = Path(sys.executable).with_name("fcgrasp")
BUILT_IN = ["rectangle", "bracket", "quad", "washer", "cam", "blob", "triangle"]


def run(argv: list[str]) -> tuple[float | None, dict | None]:
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "plan.json")
        proc = subprocess.Popen([str(FCGRASP), *argv, "--json", out, "--quiet"],
                                stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
        _, status, usage = os.wait4(proc.pid, 0)
        proc.stderr and proc.stderr.close()
        if os.waitstatus_to_exitcode(status) not in (0, 1):
            return None, None
        return usage.ru_utime + usage.ru_stime, json.loads(Path(out).read_text())


def scene(part, thickness: float, table: bool = True):
    """python-fcl's collision manager of the plate (the part extruded) on the table."""
    import shapely
    import trimesh

    m = trimesh.collision.CollisionManager()
    m.add_object("plate", trimesh.creation.extrude_polygon(
        shapely.Polygon(part.vertices, [h for h in part.holes]), thickness))
    if table:
        slab = trimesh.creation.box(extents=(1e4, 1e4, 10.0))
        slab.apply_translation((0.0, 0.0, -5.0))
        m.add_object("table", slab)
    return m


def hand_hits(m, hand, opening: float, origin, R) -> bool:
    """Whether the hand's boxes at ``opening``, its tool frame at ``origin`` turned by
    ``R``, meet the plate or the table (``m``)."""
    import trimesh

    for b in hand.boxes(opening):
        T = np.eye(4)
        T[:3, :3] = R @ np.asarray(b.rotation)
        T[:3, 3] = origin + R @ np.asarray(b.centre)
        if m.in_collision_single(trimesh.creation.box(extents=np.asarray(b.size) - 2e-6,
                                                      transform=T)):
            return True
    return False


def _frame(hand, grasp: dict, height: float, side: int = 0):
    """The tool frame (origin, axes) of a bare plan's centre pose
    (:func:`fcgrasp.io.moveit.jaw_tool_pose`: picked from above, or held in the plane on
    ``side`` of the strip) and the opening between its stops."""
    from fcgrasp.io.moveit import jaw_tool_pose

    theta, offset = grasp["centre"]
    stops = (grasp["contacts"]["a"]["stop"], grasp["contacts"]["b"]["stop"])
    origin, R = jaw_tool_pose(grasp["centroid"], theta, offset, stops, height, side,
                              sum(hand.pad_span) / 2)
    return origin, R, abs(stops[0] - stops[1])


def collides(m, hand, grasp: dict, height: float) -> bool:
    """The hand at a bare plan's centre pose, picked from above with its tool frame at
    ``height``, against the plate and the table (``m``, :func:`scene`'s)."""
    origin, R, opening = _frame(hand, grasp, height)
    if grasp["mode"] == "internal":
        # the pads are the fingers' outer faces: the inner ones are a finger's
        # thickness in from each
        thick = float(hand.pad_box.size[1])
        opening -= 2 * thick
        if opening < 0:
            return True                     # the fingers do not fit between the stops
    return hand_hits(m, hand, opening, origin, R)


def plane_collides(m, hand, grasp: dict, side: int, height: float) -> bool:
    """The hand lying in the plate's plane at a plan's centre pose, its palm on ``side``
    of the pads' strip (``+1``: ``+n``) and its tool frame at ``height``, against the
    plate (``m``); an internal grip counts as colliding."""
    if grasp["mode"] == "internal":
        return True
    origin, R, opening = _frame(hand, grasp, height, side)
    return hand_hits(m, hand, opening, origin, R)


def rows(parts: list[str], thickness: float, base: list[str], bare_args: list[str],
         hand_args: list[str], cells, n: int, table: bool = True) -> list[int]:
    """For each part the two runs (``base`` with the part, then ``bare_args`` or
    ``hand_args``), the plate's scene and the row: the ``n`` counts of ``cells(scene,
    bare report, hand report)``, the two CPU times and their ratio; the counts' sums."""
    import fcgrasp as fc

    sums = [0] * n
    for src in parts:
        argv = [base[0], src, *base[1:]]
        t_bare, bare = run(argv + bare_args)
        t_hand, mine = run(argv + hand_args)
        label = src.replace(str(HERE / "corpus") + "/", "")
        if bare is None or mine is None:
            print(f"| {label} | error |" + " |" * (n + 2))
            continue
        counts = cells(scene(fc.read_part(src), thickness, table), bare, mine)
        sums = [a + b for a, b in zip(sums, counts, strict=True)]
        ratio = "-" if not t_bare else f"{t_hand / t_bare:.2f}"
        print(f"| {label} | " + " | ".join(str(c) for c in counts) +
              f" | {t_bare:.2f} s | {t_hand:.2f} s | {ratio} |")
    return sums


def tips_collide(m, grasp: dict, radius: float, length: float) -> bool:
    """A plan's fingers (cylinders of ``radius``, ``length`` long from 1 mm above the
    table, their axes ``radius`` off the representative contacts along the outward
    normals) against the plate and the table (``m``, :func:`scene`'s)."""
    import trimesh

    for c, n in zip(grasp["contacts"], grasp["normals"], strict=True):
        axis = np.asarray(c) + radius * np.asarray(n) / np.linalg.norm(n)
        T = np.eye(4)
        T[:3, 3] = (axis[0], axis[1], 1.0 + length / 2)
        body = trimesh.creation.cylinder(radius=radius * (1 - 1e-6), height=length,
                                         sections=64, transform=T)
        if m.in_collision_single(body):
            return True
    return False


def tips(args: argparse.Namespace, parts: list[str]) -> int:
    """The point fingers' table (the module's docstring, ``--tips``)."""

    R, L = args.tips, 40.0
    print(f"point fingers: {args.fingers} with tips of radius {R:g} mm, {L:g} mm long, "
          f"plate {args.thickness:g} mm on a table, mu {args.mu}, top {args.top}")
    print("| part | bare plans | colliding | hand plans | colliding | bare CPU | hand CPU | "
          "ratio |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- |")
    base = ["plan", "--fingers", str(args.fingers), "--mu", args.mu, "--top", args.top]
    hand = ["--hand", f"tip={R:g},length={L:g}", "--table", "--thickness", str(args.thickness)]

    def cells(m, bare: dict, mine: dict) -> list[int]:
        got = [tips_collide(m, g, R, L) for g in bare["grasps"]]
        own = [tips_collide(m, g, R, L) for g in mine["grasps"]]
        return [len(got), sum(got), len(own), sum(own)]

    total, hits, _, own = rows(parts, args.thickness, base, [], hand, cells, 4)
    print(f"\nof {total} bare plans, {hits} put a finger of radius {R:g} into the part "
          f"({100 * hits / max(total, 1):.0f} %); of the hand's plans, {own} collide")
    return 0


def jaw_runs(args: argparse.Namespace, stroke, pad: float) -> tuple[list[str], list[str]]:
    """The jaw's ``fcgrasp plan`` options, and the bare jaw's: the hand's stroke and the
    pad the hand's strip is as wide as (``pad``)."""
    base = ["plan", "--gripper", "jaw", "--mu", args.mu, "--top", args.top]
    return base, ["--stroke", f"{stroke[0]:g},{stroke[1]:g}", "--pad", repr(pad)]


def in_plane(args: argparse.Namespace, hand, parts: list[str]) -> int:
    """The jaw's hand holding the plate in its plane (the module's docstring)."""
    T = hand.pad_width
    print(f"hand {hand.name} held in the plate's plane (strip: the pad's height "
          f"{hand.pad_height:g} mm), plate {T:g} mm, no table, mu {args.mu}, top {args.top}")
    print("| part | bare plans | colliding on both sides | hand plans | colliding | bare CPU | "
          "hand CPU | ratio |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- |")
    base, bare_args = jaw_runs(args, hand.stroke, hand.pad_height)
    hand_args = ["--hand", args.hand, "--in-plane"]

    def cells(m, bare: dict, mine: dict) -> list[int]:
        got = [all(plane_collides(m, hand, g, s, T / 2) for s in (1, -1))
               for g in bare["grasps"]]
        own = [plane_collides(m, hand, g, g["side"], g["pose"]["position"][2])
               for g in mine["grasps"]]
        return [len(got), sum(got), len(own), sum(own)]

    total, hits, _, own = rows(parts, T, base, bare_args, hand_args, cells, 4, table=False)
    print(f"\nof {total} bare plans, {hits} collide held in the plane whichever side the "
          f"palm is on ({100 * hits / max(total, 1):.0f} %); of the hand's plans, {own} "
          f"collide")
    return 0


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--hand", default="franka")
    ap.add_argument("--thickness", type=float, default=6.0)
    ap.add_argument("--mu", default="0.5")
    ap.add_argument("--top", default="5")
    ap.add_argument("--tips", type=float, default=None, metavar="R",
                    help="point fingers with tips of this radius (mm) instead of a jaw")
    ap.add_argument("--fingers", type=int, default=2)
    ap.add_argument("--in-plane", action="store_true",
                    help="the jaw's hand holding the plate in its plane")
    ap.add_argument("--files", default="gears/teeth-08.dxf,gears/teeth-12.dxf,"
                                       "gears/teeth-20.dxf,gears/teeth-32.dxf,icons/heart.svg,"
                                       "icons/droplet.svg,icons/cloud.svg")
    args = ap.parse_args()
    from fcgrasp.model.hands import hand_named

    hand = hand_named(args.hand)
    subprocess.run([sys.executable, "-c", "import fcgrasp; fcgrasp.compile_kernels()"],
                   check=True)
    parts = [f"demo:{n}" for n in BUILT_IN] + \
        [str(HERE / "corpus" / f) for f in filter(None, args.files.split(","))]
    if args.tips is not None:
        return tips(args, parts)
    if args.in_plane:
        return in_plane(args, hand, parts)
    print(f"hand {hand.name} (stroke {hand.stroke[0]:g}-{hand.stroke[1]:g} mm, pads "
          f"{hand.pad_width:g} mm), plate {args.thickness:g} mm on a table, mu {args.mu}, "
          f"top {args.top}")
    from fcgrasp.grippers.jaw import Scene, top_pick

    centred = args.thickness / 2 + sum(hand.pad_span) / 2
    safe = top_pick(hand, Scene(args.thickness, table=True)).height
    print(f"the bare plans checked with the pad centred on the plate's side (tool at "
          f"{centred:g} mm) and at the hand model's height ({safe:g} mm)")
    print("| part | bare plans | colliding, centred | colliding, at the hand's height | "
          "hand plans | bare CPU | hand CPU | ratio |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- |")
    base, bare_args = jaw_runs(args, hand.stroke, hand.pad_width)
    hand_args = ["--hand", args.hand, "--table", "--thickness", str(args.thickness)]

    def cells(m, bare: dict, mine: dict) -> list[int]:
        got = [collides(m, hand, g, centred) for g in bare["grasps"]]
        up = [collides(m, hand, g, safe) for g in bare["grasps"]]
        return [len(got), sum(got), sum(up), len(mine["grasps"])]

    total, hits, lifted, _ = rows(parts, args.thickness, base, bare_args, hand_args, cells, 4)
    print(f"\nof {total} bare plans, {hits} collide with the pad centred on the plate's side "
          f"({100 * hits / max(total, 1):.0f} %), {lifted} at the hand model's height "
          f"({100 * lifted / max(total, 1):.0f} %)")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
