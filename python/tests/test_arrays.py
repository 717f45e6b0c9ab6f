"""A lift law from numpy arrays in memory: cam.table's angles and lifts, the file's checks."""
import math

import numpy as np
import pytest

import mechgraph

SCENE = """
nodes:
  ref:   { type: cam.kurz, params: { max_lift: 8 mm, action_angle: 130 deg, accel_angle: 18 deg, base_radius: 17 mm } }
  table: { type: cam.table, params: { base_radius: 17 mm } }
outputs: [ table.max_lift, table.duration, ref.svaj ]
"""


def test_a_table_from_arrays_follows_the_law_it_samples(tmp_path):
    scene = mechgraph.Scene.from_text(SCENE)
    svaj = scene.run(outputs=["ref.svaj"]).table("ref.svaj")
    angle = svaj["cam_angle [rad]"].to_numpy()
    lift = svaj["lift [m]"].to_numpy()
    r = scene.run(set={"table.angles": angle, "table.lifts": lift}, si=True,
                  outputs=["table.max_lift", "table.duration", "ref.duration", "table.max_acceleration", "ref.max_acceleration"])
    # the spline through 361 samples of the Kurz law gives back its lift and event
    assert math.isclose(r["table.max_lift"], 0.008, rel_tol=1e-6)
    assert math.isclose(r["table.duration"], r["ref.duration"], rel_tol=1e-6)
    assert math.isclose(r["table.max_acceleration"], r["ref.max_acceleration"], rel_tol=2e-2)

    # the same rows through a file give the same law
    csv = tmp_path / "lift.csv"
    csv.write_text("".join(f"{math.degrees(a)!r},{h * 1e3!r}\n" for a, h in zip(angle, lift)))
    f = mechgraph.Scene.from_text(SCENE).run(set={"table.file": str(csv)}, outputs=["table.max_lift"])
    assert math.isclose(f["table.max_lift"], r["table.max_lift"], rel_tol=1e-12)


def test_the_file_checks_apply_to_arrays():
    scene = mechgraph.Scene.from_text(SCENE)
    angle = np.radians(np.linspace(-65, 65, 41))
    lift = 0.008 * np.cos(np.linspace(-np.pi / 2, np.pi / 2, 41)) ** 2
    with pytest.raises(mechgraph.EvaluationError, match="increase"):
        scene.run(set={"table.angles": angle[::-1], "table.lifts": lift}, si=True, outputs=["table.max_lift"])
    bad = lift.copy()
    bad[5] = -1e-6
    with pytest.raises(mechgraph.EvaluationError, match="negative"):
        scene.run(set={"table.angles": angle, "table.lifts": bad}, si=True, outputs=["table.max_lift"])
    with pytest.raises(mechgraph.EvaluationError, match="as long"):
        scene.run(set={"table.angles": angle, "table.lifts": lift[:-1]}, si=True, outputs=["table.max_lift"])
    with pytest.raises(mechgraph.EvaluationError, match="no table"):
        scene.run(outputs=["table.max_lift"])
    with pytest.raises(mechgraph.SceneError):
        scene.run(set={"table.angles": angle * np.nan, "table.lifts": lift}, si=True, outputs=["table.max_lift"])


def test_arrays_go_to_list_parameters_only_and_are_checked_whole():
    scene = mechgraph.Scene.from_text(SCENE)
    angle = np.radians(np.linspace(-65, 65, 53))
    with pytest.raises(mechgraph.SceneError, match="did you mean 'angles'"):
        scene.run(set={"table.angle": angle}, outputs=["table.max_lift"])
    with pytest.raises(mechgraph.SceneError, match="not an array"):
        scene.run(set={"table.base_radius": angle}, outputs=["table.max_lift"])
    with pytest.raises(mechgraph.SceneError, match="scene parameter"):
        scene.run(set={"lift": angle}, outputs=["table.max_lift"])
    inf = angle.copy()
    inf[7] = np.inf
    with pytest.raises(mechgraph.SceneError, match="element 7"):
        scene.run(set={"table.angles": inf, "table.lifts": angle}, si=True, outputs=["table.max_lift"])


def test_a_long_table_is_written_in_place_not_through_text():
    # 20,001 rows: passed as the array itself (no YAML of 20,001 numbers); the law is the same as
    # for 2,001 rows of the same curve to the interpolation's accuracy.
    scene = mechgraph.Scene.from_text(SCENE)
    results = []
    for n in (2001, 20001):
        angle = np.radians(np.linspace(-65, 65, n))
        lift = 9e-3 * np.cos(np.pi * np.degrees(angle) / 130) ** 2
        lift[0] = lift[-1] = 0.0
        r = scene.run(set={"table.angles": angle, "table.lifts": lift, "table.base_radius": "30 mm"}, si=True,
                      outputs=["table.max_lift"])
        results.append(r["table.max_lift"])
        assert r.provenance["overrides"][0] == f"table.angles=<{n} values, SI>"
    assert math.isclose(results[0], 9e-3, rel_tol=1e-9)
    assert math.isclose(results[1], 9e-3, rel_tol=1e-9)
