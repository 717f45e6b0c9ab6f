"""Scene.study: distributions from Python, answers as DataFrames, the same numbers as the command."""
import json
import subprocess

import numpy as np
import pytest

import mechgraph
import mechgraph.dask
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
    assert set(study.samples.columns) == {"x1", "x2", "x3", "f.y", "exit", "role"}
    # The rows the statistics are made of are A and B; each AB row takes one parameter from B.
    samples = study.samples
    assert list(samples["role"][:5]) == ["A", "B", "AB x1", "AB x2", "AB x3"]
    statistical = samples[samples["role"].isin(["A", "B"])]
    assert len(statistical) == summary.loc["f.y", "n"]
    assert statistical["f.y"].mean() == pytest.approx(summary.loc["f.y", "mean"], rel=1e-12)
    ab = samples[samples["role"] == "AB x2"].reset_index(drop=True)
    a = samples[samples["role"] == "A"].reset_index(drop=True)
    b = samples[samples["role"] == "B"].reset_index(drop=True)
    assert (ab["x1"] == a["x1"]).all() and (ab["x2"] == b["x2"]).all() and (ab["x3"] == a["x3"]).all()
    # Handed over as arrays, not lists of Python numbers (a study of 10^6 cases took seconds and
    # 600 MB more that way): numbers as float64, exit as int64, the roles as Python strings.
    assert all(samples[c].dtype == np.float64 for c in ("x1", "x2", "x3", "f.y"))
    assert samples["exit"].dtype == np.int64 and set(samples["exit"]) == {0}
    assert samples["role"].dtype == object and all(type(r) is str for r in samples["role"][:5])
    assert (study.quantiles["unit"] == summary.loc["f.y", "unit"]).all()
    assert (study.histograms["unit"] == summary.loc["f.y", "unit"]).all()
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
    # The samples show each parameter as the sweep's rows do: its unit in the header, its numbers
    # in that unit (never SI under a bare name).
    samples = study.samples
    assert "x1" not in samples.columns
    assert samples["x1 [mm]"].mean() == pytest.approx(1.0, rel=0.01)
    assert 0.0 <= samples["x2 [mm]"].min() and samples["x2 [mm]"].max() <= 0.6
    with pytest.raises(mechgraph.SceneError, match="sigma"):
        scene.study({"x1": {"normal": {"mean": "1 mm", "sigm": "0.1 mm"}}}, samples=10)
    with pytest.raises(mechgraph.SceneError, match="no 'uncertainty'|no 'parameters'"):
        scene.study(samples=10)


def test_study_summary_counts_the_failed_cases_out_of_spec_as_well():
    # y = 4.957 + 1.1 sin x1 fails above 4.99 (about half the cases) and never reaches 5.5: no
    # value is out of spec, yet every failed case may be; the summary says both.
    scene = mechgraph.Scene.from_text("params: { x1: 0 }\nnodes:\n  f: { type: test.ishigami, params: "
                                      "{ x1: $x1, x2: 1, x3: 1, fail_above: 4.99 } }\noutputs: [f.y]\n")
    study = scene.study({"x1": {"uniform": {"lower": -3, "upper": 3}}}, samples=64, seed=2, limits={"f.y": {"upper": 5.5}})
    row = study.summary.loc["f.y"]
    assert 0 < row["failed"] < 64
    assert row["ppm"] == 0
    assert row["ppm_or_failed"] == pytest.approx(1e6 * row["failed"] / 64, rel=1e-12)
    assert row["ppm_or_failed_lower"] < row["ppm_or_failed"] < row["ppm_or_failed_upper"]


LINEAR = ("params: { x1: 0 mm, x2: 0 mm, x3: 0 mm }\n"
          "nodes:\n  f: { type: test.linear, params: { x1: $x1, x2: $x2, x3: $x3 } }\noutputs: [f.y]\n")


def test_study_values_take_pint_quantities_and_unit_pairs_as_text_does():
    import pint
    ureg = pint.UnitRegistry()
    scene = mechgraph.Scene.from_text(LINEAR)
    as_text = scene.study({"x1": {"normal": {"mean": "1 mm", "sigma": "0.1 mm"}}}, samples=64, seed=3,
                          limits={"f.y": {"upper": "1.2 mm"}}, events={"high": {"output": "f.y", "above": "1.1 mm"}})
    as_pint = scene.study({"x1": {"normal": {"mean": ureg.Quantity(1, "mm"), "sigma": ureg.Quantity(100, "um")}}},
                          samples=64, seed=3, limits={"f.y": {"upper": ureg.Quantity(1.2, "mm")}},
                          events={"high": {"output": "f.y", "above": (1.1, "mm")}})
    # The same numbers (pint writes SI text, "0.0001 m" for 100 um, which may round differently in the last bit).
    for key in ("mean", "standard_deviation", "cpk", "ppm"):
        assert as_pint.summary.loc["f.y", key] == pytest.approx(as_text.summary.loc["f.y", key], rel=1e-12, abs=1e-15)
    assert as_pint.events.loc[0, "probability"] == as_text.events.loc[0, "probability"]
    with pytest.raises(TypeError, match="carries its unit"):
        scene.study({"x1": {"normal": {"mean": mechgraph.si(1e-3), "sigma": "0.1 mm"}}}, samples=8)
    # samples and seed are whole numbers: 10.7 is refused, not rounded down.
    with pytest.raises(TypeError, match="whole number"):
        scene.study({"x1": {"normal": {"mean": "1 mm", "sigma": "0.1 mm"}}}, samples=10.7)
    assert len(scene.study({"x1": {"normal": {"mean": "1 mm", "sigma": "0.1 mm"}}}, samples=8.0).samples) == 8
    # Out of range or an unknown method: said in Python's words (the argument, the valid range or names).
    with pytest.raises(ValueError, match="samples: 1 is not from 2"):
        scene.study({"x1": {"normal": {"mean": "1 mm", "sigma": "0.1 mm"}}}, samples=1)
    with pytest.raises(ValueError, match="latin_hypercube"):
        scene.study({"x1": {"normal": {"mean": "1 mm", "sigma": "0.1 mm"}}}, samples=8, method="lhs")


def test_study_settings_reach_the_block_and_units_cannot_slip():
    scene = mechgraph.Scene.from_text(LINEAR)
    x1 = {"x1": {"normal": {"mean": "1 mm", "sigma": "0.1 mm"}}}
    study = scene.study(x1, samples=64, settings={"quantiles": [0.5], "confidence": 0.9, "bins": 4})
    assert list(study.quantiles["level"]) == [0.5]
    assert len(study.histograms) == 4
    # The mean's interval at 90 % against 95 %, the same samples: t(0.95, 63) / t(0.975, 63) = 0.835.
    wide = scene.study(x1, samples=64).summary.loc["f.y"]
    narrow = study.summary.loc["f.y"]
    ratio = (narrow["mean_upper"] - narrow["mean_lower"]) / (wide["mean_upper"] - wide["mean_lower"])
    assert ratio == pytest.approx(1.6694 / 1.9983, rel=0.01)
    with pytest.raises(TypeError, match="argument of its own"):
        scene.study(x1, samples=8, settings={"samples": 8})
    # A limit or a threshold in another dimension than its output, or bare on a length: refused.
    with pytest.raises(mechgraph.SceneError, match="bare number"):
        scene.study(x1, samples=8, limits={"f.y": {"upper": 0.0012}})
    with pytest.raises(mechgraph.SceneError, match="mass"):
        scene.study(x1, samples=8, events={"heavy": {"output": "f.y", "above": "2 g"}})
    # A value set on a parameter that has a distribution would be ignored by every sample: refused.
    with pytest.raises(mechgraph.SceneError, match="uncertain"):
        scene.study(x1, samples=8, set={"x1": "2 mm"})


def test_sample_columns_are_named_as_a_sweep_names_them():
    # An angle's column carries its frame, "[deg (cam)]", as the sweep's rows (and so
    # mechgraph.dask.study, which reads them) name it: cam and crank degrees differ by a factor 2.
    scene = mechgraph.Scene.load(SOURCE / "scenes" / "valve_timing_tolerances.yaml")
    study = scene.study(samples=2, threads=1, outputs=["v.opening_angle", "float.float_speed"])
    swept = scene.sweep({"lash": ["0.25 mm"]}, outputs=["v.opening_angle", "float.float_speed"])
    outputs = [c for c in swept.columns if c.startswith(("v.", "float."))]
    assert outputs == ["v.opening_angle [deg (cam)]", "float.float_speed [rpm]"]
    assert all(c in study.samples.columns for c in outputs)


def test_study_errors_carry_where_and_which_parameter_as_data():
    scene = mechgraph.Scene.from_text(
        "params: { x1: 0 mm, x2: 0 mm, x3: 0 mm }\n"
        "uncertainty:\n  parameters:\n    x1: { normal: { mean: 1 mm, sigma: 0.1 mm } }\n"
        "nodes:\n  f: { type: test.linear, params: { x1: $x1, x2: $x2, x3: $x3 } }\noutputs: [f.y]\n", name="uq.yaml")
    with pytest.raises(mechgraph.SceneError) as refused:
        scene.study(samples=8, set={"x1": "2 mm"})
    assert refused.value.location == ("uq.yaml", 4, 5)
    assert refused.value.parameter == "x1"
    with pytest.raises(mechgraph.SceneError) as limit:
        scene.study(samples=8, limits={"f.z": {"upper": "1 mm"}})
    assert "f.y" in str(limit.value)  # the outputs it could name


def test_a_dask_studys_design_keeps_scene_studys_budget():
    # Sixty outputs of one uncertain parameter, 3e6 samples: within the design's cap (9e6
    # evaluations), but the outputs' values and the Sobol' rows would hold about 12 GB beside the
    # cases. Before, the Dask study's design (made here, its cases sent out) was made unchecked.
    nodes = "".join(f"  f{i}: {{ type: test.linear, params: {{ x1: $x1, x2: {i} mm, x3: 0 mm }} }}\n" for i in range(60))
    outputs = ", ".join(f"f{i}.y" for i in range(60))
    scene = mechgraph.Scene.from_text(
        "params: { x1: 0 mm }\nuncertainty:\n  parameters:\n    x1: { uniform: { lower: 0 mm, upper: 1 mm } }\n"
        f"nodes:\n{nodes}outputs: [{outputs}]\n", name="wide.yaml")
    messages = []
    for study in (lambda: scene.study(samples=3_000_000, sensitivity=True),
                  lambda: mechgraph.dask.study(None, scene, samples=3_000_000, sensitivity=True)):  # refused before a client is used
        with pytest.raises(mechgraph.SceneError) as refused:
            study()
        messages.append(str(refused.value))
    assert "the study would hold about" in messages[0] and "the Sobol' rows" in messages[0]
    assert "raise the budget with max_memory=" in messages[0]  # the keyword, not the command's flag
    assert messages[1] == messages[0]
    # The budget is the caller's: a small study under a small budget is refused, then allowed.
    with pytest.raises(mechgraph.SceneError, match="raise the budget with max_memory="):
        scene.study(samples=64, max_memory=1e4)
    assert scene.study(samples=64, max_memory=1e9, max_work=1e9).summary.loc["f0.y", "n"] == 64


def test_a_designs_refusals_name_the_keywords_not_the_flags():
    # Before, Python users read "--samples 60000000: ...". (Python checks a method's name itself.)
    scene = mechgraph.Scene.load(ISHIGAMI)
    with pytest.raises(mechgraph.SceneError,
                       match=r"^samples 60000000: the design would need 300000000 evaluations, more than 2\.5 x 10\^8"):
        scene.study(samples=60_000_000, sensitivity=True)
    with pytest.raises(ValueError, match=r"^samples: 300000000 is not from 2 to 250000000"):
        scene.study(samples=300_000_000)


FIT_AT_TEMPERATURE = ("params: { t: 20 degC }\n"
                      "nodes:\n  fit: { type: fit.iso286, effects: [thermal], params: { size: 30 mm, hole: H7, shaft: g6, "
                      "operating_temperature: $t } }\noutputs: [fit.clearance_mean]\n")


def test_study_reads_a_celsius_width_as_a_width_and_numpy_arrays_as_lists():
    import pint
    ureg = pint.UnitRegistry()
    scene = mechgraph.Scene.from_text(FIT_AT_TEMPERATURE)
    as_text = scene.study({"t": {"normal": {"mean": "80 degC", "sigma": "5 degC"}}}, samples=64, seed=3)
    # A pint temperature in degC is a level as a mean and a width as a sigma, as the text is: 5 degC
    # of sigma is 5 K (converted to kelvin as a level it was 278.15 K, a spread of the whole scale).
    as_pint = scene.study({"t": {"normal": {"mean": ureg.Quantity(80, "degC"), "sigma": ureg.Quantity(5, "degC")}}},
                          samples=64, seed=3)
    for key in ("mean", "standard_deviation"):
        assert as_pint.summary.loc["fit.clearance_mean", key] == as_text.summary.loc["fit.clearance_mean", key]
    assert as_pint.samples["t [degC]"].std() == pytest.approx(5.0, rel=0.2)
    # Another offset scale has no reading mechgraph shares: refused, saying what to give.
    with pytest.raises(TypeError, match="give it in degC or K"):
        scene.study({"t": {"normal": {"mean": "80 degC", "sigma": ureg.Quantity(9, "degF")}}}, samples=8)
    # A numpy array in the settings is the list it holds.
    listed = scene.study({"t": {"normal": {"mean": "80 degC", "sigma": "5 degC"}}}, samples=64, seed=3,
                         settings={"quantiles": np.array([0.1, 0.5, 0.9])})
    assert list(listed.quantiles["level"]) == [0.1, 0.5, 0.9]


def test_dask_study_refuses_a_design_beyond_a_sweeps_values_in_the_studys_words():
    # mechgraph.dask.study sends its design out as a sweep's cases, which hold 2 x 10^7 values: a
    # larger design (Scene.study holds it) is refused before anything is sent, naming the most
    # samples that fit and the in-process study, not "split it into several sweeps".
    scene = mechgraph.Scene.from_text("params: { x1: 0 mm, x2: 0 mm, x3: 0 mm }\n"
                                      "nodes:\n  f: { type: test.linear, params: { x1: $x1, x2: $x2, x3: $x3 } }\n"
                                      "outputs: [f.y]\n")
    uniform = {"uniform": {"lower": "0 mm", "upper": "1 mm"}}

    class NoCluster:
        def submit(self, *args, **kwargs):
            raise AssertionError("a chunk was sent although the design is refused")

    with pytest.raises(mechgraph.SceneError, match=r"samples: 6700000 make 6700000 cases of 3 values each.*"
                                                   r"at most 6666666 samples here.*Scene\.study"):
        mechgraph.dask.study(NoCluster(), scene, {"x1": uniform, "x2": uniform, "x3": uniform}, samples=6_700_000,
                             method="monte_carlo")
