"""Units that cannot slip (issue 32, item 2): a bare number for a parameter with a dimension is
refused, naming its dimension and the scene's unit, wherever Python sets parameters (run's set=,
a sweep's columns and fixed values, arrays for list parameters); a unit comes as text, a
(value, unit) pair, a pint quantity or a column header, and SI is said with mechgraph.si() or
si=True. Dimensionless parameters (counts, ratios) keep taking bare numbers."""
import datetime
import decimal
import io
import math

import numpy as np
import pandas as pd
import pint
import pytest

import mechgraph

UREG = pint.UnitRegistry()
Q_ = UREG.Quantity
OUTPUTS = ["v_kurz.max_lift", "ta_kurz.time_area", "kurz.min_curvature_radius"]


def close(a, b, rel=1e-12, abs_=1e-300):
    return math.isclose(a, b, rel_tol=rel, abs_tol=abs_)


@pytest.fixture(scope="module")
def cams(scenes):
    return mechgraph.Scene.load(scenes / "valvetrain_cams.yaml")


def test_the_issues_example_nine_is_refused_and_every_way_of_saying_9_mm_agrees(cams):
    # Before: 9 was 9 m and the run succeeded (valve lift 13.5 m).
    with pytest.raises(mechgraph.SceneError) as e:
        cams.run(set={"kurz.max_lift": 9}, outputs=OUTPUTS)
    message = str(e.value)
    assert "kurz.max_lift" in message and "length" in message and "mm" in message, message
    assert "mechgraph.si" in message and '(9, "mm")' in message
    results = [cams.run(set={"kurz.max_lift": v}, outputs=OUTPUTS)
               for v in ["9 mm", (9, "mm"), mechgraph.si(0.009), Q_(9, "mm"), Q_(0.9, "cm"), (9.0, " mm ")]]
    results.append(cams.run(set={"kurz.max_lift": 0.009}, outputs=OUTPUTS, si=True))
    for label in OUTPUTS:
        values = [r[label] for r in results]
        assert all(close(v, values[0]) for v in values), (label, values)
    assert close(results[0]["v_kurz.max_lift"], 1.5 * 0.009 - 0.00025)


@pytest.mark.parametrize("name, value, dimension, unit", [
    ("rpm", 6500, "angle/time", "rpm"),             # 6500 rad/s before
    ("lift", 9, "length", "mm"),                     # a scene parameter
    ("kurz.action_angle", 130, "angle", "deg"),     # written $action (130 deg)
    ("kurz.base_radius", np.float32(17), "length", "mm"),
    ("drive", decimal.Decimal(4000), "mass/time^2", "N/mm"),
])
def test_a_bare_number_names_its_dimension_and_the_scenes_unit(cams, name, value, dimension, unit):
    with pytest.raises(mechgraph.SceneError) as e:
        cams.run(set={name: value}, outputs=OUTPUTS)
    message = str(e.value)
    assert message.startswith(f"set {name}: ") and dimension in message and f"the scene's unit: {unit}" in message, message


def test_dimensionless_parameters_take_bare_numbers(cams):
    a = cams.run(set={"rocker": 1.6, "kurz.curve_points": 181}, outputs=OUTPUTS)
    b = cams.run(set={"rocker": "1.6", "kurz.curve_points": "181"}, outputs=OUTPUTS)
    assert a["v_kurz.max_lift"] == b["v_kurz.max_lift"]
    assert close(a["v_kurz.max_lift"], 1.6 * 0.008 - 0.00025)


def test_pint_quantities_convert_to_si(cams):
    a = cams.run(set={"rpm": Q_(6500, "rpm"), "kurz.action_angle": Q_(130, "deg"), "drive": Q_(4000, "N/mm")},
                 outputs=OUTPUTS)
    b = cams.run(set={"rpm": "6500 rpm", "kurz.action_angle": "130 deg", "drive": "4000 N/mm"}, outputs=OUTPUTS)
    for label in OUTPUTS:
        assert close(a[label], b[label]), label
    with pytest.raises(mechgraph.SceneError, match="angle"):
        cams.run(set={"kurz.max_lift": Q_(9, "deg")}, outputs=OUTPUTS)     # a unit of the wrong dimension
    with pytest.raises(mechgraph.SceneError, match="ampere"):
        cams.run(set={"kurz.max_lift": Q_(9, "A")}, outputs=OUTPUTS)       # a unit mechgraph does not know
    with pytest.raises(mechgraph.SceneError):
        cams.run(set={"kurz.max_lift": (9, "deg")}, outputs=OUTPUTS)


def test_the_scenes_unit_falls_back_to_its_display_units_then_si():
    text = """
units: {units}
nodes:
  k: {{ type: cam.kurz, params: {{ max_lift: 8 mm, action_angle: 130 deg, accel_angle: 18 deg, base_radius: 17 mm }} }}
outputs: [ k.max_lift ]
"""
    # checking_lift is not written in the scene: the scene's display unit for lengths, else SI
    with pytest.raises(mechgraph.SceneError, match=r"the scene's unit: um; SI: m\)"):
        mechgraph.Scene.from_text(text.format(units="{ length: um }")).run(set={"k.checking_lift": 1})
    with pytest.raises(mechgraph.SceneError, match=r"the scene's unit: m\)"):
        mechgraph.Scene.from_text(text.format(units="{}")).run(set={"k.checking_lift": 1})


TABLE_SCENE = """
nodes:
  ref:   { type: cam.kurz, params: { max_lift: 8 mm, action_angle: 130 deg, accel_angle: 18 deg, base_radius: 17 mm } }
  table: { type: cam.table, params: { base_radius: 17 mm } }
outputs: [ table.max_lift ]
"""


def test_arrays_for_list_parameters_say_their_unit_too():
    scene = mechgraph.Scene.from_text(TABLE_SCENE)
    svaj = scene.run(outputs=["ref.svaj"]).table("ref.svaj")
    angle_deg = np.degrees(svaj["cam_angle [rad]"].to_numpy())
    lift_mm = svaj["lift [m]"].to_numpy() * 1e3
    with pytest.raises(mechgraph.SceneError) as e:
        scene.run(set={"table.angles": angle_deg, "table.lifts": (lift_mm, "mm")})
    assert "angle" in str(e.value) and "(values, " in str(e.value)
    a = scene.run(set={"table.angles": (angle_deg, "deg"), "table.lifts": (lift_mm, "mm")})
    b = scene.run(set={"table.angles": Q_(angle_deg, "deg"), "table.lifts": Q_(lift_mm, "mm")})
    c = scene.run(set={"table.angles": mechgraph.si(np.radians(angle_deg)), "table.lifts": mechgraph.si(lift_mm / 1e3)})
    assert close(a["table.max_lift"], 0.008, rel=1e-6)
    assert close(a["table.max_lift"], b["table.max_lift"]) and close(a["table.max_lift"], c["table.max_lift"], rel=1e-9)
    assert a.provenance["overrides"][0] == f"table.angles=<{len(angle_deg)} values, deg>"
    with pytest.raises(mechgraph.SceneError, match="length"):
        scene.run(set={"table.angles": (angle_deg, "mm"), "table.lifts": (lift_mm, "mm")})


def test_sweep_columns_without_a_unit_are_refused_for_dimensional_parameters(cams):
    with pytest.raises(mechgraph.SceneError) as e:
        cams.sweep({"kurz.max_lift": [8, 9]}, outputs=OUTPUTS)
    message = str(e.value)
    assert message.startswith("cases: column 'kurz.max_lift'") and "length" in message and "[mm]" in message, message
    with pytest.raises(mechgraph.SceneError, match="cases: column 'kurz.max_lift'"):
        cams.sweep(pd.DataFrame({"kurz.max_lift": [8.0, 9.0]}), outputs=OUTPUTS)
    with pytest.raises(mechgraph.SceneError, match="cases: column 'kurz.max_lift'"):
        cams.sweep({"kurz.max_lift": ["8", "9"]}, outputs=OUTPUTS)  # text cells without a unit
    # a fixed value of a sweep follows run()'s rule
    with pytest.raises(mechgraph.SceneError, match="set rpm: 6500 is a bare number"):
        cams.sweep({"kurz.max_lift [mm]": [8, 9]}, set={"rpm": 6500}, outputs=OUTPUTS)


def test_every_way_of_giving_a_columns_unit_gives_the_same_rows(cams):
    ways = [{"kurz.max_lift [mm]": [8, 9]},
            {"kurz.max_lift": ([8, 9], "mm")},
            {"kurz.max_lift": Q_(np.array([8, 9]), "mm")},
            {"kurz.max_lift": [Q_(8, "mm"), (9, "mm")]},
            {"kurz.max_lift": ["8 mm", "9 mm"]},
            {"kurz.max_lift": mechgraph.si(np.array([0.008, 0.009]))}]
    frames = [cams.sweep(w, outputs=OUTPUTS) for w in ways]
    frames.append(cams.sweep({"kurz.max_lift": [0.008, 0.009]}, outputs=OUTPUTS, si=True))
    column = "ta_kurz.time_area [mm^2*s]" if "ta_kurz.time_area [mm^2*s]" in frames[0] else \
        [c for c in frames[0].columns if c.startswith("ta_kurz.time_area")][0]
    for f in frames:
        assert list(f["exit"]) == [0, 0]
        assert np.allclose(f[column].to_numpy(dtype=float), frames[0][column].to_numpy(dtype=float), rtol=1e-12, atol=0)
    assert frames[0][column].iloc[1] > frames[0][column].iloc[0]
    # dimensionless columns take bare numbers
    counts = cams.sweep({"kurz.curve_points": [181, 361], "rocker": [1.5, 1.6]}, outputs=OUTPUTS)
    assert list(counts["exit"]) == [0, 0]
    with pytest.raises(mechgraph.SceneError, match="give one"):
        cams.sweep({"kurz.max_lift [mm]": ([8, 9], "mm")}, outputs=OUTPUTS)


def test_csv_columns_follow_their_headers(cams):
    with pytest.raises(mechgraph.SceneError, match="cases: column 'kurz.max_lift'.*length"):
        cams.sweep(pd.read_csv(io.StringIO("kurz.max_lift,rocker\n8,1.5\n9,1.5\n")), outputs=OUTPUTS)
    rows = cams.sweep(pd.read_csv(io.StringIO("kurz.max_lift [mm],rocker\n8,1.5\n9,1.5\n")), outputs=OUTPUTS)
    assert list(rows["exit"]) == [0, 0]
    # A unit with the angle it counts, as mechgraph's own labels write it, reads as the plain unit.
    from mechgraph._cases import split_header
    assert split_header("kurz.accel_angle [deg (cam)]") == ("kurz.accel_angle", "deg")
    assert split_header("v.speed [mm (cam)]") == ("v.speed", "mm (cam)")  # no degrees: not a tag
    tagged = cams.sweep(pd.read_csv(io.StringIO("kurz.accel_angle [deg (cam)]\n18\n19\n")), outputs=OUTPUTS)
    plain = cams.sweep(pd.read_csv(io.StringIO("kurz.accel_angle [deg]\n18\n19\n")), outputs=OUTPUTS)
    assert list(tagged["exit"]) == [0, 0]
    assert tagged.drop(columns=[c for c in tagged.columns if c.startswith("kurz.accel_angle")]).equals(
        plain.drop(columns=[c for c in plain.columns if c.startswith("kurz.accel_angle")]))


@pytest.mark.parametrize("column, words", [
    (pd.Series(pd.date_range("2020-01-01", periods=2)), "date or time"),
    (pd.Series(pd.to_timedelta([8, 9], unit="ms")), "duration"),
    ([datetime.datetime(2020, 1, 1), datetime.datetime(2020, 1, 2)], "date or time"),
    ([datetime.timedelta(milliseconds=8), datetime.timedelta(milliseconds=9)], "duration"),
])
def test_date_and_duration_columns_are_refused_even_with_si(cams, column, words):
    with pytest.raises(mechgraph.SceneError, match="cases: column 'kurz.max_lift'.*" + words):
        cams.sweep(pd.DataFrame({"kurz.max_lift": column}), outputs=OUTPUTS, si=True)
    with pytest.raises(mechgraph.SceneError, match=words):
        cams.sweep(pd.DataFrame({"kurz.max_lift [mm]": column}), outputs=OUTPUTS)


def test_si_marks_numbers_only():
    with pytest.raises(TypeError):
        mechgraph.si("9 mm")
    with pytest.raises(TypeError):
        mechgraph.si(Q_(9, "mm"))
    assert repr(mechgraph.si(0.009)) == "mechgraph.si(0.009)"
    assert mechgraph.si(mechgraph.si(0.009)).value == 0.009


def test_a_scene_from_a_dict_takes_pint_quantities_and_refuses_bare_lengths():
    def scene(lift):
        return {"nodes": {"k": {"type": "cam.kurz", "params": {"max_lift": lift, "action_angle": Q_(130, "deg"),
                                                               "accel_angle": "18 deg", "base_radius": Q_(17, "mm")}}},
                "outputs": ["k.max_lift"]}

    a = mechgraph.Scene.from_dict(scene(Q_(9, "mm"))).run()
    b = mechgraph.Scene.from_dict(scene("9 mm")).run()
    assert close(a["k.max_lift"], b["k.max_lift"])
    with pytest.raises(mechgraph.SceneError, match="no unit"):
        mechgraph.Scene.from_dict(scene(9)).validate()
