"""Scene.study: distributions from Python, answers as DataFrames, the same numbers as the command."""
import json
import subprocess

import pytest

import mechgraph
from conftest import BINARY, SOURCE

ISHIGAMI = SOURCE / "tests" / "uncertainty" / "ishigami.yaml"
PLUGINS = BINARY / "test_plugins" / "test_uq"


@pytest.fixture(autouse=True)
def uq_plugins():
    mechgraph.load_plugins([str(PLUGINS)])
    yield
    mechgraph.load_plugins()


def test_study_gives_the_command_lines_answers(cli):
    study = mechgraph.Scene.load(ISHIGAMI).study(samples=256, threads=2)
    command = json.loads(subprocess.run([str(cli), "--plugin-dir", str(PLUGINS), "study", str(ISHIGAMI), "--samples", "256",
                                         "--json", "--threads", "1"], check=True, capture_output=True, text=True).stdout)
    assert "provenance" in command  # the command records how it was made; the answers are the same
    del command["provenance"]
    assert study.json == command
    summary = study.summary
    assert summary.loc["f.y", "n"] == 512
    assert summary.loc["f.y", "cpk"] == pytest.approx(command["outputs"]["f.y"]["cpk"])
    sobol = study.sobol
    assert list(sobol["parameter"]) == ["x1", "x2", "x3"]
    assert (sobol["first_lower"] <= sobol["first"]).all()
    assert len(study.samples) == 256 * 5
    assert set(study.samples.columns) == {"x1", "x2", "x3", "f.y", "exit"}
    assert study.events.loc[0, "event"] == "high"


def test_distributions_from_python_merge_over_the_scene():
    scene = mechgraph.Scene.from_text(
        "params: { x1: 0 mm, x2: 0 mm, x3: 0 mm }\n"
        "nodes:\n  f: { type: test.linear, params: { x1: $x1, x2: $x2, x3: $x3 } }\noutputs: [f.y]\n")
    study = scene.study({"x1": {"normal": {"mean": "1 mm", "sigma": "0.1 mm"}},
                         "x2": {"uniform": {"lower": "0 mm", "upper": "0.6 mm"}}},
                        samples=4000, method="latin_hypercube", limits={"f.y": {"upper": "1.9 mm"}})
    row = study.summary.loc["f.y"]
    assert row["unit"] == "m"
    assert row["mean"] == pytest.approx(1.3e-3, rel=0.01)
    assert row["standard_deviation"] == pytest.approx((0.1e-3 ** 2 + 0.6e-3 ** 2 / 12) ** 0.5, rel=0.03)
    assert row["cpk"] > 0
    with pytest.raises(mechgraph.SceneError, match="sigma"):
        scene.study({"x1": {"normal": {"mean": "1 mm", "sigm": "0.1 mm"}}}, samples=10)
    with pytest.raises(mechgraph.SceneError, match="no 'uncertainty'|no 'parameters'"):
        scene.study(samples=10)
