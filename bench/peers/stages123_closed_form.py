"""The closed-form peer of the three-cam study (stages 1-3, eight outputs; stages123_cases.py): what
a script reaches that knows each law's closed form, in numpy vectorised over all designs.

Per law (formulas of docs/methods/valvetrain.md, as stages123_grid.py writes them), with the valve
x = i h - lash open where h > h_l = lash / i, the event symmetric about the nose (so every integral
is twice the rising half's):
  * opening angle: exact for the three-arc (1 - cos = 2 sin^2 of the half angle, inverted), Newton
    on the exact lift for the Kurz quarter sine and quarter cosine (monotone convergence from the
    start used), a quadratic in t^2 for its parabola, and Newton from a table for the polydyne;
  * int x dphi and int x^2 dphi over the open period from antiderivatives: of a + b cos t for the
    three-arc's circular arcs, of c1^2 (th - sin th) and its square for the Kurz quarter sine,
    of a + b y - c cos(y/c2) and its square for the quarter cosine, term by term for the Kurz
    parabola (a polynomial in t^2) and the polydyne (P and P^2, polynomials in u);
    time-area = (k1 int x + k2 int x^2) / w_k (f_v = k1 x + k2 x^2, conical seat);
  * acceleration peaks where they are: the three-arc's h'' = e cos psi falls along the flank (largest
    at the opening) and -a cos t is least at the nose; the Kurz h'' rises to A+ at phi_1 and falls
    after it; the polydyne's P'' at u = 0, at the opening or at a root of P''' inside (roots found
    once for the exponents).
"""

import math

import numpy as np

from stages123_cases import OUTPUTS, POLYDYNE_EXPONENTS, SEAT_ANGLE, slice_table
from stages123_grid import kurz_constants, polydyne_coefficients


def _arc_integrals(alpha, beta, t0, t1):
    """int x and int x^2 over [t0, t1] for x = alpha + beta cos t."""
    d = t1 - t0
    ds = np.sin(t1) - np.sin(t0)
    ds2 = 0.25 * (np.sin(2.0 * t1) - np.sin(2.0 * t0))
    return alpha * d + beta * ds, alpha * alpha * d + 2.0 * alpha * beta * ds + beta * beta * (0.5 * d + ds2)


def three_arc(H, php, phy, i, lash):
    """(int x, int x^2, max h'', min h'') over the open period of the three-arc cam (flat tappet)."""
    s = np.sin(php) / np.sin(phy)
    cp = np.cos(php)
    qa = 2.0 * (s - 1.0) * (1.0 - cp)
    qb = -2.0 * H * (s - 1.0 + cp)
    a = (-qb + np.sqrt(qb * qb + 4.0 * qa * H * H)) / (2.0 * qa)
    e = a * (s - 1.0) + H
    hl = lash / i
    on_flank = hl < 2.0 * e * np.sin(0.5 * phy) ** 2
    # Flank: e (1 - cos psi) = hl; nose: H - a (1 - cos t) = hl; 1 - cos y = 2 sin^2(y/2).
    psi_o = 2.0 * np.arcsin(np.sqrt(np.minimum(hl / (2.0 * e), 1.0)))
    t_o = 2.0 * np.arcsin(np.sqrt(np.clip((H - hl) / (2.0 * a), 0.0, 1.0)))
    fx, fxx = _arc_integrals(i * e - lash, -i * e, np.where(on_flank, psi_o, phy), phy)
    fx, fxx = np.where(on_flank, fx, 0.0), np.where(on_flank, fxx, 0.0)
    nx, nxx = _arc_integrals(i * (H - a) - lash, i * a, 0.0, np.where(on_flank, php - phy, t_o))
    top = np.where(on_flank, e * np.cos(psi_o), -a * np.cos(t_o))
    return 2.0 * (fx + nx), 2.0 * (fxx + nxx), top, -a


def _newton(f, x, iterations):
    """Newton's steps; a zero slope (a root at a double zero: no lash) leaves x where it is."""
    for _ in range(iterations):
        value, slope = f(x)
        x = x - np.where(slope != 0.0, value, 0.0) / np.where(slope != 0.0, slope, 1.0)
    return x


def kurz(H, php, phy, i, lash):
    """(int x, int x^2, max h'') over the open period of the Kurz cam."""
    ph1, c1, c2, ap, an, h1, v1 = kurz_constants(H, php, phy)
    ph2, ph3 = phy - ph1, php - phy
    h2 = h1 + v1 * ph2 + ap * c2 * c2                         # lift at phi_y
    hl = lash / i
    # Opening in the quarter sine: c1^2 (th - sin th) = hl / A+; th^3/6 >= th - sin th, so Newton
    # from cbrt(6 g) approaches from above, monotonically (th - sin th is convex and increasing).
    g = hl / (ap * c1 * c1)
    th = _newton(lambda t: (t - np.sin(t) - g, 1.0 - np.cos(t)), np.minimum(np.cbrt(6.0 * g), 0.5 * math.pi), 7)
    psi_o = c1 * th
    if np.any(hl >= h1):
        # In the quarter cosine: h1 + v1 y + A+ c2^2 (1 - cos(y/c2)) = hl, convex and increasing in y:
        # Newton from y = 0 overshoots once, then falls monotonically.
        y = _newton(lambda y: (h1 + v1 * y + 2.0 * ap * c2 * c2 * np.sin(0.5 * y / c2) ** 2 - hl,
                               v1 + ap * c2 * np.sin(y / c2)), np.zeros_like(H), 8)
        # In the parabola: H + A- (s/2 - s^2/(12 phi_3^2)) = hl, s = t^2, the root with s <= phi_3^2.
        c = (H - hl) / (-an)
        P3 = ph3 * ph3
        t_par = np.sqrt(12.0 * P3 * c / (3.0 * P3 + np.sqrt(np.maximum(9.0 * P3 * P3 - 12.0 * P3 * c, 0.0))))
        psi_o = np.where(hl < h1, psi_o, np.where(hl < h2, ph1 + y, php - t_par))
    # Quarter sine over [th0, pi/2], th = psi/c1: int h dpsi = A+ c1^3 [th^2/2 + cos th],
    # int h^2 dpsi = A+^2 c1^5 [th^3/3 - 2 (sin th - th cos th) + th/2 - sin(2 th)/4].
    th0 = np.minimum(psi_o, ph1) / c1
    F1 = lambda t: 0.5 * t * t + np.cos(t)
    F2 = lambda t: t ** 3 / 3.0 - 2.0 * (np.sin(t) - t * np.cos(t)) + 0.5 * t - 0.25 * np.sin(2.0 * t)
    q = 0.5 * math.pi
    sh = ap * c1 ** 3 * (F1(q) - F1(th0))
    shh = ap * ap * c1 ** 5 * (F2(q) - F2(th0))
    sd = ph1 - th0 * c1
    # Quarter cosine over [y0, phi_2]: h = al + v1 y - be cos(y/c2), al = h1 + A+ c2^2, be = A+ c2^2.
    y0 = np.clip(psi_o - ph1, 0.0, ph2)
    al, be = h1 + ap * c2 * c2, ap * c2 * c2

    def cosine_piece(y):
        sn, cs = np.sin(y / c2), np.cos(y / c2)
        lin = al + v1 * y
        ih = al * y + 0.5 * v1 * y * y - be * c2 * sn
        # (al + v1 y)^2 - 2 be (al + v1 y) cos + be^2 cos^2
        ihh = (al * al * y + al * v1 * y * y + v1 * v1 * y ** 3 / 3.0
               - 2.0 * be * (lin * c2 * sn + v1 * c2 * c2 * cs)
               + be * be * (0.5 * y + 0.25 * c2 * np.sin(2.0 * y / c2)))
        return ih, ihh
    ch1, chh1 = cosine_piece(ph2)
    ch0, chh0 = cosine_piece(y0)
    ch, chh, cd = ch1 - ch0, chh1 - chh0, ph2 - y0
    # Parabola, t from the nose over [0, T]: h = H + (A-/2) t^2 - A-/(12 phi_3^2) t^4.
    T = np.minimum(ph3, php - psi_o)
    p0, p2, p4 = H, 0.5 * an, -an / (12.0 * ph3 * ph3)
    T2 = T * T
    ph = T * (p0 + T2 * (p2 / 3.0 + T2 * p4 / 5.0))
    phh = T * (p0 * p0 + T2 * (2.0 * p0 * p2 / 3.0 + T2 * ((p2 * p2 + 2.0 * p0 * p4) / 5.0
                                                             + T2 * (2.0 * p2 * p4 / 7.0 + T2 * p4 * p4 / 9.0))))
    Ih, Ihh, length = sh + ch + ph, shh + chh + phh, sd + cd + T
    Ix = i * Ih - lash * length
    Ixx = i * i * Ihh - 2.0 * i * lash * Ih + lash * lash * length
    tt = (php - psi_o) / ph3
    top = np.where(psi_o <= ph1, ap, np.where(psi_o <= phy, ap * np.cos((psi_o - ph1) / c2), an * (1.0 - tt * tt)))
    return 2.0 * Ix, 2.0 * Ixx, top


class PolydyneTables:
    """What depends on the exponents only: P(u) = 1 + sum C_n u^n, the exponents and coefficients
    of int_0^u P and int_0^u P^2, the roots of P''' in (0, 1) with P'' there, and a table of P to
    start Newton from."""

    def __init__(self, exponents):
        n = np.array(exponents, dtype=float)
        C = np.array(polydyne_coefficients(exponents))
        self.n, self.C = n, C
        self.e1 = np.concatenate(([1.0], n + 1.0))
        self.k1 = np.concatenate(([1.0], C / (n + 1.0)))
        square = {0: 1.0}
        for ci, ni in zip(C, exponents):
            square[ni] = square.get(ni, 0.0) + 2.0 * ci
            for cj, nj in zip(C, exponents):
                square[ni + nj] = square.get(ni + nj, 0.0) + ci * cj
        powers = sorted(square)
        self.e2 = np.array(powers, dtype=float) + 1.0
        self.k2 = np.array([square[p] for p in powers]) / self.e2
        self.d2 = C * n * (n - 1.0)
        d3 = self.d2 * (n - 2.0)
        u = np.linspace(0.0, 1.0, 8193)[1:-1]
        p3 = (u[:, None] ** (n - 3.0)) @ d3
        k = np.nonzero(np.sign(p3[:-1]) != np.sign(p3[1:]))[0]
        r = 0.5 * (u[k] + u[k + 1])
        for _ in range(40):
            r = r - ((r[:, None] ** (n - 3.0)) @ d3) / ((r[:, None] ** (n - 4.0)) @ (d3 * (n - 3.0)))
        self.turns = r
        self.turn_p2 = (r[:, None] ** (n - 2.0)) @ self.d2
        self.u_table = np.linspace(0.0, 1.0, 2049)
        self.p_table = 1.0 + (self.u_table[:, None] ** n) @ C


def polydyne(H, php, i, lash, tables):
    """(int x, int x^2, max h'', min h'') over the open period of the polydyne h = H P(phi/phi_p)."""
    T = tables
    g = lash / (i * H)                                         # P(u_o) = g at the opening
    u = np.interp(g, T.p_table[::-1], T.u_table[::-1])
    for _ in range(4):
        un = u[:, None] ** (T.n - 1.0)
        u = u - (1.0 + (un * u[:, None]) @ T.C - g) / (un @ (T.C * T.n))
    u = np.where(g > 0.0, u, 1.0)       # no lash: open to the event's end (P(1) = P'(1) = 0 there)
    I1 = (u[:, None] ** T.e1) @ T.k1                           # int_0^u P
    I2 = (u[:, None] ** T.e2) @ T.k2                           # int_0^u P^2
    iH = i * H
    Ix = 2.0 * php * (iH * I1 - lash * u)
    Ixx = 2.0 * php * (iH * iH * I2 - 2.0 * iH * lash * I1 + lash * lash * u)
    at_open = (u[:, None] ** (T.n - 2.0)) @ T.d2
    inside = T.turns[None, :] < u[:, None]
    hi = np.maximum(np.maximum(T.d2[0], at_open), np.max(np.where(inside, T.turn_p2, -np.inf), axis=1, initial=-np.inf))
    lo = np.minimum(np.minimum(T.d2[0], at_open), np.min(np.where(inside, T.turn_p2, np.inf), axis=1, initial=np.inf))
    scale = H / (php * php)
    return Ix, Ixx, scale * hi, scale * lo


def study_batch(P, tables):
    H, php, phy, i, lash = P["lift"], 0.5 * P["action"], P["accel"], P["rocker"], P["lash"]
    w = 0.5 * P["rpm"]
    ca, sa = math.cos(SEAT_ANGLE), math.sin(SEAT_ANGLE)
    k1, k2 = math.pi * P["seat"] * ca, math.pi * sa * ca * ca
    ax, axx, a_hi, a_lo = three_arc(H, php, phy, i, lash)
    kx, kxx, k_hi = kurz(H, php, phy, i, lash)
    px, pxx, p_hi, p_lo = polydyne(H, php, i, lash, tables)
    w2i = w * w * i
    out = {"ta_arc.time_area": (k1 * ax + k2 * axx) / w, "ta_kurz.time_area": (k1 * kx + k2 * kxx) / w,
           "ta_poly.time_area": (k1 * px + k2 * pxx) / w, "v_arc.max_acceleration": w2i * a_hi,
           "v_kurz.max_acceleration": w2i * k_hi, "v_poly.max_acceleration": w2i * p_hi,
           "v_arc.min_acceleration": w2i * a_lo, "v_poly.min_acceleration": w2i * p_lo}
    return {k: out[k] for k in OUTPUTS}


def study(P, batch=4096, tables=None):
    """The eight outputs over all cases, `batch` cases at a time (the temporaries stay in cache)."""
    tables = tables or PolydyneTables(POLYDYNE_EXPONENTS)
    n = len(P["lift"])
    parts = [study_batch(slice_table(P, s, s + batch), tables) for s in range(0, n, batch)]
    return {k: np.concatenate([p[k] for p in parts]) for k in OUTPUTS}
