"""The grid peer of the three-cam study (stages 1-3, eight outputs; stages123_cases.py): the laws
taken as black boxes, as a generic script must take them, everything else from a fine uniform grid
over each design's lift event, in numpy vectorised across designs (a batch of cases at a time,
each array cases x grid points).

Each law gives lift h and acceleration h'' at any cam angle phi (measured from the start of lift)
from its own formulas (docs/methods/valvetrain.md); nothing else of a law is used: no breakpoint,
no peak location, no integral. Per design, on G points phi_j = j * action / (G - 1) with G from
the batch's largest action and the step (so every design's own step d <= the step):
  * valve lift x = i h - lash, open where x > 0; the opening and closing angles where x = 0 by
    inverse cubic interpolation through the four grid points around each crossing;
  * time-area (1/w_k) int f_v dphi over the open period, f_v = k1 x + k2 x^2 (conical seat):
    composite Simpson over the open grid points (when their interval count is odd, the last
    interval by the quadratic through the last three points, d/12 (-f0 + 8 f1 + 5 f2)), plus the
    two cut cells at the ends by the quadratic through the crossing (f = 0) and the next two points:
    int_0^p = f1 p/2 - p^2 (f2 p/q - f1)/(6 d), p the cell's open part, q = p + d;
  * valve accelerations w_k^2 i h'': the largest and least grid value over the open period, each
    refined by the parabola through it and its two neighbours (vertex offset
    s = (y- - y+) / (2 (y- - 2 y0 + y+)), value y0 - (y- - y+) s / 4, kept when the vertex lies in
    the open period), against the law's value at the opening and closing angles (a peak on the edge).
The step that meets the study's bound 1e-6 (relative, every output, against mechgraph) is 0.045 deg:
the Kurz acceleration peak sits where h''' is continuous but h'''' jumps, so the parabola's error
there depends on where the grid falls (up to ~8e-7 at 0.045 deg); everything else is better than
2e-7. The base radius does not enter a flat-tappet lift (it only decides undercut, which
mechgraph checks and this peer does not).
"""

import math

import numpy as np

from stages123_cases import OUTPUTS, POLYDYNE_EXPONENTS, SEAT_ANGLE, slice_table

DEG = math.pi / 180.0
STEP = 0.045 * DEG


# --- The laws: constructors from per-case columns (arrays of shape cases x 1) to a function
# phi -> (h, h''), phi any array broadcasting against the columns.

def three_arc(H, action, phy):
    """Three-arc cam, flat tappet: flank h = e (1 - cos psi) up to psi = phi_y, nose
    h = H - a (1 - cos t), t from the nose; a, e from tangency at phi_y and h(nose) = H."""
    php = 0.5 * action
    s = np.sin(php) / np.sin(phy)
    cp = np.cos(php)
    qa = 2.0 * (s - 1.0) * (1.0 - cp)
    qb = -2.0 * H * (s - 1.0 + cp)
    a = (-qb + np.sqrt(qb * qb + 4.0 * qa * H * H)) / (2.0 * qa)
    e = a * (s - 1.0) + H

    def law(phi):
        psi = np.minimum(phi, action - phi)          # from the nearer end of the event
        t = php - psi                                # from the nose
        flank = psi < phy
        sp = np.sin(0.5 * psi)
        h = np.where(flank, 2.0 * e * sp * sp, H - a * (1.0 - np.cos(t)))
        acc = np.where(flank, e * np.cos(psi), -a * np.cos(t))
        return h, acc
    return law


def kurz_split(php, phy):
    """mechgraph's default share phi_1 / phi_y of the quarter sine: h''' continuous at phi_y when
    that is possible, else the minimax split."""
    ph3 = php - phy
    smooth = 1.0 - math.pi ** 2 * (ph3 / phy) ** 2 / 12.0
    kappa = 6.0 * phy * phy / (math.pi * ph3 * ph3)
    minimax = 0.5 * (1.0 + kappa / (math.pi + np.hypot(math.pi, kappa)))
    return np.where(smooth > 0.0, smooth, minimax)


def kurz_constants(H, php, phy):
    """(phi_1, c1, c2, A+, A-, h1, v1): quarter sine h'' = A+ sin(psi/c1) over [0, phi_1], quarter
    cosine A+ cos((psi - phi_1)/c2) up to phi_y, then A- (1 - t^2/phi_3^2), t from the nose;
    c_k = 2 phi_k / pi. A- from h'(nose) = 0, A+ from h(nose) = H; h1, v1 lift and velocity at phi_1."""
    ph1 = kurz_split(php, phy) * phy
    ph3 = php - phy
    c1, c2 = 2.0 * ph1 / math.pi, 2.0 * (phy - ph1) / math.pi
    ap = H / (c1 * (phy - c1) + c2 * c2 + 5.0 * phy * ph3 / (4.0 * math.pi))
    an = -3.0 * ap * phy / (math.pi * ph3)
    return ph1, c1, c2, ap, an, ap * c1 * (0.5 * math.pi * c1 - c1), ap * c1


def kurz(H, action, phy):
    php = 0.5 * action
    ph3 = php - phy
    ph1, c1, c2, ap, an, h1, v1 = kurz_constants(H, php, phy)

    def law(phi):
        psi = np.minimum(phi, action - phi)
        t = php - psi
        th = psi / c1
        r = (psi - ph1) / c2
        tt = t * t / (ph3 * ph3)
        sin_th, cos_r = np.sin(th), np.cos(r)
        h = np.where(psi < ph1, ap * c1 * c1 * (th - sin_th),
                     np.where(psi < phy, h1 + v1 * (psi - ph1) + ap * c2 * c2 * (1.0 - cos_r),
                              H + an * t * t * (0.5 - tt / 12.0)))
        acc = np.where(psi < ph1, ap * sin_th, np.where(psi < phy, ap * cos_r, an * (1.0 - tt)))
        return h, acc
    return law


def polydyne_coefficients(exponents):
    """C_n of P(u) = 1 + sum C_n u^n with P(1) = 0 and P', P'', ... (as many as there are terms
    less one) zero at u = 1: C_i = -prod_{j != i} n_j / prod_{j != i} (n_i - n_j)."""
    n = [float(v) for v in exponents]
    return [-math.prod(n[j] for j in range(len(n)) if j != i) / math.prod(n[i] - n[j] for j in range(len(n)) if j != i)
            for i in range(len(n))]


def polydyne(H, action, exponents=POLYDYNE_EXPONENTS):
    """Polydyne h = H P(u), u = (phi - phi_p)/phi_p, h'' = H P''(u)/phi_p^2. The exponents here are
    2 + g k (g = 12): P - 1 = u^2 sum_k C_k w^k and P'' = sum_k D_k w^k, w = u^g, both by Horner."""
    gap = exponents[1] - exponents[0]
    if exponents[0] != 2 or any(b - a != gap for a, b in zip(exponents, exponents[1:])) or gap % 2:
        raise ValueError("this peer evaluates polydynes with exponents 2, 2 + g, 2 + 2g, ... (g even)")
    C = polydyne_coefficients(exponents)
    D = [c * n * (n - 1) for c, n in zip(C, exponents)]
    php = 0.5 * action
    scale = H / (php * php)

    def law(phi):
        u = phi / php - 1.0
        v = u * u
        w = v ** (gap // 2)
        p, q = C[-1], D[-1]
        for c, d in zip(C[-2::-1], D[-2::-1]):
            p = p * w + c
            q = q * w + d
        return H * (1.0 + v * p), scale * q
    return law


# --- The generic part: the valve, its events, the time-area integral and the peaks on the grid.

def _inverse_cubic(phi, x):
    """The angle where x = 0, by the cubic through the four (x_j, phi_j) of each row (Lagrange)."""
    out = np.zeros(phi.shape[0])
    for j in range(4):
        weight = phi[:, j].copy()
        for m in range(4):
            if m != j:
                weight *= x[:, m] / (x[:, m] - x[:, j])
        out += weight
    return out


def _cut_cell(f_near, f_far, p, d):
    """int_0^p of the quadratic through (0, 0), (p, f_near), (p + d, f_far)."""
    return f_near * p / 2.0 - p * p * (f_far * p / (p + d) - f_near) / (6.0 * d)


def valve_on_grid(law, phi, d, rocker, lash, k1, k2, want_low=True):
    """One law over a batch of designs: (int f_v dphi over the open period, largest and least h''
    over it; the least only when asked), per design. phi: the designs' grids (cases x G), d: their
    steps (cases x 1)."""
    rows = np.arange(phi.shape[0])
    G = phi.shape[1]
    h, acc = law(phi)
    x = rocker * h - lash
    is_open = x > 0.0
    a = np.argmax(is_open, axis=1)                             # first open point
    b = G - 1 - np.argmax(is_open[:, ::-1], axis=1)            # last open point
    near_a = a[:, None] + np.arange(-1, 3)
    near_b = b[:, None] + np.arange(-2, 2)
    phi_o = _inverse_cubic(phi[rows[:, None], near_a], x[rows[:, None], near_a])
    phi_c = _inverse_cubic(phi[rows[:, None], near_b], x[rows[:, None], near_b])

    xo = np.where(is_open, x, 0.0)
    f = (k1 + k2 * xo) * xo                                    # zero where closed
    sums = np.stack((f[:, 0::2].sum(axis=1), f[:, 1::2].sum(axis=1)), axis=1)
    same, other = sums[rows, a % 2], sums[rows, 1 - a % 2]    # points of a's parity and the others
    fa, fb, fb1, fb2 = f[rows, a], f[rows, b], f[rows, b - 1], f[rows, b - 2]
    step = d[:, 0]
    even = (b - a) % 2 == 0
    simpson_even = step / 3.0 * (4.0 * other + 2.0 * same - fa - fb)
    simpson_odd = step / 3.0 * (4.0 * (other - fb) + 2.0 * same - fa - fb1) + step / 12.0 * (-fb2 + 8.0 * fb1 + 5.0 * fb)
    integral = np.where(even, simpson_even, simpson_odd)
    integral += _cut_cell(fa, f[rows, a + 1], phi[rows, a] - phi_o, step)
    integral += _cut_cell(fb, fb1, phi_c - phi[rows, b], step)

    _, edge = law(np.stack((phi_o, phi_c), axis=1))            # h'' at the opening and closing

    def peak(k, sign):
        y0, ym, yp = acc[rows, k], acc[rows, k - 1], acc[rows, np.minimum(k + 1, G - 1)]
        curvature = ym - 2.0 * y0 + yp
        bent = sign * curvature < 0.0
        s = np.where(bent, (ym - yp) / (2.0 * np.where(bent, curvature, 1.0)), 0.0)
        where = phi[rows, k] + s * step
        inside = bent & (np.abs(s) <= 1.0) & (where >= phi_o) & (where <= phi_c)
        top = np.where(inside, y0 - 0.25 * (ym - yp) * s, y0)
        return sign * np.maximum(sign * top, np.max(sign * edge, axis=1))

    hi = peak(np.argmax(np.where(is_open, acc, -np.inf), axis=1), 1.0)
    lo = peak(np.argmin(np.where(is_open, acc, np.inf), axis=1), -1.0) if want_low else None
    return integral, hi, lo


def study_batch(P, step=STEP):
    """The eight outputs (SI) of a batch of cases (P: every scene parameter as an SI array)."""
    col = lambda name: P[name][:, None]
    H, action, phy, rocker, lash = col("lift"), col("action"), col("accel"), col("rocker"), col("lash")
    w = P["rpm"] / 2.0                                         # camshaft speed, rad/s
    ca, sa = math.cos(SEAT_ANGLE), math.sin(SEAT_ANGLE)
    k1, k2 = math.pi * col("seat") * ca, math.pi * sa * ca * ca
    G = int(math.ceil(float(np.max(P["action"])) / step - 1e-9)) + 1
    phi = action * np.linspace(0.0, 1.0, G)
    d = action / (G - 1)
    out = {}
    for name, law in (("arc", three_arc(H, action, phy)), ("kurz", kurz(H, action, phy)), ("poly", polydyne(H, action))):
        want_low = f"v_{name}.min_acceleration" in OUTPUTS
        integral, hi, lo = valve_on_grid(law, phi, d, rocker, lash, k1, k2, want_low)
        w2i = w * w * P["rocker"]
        out[f"ta_{name}.time_area"] = integral / w
        out[f"v_{name}.max_acceleration"] = w2i * hi
        if want_low:
            out[f"v_{name}.min_acceleration"] = w2i * lo
    return {k: out[k] for k in OUTPUTS}


def study(P, batch=50, step=STEP):
    """The eight outputs over all cases, `batch` cases (3 x batch designs) at a time."""
    n = len(P["lift"])
    parts = [study_batch(slice_table(P, s, s + batch), step) for s in range(0, n, batch)]
    return {k: np.concatenate([p[k] for p in parts]) for k in OUTPUTS}
