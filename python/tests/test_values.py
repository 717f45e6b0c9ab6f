"""Values from Python (issue 28, classes 8 and 4): one conversion for `set=`, a sweep's columns and
arrays, refusing every bool-like, complex, date, time and duration wherever it is given; scenes
from text bounded as scene files are; a run's provenance records what the run used, and text
values are never read again as YAML."""
import datetime
import decimal
import fractions
import math
import os
import time

import numpy as np
import pandas as pd
import pytest

import mechgraph

SCENE = """
params: { lift: 8 mm }
nodes:
  ref:   { type: cam.kurz, params: { max_lift: $lift, action_angle: 130 deg, accel_angle: 18 deg, base_radius: 17 mm } }
  table: { type: cam.table, params: { base_radius: 17 mm, angles: [ -10 deg, 0 deg, 10 deg ], lifts: [ 0 mm, 1 mm, 0 mm ] } }
outputs: [ ref.max_lift ]
"""

BOOL_LIKE = [True, False, np.bool_(True), np.array(True)]
COMPLEX = [0.008 + 0j, np.complex128(0.008), np.complex64(0.008), np.array(0.008 + 0j)]
DATES = [datetime.datetime(2020, 1, 1), datetime.date(2020, 1, 1), datetime.time(1, 2), np.datetime64("2020-01-01"),
         pd.Timestamp("2020-01-01")]
DURATIONS = [datetime.timedelta(seconds=1), np.timedelta64(5, "ns"), pd.Timedelta(seconds=1)]
OTHER = [None, b"8 mm", pd.NA, {"a": 1}]


@pytest.fixture(scope="module")
def scene():
    return mechgraph.Scene.from_text(SCENE)


@pytest.mark.parametrize("value, words", [(v, "True/False") for v in BOOL_LIKE] + [(v, "complex") for v in COMPLEX] +
                         [(v, "date or time") for v in DATES] + [(v, "duration") for v in DURATIONS] +
                         [(v, "") for v in OTHER])
def test_a_refused_kind_is_refused_as_one_value(scene, value, words):
    with pytest.raises(mechgraph.SceneError, match="set lift: .*" + words):
        scene.run(set={"lift": value})


def test_accepted_numbers_and_text_give_the_same_lift(scene):
    for value in [0.008, np.float64(0.008), np.float32(0.008), decimal.Decimal("0.008"), fractions.Fraction(1, 125), "8 mm",
                  np.str_("8 mm"), np.array(0.008)]:
        lift = scene.run(set={"lift": value if isinstance(value, str) else mechgraph.si(value)})["ref.max_lift"]
        assert scene.run(set={"lift": value}, si=True)["ref.max_lift"] == lift
        assert math.isclose(lift, 0.008, rel_tol=1e-7, abs_tol=1e-12), repr(value)
    # integers: a cam's base radius of 1 m from int and numpy int types alike
    for value in [1, np.int64(1), np.int32(1), np.uint8(1)]:
        r = scene.run(set={"ref.base_radius": mechgraph.si(value)})
        assert r.provenance["nodes"]["ref"]["used_si"]["base_radius"] == 1.0, repr(value)


def _law():
    svaj = mechgraph.Scene.from_text(SCENE).run(outputs=["ref.svaj"]).table("ref.svaj")
    return svaj["cam_angle [rad]"].to_numpy(), svaj["lift [m]"].to_numpy()


@pytest.mark.parametrize("convert, words", [
    (lambda a: a.astype(complex), "complex"),
    (lambda a: a > 0, "True/False"),
    (lambda a: np.array(["2020-01-01"] * len(a), dtype="datetime64[ns]"), "date or time"),
    (lambda a: (a * 1e9).astype("timedelta64[ns]"), "duration"),
    (lambda a: [True] + list(a[1:]), "True/False"),  # one bool in a list of floats
    (lambda a: list(a[:-1]) + [1j], "complex"),
    (lambda a: pd.Series(a > 0), "True/False"),
])
def test_a_refused_kind_is_refused_in_an_array(scene, convert, words):
    angle, lift = _law()
    with pytest.raises(mechgraph.SceneError, match="set table.lifts.*" + words):
        scene.run(set={"table.angles": angle, "table.lifts": convert(lift)}, outputs=["table.max_lift"], si=True)


def test_accepted_arrays(scene):
    angle, lift = _law()
    for lifts in [lift, list(lift), tuple(lift), pd.Series(lift), lift.astype(np.float32)]:
        r = scene.run(set={"table.angles": angle, "table.lifts": lifts}, outputs=["table.max_lift"], si=True)
        assert math.isclose(r["table.max_lift"], 0.008, rel_tol=1e-6), type(lifts)


@pytest.mark.parametrize("column, words", [
    (pd.Series([True, False]), "True/False"),
    (np.array([True, False]), "True/False"),
    ([0.008, True], "row 1: True/False"),
    (pd.Series([0.008, np.bool_(True)], dtype=object), "row 1: True/False"),
    (np.array([0.008 + 1j, 0.009]), "complex"),
    (pd.Series(pd.date_range("2020-01-01", periods=2)), "date or time"),
    (pd.Series(pd.date_range("2020-01-01", periods=2, tz="UTC")), "date or time"),
    (np.array(["2020-01-01", "2020-01-02"], dtype="datetime64[ns]"), "date or time"),
    (pd.Series(pd.to_timedelta([1, 2], unit="s")), "duration"),
    ([datetime.timedelta(seconds=1), datetime.timedelta(seconds=2)], "duration"),
    (pd.Series([0.008, None], dtype="Float64"), "row 1"),
    ([b"8 mm", b"9 mm"], "bytes"),
])
def test_a_refused_kind_is_refused_in_a_sweep_column_naming_it(scene, column, words):
    with pytest.raises(mechgraph.SceneError, match="cases: column 'lift'.*" + words):
        scene.sweep({"lift": column}, outputs=["ref.max_lift"])
    with pytest.raises(mechgraph.SceneError, match="cases: column 'lift'.*" + words):
        scene.sweep(pd.DataFrame({"lift": column}), outputs=["ref.max_lift"])


def test_accepted_sweep_columns(scene):
    expected = [0.008, 0.009]
    for column in [np.array([8, 9], dtype=np.int32), np.array([8, 9], dtype=np.uint16), [8, 9], (8.0, 9.0), ["8", "9 mm"],
                   pd.Series([8, 9], dtype="Int64"), np.array([8.0, 9.0], dtype=np.float32), range(8, 10)]:
        frame = scene.sweep({"lift [mm]": column}, outputs=["ref.max_lift"])
        assert list(frame["exit"]) == [0, 0], repr(column)
        assert np.allclose(frame["ref.max_lift [mm]"], [8.0, 9.0]), repr(column)
    frame = scene.sweep({"lift": mechgraph.si([0.008, np.float64(0.009)])}, outputs=["ref.max_lift"])
    assert np.allclose(frame["ref.max_lift [mm]"] / 1e3, expected)


def test_a_sweeps_fixed_values_take_the_same_conversion_and_are_never_yaml(scene):
    frame = scene.sweep({"ref.base_radius [mm]": [17.0]}, set={"lift": mechgraph.si(0.009)}, outputs=["ref.max_lift"])
    assert math.isclose(frame["ref.max_lift [mm]"][0], 9.0, rel_tol=1e-9)
    frame = scene.sweep({"ref.base_radius [mm]": [17.0]}, set={"lift": "9 mm"}, outputs=["ref.max_lift"])
    assert math.isclose(frame["ref.max_lift [mm]"][0], 9.0, rel_tol=1e-9)
    with pytest.raises(mechgraph.SceneError, match="True/False"):
        scene.sweep({"ref.base_radius [mm]": [17.0]}, set={"lift": np.bool_(True)}, outputs=["ref.max_lift"])
    # "*x" is a YAML alias and "[1, 2]" a YAML list: as values they are text, whatever YAML makes of them
    for text in ["*x", "[1, 2]", "&a b", "~"]:
        frame = scene.sweep({"ref.base_radius [mm]": [17.0]}, set={"table.file": text}, outputs=["ref.max_lift"])
        assert list(frame["exit"]) == [0]


def test_provenance_records_the_arrays_a_run_used_not_the_scenes_rows(scene):
    angle, lift = _law()
    r = scene.run(set={"table.angles": angle, "table.lifts": lift}, outputs=["table.max_lift"], si=True)
    used = r.provenance["nodes"]["table"]["used_si"]
    assert np.array_equal(used["angles"], angle)
    assert np.array_equal(used["lifts"], lift)
    assert r.provenance["overrides"] == [f"table.angles=<{len(angle)} values, SI>", f"table.lifts=<{len(lift)} values, SI>"]
    # a later run with other values does not change what an earlier result says it used
    later = scene.run(set={"table.angles": angle, "table.lifts": lift * 0.5}, outputs=["table.max_lift"], si=True)
    assert np.array_equal(r.provenance["nodes"]["table"]["used_si"]["lifts"], lift)
    assert np.array_equal(later.provenance["nodes"]["table"]["used_si"]["lifts"], lift * 0.5)


def test_provenance_never_reads_a_text_value_as_yaml(scene):
    for text in ["*x", "[1, 2]", "{a: b}", "&a b", "~", "'q"]:
        r = scene.run(set={"table.file": text, "lift": mechgraph.si(0.0085)})  # table is not needed: the run succeeds
        p = r.provenance
        assert p["overrides"][0] == f"table.file={text}"
        assert p["overrides"][1].startswith("lift=0.0085")
        assert math.isclose(p["nodes"]["ref"]["used_si"]["max_lift"], 0.0085, rel_tol=1e-12)


def test_scenes_from_text_and_dicts_are_bounded_as_files_are():
    start = time.monotonic()
    with pytest.raises(mechgraph.SceneError, match="more than the limit of 1048576 bytes"):
        mechgraph.Scene.from_text("title: " + "x" * (300 << 20))
    with pytest.raises(mechgraph.SceneError, match="more than the limit"):
        mechgraph.Scene.from_dict({"title": "x" * (2 << 20), "nodes": {}})
    assert time.monotonic() - start < 10  # was 47 s for the 300 MB title alone
    # just under the bound still loads
    assert mechgraph.Scene.from_text("title: " + "x" * 1_000_000 + "\nnodes: {}\n").title.startswith("xxx")


def test_log_messages_and_descriptions_hold_no_control_sequence(capfd):
    """The module's log messages pass through the same terminal-safe sink as the command line's
    (issue 28, class 7): a plugin's warning quoting ESC, OSC and CSI reaches stderr as text."""
    binary = os.environ.get("MECHGRAPH_BINARY_DIR", os.path.join(os.path.dirname(__file__), "..", "..", "build"))
    mechgraph.load_plugins([os.path.join(binary, "test_plugins", "test_hostile_values")])
    try:
        scene = mechgraph.Scene.from_text("nodes:\n  t: { type: hostile.evil_text }\noutputs: [ t.curve ]\n")
        capfd.readouterr()
        r = scene.run(set={"t.label": "L\x1b]0;PWNED\x07\u009b31m"})
        err = capfd.readouterr().err
        assert "a warning" in err and "PWNED" in err
        assert not any(c in err for c in "\x1b\x07\x9b\u009b\u202e\x7f\r\b")
        text = str(mechgraph.describe("hostile.evil_text"))
        assert "PWNED" in text and not any(c in text for c in "\x1b\x07\u009b\u202e\x7f\r\b")
        # Results are data: the plugin's bytes that are not UTF-8 (a raw 0x9B) arrive as U+FFFD
        # instead of a UnicodeDecodeError, in notes, labels and error messages alike.
        assert any("\ufffd" in note for _, note in r.notes)
        assert r.axis("t.curve")[2][0] == "L\x1b]0;PWNED\x07\u009b31m" and "\ufffd" in r.axis("t.curve")[2][1]
        with pytest.raises(mechgraph.EvaluationError, match="refused .*\ufffd"):
            scene.run(set={"t.label": "fail"})
    finally:
        mechgraph.load_plugins()
