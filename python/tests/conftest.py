"""Shared paths: the source tree (scenes), the build tree (the `mechgraph` program)."""
import os
import pathlib

import pytest

SOURCE = pathlib.Path(os.environ.get("MECHGRAPH_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))
BINARY = pathlib.Path(os.environ.get("MECHGRAPH_BINARY_DIR", SOURCE / "build"))


@pytest.fixture(scope="session")
def scenes():
    return SOURCE / "scenes"


@pytest.fixture(scope="session")
def cli():
    return BINARY / "bin" / "mechgraph"
