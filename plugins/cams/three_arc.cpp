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

ThreeArcConstants three_arc_constants(const ThreeArcGeometry& g, double roller_radius) {
  ThreeArcConstants k;
  k.half_action = g.half_action;
  k.max_lift = g.max_lift;
  k.base_radius = g.base_radius;
  k.nose_radius = g.nose_radius;
  k.nose_centre = g.nose_centre;
  k.flank_centre = g.flank_centre;
  k.roller_radius = roller_radius;
  if (roller_radius <= 0.0) {
    k.switch_angle = g.junction_normal;
    return k;
  }
  // Roller: the pitch-curve junction N + (r2 + rr) n_alpha, seen from O.
  const double R2 = g.nose_radius + roller_radius;
  const double px = g.nose_centre + R2 * std::cos(g.junction_normal);
  const double py = R2 * std::sin(g.junction_normal);
  k.switch_angle = std::atan2(py, px);
  const double sb = std::sin(k.switch_angle);
  if (!(R2 * R2 - g.nose_centre * g.nose_centre * sb * sb > 0.0) || !(k.switch_angle > 0.0)) {
    throw NodeError("roller_radius", "the roller pitch curve of this three-arc cam has no nose contact (roller_radius = " +
                                         mm(roller_radius) + ")");
  }
  return k;
}

ThreeArcLaw::ThreeArcLaw(const ThreeArcGeometry& geometry, double roller_radius)
    : g_(geometry), constants_(three_arc_constants(geometry, roller_radius)) {}

bool three_arc_monotone_breaks(const ThreeArcConstants& k, int order, std::vector<double>& breaks) {
  // Flat tappet only (the roller's pitch-curve lift has no such simple signs). On the flank
  // h = e (1 - cos x), x = phi_p - |phi| in [0, phi_1], phi_1 < phi_p < pi: h' ~ sin x and
  // h''' ~ sin x keep their signs, h'' = e cos x changes sign at x = 90 deg if the flank reaches
  // it. On the nose h = a cos t - (r0 - r2), t = |phi| <= alpha <= 90 deg (checked at
  // construction): h' ~ sin t, h'' = -a cos t, h''' ~ sin t change sign at the nose only.
  // The lift itself (order 0) rises on the whole rise and falls on the whole return: h' changes
  // sign at the nose only, so the nose is its one cut.
  if (k.roller_radius > 0.0 || order < 0 || order > 2) return false;
  if (order == 0) {
    breaks = {0.0};
    return true;
  }
  const double alpha = k.switch_angle;
  breaks = {-alpha, 0.0, alpha};
  const double flank_angle = k.half_action - alpha;  // phi_1 (the flat tappet switches at alpha)
  if (order == 1 && flank_angle > 0.5 * std::numbers::pi) {
    const double quarter = k.half_action - 0.5 * std::numbers::pi;  // |phi| where x = 90 deg
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

bool three_arc_lift_integrals(const ThreeArcConstants& k, double a, double b, double& integral, double& integral_of_square) {
  // Flat tappet: flank h = e m(x), x = phi_p - |phi|; nose h = H - A m(t), t = |phi| (A the
  // nose-centre distance). P(phi) = the integrals from the start of lift to phi, piece by piece;
  // the answer is P(b) - P(a).
  if (k.roller_radius > 0.0) return false;
  const double e = k.flank_centre, A = k.nose_centre, H = k.max_lift, alpha = k.switch_angle;
  const double x1 = k.half_action - alpha;  // the flank's span
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
      flank(k.half_action + phi, p1, p2);
    } else if (phi <= 0.0) {
      nose(-phi, q1, q2);
      p1 = f1 + n1 - q1;
      p2 = f2 + n2 - q2;
    } else if (phi <= alpha) {
      nose(phi, q1, q2);
      p1 = f1 + n1 + q1;
      p2 = f2 + n2 + q2;
    } else {
      flank(k.half_action - phi, q1, q2);
      p1 = 2.0 * (f1 + n1) - q1;
      p2 = 2.0 * (f2 + n2) - q2;
    }
  };
  double pa1, pa2, pb1, pb2;
  P(std::clamp(a, -k.half_action, k.half_action), pa1, pa2);
  P(std::clamp(b, -k.half_action, k.half_action), pb1, pb2);
  integral = pb1 - pa1;
  integral_of_square = pb2 - pa2;
  return true;
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

// The geometry of the choice, its accel_angle or nose_radius `shape` and its roller radius (0:
// flat), with its extra outputs set.
ThreeArcGeometry three_arc_geometry(const CamBasics& basics, const ThreeArcChoice& c, double shape, double roller,
                                    OutputSet& extra) {
  if (c.roller && !(roller > 0.0)) throw NodeError("roller_radius", "roller_radius = " + mm(roller) + " must be > 0");
  const ThreeArcGeometry g = c.by_accel_angle ? three_arc_from_accel_angle(basics, shape) : three_arc_from_nose_radius(basics, shape);
  extra.set_scalar("flank_radius", g.flank_radius);
  extra.set_scalar("nose_radius", g.nose_radius);
  return g;
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
    const double roller = c.roller ? params.number("roller_radius") : 0.0;
    const ThreeArcGeometry g =
        three_arc_geometry(basics, c, params.number(c.by_accel_angle ? "accel_angle" : "nose_radius"), roller, extra);
    return std::make_shared<const ThreeArcLaw>(g, roller);
  };
  // A block: which parameters are given and the follower (the same for every case) read once; each
  // case reads its accel_angle or nose_radius and roller radius from the columns.
  d.prepare_block = [](const BlockParams& p) -> CamLawCaseFactory {
    const ThreeArcChoice c = three_arc_choice(p.fixed());
    const BlockColumn shape = p.number(c.by_accel_angle ? "accel_angle" : "nose_radius");
    const BlockColumn roller = c.roller ? p.number("roller_radius") : BlockColumn{};
    return [c, shape, roller](const CamBasics& basics, const ParamSet&, std::size_t k,
                              OutputSet& extra) -> std::shared_ptr<const CamLaw> {
      const double rr = c.roller ? roller[k] : 0.0;
      return std::make_shared<const ThreeArcLaw>(three_arc_geometry(basics, c, shape[k], rr, extra), rr);
    };
  };
  return d;
}

}  // namespace mechgraph::cams
