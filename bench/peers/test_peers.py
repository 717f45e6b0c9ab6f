#!/usr/bin/python3
"""Tests of the peers in bench/peers (Debian's python3-numpy and python3-scipy; mechgraph from
$MECHGRAPH or build/bin/mechgraph, the tests that need it skipped without it).

    /usr/bin/python3 bench/peers/test_peers.py [-v] [-k NAME]

What is tested, each against an independent value:
  * the grid peer's machinery (crossings, Simpson with the cut end cells, peaks) on a law whose
    time-area and acceleration peaks have a closed form of their own (a half sine);
  * the closed-form peer against the grid peer at a fine step, on designs that take every branch
    (the Kurz cam opening in each of its three pieces, the three-arc opening on its nose, the
    smooth and the minimax Kurz split, no lash at all);
  * both stage 1-3 peers against mechgraph's sweep rows on the same designs (the study's and the
    hard ones), and the check failing when a peer is off;
  * the Monte Carlo peer: the clipped-normal moments against numerical integration, the tail-kept
    quantiles against numpy's quantile of all the samples, the sample moments against the exact
    ones;
  * run.sh --quick end to end: every peer verified and timed, three ratio lines, exit status 0;
  * side_by_side.py with one build on both sides: the rows agree, both sides timed, a ratio line.
"""

import math
import os
import subprocess
import sys
import tempfile
import unittest

sys.dont_write_bytecode = True
HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, HERE)

import numpy as np  # noqa: E402
from scipy import integrate  # noqa: E402

import backlash_chain_mc as mc  # noqa: E402
import stages123_cases as cases_mod  # noqa: E402
import stages123_closed_form as closed_form  # noqa: E402
import stages123_grid as grid  # noqa: E402

MECHGRAPH = cases_mod.default_exe(ROOT)
HAVE_MECHGRAPH = os.access(MECHGRAPH, os.X_OK)
DEG = math.pi / 180.0

# Designs that take every branch: (lift mm, action deg, accel deg, r0 mm, rpm, lash mm).
HARD = [(8.0, 130.0, 18.0, 28.0, 5600.0, 0.0),     # no lash: open over the whole event
        (9.0, 120.0, 21.0, 28.0, 7000.0, 0.01),    # a hair of lash
        (8.0, 130.0, 18.0, 28.0, 5600.0, 1.0),     # Kurz opens in its quarter cosine
        (7.0, 140.0, 15.0, 28.0, 4000.0, 2.5),     # Kurz opens in its parabola
        (8.0, 130.0, 18.0, 28.0, 5600.0, 6.0),     # three-arc opens on its nose
        (8.0, 130.0, 35.0, 28.0, 5600.0, 0.25),    # Kurz with the smooth split (h''' continuous)
        (7.0, 140.0, 15.0, 24.0, 4000.0, 0.4),     # the study's corners
        (9.0, 120.0, 21.0, 24.0, 7000.0, 0.1)]


def hard_cases():
    names = [name for name, _, _, _ in cases_mod.RANGES]
    return {name: np.array([row[j] for row in HARD]) for j, name in enumerate(names)}


def rel(a, b):
    return np.abs(np.asarray(a) - np.asarray(b)) / np.abs(np.asarray(b))


class GridMachinery(unittest.TestCase):
    """valve_on_grid on h = A sin(pi phi / L) over [0, L]: x = i h - lash opens at
    sin(pi phi_o / L) = s0 = lash / (i A); int f_v over the open period and the peaks in closed form."""

    def test_half_sine(self):
        A, L, i, lash, k1, k2 = 8e-3, 130 * DEG, 1.5, 0.3e-3, 0.07, 2.2
        law = lambda phi: (A * np.sin(math.pi * phi / L), -A * (math.pi / L) ** 2 * np.sin(math.pi * phi / L))
        s0 = lash / (i * A)
        t0 = math.asin(s0)                       # theta = pi phi / L at the opening
        t1 = math.pi - t0
        # int x dphi = (L/pi) int (i A sin t - lash) dt, int x^2 likewise
        ix = (L / math.pi) * (i * A * (math.cos(t0) - math.cos(t1)) - lash * (t1 - t0))
        ixx = (L / math.pi) * (i * i * A * A * (0.5 * (t1 - t0) - 0.25 * (math.sin(2 * t1) - math.sin(2 * t0)))
                               - 2 * i * A * lash * (math.cos(t0) - math.cos(t1)) + lash * lash * (t1 - t0))
        want = k1 * ix + k2 * ixx
        for G in (2001, 2002):                   # an even and an odd number of open intervals
            phi = np.linspace(0.0, L, G)[None, :]
            d = np.array([[L / (G - 1)]])
            got, hi, lo = grid.valve_on_grid(law, phi, d, i, lash, k1, k2)
            self.assertLess(rel(got[0], want), 1e-10, G)
            # h'' is least at the nose, greatest at the opening (the edge, from the law's value there)
            self.assertLess(rel(lo[0], -A * (math.pi / L) ** 2), 1e-12)
            self.assertLess(rel(hi[0], -A * (math.pi / L) ** 2 * s0), 1e-9)

    def test_inverse_cubic_is_exact_for_a_cubic_inverse(self):
        # phi = 0.3 + 0.5 x - 0.2 x^2 + 0.1 x^3 through four points: phi(0) = 0.3 exactly
        x = np.array([[-0.3, -0.1, 0.2, 0.5]])
        phi = 0.3 + 0.5 * x - 0.2 * x ** 2 + 0.1 * x ** 3
        self.assertAlmostEqual(float(grid._inverse_cubic(phi, x)[0]), 0.3, delta=1e-15)


class ClosedFormAgainstFineGrid(unittest.TestCase):
    """Two methods on the same laws: closed forms against the grid at 0.01 deg."""

    def test_every_branch(self):
        P = cases_mod.design_table(hard_cases())
        exact = closed_form.study(P)
        fine = grid.study(P, batch=len(HARD), step=0.01 * DEG)
        for name in cases_mod.OUTPUTS:
            for k in range(len(HARD)):
                if HARD[k][5] == 0.0 and name.startswith("ta_"):
                    bound = 1e-8     # no lash: the crossings are a double (or higher) zero at the event's ends
                else:
                    bound = 1e-7
                self.assertLess(rel(exact[name][k], fine[name][k]), bound, f"{name}, design {HARD[k]}")

    def test_study_sample(self):
        P = cases_mod.design_table(cases_mod.latin_hypercube(40, 7))
        exact = closed_form.study(P)
        fine = grid.study(P, batch=20, step=0.01 * DEG)
        for name in cases_mod.OUTPUTS:
            self.assertLess(float(np.max(rel(exact[name], fine[name]))), 1e-7, name)


@unittest.skipUnless(HAVE_MECHGRAPH, f"no mechgraph at {MECHGRAPH}")
class AgainstMechgraph(unittest.TestCase):

    def sweep(self, cases):
        work = tempfile.mkdtemp(prefix="mechgraph_peers_test_")
        self.addCleanup(lambda: subprocess.run(["rm", "-rf", work]))
        cases_csv, rows_csv = os.path.join(work, "cases.csv"), os.path.join(work, "rows.csv")
        cases = cases_mod.write_cases_csv(cases_csv, cases)
        cases_mod.run_sweep(MECHGRAPH, os.path.join(HERE, "stages123_study.yaml"), cases_csv, rows_csv)
        return cases, rows_csv

    def test_study_cases(self):
        cases, rows = self.sweep(cases_mod.latin_hypercube(60, 3))
        P = cases_mod.design_table(cases)
        ok, worst = cases_mod.verify("grid", grid.study(P, 25), cases, rows, 1e-6)
        self.assertTrue(ok, worst)
        ok, worst = cases_mod.verify("closed form", closed_form.study(P), cases, rows, 1e-9)
        self.assertTrue(ok, worst)

    def test_hard_cases_closed_form(self):
        cases, rows = self.sweep(hard_cases())
        ok, worst = cases_mod.verify("closed form", closed_form.study(cases_mod.design_table(cases)), cases, rows, 1e-9)
        self.assertTrue(ok, worst)

    def test_check_fails_when_a_peer_is_off(self):
        cases, rows = self.sweep(cases_mod.latin_hypercube(10, 5))
        got = closed_form.study(cases_mod.design_table(cases))
        got["ta_kurz.time_area"] = got["ta_kurz.time_area"] * (1.0 + 3e-9)
        self.assertFalse(cases_mod.verify("off by 3e-9", got, cases, rows, 1e-9)[0])
        other = cases_mod.latin_hypercube(10, 6)          # the right figures of other designs
        self.assertFalse(cases_mod.verify("other cases", got, other, rows, 1.0)[0])


class MonteCarlo(unittest.TestCase):

    def test_clipped_normal_moments_against_quadrature(self):
        means, sigmas = np.array([25e-6, 1e-6, -2e-6]), np.array([8e-6, 3e-6, 1e-6])
        m1 = m2 = 0.0
        for m, s in zip(means, sigmas):
            pdf = lambda x, m=m, s=s: math.exp(-0.5 * ((x - m) / s) ** 2) / (s * math.sqrt(2 * math.pi))
            a1 = integrate.quad(lambda x: x * pdf(x), 0.0, m + 12 * s, epsabs=0, epsrel=1e-13)[0]
            a2 = integrate.quad(lambda x: x * x * pdf(x), 0.0, m + 12 * s, epsabs=0, epsrel=1e-13)[0]
            m1, m2 = m1 + a1, m2 + a2 - a1 * a1
        mean, sigma = mc.exact_moments(means, sigmas)
        self.assertLess(abs(mean - m1) / m1, 1e-10)
        self.assertLess(abs(sigma - math.sqrt(m2)) / math.sqrt(m2), 1e-10)

    def test_tail_quantiles_are_numpys_of_all_samples(self):
        means, sigmas = mc.sampled_terms(mc.play_terms())
        n, block = 200_003, 1 << 14                       # several blocks, a short last one
        r = mc.monte_carlo(means, sigmas, n, usl=1e-3, seed=11, block=block)
        rng = np.random.Generator(np.random.SFC64(11))    # the same stream, every sample kept
        ys = []
        for start in range(0, n, block):
            m = min(block, n - start)
            z = rng.standard_normal(len(means) * m).reshape(len(means), m)
            ys.append(sigmas @ np.maximum(z, (-means / sigmas)[:, None]) + means.sum())
        y = np.concatenate(ys)
        self.assertEqual(r["q_high"], float(np.quantile(y, mc.P_HIGH)))
        self.assertEqual(r["q_low"], float(np.quantile(y, mc.P_LOW)))
        self.assertAlmostEqual(r["mean"], float(y.mean()), delta=1e-12 * y.mean())
        self.assertAlmostEqual(r["sigma"], float(y.std(ddof=1)), delta=1e-9 * y.std())
        self.assertEqual(r["out_of_spec"], float(np.count_nonzero(y > 1e-3)) / n)
        self.assertEqual(int(r["histogram"].sum()), n)
        self.assertEqual((r["min"], r["max"]), (float(y.min()), float(y.max())))

    def test_sample_moments_against_exact(self):
        means, sigmas = mc.sampled_terms(mc.play_terms())
        n = 1_000_000
        r = mc.monte_carlo(means, sigmas, n, usl=1e-3, seed=3)
        mean, sigma = mc.exact_moments(means, sigmas)
        self.assertLess(abs(r["mean"] - mean) / (sigma / math.sqrt(n)), 4.0)
        self.assertLess(abs(r["sigma"] - sigma) / (sigma / math.sqrt(2.0 * (n - 1))), 4.0)


@unittest.skipUnless(HAVE_MECHGRAPH, f"no mechgraph at {MECHGRAPH}")
class RunScript(unittest.TestCase):

    def test_quick(self):
        proc = subprocess.run([os.path.join(HERE, "run.sh"), "--quick"], capture_output=True, text=True,
                              env={**os.environ, "MECHGRAPH": MECHGRAPH})
        self.assertEqual(proc.returncode, 0, proc.stdout[-3000:] + proc.stderr[-3000:])
        summary = proc.stdout.split("=== summary")[-1]
        for name in ("dynamics: ratio dynamics", "stages123: ratio stages 1-3 vs grid peer",
                     "stages123: ratio stages 1-3 vs closed-form peer", "mc: ratio Monte Carlo"):
            self.assertIn(name, summary)
        self.assertNotIn("FAILED", summary)
        self.assertEqual(proc.stdout.count("verify grid peer (0.045 deg): ok"), 1)
        self.assertEqual(proc.stdout.count("verify closed-form peer: ok"), 1)
        self.assertEqual(proc.stdout.count("verify Monte Carlo peer: ok"), 1)


@unittest.skipUnless(HAVE_MECHGRAPH, f"no mechgraph at {MECHGRAPH}")
class SideBySide(unittest.TestCase):

    def test_one_build_against_itself(self):
        proc = subprocess.run([sys.executable, os.path.join(HERE, "side_by_side.py"), "--before", MECHGRAPH,
                               "--after", MECHGRAPH, "--cases", "10", "--rounds", "2"], capture_output=True, text=True)
        self.assertEqual(proc.returncode, 0, proc.stdout[-3000:] + proc.stderr[-3000:])
        self.assertIn("30 designs", proc.stdout)
        lines = proc.stdout.splitlines()
        for side in ("before", "after"):
            self.assertEqual(sum(line.startswith(side + " ") and "wall fastest" in line for line in lines), 1)
        self.assertIn("after / before, designs/s (fastest runs):", proc.stdout)


if __name__ == "__main__":
    unittest.main()
