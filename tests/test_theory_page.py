"""The theory page's snippets run as the page says they do, and name only what the
package has."""

import re
from pathlib import Path

import numpy as np

import fcgrasp as fc

PAGE = Path(__file__).resolve().parents[1] / "docs" / "guide" / "theory.md"


def test_every_snippet_runs():
    blocks = re.findall(r"```python\n(.*?)```", PAGE.read_text(), flags=re.S)
    assert len(blocks) >= 3
    for code in blocks:
        exec(compile(code, str(PAGE), "exec"), {"np": np, "fc": fc})


def test_every_name_it_gives_exists():
    names = set(re.findall(r"`fc\.([A-Za-z_]+)", PAGE.read_text()))
    assert len(names) >= 15
    assert sorted(n for n in names if not hasattr(fc, n)) == []
