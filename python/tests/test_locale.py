"""A program's locale does not reach mechgraph's numbers. Under a German locale (decimal comma,
set by locale.setlocale as a program may), a sweep and a study read and show every number as
under "C": the C library's strtod, which reads by LC_NUMERIC, had shown 8.5 mm as 8.0 in the
sweep's input column, and the plugins' messages and notes, written by printf, had "8,25 mm"."""
import json
import os
import pathlib
import re
import shutil
import subprocess
import sys

import pytest

GERMAN = "de_DE.UTF-8"

CHILD = r"""
import json, locale, re, sys
import mechgraph
if sys.argv[1] != "C":
    locale.setlocale(locale.LC_ALL, sys.argv[1])
    assert locale.localeconv()["decimal_point"] == ","
scene = mechgraph.Scene.load(sys.argv[2])
frame = scene.sweep({"lift [mm]": [8.5, 8.25], "rpm": ["5600.5 rpm", "6000 rpm"], "lash": ["0.25 mm", "0.3 mm"]},
                    outputs=["ta_poly.time_area"], progress=False)
study = scene.study({"lash": {"normal": {"mean": "0.25 mm", "sigma": "0.01 mm"}}}, samples=64, seed=3,
                    limits={"ta_poly.time_area": {"lower": "4.5 mm^2*s"}}, outputs=["ta_poly.time_area"])
try:  # a bare number for a length: the refusal names the scene's unit, read from "0.25 mm"
    scene.run(set={"lash": 0.3})
    refusal = None
except mechgraph.SceneError as e:
    refusal = str(e)
# the first case fails (an infeasible base radius): its row and the rows after it
failing = scene.sweep({"r0 [mm]": [3.0, 17.5]}, outputs=["arc.min_curvature_radius"], progress=False)
# the plugins' words: a node's error and notes with numbers in them (a cam, the valve, the backlash
# chain, the valve train's dynamics)
try:
    scene.run(set={"arc.checking_lift": "8.25 mm"}, outputs=["arc.opening_angle"])
    plugin_error = None
except mechgraph.EvaluationError as e:
    plugin_error = str(e)
notes = scene.run(set={"lash": "0.3 mm"}, outputs=["v_arc.opening_angle"]).notes
notes += mechgraph.Scene.load(sys.argv[3]).run().notes + mechgraph.Scene.load(sys.argv[4]).run().notes
print(json.dumps({"sweep": frame.to_dict("list"), "study": study.summary.to_dict("list"),
                  "samples": study.samples.to_dict("list"), "refusal": refusal, "failing": failing.to_dict("list"),
                  "shown": re.sub(r" in \S+ ms", "", str(scene.run(outputs=["ta_poly.time_area"]))),
                  "plugin_error": plugin_error, "notes": notes}))
"""


@pytest.fixture(scope="module")
def german_locale(tmp_path_factory):
    """The environment in which GERMAN can be set: the system's, or one compiled here by
    localedef (Debian's `locales` package) into a folder named by LOCPATH."""
    env = dict(os.environ)
    probe = [sys.executable, "-c", f"import locale; locale.setlocale(locale.LC_ALL, {GERMAN!r})"]
    if subprocess.run(probe, env=env, capture_output=True).returncode == 0:
        return env
    localedef = shutil.which("localedef")
    assert localedef, "localedef (Debian package libc-bin) is needed to make a German locale"
    assert pathlib.Path("/usr/share/i18n/locales/de_DE").is_file(), "the locales' sources are needed: Debian package locales"
    folder = tmp_path_factory.mktemp("locales")
    made = subprocess.run([localedef, "-c", "-i", "de_DE", "-f", "UTF-8", str(folder / GERMAN)], capture_output=True, text=True)
    env["LOCPATH"] = str(folder)
    assert subprocess.run(probe, env=env, capture_output=True).returncode == 0, \
        f"localedef made no usable {GERMAN} (exit {made.returncode}): {made.stderr}"
    return env


def run_child(env, locale_name, scenes):
    out = subprocess.run([sys.executable, "-c", CHILD, locale_name, str(scenes / "valvetrain_cams.yaml"),
                          str(scenes / "backlash_chain.yaml"), str(scenes / "valvetrain_dynamics.yaml")], env=env,
                         capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    return json.loads(out.stdout)


def test_a_german_locale_changes_no_number(scenes, german_locale):
    plain = run_child(german_locale, "C", scenes)
    german = run_child(german_locale, GERMAN, scenes)
    sweep = german["sweep"]
    assert sweep["lift [mm]"] == [8.5, 8.25]
    # Text cells in a column without a unit: shown in the unit of its first number.
    assert sweep["rpm [rpm]"] == [5600.5, 6000.0]
    assert sweep["lash [mm]"] == [0.25, 0.3]
    assert sweep["exit"] == [0, 0]
    assert "mm" in german["refusal"] and german["failing"]["exit"] == [3, 0]
    # The plugins write their numbers with a point too (printf_number.hpp; printf had "8,25 mm").
    assert "checking_lift 8.25 mm is not below" in german["plugin_error"]
    assert any(re.search(r"opens \d+\.\d deg", text) for _, text in german["notes"]), german["notes"]
    assert any(re.search(r"standard error of the mean \d+\.\d+ mm", text) for _, text in german["notes"]), german["notes"]
    assert any(re.search(r"step cap is \d+\.\d+, inside", text) for _, text in german["notes"]), german["notes"]
    assert any(re.search(r"first at cam angle -?\d+\.\d deg \(\d+\.\d+ m/s\)", text) for _, text in german["notes"]), german["notes"]
    assert german == plain  # every value of the sweep, the study's answers and its samples
