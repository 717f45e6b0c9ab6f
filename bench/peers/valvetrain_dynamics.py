#!/usr/bin/python3
"""Peer benchmark: mechgraph's `valvetrain.dynamics` (SUNDIALS CVODE, BDF with root finding)
against the same model written the way an engineer would in Python, with scipy's
`solve_ivp(..., events=...)`: the explicit DOP853 and RK45 (the model has two states and is not
stiff, an explicit solver's case), and the implicit Radau for reference.

Requirements: Debian's /usr/bin/python3 with python3-numpy and python3-scipy
(`apt-get install -y python3-numpy python3-scipy`); a built mechgraph CLI.

Usage:
    /usr/bin/python3 bench/peers/valvetrain_dynamics.py [--mechgraph build/bin/mechgraph]
        [--scene bench/peers/valvetrain_dynamics.yaml] [--repeats 5] [--quick] [--all-methods]
        [--max-step]
or simply bench/peers/run.sh (same arguments). MECHGRAPH in the environment names the CLI.

The model (plugins/valvetrain/chain_model.hpp; the node's setup in dynamics_node.cpp /
valve_simulation.cpp), valve side:
    cam angle   phi = -pi + w_k t,  w_k = rpm/2 in rad/s (t = 0 on the base circle, at -pi)
    drive       y = i h(phi) - lash (here lash = 0), y' = w_k i h'(phi)
    force       N = k_d (y - x) + c (y' - x'),  c = 2 zeta sqrt((k_d + c_s) M)  (the first mode at zeta)
    seated      x = x' = 0 until N - P0 crosses 0 upward (lift-off)
    attached    M x'' = N - P0 - c_s x, until x crosses 0 downward (landing: x' = 0 and seated,
                or attached on at once if the drive already pushes harder than P0)
with the cycloidal rise-return law h of plugins/cams/rise_law.cpp (nose at phi = 0, event over
[-action/2, action/2]). P0, c_s and M_red are read from mechgraph's sd.* outputs. Two revolutions
are simulated; the lift of the last one is read at 1441 points over [-pi, pi]. Both sides restart
the integration at the cam's knots (start and end of the event, the nose) and use the same
tolerances: rtol = tol, atol = tol h_max for x and tol h_max w_k for x' (h_max = i H - lash).
mechgraph also caps the step at half a cam degree (period/720); scipy runs without a cap
(solve_ivp's default, the script an engineer would write, and the faster one; --max-step adds
Radau with the same cap).

Sides: mechgraph with each of its integrators (dyn.integrator: cvode, the default, and dopri5);
scipy DOP853, RK45 and Radau (--max-step: Radau with mechgraph's step cap too; --all-methods: BDF
and LSODA).

Timing. mechgraph: the node's own time, `nodes.dyn.seconds` of `mechgraph run --json` (process
start, plugin loading, scene parsing and the other nodes are excluded; the node time does
include filling its seven output curves). scipy: time.perf_counter around the simulation
(the 1441 lift values included). Each point is the fastest of --repeats runs, taken in rounds
over the whole ladder so that a burst of load elsewhere on the machine spoils no single point.

Error. max |x - x_ref| over the 1441 points, x_ref: mechgraph at tolerance 1e-12. Before anything
is timed the peer is checked against it: the drive displacement mechgraph reports must be the
peer's to 1e-12 m, and scipy DOP853 and Radau at rtol 1e-13 must both reproduce x_ref within
AGREEMENT (2e-9 m, 1.7e-7 of the valve lift; otherwise exit status 1). Errors below about twice the
printed difference are limited by the reference. The speed ratio at equal error interpolates log
time over log error on each side's Pareto front.

The scipy side is meant to be the honest, reasonably efficient script: for the implicit methods
the Jacobian of the attached mode is constant and passed to Radau as a matrix (never re-evaluated; scipy refactors
only when the step size changes), the right-hand side works on Python floats with `math` (faster
than numpy on scalars), the outputs come from solve_ivp's t_eval, and the seated phases -- where
x = x' = 0 exactly and the lift-off condition does not depend on the state -- are not
integrated: the lift-off is the first upward sign change of N - P0 on a half-degree grid
(evaluated vectorised once), refined by brentq to machine precision, which is what solve_ivp's
event location would find there, without the stepping. Landings are solve_ivp terminal events
(direction -1); each event restarts solve_ivp. --all-methods adds scipy's BDF and LSODA (same
code, no max_step) for context.
"""

import argparse
import json
import math
import os
import subprocess
import sys
import time

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))

# --- The scene's parameters (bench/peers/valvetrain_dynamics.yaml), SI, converted as mechgraph does.
PI = math.pi
MAX_LIFT = 8.0 * 1e-3                 # H, m
ACTION = 130.0 * (PI / 180.0)         # rad
RPM = 5600.0 * (2.0 * PI / 60.0)      # crank speed, rad/s
W = RPM / 2.0                         # camshaft speed w_k, rad/s
RATIO = 1.5                           # rocker ratio i
LASH = 0.0                            # m
K_D = 4000.0 * 1e3                    # drive stiffness, N/m
ZETA = 0.06                           # damping ratio (default)
REVOLUTIONS = 2
CURVE_POINTS = 1441
PERIOD = 2.0 * PI / W
MAX_STEP = PERIOD / 720.0             # half a cam degree, as dynamics_node.cpp
H_MAX = RATIO * MAX_LIFT - LASH
AGREEMENT = 2e-9                      # m: the scipy model at rtol 1e-13 against mechgraph at 1e-12

HALF = 0.5 * ACTION
KH = 1.0 / HALF
TWO_PI = 2.0 * PI


# --- The cam: cycloidal rise over [-HALF, 0], mirrored return over [0, HALF], zero elsewhere.
def drive_scalar(t):
    """y(t) and y'(t) (m, m/s) of the drive at time t; Python floats, for the right-hand side."""
    phi = -PI + W * t
    phi -= TWO_PI * math.floor((phi + PI) / TWO_PI)          # into [-pi, pi)
    if phi <= -HALF or phi >= HALF:
        return 0.0, 0.0
    if phi <= 0.0:
        x, sign = (phi + HALF) * KH, 1.0
    else:
        x, sign = (HALF - phi) * KH, -1.0
    a = TWO_PI * x
    s = x - math.sin(a) / TWO_PI
    ds = 1.0 - math.cos(a)
    return RATIO * MAX_LIFT * s - LASH, sign * W * RATIO * MAX_LIFT * ds * KH


def drive_array(t):
    """y(t), y'(t) on an array of times (vectorised)."""
    phi = -PI + W * np.asarray(t, dtype=float)
    phi = phi - TWO_PI * np.floor((phi + PI) / TWO_PI)
    inside = (phi > -HALF) & (phi < HALF)
    rising = phi <= 0.0
    x = np.where(rising, (phi + HALF) * KH, (HALF - phi) * KH)
    a = TWO_PI * x
    s = x - np.sin(a) / TWO_PI
    ds = 1.0 - np.cos(a)
    y = np.where(inside, RATIO * MAX_LIFT * s - LASH, 0.0)
    dy = np.where(inside, np.where(rising, 1.0, -1.0) * W * RATIO * MAX_LIFT * ds * KH, 0.0)
    return y, dy


class Model:
    """The single-mass model with the spring design mechgraph computed (P0, c_s, M_red)."""

    def __init__(self, preload, spring_rate, mass):
        self.P0, self.cs, self.M = preload, spring_rate, mass
        self.c = 2.0 * ZETA * math.sqrt((K_D + spring_rate) * mass)
        self.jac = np.array([[0.0, 1.0], [-(K_D + spring_rate) / mass, -self.c / mass]])
        P0, cs, M, c = self.P0, self.cs, self.M, self.c

        def rhs(t, s):
            x, v = s
            y, dy = drive_scalar(t)
            return [v, (K_D * (y - x) + c * (dy - v) - P0 - cs * x) / M]

        def landing(t, s):
            return s[0]
        landing.terminal = True
        landing.direction = -1.0

        self.rhs, self.landing = rhs, landing

        # Knots: where the excitation is not smooth (event start, nose, event end), every revolution.
        knots = []
        for r in range(REVOLUTIONS):
            for k in (-HALF, 0.0, HALF):
                knots.append((r + (k + PI) / TWO_PI) * PERIOD)
        self.knots = np.array(sorted(knots))
        self.t_end = REVOLUTIONS * PERIOD
        last = (REVOLUTIONS - 1) * PERIOD
        phi = -PI + TWO_PI * np.arange(CURVE_POINTS) / (CURVE_POINTS - 1)
        self.phi = phi
        self.t_out = last + (phi + PI) / W
        # Lift-off search grid: one point per max_step (half a cam degree) over the whole run.
        self.grid = np.linspace(0.0, self.t_end, 720 * REVOLUTIONS + 1)
        y, dy = drive_array(self.grid)
        self.g_grid = K_D * y + self.c * dy - P0       # N - P0 with the valve seated

    def lift_off_g(self, t):
        y, dy = drive_scalar(t)
        return K_D * y + self.c * dy - self.P0

    def next_lift_off(self, t0):
        """First upward crossing of N - P0 (seated: x = x' = 0) after t0, or None."""
        grid, g = self.grid, self.g_grid
        j = int(np.searchsorted(grid, t0, side="right"))
        if j >= len(grid):
            return None
        ts = np.concatenate(([t0], grid[j:]))
        gs = np.concatenate(([self.lift_off_g(t0)], g[j:]))
        up = np.nonzero((gs[:-1] <= 0.0) & (gs[1:] > 0.0))[0]
        if len(up) == 0:
            return None
        a, b = ts[up[0]], ts[up[0] + 1]
        t = brentq(self.lift_off_g, a, b, xtol=1e-15 * b, rtol=4.0 * np.finfo(float).eps)
        while self.lift_off_g(t) <= 0.0 and t < b:  # just past the crossing, as CVODE's root finder returns
            t = np.nextafter(t, math.inf)
        return float(t)

    def simulate(self, tol, method="Radau", max_step=None):
        """Lift x at the output times; (x, work) with work = rhs evaluations, LU decompositions, events.
        max_step None: none (solve_ivp's default); the events of the last revolution go to last_events."""
        atol = np.array([tol * H_MAX, tol * H_MAX * W])
        t_out, knots, t_end = self.t_out, self.knots, self.t_end
        x_out = np.zeros(len(t_out))
        nfev = nlu = events = 0
        t, state, seated = 0.0, (0.0, 0.0), True
        stops = [k for k in knots if 0.0 < k < t_end] + [t_end]
        kw = {"max_step": max_step} if max_step else {}
        log = []
        # A constant Jacobian: Radau and BDF take the matrix (and never re-evaluate it); LSODA wants a
        # function; the explicit methods take none.
        if method in ("RK45", "RK23", "DOP853"):
            kw_jac = {}
        else:
            kw_jac = {"jac": self.jac if method != "LSODA" else (lambda t, s, J=self.jac: J)}
        while t < t_end:
            if seated:
                # x = x' = 0 until the drive pushes harder than the preload; outputs stay 0.
                t_lift = self.next_lift_off(t)
                if t_lift is None:
                    break
                t, state, seated = t_lift, (0.0, 0.0), False
                events += 1
                log.append((t, "lift-off", 0.0))
                continue
            # Attached: integrate up to the next knot, stopping at a landing.
            t_stop = next(k for k in stops if k > t)
            i0 = int(np.searchsorted(t_out, t, side="right"))
            i1 = int(np.searchsorted(t_out, t_stop, side="right"))
            t_eval = np.clip(t_out[i0:i1], t, t_stop)
            n_out = len(t_eval)
            if n_out == 0 or t_eval[-1] != t_stop:
                t_eval = np.append(t_eval, t_stop)  # the state at the knot, to restart from
            sol = solve_ivp(self.rhs, (t, t_stop), state, method=method, t_eval=t_eval, events=self.landing,
                            rtol=tol, atol=atol, **kw_jac, **kw)
            if sol.status < 0:
                raise RuntimeError(f"solve_ivp failed at t = {t}: {sol.message}")
            nfev += sol.nfev
            nlu += sol.nlu or 0
            n = min(len(sol.t), n_out)
            if n:
                x_out[i0:i0 + n] = sol.y[0][:n]
            if sol.status == 1:  # landing: seated, unless the drive already pushes harder than P0
                events += 1
                t = float(sol.t_events[0][0])
                log.append((t, "landing", abs(float(sol.y_events[0][0][1]))))
                state = (0.0, 0.0)
                seated = not (self.lift_off_g(t) > 0.0)
            else:
                t = t_stop
                state = (float(sol.y[0][-1]), float(sol.y[1][-1]))
        last = (REVOLUTIONS - 1) * PERIOD
        self.last_events = [f"{kind} at {math.degrees(W * (te - last) - PI):.4f} deg" + (f" ({v:.4f} m/s)" if v else "")
                            for te, kind, v in log if te >= last]
        return x_out, {"rhs": nfev, "lu": nlu, "events": events}


# --- mechgraph side -------------------------------------------------------------------------------
def run_mechgraph(exe, scene, tol, repeats, integrator="cvode"):
    best, data = math.inf, None
    for _ in range(repeats):
        proc = subprocess.run([exe, "-q", "run", scene, "--json", "--set", f"dyn.tolerance={tol!r}",
                               "--set", f"dyn.integrator={integrator}"],
                              capture_output=True, text=True)
        if proc.returncode != 0:
            raise RuntimeError(f"mechgraph exited with {proc.returncode} at tolerance {tol:g}: {proc.stderr.strip()}")
        d = json.loads(proc.stdout)
        secs = d["nodes"]["dyn"]["seconds"]
        if data is None:
            data = d
        best = min(best, secs)
    cols = data["outputs"]["dyn.curves"]["value"]["columns"]
    return {
        "seconds": best,
        "lift": np.array(cols["lift"]["values"], dtype=float),
        "phi": np.array(cols["cam_angle"]["values"], dtype=float),
        "drive": np.array(cols["drive_displacement"]["values"], dtype=float),
        "work": data["nodes"]["dyn"]["work"],
        "outputs": data["outputs"],
    }


def time_scipy(model, tol, repeats, method, max_step):
    best, result = math.inf, None
    for _ in range(repeats):
        t0 = time.perf_counter()
        result = model.simulate(tol, method, max_step)
        best = min(best, time.perf_counter() - t0)
    return best, result[0], result[1]


def pareto(points):
    """(error, time) points no other point beats in both, sorted by error."""
    front, best_t = [], math.inf
    for e, t in sorted(points):
        if t < best_t and e > 0.0:
            front.append((e, t))
            best_t = t
    return front


def time_at_error(front, err):
    """Time to reach error `err` on a Pareto front, log-log interpolated; ('<=', t) when every run was
    more accurate than err (t: the cheapest run, an upper bound), None when no run reached err."""
    es = [math.log(e) for e, _ in front]
    ts = [math.log(t) for _, t in front]
    le = math.log(err)
    if not es or le < es[0]:
        return None
    if le > es[-1]:
        return ("<=", front[-1][1])
    return ("=", float(np.exp(np.interp(le, es, ts))))


def fmt_ratio(num, den):
    """num / den for time_at_error results, with the bound it is."""
    if num is None or den is None:
        return "-"
    r = num[1] / den[1]
    if num[0] == "=" and den[0] == "=":
        return f"{r:.2g}x"
    if num[0] == "<=" and den[0] == "=":
        return f"<={r:.2g}x"
    if num[0] == "=" and den[0] == "<=":
        return f">={r:.2g}x"
    return "n/a"


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--mechgraph", default=os.environ.get("MECHGRAPH", os.path.join(ROOT, "build", "bin", "mechgraph")))
    ap.add_argument("--scene", default=os.path.join(HERE, "valvetrain_dynamics.yaml"))
    ap.add_argument("--repeats", type=int, default=5, help="runs per point; the fastest counts (default 5)")
    ap.add_argument("--all-methods", action="store_true", help="also scipy's BDF and LSODA (no max_step)")
    ap.add_argument("--max-step", action="store_true", help="also scipy Radau with mechgraph's max_step (1/2 cam deg)")
    ap.add_argument("--quick", action="store_true", help="every other tolerance, 2 repetitions")
    args = ap.parse_args()
    if args.quick:
        args.repeats = min(args.repeats, 2)
    tols = [1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11]
    if args.quick:
        tols = tols[::2]
    ref_tol, scipy_tight = 1e-12, 1e-13

    print(f"mechgraph: {args.mechgraph}\nscene:     {args.scene}")
    ref = run_mechgraph(args.mechgraph, args.scene, ref_tol, 1)
    o = ref["outputs"]
    model = Model(o["sd.preload"]["value"], o["sd.stiffness"]["value"], o["sd.reduced_mass"]["value"])
    print(f"design:    P0 = {model.P0:.6g} N, c_s = {model.cs / 1e3:.6g} N/mm, M_red = {model.M * 1e3:.6g} g, "
          f"c = {model.c:.6g} N*s/m; w_k = {W:.6g} rad/s, h_max = {H_MAX * 1e3:g} mm")

    # Same cam, same output grid: the drive displacement mechgraph reports against ours.
    print(f"check:     output angles, max |numpy - mechgraph| = {np.max(np.abs(ref['phi'] - model.phi)):.3g} rad; "
          f"drive displacement y, max |numpy - mechgraph| = "
          f"{np.max(np.abs(drive_array((model.phi + PI) / W)[0] - ref['drive'])):.3g} m")
    x_ref = ref["lift"]
    print(f"reference: mechgraph at tolerance {ref_tol:g} ({ref['work'].get('steps')} steps, "
          f"{ref['work'].get('events')} events; max lift {x_ref.max() * 1e3:.6f} mm)")
    drive_diff = float(np.max(np.abs(drive_array((model.phi + PI) / W)[0] - ref["drive"])))
    agree = drive_diff <= 1e-12 and float(np.max(np.abs(ref["phi"] - model.phi))) <= 1e-12
    for method in ("DOP853", "Radau"):
        x_tight, w_tight = model.simulate(scipy_tight, method)
        d = np.abs(x_tight - x_ref)
        j = int(np.argmax(d))
        agree = agree and d[j] <= AGREEMENT
        print(f"verify:    scipy {method} at rtol {scipy_tight:g} against it: max |dx| = {d[j]:.3g} m "
              f"({d[j] / H_MAX:.2g} h_max) at cam angle {math.degrees(model.phi[j]):.2f} deg, "
              f"{w_tight['events']} events (bound {AGREEMENT:g} m)")
    print(f"events:    {', '.join(model.last_events)}")
    if not agree:
        print("valvetrain_dynamics: the scipy model disagrees with mechgraph; nothing timed", file=sys.stderr)
        sys.exit(1)

    sides = [("mechgraph CVODE BDF", None, "cvode"), ("mechgraph dopri5", None, "dopri5"),
             ("scipy DOP853", "DOP853", None), ("scipy RK45", "RK45", None), ("scipy Radau", "Radau", None)]
    if args.max_step:
        sides += [("scipy Radau, max_step 1/2 deg", "Radau", MAX_STEP)]
    if args.all_methods:
        sides += [("scipy BDF", "BDF", None), ("scipy LSODA", "LSODA", None)]
    # The repetitions are rounds over the whole ladder, so a burst of load on the machine spreads
    # over all points instead of spoiling one; each point keeps its fastest time.
    best = {}  # (name, tol) -> [error, seconds, work]
    failed = set()
    for _ in range(args.repeats):
        for tol in tols:
            for name, method, max_step in sides:
                if (name, tol) in failed:
                    continue
                try:
                    if method is None:
                        m = run_mechgraph(args.mechgraph, args.scene, tol, 1, max_step)
                        secs, x = m["seconds"], m["lift"]
                        work = f"{m['work'].get('steps')} steps, {m['work'].get('rhs_evaluations')} rhs"
                    else:
                        secs, x, w = time_scipy(model, tol, 1, method, max_step)
                        work = f"{w['rhs']} rhs, {w['lu']} LU"
                except RuntimeError as e:
                    print(f"  {name} at tol {tol:g} failed: {e}")
                    failed.add((name, tol))
                    continue
                err = float(np.max(np.abs(x - x_ref)))
                if (name, tol) not in best:
                    best[(name, tol)] = [err, secs, work]
                else:
                    if err != best[(name, tol)][0]:
                        print(f"  {name} at tol {tol:g}: not deterministic ({err:.3g} m vs {best[(name, tol)][0]:.3g} m)")
                    best[(name, tol)][1] = min(best[(name, tol)][1], secs)
    rows = {name: [(tol, *best[(name, tol)]) for tol in tols if (name, tol) in best] for name, _, _ in sides}

    print()
    print(f"work-precision: error = max |x - x_ref| over {CURVE_POINTS} points of the last revolution; "
          f"time = fastest of {args.repeats}")
    print(f"{'integrator':30s} {'tol':>7s} {'error [m]':>10s} {'err/(tol h_max)':>15s} {'time [ms]':>10s}  work")
    for name, rs in rows.items():
        for tol, err, secs, work in rs:
            print(f"{name:30s} {tol:7.0e} {err:10.3e} {err / (tol * H_MAX):15.3g} {secs * 1e3:10.3f}  {work}")
        print()
    fronts = {name: pareto([(r[1], r[2]) for r in rs]) for name, rs in rows.items()}
    mechs = [name for name, method, _ in sides if method is None]
    others = [name for name, method, _ in sides if method is not None]
    f = lambda v: "-" if v is None else ("<=" if v[0] == "<=" else "") + f"{v[1] * 1e3:.3f} ms"
    for mname in mechs:
        mech = fronts[mname]
        print(f"time at equal error, {mname} (log-log interpolation on each side's Pareto front; <=: every run of "
              "that side was more accurate, its cheapest run counts) and ratio scipy / mechgraph:")
        print(f"{'error [m]':>10s} {'mechgraph':>12s}" + "".join(f" {n[6:]:>14s} {'ratio':>7s}" for n in others))
        for err in (1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11):
            tm = time_at_error(mech, err)
            line = f"{err:10.0e} {f(tm):>12s}"
            for n in others:
                t = time_at_error(fronts[n], err)
                line += f" {f(t):>14s} {fmt_ratio(t, tm):>7s}"
            print(line)
        print()
    for mname in mechs:
        tm = time_at_error(fronts[mname], 1e-7)
        parts = [f"{fmt_ratio(time_at_error(fronts[n], 1e-7), tm)} vs {n[6:]} ({f(time_at_error(fronts[n], 1e-7))})"
                 for n in others]
        print(f"ratio dynamics at equal error 1e-7 m, {mname} ({f(tm)}): " + ", ".join(parts) + "; goal >= 10x DOP853")


if __name__ == "__main__":
    main()
