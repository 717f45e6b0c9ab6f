#!/usr/bin/python3
"""Peer benchmark: stages 1-3 of the three-cam study (bench/peers/stages123_study.yaml, eight
outputs) as a `mechgraph sweep` on one thread against two numpy peers doing the same designs:

  grid peer         stages123_grid.py: the laws as black boxes on a 0.045 deg grid per design,
                    vectorised across designs, Simpson time-area, parabolic peaks (bound 1e-6);
  closed-form peer  stages123_closed_form.py: the three laws' closed forms (exact openings and
                    integrals, peaks where the laws have them), all designs at once (bound 1e-9).

Requirements: Debian's /usr/bin/python3 with python3-numpy; a built mechgraph CLI.

Usage:
    /usr/bin/python3 bench/peers/valvetrain_stages123.py [--mechgraph build/bin/mechgraph]
        [--cases 1000] [--seed 1] [--repeats 5] [--batches 10,25,50,100] [--quick] [--default-malloc]
or bench/peers/run.sh, which runs every peer. MECHGRAPH in the environment names the CLI.

The cases: a Latin hypercube over lift 7-9 mm, action angle 120-140 deg, positive-acceleration angle
15-21 deg, base radius 24-28 mm, 4000-7000 rpm and lash 0.1-0.4 mm (so every law changes shape),
written to a CSV that the sweep reads with --cases (stages123_cases.py): the same designs, the same
text, on both sides. One case is three designs (three cams).

Order of work: (1) one sweep, and both peers on its cases, each peer checked against the sweep's
rows (every output, relative difference): a peer beyond its bound, a failed case or another case
table stops the script with exit status 1 before anything is timed; (2) timing in rounds, each
round one sweep, the grid peer at every batch size and the closed-form peer, so that load elsewhere
on the machine spoils no single side; each side's fastest run counts, the grid peer at its fastest
batch size.

Timing. mechgraph: the whole process's wall clock (start, plugin loading, scene, cases file, the
evaluation and the rows written to standard output, read through a pipe), and the sweep's own log
line for reference; the peers keep their results in memory. Beside it, the same sweep with --out
FILE, which puts the rows and the manifest beside them on the disk (each fsync-ed before its rename:
a cost of the disk, several milliseconds on a virtual machine's, not of the computation). Step (1)
checks that both ways write the same bytes. The peers:
time.perf_counter around the computation of the eight outputs from the SI case arrays (Python's
start, numpy's import and reading the cases are not counted: in the peers' favour). One core each.
The script raises glibc's malloc thresholds for its own process (--default-malloc leaves them):
with the defaults every numpy temporary above 128 KiB is mapped and unmapped afresh, which makes
the batched grid peer several times slower; mechgraph runs in its own process, unaffected.
"""

import argparse
import ctypes
import math
import os
import shutil
import sys
import tempfile
import time

sys.dont_write_bytecode = True
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")   # one core, as mechgraph's sweep --threads 1
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import stages123_cases as cases_mod          # noqa: E402
import stages123_closed_form as closed_form  # noqa: E402
import stages123_grid as grid                # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
GRID_BOUND = 1e-6
CLOSED_FORM_BOUND = 1e-9


def keep_freed_memory():
    """glibc's M_MMAP_THRESHOLD to 32 MiB and M_TRIM_THRESHOLD to 1 GiB: freed temporaries stay in
    the process. True when glibc took both."""
    try:
        libc = ctypes.CDLL("libc.so.6")
        return bool(libc.mallopt(-3, 32 << 20)) and bool(libc.mallopt(-1, 1 << 30))
    except (OSError, AttributeError):
        return False


def timed(fn, *args):
    t0 = time.perf_counter()
    result = fn(*args)
    return time.perf_counter() - t0, result


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--mechgraph", default=cases_mod.default_exe(ROOT))
    ap.add_argument("--scene", default=os.path.join(HERE, "stages123_study.yaml"))
    ap.add_argument("--cases", type=int, default=1000, help="Latin-hypercube cases, 3 designs each (default 1000)")
    ap.add_argument("--seed", type=int, default=1, help="seed of the Latin hypercube (default 1)")
    ap.add_argument("--repeats", type=int, default=5, help="timing rounds; each side's fastest counts (default 5)")
    ap.add_argument("--batches", default="10,25,50,100", help="cases per batch tried for the grid peer")
    ap.add_argument("--quick", action="store_true", help="300 cases, 2 rounds, batches 10 and 50")
    ap.add_argument("--default-malloc", action="store_true", help="leave glibc's malloc thresholds alone")
    args = ap.parse_args()
    if args.quick:
        args.cases, args.repeats, args.batches = min(args.cases, 300), min(args.repeats, 2), "10,50"
    batches = [int(b) for b in args.batches.split(",")]
    tuned = False if args.default_malloc else keep_freed_memory()
    n = args.cases
    print(f"mechgraph: {args.mechgraph}\nscene:     {os.path.relpath(args.scene, ROOT)}")
    print(f"study:     {n} cases x 3 cams = {3 * n} designs, Latin hypercube seed {args.seed} over "
          + ", ".join(f"{name} {lo:g}-{hi:g} {unit}" for name, lo, hi, unit in cases_mod.RANGES)
          + f"; eight outputs; one thread; malloc thresholds {'raised' if tuned else 'default'}")

    work = tempfile.mkdtemp(prefix="mechgraph_stages123_")
    try:
        cases_csv, rows_csv = os.path.join(work, "cases.csv"), os.path.join(work, "rows.csv")
        cases = cases_mod.write_cases_csv(cases_csv, cases_mod.latin_hypercube(n, args.seed))
        P = cases_mod.design_table(cases)
        tables = closed_form.PolydyneTables(cases_mod.POLYDYNE_EXPONENTS)

        # (1) Agreement first: a peer that does not compute what mechgraph computes is not timed.
        cases_mod.run_sweep(args.mechgraph, args.scene, cases_csv, rows_csv)
        with open(rows_csv, "rb") as fh:
            if cases_mod.run_sweep_to_pipe(args.mechgraph, args.scene, cases_csv)[3] != fh.read():
                print("\nstages123: the sweep's rows on standard output differ from its --out file; nothing timed",
                      file=sys.stderr)
                sys.exit(1)
        print()
        ok_grid, worst_grid = cases_mod.verify("grid peer (0.045 deg)", grid.study(P, batches[0]), cases, rows_csv,
                                               GRID_BOUND)
        ok_closed, worst_closed = cases_mod.verify("closed-form peer", closed_form.study(P, tables=tables), cases,
                                                   rows_csv, CLOSED_FORM_BOUND)
        for b in batches[1:]:   # the batch size changes nothing but the speed: checked
            ok_b, _ = cases_mod.verify(f"grid peer, {b} cases a batch", grid.study(P, b), cases, rows_csv, GRID_BOUND)
            ok_grid = ok_grid and ok_b
        if not (ok_grid and ok_closed):
            print("\nstages123: a peer disagrees with mechgraph beyond its bound; nothing timed", file=sys.stderr)
            sys.exit(1)

        # (2) Timing in rounds.
        best = {"mechgraph": math.inf, "mechgraph log": math.inf, "mechgraph file": math.inf, "closed": math.inf}
        best.update({("grid", b): math.inf for b in batches})
        for _ in range(args.repeats):
            wall, log_seconds, count, _ = cases_mod.run_sweep_to_pipe(args.mechgraph, args.scene, cases_csv)
            if count not in (n, -1):
                raise RuntimeError(f"the sweep ran {count} cases, not {n}")
            best["mechgraph"] = min(best["mechgraph"], wall)
            best["mechgraph log"] = min(best["mechgraph log"], log_seconds)
            best["mechgraph file"] = min(best["mechgraph file"], cases_mod.run_sweep(args.mechgraph, args.scene, cases_csv,
                                                                                     rows_csv)[0])
            for b in batches:
                best[("grid", b)] = min(best[("grid", b)], timed(grid.study, P, b)[0])
            best["closed"] = min(best["closed"], timed(closed_form.study, P, 4096, tables)[0])
    finally:
        shutil.rmtree(work, ignore_errors=True)

    designs = 3 * n
    rate = {k: designs / v for k, v in best.items()}
    grid_batch = max(batches, key=lambda b: rate[("grid", b)])
    print(f"\nstages 1-3, designs per second on one core ({designs} designs, fastest of {args.repeats} rounds):")
    print(f"{'side':58s} {'designs/s':>10s} {'worst rel. diff.':>17s}")
    print(f"{'mechgraph sweep --threads 1 (whole process, rows to a pipe)':58s} {rate['mechgraph']:10.4g} {'reference':>17s}")
    print(f"{'the same with --out FILE (rows and manifest fsync-ed)':58s} {rate['mechgraph file']:10.4g} {'reference':>17s}")
    if math.isfinite(best["mechgraph log"]):
        print(f"{'mechgraph sweep (its log line: evaluation and rows)':58s} {rate['mechgraph log']:10.4g} {'reference':>17s}")
    for b in batches:
        mark = "  <- fastest" if b == grid_batch else ""
        print(f"{f'grid peer 0.045 deg, {b} cases ({3 * b} designs) a batch':58s} {rate[('grid', b)]:10.4g} "
              f"{worst_grid:17.1e}{mark}")
    print(f"{'closed-form peer (all designs at once)':58s} {rate['closed']:10.4g} {worst_closed:17.1e}")
    r_grid = rate["mechgraph"] / rate[("grid", grid_batch)]
    r_closed = rate["mechgraph"] / rate["closed"]
    print()
    print(f"ratio stages 1-3 vs grid peer (mechgraph whole process / numpy, designs/s): {r_grid:.2f}x "
          f"({rate['mechgraph']:.3g} vs {rate[('grid', grid_batch)]:.3g}; goal >= 5x)")
    print(f"ratio stages 1-3 vs closed-form peer (mechgraph whole process / numpy, designs/s): {r_closed:.3g}x, "
          f"the peer {1.0 / r_closed:.3g}x faster ({rate['mechgraph']:.3g} vs {rate['closed']:.3g}; goal: within 3x, "
          f"ratio >= 0.33x)")


if __name__ == "__main__":
    main()
