#!/usr/bin/python3
"""Two builds of mechgraph side by side on the stage 1-3 sweep of bench/peers (the same scene and
cases as valvetrain_stages123.py): is the newer one as fast?

    /usr/bin/python3 bench/peers/side_by_side.py --before OLD/bin/mechgraph --after build/bin/mechgraph
        [--cases 1000] [--rounds 30] [--instructions]

Wall clock and CPU time: `rounds` rounds, each running both builds once, in alternating order, the
whole process of `mechgraph sweep SCENE --cases CASES --threads 1` (start, plugins, scene, cases,
evaluation, rows). Printed per build: the fastest and the median run, and designs/s from the fastest
(a case is three designs). A shared machine spoils single runs; alternation spreads the spoiling
over both builds, and the fastest run of each is the one least spoiled.

Instructions (--instructions, needs valgrind): each build once under callgrind with 1 case and with
101 cases; the difference over 100 is the instructions per case, the 1-case run less one case the
start (dynamic loading, plugins, scene). Exact and independent of the machine's load: what to
decide by, with the wall clock for the claim.

Both builds run with their own probe cache (XDG_CACHE_HOME in a temporary folder, filled by a first
run of each), so the machine's shared cache (one line per plugin file any build tree loaded) weighs
on neither. Both must give the same rows: the script stops (exit status 1) when they differ.
"""

import argparse
import os
import re
import statistics
import subprocess
import sys
import tempfile
import time

sys.dont_write_bytecode = True
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import stages123_cases as cases_mod  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))


def sweep_command(exe, scene, cases_csv, rows_csv):
    return [exe, "sweep", scene, "--cases", cases_csv, "--threads", "1", "--out", rows_csv, "--force"]


def run_once(command, env):
    """One run; any exit but 0 is an error."""
    proc = subprocess.run(command, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, env=env)
    if proc.returncode != 0:
        raise RuntimeError(f"{command[0]} exited with {proc.returncode}: {proc.stderr.decode(errors='replace').strip()}")


def instructions(exe, scene, cases_csv, rows_csv, env, folder):
    """Instructions of one run under callgrind (its 'Collected' total)."""
    out = os.path.join(folder, "callgrind.out")
    proc = subprocess.run(["valgrind", "--tool=callgrind", f"--callgrind-out-file={out}"] +
                          sweep_command(exe, scene, cases_csv, rows_csv), capture_output=True, text=True, env=env)
    if proc.returncode != 0:
        raise RuntimeError(f"callgrind on {exe} exited with {proc.returncode}: {proc.stderr.strip()[-400:]}")
    os.remove(out)
    totals = re.findall(r"Collected : (\d+)", proc.stderr)
    if not totals:
        raise RuntimeError(f"callgrind on {exe}: no total in its output")
    return int(totals[-1])


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--before", required=True, help="the mechgraph command of the older build")
    ap.add_argument("--after", required=True, help="the mechgraph command of the newer build")
    ap.add_argument("--scene", default=os.path.join(HERE, "stages123_study.yaml"))
    ap.add_argument("--cases", type=int, default=1000)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--rounds", type=int, default=30)
    ap.add_argument("--instructions", action="store_true", help="also count instructions under callgrind")
    args = ap.parse_args()
    builds = [("before", os.path.abspath(args.before)), ("after", os.path.abspath(args.after))]

    with tempfile.TemporaryDirectory(prefix="mechgraph_side_by_side.") as folder:
        env = dict(os.environ, XDG_CACHE_HOME=os.path.join(folder, "cache"))
        cases_csv = os.path.join(folder, "cases.csv")
        cases_mod.write_cases_csv(cases_csv, cases_mod.latin_hypercube(args.cases, args.seed))
        rows = {}
        for name, exe in builds:  # fills each build's probe cache; the rows must agree
            rows[name] = os.path.join(folder, f"rows_{name}.csv")
            run_once(sweep_command(exe, args.scene, cases_csv, rows[name]), env)
        with open(rows["before"], "rb") as a, open(rows["after"], "rb") as b:
            if a.read() != b.read():
                print("side_by_side: the two builds give different rows; nothing timed", file=sys.stderr)
                return 1
        print(f"scene {os.path.relpath(os.path.abspath(args.scene), ROOT)}, {args.cases} cases ({3 * args.cases} designs), "
              f"{args.rounds} alternating rounds, one thread")

        wall = {name: [] for name, _ in builds}
        cpu = {name: [] for name, _ in builds}
        for r in range(args.rounds):
            for name, exe in (builds if r % 2 == 0 else builds[::-1]):
                t0 = time.perf_counter()
                child = subprocess.Popen(sweep_command(exe, args.scene, cases_csv, rows[name]),
                                         stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, env=env)
                _, status, usage = os.wait4(child.pid, 0)
                wall[name].append(time.perf_counter() - t0)
                cpu[name].append(usage.ru_utime + usage.ru_stime)
                if status != 0:
                    raise RuntimeError(f"{exe} failed (wait status {status})")
        designs = 3 * args.cases
        best = {}
        for name, exe in builds:
            w, c = wall[name], cpu[name]
            best[name] = designs / min(w)
            print(f"{name:7s} wall fastest {min(w) * 1e3:8.2f} ms, median {statistics.median(w) * 1e3:8.2f} ms; "
                  f"CPU fastest {min(c) * 1e3:8.2f} ms, median {statistics.median(c) * 1e3:8.2f} ms; "
                  f"{best[name]:8.0f} designs/s  ({exe})")
        print(f"after / before, designs/s (fastest runs): {best['after'] / best['before']:.3f}")

        if args.instructions:
            one = os.path.join(folder, "one.csv")
            many = os.path.join(folder, "many.csv")
            cases_mod.write_cases_csv(one, cases_mod.latin_hypercube(1, args.seed))
            cases_mod.write_cases_csv(many, cases_mod.latin_hypercube(101, args.seed))
            counts = {}
            for name, exe in builds:
                n1 = instructions(exe, args.scene, one, rows[name], env, folder)
                n101 = instructions(exe, args.scene, many, rows[name], env, folder)
                per_case = (n101 - n1) / 100.0
                counts[name] = (n1 - per_case, per_case, n1 - per_case + args.cases * per_case)
                print(f"{name:7s} instructions: start {counts[name][0] / 1e6:8.2f} M, per case {per_case / 1e3:8.1f} k, "
                      f"{args.cases} cases {counts[name][2] / 1e6:8.1f} M")
            for i, what in enumerate(("start", "per case", f"{args.cases} cases")):
                print(f"after / before, instructions, {what}: {counts['after'][i] / counts['before'][i]:.3f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
