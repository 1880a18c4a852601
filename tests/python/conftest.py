"""Shared by the Python module's tests: where the sources, the program and a scratch folder are."""

import os
import pathlib
import subprocess

import pytest

SOURCE = pathlib.Path(os.environ["FABMESH_SOURCE_DIR"])
BINARY = os.environ["FABMESH_BINARY"]


def example(name):
    return str(SOURCE / "configs" / "examples" / name)


def corpus(name):
    return str(SOURCE / "tests" / "data" / "check-corpus" / name)


def without_timings(value):
    """A report with its timings left out (they differ from run to run)."""
    if isinstance(value, dict):
        return {k: without_timings(v) for k, v in value.items() if not k.startswith("timings")}
    if isinstance(value, list):
        return [without_timings(v) for v in value]
    return value


def cli(*arguments):
    """Runs the command line; returns (exit code, stdout)."""
    done = subprocess.run([BINARY, *arguments], capture_output=True, text=True, check=False)
    return done.returncode, done.stdout


@pytest.fixture
def scratch(tmp_path):
    return tmp_path
