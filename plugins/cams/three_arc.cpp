#include "three_arc.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <memory>
#include <numbers>
#include <sstream>
#include <string>

namespace mechgraph::cams {
namespace {

constexpr double pi = std::numbers::pi;

std::string deg(double rad) {
  std::ostringstream s;
  s << std::setprecision(4) << rad * 180.0 / pi << " deg";
  return s.str();
}

std::string mm(double m) {
  std::ostringstream s;
  s << std::setprecision(4) << m * 1e3 << " mm";
  return s.str();
}

// The roller centre on an offset arc of radius R whose centre is c from the cam centre, at angle
// t: s = +-c cos t + g, g = sqrt(q), q = R^2 - c^2 sin^2 t. Returns R - g = c^2 sin^2 t / (R + g)
// (no cancellation) and the first three derivatives of g over t, from those of q:
// g1 = q1/2g, g2 = q2/2g - q1^2/4gq, g3 = q3/2g - 3 q1 q2/4gq + 3 q1^3/8gq^2.
struct ArcRoot {
  double excess, d1, d2, d3;
};
ArcRoot arc_root(double c, double R, double t) {
  const double c2 = c * c, st = std::sin(t);
  const double q = R * R - c2 * st * st;
  const double g = std::sqrt(q);
  const double sin2 = std::sin(2.0 * t), cos2 = std::cos(2.0 * t);
  const double q1 = -c2 * sin2, q2 = -2.0 * c2 * cos2, q3 = 4.0 * c2 * sin2;
  return {c2 * st * st / (R + g), q1 / (2.0 * g), q2 / (2.0 * g) - q1 * q1 / (4.0 * g * q),
          q3 / (2.0 * g) - 3.0 * q1 * q2 / (4.0 * g * q) + 3.0 * q1 * q1 * q1 / (8.0 * g * q * q)};
}

// Completes the geometry from h, phi_p, r0, r2 (so a) and e, and checks the tangency closes.
ThreeArcGeometry complete(const CamBasics& b, double r2, double e, const char* parameter) {
  ThreeArcGeometry g;
  g.max_lift = b.max_lift;
  g.half_action = 0.5 * b.action_angle;
  g.base_radius = b.base_radius;
  g.nose_radius = r2;
  g.nose_centre = b.base_radius + b.max_lift - r2;
  g.flank_centre = e;
  g.flank_radius = b.base_radius + e;
  // Direction of the common normal N - F = (a + e cos phi_p, e sin phi_p), from the nose.
  g.junction_normal = std::atan2(e * std::sin(g.half_action), g.nose_centre + e * std::cos(g.half_action));
  g.flank_angle = g.half_action - g.junction_normal;
  // Each closing condition on its own, so the message names the one that failed (the stream is
  // made only then: a sweep makes a contour per case).
  const bool closes = std::isfinite(g.flank_radius) && e > 0.0 && g.nose_centre > 0.0 && g.flank_radius > g.nose_radius &&
                      g.flank_angle > 0.0 && g.junction_normal > 0.0 && !(g.junction_normal > 0.5 * pi);
  if (closes) return g;
  std::ostringstream msg;
  if (!std::isfinite(g.flank_radius) || !(e > 0.0))
    msg << "the flank radius " << mm(g.flank_radius) << " must be finite and larger than the base radius";
  else if (!(g.nose_centre > 0.0))
    msg << "the nose-centre distance a = r0 + h - r2 = " << mm(g.nose_centre) << " must be > 0";
  else if (!(g.flank_radius > g.nose_radius))
    msg << "the flank radius " << mm(g.flank_radius) << " must exceed the nose radius " << mm(r2);
  else if (!(g.flank_angle > 0.0) || !(g.junction_normal > 0.0))
    msg << "the flank/nose junction falls outside the half action angle (flank angle " << deg(g.flank_angle)
        << ", nose angle " << deg(g.junction_normal) << ")";
  else if (g.junction_normal > 0.5 * pi)
    // On the nose arc h'' = -a cos t: beyond t = 90 deg from the nose it turns positive, and the
    // positive-acceleration phase would no longer be the flank angle.
    msg << "the nose arc would span " << deg(g.junction_normal)
        << " from the nose, past 90 deg where its acceleration turns positive; the flank angle must be at least "
           "half the action angle minus 90 deg ("
        << deg(g.half_action - 0.5 * pi) << ")";
  if (!msg.str().empty()) throw NodeError(parameter, "the three-arc contour does not close: " + msg.str());
  return g;
}

}  // namespace

ThreeArcGeometry three_arc_from_accel_angle(const CamBasics& b, double phi_y) {
  const double h = b.max_lift, r0 = b.base_radius;
  const double phi_p = 0.5 * b.action_angle;
  const double c = std::cos(phi_p), sp = std::sin(phi_p);
  // s = sin(phi_p)/sin(phi_y) must exceed 1 with an acute phi_y (flank acceleration e cos x > 0):
  // phi_y < phi_p, and phi_y < 180 deg - phi_p when the half action angle is obtuse.
  const double phi_y_max = phi_p <= 0.5 * pi ? phi_p : pi - phi_p;
  if (!(phi_y > 0.0) || !(phi_y < phi_y_max)) {
    std::ostringstream msg;
    msg << "accel_angle = " << deg(phi_y) << " must be > 0 and below "
        << (phi_p <= 0.5 * pi ? "half the action angle (" : "180 deg minus half the action angle (")
        << deg(phi_y_max) << ")";
    throw NodeError("accel_angle", msg.str());
  }
  const double s = sp / std::sin(phi_y);
  // valvetrain.md: A a^2 + B a + C = 0, the positive root; the form without cancellation.
  const double A = 2.0 * (s - 1.0) * (1.0 - c);
  const double B = -2.0 * h * (s - 1.0 + c);
  const double C = -h * h;
  const double disc = B * B - 4.0 * A * C;
  if (!(A > 0.0) || !(disc >= 0.0) || !std::isfinite(disc)) {
    std::ostringstream msg;
    msg << "accel_angle = " << deg(phi_y) << " gives no real nose-centre distance (A = " << A
        << ", discriminant = " << disc << "); choose accel_angle further inside (0, " << deg(phi_y_max) << ")";
    throw NodeError("accel_angle", msg.str());
  }
  const double root = std::sqrt(disc);
  const double a = B <= 0.0 ? (-B + root) / (2.0 * A) : 2.0 * h * h / (B + root);
  const double r2 = r0 + h - a;
  if (!(r2 > 0.0)) {
    // r2 = 0 means a = r0 + h; then the quadratic is linear in (s - 1):
    // (s - 1) 2 a ((1 - c) a - h) = h^2 + 2 h a c, one crossing at most.
    const double a0 = r0 + h;
    const double K = 2.0 * a0 * ((1.0 - c) * a0 - h);
    const double sm1 = K != 0.0 ? (h * h + 2.0 * h * a0 * c) / K : -1.0;
    std::ostringstream msg;
    msg << "accel_angle = " << deg(phi_y) << " gives nose_radius = " << mm(r2) << "; it must be > 0: ";
    if (sm1 > 0.0 && std::isfinite(sm1)) {
      const double limit = std::asin(sp / (1.0 + sm1));
      msg << "choose accel_angle " << (phi_y > limit ? "below " : "above ") << deg(limit);
    } else {
      msg << "no accel_angle below " << deg(phi_y_max)
          << " gives a positive nose radius with this max_lift, action_angle and base_radius";
    }
    throw NodeError("accel_angle", msg.str());
  }
  const double e = a * (s - 1.0) + h;  // r1 - r0
  return complete(b, r2, e, "accel_angle");
}

ThreeArcGeometry three_arc_from_nose_radius(const CamBasics& b, double r2) {
  const double h = b.max_lift, r0 = b.base_radius;
  const double phi_p = 0.5 * b.action_angle;
  const double c = std::cos(phi_p);
  // The flank radius grows without bound as r2 -> r2_max = r0 - h cos(phi_p)/(1 - cos(phi_p))
  // (the zero of the denominator below); beyond it no contour closes.
  const double r2_max = r0 - h * c / (1.0 - c);
  if (!(r2 > 0.0) || !(r2 < r2_max)) {
    std::ostringstream msg;
    msg << "nose_radius = " << mm(r2) << " is infeasible: it must be > 0 and below " << mm(r2_max)
        << " (= r0 - h cos(phi_p)/(1 - cos(phi_p)), where the flank radius becomes infinite)";
    if (!(r2_max > 0.0)) msg << "; no nose radius works: increase base_radius or action_angle";
    throw NodeError("nose_radius", msg.str());
  }
  // Tangency with a = r0 + h - r2, b = r0 - r2 (a - b = h) is linear in e:
  // e = (a^2 - b^2) / (2 (b - a c)) = h (a + b) / (2 (b - a c)).
  const double a = r0 + h - r2, bb = r0 - r2;
  const double e = h * (a + bb) / (2.0 * (bb - a * c));
  return complete(b, r2, e, "nose_radius");
}

ThreeArcLaw::ThreeArcLaw(const ThreeArcGeometry& geometry, double roller_radius)
    : g_(geometry), roller_radius_(roller_radius) {
  if (roller_radius_ <= 0.0) {
    switch_angle_ = g_.junction_normal;
    return;
  }
  // Roller: the pitch-curve junction N + (r2 + rr) n_alpha, seen from O.
  const double R2 = g_.nose_radius + roller_radius_;
  const double px = g_.nose_centre + R2 * std::cos(g_.junction_normal);
  const double py = R2 * std::sin(g_.junction_normal);
  switch_angle_ = std::atan2(py, px);
  const double sb = std::sin(switch_angle_);
  if (!(R2 * R2 - g_.nose_centre * g_.nose_centre * sb * sb > 0.0) || !(switch_angle_ > 0.0)) {
    throw NodeError("roller_radius", "the roller pitch curve of this three-arc cam has no nose contact (roller_radius = " +
                                         mm(roller_radius_) + ")");
  }
}

bool ThreeArcLaw::monotone_breaks(int order, std::vector<double>& breaks) const {
  // Flat tappet only (the roller's pitch-curve lift has no such simple signs). On the flank
  // h = e (1 - cos x), x = phi_p - |phi| in [0, phi_1], phi_1 < phi_p < pi: h' ~ sin x and
  // h''' ~ sin x keep their signs, h'' = e cos x changes sign at x = 90 deg if the flank reaches
  // it. On the nose h = a cos t - (r0 - r2), t = |phi| <= alpha <= 90 deg (checked at
  // construction): h' ~ sin t, h'' = -a cos t, h''' ~ sin t change sign at the nose only.
  // The lift itself (order 0) rises on the whole rise and falls on the whole return: h' changes
  // sign at the nose only, so the nose is its one cut.
  if (roller_radius_ > 0.0 || order < 0 || order > 2) return false;
  if (order == 0) {
    breaks = {0.0};
    return true;
  }
  const double alpha = switch_angle_;
  breaks = {-alpha, 0.0, alpha};
  if (order == 1 && g_.flank_angle > 0.5 * std::numbers::pi) {
    const double quarter = g_.half_action - 0.5 * std::numbers::pi;  // |phi| where x = 90 deg
    breaks = {-quarter, -alpha, 0.0, alpha, quarter};
  }
  return true;
}

namespace {

// Integrals from 0 to X of m = 1 - cos x and of m^2 (valvetrain.md, stage 3 in closed form):
//   int m = X - sin X,   int m^2 = 3X/2 - 2 sin X + sin(2X)/4.
// Both cancel for small X (they go as X^3/6 and X^5/20); below X = 1 they are summed as their
// Taylor series instead, from the series of sin X and sin 2X:
//   X - sin X   = sum_{k>=1} (-1)^(k+1) X^(2k+1) / (2k+1)!
//   int m^2     = sum_{k>=2} (-1)^k (2^(2k-1) - 2) X^(2k+1) / (2k+1)!
// (at X = 1 the 12th terms are below 1e-19 of the first).
struct ArcIntegrals {
  double m, m2;
};
ArcIntegrals arc_integrals(double X) {
  if (std::abs(X) >= 1.0) {
    const double s = std::sin(X);
    return {X - s, 1.5 * X - 2.0 * s + 0.25 * std::sin(2.0 * X)};
  }
  double m = 0.0, m2 = 0.0;
  double term = X;          // X^(2k+1) / (2k+1)!
  double four_power = 0.5;  // 2^(2k-1)
  for (int k = 1; k <= 14; ++k) {
    term *= X * X / ((2.0 * k) * (2.0 * k + 1.0));
    four_power *= 4.0;
    const double sign = k % 2 == 0 ? 1.0 : -1.0;
    m -= sign * term;
    if (k >= 2) m2 += sign * (four_power - 2.0) * term;
  }
  return {m, m2};
}

}  // namespace

bool ThreeArcLaw::lift_integrals(double a, double b, double& integral, double& integral_of_square) const {
  // Flat tappet: flank h = e m(x), x = phi_p - |phi|; nose h = H - A m(t), t = |phi| (A the
  // nose-centre distance). P(phi) = the integrals from the start of lift to phi, piece by piece;
  // the answer is P(b) - P(a).
  if (roller_radius_ > 0.0) return false;
  const double e = g_.flank_centre, A = g_.nose_centre, H = g_.max_lift, alpha = switch_angle_;
  const double x1 = g_.half_action - alpha;  // the flank's span
  auto flank = [&](double x, double& p1, double& p2) {
    const ArcIntegrals m = arc_integrals(x);
    p1 = e * m.m;
    p2 = e * e * m.m2;
  };
  auto nose = [&](double t, double& p1, double& p2) {  // from the nose out to t
    const ArcIntegrals m = arc_integrals(t);
    p1 = H * t - A * m.m;
    p2 = H * H * t - 2.0 * H * A * m.m + A * A * m.m2;
  };
  double f1, f2, n1, n2;
  flank(x1, f1, f2);
  nose(alpha, n1, n2);
  auto P = [&](double phi, double& p1, double& p2) {
    double q1, q2;
    if (phi <= -alpha) {
      flank(g_.half_action + phi, p1, p2);
    } else if (phi <= 0.0) {
      nose(-phi, q1, q2);
      p1 = f1 + n1 - q1;
      p2 = f2 + n2 - q2;
    } else if (phi <= alpha) {
      nose(phi, q1, q2);
      p1 = f1 + n1 + q1;
      p2 = f2 + n2 + q2;
    } else {
      flank(g_.half_action - phi, q1, q2);
      p1 = 2.0 * (f1 + n1) - q1;
      p2 = 2.0 * (f2 + n2) - q2;
    }
  };
  double pa1, pa2, pb1, pb2;
  P(std::clamp(a, -g_.half_action, g_.half_action), pa1, pa2);
  P(std::clamp(b, -g_.half_action, g_.half_action), pb1, pb2);
  integral = pb1 - pa1;
  integral_of_square = pb2 - pa2;
  return true;
}

LiftDerivatives ThreeArcLaw::evaluate_in_event(double phi) const {
  // Work in psi = |phi| (from the nose); h is even in phi, h' and h''' odd.
  const double psi = std::abs(phi);
  const double sign = phi < 0.0 ? -1.0 : 1.0;
  const double a = g_.nose_centre, e = g_.flank_centre, rr = roller_radius_;
  double H = 0.0, H1 = 0.0, H2 = 0.0, H3 = 0.0;  // derivatives over psi
  if (psi <= switch_angle_) {
    const double t = psi;
    double st, ct;
    ::sincos(t, &st, &ct);
    const double omc = ct >= 0.0 ? st * st / (1.0 + ct) : 1.0 - ct;  // 1 - cos t without cancellation
    if (rr <= 0.0) {
      // Flat tappet on the nose arc: h = a cos t - (r0 - r2) = h_max - a (1 - cos t).
      H = g_.max_lift - a * omc;
      H1 = -a * st;
      H2 = -a * ct;
      H3 = a * st;
    } else {
      // Roller centre on the pitch nose arc (centre distance a, radius R2 = r2 + rr, theta = t):
      // s = a cos t + sqrt(R2^2 - a^2 sin^2 t); h = s - (r0 + rr), and a + R2 = r0 + rr + h_max, so
      // h = h_max - a (1 - cos t) - a^2 sin^2 t / (R2 + sqrt(...)).
      const ArcRoot r = arc_root(a, g_.nose_radius + rr, t);
      H = g_.max_lift - a * omc - r.excess;
      H1 = -a * st + r.d1;
      H2 = -a * ct + r.d2;
      H3 = a * st + r.d3;
    }
  } else {
    // Flank, x = phi_p - psi from the start of lift: d/dpsi = -d/dx.
    const double x = g_.half_action - psi;
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
      const double c0 = g_.base_radius + rr, R1 = e + c0;
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

namespace {

// What the parameters choose, the same for every case of a block: the design by accel_angle or by
// nose_radius (exactly one given), and a flat or roller follower (roller_radius given with it alone).
struct ThreeArcChoice {
  bool by_accel_angle = false;
  bool roller = false;
};

ThreeArcChoice three_arc_choice(const ParamSet& params) {
  const bool has_accel = params.has("accel_angle");
  const bool has_nose = params.has("nose_radius");
  if (has_accel == has_nose) {
    throw NodeError("accel_angle", std::string("give exactly one of accel_angle and nose_radius (") +
                                       (has_accel ? "both are set" : "neither is set") + ")");
  }
  const bool is_roller = params.has("follower") && params.text("follower") == "roller";
  if (is_roller && !params.has("roller_radius")) throw NodeError("roller_radius", "follower = roller needs roller_radius");
  if (!is_roller && params.has("roller_radius"))
    throw NodeError("roller_radius", "roller_radius is set but follower is flat: set follower: roller or remove it");
  return {has_accel, is_roller};
}

// The law of the choice, its accel_angle or nose_radius `shape` and its roller radius (0: flat).
std::shared_ptr<const CamLaw> make_three_arc(const CamBasics& basics, const ThreeArcChoice& c, double shape, double roller,
                                             OutputSet& extra) {
  if (c.roller && !(roller > 0.0)) throw NodeError("roller_radius", "roller_radius = " + mm(roller) + " must be > 0");
  const ThreeArcGeometry g = c.by_accel_angle ? three_arc_from_accel_angle(basics, shape) : three_arc_from_nose_radius(basics, shape);
  extra.set_scalar("flank_radius", g.flank_radius);
  extra.set_scalar("nose_radius", g.nose_radius);
  return std::make_shared<const ThreeArcLaw>(g, roller);
}

}  // namespace

CamLawDefinition three_arc_definition() {
  CamLawDefinition d;
  d.type = "cam.three_arc";
  d.version = 1;
  d.summary =
      "Three-arc convex cam (base circle, flank arcs, nose arc) with a flat or in-line roller tappet; "
      "exact lift; not shockless (the acceleration jumps at the start of lift and at the flank/nose switch)";
  d.params = {
      ParamSpec::number("accel_angle", dim::angle,
                        "flank angle phi_1 from the start of lift, which is the positive-acceleration phase of a "
                        "flat tappet (a roller reaches the nose arc later: its achieved phase is the accel_angle "
                        "output); the radii follow in closed form. Give exactly one of accel_angle and nose_radius",
                        "deg")
          .optional()
          .at_least(2.0 * min_start_of_lift_ulp)
          .because(">= 2 x 2^-63 rad: the flank arc must hold a double angle of its own, two ulps of the start of lift at the smallest action angle (0.05 deg from the nose)")
          .with_example(30.0 * std::numbers::pi / 180.0),
      ParamSpec::number("nose_radius", dim::length,
                        "nose-arc radius r2 of the contour; the flank radius and angle follow in closed form. Give "
                        "exactly one of accel_angle and nose_radius",
                        "mm")
          .optional()
          .positive()
          .because("> 0: a radius (its upper limit, where the flank arcs vanish, follows from the design and is checked with it)"),
      ParamSpec::choice("follower", {"flat", "roller"},
                        "flat-faced tappet, or in-line roller (the lift is that of the roller centre on the offset "
                        "contour)")
          .with_default(std::string("flat")),
      ParamSpec::number("roller_radius", dim::length, "roller radius, required for follower = roller", "mm")
          .optional()
          .positive()
          .because("> 0: a radius"),
  };
  d.extra_outputs = {
      PortSpec::scalar("flank_radius", dim::length, "flank-arc radius r1 of the contour", "mm"),
      PortSpec::scalar("nose_radius", dim::length, "nose-arc radius r2 of the contour", "mm"),
  };
  d.make = [](const CamBasics& basics, const ParamSet& params, OutputSet& extra) -> std::shared_ptr<const CamLaw> {
    const ThreeArcChoice c = three_arc_choice(params);
    return make_three_arc(basics, c, params.number(c.by_accel_angle ? "accel_angle" : "nose_radius"),
                          c.roller ? params.number("roller_radius") : 0.0, extra);
  };
  // A block: which parameters are given and the follower (the same for every case) read once; each
  // case reads its accel_angle or nose_radius and roller radius from the columns.
  d.prepare_block = [](const BlockParams& p) -> CamLawCaseFactory {
    const ThreeArcChoice c = three_arc_choice(p.fixed());
    const BlockColumn shape = p.number(c.by_accel_angle ? "accel_angle" : "nose_radius");
    const BlockColumn roller = c.roller ? p.number("roller_radius") : BlockColumn{};
    return [c, shape, roller](const CamBasics& basics, const ParamSet&, std::size_t k,
                              OutputSet& extra) -> std::shared_ptr<const CamLaw> {
      return make_three_arc(basics, c, shape[k], c.roller ? roller[k] : 0.0, extra);
    };
  };
  return d;
}

}  // namespace mechgraph::cams
