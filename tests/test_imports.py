"""``import fcgrasp`` stays light: no scipy.optimize, matplotlib or reader
library until used; the version literal matches the package metadata."""

from __future__ import annotations

import subprocess
import sys
import tomllib
from pathlib import Path

HEAVY = ("scipy.optimize", "scipy.spatial", "matplotlib", "svgelements", "ezdxf", "skimage",
         "importlib.metadata")


def test_import_fcgrasp_loads_no_heavy_module():
    code = f"import sys, fcgrasp; print(','.join(m for m in {HEAVY!r} if m in sys.modules))"
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert r.stdout.strip() == "", r.stdout


def test_version_matches_pyproject():
    import fcgrasp

    meta = tomllib.loads((Path(__file__).parents[1] / "pyproject.toml").read_text())
    assert fcgrasp.__version__ == meta["project"]["version"]


def _type_checking_names() -> dict[str, str]:
    """The names the ``if TYPE_CHECKING:`` block of fcgrasp/__init__.py imports, each with
    its module (what a type checker sees)."""
    import ast

    tree = ast.parse((Path(__file__).parents[1] / "src" / "fcgrasp" / "__init__.py")
                     .read_text())
    out: dict[str, str] = {}
    for node in tree.body:
        if isinstance(node, ast.If) and getattr(node.test, "id", "") == "_TYPE_CHECKING":
            for imp in node.body:
                assert isinstance(imp, ast.ImportFrom) and imp.level == 1
                out.update({a.name: imp.module for a in imp.names})
    return out


def test_the_public_names_are_one_list():
    """The lazy table, __all__, the type checkers' imports and dir() agree, and every
    public name loads from the module the table says."""
    import importlib

    import fcgrasp

    lazy = fcgrasp._LAZY
    assert fcgrasp.__all__ == ["TOL", "__version__", *lazy]
    assert _type_checking_names() == lazy
    assert dir(fcgrasp) == sorted(fcgrasp.__all__)
    for name, module in lazy.items():
        mod = importlib.import_module(f"fcgrasp.{module}")
        assert getattr(fcgrasp, name) is getattr(mod, name)
        assert name in getattr(mod, "__all__", [name]), (name, module)
    assert not {"Any", "TYPE_CHECKING", "import_module"} & set(dir(fcgrasp))


def _prints_ok(code):
    """Run ``code`` in a fresh interpreter: it must print ``ok``."""
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=600)
    assert r.returncode == 0 and r.stdout.strip() == "ok", r.stderr


def test_the_jaw_is_imported_on_first_use():
    """A plan of point fingers does not import the jaw; asking the package for it (as
    ``hasattr`` and Sphinx do, before anything imported it) imports it once, with no
    recursion."""
    code = ("import sys, fcgrasp as fc, fcgrasp.grippers as g\n"
            "fc.plan(fc.read_part('demo:blob'), fingers=2, mu=0.3, top=1)\n"
            "assert 'fcgrasp.grippers.jaw' not in sys.modules\n"
            "assert hasattr(g, 'jaw') and g.ParallelJaw is g.jaw.ParallelJaw\n"
            "assert not hasattr(g, 'no_such_gripper')\n"
            "print('ok')")
    _prints_ok(code)


def test_a_plane_part_plans_without_the_solids_programs():
    """``fcgrasp plan demo:blob`` asks the mesh reader whether the part is a solid, which
    needs :mod:`fcgrasp.spatial.solid` only: the package imports each of its modules on
    first use (the soft fingers' cone programs and the triples cost 16 ms of every plane
    plan's start-up); every public name still resolves to its module's."""
    code = ("import sys\n"
            "from fcgrasp.apps.cli import main\n"
            "assert main(['plan', 'demo:blob', '--quiet']) in (0, None)\n"
            "heavy = [m for m in ('fcgrasp.spatial.regions', 'fcgrasp.spatial.triples',\n"
            "                     'fcgrasp.spatial.jaw', 'fcgrasp.spatial.quality')\n"
            "         if m in sys.modules]\n"
            "assert not heavy, heavy\n"
            "import fcgrasp.spatial as s\n"
            "assert sorted(s._LAZY) == sorted(s.__all__) == dir(s)\n"
            "assert s.soft_pair_plans is sys.modules['fcgrasp.spatial.surfaces'].soft_pair_plans\n"
            "assert not hasattr(s, 'no_such_name')\n"
            "print('ok')")
    _prints_ok(code)
