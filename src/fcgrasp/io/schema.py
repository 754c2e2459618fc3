"""The JSON Schema of a plan report (``format_version`` 3), shipped in the package.

:func:`schema` reads ``fcgrasp/schema/plan-report.schema.json``; :func:`validate`
checks a report against it with ``jsonschema`` (an optional dependency: ``pip install
jsonschema``), raising :class:`~fcgrasp.errors.ArgumentError` with the path of the first
field that does not fit.  Every report the command line, the batch runner and the
explorer write validates (tested for every gripper on planar parts and solids).

>>> from fcgrasp.planning import PlanRequest, plan_document
>>> validate(plan_document(PlanRequest(part="demo:quad", top=1)).report)
"""

from __future__ import annotations

import json
from functools import cache
from importlib import resources
from typing import Any

from ..errors import ArgumentError

__all__ = ["schema", "validate"]


@cache
def _text() -> str:
    return resources.files("fcgrasp").joinpath("schema", "plan-report.schema.json") \
        .read_text(encoding="utf-8")


def schema() -> dict[str, Any]:
    """The plan report's JSON Schema (draft 2020-12), a fresh copy."""
    out: dict[str, Any] = json.loads(_text())
    return out


def validate(report: dict[str, Any]) -> None:
    """Check ``report`` (a plan report, as written: a JSON document or the dictionary it
    was made from) against :func:`schema`; an ArgumentError names the first field that
    does not fit."""
    try:
        import jsonschema  # type: ignore[import-untyped]
    except ImportError as exc:  # pragma: no cover - depends on the install
        raise ImportError("validating a report needs jsonschema: pip install jsonschema") \
            from exc
    from ..core._json import json_ready

    doc = json.loads(json.dumps(json_ready(report)))
    validator = jsonschema.Draft202012Validator(schema())
    errors = sorted(validator.iter_errors(doc), key=lambda e: list(e.absolute_path))
    if errors:
        first = errors[0]
        where = "/".join(str(p) for p in first.absolute_path) or "(the document)"
        raise ArgumentError(f"report does not fit the plan report schema at {where}: "
                            f"{first.message[:200]}", "report")
