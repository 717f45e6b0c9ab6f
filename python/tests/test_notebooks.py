"""The example notebooks run from top to bottom (nbclient, a python3 kernel), so they cannot rot."""
import os
import pathlib
import sys

import nbformat
import pytest
from nbclient import NotebookClient

from conftest import SOURCE

NOTEBOOKS = sorted((SOURCE / "examples" / "notebooks").glob("*.ipynb"))


@pytest.mark.parametrize("path", NOTEBOOKS, ids=[p.stem for p in NOTEBOOKS])
def test_notebook_runs(path, tmp_path):
    nb = nbformat.read(path, as_version=4)
    # the kernel inherits PYTHONPATH (the build tree's package) and MPLBACKEND=Agg from CTest
    client = NotebookClient(nb, timeout=120, kernel_name="python3", resources={"metadata": {"path": str(path.parent)}})
    client.execute()
    errors = [o for c in nb.cells if c.cell_type == "code" for o in c.get("outputs", []) if o.get("output_type") == "error"]
    assert not errors


def test_there_are_notebooks():
    assert {p.stem for p in NOTEBOOKS} >= {"cam_optimisation", "backlash_study"}
