"""Threads that cannot start: a Python sweep and run under an address-space limit (each thread must
map its stack) do their work on the threads they get, with the rows of an unlimited run; the
interpreter never dies of std::terminate. The limit is set by prlimit on a child interpreter."""
import os
import shutil
import subprocess
import sys

import pytest

from conftest import SOURCE

SCRIPT = r"""
import json, sys
import mechgraph
scene = mechgraph.Scene.load(sys.argv[1])
frame = scene.sweep({"rpm [rpm]": [3000, 4000, 5000, 6000, 7000, 7500]}, outputs=["ta_kurz.time_area"], threads=8)
result = scene.run(outputs=["ta_kurz.time_area"], threads=8)
print(json.dumps({"rows": [str(v) for v in frame.iloc[:, -1].tolist()], "run": str(result["ta_kurz.time_area"])}))
"""


@pytest.mark.skipif(shutil.which("prlimit") is None, reason="prlimit (util-linux) is not installed")
def test_sweep_and_run_under_an_address_space_limit_give_the_same_rows():
    scene = str(SOURCE / "scenes" / "valvetrain_cams.yaml")
    env = dict(os.environ)
    free = subprocess.run([sys.executable, "-c", SCRIPT, scene], capture_output=True, text=True, env=env, timeout=300)
    assert free.returncode == 0, free.stderr
    # A 1 GiB stack for every thread in 3 GiB of address space: a thread or two start, the rest cannot.
    limited = subprocess.run(["prlimit", "--stack=1073741824", "--as=3221225472", "--", sys.executable, "-c", SCRIPT,
                              scene], capture_output=True, text=True, env=env, timeout=300)
    assert limited.returncode >= 0, f"killed by signal {-limited.returncode}: {limited.stderr[-2000:]}"
    assert limited.returncode == 0, limited.stderr[-2000:]
    assert limited.stdout == free.stdout
