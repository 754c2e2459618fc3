"""The gripper interface and its registry.

A gripper is one object that knows its parameters (checked when it is built), how to
search a part for its plans, and how its plans are described: :class:`Gripper` is that
interface (a :class:`typing.Protocol`: any class with these members is a gripper, no
base class needed).  :func:`fcgrasp.plan` dispatches once, ``gripper.plan(polygon,
options)``; :class:`~fcgrasp.planning.PlanRequest` builds a gripper from its flat options
through :data:`REGISTRY`, so adding a gripper is one new module and one
:func:`register` line.

The paper's grippers (sections 6-8) are in :mod:`~fcgrasp.grippers.fingers` (two or
three fingers with friction, three frictionless fingers with gravity, four frictionless
fingers) and :mod:`~fcgrasp.grippers.jaw` (a parallel jaw).
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any, Protocol, runtime_checkable

from ..core._checks import check_int, check_margin, check_tol
from ..core.tolerances import SOLVER_TOL
from ..model.ranking import MEASURES
from ..model.regions import DEFAULT_MARGIN_DEG

__all__ = ["Gripper", "SearchOptions", "REGISTRY", "register", "gripper_from_options",
           "DEFAULT_MU"]

#: The friction coefficient of a request that gives none (fingers with friction, the
#: parallel jaw, soft fingers on a solid).
DEFAULT_MU = 0.3


@dataclass(frozen=True)
class SearchOptions:
    """What every gripper's search takes besides the part: how many plans (``top``,
    None: all), the ranking measure, the safety ``margin`` in degrees, the resistance
    measure's ``disturbance`` (translation, rotation in degrees), the solver's relative
    ``tol``, the memory budget in bytes, a ``progress(done, total)`` callback and a
    ``map(function, batches)`` to solve candidate batches elsewhere.  A gripper uses the
    ones that apply to it; the others keep their defaults."""

    top: int | None = 10
    rank_by: str = "min_region"
    margin: float = DEFAULT_MARGIN_DEG
    disturbance: tuple[float, float] = (10.0, 15.0)
    tol: float = SOLVER_TOL
    max_memory: int | None = None
    progress: Callable[[int, int], None] | None = None
    map: Any = None

    def __post_init__(self) -> None:
        if self.top is not None:
            object.__setattr__(self, "top", check_int(self.top, "top", minimum=1))
        if not isinstance(self.rank_by, str):
            raise TypeError(f"rank_by must be a string, got {self.rank_by!r}")
        if self.rank_by not in MEASURES:
            raise ValueError(f"rank_by must be one of {', '.join(MEASURES)}, got "
                             f"{self.rank_by!r}")
        object.__setattr__(self, "margin", check_margin(self.margin))
        object.__setattr__(self, "tol", check_tol(self.tol))
        if self.progress is not None and not callable(self.progress):
            raise TypeError(f"progress must be a callable progress(done, total) or None, "
                            f"got {self.progress!r}")


@runtime_checkable
class Gripper(Protocol):
    """What every gripper provides.

    ``name``: its registry name; ``plan(polygon, options)``: its plans of a part, best
    first (the candidates -> solve -> rank search of section 7, or the jaw's boxes);
    ``check_part(polygon, options)``: refuse at once what it cannot plan (a ValueError),
    and return an estimate of the search's size (or None);
    ``parameters(options)``: its parameters and the search options it uses, as recorded
    in a plan document's JSON;
    ``no_grasp_reason(margin)``: one line saying why a part has no plan;
    ``title``: how a figure names it.

    Optional members, read with ``getattr``: ``default_distinct``, the ``distinct``
    fraction its plans get when none is given (0, the ranked list, where absent; every
    built-in gripper's is 0.5: its plans are distinct alternatives by default);
    ``distinct_plans(polygon,
    plans, fraction)``, what distinct means for its plans (regions of contact where
    absent); ``distinct_search(polygon, options, fraction)``, a search for distinct
    plans of its own (or None where it does not apply); ``distinct_depth``, how many
    times ``top`` plans ``distinct=`` reads at most.  A gripper that plans solid parts
    has ``solid_plans(solid, options, fraction)``, ``solid_parameters(options)``,
    ``solid_title`` and ``solid_no_grasp_reason(margin)``
    (:mod:`fcgrasp.grippers.solids`); one without them refuses a solid by name.
    """

    @property
    def name(self) -> str: ...

    def plan(self, polygon: Any, options: SearchOptions) -> list[Any]: ...

    def check_part(self, polygon: Any, options: SearchOptions) -> Any: ...

    def parameters(self, options: SearchOptions) -> dict[str, Any]: ...

    def no_grasp_reason(self, margin: float) -> str: ...

    @property
    def title(self) -> str: ...


#: Builders of grippers from a plan request's flat options, by the request's gripper
#: name: ``REGISTRY[name](options)`` returns a :class:`Gripper` or raises
#: :class:`~fcgrasp.errors.RequestError` naming the option that does not fit.
REGISTRY: dict[str, Callable[[Mapping[str, Any]], Gripper]] = {}


#: The classes of the registered grippers, by name: ``TYPES[name](options)`` is the
#: class the builder makes, chosen by the options of its kind alone (:func:`gripper_type`).
TYPES: dict[str, Callable[[Mapping[str, Any]], type | None]] = {}


def register(name: str, builder: Callable[[Mapping[str, Any]], Gripper],
             kind: Callable[[Mapping[str, Any]], type | None] | None = None) -> None:
    """Make ``name`` a gripper of plan requests (``--gripper NAME``), built by
    ``builder(options)`` from the request's options (a mapping of option name to value,
    None where not given); ``kind(options)``: the class it builds, from the options
    that choose it alone (:func:`gripper_type`)."""
    if not isinstance(name, str) or not name:
        raise ValueError(f"name must be a non-empty string, got {name!r}")
    if not callable(builder):
        raise TypeError(f"builder must be callable, got {builder!r}")
    if kind is not None and not callable(kind):
        raise TypeError(f"kind must be callable or None, got {kind!r}")
    REGISTRY[name] = builder
    if kind is not None:
        TYPES[name] = kind


#: The built-in grippers' modules, imported (and so registered) when a request first
#: names them: a plan of point fingers does not pay the jaw's import.
BUILT_IN = {"fingers": "fcgrasp.grippers.fingers", "jaw": "fcgrasp.grippers.jaw"}


def _register_built_in(name: str | None = None) -> None:
    import importlib

    for key, module in BUILT_IN.items():
        if (name is None or key == name) and key not in REGISTRY:
            importlib.import_module(module)


def gripper_type(name: str, options: Mapping[str, Any]) -> type | None:
    """The class of the gripper ``gripper_from_options(name, options)`` would build,
    chosen by its kind's options alone (``fingers``, ``gravity``), its parameters
    unread: what a front end asks of a gripper before they are given (whether it plans
    solids, the options it takes there).  None for a gripper registered without its
    ``kind``."""
    _register_built_in(name if name in BUILT_IN else None)
    kind = TYPES.get(name)
    return None if kind is None else kind(options)


def gripper_from_options(name: str, options: Mapping[str, Any]) -> Gripper:
    """The gripper a request names, built from its options (see :func:`register`; the
    built-in grippers register when first named)."""
    _register_built_in(name if name in BUILT_IN else None)
    if name not in REGISTRY:
        raise ValueError(f"gripper must be one of {', '.join(sorted(REGISTRY))}, got "
                         f"{name!r}")
    return REGISTRY[name](options)
