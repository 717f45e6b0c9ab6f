"""mechgraph.dask.sweep on a LocalCluster of two worker processes equals Scene.sweep row for row."""
import numpy as np
import pandas as pd
import pytest

import mechgraph
import mechgraph.dask

distributed = pytest.importorskip("distributed")


def test_dask_sweep_equals_the_single_process_sweep(scenes):
    scene = mechgraph.Scene.load(scenes / "valvetrain_cams.yaml")
    rpm = np.linspace(4000, 8000, 37)
    r0 = np.where(np.arange(37) == 11, 3.0, 17.0)  # one infeasible case, a failed row
    # units three ways: a header, a (values, unit) pair, numbers marked SI; each chunk keeps them
    # and text cells under a name without a unit: the column shows the unit of its first number
    # (mm) in every chunk, though each chunk but the first starts with a cell in m
    lash = ["0.00025 m" if i % 8 == 0 and i > 0 else "0.3 mm" if i % 2 else "0.25 mm" for i in range(37)]
    cases = {"rpm [rpm]": rpm, "r0": (r0, "mm"), "lift": mechgraph.si(np.linspace(0.007, 0.009, 37)), "lash": lash}
    outputs = ["arc.min_curvature_radius", "v_kurz.max_acceleration", "ta_kurz.time_area"]
    local = scene.sweep(cases, outputs=outputs, threads=1)
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster, \
            distributed.Client(cluster) as client:
        remote = mechgraph.dask.sweep(client, scene, cases, chunk=8, outputs=outputs)
        workers = client.run(lambda: sorted(__import__("mechgraph.dask").dask._worker_scenes.keys()))
    assert len(workers) == 2
    assert list(remote.columns) == list(local.columns)
    assert "lash [mm]" in local.columns and local["lash [mm]"].iloc[8] == 0.25
    pd.testing.assert_frame_equal(remote.reset_index(drop=True), local.reset_index(drop=True), check_exact=True)
    assert (remote["exit"] != 0).sum() == 1


def test_dask_study_equals_the_single_process_study(monkeypatch):
    # An uncertainty study's cases on the workers (mechgraph.dask.study) give Scene.study's answers
    # bit for bit; the workers find the test plugin by MECHGRAPH_PLUGIN_PATH.
    from conftest import BINARY, SOURCE

    plugins = str(BINARY / "test_plugins" / "test_uq")
    monkeypatch.setenv("MECHGRAPH_PLUGIN_PATH", plugins)
    mechgraph.load_plugins()
    try:
        scene = mechgraph.Scene.load(SOURCE / "tests" / "uncertainty" / "ishigami.yaml")
        local = scene.study(samples=64, threads=1)
        with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster, \
                distributed.Client(cluster) as client:
            remote = mechgraph.dask.study(client, scene, samples=64, chunk=50)
            # Parameters with units: the samples' columns are the sweep's (`x1 [mm]`, in mm) on both paths.
            linear = mechgraph.Scene.from_text(
                "params: { x1: 0 mm, x2: 0 mm, x3: 0 mm }\n"
                "nodes:\n  f: { type: test.linear, params: { x1: $x1, x2: $x2, x3: $x3 } }\noutputs: [f.y]\n")
            distributions = {"x1": {"normal": {"mean": "1 mm", "sigma": "0.1 mm"}}, "x2": {"uniform": {"lower": "0 mm", "upper": "0.6 mm"}}}
            local_linear = linear.study(distributions, samples=40, method="latin_hypercube")
            remote_linear = mechgraph.dask.study(client, linear, distributions, samples=40, method="latin_hypercube", chunk=15)
        assert remote.json == local.json
        assert list(remote.samples.columns) == list(local.samples.columns)
        pd.testing.assert_frame_equal(remote.samples, local.samples, check_exact=True, check_dtype=False)
        assert remote_linear.json == local_linear.json
        assert list(local_linear.samples.columns) == ["x1 [mm]", "x2 [mm]", "f.y [mm]", "exit", "role"]
        pd.testing.assert_frame_equal(remote_linear.samples, local_linear.samples, check_exact=True, check_dtype=False)
    finally:
        monkeypatch.delenv("MECHGRAPH_PLUGIN_PATH")
        mechgraph.load_plugins()


def test_dask_sweep_checks_the_whole_sweeps_budget_before_a_chunk_is_sent(scenes):
    # max_work bounds all the cases together, as Scene.sweep's does: chunks of one case, each within
    # the budget alone, must not let ten cases through. The refusal comes before any submit.
    import re

    scene = mechgraph.Scene.load(scenes / "valvetrain_cams.yaml")
    rpm = np.linspace(4000, 8000, 10)
    with pytest.raises(mechgraph.SceneError) as refused:
        scene.sweep({"rpm [rpm]": rpm[:1]}, max_work=1, progress=False)
    one_case = float(re.search(r"max_work=([0-9.e+]+)", str(refused.value)).group(1))  # the budget one case needs
    budget = 3 * one_case
    assert (scene.sweep({"rpm [rpm]": rpm[:1]}, max_work=budget, progress=False)["exit"] == 0).all()

    class NoCluster:
        def submit(self, *args, **kwargs):
            raise AssertionError("a chunk was sent although the whole sweep is over its budget")

    with pytest.raises(mechgraph.SceneError, match="raise the budget with max_work="):
        mechgraph.dask.sweep(NoCluster(), scene, {"rpm [rpm]": rpm}, chunk=1, max_work=budget, progress=False)
    # Within the budget, the check lets the chunks go.
    with pytest.raises(AssertionError, match="a chunk was sent"):
        mechgraph.dask.sweep(NoCluster(), scene, {"rpm [rpm]": rpm}, chunk=1, max_work=20 * one_case, progress=False)
