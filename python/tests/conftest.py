"""Where the `vcnc` command line is, for the tests that compare the module
with it: $VCNC_BIN, else the workspace's target directory."""

import os
import pathlib

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]


@pytest.fixture(scope="session")
def vcnc_bin() -> str:
    candidates = [os.environ.get("VCNC_BIN", "")]
    candidates += [str(ROOT / "target" / p / "vcnc") for p in ("debug", "release")]
    for c in candidates:
        if c and os.access(c, os.X_OK):
            return c
    pytest.fail("no vcnc binary: run `cargo build -p vcnc` or set VCNC_BIN")
