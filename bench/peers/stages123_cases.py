"""The three-cam study's cases and mechgraph's side of it, shared by the stage 1-3 peers
(stages123_grid.py, stages123_closed_form.py) and their driver (valvetrain_stages123.py).

The study is bench/peers/stages123_study.yaml: three cams (cam.three_arc, cam.kurz, cam.polydyne
with exponents [2, 14, 26, 38, 50]) of one lift, action angle, base radius and (three-arc, Kurz)
positive-acceleration angle, each through valvetrain.valve_motion (rocker 1.5, the case's rpm and
lash) and valvetrain.time_area (conical seat, d0 = 34 mm, 45 deg), eight outputs (OUTPUTS).

A case varies six of the scene's parameters at once (RANGES), so that every law changes shape from
case to case: lift, action angle, positive-acceleration angle, base radius, rpm and lash. The cases
are a Latin hypercube drawn here (numpy's PCG64, a seed), written to a CSV that `mechgraph sweep
--cases` reads: both sides compute the same designs from the same text, read the same way (the
number times its unit's SI scale, as mechgraph's unit table has it). The base radius keeps every
contour clear of undercut (from 24 mm; the Kurz contour undercuts below about 23.8 mm at lift
9 mm, action 120 deg, accel 21 deg): a case mechgraph refuses would be a design the peers did not
have to do, and the driver fails if there is one.
"""

import csv
import math
import os
import re
import subprocess
import time

import numpy as np

DEG = math.pi / 180.0
# SI scale of every unit written or read here: the products mechgraph's unit table gives.
UNIT_SCALE = {"1": 1.0, "mm": 1e-3, "m": 1.0, "deg": math.pi / 180.0, "rad": 1.0, "rpm": 2.0 * math.pi / 60.0,
              "s": 1.0, "mm^2*s": 1e-6, "m^2*s": 1.0, "m/s^2": 1.0}

# The swept parameters: (name, low, high, unit), low and high in that unit.
RANGES = (("lift", 7.0, 9.0, "mm"), ("action", 120.0, 140.0, "deg"), ("accel", 15.0, 21.0, "deg"),
          ("r0", 24.0, 28.0, "mm"), ("rpm", 4000.0, 7000.0, "rpm"), ("lash", 0.1, 0.4, "mm"))
# The scene's parameters that stay fixed (SI), and what the scene fixes in its nodes.
FIXED = {"rocker": 1.5, "seat": 34e-3}
SEAT_ANGLE = 45.0 * DEG
POLYDYNE_EXPONENTS = (2, 14, 26, 38, 50)

OUTPUTS = ("ta_arc.time_area", "ta_kurz.time_area", "ta_poly.time_area",
           "v_arc.max_acceleration", "v_kurz.max_acceleration", "v_poly.max_acceleration",
           "v_arc.min_acceleration", "v_poly.min_acceleration")


def latin_hypercube(n, seed):
    """n cases: {name: values in the RANGES unit}. Each variable's range is cut into n equal strata,
    one case per stratum at a uniform point inside it, the strata of the variables paired by
    independent random permutations."""
    rng = np.random.Generator(np.random.PCG64(seed))
    cases = {}
    for name, lo, hi, _ in RANGES:
        u = (rng.permutation(n) + rng.random(n)) / n
        cases[name] = lo + (hi - lo) * u
    return cases


def write_cases_csv(path, cases):
    """The cases as `mechgraph sweep --cases` reads them: a header `name [unit]`, the numbers as the
    shortest text that reads back to the same double. Returns the cases as read back from that text
    (what both sides compute)."""
    names = [name for name, _, _, _ in RANGES]
    units = {name: unit for name, _, _, unit in RANGES}
    n = len(cases[names[0]])
    with open(path, "w", newline="") as fh:
        fh.write(",".join(f"{name} [{units[name]}]" for name in names) + "\n")
        for k in range(n):
            fh.write(",".join(repr(float(cases[name][k])) for name in names) + "\n")
    return read_cases_csv(path)


def read_cases_csv(path):
    """{name: values in the column's unit} of a cases CSV written by write_cases_csv."""
    with open(path, newline="") as fh:
        rows = list(csv.reader(fh))
    header = [re.match(r"(\S+) \[(.+)\]$", h).groups() for h in rows[0]]
    cases = {name: np.array([float(r[j]) for r in rows[1:]]) for j, (name, _) in enumerate(header)}
    for name, unit in header:
        if unit != dict((r[0], r[3]) for r in RANGES)[name]:
            raise ValueError(f"{path}: column {name} in {unit}, expected its RANGES unit")
    return cases


def design_table(cases):
    """Every parameter of the scene the peers use as an SI array over the cases: the swept ones
    (value times the unit's scale, as mechgraph converts them) and the fixed ones."""
    units = {name: unit for name, _, _, unit in RANGES}
    n = len(next(iter(cases.values())))
    P = {name: np.asarray(values, dtype=float) * UNIT_SCALE[units[name]] for name, values in cases.items()}
    for name, value in FIXED.items():
        P[name] = np.full(n, value)
    return P


def slice_table(P, start, stop):
    return {k: v[start:stop] for k, v in P.items()}


# --- mechgraph's side -----------------------------------------------------------------------------

def run_sweep(exe, scene, cases_csv, rows_csv):
    """One `mechgraph sweep SCENE --cases CASES --threads 1 --out ROWS`: (whole process wall-clock
    seconds, the seconds of its own log line 'sweep: N cases in S s', N). --out writes the rows and
    the manifest beside them each through a temporary, fsync'd and renamed. Any exit but 0 is an error."""
    wall, seconds, count, _ = _sweep([exe, "sweep", scene, "--cases", cases_csv, "--threads", "1", "--out", rows_csv,
                                      "--force"])
    return wall, seconds, count


def run_sweep_to_pipe(exe, scene, cases_csv):
    """The same sweep with its rows on standard output, read through a pipe (no file, no fsync):
    (whole process wall-clock seconds, the log line's seconds, N, the rows' bytes)."""
    return _sweep([exe, "sweep", scene, "--cases", cases_csv, "--threads", "1"])


def _sweep(cmd):
    t0 = time.perf_counter()
    proc = subprocess.run(cmd, capture_output=True)
    wall = time.perf_counter() - t0
    stderr = proc.stderr.decode(errors="replace")
    if proc.returncode != 0:
        raise RuntimeError(f"mechgraph sweep exited with {proc.returncode}: {stderr.strip()}")
    m = re.search(r"sweep: (\d+) cases in ([0-9.eE+-]+) s", stderr)
    return wall, (float(m.group(2)) if m else math.nan), (int(m.group(1)) if m else -1), proc.stdout


def read_rows(path):
    """A sweep's CSV: ({input name: cell texts}, {output: SI array, NaN where the case failed},
    exit codes, error texts)."""
    with open(path, newline="") as fh:
        rows = list(csv.reader(fh))
    header, body = rows[0], rows[1:]
    inputs, outputs = {}, {}
    for j, h in enumerate(header):
        m = re.match(r"(\S+) \[(.+)\]$", h)
        if not m:
            continue
        name, unit = m.groups()
        unit = re.sub(r" \(.*\)$", "", unit)  # "deg (crank)": the angle the column counts, not its scale
        if "." in name:
            scale = UNIT_SCALE[unit]
            outputs[name] = np.array([float(r[j]) * scale if r[j] else math.nan for r in body])
        else:
            inputs[name] = [r[j] for r in body]
    exits = np.array([int(r[header.index("exit")]) for r in body])
    errors = [r[header.index("error")] for r in body]
    return inputs, outputs, exits, errors


def verify(label, got, cases, rows_csv, bound):
    """Every output of `got` ({output: SI array over the cases}) against mechgraph's rows of the
    same cases, relative difference; prints the worst per output. True when mechgraph's inputs are
    the cases (its input cells are written to 15 digits, so equal to 1e-14), every case succeeded on both sides and the worst difference is within bound."""
    inputs, want, exits, errors = read_rows(rows_csv)
    n = len(exits)
    problems = []
    for name, values in cases.items():
        if inputs.get(name) is None or len(inputs[name]) != len(values) or \
                any(abs(float(text) - v) > 1e-14 * abs(v) for text, v in zip(inputs[name], values)):
            problems.append(f"mechgraph's column {name} is not the cases' values")
    if np.any(exits != 0):
        k = int(np.argmax(exits != 0))
        problems.append(f"{int(np.sum(exits != 0))} cases failed in mechgraph (case {k}: {errors[k]})")
    worst = 0.0
    print(f"{label}: relative difference against mechgraph's rows ({n} cases, {3 * n} designs):")
    for name in OUTPUTS:
        if name not in want:
            problems.append(f"no column {name} in {rows_csv}")
            continue
        a, b = np.asarray(got[name]), want[name]
        if len(a) != n or not np.all(np.isfinite(a)):
            problems.append(f"{name}: the peer has {len(a)} values, not all finite")
            continue
        rel = np.abs(a - b) / np.abs(b)
        k = int(np.argmax(rel))
        worst = max(worst, float(rel[k]))
        print(f"  {name:26s} worst {rel[k]:9.2e} (case {k})")
    ok = not problems and worst <= bound
    for p in problems:
        print(f"  problem: {p}")
    print(f"  verify {label}: {'ok' if ok else 'FAILED'} (worst {worst:.2e}, bound {bound:g})")
    return ok, worst


def default_exe(root):
    return os.environ.get("MECHGRAPH", os.path.join(root, "build", "bin", "mechgraph"))
