"""Contact files (the input of ``fcgrasp check``): contacts on a part, read strictly."""

from __future__ import annotations

import json
import os
import sys
from pathlib import Path
from typing import Any

import numpy as np

from ..core.contacts import FrictionlessPoint, FrictionPoint, Gravity
from ..core.tolerances import ON_EDGE_TOL
from ..model.polygon import Polygon
from ._read_json import read_json

# ----------------------------------------------------------------------------- contact files

_CONTACTS_KEYS = {"contacts", "gravity"}
_CONTACT_KEYS = {"point", "type", "mu", "edge", "normal", "vertex"}
_GRAVITY_KEYS = {"direction"}


def _unknown(d: dict[str, Any], allowed: set[str], where: str) -> None:
    extra = sorted(set(d) - allowed)
    if extra:
        raise ValueError(f"{where}: unknown key {extra[0]!r} (expected "
                       f"{', '.join(sorted(allowed))})")


def _index(value: Any, name: str, where: str, upto: int) -> int:
    if isinstance(value, bool) or not isinstance(value, int) or not 0 <= value < upto:
        raise ValueError(f"{where}: {name} must be an index from 0 to {upto - 1}, got "
                       f"{json.dumps(value)}")
    return value


def _number_pair(value: Any, name: str, where: str) -> np.ndarray:
    if (not isinstance(value, list) or len(value) != 2
            or not all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in value)
            or not all(np.isfinite(value))):
        raise ValueError(f"{where}: {name} must be [x, y] finite numbers, got "
                       f"{json.dumps(value)}")
    return np.asarray(value, dtype=float)


def read_contacts(path: str | os.PathLike[str], polygon: Polygon
                  ) -> tuple[list[Any], list[dict[str, Any]]]:
    """Read a contacts file (the input of ``fcgrasp check``) for ``polygon``.

    Layout: ``{"contacts": [{"point": [x, y], "type": "friction", "mu": 0.3,
    "edge": 2}, ...], "gravity": {"direction": [0, -1]}}``; ``type`` is ``friction``,
    ``frictionless`` or ``soft`` (a soft finger on the convex vertex ``"vertex": k``, the
    start of edge ``k``); the normal comes from ``edge``, the nearest edge, or
    ``"normal"``.  Read strictly: an unknown key is a :class:`ValueError` naming it.

    Returns the contacts (for :class:`~fcgrasp.Grasp`) and their JSON description.
    """
    path = os.fspath(path)
    try:
        raw = sys.stdin.buffer.read() if path == "-" else Path(path).read_bytes()
    except FileNotFoundError:
        raise ValueError(f"{path}: no such file") from None
    except OSError as exc:
        raise ValueError(f"{path}: cannot read ({exc.strerror or exc})") from None
    return contacts_from_data(read_json(raw, path), polygon, path)


def contacts_from_data(data: Any, polygon: Polygon, where: str = "contacts"
                       ) -> tuple[list[Any], list[dict[str, Any]]]:
    """Contacts from the decoded JSON of a contacts file (see :func:`read_contacts`),
    checked as strictly; ``where`` names the source in error messages.

    >>> from fcgrasp.io.parts import demo_part
    >>> cs, _ = contacts_from_data({"contacts": [{"point": [0, 15], "mu": 0.3}]},
    ...                            demo_part("rectangle"))
    >>> type(cs[0]).__name__, cs[0].normal.tolist() == [-1, 0]
    ('FrictionPoint', True)
    """
    path = where
    if isinstance(data, dict):
        _unknown(data, _CONTACTS_KEYS, path)
    items = data.get("contacts") if isinstance(data, dict) else data
    if not isinstance(items, list) or not items:
        raise ValueError(f"{path}: expected {{'contacts': [...]}} with at least one contact")
    contacts: list[Any] = []
    described: list[dict[str, Any]] = []
    for k, c in enumerate(items):
        where = f"{path} contacts[{k}]"
        if not isinstance(c, dict):
            raise ValueError(f"{where}: expected an object, got {type(c).__name__}")
        _unknown(c, _CONTACT_KEYS, where)
        kind = c.get("type", "friction" if "mu" in c else "frictionless")
        mu = c.get("mu", 0.0)
        if not isinstance(mu, (int, float)) or isinstance(mu, bool) or not mu >= 0 \
                or not np.isfinite(mu):
            raise ValueError(f"{where}: mu must be a finite number >= 0, got {json.dumps(mu)}")
        if kind == "soft":
            if "vertex" not in c:
                raise ValueError(f"{where}: a soft contact needs 'vertex' (a vertex index)")
            k_v = _index(c["vertex"], "vertex", where, polygon.n_edges)
            try:
                contacts.append(polygon.soft_finger_at(k_v, mu))
            except ValueError as exc:
                raise ValueError(f"{where}: {exc}") from None
            described.append({"type": "soft", "vertex": k_v, "point": polygon.starts[k_v],
                              "mu": mu})
            continue
        if kind not in ("friction", "frictionless"):
            raise ValueError(f"{where}: type must be friction, frictionless or soft, got "
                           f"{json.dumps(kind)}")
        if "vertex" in c:
            raise ValueError(f"{where}: 'vertex' goes with a soft contact, not {kind}")
        if "point" not in c:
            raise ValueError(f"{where}: missing 'point'")
        pt = _number_pair(c["point"], "point", where)
        if "normal" in c:
            n = _number_pair(c["normal"], "normal", where)
            if not np.any(n):
                raise ValueError(f"{where}: normal must be a non-zero vector")
            edge = None if "edge" not in c else _index(c["edge"], "edge", where,
                                                       polygon.n_edges)
        else:
            dist = polygon.distance_to_edges(pt)
            if "edge" in c:
                e = _index(c["edge"], "edge", where, polygon.n_edges)
                if not polygon.usable[e]:
                    raise ValueError(f"{where}: edge {e} has zero length")
            else:
                e = int(np.argmin(dist))
            d_e = float(dist[e])
            if d_e > ON_EDGE_TOL * polygon.size:
                raise ValueError(f"{where}: point {pt.tolist()} is not on edge {e} "
                               f"(distance {d_e:.3g})")
            n = polygon.normals[e]
            edge = e
        if kind == "friction":
            contacts.append(FrictionPoint(pt, n, mu))
        else:
            contacts.append(FrictionlessPoint(pt, n))
        described.append({"type": kind, "point": pt, "normal": n, "edge": edge, "mu": mu})
    g = data.get("gravity") if isinstance(data, dict) else None
    if g is not None:
        if not isinstance(g, dict):
            raise ValueError(f"{path}: gravity must be an object such as "
                           f'{{"direction": [0, -1]}}, got {json.dumps(g)}')
        _unknown(g, _GRAVITY_KEYS, f"{path} gravity")
        direction = _number_pair(g.get("direction", [0, -1]), "direction", f"{path} gravity")
        if not np.any(direction):
            raise ValueError(f"{path} gravity: direction must be a non-zero vector")
        contacts.append(Gravity(polygon.centroid, direction))
        described.append({"type": "gravity", "point": polygon.centroid, "direction": direction})
    return contacts, described
