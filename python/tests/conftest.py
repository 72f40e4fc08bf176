"""Shared fixtures: the compiled module must be importable (PYTHONPATH=<repo>/python:<build>/python,
as set by ctest); PACKLAB_BINARY (set by ctest) names the command line for cross checks."""

import os
import shutil
import subprocess

import pytest

import packlab

if packlab._core_error is not None:  # fail loudly: the tests are about the compiled module
    raise ImportError(f"packlab._core is not importable: {packlab._core_error}")


@pytest.fixture
def cli():
    """Runs the packlab command line; skips when it is not built."""
    binary = os.environ.get("PACKLAB_BINARY") or shutil.which("packlab")
    if not binary or not os.path.exists(binary):
        pytest.skip("packlab binary not found (set PACKLAB_BINARY)")

    def run(*args, check=True):
        result = subprocess.run([binary, *map(str, args)], capture_output=True, text=True)
        if check and result.returncode != 0:
            raise AssertionError(f"packlab {' '.join(map(str, args))} failed: {result.stderr}")
        return result

    return run
