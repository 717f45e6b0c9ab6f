"""The example notebooks run from top to bottom (nbclient, a python3 kernel) as a user opens them:
plots inline (no backend forced, MPLBACKEND removed), each cell that plots gives an image, and a
copy outside the repository stops at once with a clear error instead of searching for the
repository's top folder forever."""
import os
import pathlib
import shutil
import time

import nbformat
import pytest
from nbclient import NotebookClient
from nbclient.exceptions import CellExecutionError

from conftest import SOURCE

NOTEBOOKS = sorted((SOURCE / "examples" / "notebooks").glob("*.ipynb"))


def execute(path, cwd, timeout=240):
    nb = nbformat.read(path, as_version=4)
    client = NotebookClient(nb, timeout=timeout, kernel_name="python3", resources={"metadata": {"path": str(cwd)}})
    client.execute()
    return nb


def plots(cell):
    return cell.cell_type == "code" and ("plt." in cell.source or "fig." in cell.source)


@pytest.mark.parametrize("path", NOTEBOOKS, ids=[p.stem for p in NOTEBOOKS])
def test_notebook_runs_and_every_plot_cell_shows_an_image(path, monkeypatch):
    monkeypatch.delenv("MPLBACKEND", raising=False)  # as in Jupyter: the kernel's inline backend
    nb = execute(path, path.parent)
    code = [c for c in nb.cells if c.cell_type == "code"]
    errors = [o for c in code for o in c.get("outputs", []) if o.get("output_type") == "error"]
    assert not errors
    plotting = [c for c in code if plots(c)]
    assert plotting
    for cell in plotting:
        images = [o for o in cell.get("outputs", []) if "image/png" in o.get("data", {})]
        assert images, "a plot cell without an image:\n" + cell.source[:200]
    source = "".join(c.source for c in code)
    assert 'matplotlib.use("Agg")' not in source and "%matplotlib inline" in source


def test_a_copy_outside_the_repository_stops_with_a_clear_error(tmp_path, monkeypatch):
    monkeypatch.delenv("MECHGRAPH_SOURCE_DIR", raising=False)
    monkeypatch.delenv("MPLBACKEND", raising=False)
    for path in NOTEBOOKS:
        copy = tmp_path / path.name
        shutil.copy(path, copy)
        start = time.monotonic()
        with pytest.raises(CellExecutionError) as e:
            execute(copy, tmp_path, timeout=60)
        assert "FileNotFoundError" in str(e.value) and "MECHGRAPH_SOURCE_DIR" in str(e.value)
        assert time.monotonic() - start < 60


def test_a_copy_finds_the_scenes_through_mechgraph_source_dir(tmp_path, monkeypatch):
    monkeypatch.setenv("MECHGRAPH_SOURCE_DIR", str(SOURCE))
    monkeypatch.delenv("MPLBACKEND", raising=False)
    copy = tmp_path / "cam_optimisation.ipynb"
    shutil.copy(SOURCE / "examples" / "notebooks" / "cam_optimisation.ipynb", copy)
    nb = nbformat.read(copy, as_version=4)
    nb.cells = nb.cells[:2]  # loading the scene is what the search is for
    nbformat.write(nb, copy)
    execute(copy, tmp_path)


def test_there_are_notebooks():
    assert {p.stem for p in NOTEBOOKS} >= {"cam_optimisation", "backlash_study"}
