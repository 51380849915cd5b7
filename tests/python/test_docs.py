# The Python examples of docs/python.md run as written (from the repository root, as the page says).
import os
import pathlib
import re

import pytest

from conftest import SOURCE_DIR

PAGE = SOURCE_DIR / "docs" / "python.md"
BLOCKS = re.findall(r"```python\n(.*?)```", PAGE.read_text(), re.S)


def test_page_has_examples():
    assert len(BLOCKS) >= 4


@pytest.mark.parametrize("index", range(len(BLOCKS)))
def test_example_runs(index, monkeypatch, tmp_path):
    monkeypatch.chdir(SOURCE_DIR)
    code = BLOCKS[index].replace("/tmp/ball_on_board.glb", str(tmp_path / "ball_on_board.glb"))
    # As a script runs: an example guarded by `if __name__ == "__main__":` (as Dask wants) runs its body.
    exec(compile(code, f"{PAGE}:example {index}", "exec"), {"__name__": "__main__"})
