"""Scene.sweep: the rows of `mechgraph sweep`, as a DataFrame, failed cases included."""
import json
import math
import subprocess

import numpy as np
import pandas as pd
import pytest

import mechgraph

OUTPUTS = ["arc.min_curvature_radius", "v_kurz.max_acceleration", "ta_poly.time_area"]


def cli_rows(cli, scene, csv_file, outputs, threads=2):
    out = subprocess.run([str(cli), "-q", "sweep", str(scene), "--cases", str(csv_file), "--format", "jsonl",
                          "--outputs", ",".join(outputs), "--threads", str(threads)],
                         capture_output=True, text=True, check=True).stdout
    return [json.loads(line) for line in out.splitlines() if line.strip()]


def assert_rows_equal(frame, expected):
    """The frame holds the JSON Lines rows `expected`, cell for cell (numbers bit for bit)."""
    assert list(frame.columns) == list(expected[0].keys())
    assert len(frame) == len(expected)
    for row, want in zip(frame.to_dict("records"), expected):
        for key, value in want.items():
            got = row[key]
            if isinstance(value, float) or (isinstance(value, int) and not isinstance(value, bool)):
                assert got == value, (key, got, value)  # bit for bit: the same text, the same double
            elif value is None:
                assert got is None or (isinstance(got, float) and math.isnan(got))
            else:
                assert got == value, key


def test_rows_identical_to_the_command_line(scenes, cli, tmp_path):
    rpm = [5000, 5600, 6200, 7000, 7600]
    r0 = [17, 16, 3, 18, 17.5]  # 3 mm: the three-arc cam cannot be made (a failed row)
    csv_file = tmp_path / "cases.csv"
    csv_file.write_text("rpm [rpm],r0 [mm]\n" + "".join(f"{a},{b}\n" for a, b in zip(rpm, r0)))
    expected = cli_rows(cli, scenes / "valvetrain_cams.yaml", csv_file, OUTPUTS)

    scene = mechgraph.Scene.load(scenes / "valvetrain_cams.yaml")
    frame = scene.sweep(pd.DataFrame({"rpm [rpm]": rpm, "r0 [mm]": r0}), outputs=OUTPUTS, threads=2)
    assert isinstance(frame, pd.DataFrame)
    assert_rows_equal(frame, expected)
    assert len(frame) == 5
    failed = frame[frame["exit"] != 0]
    assert len(failed) == 1 and int(failed["exit"].iloc[0]) == 3 and "arc" in failed["error"].iloc[0]
    assert frame.attrs["summary"]["failed"] == 1


def sweep_like_the_command_line(scenes, cli, tmp_path, columns):
    """Scene.sweep of `columns` (name: cells), checked cell for cell against the JSON rows of
    `mechgraph sweep` of the same cells written as a cases file; returns the frame."""
    csv_file = tmp_path / "cases.csv"
    lines = [",".join(columns)] + [",".join(str(c) for c in row) for row in zip(*columns.values())]
    csv_file.write_text("\n".join(lines) + "\n")
    expected = cli_rows(cli, scenes / "valvetrain_cams.yaml", csv_file, OUTPUTS)
    scene = mechgraph.Scene.load(scenes / "valvetrain_cams.yaml")
    frame = scene.sweep(columns, outputs=OUTPUTS, threads=2, progress=False)
    assert_rows_equal(frame, expected)
    return frame


def test_text_cells_identical_to_the_command_line(scenes, cli, tmp_path):
    # A column of text cells: numbers under the column's unit or in another unit of its dimension
    # (numbers in the frame), and a cell of another dimension, which the row shows as written (an
    # object column: floats and that text) and whose case fails as a scene error.
    lash = ["0.25", "0.3 mm", "1 degC", "0.0002 m", "0.2"]
    frame = sweep_like_the_command_line(scenes, cli, tmp_path, {"rpm [rpm]": [5000, 5600, 6200, 7000, 7600], "lash [mm]": lash})
    assert frame["lash [mm]"].dtype == object and frame["lash [mm]"].iloc[2] == "1 degC"
    assert list(frame["exit"]) == [0, 0, 2, 0, 0] and frame["error"].iloc[0] is None
    assert "lash" in frame["error"].iloc[2]


def test_a_column_without_a_unit_shows_its_first_units_as_the_command_line_does(scenes, cli, tmp_path):
    # Text cells under a name without a unit: the column takes the unit of its first number written
    # with one (rpm), as a cases file's does; a cell in another unit is shown in it, a cell of
    # another dimension as written (its case refused).
    rpm = ["5600.5 rpm", "600 rad/s", "6000 rpm", "6100 mm", "6200 rpm"]
    frame = sweep_like_the_command_line(scenes, cli, tmp_path, {"rpm": rpm})
    assert "rpm [rpm]" in frame.columns and frame["rpm [rpm]"].iloc[0] == 5600.5
    assert list(frame["exit"]) == [0, 0, 0, 2, 0]


@pytest.mark.parametrize("r0", [[3, 17, 16], [3, 2.5]], ids=["the first fails", "all fail"])
def test_failed_first_rows_identical_to_the_command_line(scenes, cli, tmp_path, r0):
    # Rows wait for the first success to fix the columns; when none succeeds the columns are the
    # scalar outputs alone and every output is NaN (null in the JSON rows).
    frame = sweep_like_the_command_line(scenes, cli, tmp_path, {"r0 [mm]": r0})
    assert frame["exit"].iloc[0] == 3 and frame.attrs["summary"]["failed"] == sum(1 for x in r0 if x < 10)


def test_si_numbers_and_dict_of_arrays(scenes):
    scene = mechgraph.Scene.load(scenes / "valvetrain_cams.yaml")
    rpm_si = np.array([5000.0, 6000.0]) * 2 * math.pi / 60
    a = scene.sweep({"rpm": mechgraph.si(rpm_si)}, outputs=["v_kurz.max_acceleration"])
    b = scene.sweep({"rpm [rpm]": [5000.0, 6000.0]}, outputs=["v_kurz.max_acceleration"])
    col = [c for c in a.columns if c.startswith("v_kurz.max_acceleration")][0]
    assert np.allclose(a[col].to_numpy(dtype=float), b[col].to_numpy(dtype=float), rtol=1e-14, atol=0)
    # and a single run gives the same number (SI)
    r = scene.run(set={"rpm": "6000 rpm"}, outputs=["v_kurz.max_acceleration"])
    assert math.isclose(float(b[col].iloc[1]), r["v_kurz.max_acceleration"], rel_tol=1e-15)


def test_numbers_in_a_columns_unit_are_the_values_their_text_gives(scenes):
    # A column of numbers under a unit takes (x + offset) * scale with the unit parsed once; the
    # same numbers written as text cells ("x mm", read as a cases file reads them) must give the
    # same cases: the same inputs in the rows and the same outputs, bit for bit. Random values with
    # 17 significant digits, so that no rounding of the text hides a difference.
    rng = np.random.default_rng(7)
    n = 40
    columns = {"rpm [rpm]": rng.uniform(4000, 7000, n), "r0 [mm]": rng.uniform(15, 19, n),
               "arc.accel_angle [deg]": rng.uniform(15, 21, n)}
    texts = {name.split(" [")[0]: [f"{x!r} {name.split('[')[1][:-1]}" for x in values] for name, values in columns.items()}
    scene = mechgraph.Scene.load(scenes / "valvetrain_cams.yaml")
    outputs = ["v_kurz.max_acceleration", "ta_poly.time_area", "arc.max_velocity"]
    numbers = scene.sweep(columns, outputs=outputs, threads=2, progress=False)
    written = scene.sweep(texts, outputs=outputs, threads=2, progress=False)
    assert (numbers["exit"] == 0).all() and (written["exit"] == 0).all()
    for name, values in columns.items():
        assert list(numbers[name]) == list(values)  # the row shows the number given
    for out in [c for c in numbers.columns if c.split(" [")[0] in outputs]:
        assert list(numbers[out]) == list(written[out]), out


def test_words_as_text_cells(scenes):
    scene = mechgraph.Scene.load(scenes / "valvetrain_cams.yaml")
    frame = scene.sweep({"arc.follower": ["flat", "roller"], "arc.roller_radius [mm]": [12.0, 12.0]},
                        outputs=["arc.min_curvature_radius"])
    assert list(frame["exit"]) == [0, 0] or set(frame["exit"]) <= {0, 2, 3}


def test_bad_cases_are_scene_errors(scenes):
    scene = mechgraph.Scene.load(scenes / "valvetrain_cams.yaml")
    with pytest.raises(mechgraph.SceneError):
        scene.sweep({"rmp [rpm]": [5000.0]})
    with pytest.raises(mechgraph.SceneError):
        scene.sweep({"rpm [rpm]": [5000.0, 6000.0], "lift [mm]": [8.0]})


def test_no_cases_give_an_empty_frame_and_nan_is_refused(scenes):
    scene = mechgraph.Scene.load(scenes / "valvetrain_cams.yaml")
    empty = scene.sweep({"rpm [rpm]": np.array([], dtype=float)}, outputs=["v_kurz.max_acceleration"])
    assert len(empty) == 0 and "case" in empty.columns
    with pytest.raises(mechgraph.SceneError):
        scene.sweep({"rpm [rpm]": [5000.0, float("nan")]}, outputs=["v_kurz.max_acceleration"])
    with pytest.raises(mechgraph.SceneError):
        scene.sweep({"lift": [0.008, float("inf")]}, si=True, outputs=["v_kurz.max_acceleration"])


def test_a_wide_frame_is_checked_for_repeated_columns_in_linear_time(scenes):
    # 300000 columns took about 110 s when each name was compared with every earlier one.
    import time

    from mechgraph._cases import case_columns

    columns = {f"c{i}": [1.0] for i in range(300000)}
    start = time.monotonic()
    names, _, _, _ = case_columns(columns)
    assert len(names) == 300000 and time.monotonic() - start < 10
    columns["c299999 [mm]"] = [1.0]
    with pytest.raises(mechgraph.SceneError, match="appears twice"):
        case_columns(columns)


def test_each_case_is_estimated_with_its_own_values(scenes):
    # The scene's 361 points would pass; the cases' own 10^6 points each, 200 cases at once, hold
    # more than the 4 GiB of memory of the budget.
    scene = mechgraph.Scene.load(scenes / "valvetrain_cams.yaml")
    with pytest.raises(mechgraph.SceneError, match="curve_points = 1000000"):
        scene.sweep({"kurz.curve_points": [1e6] * 200}, outputs=["v_kurz.max_acceleration"], threads=200)


def test_progress_is_reported_while_cases_run_and_a_bar_shows_only_for_long_sweeps(scenes, capfd, monkeypatch):
    import mechgraph._progress

    scene = mechgraph.Scene.load(scenes / "valvetrain_cams.yaml")
    cases = {"rpm [rpm]": np.linspace(3000, 8000, 20000)}
    seen = []
    rows = scene.sweep(cases, outputs=["ta_kurz.time_area"], threads=1, progress=lambda done, total: seen.append((done, total)))
    assert len(rows) == 20000
    assert seen and all(total == 20000 for _, total in seen)
    assert [d for d, _ in seen] == sorted(d for d, _ in seen)
    assert seen[-1] == (20000, 20000)  # the final count comes however fast the cases ran
    short = []
    scene.sweep({"rpm [rpm]": [5000.0]}, outputs=["ta_kurz.time_area"], progress=lambda d, t: short.append((d, t)))
    assert short and short[-1] == (1, 1)
    capfd.readouterr()
    scene.sweep({"rpm [rpm]": [5000.0, 6000.0]}, outputs=["ta_kurz.time_area"])  # short: no bar
    assert capfd.readouterr().err == ""
    monkeypatch.setattr(mechgraph._progress, "DELAY_S", 0.0)  # a long sweep's bar, without waiting a second
    scene.sweep(cases, outputs=["ta_kurz.time_area"], threads=1)
    err = capfd.readouterr().err
    assert "100%" in err and "20000/20000" in err and "case" in err


def test_a_progress_callable_that_raises_stops_the_sweep(scenes):
    scene = mechgraph.Scene.load(scenes / "valvetrain_cams.yaml")

    def stop(done, total):
        raise RuntimeError("enough")

    with pytest.raises(RuntimeError, match="enough"):
        scene.sweep({"rpm [rpm]": np.linspace(3000, 8000, 200000)}, outputs=["ta_kurz.time_area"], threads=2, progress=stop)
    assert len(scene.sweep({"rpm [rpm]": [5000.0]}, outputs=["ta_kurz.time_area"])) == 1
