#!/usr/bin/python3
"""Peer benchmark: stages 1-3 of mechgraph's three-cam study (scenes/valvetrain_cams.yaml) against
the same calculation written in numpy the way an engineer would: one design at a time, each cam
law sampled on a fine grid and everything taken from the samples.

Requirements: Debian's /usr/bin/python3 with python3-numpy; a built mechgraph CLI.

Usage:
    /usr/bin/python3 bench/peers/valvetrain_stages123.py [--mechgraph build/bin/mechgraph]
        [--scene scenes/valvetrain_cams.yaml] [--cases 1000] [--repeats 5] [--quick]
or bench/peers/run.sh, which runs every peer. MECHGRAPH in the environment names the CLI.

One design = one cam through stages 1-3 (docs/methods/valvetrain.md), on both sides:
  stage 1  the law h(phi) and h', h'', h''' (exact formulas of the three-arc, Kurz and polydyne
           laws, as plugins/cams/three_arc.cpp, kurz.cpp + shockless.cpp, polydyne.cpp define
           them), peak |h'|, max and min h'', the positive-acceleration phase (first + to - change
           of h'') and the least radius of curvature of the contour, rho = r0 + h + h'' (flat
           tappet);
  stage 2  valve lift i h - lash (clipped at 0), opening and closing angles, open angle, peak
           valve velocity w_k max|i h'| and accelerations w_k^2 i h'' over the open period
           (w_k = rpm/2 in rad/s);
  stage 3  time-area: the conical seat's flow area f_v = pi x cos a (d0 + x sin a cos a)
           integrated over cam angle across the open period, divided by w_k; angle-area and mean
           flow area.
The study: a Latin hypercube of lift in [7, 9] mm and base radius in [15, 19] mm, three cams per
case (mechgraph's benchmark BM_SweepStages123), designs/s = 3 x cases/s.

How the numpy side computes (the obvious engineer's way, vectorised over angle; `design`):
  * the law is sampled every 0.1 cam degree over the whole event, plus the law's own knots (where
    the formula changes: the three-arc flank/nose switch, the Kurz shape junctions) taken from
    both sides, so that a jump of h'' (three-arc) is seen with both its one-sided values; each
    smooth piece is evaluated with its own formula on its own samples;
  * peaks are the largest/smallest samples (exact where the peak sits on a knot or the nose, else
    off by the grid: ~1e-6 relative, up to ~1e-5 for the polydyne's least curvature radius);
  * the end of the acceleration phase and the opening and closing angles: linear interpolation
    between the two samples around the sign change, then one Newton step on the law's exact
    derivatives (a sign change across a knot's two one-sided samples is exact as it is);
  * the valve arrays run from the opening angle to the closing angle (the law evaluated there
    too), the time-area is np.trapz over them: the trapezoid rule, 0.1 deg, ~2e-7 relative.
mechgraph finds peaks and roots by sampling and refining (Brent, TOMS 748) to full precision and
integrates by adaptive Gauss-Kronrod (tolerance 1e-10): it is the reference.
Design cases where a law cannot be built (three-arc radius r2 <= 0) or the contour is undercut
(rho < 0: mechgraph stops the case with an error; Kurz at high lift on a small base circle) are
counted; numpy still computes them.

A second numpy variant, for context (`study_batched`): the same samples, formulas and refinements
with the designs of one cam batched into 2-D arrays (row = design, --batch rows at a time, 50 by
default: larger batches fall out of the cache and are slower). It gives the same figures to
rounding (checked) and shows how much of the gap is Python's per-design overhead. For it the
script raises glibc's malloc thresholds (keep_freed_memory; --default-malloc leaves them), since
by default every numpy temporary above 128 KiB is mapped and unmapped afresh.

Timing. mechgraph: `mechgraph sweep ... --threads 1`, its own log line "sweep: N cases in S s"
(evaluation and CSV rows, no process start or scene loading), and the whole process's wall clock.
numpy: time.perf_counter around the design loop (results kept in an array). Each side: the best
of --repeats runs, taken in rounds over the sides so that a burst of load elsewhere spoils no
single side. All on one core (numpy does not thread these element-wise operations).
"""

import argparse
import json
import math
import os
import re
import subprocess
import shutil
import tempfile
import time
from fractions import Fraction

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))

# --- The scene's parameters (scenes/valvetrain_cams.yaml), SI.
PI = math.pi
DEG = PI / 180.0
LIFT = 8.0e-3                    # max tappet lift h_max, m (swept 7..9 mm)
ACTION = 130.0 * DEG             # action angle phi_d
HALF = 0.5 * ACTION              # phi_p
ACCEL = 18.0 * DEG               # positive-acceleration phase phi_y (three-arc, Kurz)
R0 = 17.0e-3                     # base radius, m (swept 15..19 mm)
W_K = 5600.0 * 2.0 * PI / 60.0 / 2.0   # camshaft speed, rad/s
ROCKER = 1.5                     # valve lift / tappet lift
LASH = 0.25e-3                   # m
SEAT_D = 34.0e-3                 # inner seat diameter d0, m
SEAT_A = 45.0 * DEG              # seat angle
POLY_EXPONENTS = (2, 14, 26, 38, 50)
STEP = 0.1 * DEG                 # sampling step of the numpy side
LIFT_RANGE = (7.0e-3, 9.0e-3)
R0_RANGE = (15.0e-3, 19.0e-3)
CAMS = ("arc", "kurz", "poly")
COS_A, SIN_A = math.cos(SEAT_A), math.sin(SEAT_A)

# The figures of one design, in this order (SI: m, rad, m/rad^k, m/s, m/s^2, m^2*s, m^2*rad, m^2).
FIELDS = ("accel_angle", "min_curvature_radius", "max_velocity_cam", "max_acceleration_cam", "min_acceleration_cam",
          "valve_max_lift", "open_angle", "max_velocity", "max_acceleration", "min_acceleration",
          "time_area", "angle_area", "mean_flow_area")
# The mechgraph port of each figure, "{c}" the cam node.
PORTS = ("{c}.accel_angle", "{c}.min_curvature_radius", "{c}.max_velocity", "{c}.max_acceleration",
         "{c}.min_acceleration", "v_{c}.max_lift", "v_{c}.open_angle", "v_{c}.max_velocity",
         "v_{c}.max_acceleration", "v_{c}.min_acceleration", "ta_{c}.time_area", "ta_{c}.angle_area",
         "ta_{c}.mean_flow_area")


# --- Cam laws --------------------------------------------------------------------------------------
# A law is described on the rising half by x, the cam angle from the start of lift (0 .. phi_p):
# `starts` are the x where its smooth pieces begin (starts[0] = 0) and `pieces` one function per
# piece, x (array) -> h, dh/dx, d2h/dx2, d3h/dx3. The law is symmetric about the nose (phi = 0):
# h(phi) = H(phi_p - |phi|), so dh/dphi = +dH/dx before the nose and -dH/dx after it.

def three_arc_law(h, r0, phi_y=ACCEL, phi_p=HALF):
    """Three-arc convex cam, flat tappet, radii from the flank angle (the closed form of the
    method note): flank arc h = e (1 - cos x), nose arc h = h_max - a (1 - cos t), t = phi_p - x.
    Returns (starts, pieces, r2); r2 <= 0 means no such cam. h and r0 may be scalars or columns
    of an array (one design per row; so may the laws below)."""
    c = math.cos(phi_p)
    s = math.sin(phi_p) / math.sin(phi_y)
    qa = 2.0 * (s - 1.0) * (1.0 - c)
    qb = -2.0 * h * (s - 1.0 + c)
    qc = -h * h
    a = (-qb + np.sqrt(qb * qb - 4.0 * qa * qc)) / (2.0 * qa)     # nose-centre distance
    e = a * (s - 1.0) + h                                          # flank-centre distance r1 - r0
    r2 = r0 + h - a
    alpha = np.arctan2(e * math.sin(phi_p), a + e * c)             # the switch, from the nose
    x_switch = phi_p - alpha                                       # = phi_y for the flat tappet

    def flank(x):
        sx, cx = np.sin(x), np.cos(x)
        return e * (1.0 - cx), e * sx, e * cx, -e * sx

    def nose(x):
        t = phi_p - x
        st, ct = np.sin(t), np.cos(t)
        return h - a * (1.0 - ct), a * st, -a * ct, -a * st

    return (0.0, x_switch), (flank, nose), r2


def kurz_law(h, r0, phi_y=ACCEL, phi_p=HALF):
    """Kurz (shockless) cam: acceleration A+ sin(pi/2 tau) over phi_1, A+ cos(pi/2 tau) over
    phi_2 (phi_1 + phi_2 = phi_y), then A- (1 - (1 - tau)^2) up to the nose over phi_3 =
    phi_p - phi_y; A+ and A- from h'(nose) = 0 and h(nose) = h_max. The split phi_1/phi_y is
    mechgraph's default: jerk continuous at phi_y when that exists, else the minimax split."""
    phi_3 = phi_p - phi_y
    split = 1.0 - PI * PI * (phi_3 / phi_y) ** 2 / 12.0
    if split <= 0.0:
        kappa = 6.0 * phi_y * phi_y / (PI * phi_3 * phi_3)
        split = 0.5 * (1.0 + kappa / (PI + math.hypot(PI, kappa)))
    l1 = split * phi_y
    l2 = phi_y - l1
    k = 2.0 / PI
    # Lift and velocity at the nose per unit amplitude of each phase: a shape of length L adds
    # L * int(a) to the velocity and L^2 * int(int(a)) (plus velocity * L) to the lift.
    v_pos = l1 * k + l2 * k
    h_pos = l1 * l1 * k * k * (PI / 2.0 - 1.0) + (l1 * k) * l2 + l2 * l2 * k * k + v_pos * phi_3
    v_neg = phi_3 * 2.0 / 3.0
    h_neg = phi_3 * phi_3 / 4.0
    det = v_pos * h_neg - v_neg * h_pos
    ap = -v_neg * h / det
    an = v_pos * h / det
    # Lift and velocity where the 2nd and 3rd pieces start.
    h1, v1 = ap * l1 * l1 * k * k * (PI / 2.0 - 1.0), ap * l1 * k
    h2, v2 = h1 + v1 * l2 + ap * l2 * l2 * k * k, v1 + ap * l2 * k

    def quarter_sine(x):
        th = 0.5 * PI * x / l1
        s, c = np.sin(th), np.cos(th)
        return ap * l1 * l1 * k * k * (th - s), ap * l1 * k * (1.0 - c), ap * s, ap * 0.5 * PI * c / l1

    def quarter_cosine(x):
        y = x - l1
        th = 0.5 * PI * y / l2
        s, c = np.sin(th), np.cos(th)
        return h1 + v1 * y + ap * l2 * l2 * k * k * (1.0 - c), v1 + ap * l2 * k * s, ap * c, -ap * 0.5 * PI * s / l2

    def parabola(x):
        y = x - phi_y
        tau = y / phi_3
        return (h2 + v2 * y + an * phi_3 * phi_3 * tau ** 3 * (4.0 - tau) / 12.0,
                v2 + an * phi_3 * tau * tau * (1.0 - tau / 3.0), an * tau * (2.0 - tau), an * 2.0 * (1.0 - tau) / phi_3)

    return (0.0, l1, phi_y), (quarter_sine, quarter_cosine, parabola), None


def polydyne_coefficients(exponents):
    """C_i = -prod_{j != i} n_j / prod_{j != i} (n_i - n_j), exactly, then as floats."""
    out = []
    for i, ni in enumerate(exponents):
        num, den = -1, 1
        for j, nj in enumerate(exponents):
            if j != i:
                num *= nj
                den *= ni - nj
        out.append(float(Fraction(num, den)))
    return out


POLY_C = polydyne_coefficients(POLY_EXPONENTS)


def polydyne_law(h, r0, phi_p=HALF):
    """Kinematic polydyne x = h [1 + sum C_n u^n], u = |phi| / phi_p = 1 - x / phi_p, summed as
    written (monomials; near the seat the terms cancel, which costs digits only in lifts far below
    anything the study looks at)."""
    def poly(x):
        u = 1.0 - x / phi_p
        f0, f1, f2, f3 = 1.0, 0.0, 0.0, 0.0   # d^m/du^m of x/h
        for n, cn in zip(POLY_EXPONENTS, POLY_C):
            if n == 2:
                f0 = f0 + cn * u * u
                f1 = f1 + 2.0 * cn * u
                f2 = f2 + 2.0 * cn
            else:
                p = u ** (n - 3)
                f3 = f3 + cn * n * (n - 1) * (n - 2) * p
                p = p * u
                f2 = f2 + cn * n * (n - 1) * p
                p = p * u
                f1 = f1 + cn * n * p
                f0 = f0 + cn * p * u
        # d/dx = -(1/phi_p) d/du
        return h * f0, -h * f1 / phi_p, h * f2 / phi_p ** 2, -h * f3 / phi_p ** 3

    return (0.0,), (poly,), None


LAWS = {"arc": three_arc_law, "kurz": kurz_law, "poly": polydyne_law}

GRID = np.linspace(-HALF, HALF, int(round(ACTION / STEP)) + 1)   # 0.1 deg over the event, ends included


def law_at(starts, pieces, phi):
    """The law at a few angles phi (scalars): h, h', h'', h''' over cam angle."""
    out = []
    for p in phi:
        x = HALF - abs(p)
        j = max(0, int(np.searchsorted(starts, x, side="right")) - 1)
        v = pieces[j](np.array([x]))
        sign = 1.0 if p < 0.0 else -1.0
        out.append((float(v[0][0]), sign * float(v[1][0]), float(v[2][0]), sign * float(v[3][0])))
    return out


def design(cam, h_max, r0):
    """Stages 1-3 of one cam design; the FIELDS as a list, and a flag: 0 fine, 1 no such cam,
    2 undercut contour."""
    starts, pieces, r2 = LAWS[cam](h_max, r0)
    flag = 1 if (r2 is not None and r2 <= 0.0) else 0
    m = len(starts)
    # Knots over the whole event: the piece starts on the rising side, mirrored on the falling
    # side; the segment over the nose belongs to the last piece.
    x_knots = np.array(starts)
    knots = np.concatenate((x_knots - HALF, HALF - x_knots[::-1]))
    phis, hs, h1s, h2s = [], [], [], []
    for s in range(2 * m - 1):
        a, b = knots[s], knots[s + 1]
        lo, hi = np.searchsorted(GRID, a, side="right"), np.searchsorted(GRID, b, side="left")
        phi = np.concatenate(([a], GRID[lo:hi], [b]))
        piece = s if s < m else 2 * m - 2 - s
        h, d1, d2, _ = pieces[piece](HALF - np.abs(phi))
        if s < m - 1:
            sign = 1.0
        elif s > m - 1:
            sign = -1.0
        else:
            sign = np.where(phi < 0.0, 1.0, -1.0)
        phis.append(phi)
        hs.append(h)
        h1s.append(sign * d1)
        h2s.append(d2)
    phi = np.concatenate(phis)
    h = np.concatenate(hs)
    h1 = np.concatenate(h1s)
    h2 = np.concatenate(h2s)

    # Stage 1: peaks, acceleration phase, curvature.
    max_v = np.max(np.abs(h1))
    max_a, min_a = np.max(h2), np.min(h2)
    rho = min(np.min(r0 + h + h2), r0)
    if rho <= 0.0 and flag == 0:
        flag = 2
    i0 = int(np.argmax(h2 > 0.0))                       # first positive acceleration
    j = i0 + int(np.argmax(h2[i0:] <= 0.0))             # first sample after it that is not
    accel_end = phi[j - 1] + (phi[j] - phi[j - 1]) * h2[j - 1] / (h2[j - 1] - h2[j])

    # Stage 2: the valve, open between the crossings of i h = lash.
    g = ROCKER * h - LASH
    is_open = g > 0.0
    i1 = int(np.argmax(is_open))
    i2 = len(g) - 1 - int(np.argmax(is_open[::-1]))
    opening = phi[i1 - 1] + (phi[i1] - phi[i1 - 1]) * g[i1 - 1] / (g[i1 - 1] - g[i1])
    closing = phi[i2] + (phi[i2 + 1] - phi[i2]) * g[i2] / (g[i2] - g[i2 + 1])

    # The three roots from linear interpolation are refined by one Newton step on the law's exact
    # derivatives (the law evaluated there; the valve's velocity and acceleration at the refined
    # opening and closing follow by a first-order Taylor step). A sign change between the two
    # one-sided samples of a knot (a jump of h'') is exact already and is left alone.
    (_, _, a_e, j_e), (h_o, v_o, a_o, j_o), (h_c, v_c, a_c, j_c) = law_at(starts, pieces, (accel_end, opening, closing))
    if phi[j] > phi[j - 1]:
        accel_end -= a_e / j_e
    accel_angle = accel_end + HALF
    d_o = -(ROCKER * h_o - LASH) / (ROCKER * v_o)
    d_c = -(ROCKER * h_c - LASH) / (ROCKER * v_c)
    opening, v_o, a_o = opening + d_o, v_o + a_o * d_o, a_o + j_o * d_o
    closing, v_c, a_c = closing + d_c, v_c + a_c * d_c, a_c + j_c * d_c
    v_phi = np.concatenate(([opening], phi[i1:i2 + 1], [closing]))
    v_lift = np.concatenate(([0.0], g[i1:i2 + 1], [0.0]))
    v_vel = ROCKER * np.concatenate(([v_o], h1[i1:i2 + 1], [v_c]))
    v_acc = ROCKER * np.concatenate(([a_o], h2[i1:i2 + 1], [a_c]))
    open_angle = closing - opening

    # Stage 3: time-area through the conical seat, trapezoid rule over cam angle.
    f = PI * v_lift * COS_A * (SEAT_D + v_lift * SIN_A * COS_A)
    angle_area = np.trapz(f, v_phi)

    return [accel_angle, rho, max_v, max_a, min_a,
            np.max(v_lift), open_angle, W_K * np.max(np.abs(v_vel)), W_K * W_K * np.max(v_acc),
            W_K * W_K * np.min(v_acc), angle_area / W_K, angle_area, angle_area / open_angle], flag


# --- The same study with the designs batched: one cam type, all cases at once, 2-D arrays
# (row = design, column = sample). Not the script the brief describes (that is `design` above, one
# design at a time); shown for context, because it is what numpy is best at. Same samples, same
# formulas, same refinements, so the same figures to rounding.

def law_batch(starts, pieces, phi, piece):
    """h, h', h'', h''' over cam angle at phi[row, col], each sample with the piece `piece` gives
    it (every piece's formula is evaluated on the whole array and the right one kept)."""
    x = HALF - np.abs(phi)
    out = [np.zeros_like(phi) for _ in range(4)]
    for k, f in enumerate(pieces):
        vals = f(x)
        mask = piece == k
        for o, v in zip(out, vals):
            np.copyto(o, v, where=mask)
    sign = np.where(phi < 0.0, 1.0, -1.0)
    return out[0], sign * out[1], out[2], sign * out[3]


def piece_of(starts, x):
    """The piece each x (from the start of lift) falls in."""
    piece = np.zeros(x.shape, dtype=int)
    for s in starts[1:]:
        piece += x >= s
    return piece


def study_batched(cases):
    """Every cam for every case, each cam type in one batch: results[case, cam, field], flags."""
    n = len(cases)
    lift, r0 = cases[:, :1], cases[:, 1:]
    results = np.empty((n, len(CAMS), len(FIELDS)))
    flags = np.zeros((n, len(CAMS)), dtype=int)
    rows = np.arange(n)
    for c, cam in enumerate(CAMS):
        starts, pieces, r2 = LAWS[cam](lift, r0)
        m = len(starts)
        # Columns: left-hand copies of the inner knots, the grid, right-hand copies; a stable sort
        # by angle keeps that order among equal angles (left value, grid, right value).
        inner = [np.broadcast_to(np.asarray(s, dtype=float), (n, 1)) for s in starts[1:]]
        k_phi = [s - HALF for s in inner] + [HALF - s for s in inner]
        k_left = [k - 1 for k in range(1, m)] + [k for k in range(1, m)]     # piece before the knot
        k_right = [k for k in range(1, m)] + [k - 1 for k in range(1, m)]    # and after it
        grid = np.broadcast_to(GRID, (n, len(GRID)))
        phi = np.concatenate(k_phi + [grid] + k_phi, axis=1)
        piece = np.concatenate([np.full((n, 1), k) for k in k_left] + [piece_of(starts, HALF - np.abs(grid))]
                               + [np.full((n, 1), k) for k in k_right], axis=1)
        order = np.argsort(phi, axis=1, kind="stable")
        phi = np.take_along_axis(phi, order, axis=1)
        piece = np.take_along_axis(piece, order, axis=1)
        h, h1, h2, _ = law_batch(starts, pieces, phi, piece)
        col = np.arange(phi.shape[1])

        max_v = np.max(np.abs(h1), axis=1)
        max_a, min_a = np.max(h2, axis=1), np.min(h2, axis=1)
        rho = np.minimum(np.min(r0 + h + h2, axis=1), r0[:, 0])
        i0 = np.argmax(h2 > 0.0, axis=1)
        j = np.argmax((h2 <= 0.0) & (col >= i0[:, None]), axis=1)
        p0, p1, a0, a1 = phi[rows, j - 1], phi[rows, j], h2[rows, j - 1], h2[rows, j]
        accel_end = p0 + (p1 - p0) * a0 / (a0 - a1)

        g = ROCKER * h - LASH
        is_open = g > 0.0
        i1 = np.argmax(is_open, axis=1)
        i2 = phi.shape[1] - 1 - np.argmax(is_open[:, ::-1], axis=1)
        opening = phi[rows, i1 - 1] + (phi[rows, i1] - phi[rows, i1 - 1]) * g[rows, i1 - 1] / (g[rows, i1 - 1] - g[rows, i1])
        closing = phi[rows, i2] + (phi[rows, i2 + 1] - phi[rows, i2]) * g[rows, i2] / (g[rows, i2] - g[rows, i2 + 1])

        # One Newton step for each of the three roots, as `design` does.
        pts = np.column_stack((accel_end, opening, closing))
        e_h, e_v, e_a, e_j = law_batch(starts, pieces, pts, piece_of(starts, HALF - np.abs(pts)))
        accel_end = np.where(p1 > p0, accel_end - e_a[:, 0] / e_j[:, 0], accel_end)
        d = -(ROCKER * e_h[:, 1:] - LASH) / (ROCKER * e_v[:, 1:])
        ends_v = e_v[:, 1:] + e_a[:, 1:] * d
        ends_a = e_a[:, 1:] + e_j[:, 1:] * d
        opening, closing = opening + d[:, 0], closing + d[:, 1]

        lift_v = np.where(is_open, g, 0.0)
        f = PI * lift_v * COS_A * (SEAT_D + lift_v * SIN_A * COS_A)
        # Trapezoids over the row, less the parts of the two cells cut by the opening and closing.
        area = np.sum(0.5 * (f[:, 1:] + f[:, :-1]) * np.diff(phi, axis=1), axis=1)
        area -= 0.5 * f[rows, i1] * (opening - phi[rows, i1 - 1]) + 0.5 * f[rows, i2] * (phi[rows, i2 + 1] - closing)
        open_angle = closing - opening
        vel = np.maximum(np.max(np.where(is_open, np.abs(h1), 0.0), axis=1), np.max(np.abs(ends_v), axis=1))
        acc_max = np.maximum(np.max(np.where(is_open, h2, -np.inf), axis=1), np.max(ends_a, axis=1))
        acc_min = np.minimum(np.min(np.where(is_open, h2, np.inf), axis=1), np.min(ends_a, axis=1))
        results[:, c] = np.column_stack((
            accel_end + HALF, rho, max_v, max_a, min_a, np.max(lift_v, axis=1), open_angle,
            W_K * ROCKER * vel, W_K * W_K * ROCKER * acc_max, W_K * W_K * ROCKER * acc_min,
            area / W_K, area, area / open_angle))
        flags[:, c] = np.where(rho <= 0.0, 2, 0)
        if r2 is not None:
            flags[:, c] = np.where(r2[:, 0] <= 0.0, 1, flags[:, c])
    return results, flags


def keep_freed_memory():
    """Ask glibc's malloc to keep freed memory instead of returning it to the system at once: by
    default an array above 128 KiB is mmap-ed and unmapped again, so every large numpy temporary
    costs fresh page faults (this made the batched variant 5-7x slower, depending on what had been
    allocated before). Matters only for the batched variant (the one-design arrays are ~10 KiB);
    mechgraph runs in its own process, unaffected. Returns whether it took effect."""
    try:
        import ctypes
        libc = ctypes.CDLL("libc.so.6")
        m_trim_threshold, m_mmap_threshold = -1, -3
        return bool(libc.mallopt(m_mmap_threshold, 32 << 20)) and bool(libc.mallopt(m_trim_threshold, 128 << 20))
    except (OSError, AttributeError):
        return False


def latin_hypercube(n, seed):
    """n cases of (lift, r0): one per stratum of each variable, strata paired at random."""
    rng = np.random.default_rng(seed)
    cols = []
    for lo, hi in (LIFT_RANGE, R0_RANGE):
        u = (rng.permutation(n) + rng.random(n)) / n
        cols.append(lo + (hi - lo) * u)
    return np.column_stack(cols)


def study(cases):
    """Every cam for every case: results[case, cam, field] and flags[case, cam]."""
    results = np.empty((len(cases), len(CAMS), len(FIELDS)))
    flags = np.zeros((len(cases), len(CAMS)), dtype=int)
    for i, (lift, r0) in enumerate(cases):
        for c, cam in enumerate(CAMS):
            results[i, c], flags[i, c] = design(cam, lift, r0)
    return results, flags


# --- mechgraph side --------------------------------------------------------------------------------
UNITS = {"1": 1.0, "m": 1.0, "rad": 1.0, "mm": 1e-3, "deg": DEG, "mm/deg": 1e-3 / DEG, "m/rad": 1.0,
         "m/rad^2": 1.0, "m/s": 1.0, "m/s^2": 1.0, "mm^2*s": 1e-6, "m^2*s": 1.0, "mm^2*deg": 1e-6 * DEG,
         "m^2*rad": 1.0, "mm^2": 1e-6, "m^2": 1.0}


def sweep_outputs():
    return ",".join(p.format(c=c) for c in CAMS for p in PORTS)


def run_sweep(exe, scene, n, out_csv):
    """One `mechgraph sweep`: (cases/s from its log line, process wall-clock seconds, cases)."""
    cmd = [exe, "sweep", scene, "--sample", "lift=7mm:9mm", "--sample", "r0=15mm:19mm", "--n", str(n),
           "--seed", "1", "--threads", "1", "--outputs", sweep_outputs(), "--out", out_csv, "--force"]
    t0 = time.perf_counter()
    proc = subprocess.run(cmd, capture_output=True, text=True)
    wall = time.perf_counter() - t0
    if proc.returncode not in (0, 3):   # 3: some cases failed (undercut), rows still written
        raise RuntimeError(f"mechgraph sweep exited with {proc.returncode}: {proc.stderr.strip()}")
    m = re.search(r"sweep: (\d+) cases in ([0-9.eE+-]+) s \(([0-9.eE+-]+)/s on (\d+) thread", proc.stderr)
    if not m:
        raise RuntimeError(f"no 'sweep: N cases in S s' line in mechgraph's log: {proc.stderr.strip()}")
    cases = int(m.group(1))
    return cases / float(m.group(2)), wall, cases


def read_sweep_csv(path):
    """Case values and results of a sweep CSV, converted to SI: (cases [n, 2], results [n, cam,
    field] with NaN for failed cases, failed flags)."""
    import csv
    with open(path, newline="") as fh:
        rows = list(csv.reader(fh))
    header = rows[0]
    col, scale = {}, {}
    for i, name in enumerate(header):
        m = re.match(r"(.+?) \[(.+)\]$", name)
        if m:
            col[m.group(1)], scale[m.group(1)] = i, UNITS[m.group(2)]
    cases = np.array([[float(r[col["lift"]]) * scale["lift"], float(r[col["r0"]]) * scale["r0"]] for r in rows[1:]])
    results = np.full((len(cases), len(CAMS), len(FIELDS)), np.nan)
    failed = np.array([r[header.index("error")] != "" for r in rows[1:]])
    for k, r in enumerate(rows[1:]):
        for c, cam in enumerate(CAMS):
            for f, port in enumerate(PORTS):
                p = port.format(c=cam)
                if r[col[p]] != "":
                    results[k, c, f] = float(r[col[p]]) * scale[p]
    return cases, results, failed


def nominal_reference(exe, scene, extra=()):
    """mechgraph's outputs of the nominal scene (`run --json`): {port: SI value}."""
    proc = subprocess.run([exe, "-q", "run", scene, "--json", *extra], capture_output=True, text=True)
    if proc.returncode != 0:
        raise RuntimeError(f"mechgraph run exited with {proc.returncode}: {proc.stderr.strip()}")
    return {k: v["value"] for k, v in json.loads(proc.stdout)["outputs"].items() if isinstance(v.get("value"), float)}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--mechgraph", default=os.environ.get("MECHGRAPH", os.path.join(ROOT, "build", "bin", "mechgraph")))
    ap.add_argument("--scene", default=os.path.join(ROOT, "scenes", "valvetrain_cams.yaml"))
    ap.add_argument("--cases", type=int, default=1000, help="Latin-hypercube cases (default 1000, x 3 cams)")
    ap.add_argument("--repeats", type=int, default=5, help="timed runs per side; the fastest counts (default 5)")
    ap.add_argument("--batch", type=int, default=50, help="designs per 2-D array of the batched numpy variant (default 50)")
    ap.add_argument("--quick", action="store_true", help="300 cases, 2 repetitions")
    ap.add_argument("--default-malloc", action="store_true", help="leave glibc's malloc thresholds alone "
                    "(see keep_freed_memory)")
    args = ap.parse_args()
    tuned = False if args.default_malloc else keep_freed_memory()
    if args.quick:
        args.cases, args.repeats = min(args.cases, 300), min(args.repeats, 2)
    print(f"mechgraph: {args.mechgraph}\nscene:     {args.scene}")
    print(f"study:     {args.cases} cases (lift 7-9 mm, r0 15-19 mm, Latin hypercube) x 3 cams "
          f"(three-arc, Kurz, polydyne {list(POLY_EXPONENTS)}); numpy samples every {STEP / DEG:g} deg")

    # --- Accuracy at the nominal design (lift 8 mm, r0 17 mm) against mechgraph's `run --json`.
    ref = nominal_reference(args.mechgraph, args.scene)
    # mechgraph's own quadrature error: the same run at the tightest tolerance it accepts.
    tight = nominal_reference(args.mechgraph, args.scene, [a for c in CAMS for a in ("--set", f"ta_{c}.tolerance=1e-13")])
    print()
    print("nominal design, numpy (0.1 deg) against mechgraph (relative error; '-' not in `run --json`):")
    print(f"{'figure':24s}" + "".join(f"{c:>24s}" for c in ("three-arc", "Kurz", "polydyne")))
    worst_numpy = 0.0
    for f, field in enumerate(FIELDS):
        line = f"{field:24s}"
        for cam in CAMS:
            mine = design(cam, LIFT, R0)[0][f]
            port = PORTS[f].format(c=cam)
            if port in ref:
                err = abs(mine - ref[port]) / abs(ref[port])
                worst_numpy = max(worst_numpy, err)
                line += f"  {mine:11.6g} {err:9.1e}  "
            else:
                line += f"  {mine:11.6g} {'-':>9s}  "
        print(line)
    worst_mech = max(abs(ref[p] - tight[p]) / abs(tight[p]) for p in tight if p.startswith("ta_") and p in ref)
    ta_err = max(abs(design(c, LIFT, R0)[0][FIELDS.index(k)] - ref[f"ta_{c}.{k}"]) / ref[f"ta_{c}.{k}"]
                 for c in CAMS for k in ("time_area", "angle_area"))
    print(f"largest numpy error over these figures: {worst_numpy:.1e} (time-area and angle-area: {ta_err:.1e}); "
          f"mechgraph's time-area at tolerance 1e-10 against 1e-13: {worst_mech:.1e}")

    # --- Timing, in rounds over the sides (a burst of load elsewhere spoils no single side); the
    # fastest run of each side counts.
    # A fresh folder of our own: mechgraph writes the table there itself (it refuses to replace a
    # file it did not write, such as an empty one made in advance).
    work_dir = tempfile.mkdtemp(prefix="mechgraph_stages123_")
    csv_path = os.path.join(work_dir, "sweep.csv")
    cases = latin_hypercube(args.cases, 1)
    study(cases[:5])           # warm-up
    study_batched(cases[:5])
    best = {"log": 0.0, "wall": math.inf, "loop": math.inf, "batched": math.inf}
    try:
        for _ in range(args.repeats):
            rate, wall, sweep_n = run_sweep(args.mechgraph, args.scene, args.cases, csv_path)
            best["log"], best["wall"] = max(best["log"], rate), min(best["wall"], wall)
            t0 = time.perf_counter()
            _, flags = study(cases)
            best["loop"] = min(best["loop"], time.perf_counter() - t0)
            t0 = time.perf_counter()
            for i in range(0, len(cases), args.batch):
                study_batched(cases[i:i + args.batch])
            best["batched"] = min(best["batched"], time.perf_counter() - t0)
        m_cases, m_results, m_failed = read_sweep_csv(csv_path)
    finally:
        shutil.rmtree(work_dir, ignore_errors=True)

    # --- Accuracy over the whole sweep: numpy on mechgraph's own cases.
    n_results, n_flags = study(m_cases)
    b_results, _ = study_batched(m_cases)
    ok = ~np.isnan(m_results)
    rel = np.where(ok, np.abs(n_results - m_results) / np.where(ok, np.abs(m_results), 1.0), 0.0)
    same = np.max(np.abs(b_results - n_results) / np.abs(n_results))
    print()
    print(f"whole sweep, numpy on mechgraph's {len(m_cases)} cases ({int(m_failed.sum())} failed in mechgraph, "
          f"{int((n_flags == 2).sum())} designs undercut by numpy's check, "
          f"{int((n_flags == 1).sum())} three-arc cams impossible): largest relative error per figure")
    for f, field in enumerate(FIELDS):
        print(f"  {field:22s} " + "  ".join(f"{cam} {rel[:, c, f].max():8.1e}" for c, cam in enumerate(CAMS)))
    print(f"  (numpy batched against numpy one at a time: largest relative difference {same:.1e})")
    print(f"numpy's own sample ({len(cases)} cases): {int((flags == 2).sum())} designs undercut, "
          f"{int((flags == 1).sum())} three-arc cams impossible (computed all the same)")

    n = len(cases)
    d_mech, d_wall = 3.0 * best["log"], 3.0 * sweep_n / best["wall"]
    d_loop, d_batch = 3.0 * n / best["loop"], 3.0 * n / best["batched"]
    ta_mech = f"{worst_mech:.1e}"
    rows = [("mechgraph sweep (its log: evaluation + rows)", d_mech, ta_mech, "reference"),
            ("mechgraph sweep (whole process, wall clock)", d_wall, ta_mech, "reference"),
            ("numpy, one design at a time (the script)", d_loop, f"{ta_err:.1e}", f"{worst_numpy:.1e}"),
            (f"numpy, {args.batch} designs per 2-D batch" + ("" if tuned else " (malloc default)"), d_batch, f"{ta_err:.1e}", f"{worst_numpy:.1e}")]
    print()
    print(f"stages 1-3, designs per second on one core (3 designs per case, {n} cases; fastest of {args.repeats} runs); "
          "errors: relative, nominal design, against mechgraph (mechgraph's time-area: tolerance 1e-10 against 1e-13)")
    print(f"{'side':50s} {'designs/s':>10s} {'time-area err':>14s} {'largest err':>12s} {'mechgraph log / side':>21s}")
    for name, rate, e_ta, e_all in rows:
        print(f"{name:50s} {rate:10.0f} {e_ta:>14s} {e_all:>12s} {d_mech / rate:20.2f}x")
    print()
    print(f"ratio stages 1-3, mechgraph / numpy (designs/s): {d_mech / d_loop:.1f}x against the one-design-at-a-time "
          f"script ({d_wall / d_loop:.1f}x counting mechgraph's whole process); {d_mech / d_batch:.1f}x against numpy "
          f"batched {args.batch} designs at a time")


if __name__ == "__main__":
    main()
