"""One base for fcgrasp's own exceptions, each carrying the field it is about, and each
still the built-in exception a caller would catch."""

from __future__ import annotations

import pytest

import fcgrasp as fc
from fcgrasp import errors
from fcgrasp.apps._explorer_data import plan_request
from fcgrasp.core.budget import BudgetExhausted
from fcgrasp.io.limits import LimitExceeded
from fcgrasp.io.parts import demo_part
from fcgrasp.planning import PlanRequest


@pytest.mark.parametrize("cls", [errors.ArgumentError, errors.ArgumentTypeError,
                                 errors.RequestError, errors.SearchTooLarge,
                                 errors.OutputError, errors.PartTimeout, LimitExceeded,
                                 BudgetExhausted])
def test_every_exception_has_the_one_base(cls):
    assert issubclass(cls, errors.FcgraspError)


@pytest.mark.parametrize(("call", "cls", "field"), [
    (lambda: fc.plan(demo_part("blob"), mu=-1.0), ValueError, "mu"),
    (lambda: fc.plan(demo_part("blob"), mu="lots"), TypeError, "mu"),
    (lambda: fc.plan(demo_part("blob"), top=0), ValueError, "top"),
    (lambda: fc.plan(demo_part("blob"), margin=95), ValueError, "margin"),
    (lambda: PlanRequest(part="demo:blob", top="3"), TypeError, "top"),
    (lambda: PlanRequest(part="demo:blob", stroke=(1, 2, 3)), TypeError, "stroke"),
])
def test_a_bad_argument_names_its_field(call, cls, field):
    with pytest.raises(cls) as info:
        call()
    assert isinstance(info.value, errors.FcgraspError)
    assert info.value.field == field
    assert field in str(info.value)


def test_the_explorer_reads_the_field_of_the_error_not_its_message():
    with pytest.raises(errors.RequestError) as info:
        plan_request({"gripper": "jaw", "stroke": [1, "x"], "pad": 2})
    assert info.value.field == "stroke"


@pytest.mark.parametrize("exc", [errors.ArgumentError("mu must be >= 0", "mu"),
                                 errors.RequestError("bad stroke", "stroke", 422),
                                 errors.PartTimeout("late"), BudgetExhausted("max_memory"),
                                 LimitExceeded("too many")])
def test_errors_cross_processes_whole(exc):
    import pickle

    back = pickle.loads(pickle.dumps(exc))
    assert type(back) is type(exc) and str(back) == str(exc)
    assert back.field == exc.field
    assert getattr(back, "status", None) == getattr(exc, "status", None)
