#!/usr/bin/python3
"""Peer benchmark: the Monte Carlo of mechgraph's `backlash.chain` (scenes/backlash_chain.yaml,
effect monte_carlo) against the same model, the same figures and the same way of sampling written
in numpy: one normal per play term, clipped at zero, numpy's SFC64 generator, blocks of 65,536
samples.

Requirements: Debian's /usr/bin/python3 with python3-numpy; a built mechgraph CLI.

Usage:
    /usr/bin/python3 bench/peers/backlash_chain_mc.py [--mechgraph build/bin/mechgraph]
        [--scene scenes/backlash_chain.yaml] [--samples 10000000] [--repeats 3] [--quick]
or bench/peers/run.sh, which runs every peer. MECHGRAPH in the environment names the CLI.

The model (docs/methods/backlash.md; plugins/fits, plugins/joints, plugins/backlash): five hinges
on the rod's line (transfer ratios 1) and the actuator's own backlash; every play peak to peak.
  * fit "D H11/h11" (fit.iso286): hole deviation normal around the middle of [0, +IT11], shaft
    deviation normal around the middle of [-IT11, 0], each sigma = IT11/6; the fit's play term is
    max(0, hole - shaft). Hole and shaft are independent, so hole - shaft is ONE normal of mean
    IT11 and variance 2 (IT11/6)^2: drawn as one normal, exact in distribution, as mechgraph does.
    IT11 from ISO 286-1: 110 um for 10 < D <= 18 mm, 130 um for 18 < D <= 30 mm.
  * joint.pin (h1, h3, h4): the fit's term; joint.spherical (h2, h5): the fit's term plus the
    bearing's radial internal clearance, normal over the ISO 12240-1 "normal" group range
    (range = 6 sigma), clipped at zero: 40-82 um (bore 20 mm), 50-100 um (bore 25 mm).
  * the actuator: normal, mean 25 um, limit 25 um = 3 sigma, clipped at zero.
  * rod backlash y = sum of the eight clipped terms; nozzle backlash y / arm, the arm (500 mm) from
    the rod's attachment points and the swivel axis; the spec: at most 6.5 arcmin at the nozzle.
The script checks its terms against mechgraph's h*.play_min / play_mean / play_max and its arm
against chain.lever_arm before sampling.

Per block of 65,536 samples: 8 x 65,536 standard normals (SFC64, numpy's ziggurat) into one
buffer, each row clipped at -mean/sigma (max(0, m + s z) = s max(z, -m/s) + m), the rod play as
sigma . z + sum(m) (one matrix-vector product); then what mechgraph's streamed summary does per
block: sums and squares about a shift (the first sample), least and greatest, the count above the
spec, a 40-bin histogram over the first block's range widened by 10 bins each side, and the
samples beyond the first block's mean +- 2 sigma kept for the quantiles. At the end: mean,
sigma (N - 1), the Phi(-3) and Phi(3) quantiles (Hyndman-Fan type 7, numpy's default: by selection
among the kept tails), Cpk, the share out of spec with its standard error.

Verified before timing, statistically (the two generators differ: mechgraph xoshiro256++ and its
ziggurat): mean, sigma, the 99.865 % quantile and the share out of spec of both sides within 4
standard errors of their difference, and both sides' mean and sigma within 4 standard errors of
the exact mean and sigma of a sum of independent clipped normals. A failure stops the script
(exit status 1) before anything is timed.

Timing. mechgraph: `mechgraph run SCENE --json --set chain.samples=N`, the whole process's wall
clock (start, plugins, scene, every node) and the chain node's own `seconds`. numpy:
time.perf_counter around sampling and summary (not Python's start or numpy's import). Best of
--repeats for each, taken in rounds. One core each.
"""

import argparse
import json
import math
import os
import subprocess
import sys
import tempfile
import time

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")   # one core, as mechgraph's chain node
import numpy as np  # noqa: E402

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



ARCMIN = math.pi / 10800.0
SPEC_ARCMIN = 6.5
P_LOW = 1.0 - P_HIGH
BLOCK = 1 << 16
BINS = 40
# The rod's attachment points and the swivel axis of the scene's chain node (m).
ROD_FIXED, ROD_MOVING = np.array([0.0, 0.5, -0.4]), np.array([0.0, 0.5, 0.2])
AXIS_POINT, AXIS_DIRECTION = np.zeros(3), np.array([1.0, 0.0, 0.0])


def lever_arm():
    """Moment arm of the rod about the swivel axis: |((P - A) x u) . n|, u the rod's direction."""
    u = (ROD_MOVING - ROD_FIXED) / np.linalg.norm(ROD_MOVING - ROD_FIXED)
    n = AXIS_DIRECTION / np.linalg.norm(AXIS_DIRECTION)
    return float(abs(np.cross(ROD_MOVING - AXIS_POINT, u) @ n))


def sampled_terms(terms):
    """(mean, sigma) of each clipped normal the chain adds, the actuator first: one per fit
    (hole - shaft, variances added), one per bearing clearance."""
    means, sigmas = [ACTUATOR_MEAN], [ACTUATOR_SIGMA]
    for _, _, kind, p in terms:
        if kind == "fit":
            means.append(p[0] - p[2])
            sigmas.append(math.hypot(p[1], p[3]))
        else:
            means.append(p[0])
            sigmas.append(p[1])
    return np.array(means), np.array(sigmas)


def exact_moments(means, sigmas):
    """Mean and sigma of a sum of independent max(0, N(m, s^2)): per term, with a = m/s,
    E = m Phi(a) + s phi(a), E[X^2] = (m^2 + s^2) Phi(a) + m s phi(a)."""
    a = means / sigmas
    Phi = np.array([0.5 * math.erfc(-v / math.sqrt(2.0)) for v in a])
    phi = np.exp(-0.5 * a * a) / math.sqrt(2.0 * math.pi)
    m1 = means * Phi + sigmas * phi
    m2 = (means * means + sigmas * sigmas) * Phi + means * sigmas * phi
    return float(m1.sum()), float(math.sqrt((m2 - m1 * m1).sum()))


def monte_carlo(means, sigmas, n, usl, seed=1, block=BLOCK, bins=BINS):
    """n samples of the rod backlash, summarised block by block; a dict of the figures."""
    rng = np.random.Generator(np.random.SFC64(seed))
    k = len(means)
    floor = (-means / sigmas)[:, None]
    offset = float(means.sum())
    buffer = np.empty(k * block)
    total = squares = 0.0
    above = 0
    low = high = shift = None
    t_low = t_high = None
    edges = None
    counts = np.zeros(bins + 20, dtype=np.int64)
    scaled, cell = np.empty(block), np.empty(block, dtype=np.intp)     # the histogram's scratch
    low_tails, high_tails = [], []
    for start in range(0, n, block):
        m = min(block, n - start)
        z = buffer[:k * m].reshape(k, m)             # contiguous for the generator to fill
        rng.standard_normal(out=z)
        np.maximum(z, floor, out=z)
        y = sigmas @ z
        y += offset
        if shift is None:                 # the first block sets the shift, tails and bins
            shift, low, high = float(y[0]), float(y[0]), float(y[0])
            mu, sd = float(y.mean()), float(y.std())
            t_low, t_high = (mu - 2.0 * sd, mu + 2.0 * sd) if n > block else (math.inf, -math.inf)
            width = (float(y.max()) - float(y.min())) / bins
            edges = (float(y.min()) - 10.0 * width, width)
        d = y - shift
        total += float(d.sum())
        squares += float(d @ d)
        low, high = min(low, float(y.min())), max(high, float(y.max()))
        above += int(np.count_nonzero(y > usl))
        u = scaled[:m]
        np.subtract(y, edges[0], out=u)
        u *= 1.0 / edges[1]
        np.clip(u, 0.0, len(counts) - 1, out=u)       # beyond the bins: into the end bins
        cell[:m] = u
        counts += np.bincount(cell[:m], minlength=len(counts))
        low_tails.append(y[y < t_low])
        high_tails.append(y[y > t_high])
    low_tail, high_tail = np.concatenate(low_tails), np.concatenate(high_tails)

    def quantile(p, tail, first):
        """Type-7 quantile from the tail that holds ranks first .. first + len(tail) - 1."""
        h = (n - 1) * p
        r = int(math.floor(h))
        if r < first or r + 1 >= first + len(tail):
            raise RuntimeError(f"the kept tail does not hold rank {r} (threshold too close)")
        part = np.partition(tail, (r - first, r - first + 1))
        return float(part[r - first] + (h - r) * (part[r - first + 1] - part[r - first]))

    mean = shift + total / n
    sigma = math.sqrt(max(0.0, (squares - total * total / n) / (n - 1)))
    share = above / n
    return {"mean": mean, "sigma": sigma, "min": low, "max": high,
            "q_low": quantile(P_LOW, low_tail, 0), "q_high": quantile(P_HIGH, high_tail, n - len(high_tail)),
            "out_of_spec": share, "out_of_spec_error": math.sqrt(share * (1.0 - share) / n),
            "cpk": (usl - mean) / (3.0 * sigma), "histogram": counts}


# --- mechgraph's side ------------------------------------------------------------------------------
UNIT = {"um": UM, "mm": 1e-3, "m": 1.0, "arcmin": ARCMIN, "ppm": 1e-6, "1": 1.0}


def mechgraph_figures(exe, scene, n):
    """The chain's Monte Carlo figures for n samples (SI), from a one-case sweep (JSON Lines)."""
    names = ("rod_backlash_mc_mean", "rod_backlash_mc_sigma", "rod_backlash_mc_q999", "mc_out_of_spec",
             "lever_arm", "mc_cpk")
    fd, path = tempfile.mkstemp(prefix="mechgraph_mc_", suffix=".jsonl")
    os.close(fd)
    os.remove(path)
    try:
        proc = subprocess.run([exe, "-q", "sweep", scene, "--vary", f"chain.samples={n}", "--threads", "1",
                               "--outputs", ",".join(f"chain.{k}" for k in names), "--format", "jsonl",
                               "--out", path], capture_output=True, text=True)
        if proc.returncode != 0:
            raise RuntimeError(f"mechgraph sweep exited with {proc.returncode}: {proc.stderr.strip()}")
        with open(path) as fh:
            row = json.loads(fh.readline())
    finally:
        for p in (path, path + ".json", path + ".lock"):
            if os.path.exists(p):
                os.remove(p)
    out = {}
    for key, value in row.items():
        if key.startswith("chain."):
            name, _, unit = key[len("chain."):].partition(" [")
            out[name] = value * UNIT[unit.rstrip("]") or "1"]
    return out


def run_mechgraph(exe, scene, n):
    """(whole process seconds, chain node seconds, the JSON) of `mechgraph run --json`."""
    t0 = time.perf_counter()
    proc = subprocess.run([exe, "-q", "run", scene, "--json", "--set", f"chain.samples={n}"],
                          capture_output=True, text=True)
    wall = time.perf_counter() - t0
    if proc.returncode != 0:
        raise RuntimeError(f"mechgraph run exited with {proc.returncode}: {proc.stderr.strip()}")
    d = json.loads(proc.stdout)
    return wall, d["nodes"]["chain"]["seconds"], d


def check_model(exe, scene, terms, arm):
    """The terms' clipped least, mean and greatest play per hinge and the arm against mechgraph's."""
    _, _, d = run_mechgraph(exe, scene, 1000)
    out = {k: v["value"] for k, v in d["outputs"].items() if isinstance(v.get("value"), (int, float))}
    mine = hinge_figures(terms)
    worst = max(abs(a - out[f"{node}.play_{k}"]) for node, _, _, _ in HINGES
                for a, k in zip(mine[node], ("min", "mean", "max")))
    arm_diff = abs(arm - out["chain.lever_arm"])
    print(f"model:     per-hinge least/mean/greatest play against mechgraph's: largest difference "
          f"{worst / UM:.2g} um; arm {arm * 1e3:g} mm (mechgraph {out['chain.lever_arm'] * 1e3:g} mm)")
    return worst <= 1e-12 and arm_diff <= 1e-12


def verify(peer, theirs, means, sigmas, n, arm):
    """Both sides' figures within 4 standard errors of each other and of the exact moments."""
    s = peer["sigma"]
    # Density of the rod play at the quantile, from the peer's histogram, for the quantile's error.
    z3 = (peer["q_high"] - peer["mean"]) / s
    density = math.exp(-0.5 * z3 * z3) / (s * math.sqrt(2.0 * math.pi))
    se_q = math.sqrt(P_HIGH * (1.0 - P_HIGH) / n) / density
    share = 0.5 * (peer["out_of_spec"] + theirs["mc_out_of_spec"])
    rows = [("rod mean", peer["mean"], theirs["rod_backlash_mc_mean"], s / math.sqrt(n), UM, "um"),
            ("rod sigma", s, theirs["rod_backlash_mc_sigma"], s / math.sqrt(2.0 * (n - 1)), UM, "um"),
            ("rod q99.865 %", peer["q_high"], theirs["rod_backlash_mc_q999"], se_q, UM, "um"),
            ("out of spec", peer["out_of_spec"], theirs["mc_out_of_spec"], math.sqrt(share * (1 - share) / n), 1e-6, "ppm")]
    exact_mean, exact_sigma = exact_moments(means, sigmas)
    exact = {"rod mean": exact_mean, "rod sigma": exact_sigma}
    worst = 0.0
    print(f"\nverify, {n:.3g} samples each: numpy | mechgraph | exact; z = difference / its standard error")
    for name, a, b, se, scale, unit in rows:
        z = (a - b) / (math.sqrt(2.0) * se)
        worst = max(worst, abs(z))
        line = f"  {name:14s} {a / scale:12.5f} | {b / scale:12.5f} | "
        if name in exact:
            za, zb = (a - exact[name]) / se, (b - exact[name]) / se
            worst = max(worst, abs(za), abs(zb))
            line += f"{exact[name] / scale:12.5f} {unit:4s} z {z:+.2f} (numpy {za:+.2f}, mechgraph {zb:+.2f} vs exact)"
        else:
            line += f"{'-':>12s} {unit:4s} z {z:+.2f}"
        print(line)
    print(f"  Cpk            {peer['cpk']:12.5f} | {theirs['mc_cpk']:12.5f}; "
          f"nozzle q99.865 % {peer['q_high'] / arm / ARCMIN:.5f} arcmin (numpy)")
    ok = worst <= 4.0
    print(f"  verify Monte Carlo peer: {'ok' if ok else 'FAILED'} (worst |z| {worst:.2f}, bound 4)")
    return ok


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--mechgraph", default=os.environ.get("MECHGRAPH", os.path.join(ROOT, "build", "bin", "mechgraph")))
    ap.add_argument("--scene", default=os.path.join(ROOT, "scenes", "backlash_chain.yaml"))
    ap.add_argument("--samples", type=int, default=10_000_000, help="Monte Carlo samples (default 1e7)")
    ap.add_argument("--repeats", type=int, default=3, help="timing rounds; each side's fastest counts (default 3)")
    ap.add_argument("--seed", type=int, default=1, help="numpy's seed (default 1)")
    ap.add_argument("--quick", action="store_true", help="2e6 samples, 2 rounds")
    args = ap.parse_args()
    if args.quick:
        args.samples, args.repeats = min(args.samples, 2_000_000), min(args.repeats, 2)
    n = args.samples
    print(f"mechgraph: {args.mechgraph}\nscene:     {os.path.relpath(args.scene, ROOT)}\nsamples:   {n:.3g} per run, "
          f"numpy SFC64, one normal per term (8 per sample), blocks of {BLOCK}")
    terms = play_terms()
    means, sigmas = sampled_terms(terms)
    arm = lever_arm()
    usl = SPEC_ARCMIN * ARCMIN * arm
    if not check_model(args.mechgraph, args.scene, terms, arm):
        print("backlash_chain_mc: the model differs from mechgraph's; nothing timed", file=sys.stderr)
        sys.exit(1)
    peer = monte_carlo(means, sigmas, n, usl, args.seed)
    if not verify(peer, mechgraph_figures(args.mechgraph, args.scene, n), means, sigmas, n, arm):
        print("backlash_chain_mc: the peer disagrees with mechgraph; nothing timed", file=sys.stderr)
        sys.exit(1)

    best = {"wall": math.inf, "node": math.inf, "numpy": math.inf}
    for _ in range(args.repeats):
        wall, node, _ = run_mechgraph(args.mechgraph, args.scene, n)
        best["wall"], best["node"] = min(best["wall"], wall), min(best["node"], node)
        t0 = time.perf_counter()
        monte_carlo(means, sigmas, n, usl, args.seed)
        best["numpy"] = min(best["numpy"], time.perf_counter() - t0)
    rate = {k: n / v for k, v in best.items()}
    print(f"\nMonte Carlo of the chain, samples per second on one core (fastest of {args.repeats} rounds):")
    print(f"{'side':52s} {'seconds':>9s} {'samples/s':>11s}")
    print(f"{'mechgraph run (whole process)':52s} {best['wall']:9.3f} {rate['wall']:11.4g}")
    print(f"{'mechgraph chain node (nodes.chain.seconds)':52s} {best['node']:9.3f} {rate['node']:11.4g}")
    print(f"{'numpy, one normal per term, SFC64, blocks of 65,536':52s} {best['numpy']:9.3f} {rate['numpy']:11.4g}")
    print(f"\nratio Monte Carlo (mechgraph whole process / numpy, samples/s): {rate['wall'] / rate['numpy']:.2f}x "
          f"({rate['node'] / rate['numpy']:.2f}x counting the chain node alone; goal >= 4x)")


if __name__ == "__main__":
    main()
