"""docs/python.md's examples run as written, in a folder where configs/examples/ is where they look."""

import os
import re

import pytest

from conftest import SOURCE

BLOCKS = re.findall(r"```python\n(.*?)```", (SOURCE / "docs" / "python.md").read_text(), re.S)


def test_the_page_has_its_examples():
    assert len(BLOCKS) >= 5


@pytest.mark.parametrize("index", range(len(BLOCKS)))
def test_example_runs(index, tmp_path):
    (tmp_path / "configs").symlink_to(SOURCE / "configs")
    here = os.getcwd()
    os.chdir(tmp_path)
    try:
        exec(compile(BLOCKS[index], f"docs/python.md example {index + 1}", "exec"), {})
    finally:
        os.chdir(here)
