"""The tutorial of docs/python.md runs as written (each ```python block, in order, in a
fresh folder; blocks guarded by `if __name__ == "__main__":` are compiled only)."""

from __future__ import annotations

import os
import pathlib
import re

import pytest

DOC = pathlib.Path(__file__).resolve().parents[2] / "docs" / "python.md"


def blocks():
    if not DOC.is_file():
        return []
    return re.findall(r"```python\n(.*?)```", DOC.read_text(), flags=re.S)


@pytest.mark.skipif(not DOC.is_file(), reason="docs/python.md is not beside the tests")
@pytest.mark.parametrize("i", range(len(blocks())))
def test_the_tutorial_block_runs(i, tmp_path, capsys):
    code = blocks()[i]
    here = os.getcwd()
    os.chdir(tmp_path)
    try:
        exec(compile(code, f"docs/python.md block {i + 1}", "exec"), {"__name__": "docs"})
    finally:
        os.chdir(here)
    capsys.readouterr()


def test_the_tutorial_has_blocks():
    if DOC.is_file():
        assert len(blocks()) >= 6
