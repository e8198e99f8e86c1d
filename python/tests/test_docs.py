"""docs/python.md's examples run as they stand, from a folder holding the repository's scenes."""
import contextlib
import io
import os
import re

import pytest
from conftest import SRC

DOC = os.path.join(SRC, "docs", "python.md")


def python_blocks():
    text = open(DOC).read()
    return re.findall(r"^```python\n(.*?)^```$", text, flags=re.S | re.M)


def test_there_are_examples():
    assert len(python_blocks()) >= 8


@pytest.mark.parametrize("index", range(len(python_blocks())))
def test_example_runs(index, tmp_path, monkeypatch):
    os.symlink(os.path.join(SRC, "scenes"), tmp_path / "scenes")
    monkeypatch.chdir(tmp_path)
    code = python_blocks()[index]
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        exec(compile(code, "%s block %d" % (DOC, index), "exec"), {"__name__": "__main__"})
    # Where an example says what it prints ("print(x)  # shown"), it prints that.
    printed = out.getvalue().split("\n")
    for call in re.finditer(r"^print\((.*)\)\s+# (.+)$", code, flags=re.M):
        shown = call.group(2)
        if "..." in shown:
            shown = shown.split("...")[0].rstrip()
        assert any(line.startswith(shown) for line in printed), (call.group(0), printed)
