"""Shared fixtures of the Python module's tests.

The tests import `curvemesh` from PYTHONPATH (ctest points it at the build tree's package,
build/python) and compare with the command line, found by the environment:

    CURVEMESH_EXE        the curvemesh executable (default: build/curvemesh)
    CURVEMESH_EXAMPLES   the bundled drawings (default: examples/ of this repository)
"""
import os
import pathlib
import subprocess

import pytest

REPO = pathlib.Path(__file__).resolve().parents[2]


def pytest_configure(config):
    config.addinivalue_line("markers", "timing: measures wall time; run alone (ctest: python_threads_timing)")


@pytest.fixture(scope="session")
def repo():
    return REPO


@pytest.fixture(scope="session")
def exe():
    path = pathlib.Path(os.environ.get("CURVEMESH_EXE", REPO / "build" / "curvemesh"))
    if not path.is_file():
        pytest.fail(f"the curvemesh executable {path} is missing (set CURVEMESH_EXE)")
    return path


@pytest.fixture(scope="session")
def examples():
    path = pathlib.Path(os.environ.get("CURVEMESH_EXAMPLES", REPO / "examples"))
    if not path.is_dir():
        pytest.fail(f"the examples folder {path} is missing (set CURVEMESH_EXAMPLES)")
    return path


@pytest.fixture(scope="session")
def run_cli(exe):
    """Runs `curvemesh ARGS...`; returns the CompletedProcess (text)."""

    def run(*args, check=True):
        result = subprocess.run([str(exe), *map(str, args)], capture_output=True, text=True, timeout=600)
        if check and result.returncode != 0:
            raise AssertionError(f"curvemesh {' '.join(map(str, args))} failed: {result.stderr}")
        return result

    return run
