"""Results as a pandas and Jupyter user expects them (issue 32, item 3): a compact repr and an HTML
one, values and tables in the scene's display units, the report's tables as DataFrames, sweeps as
numpy columns, errors whose location, node and parameter are data, documented error classes, and
a docstring for help() on every public name."""
import html.parser
import inspect
import math

import numpy as np
import pandas as pd
import pytest

import mechgraph


def close(a, b, rel=1e-12, abs_=1e-300):
    return math.isclose(a, b, rel_tol=rel, abs_tol=abs_)


@pytest.fixture(scope="module")
def cams(scenes):
    return mechgraph.Scene.load(scenes / "valvetrain_cams.yaml")


@pytest.fixture(scope="module")
def whole(cams):
    return cams.run(set={"rpm": "6500 rpm"})


def test_repr_is_one_short_line_and_html_is_a_table(whole):
    text = repr(whole)
    assert "\n" not in text and len(text) < 400, text   # was one line of 135 items
    assert text.startswith("<Result of ") and "more>" in text

    class Cells(html.parser.HTMLParser):
        def __init__(self):
            super().__init__()
            self.cells, self.tags = [], []

        def handle_starttag(self, tag, attrs):
            self.tags.append(tag)

        def handle_data(self, data):
            self.cells.append(data)

    page = Cells()
    page.feed(whole._repr_html_())
    assert page.tags.count("tr") == len(whole) + 1
    assert "v_kurz.max_acceleration" in page.cells


def test_values_and_tables_in_the_scenes_display_units(scenes):
    # cam_contour.yaml says units: { length: mm, angle: deg }
    scene = mechgraph.Scene.load(scenes / "cam_contour.yaml")
    r = scene.run()
    table_label = next(k for k in r.keys() if r.kind(k) == "table")
    si = r.table(table_label)
    shown = r.table(table_label, units="display")
    assert len(si) == len(shown) and len(si.columns) == len(shown.columns)
    units = [c.split("[")[1].rstrip("]") for c in shown.columns if "[" in c]
    assert units and all(u.startswith(("mm", "deg", "1/mm")) or "mm" in u or "deg" in u for u in units), shown.columns
    for a, b in zip(si.columns, shown.columns):
        si_unit, unit = a.split(" [")[1][:-1], b.split(" [")[1][:-1]
        scale, offset, dimension = mechgraph._core.unit_scale(unit)
        assert np.allclose(shown[b].to_numpy(), si[a].to_numpy() / scale - offset, rtol=1e-14, atol=0), (a, b)
    scalar = next(k for k in r.keys() if r.kind(k) == "scalar" and r.unit(k) == "m")
    assert r.display_unit(scalar) == "mm"
    assert close(r.value(scalar, units="display"), r[scalar] * 1e3)
    assert close(r.value(scalar, units="um"), r[scalar] * 1e6)
    assert r.value(scalar) == r[scalar]  # SI stays the default


def test_a_wrong_unit_is_a_unit_error(whole):
    for bad in ["deg", "furlong", "mm/"]:
        with pytest.raises(mechgraph.UnitError) as e:
            whole.quantity("kurz.max_lift", bad)
        assert isinstance(e.value, ValueError) and e.value.exit_code == 2
    with pytest.raises(mechgraph.UnitError):
        whole.value("kurz.max_lift", units="s")
    assert close(whole.quantity("kurz.max_lift", "mm").display_value, 8.0)


def test_report_tables_are_dataframes_of_numbers(whole):
    tables = whole.report_tables()
    assert len(tables) >= 1
    first = tables[0]
    assert isinstance(first, pd.DataFrame) and first.attrs["title"]
    assert list(first.columns)[0] == "unit" and len(first.columns) == 4  # three cams
    assert all(first[c].dtype == np.float64 for c in first.columns[1:])
    lift = first.loc["tappet lift (cam)"]
    assert lift["unit"] == "mm" and np.allclose(lift.iloc[1:].to_numpy(dtype=float), 8.0, rtol=1e-12)
    # a run of other outputs has no report
    assert whole is not None and mechgraph.Scene.load(whole.provenance["scene"]["file"]).run(
        outputs=["kurz.max_lift"]).report_tables() == []


def test_an_output_not_asked_for_is_evaluated_on_first_use_with_the_runs_values(cams):
    r = cams.run(set={"kurz.max_lift": "9 mm"}, outputs=["ta_kurz.time_area"])
    assert "kurz.svaj" not in r
    frame = r.table("kurz.svaj")                      # not asked for: evaluated now, 9 mm
    assert close(frame["lift [m]"].max(), 0.009, rel=1e-9)
    cams.run(set={"kurz.max_lift": "7 mm"}, outputs=["ta_kurz.time_area"])  # a later run changes nothing here
    assert close(r.table("kurz.svaj")["lift [m]"].max(), 0.009, rel=1e-9)
    assert close(r["kurz.max_lift"], 0.009)
    with pytest.raises(KeyError, match="kurz"):
        r["kurtz.svaj"]


def test_sweeps_return_numpy_columns(cams):
    rows = cams.sweep({"rpm [rpm]": [5000, 6000], "r0 [mm]": [17, 3]}, outputs=["arc.min_curvature_radius"])
    assert rows["case"].dtype == np.int64 and rows["exit"].dtype == np.int64
    assert rows["rpm [rpm]"].dtype == np.float64
    out = [c for c in rows.columns if c.startswith("arc.min_curvature_radius")][0]
    assert rows[out].dtype == np.float64 and math.isnan(rows[out].iloc[1]) and rows[out].iloc[0] > 0
    assert rows["error"].iloc[0] is None and "arc" in rows["error"].iloc[1]


def test_error_fields_are_data_not_parsed_from_messages(tmp_path):
    # A file name that looks like a location: parsing the message would find line 9, column 9.
    bad = tmp_path / "study:9:9: x.yaml"
    bad.write_text("nodes:\n  k: { type: cam.kurtz }\noutputs: [k.law]\n")
    with pytest.raises(mechgraph.SceneError) as e:
        mechgraph.Scene.load(bad).validate()
    assert e.value.location == (str(bad), 2, 14) and e.value.node == "k"
    with pytest.raises(mechgraph.SceneError) as e:
        mechgraph.Scene.from_text("nodes: {k: [1\n", name="a:1:1: b").validate()
    assert e.value.location[0] == "a:1:1: b" and e.value.location[1:] == (1, 15) or e.value.location[1] >= 1


def test_evaluation_errors_name_node_parameter_and_place(cams, scenes):
    with pytest.raises(mechgraph.EvaluationError) as e:
        cams.run(set={"r0": "3 mm", "lift": "14 mm"}, outputs=["arc.min_curvature_radius"])
    assert e.value.node == "arc" and e.value.parameter == "accel_angle"
    file, line, column = e.value.location
    assert file.endswith("valvetrain_cams.yaml") and line > 1 and column > 1
    with pytest.raises(mechgraph.SceneError) as e:
        cams.run(set={"kurz.max_lift": 9})
    assert (e.value.node, e.value.parameter, e.value.location) == ("kurz", "max_lift", None)


def test_a_missing_scene_file_is_also_file_not_found(tmp_path):
    with pytest.raises(FileNotFoundError) as e:
        mechgraph.Scene.load(tmp_path / "absent.yaml")
    assert isinstance(e.value, mechgraph.SceneError) and e.value.exit_code == 2
    assert e.value.filename == str(tmp_path / "absent.yaml") and "absent.yaml" in str(e.value)


@pytest.mark.parametrize("sets, outputs", [
    ({"rmp": "6000 rpm"}, None),
    ({"kurz.max_lfit": "9 mm"}, None),
    ({"krz.max_lift": "9 mm"}, None),
    ({"rpm": "6000 mm"}, None),
    ({"rpm": ["6000 rpm", "7000 rpm"]}, None),
    ({"rpm": "6000 rpm"}, ["kurz.max_lift"]),               # set a value no output needs
    ({"r0": "3 mm", "lift": "14 mm"}, ["arc.min_curvature_radius"]),
    ({"kurz.max_lift": "900 mm"}, ["kurz.min_curvature_radius"]),
])
def test_run_messages_do_not_speak_of_sweeps(cams, capfd, sets, outputs):
    mechgraph.set_log_level("debug")
    try:
        capfd.readouterr()
        try:
            cams.run(set=sets, outputs=outputs)
            message = ""
        except mechgraph.MechgraphError as e:
            message = str(e)
        logged = capfd.readouterr().err
    finally:
        mechgraph.set_log_level("warn")
    for text in (message, logged):
        assert "sweep" not in text.lower() and "swept" not in text.lower() and "--vary" not in text, text


def _public_names():
    import mechgraph.dask

    for name in mechgraph.__all__:
        obj = getattr(mechgraph, name)
        yield f"mechgraph.{name}", obj
        if inspect.isclass(obj):
            for member, value in vars(obj).items():
                if member.startswith("_") or member in ("count", "index"):
                    continue
                if callable(value) or isinstance(value, (property, classmethod, staticmethod)):
                    yield f"mechgraph.{name}.{member}", value
    for name in ("sweep",):
        yield f"mechgraph.dask.{name}", getattr(mechgraph.dask, name)
    yield "mechgraph", mechgraph
    yield "mechgraph.dask", mechgraph.dask


def test_every_public_name_has_a_docstring():
    missing = []
    for name, obj in _public_names():
        target = obj.__func__ if isinstance(obj, (classmethod, staticmethod)) else obj
        target = target.fget if isinstance(target, property) else target
        doc = inspect.getdoc(target)
        if not doc or len(doc) < 20:
            missing.append(name)
    assert not missing, missing


@pytest.mark.parametrize("text", [
    "nodes:\n  k: { type: cam.kurtz }\n",                                                     # unknown node type
    "nodes: {k: [1\n",                                                                          # YAML syntax
    "units: { lenght: mm }\nnodes: {}\n",                                                       # unknown quantity
    "units: { length: deg }\nnodes: {}\n",                                                      # a unit of another dimension
    "nodes:\n  k: { type: cam.kurz, params: { max_lift: 9, action_angle: 130 deg, accel_angle: 18 deg, base_radius: 17 mm } }\n"
    "outputs: [k.max_lift]\n",                                                                   # a length without its unit
    "nodes:\n  k: { type: cam.kurz, params: { max_lift: 9 mm, max_lift: 8 mm } }\n",           # a key given twice
    "nodes:\n  v: { type: valvetrain.time_area, inputs: { valve: nope.motion } }\n",            # an unknown source node
    "title: caf\xe9\nnodes: {}\n",                                                             # not UTF-8 (as bytes)
])
def test_every_scene_error_that_names_a_place_carries_it_as_data(tmp_path, text):
    scene = tmp_path / "scene.yaml"
    scene.write_bytes(text.encode("latin-1"))
    with pytest.raises(mechgraph.SceneError) as e:
        mechgraph.Scene.load(scene).validate()
    message = str(e.value)
    assert message.startswith(str(scene) + ":"), message
    assert e.value.location is not None, message
    file, line, column = e.value.location
    assert message.startswith(f"{file}:{line}:{column}: ") and line >= 1 and column >= 1


def test_a_parameters_scene_error_names_node_and_parameter(tmp_path):
    scene = tmp_path / "scene.yaml"
    scene.write_text("nodes:\n  k: { type: cam.kurz, params: { max_lift: 9, action_angle: 130 deg, accel_angle: 18 deg,"
                     " base_radius: 17 mm } }\noutputs: [k.max_lift]\n")
    with pytest.raises(mechgraph.SceneError) as e:
        mechgraph.Scene.load(scene).validate()
    assert (e.value.node, e.value.parameter, e.value.location[1]) == ("k", "max_lift", 2)
    scene.write_text("nodes:\n  k: { type: cam.kurz, params: { max_lfit: 9 mm } }\noutputs: [k.max_lift]\n")
    with pytest.raises(mechgraph.SceneError) as e:
        mechgraph.Scene.load(scene).validate()
    assert (e.value.node, e.value.parameter) == ("k", "max_lfit") and "max_lift" in str(e.value)


@pytest.mark.parametrize("sets", [{"kurz.curve_points": 1e9}, {"kurz.max_lift": "9 deg"}, {"kurz.ramp": "wavy"},
                                  {"kurz.max_lift": "-9 mm"}])
def test_a_refused_value_names_the_node_and_parameter_it_reached(cams, sets):
    with pytest.raises(mechgraph.SceneError) as e:
        cams.run(set=sets, outputs=["kurz.max_lift"])
    assert (e.value.node, e.value.parameter) == ("kurz", next(iter(sets)).split(".")[1]), str(e.value)


def test_a_scalar_at_rounding_level_shows_as_0_and_keeps_its_value():
    # The midpoint of events at -65 and +65 deg of a symmetric polydyne lobe: rounding noise, shown 0
    # (the same rule as the terminal and the report: core/include/mechgraph/shown_number.hpp).
    scene = mechgraph.Scene.from_text(
        "nodes:\n"
        "  cam: { type: cam.polydyne, params: { max_lift: 8 mm, action_angle: 130 deg, base_radius: 17 mm,"
        " exponents: [2, 14, 26, 38, 50] } }\n"
        "outputs: [ cam.events ]\n")
    r = scene.run()
    noise = float(r["cam.events"]["centreline"][0])
    q = mechgraph.Quantity(noise, "rad", math.degrees(noise), "deg")
    assert str(q) == "0 deg"
    assert str(mechgraph.Quantity(0.92, "rad", math.degrees(0.92), "deg")) == "52.7121 deg"
    assert str(mechgraph.Quantity(1.1e-11, "m", 1.1e-8, "mm")) == "1.1e-08 mm"   # a length alone keeps its digits


UNITLESS_ROWS = """title: rows that name no unit, of ports that name none
nodes:
  kurz: { type: cam.kurz, params: { max_lift: 9 mm, action_angle: 130 deg, accel_angle: 18 deg, base_radius: 17 mm } }
  arc:  { type: cam.three_arc, params: { max_lift: 9 mm, action_angle: 120 deg, base_radius: 18 mm, nose_radius: 6 mm } }
outputs: [ kurz.max_lift ]
report:
  columns: [ Kurz, three-arc ]
  rows:
    - [ greatest acceleration, [ kurz.max_acceleration, arc.max_acceleration ] ]
    - [ least acceleration, [ kurz.min_acceleration, arc.min_acceleration ] ]
    - [ lift, [ kurz.max_lift, arc.max_lift ] ]
"""


@pytest.mark.parametrize("name", ["valvetrain_cams", "valvetrain_dynamics", "polydyne_synthesis", "backlash_chain",
                                  "unitless_rows"])
def test_report_tables_show_the_units_and_numbers_of_the_page(name, scenes, cli, tmp_path):
    # One rule of units for the page's tables and Python's (report_row_units): the same unit per
    # row, the same numbers to the page's six digits. The last scene's rows name no unit and their
    # ports none either: both show the reader's unit (mm/deg^2), not SI in one and mm/deg^2 in the other.
    import csv
    import subprocess

    file = scenes / f"{name}.yaml"
    if name == "unitless_rows":
        file = tmp_path / "unitless_rows.yaml"
        file.write_text(UNITLESS_ROWS, encoding="utf-8")
    done = subprocess.run([str(cli), "-q", "report", str(file), "--out", str(tmp_path / "r")],
                          capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stderr
    frames = mechgraph.Scene.load(file).run().report_tables()
    if name == "unitless_rows":
        assert list(frames[0]["unit"]) == ["mm/deg^2", "mm/deg^2", "mm"]
    assert frames
    for k, frame in enumerate(frames, start=1):
        with open(tmp_path / "r" / f"table_{k}.csv", newline="", encoding="utf-8") as f:
            rows = list(csv.reader(f))[1:]
        assert len(rows) == len(frame)
        for page_row, (label, py_row) in zip(rows, frame.iterrows()):
            assert page_row[0] == label
            # the page says which angle ("deg (cam)"); Python's unit stays one pint can read
            assert page_row[1].split(" (")[0] == py_row["unit"], label
            for text, value in zip(page_row[2:], py_row.iloc[1:]):
                if text in ("", "-"):
                    assert math.isnan(value)
                else:
                    assert math.isclose(float(text), value, rel_tol=5e-6, abs_tol=1e-9 * max(1.0, abs(value))), (label, text, value)


PUMP = """nodes:
  p: { type: pump.stroke, params: { stroke: 20 mm, points: 17 } }
outputs: [ p.peak_angle, p.port_events, p.motion ]
"""


@pytest.mark.parametrize("plugin", ["test_stroke", "test_stroke_sdk1"])
def test_frames_and_code_names_as_the_command_line_shows_them(plugin, cli, tmp_path):
    # A node type from outside (tests/test_plugins/stroke_plugin.cpp) declares its angle frames and
    # its events' codes; Python presents them from the declarations, as the terminal and CSV do.
    import subprocess
    from conftest import BINARY

    plugins = BINARY / "test_plugins" / plugin
    mechgraph.load_plugins([str(plugins)], only=True)
    try:
        scene_file = tmp_path / "pump.yaml"
        scene_file.write_text(PUMP, encoding="utf-8")
        r = mechgraph.Scene.load(scene_file).run()
        q = r.quantity("p.peak_angle")
        assert q.display_unit == "deg" and q.frame == "shaft"
        assert str(q) == "-90 deg (shaft)"
        assert r.frame("p.peak_angle") == "shaft"
        shown = subprocess.run([str(cli), "-q", "--only-plugin-dir", str(plugins), "run", str(scene_file)],
                               capture_output=True, text=True, check=True).stdout
        assert "p.peak_angle = -90 deg (shaft)" in shown
        events = r.table("p.port_events")
        assert list(events.columns)[:3] == ["travel [m]", "kind", "kind_name"]
        assert list(events["kind_name"]) == ["suction_port", "delivery_port"]
        assert list(events["kind_name"].cat.categories) == ["suction_port", "delivery_port"]
        assert events.attrs["codes"] == {"kind": {1.0: "suction_port", 2.0: "delivery_port"}}
        assert events.attrs["frames"] == {"opens_shaft [rad]": "shaft", "opens_rotor [rad]": "rotor", "closes_rotor [rad]": "rotor"}
        motion = r.table("p.motion", units="display")
        # Degrees name their angle in the label itself, as the CLI's CSV header and terminal do
        # (radians carry no tag): a column cannot be read in the wrong angle.
        assert motion.attrs["frames"] == {"shaft_angle [deg (shaft)]": "shaft", "rotor_angle [deg (rotor)]": "rotor",
                                          "speed [mm/deg (shaft)]": "shaft", "accel [mm/deg^2 (shaft)]": "shaft"}
        assert mechgraph._core.unit_scale("mm/deg (shaft)") == mechgraph._core.unit_scale("mm/deg")
    finally:
        mechgraph.load_plugins()
