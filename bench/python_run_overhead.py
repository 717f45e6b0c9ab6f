#!/usr/bin/env python3
"""What a run from Python costs beyond its evaluation, against one `mechgraph run --json --set` process.

    PYTHONPATH=build/lib/python3.11/dist-packages /usr/bin/python3 bench/python_run_overhead.py

A second run that changes one parameter writes it into the built graph and evaluates only the nodes
downstream of it (the memo cache holds the rest); the overhead is the whole call's wall time minus
the evaluation's (Result.seconds, timed inside the C++ run), medians over many calls. Not a test:
it prints numbers for the README and docs/python.md.
"""
import pathlib
import statistics
import subprocess
import sys
import time

import mechgraph

ROOT = pathlib.Path(__file__).resolve().parents[1]
SCENE = ROOT / "scenes" / "valvetrain_cams.yaml"
CLI = ROOT / "build" / "bin" / "mechgraph"


def python_runs(n, outputs):
    scene = mechgraph.Scene.load(SCENE)
    scene.run(set={"rpm": "5000 rpm"}, outputs=outputs)
    totals, overheads = [], []
    for i in range(n):
        rpm = f"{5000 + i} rpm"  # a new speed each time: nothing downstream of rpm is in the cache
        start = time.perf_counter()
        r = scene.run(set={"rpm": rpm}, outputs=outputs)
        value = r[outputs[0]]
        total = time.perf_counter() - start
        totals.append(total)
        overheads.append(total - r.seconds)
    return statistics.median(totals), statistics.median(overheads), value


def cli_runs(n):
    times = []
    for i in range(n):
        start = time.perf_counter()
        subprocess.run([str(CLI), "-q", "run", str(SCENE), "--json", "--set", f"rpm={5000 + i}rpm"], check=True,
                       capture_output=True)
        times.append(time.perf_counter() - start)
    return statistics.median(times)


def main():
    n = int(sys.argv[1]) if len(sys.argv) > 1 else 2000
    for outputs in (["v_kurz.max_acceleration"], ["ta_kurz.time_area", "v_kurz.max_acceleration", "v_arc.max_acceleration"]):
        total, overhead, _ = python_runs(n, outputs)
        print(f"python run, outputs {outputs}: {total * 1e6:.1f} us a call, of which {overhead * 1e6:.1f} us "
              f"beyond the evaluation (median of {n})")
    whole = mechgraph.Scene.load(SCENE)
    whole.run()
    start = time.perf_counter()
    for i in range(50):
        whole.run(set={"rpm": f"{6000 + i} rpm"})
    print(f"python run, the whole scene (report included): {(time.perf_counter() - start) / 50 * 1e3:.2f} ms a call")
    if CLI.exists():
        print(f"command line, mechgraph run --json --set: {cli_runs(30) * 1e3:.1f} ms a call (median of 30)")


if __name__ == "__main__":
    main()
