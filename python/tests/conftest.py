# Fixtures of the Python module's tests: the CLI beside the module, phantoms made once per session.
# SPDX-License-Identifier: GPL-3.0-or-later
import os
import shutil
import subprocess
from pathlib import Path

import pytest


def cli_path():
    path = os.environ.get("C4D_CLI") or shutil.which("contour4d")
    if not path:
        pytest.fail("C4D_CLI is not set and contour4d is not on PATH (ctest sets it)")
    return path


def run_cli(*args, check=True):
    """Runs the contour4d command line; returns the CompletedProcess."""
    p = subprocess.run([cli_path(), *map(str, args)], capture_output=True, text=True)
    if check and p.returncode != 0:
        raise AssertionError(f"contour4d {' '.join(map(str, args))} exited {p.returncode}: {p.stderr}")
    return p


@pytest.fixture(scope="session")
def cli():
    return run_cli


@pytest.fixture(scope="session")
def data_dir():
    d = Path(os.environ.get("C4D_DATA", Path(__file__).resolve().parents[3] / "shared" / "data"))
    if not d.is_dir():
        pytest.fail(f"../shared/data is missing beside the checkout ({d}); the real-data tests need it")
    return d


@pytest.fixture(scope="session")
def phantoms(tmp_path_factory):
    """Phantom folders by name (contours.json and truth/), each made once."""
    root = tmp_path_factory.mktemp("phantoms")
    made = {}

    def make(name, *extra):
        key = (name, *extra)
        if key not in made:
            out = root / "_".join([name, *[str(e).strip("-") for e in extra]])
            run_cli("phantom", name, "-o", out, *extra)
            made[key] = out
        return made[key]

    return make
