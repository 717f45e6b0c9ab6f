#pragma once
// A three-arc law from its constants alone (docs/methods/valvetrain.md, stage 1; the contour and
// the followers as three_arc.hpp states them): a point, the monotone runs and the lift integrals.
// ThreeArcLaw answers through these functions, and so could a family of three-arc laws over arrays
// of cases: one implementation for both, so that each case would give exactly the bits of its
// scalar law (docs/design/sdk-1.6-laws-over-arrays.md, step 1).
#include <mechgraph/domain/cam_law.hpp>

#include <cmath>
#include <vector>

namespace mechgraph::cams {

/// What a point of one three-arc law needs, in SI (m, rad): plain numbers, so that a column of
/// cases can hold them.
struct ThreeArcConstants {
  double half_action = 0.0;    // phi_p
  double max_lift = 0.0;       // h_max
  double base_radius = 0.0;    // r0
  double nose_radius = 0.0;    // r2
  double nose_centre = 0.0;    // a = r0 + h_max - r2
  double flank_centre = 0.0;   // e = r1 - r0
  double roller_radius = 0.0;  // rr; 0 for a flat-faced tappet
  double switch_angle = 0.0;   // |phi| where the follower passes from flank to nose (alpha flat, beta roller)
};

namespace three_arc_detail {

// The roller centre on an offset arc of radius R whose centre is c from the cam centre, at angle
// t: s = +-c cos t + g, g = sqrt(q), q = R^2 - c^2 sin^2 t. Returns R - g = c^2 sin^2 t / (R + g)
// (no cancellation) and the first three derivatives of g over t, from those of q:
// g1 = q1/2g, g2 = q2/2g - q1^2/4gq, g3 = q3/2g - 3 q1 q2/4gq + 3 q1^3/8gq^2.
struct ArcRoot {
  double excess, d1, d2, d3;
};
inline ArcRoot arc_root(double c, double R, double t) {
  const double c2 = c * c, st = std::sin(t);
  const double q = R * R - c2 * st * st;
  const double g = std::sqrt(q);
  const double sin2 = std::sin(2.0 * t), cos2 = std::cos(2.0 * t);
  const double q1 = -c2 * sin2, q2 = -2.0 * c2 * cos2, q3 = 4.0 * c2 * sin2;
  return {c2 * st * st / (R + g), q1 / (2.0 * g), q2 / (2.0 * g) - q1 * q1 / (4.0 * g * q),
          q3 / (2.0 * g) - 3.0 * q1 * q2 / (4.0 * g * q) + 3.0 * q1 * q1 * q1 / (8.0 * g * q * q)};
}

}  // namespace three_arc_detail

/// Lift and three derivatives over cam angle at phi inside the event (-phi_p < phi < phi_p).
/// Inlined into each caller, so that a point costs one call.
[[gnu::always_inline]] inline LiftDerivatives three_arc_point(const ThreeArcConstants& k, double phi) {
  // Work in psi = |phi| (from the nose); h is even in phi, h' and h''' odd.
  const double psi = std::abs(phi);
  const double sign = phi < 0.0 ? -1.0 : 1.0;
  const double a = k.nose_centre, e = k.flank_centre, rr = k.roller_radius;
  double H = 0.0, H1 = 0.0, H2 = 0.0, H3 = 0.0;  // derivatives over psi
  if (psi <= k.switch_angle) {
    const double t = psi;
    double st, ct;
    ::sincos(t, &st, &ct);
    const double omc = ct >= 0.0 ? st * st / (1.0 + ct) : 1.0 - ct;  // 1 - cos t without cancellation
    if (rr <= 0.0) {
      // Flat tappet on the nose arc: h = a cos t - (r0 - r2) = h_max - a (1 - cos t).
      H = k.max_lift - a * omc;
      H1 = -a * st;
      H2 = -a * ct;
      H3 = a * st;
    } else {
      // Roller centre on the pitch nose arc (centre distance a, radius R2 = r2 + rr, theta = t):
      // s = a cos t + sqrt(R2^2 - a^2 sin^2 t); h = s - (r0 + rr), and a + R2 = r0 + rr + h_max, so
      // h = h_max - a (1 - cos t) - a^2 sin^2 t / (R2 + sqrt(...)).
      const three_arc_detail::ArcRoot r = three_arc_detail::arc_root(a, k.nose_radius + rr, t);
      H = k.max_lift - a * omc - r.excess;
      H1 = -a * st + r.d1;
      H2 = -a * ct + r.d2;
      H3 = a * st + r.d3;
    }
  } else {
    // Flank, x = phi_p - psi from the start of lift: d/dpsi = -d/dx.
    const double x = k.half_action - psi;
    double sx, cx;
    ::sincos(x, &sx, &cx);
    const double omc = cx >= 0.0 ? sx * sx / (1.0 + cx) : 1.0 - cx;  // 1 - cos x without cancellation
    double F = 0.0, F1 = 0.0, F2 = 0.0, F3 = 0.0;  // derivatives over x
    if (rr <= 0.0) {
      // Flat tappet on the flank arc: h = e (1 - cos x).
      F = e * omc;
      F1 = e * sx;
      F2 = e * cx;
      F3 = -e * sx;
    } else {
      // Roller centre on the pitch flank arc (centre distance e, radius R1 = r1 + rr = e + c0,
      // c0 = r0 + rr, the centre opposite the follower): s = sqrt(R1^2 - e^2 sin^2 x) - e cos x.
      // Near the largest nose radius e is many times c0 and that difference cancels (and so do its
      // derivatives, e cos x against e^2 terms). Without cancellation: with u = e cos x and
      // g = sqrt(u^2 + c0 (2e + c0)), s = c0 (2e + c0) / (g + u), so (ln s)' = w = e sin x / g,
      //   s' = s w,  s'' = s (w^2 + w'),  s''' = s (w^3 + 3 w w' + w''),
      //   w' = u R1^2 / g^3,  w'' = R1^2 e sin x (3 u^2 - g^2) / g^5   (g^2 + e^2 sin^2 x = R1^2);
      // and h = s - c0 = c0 [e (1 - cos x) + e^2 sin^2 x / (R1 + g)] / (g + u).
      const double c0 = k.base_radius + rr, R1 = e + c0;
      const double u = e * cx, n = c0 * (2.0 * e + c0);
      const double g = std::sqrt(u * u + n);
      const double D = u >= 0.0 ? g + u : n / (g - u);  // g + u without cancellation when u < 0
      const double S = n / D;
      const double w = e * sx / g, g2 = g * g, g3 = g2 * g;
      const double w1 = u * R1 * R1 / g3, w2 = R1 * R1 * e * sx * (3.0 * u * u - g2) / (g3 * g2);
      F = c0 * (e * omc + e * e * sx * sx / (R1 + g)) / D;
      F1 = S * w;
      F2 = S * (w * w + w1);
      F3 = S * (w * w * w + 3.0 * w * w1 + w2);
    }
    H = F;
    H1 = -F1;
    H2 = F2;
    H3 = -F3;
  }
  return {H, sign * H1, H2, sign * H3};
}

/// CamLaw::monotone_breaks of the law. Flat tappet: the flank/nose switches and the nose (plus
/// 90 deg into a long flank for the velocity). A roller: false (the generic search).
bool three_arc_monotone_breaks(const ThreeArcConstants& k, int order, std::vector<double>& breaks);

/// CamLaw::lift_integrals of the law. Flat tappet: the integrals of h and h^2 in closed form (arcs:
/// x - sin x and its square's). A roller: false (quadrature).
bool three_arc_lift_integrals(const ThreeArcConstants& k, double a, double b, double& integral, double& integral_of_square);

}  // namespace mechgraph::cams
