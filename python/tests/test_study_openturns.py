"""A graph study against OpenTURNS' estimators on the same samples (docs/methods/uncertainty.md).

The Ishigami scene's Saltelli design runs as `mechgraph sweep --study` rows; the same outputs go to
OpenTURNS 1.20 (python3-openturns) in its layout [A; B; E_1 .. E_d] (E_j: A with column j from B),
and `mechgraph study --rows` analyses those rows. OpenTURNS' MauntzKucherenkoSensitivityAlgorithm
is the first-order formula of Saltelli et al. 2010 and its JansenSensitivityAlgorithm Jansen's
total, with its own normalisation: sums over N - 1 and 2N - 1, the variance of f(A) alone. So
S_OT = S N/(N-1) V/V_A and ST_OT = ST 2N/(2N-1) V/V_A, where V is ours (f(A) and f(B) pooled).
"""
import csv
import json
import subprocess

import numpy as np
import pytest

ot = pytest.importorskip("openturns")


def test_sobol_indices_equal_openturns_on_the_same_samples(cli, tmp_path):
    from conftest import BINARY, SOURCE

    scene = SOURCE / "tests" / "uncertainty" / "ishigami.yaml"
    plugins = ["--plugin-dir", str(BINARY / "test_plugins" / "test_uq")]
    rows = tmp_path / "rows.csv"
    n = 512
    subprocess.run([str(cli), *plugins, "sweep", str(scene), "--study", "--samples", str(n), "--threads", "2", "--out", str(rows)],
                   check=True, capture_output=True)
    ours = json.loads(subprocess.run([str(cli), *plugins, "study", str(scene), "--samples", str(n), "--rows", str(rows), "--json"],
                                     check=True, capture_output=True, text=True).stdout)
    with open(rows, newline="") as f:
        table = list(csv.DictReader(f))
    assert [int(r["case"]) for r in table] == list(range(n * 5))
    x = np.array([[float(r["x1"]), float(r["x2"]), float(r["x3"])] for r in table])
    y = np.array([float(r["f.y"]) for r in table])
    d = 3
    # Our case order is per base sample (A_i, B_i, AB_i^1..AB_i^d); OpenTURNS wants blocks.
    blocks = [np.arange(n) * (d + 2) + r for r in range(d + 2)]
    x_ot = np.vstack([x[b] for b in blocks])
    y_ot = np.concatenate([y[b] for b in blocks])[:, None]
    first = np.array(ot.MauntzKucherenkoSensitivityAlgorithm(ot.Sample(x_ot), ot.Sample(y_ot), n).getFirstOrderIndices())
    total = np.array(ot.JansenSensitivityAlgorithm(ot.Sample(x_ot), ot.Sample(y_ot), n).getTotalOrderIndices())

    y_a, y_b = y[blocks[0]], y[blocks[1]]
    v_pooled = np.var(np.concatenate([y_a, y_b]), ddof=1)
    v_a = np.var(y_a, ddof=1)
    indices = ours["outputs"]["f.y"]["sobol"]["indices"]
    s = np.array([indices[f"x{j + 1}"]["first"] for j in range(d)])
    st = np.array([indices[f"x{j + 1}"]["total"] for j in range(d)])
    np.testing.assert_allclose(s * n / (n - 1) * v_pooled / v_a, first, rtol=1e-9, atol=1e-12)
    np.testing.assert_allclose(st * 2 * n / (2 * n - 1) * v_pooled / v_a, total, rtol=1e-9, atol=1e-12)
    # And the answers are near the closed form (a = 7, b = 0.1).
    np.testing.assert_allclose(s, [0.3139, 0.4424, 0.0], atol=0.08)


def test_moments_and_quantiles_equal_openturns(cli, tmp_path):
    from conftest import BINARY, SOURCE

    scene = SOURCE / "tests" / "uncertainty" / "ishigami.yaml"
    plugins = ["--plugin-dir", str(BINARY / "test_plugins" / "test_uq")]
    rows = tmp_path / "rows.csv"
    subprocess.run([str(cli), *plugins, "sweep", str(scene), "--study", "--samples", "300", "--out", str(rows)], check=True,
                   capture_output=True)
    ours = json.loads(subprocess.run([str(cli), *plugins, "study", str(scene), "--samples", "300", "--rows", str(rows), "--json"],
                                     check=True, capture_output=True, text=True).stdout)["outputs"]["f.y"]
    with open(rows, newline="") as f:
        table = list(csv.DictReader(f))
    # The statistical samples of a Saltelli design: the A and B rows.
    y = ot.Sample([[float(r["f.y"])] for r in table if int(r["case"]) % 5 < 2])
    assert ours["n"] == y.getSize()
    assert ours["mean"] == pytest.approx(y.computeMean()[0], rel=1e-13)
    assert ours["standard_deviation"] == pytest.approx(y.computeStandardDeviation()[0], rel=1e-12)
    values = np.sort(np.array(y).ravel())
    for q in ours["quantiles"]:
        assert q["value"] == pytest.approx(np.quantile(values, q["level"]), rel=1e-12, abs=1e-12)
