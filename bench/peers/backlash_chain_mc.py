#!/usr/bin/python3
"""Peer benchmark: the Monte Carlo of mechgraph's `backlash.chain` (scenes/backlash_chain.yaml,
effect monte_carlo) against the same model written in numpy the way an engineer would: every
random size drawn with numpy's default_rng, vectorised over all samples at once.

Requirements: Debian's /usr/bin/python3 with python3-numpy; a built mechgraph CLI.

Usage:
    /usr/bin/python3 bench/peers/backlash_chain_mc.py [--mechgraph build/bin/mechgraph]
        [--scene scenes/backlash_chain.yaml] [--samples 10000000] [--repeats 3] [--quick]
or bench/peers/run.sh, which runs every peer. MECHGRAPH in the environment names the CLI.

The model (docs/methods/backlash.md; plugins/fits, plugins/joints, plugins/backlash): five hinges
on the rod's line (transfer ratios 1) and the actuator's own backlash; every play peak to peak.
  * fit "D H11/h11" (fit.iso286): hole diameter deviation normal around the middle of its zone
    [0, +IT11], shaft deviation normal around the middle of [-IT11, 0], each sigma = tolerance/6
    (tolerance = 6 sigma, the default distribution); the fit's play term is max(0, hole - shaft).
    IT11 from ISO 286-1: 110 um for 10 < D <= 18 mm (the 16 mm pins), 130 um for 18 < D <= 30 mm
    (20 and 25 mm).
  * joint.pin (h1, h3, h4): the one fit's term.
  * joint.spherical (h2, h5): the fit's term plus the bearing's radial internal clearance, a
    term of its own, normal over the ISO 12240-1 "normal" group range (range = 6 sigma), clipped
    at zero: 40-82 um for bores 12 < d <= 20 mm (h2, 20 mm), 50-100 um for 20 < d <= 35 mm (h5,
    25 mm).
  * the actuator: normal, mean 25 um, limit 25 um = 3 sigma, clipped at zero.
  * rod backlash = the actuator's term + every hinge's play terms (seven: five fits, two
    bearings), each term clipped at zero on its own, transfer ratios 1.
The script derives these from the two small tables above and checks them against mechgraph's own
h*.play_min / play_mean / play_max (`mechgraph run --json`) before sampling.
Reported as mechgraph does: mean, standard deviation (divisor N - 1) and the quantile at
Phi(3) = 99.865 % (linear between order statistics, numpy's default method = mechgraph's).

Two numpy variants are timed:
  * "hole and shaft apart": each hole and each shaft drawn on its own (13 normal draws per
    sample), the model as written above -- the script an engineer writes;
  * "one normal per fit": hole - shaft of a fit drawn as a single normal of variance
    sigma_hole^2 + sigma_shaft^2 (the same distribution; 8 draws per sample), which is what
    mechgraph does (plugins/backlash/stacking.cpp, CompiledSum).
The two give different random samples (same distribution), so both are compared with mechgraph
within their standard errors, not digit for digit: mechgraph uses its own generator
(xoshiro256++ and a ziggurat, plugins/backlash/variates.hpp), numpy PCG64 and its ziggurat.

Timing. mechgraph: `nodes.chain.seconds` of `mechgraph run --json --set chain.samples=N` (the
chain node alone: sampling, sums, mean, sigma, quantile; no process start). numpy: perf_counter
around drawing, summing, mean, std and quantile. Best of --repeats for each, in rounds.
"""

import argparse
import json
import math
import os
import subprocess
import tempfile
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
UM = 1e-6

# ISO 286-1 standard tolerance IT11 by nominal size range (mm, exclusive lower, inclusive upper).
IT11_UM = ((10.0, 18.0, 110.0), (18.0, 30.0, 130.0))
# ISO 12240-1 radial internal clearance, group "normal", steel/steel series E, by bore (mm): um.
NORMAL_CLEARANCE_UM = ((12.0, 20.0, 40.0, 82.0), (20.0, 35.0, 50.0, 100.0))

# The chain of scenes/backlash_chain.yaml: (node, kind, fit size mm, bearing bore mm or None).
HINGES = (("h1", "pin", 20.0, None), ("h2", "spherical", 20.0, 20.0), ("h3", "pin", 16.0, None),
          ("h4", "pin", 16.0, None), ("h5", "spherical", 25.0, 25.0))
ACTUATOR_MEAN = 25.0 * UM
ACTUATOR_SIGMA = 25.0 * UM / 3.0
P_HIGH = 1.0 - 0.5 * math.erfc(3.0 / math.sqrt(2.0))    # Phi(3) = 0.99865...


def lookup(table, size):
    for row in table:
        if row[0] < size <= row[1]:
            return row[2:]
    raise ValueError(f"size {size} mm is outside the table")


def play_terms():
    """Every play term of the chain as (hinge, label, kind, parameters), SI:
    ("fit", (hole_mean, hole_sigma, shaft_mean, shaft_sigma)) or ("normal", (mean, sigma))."""
    terms = []
    for node, kind, size, bore in HINGES:
        it = lookup(IT11_UM, size)[0] * UM
        # H11: hole deviations [0, +IT]; h11: shaft deviations [-IT, 0]; sigma = IT/6.
        terms.append((node, f"{size:g} H11/h11", "fit", (0.5 * it, it / 6.0, -0.5 * it, it / 6.0)))
        if kind == "spherical":
            lo, hi = (v * UM for v in lookup(NORMAL_CLEARANCE_UM, bore))
            terms.append((node, f"bearing {bore:g} mm CN", "normal", (0.5 * (lo + hi), (hi - lo) / 6.0)))
    return terms


def hinge_figures(terms):
    """play_min / play_mean / play_max per hinge as mechgraph's joints report them: sums over the
    terms of the clipped least, mean and greatest clearance (the range is +-3 sigma)."""
    out = {}
    for node, _, kind, p in terms:
        if kind == "fit":
            mean, half = p[0] - p[2], 3.0 * (p[1] + p[3])
        else:
            mean, half = p[0], 3.0 * p[1]
        lo, mid, hi = out.get(node, (0.0, 0.0, 0.0))
        out[node] = (lo + max(0.0, mean - half), mid + max(0.0, mean), hi + max(0.0, mean + half))
    return out


def monte_carlo(terms, n, seed, one_normal_per_fit):
    """n samples of the rod backlash, and their mean, sigma and Phi(3) quantile."""
    rng = np.random.default_rng(seed)
    total = np.maximum(rng.normal(ACTUATOR_MEAN, ACTUATOR_SIGMA, n), 0.0)
    for _, _, kind, p in terms:
        if kind == "fit" and one_normal_per_fit:
            clearance = rng.normal(p[0] - p[2], math.hypot(p[1], p[3]), n)
        elif kind == "fit":
            clearance = rng.normal(p[0], p[1], n) - rng.normal(p[2], p[3], n)
        else:
            clearance = rng.normal(p[0], p[1], n)
        total += np.maximum(clearance, 0.0)
    return total, float(np.mean(total)), float(np.std(total, ddof=1)), float(np.quantile(total, P_HIGH))


def run_mechgraph(exe, scene, n):
    proc = subprocess.run([exe, "-q", "run", scene, "--json", "--set", f"chain.samples={n}"],
                          capture_output=True, text=True)
    if proc.returncode != 0:
        raise RuntimeError(f"mechgraph run exited with {proc.returncode}: {proc.stderr.strip()}")
    return json.loads(proc.stdout)


def mechgraph_sigma(exe, scene, n):
    """rod_backlash_mc_sigma (not among the scene's report cells) from a one-case sweep."""
    fd, path = tempfile.mkstemp(prefix="mechgraph_mc_", suffix=".jsonl")
    os.close(fd)
    try:
        proc = subprocess.run([exe, "-q", "sweep", scene, "--vary", f"chain.samples={n}", "--threads", "1",
                               "--outputs", "chain.rod_backlash_mc_sigma", "--format", "jsonl", "--out", path,
                               "--force"], capture_output=True, text=True)
        if proc.returncode != 0:
            raise RuntimeError(f"mechgraph sweep exited with {proc.returncode}: {proc.stderr.strip()}")
        with open(path) as fh:
            row = json.loads(fh.readline())
    finally:
        for p in (path, path + ".json"):
            if os.path.exists(p):
                os.remove(p)
    (key,) = [k for k in row if k.startswith("chain.rod_backlash_mc_sigma")]
    return row[key] * {"[um]": UM, "[mm]": 1e-3, "[m]": 1.0}[key.split(" ")[-1]]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--mechgraph", default=os.environ.get("MECHGRAPH", os.path.join(ROOT, "build", "bin", "mechgraph")))
    ap.add_argument("--scene", default=os.path.join(ROOT, "scenes", "backlash_chain.yaml"))
    ap.add_argument("--samples", type=int, default=10_000_000, help="Monte Carlo samples (default 1e7)")
    ap.add_argument("--repeats", type=int, default=3, help="timed runs per side; the fastest counts (default 3)")
    ap.add_argument("--seed", type=int, default=1, help="numpy's seed (default 1)")
    ap.add_argument("--quick", action="store_true", help="2e6 samples, 2 repetitions")
    args = ap.parse_args()
    if args.quick:
        args.samples, args.repeats = min(args.samples, 2_000_000), min(args.repeats, 2)
    n = args.samples
    print(f"mechgraph: {args.mechgraph}\nscene:     {args.scene}\nsamples:   {n:.3g} per run")

    # --- The model against mechgraph's per-hinge figures.
    terms = play_terms()
    ref = run_mechgraph(args.mechgraph, args.scene, n)
    out = {k: v["value"] for k, v in ref["outputs"].items()}
    mine = hinge_figures(terms)
    worst = 0.0
    print("\nplay per hinge, um (this script's model | mechgraph):")
    for node, _, _, _ in HINGES:
        a = mine[node]
        b = tuple(out[f"{node}.play_{k}"] for k in ("min", "mean", "max"))
        worst = max(worst, max(abs(x - y) for x, y in zip(a, b)))
        print(f"  {node}: min {a[0] / UM:6.1f} | {b[0] / UM:6.1f}   mean {a[1] / UM:6.1f} | {b[1] / UM:6.1f}   "
              f"max {a[2] / UM:6.1f} | {b[2] / UM:6.1f}")
    print(f"  largest difference {worst / UM:.2g} um; terms: " + ", ".join(f"{t[0]} {t[1]}" for t in terms)
          + ", actuator 25 +- 25 um")

    # --- Timing, in rounds.
    variants = [("numpy, hole and shaft apart (the script)", False), ("numpy, one normal per fit (as mechgraph)", True)]
    best = {"mechgraph": math.inf, **{name: math.inf for name, _ in variants}}
    stats = {}
    for r in range(args.repeats):
        d = ref if r == 0 else run_mechgraph(args.mechgraph, args.scene, n)
        best["mechgraph"] = min(best["mechgraph"], d["nodes"]["chain"]["seconds"])
        for name, merged in variants:
            t0 = time.perf_counter()
            total, mean, sigma, q = monte_carlo(terms, n, args.seed, merged)
            best[name] = min(best[name], time.perf_counter() - t0)
            if name not in stats:
                # Density at the quantile (for its standard error), from neighbouring quantiles; untimed.
                lo, hi = np.quantile(total, [P_HIGH - 2e-4, P_HIGH + 2e-4])
                stats[name] = (mean, sigma, q, 4e-4 / (hi - lo))
            del total
    m_mean = out["chain.rod_backlash_mc_mean"]
    m_q = out["chain.rod_backlash_mc_q999"]
    m_sigma = mechgraph_sigma(args.mechgraph, args.scene, n)

    print(f"\nrod backlash statistics, {n:.3g} samples (um); z = difference / its standard error "
          "(both samples' errors combined):")
    print(f"{'side':42s} {'mean':>10s} {'sigma':>9s} {'q99.865%':>10s} {'z(mean)':>8s} {'z(sigma)':>9s} {'z(q)':>6s}")
    print(f"{'mechgraph (xoshiro256++, ziggurat)':42s} {m_mean / UM:10.4f} {m_sigma / UM:9.4f} {m_q / UM:10.4f}")
    for name, _ in variants:
        mean, sigma, q, density = stats[name]
        se_mean = math.sqrt(2.0) * sigma / math.sqrt(n)
        se_sigma = math.sqrt(2.0) * sigma / math.sqrt(2.0 * (n - 1))   # normal approximation
        se_q = math.sqrt(2.0) * math.sqrt(P_HIGH * (1.0 - P_HIGH) / n) / density
        print(f"{name:42s} {mean / UM:10.4f} {sigma / UM:9.4f} {q / UM:10.4f} {(mean - m_mean) / se_mean:8.2f} "
              f"{(sigma - m_sigma) / se_sigma:9.2f} {(q - m_q) / se_q:6.2f}")
    mean, sigma, q, density = stats[variants[0][0]]
    print(f"(one sample's standard errors: mean {sigma / math.sqrt(n) / UM:.4f} um, "
          f"q99.865% {math.sqrt(P_HIGH * (1 - P_HIGH) / n) / density / UM:.4f} um)")

    print(f"\nMonte Carlo of the chain, samples per second on one core (fastest of {args.repeats}):")
    print(f"{'side':42s} {'seconds':>9s} {'samples/s':>12s} {'mechgraph / side':>17s}")
    rate_m = n / best["mechgraph"]
    print(f"{'mechgraph chain node (nodes.chain.seconds)':42s} {best['mechgraph']:9.3f} {rate_m:12.4g} {1.0:16.2f}x")
    for name, _ in variants:
        rate = n / best[name]
        print(f"{name:42s} {best[name]:9.3f} {rate:12.4g} {rate_m / rate:16.2f}x")
    r_script = best[variants[0][0]] / best["mechgraph"]
    r_merged = best[variants[1][0]] / best["mechgraph"]
    print(f"\nratio Monte Carlo, mechgraph / numpy (samples/s): {r_script:.1f}x against the script "
          f"(hole and shaft apart); {r_merged:.1f}x against numpy drawing one normal per fit as mechgraph does")


if __name__ == "__main__":
    main()
