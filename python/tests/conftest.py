# Shared fixtures of the Python module's tests (python/CMakeLists.txt runs them from ctest with
# PYTHONPATH=build/python, STRAHL_CLI and STRAHL_SOURCE_DIR set).
import os
import subprocess

import pytest


@pytest.fixture
def cli():
    """Runs the strahl CLI built beside the module; skips where it is not known."""
    path = os.environ.get("STRAHL_CLI")
    if not path or not os.path.exists(path):
        pytest.skip("STRAHL_CLI is not set (run through ctest)")

    def run(*args, check=True):
        result = subprocess.run([path, *map(str, args)], capture_output=True, text=True, timeout=120)
        if check and result.returncode != 0:
            raise AssertionError(f"strahl {' '.join(map(str, args))} failed ({result.returncode}): {result.stderr}")
        return result

    return run


@pytest.fixture
def source_dir():
    path = os.environ.get("STRAHL_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
    return os.path.abspath(path)
