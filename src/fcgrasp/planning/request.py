"""What to plan, as one typed value: :class:`PlanRequest`, and :func:`plan_document`, the
one function that turns a request into the JSON document ``fcgrasp plan --json`` writes.

Every front end builds a request from its own input (the command line from argv, the
batch runner from keyword options, the explorer from a JSON body) and calls
:func:`plan_document`; none of them imports another.  A request is checked whole when it
is built (types, values, options of another gripper, outputs that would overwrite an
input), with one message per problem naming the option, so every front end refuses the
same requests with the same words.  It is a frozen dataclass: picklable, so a batch
sends it to its workers as it is.
"""

from __future__ import annotations

import re
from collections.abc import Callable
from dataclasses import asdict, dataclass, field, fields, replace
from typing import Any

from ..core._checks import check_margin
from ..core.budget import DEFAULT_TIME_LIMIT, stopped_words
from ..errors import RequestError
from ..grippers.base import DEFAULT_MU, Gripper, SearchOptions, gripper_from_options
from ..grippers.solids import check_on, no_grasp_reason_on, parameters_on, title_on
from ..io.limits import Limits
from ..io.outputs import check_outputs
from ..io.parts import Part, load_part
from ..io.report import duration, plan_report
from ..io.units import FILE_UNITS, UNITS, disturbance_step
from ..model.loads import ACCEL_SHAPES
from ..model.ranking import MEASURES
from ..model.regions import DEFAULT_MARGIN_DEG
from ._options import (
    LOAD_OPTIONS,
    PLAN_OPTIONS,
    READING_OPTIONS,
    SEARCH_OPTIONS,
    _check_kind,
    _fail,
)
from .planner import default_distinct, friction_curve, plan

__all__ = ["PlanRequest", "PlanDocument", "plan_document", "template_request",
           "PLAN_OPTIONS", "READING_OPTIONS", "LOAD_OPTIONS", "SEARCH_OPTIONS"]


@dataclass(frozen=True)
class PlanRequest:
    """One plan to make: the part, the gripper and its parameters, the search, the
    outputs.  The fields are ``fcgrasp plan``'s options (``--rank-by`` is ``rank_by``),
    typed: pairs and triples are tuples of numbers (``stroke=(10, 50)``), ``max_memory``
    is bytes.  ``None`` is "not given" (the gripper's default).

    ``part`` is a file path, ``-`` (standard input) or ``demo:NAME``; ``gripper`` a name
    in :data:`fcgrasp.grippers.base.REGISTRY` (``fingers``: point fingers, ``jaw``: a
    parallel jaw); ``json`` and ``plot`` are output paths (``json="-"``: standard
    output).  Building one checks it whole: :class:`TypeError` for a value of the wrong
    type, :class:`~fcgrasp.errors.RequestError` (a ValueError, with the ``field`` it is
    about) for a value out of range, an option the gripper does not take, or an output
    that is an input.

    >>> r = PlanRequest(part="demo:blob", fingers=3, mu=0.5, top=3)
    >>> r.gripper_object().name, r.search_options("mm").top
    ('three_fingers', 3)
    >>> PlanRequest(part="demo:blob", gripper="jaw", stroke=(50, 10), pad=8)
    Traceback (most recent call last):
    ...
    fcgrasp.errors.RequestError: stroke must have min_opening <= max_opening, got (50.0, 10.0)
    """

    part: str = "demo:blob"
    gripper: str = "fingers"
    fingers: int | None = None
    mu: float | None = None
    gravity: tuple[float, float] | None = None
    stroke: tuple[float, float] | None = None
    pad: float | None = None
    certify: bool | None = None
    top: int = 10
    single_edge: bool = False
    soft: bool = False
    rank_by: str = "min_region"
    margin: float = DEFAULT_MARGIN_DEG
    workspace: tuple[float, float, float] | None = None
    finger_radius: float = 0.0
    hand: str | None = None
    thickness: float | None = None
    table: bool = False
    rest: int | None = None
    rest_orientation: tuple[float, float, float, float] | None = None
    in_plane: bool = False
    max_memory: int | None = None
    time_limit: float | None = None
    distinct: float | None = None
    mass: float | None = None
    com: tuple[float, float] | None = None
    accel: tuple[float, float] | None = None
    accel_shape: str = "box"
    force_limit: float | None = None
    total_force: float | None = None
    placement_sigma: float | None = None
    pose_sigma: tuple[float, float, float] | None = None
    stiffness: float | None = None
    grip_force: float | None = None
    mu_high: float | None = None
    bound: bool = False
    select: str | None = None
    units: str | None = None
    file_units: str | None = None
    flatten: float | None = None
    layer: str | None = None
    gap: float | None = None
    pixel_size: float | None = None
    threshold: float | None = None
    y_down: bool = False
    simplify: float | None = None
    no_clean: bool = False
    max_bytes: int | None = None
    max_elements: int | None = None
    max_vertices: int | None = None
    repair: bool = False
    json: str | None = None
    plot: str | None = None
    _gripper: Any = field(default=None, init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        for f in fields(self):
            if f.init:
                value = getattr(self, f.name)
                if f.name in ("top", "margin", "finger_radius", "part", "gripper",
                              "rank_by", "single_edge", "y_down", "no_clean",
                              "soft", "bound", "repair") \
                        and value is None:
                    raise TypeError(f"{f.name} must be given, got None")
                object.__setattr__(self, f.name, _check_kind(f.name, value))
        self._check_values()
        self._check_outputs()
        try:
            built = gripper_from_options(self.gripper, self.plan_options())
        except RequestError:
            raise
        except ValueError as exc:             # about the option its message names first
            named = re.match(r"--([a-z-]+)", str(exc))
            raise _fail(named.group(1).replace("-", "_") if named else "gripper",
                        str(exc)) from None
        object.__setattr__(self, "_gripper", built)

    def _check_values(self) -> None:
        try:
            check_margin(self.margin, "--margin")
        except ValueError:
            raise _fail("margin", f"--margin is an angle in degrees in [0, 90), got "
                                  f"{self.margin:g}") from None
        if self.top < 1:
            raise _fail("top", f"--top must be at least 1, got {self.top}")
        if self.rank_by not in MEASURES:
            raise _fail("rank_by", f"--rank-by must be one of {', '.join(MEASURES)}, got "
                                   f"{self.rank_by!r}")
        if self.units is not None and self.units not in UNITS:
            raise _fail("units", f"--units must be one of {', '.join(UNITS)}, got "
                                 f"{self.units!r}")
        if self.file_units is not None and self.file_units not in FILE_UNITS:
            raise _fail("file_units", f"--file-units must be one of {', '.join(FILE_UNITS)}, "
                                      f"got {self.file_units!r}")
        if self.distinct is not None and not 0 <= self.distinct <= 1:
            raise _fail("distinct", f"--distinct is a fraction in [0, 1], got {self.distinct:g}")
        for name in ("mass", "force_limit", "total_force"):
            value = getattr(self, name)
            if value is not None and not value > 0:
                raise _fail(name, f"--{name.replace('_', '-')} must be > 0, got {value:g}")
        if self.mass is None and self.rank_by == "payload":
            raise _fail("rank_by", "--rank-by payload ranks by the load a plan carries: give "
                                   "the load's --mass too")
        if self.mass is None:
            for name in ("com", "accel", "force_limit", "total_force"):
                if getattr(self, name) is not None:
                    raise _fail(name, f"--{name.replace('_', '-')} describes a load: give "
                                      f"its --mass too")
        if self.placement_sigma is not None and (not self.placement_sigma > 0
                                                  or self.gripper == "jaw"
                                                  or self.fingers not in (None, 2)):
            raise _fail("placement_sigma", f"--placement-sigma is a distance > 0 for two "
                                           f"fingers, got {self.placement_sigma:g}")
        if self.pose_sigma is not None and (min(self.pose_sigma) < 0
                                            or max(self.pose_sigma) <= 0
                                            or self.gripper == "jaw"
                                            or self.gravity is not None):
            raise _fail("pose_sigma", f"--pose-sigma is three deviations >= 0, not all 0 (x, "
                                      f"y, degrees), for point fingers without gravity, got "
                                      f"{self.pose_sigma}")
        if self.stiffness is not None and (not self.stiffness > 0 or self.gripper == "jaw"
                                           or self.gravity is not None):
            raise _fail("stiffness", f"--stiffness is the fingers' spring stiffness > 0 (N per "
                                     f"unit of the part), for point fingers without "
                                     f"gravity, got {self.stiffness:g}")
        if self.grip_force is not None and (self.stiffness is None
                                            or not self.grip_force > 0):
            raise _fail("grip_force", f"--grip-force is the fingers' total squeeze > 0 in "
                                      f"newtons, with --stiffness, got {self.grip_force:g}")
        self._check_solid()
        if self.bound and (self.gripper == "jaw" or self.gravity is not None
                           or self.fingers not in (3, 4) or self.is_solid()
                           or (self.fingers == 3 and self.mu == 0)):
            raise _fail("bound", f"--bound proves an upper bound on the best smallest region "
                                 f"of three fingers with friction or four frictionless "
                                 f"fingers (--fingers 3 or 4, no --gravity) on a planar "
                                 f"part, got {self._what()}")
        if self.mu_high is not None:
            lo = DEFAULT_MU if self.mu is None else self.mu
            if self.gripper == "jaw" or self.gravity is not None \
                    or self.fingers not in (None, 2, 3) or not self.mu_high > lo:
                raise _fail("mu_high", f"--mu LOW:HIGH is a friction range of two or three "
                                       f"fingers with LOW < HIGH, got {lo:g}:"
                                       f"{self.mu_high:g}")
        if self.accel is not None and min(self.accel) < 0:
            raise _fail("accel", f"--accel is two half-widths >= 0, got {self.accel}")
        if self.accel_shape not in ACCEL_SHAPES:
            raise _fail("accel_shape", f"--accel-shape is {' or '.join(ACCEL_SHAPES)}, got "
                                       f"{self.accel_shape!r}")
        if self.time_limit is not None and not self.time_limit >= 0:
            raise _fail("time_limit", f"--time-limit is a number of seconds >= 0 (0: no "
                                      f"limit), got {self.time_limit:g}")
        if self.max_memory is not None and self.max_memory < 1:
            raise _fail("max_memory", f"--max-memory must be a positive size, got "
                                      f"{self.max_memory}")

    def _what(self) -> str:
        """The gripper asked for, in a few words (for error messages)."""
        if self.gripper != "fingers":
            return f"--gripper {self.gripper}"
        what = f"--fingers {self.fingers if self.fingers is not None else 2}"
        if self.gravity is not None:
            what += " with --gravity"
        if self.is_solid():
            what += f" on a solid ({self.part})"
        return what

    def _check_solid(self) -> None:
        """A solid part takes a gripper that plans solids (its class has ``solid_plans``:
        two fingers with friction, as soft fingers, ``soft`` or not; three fingers with
        friction; a parallel jaw), with the options its solid plans take (the class's
        ``solid_options``), each other option given refused by name; ``soft`` only where
        the gripper's contacts on a solid are soft (``solid_contact``).  On a planar part
        ``soft`` changes nothing: a soft finger's torsional friction turns about the
        contact's normal, an axis in the plane, which no planar motion turns about."""
        if not self.is_solid():
            return
        from ..grippers.base import gripper_type
        from ..grippers.solids import plans_solids

        cls = gripper_type(self.gripper, self.plan_options())
        if cls is None or not plans_solids(cls) or \
                (self.soft and getattr(cls, "solid_contact", None) != "soft"):
            raise _fail("fingers" if self.gripper == "fingers" else "gripper",
                        "a solid part (a mesh) is planned for two soft fingers (--fingers 2) "
                        "or three fingers with friction (--fingers 3 --mu MU), or a parallel "
                        "jaw (--gripper jaw); frictionless fingers hold planar parts only, "
                        f"got {self._what()}")
        takes = set(getattr(cls, "solid_options", ()))
        defaults = {f.name: f.default for f in fields(self) if f.init}
        given = [name for name in (*PLAN_OPTIONS, *LOAD_OPTIONS)
                 if name not in takes and name not in ("gripper", "fingers")
                 and getattr(self, name) != defaults[name]]
        if given:
            flags = [f"--{o.replace('_', '-')}" for o in (*PLAN_OPTIONS, *SEARCH_OPTIONS)
                     if o in takes]
            named = ["--mu LOW:HIGH" if g == "mu_high" else "--" + g.replace("_", "-")
                     for g in given]
            title = getattr(cls, "solid_title", self.gripper)
            raise _fail(given[0], f"on a solid ({self.part}) the options of {title} "
                                  f"are{_listed(flags)}, not {' '.join(named)}")

    def _check_outputs(self) -> None:
        check_outputs(self.json, self.plot, [self.part])

    # ------------------------------------------------------------------ views of it
    def gripper_object(self) -> Gripper:
        """The gripper the request names, built from its options (checked)."""
        return self._gripper

    def distinct_fraction(self) -> float:
        """The ``distinct`` fraction the plans get: the one given, or the gripper's
        default (:func:`fcgrasp.planning.planner.default_distinct`: 0.5 for every
        built-in gripper).

        >>> jaw = PlanRequest(part="demo:blob", gripper="jaw", stroke=(5, 60), pad=8)
        >>> jaw.distinct_fraction()
        0.5
        >>> PlanRequest(part="demo:blob", distinct=0.3).distinct_fraction()
        0.3
        """
        return default_distinct(self._gripper) if self.distinct is None else self.distinct

    def search_time_limit(self) -> float | None:
        """The time budget of the search in seconds (None: no limit).

        >>> PlanRequest().search_time_limit(), PlanRequest(time_limit=0).search_time_limit()
        (10.0, None)
        """
        if self.time_limit is None:
            return DEFAULT_TIME_LIMIT
        return None if self.time_limit == 0 else self.time_limit

    def plan_options(self) -> dict[str, Any]:
        """The planning options (:data:`PLAN_OPTIONS`), as given."""
        return {**{k: getattr(self, k) for k in PLAN_OPTIONS}, "units": self.units}

    def is_solid(self) -> bool:
        """The part is a solid: a mesh file or a built-in solid (``demo:box``...)."""
        from ..io.meshes import is_solid_source

        return is_solid_source(self.part)

    def load_object(self) -> Any:
        """The load the request describes (``--mass`` and the options with it), a
        :class:`fcgrasp.Load`; None without ``--mass``."""
        if self.mass is None:
            return None
        from ..model.loads import Load

        return Load(self.mass, com=self.com, accel=self.accel or (0.0, 0.0),
                    accel_shape=self.accel_shape)

    def limits(self) -> Limits:
        """The readers' limits the request gives (:mod:`fcgrasp.io.limits`)."""
        return Limits.given(self.max_bytes, self.max_elements, self.max_vertices)

    def reading(self) -> dict[str, Any]:
        """The reading options as :func:`fcgrasp.io.parts.load_part` keywords."""
        kw = {k: getattr(self, k) for k in READING_OPTIONS if k not in ("select",
                                                                         "no_clean")}
        kw["clean"] = not self.no_clean
        return kw

    def options(self) -> dict[str, Any]:
        """Every option but the part and the outputs, JSON-ready: what a batch records
        with each result (and compares on a rerun)."""
        out = {k: v for k, v in asdict(self).items()
               if k not in ("part", "json", "plot", "_gripper")}
        return {k: list(v) if isinstance(v, tuple) else v for k, v in sorted(out.items())}

    def search_options(self, units: str, progress: Callable[[int, int], None] | None = None,
                       map: Any = None) -> SearchOptions:
        """The search's options for a part in ``units`` (the resistance measure moves the
        part by :func:`fcgrasp.io.units.disturbance_step` and 15 degrees)."""
        return SearchOptions(top=self.top, rank_by=self.rank_by, margin=self.margin,
                             disturbance=(disturbance_step(units), 15.0),
                             max_memory=self.max_memory, progress=progress, map=map)

    def to_argv(self) -> list[str]:
        """The ``fcgrasp plan`` options that make this request (the part and the outputs
        left out): every option that differs from its default, in the request's order.

        >>> PlanRequest(fingers=4, single_edge=True, margin=2.0).to_argv()
        ['--fingers', '4', '--single-edge', '--margin', '2.0']
        """
        argv: list[str] = []
        for f in fields(self):
            if not f.init or f.name in ("part", "json", "plot"):
                continue
            value = getattr(self, f.name)
            if value == f.default or f.name == "mu_high":
                continue
            if f.name == "mu" and self.mu_high is not None:     # a range: --mu LOW:HIGH
                argv += ["--mu", f"{value!r}:{self.mu_high!r}"]
                continue
            flag = "--part" if f.name == "select" else "--" + f.name.replace("_", "-")
            if isinstance(value, bool):
                argv.append(flag if value else "--no-" + flag[2:])
            elif isinstance(value, tuple):
                argv += [flag, ",".join(repr(v) for v in value)]
            else:
                argv += [flag, repr(value) if isinstance(value, float) else str(value)]
        return argv

    def replace(self, **changes: Any) -> PlanRequest:
        """A copy with some options changed (checked again)."""
        return replace(self, **changes)

    def load(self, say: Callable[[str], None] | None = None) -> Part:
        """Read the request's part (a drawing's outline, or a mesh's solid: its
        ``shape``); when the file holds several, which one was taken and the reader's
        notes are said with ``say``."""
        part = load_part(self.part, self.select, **self.reading())
        if say is not None:
            for line in part.notices():
                say(line)
        return part


@dataclass
class PlanDocument:
    """What a request plans for one part: the ``report`` (the JSON document), the plans,
    the part's polygon and units, why there is no plan (``reason``) and a figure title."""

    report: dict[str, Any]
    plans: list[Any]
    polygon: Any
    units: str
    reason: str | None
    title: str


def plan_document(request: PlanRequest, part: Any = None,
                  progress: Callable[[int, int], None] | None = None,
                  say: Callable[[str], None] | None = None, map: Any = None) -> PlanDocument:
    """Plan a request: read its part (or take ``part``, a
    :class:`~fcgrasp.io.parts.Part` already read: an outline or a solid), plan it with
    its gripper and build the JSON document ``fcgrasp plan --json`` writes.
    ``progress(done, total)`` is told how the search goes, ``say(text)`` gets notes
    (which part of a file was taken, a long search's estimate), ``map`` solves
    candidate batches elsewhere (see :func:`fcgrasp.plan`).  Every front end plans
    through this function, so a batch's and the explorer's results are exactly those
    of ``fcgrasp plan --json``.

    >>> doc = plan_document(PlanRequest(part="demo:blob", top=1))
    >>> doc.report["parameters"]["fingers"], len(doc.report["grasps"])
    (2, 1)
    """
    if not isinstance(request, PlanRequest):
        raise TypeError(f"request must be a PlanRequest, got {type(request).__name__}")
    gripper = request.gripper_object()
    part = request.load(say) if part is None else part
    polygon, units = part.shape, part.units
    if polygon is None:
        raise ValueError(f"{part.source}: part {part.index} is not usable: {part.error}")
    options = request.search_options(units, progress, map)
    # ranked by payload, the search ranks by the smallest region (fcgrasp.plan re-ranks)
    size = check_on(gripper, polygon, replace(options, rank_by="min_region")
                    if options.rank_by == "payload" else options)
    # with a top and the smallest region, the exact pruning stops far sooner than
    # solving every candidate (seconds where this estimate says hours)
    pruned = options.top is not None and options.rank_by == "min_region"
    if size is not None and size.seconds > 60 and say is not None and not pruned:
        say(f"fcgrasp: {size.rows:.3g} candidate edge sets on {size.features} edges: about "
            f"{duration(size.seconds)} (--simplify TOL or fewer fingers is faster)")
    load = request.load_object()
    plans = plan(polygon, gripper=gripper, top=options.top, rank_by=options.rank_by,
                 margin=options.margin, disturbance=options.disturbance,
                 max_memory=options.max_memory, progress=progress, map=map,
                 distinct=request.distinct_fraction(), load=load,
                 force_limit=None if load is None else request.force_limit,
                 total_force=None if load is None else request.total_force,
                 time_limit=request.search_time_limit())
    params = parameters_on(gripper, polygon, options, plans)
    if request.distinct_fraction():
        params["distinct"] = request.distinct_fraction()
    if load is not None:
        params["load"] = {
            "mass_kg": load.mass, "com": None if load.com is None else list(load.com),
            "accel_m_s2": list(load.accel), "accel_shape": load.accel_shape,
            "gravity_m_s2": list(load.gravity),
            "force_limit_n": request.force_limit, "total_force_n": request.total_force}
    reason = None if plans else _stopped_reason(plans) or \
        no_grasp_reason_on(gripper, polygon, request.margin)
    report = plan_report(polygon, plans, params, units, reason, source=part.to_dict())
    mu_range = None
    if request.mu_high is not None:
        fingers: Any = gripper                 # two or three with friction (checked)
        mu_range = (float(fingers.mu), request.mu_high)
        report["parameters"]["mu_range"] = list(mu_range)
        report["friction_curve"] = friction_curve(
            polygon, mu_range, fingers=fingers.fingers, margin=options.margin,
            hand=fingers.hand, along_boundary=fingers.along_boundary).to_dict()
    if request.placement_sigma is not None:
        from ..model.robustness import placement_probability

        report["parameters"]["placement_sigma"] = request.placement_sigma
        for p, entry in zip(plans, report["grasps"], strict=True):
            entry["probability"] = placement_probability(polygon, p, request.placement_sigma,
                                                         mu_range=mu_range)
    if request.pose_sigma is not None:
        from ..model.robustness import pose_probability

        report["parameters"]["pose_sigma"] = list(request.pose_sigma)
        for p, entry in zip(plans, report["grasps"], strict=True):
            entry["pose_probability"] = pose_probability(
                polygon, p, request.pose_sigma, placement_sigma=request.placement_sigma,
                mu_range=mu_range).to_dict()
    if request.stiffness is not None:
        from ..model.stability import DEFAULT_GRIP_FORCE, plan_stability

        force = DEFAULT_GRIP_FORCE if request.grip_force is None else request.grip_force
        report["parameters"]["stiffness"] = request.stiffness
        report["parameters"]["grip_force_n"] = force
        for p, entry in zip(plans, report["grasps"], strict=True):
            entry["stability"] = plan_stability(polygon, p, request.stiffness,
                                                grip_force=force).to_dict()
    if request.bound:
        from ..model.bounds import optimum_upper_bound

        fingers_: Any = gripper                 # three with friction or four (checked)
        best = max((p.min_length for p in plans), default=0.0)
        report["optimality"] = optimum_upper_bound(
            polygon, fingers_.fingers, fingers_.mu if fingers_.fingers == 3 else 0.0,
            margin=options.margin, lower=best).to_dict()
    return PlanDocument(report, plans, polygon, units, reason,
                        f"{request.part}: {title_on(gripper, polygon)}")


def _listed(flags: list[str]) -> str:
    """`` --a, --b and --c`` (nothing for no flags)."""
    if not flags:
        return ""
    return " " + (flags[0] if len(flags) == 1 else ", ".join(flags[:-1]) + " and " + flags[-1])


def _stopped_reason(plans: Any) -> str | None:
    """Why a search that stopped early has no plan (None: it did not stop early)."""
    if getattr(plans, "complete", True):
        return None
    return f"the search stopped at {stopped_words(plans.stopped, raises=True)} before it " \
        f"proved a plan"


def template_request(options: dict[str, Any]) -> PlanRequest:
    """A batch's options as one request, checked before any work on a built-in part;
    each part's request is this one with its part."""
    return PlanRequest(part="demo:quad", **options)
