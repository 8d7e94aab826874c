"""Fixtures of the Python module's tests: the CLI to compare with, the repository, the catalog.

Run by ctest (test python_module) with PYTHONPATH=build/python, DYNOSIZE_EXE and
DYNOSIZE_SOURCE_DIR set; by hand from the repository root:
    PYTHONPATH=build/python /usr/bin/python3 -m pytest -q tests/python
"""
import json
import os
import pathlib
import subprocess

import pytest

import dynosize

SOURCE_DIR = pathlib.Path(os.environ.get("DYNOSIZE_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))
EXE = pathlib.Path(os.environ.get("DYNOSIZE_EXE", SOURCE_DIR / "build" / "dynosize"))
SHARED_DATA = SOURCE_DIR.parent / "shared" / "data"


class CliRun:
    def __init__(self, code, out, err):
        self.code, self.out, self.err = code, out, err

    def json(self):
        return json.loads(self.out)

    def message(self):
        """The CLI's error line without its 'dynosize: ' prefix (what the exception carries)."""
        lines = self.err.strip().splitlines()
        assert lines and lines[-1].startswith("dynosize: "), self.err
        return lines[-1][len("dynosize: "):]


def run_cli(*args):
    p = subprocess.run([str(EXE), *map(str, args)], cwd=SOURCE_DIR, capture_output=True, text=True, timeout=300)
    return CliRun(p.returncode, p.stdout, p.stderr)


@pytest.fixture(scope="session")
def catalog():
    return dynosize.Catalog()


@pytest.fixture(scope="session")
def repo():
    return SOURCE_DIR


@pytest.fixture
def cli():
    if not EXE.exists():
        pytest.skip(f"{EXE} not built (cmake --build build --target dynosize)")
    return run_cli
