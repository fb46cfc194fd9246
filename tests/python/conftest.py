"""Paths shared by the Python module's tests (set by ctest; see CMakeLists.txt)."""
import os
import pathlib

import pytest

SOURCE = pathlib.Path(os.environ.get("TOUCHCLOUD_SOURCE_DIR", pathlib.Path(__file__).parents[2]))
CLI = pathlib.Path(os.environ.get("TOUCHCLOUD_CLI", SOURCE / "build/bin/touchcloud"))


@pytest.fixture
def source():
    return SOURCE


@pytest.fixture
def cli():
    return CLI
