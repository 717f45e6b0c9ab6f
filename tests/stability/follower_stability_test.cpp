// Every follower walked to the ends of its parameters' ranges, against an independent evaluation.
//
// The reference (eccentric_follower.hpp): an eccentric circle under the follower, its motion from
// plane geometry in long double, the lift law's derivatives exact. Whatever the follower, the
// contour must be the circle, so the follower's contact point, roller centre, radius of curvature,
// pressure angle, face position and arm turn are known in closed form at every cam angle. Each
// follower parameter is walked towards the ends of its declared range (follower_nodes.cpp) and
// towards the geometric limits inside it (an arm that barely reaches, a lever or an offset near
// zero reach, a pivot 10 m away), with tiny and huge cams and eccentricities from 1e-9 of the
// circle to nearly all of it (the lift against the base radius).
//
// Tolerances: each quantity is compared absolutely, to a floor (positions: 1e-13 of the cam's size
// plus 16 roundings at the pivot's scale, where the follower forms its face or roller from the
// pivot; angles 1e-12 rad; the radius of curvature, a quotient of derivatives, 1e-10 of the
// circle's plus 1e-13 of the pitch radius it is taken from) plus 16 times the spread the value
// shows when one input moves by one ulp: each input of the reference (circle, eccentricity, each
// follower length, the cam angle), and each input of the follower (its own lengths, the lift and
// its two derivatives, the base radius, the cam angle; this one estimated linearly from a move of
// 2^-40, so that the follower's own rounding does not pass for its inputs' ulps). Near a limit the
// answer is ill-conditioned (a roller whose arm barely reaches the base circle turns by an angle
// that a change of the arm's last bit moves by 1e-12 rad); no double computation can do better
// than its inputs allow, and the spread says how much that is. Far from the limits it is nothing
// and the floors hold.
//
// The same designs through cam.contour (its contour points on the circle, within chord_error of
// it; its scalars min_convex_radius, undercut_margin, max_concave_curvature, max_pressure_angle,
// min_face_width, min_face_diameter and max_follower_angle against the reference's extremes; its
// contact table point by point; every output finite). Then real laws at the follower's geometric
// limits through scenes: a refusal names the node, the parameter and the limit; just inside, the
// pair computes; and an undercut by a hair is found, not passed.
//
// MECHGRAPH_STABILITY_VERBOSE=1 prints each design's worst error per quantity as a share of its
// tolerance (stderr).
#include "contour.hpp"
#include "registration.hpp"
#include "stability/eccentric_follower.hpp"
#include "test_support.hpp"

#include <followers/follower_types.hpp>
#include <mechgraph/errors.hpp>
#include <mechgraph/testing/follower_conformance.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <limits>
#include <numbers>
#include <regex>
#include <string>
#include <vector>

using namespace mechgraph;
using namespace mechgraph::testing;
namespace ecc = mechgraph::testing::eccentric;

namespace {

constexpr double pi = std::numbers::pi;
constexpr double deg = pi / 180.0;
using ecc::Design;
using ecc::Kind;
using Real = ecc::Real;

struct Walk {
  std::string what;  // the parameter walked and where
  Design design;
  // Also through the conformance kit (mechgraph/testing/follower_conformance.hpp): its second
  // methods (the circumradius of contacts 1e-5 rad apart, the roller's path by differences) are
  // made for a cam of ordinary size and are no judge at the walk's extremes (a 10 m pivot's
  // rounding, 2e-15 m, is 5 % of the curvature it reads from points 2e-7 m apart).
  bool conformance = false;
};

Design flat(double Rc, double eps) {
  Design d;
  d.kind = Kind::flat, d.circle_radius = Rc, d.eccentricity = eps;
  return d;
}
Design roller(double rr, double offset, double Rc, double eps) {
  Design d = flat(Rc, eps);
  d.kind = Kind::roller, d.roller_radius = rr, d.offset = offset;
  return d;
}
Design pivoted_flat(double px, double py, double f, double Rc, double eps) {
  Design d = flat(Rc, eps);
  d.kind = Kind::pivoted_flat, d.pivot_x = px, d.pivot_y = py, d.face_offset = f;
  return d;
}
Design pivoted_roller(double px, double py, double arm, double rr, double Rc, double eps) {
  Design d = flat(Rc, eps);
  d.kind = Kind::pivoted_roller, d.pivot_x = px, d.pivot_y = py, d.arm = arm, d.roller_radius = rr;
  return d;
}

std::string number(double v) {
  char text[40];
  std::snprintf(text, sizeof text, "%.17g", v);
  return text;
}

// The walks. Declared ranges (follower_nodes.cpp): roller_radius [1 um, 1 m], offset [-1, 1] m,
// pivot_x and pivot_y [-10, 10] m, face_offset [-1, 1] m, arm_length [0.1 mm, 10 m]. Inside them
// the geometry sets the limits: |offset| < r0 + rr; a pivoted flat face's pivot farther than
// r0 + face_offset from the cam centre (its lever sqrt(|P|^2 - (r0 + f)^2) > 0); a pivoted
// roller's arm between ||P| - r0 - rr| and |P| + r0 + rr.
std::vector<Walk> walks() {
  std::vector<Walk> out;
  // Translating flat face: no parameter; the cam from 1 um to 10 m, the lift (2 eps) from 2e-9 of
  // the circle to nearly twice it (the base radius Rc - eps down to 1e-6 of the circle).
  for (double Rc : {1e-6, 20e-3, 10.0})
    for (double share : {1e-9, 0.2, 0.9, 1.0 - 1e-6})
      out.push_back({"flat: circle " + number(Rc) + " m, eccentricity " + number(share) + " of it", flat(Rc, share * Rc),
                     Rc == 20e-3 && share == 0.2});
  // In-line roller: roller_radius to both ends of its range, on small and large lifts.
  for (double rr : {1e-6, 1e-3, 1.0})
    for (double share : {1e-9, 0.2, 0.9})
      out.push_back({"roller: roller_radius " + number(rr) + ", eccentricity " + number(share),
                     roller(rr, 0.0, 20e-3, share * 20e-3), rr == 1e-3 && share == 0.2});
  out.push_back({"roller: 1 m roller on a 1 um circle", roller(1.0, 0.0, 1e-6, 0.2e-6)});
  out.push_back({"roller: 1 um roller on a 10 m circle", roller(1e-6, 0.0, 10.0, 2.0)});
  // Offset roller: the offset up to the line through the edge of the base circle + roller
  // (r0 + rr = 26 mm at the lowest point for eps 4 mm; the lowest point moves with the offset),
  // both signs; and the declared ends +-1 m with a 1 m roller.
  for (double f : {1e-12, 1e-3, 0.5, 0.9, 0.99, 0.999})
    for (double sign : {1.0, -1.0})
      out.push_back({"offset_roller: offset " + number(sign * f) + " of 22 mm", roller(10e-3, sign * f * 22e-3, 20e-3, 4e-3), f == 0.5});
  for (double sign : {1.0, -1.0}) out.push_back({"offset_roller: offset " + number(sign) + " m, roller 1 m", roller(1.0, sign * 1.0, 0.3, 0.01)});
  // Pivoted flat face: the pivot at the ends of its range, the face offset at both ends, the lever
  // down towards zero (the pivot just outside r0 + f of the lowest pose).
  out.push_back({"pivoted_flat: the standard finger", pivoted_flat(-35e-3, 30e-3, 2e-3, 20e-3, 4e-3), true});
  out.push_back({"pivoted_flat: pivot right of the axis", pivoted_flat(33e-3, 30e-3, 2e-3, 20e-3, 4e-3), true});
  out.push_back({"pivoted_flat: pivot_x -10 m, pivot_y 10 m", pivoted_flat(-10.0, 10.0, 2e-3, 20e-3, 4e-3)});
  out.push_back({"pivoted_flat: pivot_x 10 m, pivot_y 10 m", pivoted_flat(10.0, 10.0, 2e-3, 20e-3, 4e-3)});
  out.push_back({"pivoted_flat: pivot_x -10 m, pivot_y -10 m", pivoted_flat(-10.0, -10.0, 2e-3, 20e-3, 4e-3)});
  out.push_back({"pivoted_flat: face_offset 1 m", pivoted_flat(-1.0, 1.0, 1.0, 20e-3, 4e-3)});
  out.push_back({"pivoted_flat: face_offset -1 m", pivoted_flat(-1.0, 1.0, -1.0, 20e-3, 4e-3)});
  out.push_back({"pivoted_flat: face_offset 0", pivoted_flat(-35e-3, 30e-3, 0.0, 20e-3, 4e-3)});
  out.push_back({"pivoted_flat: tiny cam", pivoted_flat(-35e-9, 30e-9, 2e-9, 20e-9, 4e-9)});
  out.push_back({"pivoted_flat: eccentricity 1e-9", pivoted_flat(-35e-3, 30e-3, 2e-3, 20e-3, 20e-12)});
  // The lever towards zero: the pivot at (1 + delta) (Rc + eps + f) from the cam centre, beyond
  // the face's reach by a hair, with a small eccentricity so that the face reaches all round.
  for (double delta : {1e-3, 1e-6, 1e-9, 1e-12}) {
    const double reach = (20e-3 + 2e-6 + 2e-3) * (1.0 + delta);
    out.push_back({"pivoted_flat: lever towards 0, delta " + number(delta),
                   pivoted_flat(-reach * 0.6, reach * 0.8, 2e-3, 20e-3, 1e-6)});
  }
  // Pivoted roller.
  out.push_back({"pivoted_roller: the standard finger", pivoted_roller(-36e-3, 28e-3, 38e-3, 7e-3, 20e-3, 4e-3), true});
  out.push_back({"pivoted_roller: pivot right of the axis", pivoted_roller(34e-3, 28e-3, 38e-3, 7e-3, 20e-3, 4e-3), true});
  // arm_length at 0.1 mm: the pivot 27 mm + a little from the cam centre, the circle's throw
  // below the arm.
  out.push_back({"pivoted_roller: arm_length 0.1 mm", pivoted_roller(-0.6 * 27.03e-3, 0.8 * 27.03e-3, 1e-4, 7e-3, 20e-3, 2e-5)});
  // arm_length 10 m: the pivot 10 m away.
  out.push_back({"pivoted_roller: arm_length 10 m", pivoted_roller(-6.0, 8.0, 10.0, 7e-3, 20e-3, 4e-3)});
  // A 10 m arm on a 2 mm circle: c = cos(psi0 - beta) is -1 + 3e-8, where acos(-c) of a c from
  // the squares lost 6 digits (the arm's angle to 1e-12 rad, 8 nm at the roller).
  out.push_back({"pivoted_roller: arm_length 10 m on a 2 mm circle", pivoted_roller(-6.0, 8.0, 10.0, 1e-3, 2e-3, 0.4e-3)});
  out.push_back({"pivoted_roller: pivot at (10 m, 10 m)", pivoted_roller(10.0, 10.0, 14.14, 7e-3, 20e-3, 4e-3)});
  // roller_radius at its ends.
  out.push_back({"pivoted_roller: roller_radius 1 um", pivoted_roller(-36e-3, 28e-3, 38e-3, 1e-6, 20e-3, 4e-3)});
  out.push_back({"pivoted_roller: roller_radius 1 m", pivoted_roller(-0.6 * 1.07, 0.8 * 1.07, 0.1, 1.0, 20e-3, 4e-3)});
  // The arm's reach towards its ends: |P| - (Rc + rr) - eps (the arm points at the cam centre)
  // and |P| - eps + Rc + rr (it points away), by a relative delta.
  for (double delta : {1e-3, 1e-6, 1e-9}) {
    const double P = 60e-3, eps = 1e-5, R = 20e-3 + 7e-3;
    out.push_back({"pivoted_roller: arm towards its shortest, delta " + number(delta),
                   pivoted_roller(-0.6 * P, 0.8 * P, (P - R + eps) * (1.0 + delta), 7e-3, 20e-3, eps)});
    out.push_back({"pivoted_roller: arm towards its longest, delta " + number(delta),
                   pivoted_roller(-0.6 * P, 0.8 * P, (P - eps + R) * (1.0 - delta), 7e-3, 20e-3, eps)});
  }
  return out;
}

std::shared_ptr<const Follower> follower_of(const Design& d) {
  switch (d.kind) {
    case Kind::flat: return followers::make_flat();
    case Kind::roller: return followers::make_roller(d.roller_radius, d.offset);
    case Kind::pivoted_flat: return followers::make_pivoted_flat(d.pivot_x, d.pivot_y, d.face_offset);
    case Kind::pivoted_roller: return followers::make_pivoted_roller(d.pivot_x, d.pivot_y, d.arm, d.roller_radius);
  }
  return nullptr;
}

// The quantities compared, as one vector (contact x, y, pitch x, y, pressure angle, curvature
// radius, face position, follower angle).
constexpr int quantities = 8;
const char* const quantity_name[quantities] = {"x", "y", "pitch_x", "pitch_y", "pressure_angle", "curvature_radius",
                                               "face_position", "follower_angle"};
using Values = std::array<double, quantities>;
Values values_of(const ecc::Contact& c) {
  return {double(c.x), double(c.y), double(c.pitch_x), double(c.pitch_y), double(c.pressure_angle),
          double(c.curvature_radius), double(c.face_position), double(c.follower_angle)};
}
Values values_of(const FollowerContact& c) {
  return {c.x, c.y, c.pitch_x, c.pitch_y, c.pressure_angle, c.curvature_radius, c.face_position, c.follower_angle};
}
LiftDerivatives derivatives_of(const ecc::Jet& h) {
  LiftDerivatives d;
  d.lift = double(h.v), d.velocity = double(h.d), d.acceleration = double(h.dd);
  return d;
}

// The design with one of its lengths moved by one ulp either way (each length that is not 0).
std::vector<Design> neighbours(const Design& d) {
  std::vector<Design> out;
  double Design::*fields[] = {&Design::roller_radius, &Design::offset, &Design::pivot_x, &Design::pivot_y,
                              &Design::face_offset,   &Design::arm,    &Design::circle_radius, &Design::eccentricity};
  for (auto field : fields)
    if (d.*field != 0.0)
      for (double to : {-INFINITY, INFINITY}) {
        Design n = d;
        n.*field = std::nextafter(d.*field, to);
        out.push_back(n);
      }
  return out;
}

// How far the follower's answer moves when one of its inputs moves by one ulp (its lengths, the
// lift and its two derivatives, the base radius, the cam angle), by the linear estimate: the input
// moved by 2^-40 of itself either way and the change scaled back to one ulp of it. (Moved by one
// ulp, the answer would also show the follower's own rounding, which is what is being judged.)
Values follower_spread(const Design& design, double phi, const LiftDerivatives& d, double r0, const Values& got) {
  Values spread{};
  const auto nudged = [](double v, double direction) { return v + direction * std::ldexp(std::abs(v), -40); };
  const auto ulp_over = [](double v, double moved) {
    return (std::nextafter(std::abs(v), INFINITY) - std::abs(v)) / std::abs(moved - v);
  };
  const auto widen = [&](const FollowerContact& c, double scale) {
    const Values v = values_of(c);
    for (int q = 0; q < quantities; ++q) spread[q] = std::max(spread[q], std::abs(v[q] - got[q]) * scale);
  };
  for (double direction : {-1.0, 1.0}) {
    double Design::*lengths[] = {&Design::roller_radius, &Design::offset, &Design::pivot_x, &Design::pivot_y,
                                 &Design::face_offset, &Design::arm};
    for (auto field : lengths)
      if (design.*field != 0.0) {
        Design n = design;
        n.*field = nudged(design.*field, direction);
        widen(follower_of(n)->contact(phi, d, r0, design.clockwise), ulp_over(design.*field, n.*field));
      }
    const auto follower = follower_of(design);
    for (double LiftDerivatives::*field : {&LiftDerivatives::lift, &LiftDerivatives::velocity, &LiftDerivatives::acceleration})
      if (d.*field != 0.0) {
        LiftDerivatives m = d;
        m.*field = nudged(d.*field, direction);
        widen(follower->contact(phi, m, r0, design.clockwise), ulp_over(d.*field, m.*field));
      }
    const double r = nudged(r0, direction);
    widen(follower->contact(phi, d, r, design.clockwise), ulp_over(r0, r));
    if (phi != 0.0) {
      const double a = nudged(phi, direction);
      widen(follower->contact(a, d, r0, design.clockwise), ulp_over(phi, a));
    }
  }
  return spread;
}

// The floor of each quantity, from the design's scale (see the file's head).
Values floors(const Design& d) {
  // Positions: a few hundred roundings at the cam's scale, and 16 at the pivot's, where the
  // follower forms its face or roller from the pivot (P + L e, m.P - f).
  const double cam = d.circle_radius + d.eccentricity + d.roller_radius + std::abs(d.offset);
  const double pivot = std::hypot(d.pivot_x, d.pivot_y) + d.arm + std::abs(d.face_offset);
  const double position = 1e-13 * cam + 16.0 * std::numeric_limits<double>::epsilon() * pivot;
  // The contour's radius is the pitch curve's less the roller's: rounded at the pitch radius's scale.
  const double curvature = 1e-10 * d.circle_radius + 1e-13 * (d.circle_radius + d.roller_radius);
  return {position, position, position, position, 1e-12, curvature, position, 1e-12};
}

struct Worst {
  double ratio = 0.0;  // error / tolerance
  std::string where;
};

}  // namespace

TEST_CASE("stability: every follower at the ends of its parameters on an eccentric circle (closed form)",
          "[stability][followers][limits]") {
  int designs = 0, points = 0;
  for (const Walk& walk : walks())
    for (const bool clockwise : {false, true}) {
      Design design = walk.design;
      design.clockwise = clockwise;
      INFO(walk.what << (clockwise ? ", cw" : ", ccw"));
      const ecc::Reference ref(design);
      REQUIRE(ref.valid());
      std::vector<ecc::Reference> near;
      for (const Design& n : neighbours(design)) {
        near.emplace_back(n);
        REQUIRE(near.back().valid());
      }
      const auto follower = follower_of(design);
      const double r0 = ref.base_radius();
      const Values floor = floors(design);
      Worst worst[quantities];
      ++designs;
      for (int i = 0; i <= 360; ++i) {
        // Every degree, the ends +-pi and a hair inside them included.
        const double phi = i == 0 ? -pi : i == 360 ? std::nextafter(pi, 0.0) : -pi + 2.0 * pi * i / 360.0;
        const ecc::Contact expected = ref.at(phi);
        const LiftDerivatives d = derivatives_of(expected.lift);
        const Values got = values_of(follower->contact(phi, d, r0, clockwise));
        const Values want = values_of(expected);
        // The spread: the reference at its inputs' neighbours, the follower at its inputs' neighbours.
        Values spread = follower_spread(design, phi, d, r0, got);
        auto widen = [&](const Values& v) {
          for (int q = 0; q < quantities; ++q) spread[q] = std::max(spread[q], std::abs(v[q] - want[q]));
        };
        for (const ecc::Reference& n : near) widen(values_of(n.at(phi)));
        for (double to : {-INFINITY, INFINITY}) widen(values_of(ref.at(std::nextafter(phi, to))));
        for (int q = 0; q < quantities; ++q) {
          REQUIRE(std::isfinite(got[q]));
          const double tolerance = floor[q] + 16.0 * spread[q];
          const double ratio = std::abs(got[q] - want[q]) / tolerance;
          if (ratio > worst[q].ratio)
            worst[q] = {ratio, "cam angle " + number(phi / deg) + " deg: " + number(got[q]) + " against " + number(want[q]) +
                                   " (floor " + number(floor[q]) + ", spread " + number(spread[q]) + ")"};
        }
        ++points;
      }
      if (std::getenv("MECHGRAPH_STABILITY_VERBOSE"))
        for (int q = 0; q < quantities; ++q)
          std::fprintf(stderr, "%s%s %s: %.3g of the tolerance (%s)\n", walk.what.c_str(), clockwise ? " cw" : " ccw", quantity_name[q], worst[q].ratio, worst[q].where.c_str());
      for (int q = 0; q < quantities; ++q) {
        INFO(quantity_name[q] << ": worst at " << worst[q].where);
        CHECK(worst[q].ratio <= 1.0);
      }
    }
  INFO(designs << " designs, " << points << " cam angles");
  CHECK(designs > 60);
}

namespace {

// The eccentric circle's motion as a cam law over the whole turn (its lowest point, lift 0, at
// +-pi), for cam.contour.
class CircleLaw final : public CamLaw {
 public:
  CircleLaw(const ecc::Reference& ref, double max_lift) : ref_(ref), max_lift_(max_lift) {}
  double event_begin() const override { return -pi; }
  double event_end() const override { return pi; }
  std::vector<double> breakpoints() const override { return {}; }
  double max_lift() const override { return max_lift_; }
  double base_radius() const override { return ref_.base_radius(); }
  LiftDerivatives evaluate_in_event(double phi) const override { return derivatives_of(ref_.lift(phi)); }

 private:
  ecc::Reference ref_;
  double max_lift_;
};

// The largest value of f over the turn: 720 samples, then golden section about each sampled
// local maximum (long double throughout).
Real reference_max(const std::function<Real(Real)>& f) {
  constexpr int n = 720;
  std::vector<Real> v(n);
  for (int i = 0; i < n; ++i) v[i] = f(-ecc::pi_l + 2 * ecc::pi_l * i / n);
  Real best = *std::max_element(v.begin(), v.end());
  const Real step = 2 * ecc::pi_l / n, r = (std::sqrt(Real(5)) - 1) / 2;
  for (int i = 0; i < n; ++i) {
    if (v[i] < v[(i + n - 1) % n] || v[i] < v[(i + 1) % n]) continue;
    Real a = -ecc::pi_l + step * (i - 1), b = a + 2 * step;
    Real c = b - r * (b - a), d = a + r * (b - a), fc = f(c), fd = f(d);
    for (int k = 0; k < 120 && b - a > 1e-17L; ++k) {
      if (fc > fd) b = d, d = c, fd = fc, c = b - r * (b - a), fc = f(c);
      else a = c, c = d, fc = fd, d = a + r * (b - a), fd = f(d);
    }
    best = std::max({best, fc, fd});
  }
  return best;
}

// Per quantity, the largest spread over the turn that one ulp of the inputs makes (as in the
// closed-form test above), at every second degree.
Values spread_over_turn(const Design& design, const ecc::Reference& ref, const Follower& follower) {
  std::vector<ecc::Reference> near;
  for (const Design& n : neighbours(design)) near.emplace_back(n);
  Values spread{};
  for (int i = 0; i < 180; ++i) {
    const double phi = -pi + 2.0 * pi * i / 180.0;
    const ecc::Contact expected = ref.at(phi);
    const Values want = values_of(expected);
    const LiftDerivatives d = derivatives_of(expected.lift);
    const Values got = values_of(follower.contact(phi, d, ref.base_radius(), design.clockwise));
    const Values own = follower_spread(design, phi, d, ref.base_radius(), got);
    for (int q = 0; q < quantities; ++q) spread[q] = std::max(spread[q], own[q]);
    for (const ecc::Reference& n : near) {
      const Values v = values_of(n.at(phi));
      for (int q = 0; q < quantities; ++q) spread[q] = std::max(spread[q], std::abs(v[q] - want[q]));
    }
  }
  return spread;
}

void check_finite(const OutputSet& out) {
  for (const auto& [name, value] : out.all()) {
    INFO("output " << name);
    CHECK(all_finite(value));
  }
}

}  // namespace

TEST_CASE("stability: cam.contour under every follower at the ends of its parameters, eccentric circle",
          "[stability][followers][limits]") {
  NodeTypeList types;
  cams::add_contour_type(types);
  const auto& contour_type = types.at(0);
  int designs = 0;
  for (const Walk& walk : walks())
    for (const bool clockwise : {false, true}) {
      Design design = walk.design;
      design.clockwise = clockwise;
      INFO(walk.what << (clockwise ? ", cw" : ", ccw"));
      const ecc::Reference ref(design);
      REQUIRE(ref.valid());
      const auto follower = follower_of(design);
      const Values spread = spread_over_turn(design, ref, *follower);
      const Values floor = floors(design);
      auto tolerance = [&](int q) { return floor[q] + 16.0 * spread[q]; };
      const Real max_lift = reference_max([&](Real phi) { return ref.lift(phi).v; });
      const auto law = std::make_shared<const CircleLaw>(ref, double(max_lift));
      const double Rc = design.circle_radius, rr = design.roller_radius;
      if (walk.conformance) {
        const auto report = check_follower(*follower, *law, clockwise);
        INFO(report.str());
        CHECK(report.passed());
      }
      const double chord_error = std::clamp(1e-5 * Rc, 1e-9, 1e-3);
      InputSet in;
      in.add("cam", Value::handle(law));
      in.add("follower", Value::handle(follower));
      OutputSet out;
      RecordingContext ctx;
      contour_type->evaluate(defaults_of(contour_type->info(), {{"rotation", ParamValue::of_choice(clockwise ? "cw" : "ccw")},
                                                                {"chord_error", ParamValue::of_number(chord_error)}}),
                             in, out, ctx);
      ++designs;
      check_finite(out);
      const auto scalar = [&](const char* name) { return out.all().at(name).as_scalar(); };
      // Contour points: the reference's contact at each point's cam angle; each chord's middle
      // within chord_error of the circle.
      const Table& contour = out.all().at("contour").as_table();
      const auto& phis = contour.axis.values;
      const auto& xs = contour.find("x")->values;
      const auto& ys = contour.find("y")->values;
      double worst_point = 0.0, worst_sagitta = 0.0;
      const Real centre_x = ref.centre_in_cam_x(), centre_y = ref.centre_in_cam_y();
      for (std::size_t i = 0; i < phis.size(); ++i) {
        const ecc::Contact e = ref.at(phis[i]);
        worst_point = std::max(worst_point, std::max(std::abs(xs[i] - double(e.x)) / tolerance(0), std::abs(ys[i] - double(e.y)) / tolerance(1)));
        const std::size_t j = (i + 1) % phis.size();
        const Real mx = 0.5L * (Real(xs[i]) + xs[j]), my = 0.5L * (Real(ys[i]) + ys[j]);
        worst_sagitta = std::max(worst_sagitta, double(Rc - std::hypot(mx - centre_x, my - centre_y)));
      }
      CHECK(worst_point <= 1.0);
      INFO("points " << phis.size() << ", worst sagitta " << worst_sagitta << " m against chord_error " << chord_error);
      CHECK(worst_sagitta <= chord_error + tolerance(0));
      // The scalars against the reference's extremes.
      CHECK_THAT(scalar("min_convex_radius"), Catch::Matchers::WithinAbs(Rc, tolerance(5)));
      CHECK(scalar("max_concave_curvature") == 0.0);
      CHECK_THAT(scalar("undercut_margin"), Catch::Matchers::WithinAbs(Rc, tolerance(5)));
      const Real max_pa = reference_max([&](Real phi) { return std::abs(ref.at(phi).pressure_angle); });
      CHECK_THAT(scalar("max_pressure_angle"), Catch::Matchers::WithinAbs(double(max_pa), 1e-9 + tolerance(4)));
      if (rr == 0.0) {
        const Real fmax = reference_max([&](Real phi) { return ref.at(phi).face_position; });
        const Real fmin = -reference_max([&](Real phi) { return -ref.at(phi).face_position; });
        INFO("face from " << number(double(fmin)) << " to " << number(double(fmax)) << " m: min_face_width "
                          << number(scalar("min_face_width")) << " m");
        CHECK_THAT(scalar("min_face_width"), Catch::Matchers::WithinAbs(double(fmax - fmin), 1e-9 * double(fmax - fmin) + 2 * tolerance(6)));
        if (design.kind == Kind::flat)
          CHECK_THAT(scalar("min_face_diameter"), Catch::Matchers::WithinAbs(double(2 * std::max(fmax, -fmin)), 1e-9 * double(fmax - fmin) + 2 * tolerance(6)));
      }
      if (design.kind == Kind::pivoted_flat || design.kind == Kind::pivoted_roller)
        CHECK_THAT(scalar("max_follower_angle"), Catch::Matchers::WithinAbs(double(max_lift / ref.lever()), 1e-9 * double(max_lift / ref.lever()) + tolerance(7)));
      // The contact table, point by point.
      const Table& contact = out.all().at("contact").as_table();
      double worst_table = 0.0;
      std::string worst_row;
      for (std::size_t i = 0; i < contact.axis.values.size(); ++i) {
        const Values want = values_of(ref.at(contact.axis.values[i]));
        const std::pair<const char*, int> channels[] = {{"pressure_angle", 4}, {"curvature_radius", 5}, {"face_offset", 6}, {"follower_angle", 7}};
        for (const auto& [name, q] : channels)
          if (const auto* column = contact.find(name)) {
            // At +-pi itself the law reads as outside its event (lift and derivatives 0): the
            // circle's h'' there is not, so the radius of curvature of that row is not the circle's.
            if (q == 5 && std::abs(contact.axis.values[i]) == pi) continue;
            const double ratio = std::abs(column->values[i] - want[q]) / tolerance(q);
            if (ratio > worst_table)
              worst_table = ratio, worst_row = std::string(name) + " at " + number(contact.axis.values[i] / deg) + " deg: " +
                                                number(column->values[i]) + " against " + number(want[q]);
          }
      }
      INFO("contact table, worst: " << worst_row);
      CHECK(worst_table <= 1.0);
    }
  CHECK(designs > 60);
}

namespace {

const std::string kCam = "  cam: { type: cam.cycloidal, params: { max_lift: 7 mm, action_angle: 140 deg, base_radius: 40 mm } }\n";

// A cam, one follower node `f` and cam.contour `cut`; either every output finite, or a refusal
// naming the node, the parameter and a limit in mm.
struct Outcome {
  bool computed = false;
  std::string message;
  RunResult result;
};
Outcome run_pair(const std::string& follower_node) {
  const std::string yaml = "nodes:\n" + kCam + "  f: " + follower_node +
                           "\n  cut: { type: cam.contour, inputs: { cam: cam.law, follower: f.follower } }\n"
                           "outputs: [cut.contour, cut.contact, cut.max_pressure_angle, cut.undercut_margin, cut.min_convex_radius]\n";
  Outcome o;
  try {
    o.result = run_yaml(yaml, project_registry());
    o.computed = true;
  } catch (const std::exception& e) {
    o.message = e.what();
  }
  return o;
}

}  // namespace

TEST_CASE("stability: each follower at its geometric limits on a real law, refused by name or computed",
          "[stability][followers][limits]") {
  // The cam: r0 40 mm. A roller of 10 mm: r0 + rr = 50 mm.
  struct Row {
    std::string node, parameter, limit;  // the follower node; the parameter a refusal must name, and its limit
    bool must_compute;
  };
  std::vector<Row> rows;
  const auto mm = [](double v) { return number(v) + " mm"; };
  // Offset roller: |offset| < r0 + rr = 50 mm.
  for (double f : {1.0 - 1e-3, 1.0 - 1e-9, 1.0, 1.0 + 1e-12, 1.2, 20.0})
    for (double sign : {1.0, -1.0})
      rows.push_back({"{ type: follower.offset_roller, params: { roller_radius: 10 mm, offset: " + mm(sign * 50.0 * f) + " } }",
                      "offset", "50 mm", f < 1.0 - 1e-6});
  // Pivoted roller: the pivot 50 mm from the cam centre, roller 8 mm: the arm between 2 and 98 mm.
  for (double arm : {2.0 * (1.0 - 1e-9), 2.0, 98.0, 98.0 * (1.0 + 1e-9), 0.1, 10000.0})
    rows.push_back({"{ type: follower.pivoted_roller, params: { pivot_x: -30 mm, pivot_y: 40 mm, roller_radius: 8 mm, arm_length: " +
                        mm(arm) + " } }",
                    "arm_length", "between 2 mm and 98 mm", false});
  // Pivoted flat face: the pivot 50 mm from the cam centre, farther than r0 + face_offset.
  for (double f : {10.0 * (1.0 - 1e-9), 10.0, 10.0 + 1e-9, 1000.0})
    rows.push_back({"{ type: follower.pivoted_flat, params: { pivot_x: -30 mm, pivot_y: 40 mm, face_offset: " + mm(f) + " } }",
                    "pivot_y", "50 mm", false});
  int computed = 0, refused = 0;
  for (const Row& row : rows) {
    INFO(row.node);
    const Outcome o = run_pair(row.node);
    if (o.computed) {
      ++computed;
      for (const char* name : {"cut.contour", "cut.contact", "cut.max_pressure_angle", "cut.undercut_margin"})
        CHECK(all_finite(output(o.result, name)));
      CHECK(scalar_output(o.result, "cut.undercut_margin") > 0.0);
      continue;
    }
    ++refused;
    INFO("refused: " << o.message);
    CHECK(!row.must_compute);
    CHECK_THAT(o.message, Catch::Contains("node '"));
    // The follower's own limit, or (inside it) an undercut naming the follower and the radius of
    // curvature it found (with the base radii that work when some do).
    const bool own = o.message.find(row.parameter) != std::string::npos && o.message.find(row.limit) != std::string::npos;
    const bool undercut = o.message.find("cannot follow this law") != std::string::npos &&
                          o.message.find("radius of curvature is") != std::string::npos;
    CHECK((own || undercut));
  }
  INFO(computed << " computed, " << refused << " refused");
  CHECK(computed > 3);
  CHECK(refused > 3);
}

TEST_CASE("stability: the offset roller's offset lowers the pressure angle on the rise, as described", "[stability][followers]") {
  double rise_max[2] = {0.0, 0.0};
  for (int k = 0; k < 2; ++k) {
    const Outcome o = run_pair(std::string("{ type: follower.offset_roller, params: { roller_radius: 10 mm, offset: ") +
                               (k == 0 ? "5 mm" : "-5 mm") + " } }");
    REQUIRE(o.computed);
    const Table& t = output(o.result, "cut.contact").as_table();
    for (std::size_t i = 0; i < t.axis.values.size(); ++i)
      if (t.axis.values[i] < 0.0) rise_max[k] = std::max(rise_max[k], std::abs(t.find("pressure_angle")->values[i]));
  }
  INFO("largest pressure angle on the rise: offset +5 mm " << rise_max[0] / deg << " deg, -5 mm " << rise_max[1] / deg << " deg");
  CHECK(rise_max[0] < rise_max[1]);
}

namespace {

// The largest of g over the law's event, read on each smooth piece (8 ulps inside its knots) at
// 4000 points and refined by golden section about the best: the reference for a narrow extremum.
double law_max(const CamLaw& law, const std::function<double(const LiftDerivatives&)>& g) {
  const std::vector<double> k = law.knots();
  double best = -INFINITY;
  for (std::size_t p = 0; p + 1 < k.size(); ++p) {
    double a = k[p], b = k[p + 1];
    for (int i = 0; i < 8; ++i) a = std::nextafter(a, INFINITY), b = std::nextafter(b, -INFINITY);
    constexpr int n = 4000;
    int at = 0;
    double top = -INFINITY;
    for (int i = 0; i <= n; ++i) {
      const double v = g(law.at(a + (b - a) * i / n));
      if (v > top) top = v, at = i;
    }
    double lo = a + (b - a) * std::max(at - 1, 0) / n, hi = a + (b - a) * std::min(at + 1, n) / n;
    const double r = 0.5 * (std::sqrt(5.0) - 1.0);
    double c = hi - r * (hi - lo), d = lo + r * (hi - lo), fc = g(law.at(c)), fd = g(law.at(d));
    for (int i = 0; i < 200 && hi - lo > 1e-15; ++i) {
      if (fc > fd) hi = d, d = c, fd = fc, c = hi - r * (hi - lo), fc = g(law.at(c));
      else lo = c, c = d, fc = fd, d = lo + r * (hi - lo), fd = g(law.at(d));
    }
    best = std::max({best, top, fc, fd});
  }
  return best;
}

std::shared_ptr<const CamLaw> law_of(const std::string& cam_params) {
  const RunResult r = run_yaml("nodes:\n  cam: { type: cam.cycloidal, params: { " + cam_params + " } }\noutputs: [cam.law]\n",
                               project_registry());
  return std::dynamic_pointer_cast<const CamLaw>(output(r, "cam.law").as_handle());
}

std::string contour_of(const std::string& cam_params, const std::string& follower, RunResult& r) {
  try {
    r = run_yaml("nodes:\n  cam: { type: cam.cycloidal, params: { " + cam_params + " } }\n  f: " + follower +
                     "\n  cut: { type: cam.contour, inputs: { cam: cam.law, follower: f.follower } }\n"
                     "outputs: [cut.undercut_margin, cut.min_convex_radius]\n",
                 project_registry());
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("stability: an undercut by a hair is found, and a hair inside it computes (flat face, roller)",
          "[stability][followers][undercut]") {
  // Flat face: undercut where r0 + h + h'' <= 0, so the least base radius is r0* = -min(h + h'')
  // (the lift does not depend on r0): 35.78 mm for 9 mm over 130 deg. A hair is 1e-7 of r0*,
  // a hundred times the 1e-9 of its scale to which the searches certify an extremum; the undercut
  // stretch is then about 0.02 deg wide.
  const std::string lift = "max_lift: 9 mm, action_angle: 130 deg, ";
  const auto law = law_of(lift + "base_radius: 40 mm");
  REQUIRE(law);
  const double r_star = law_max(*law, [](const LiftDerivatives& d) { return -(d.lift + d.acceleration); });
  CHECK_THAT(r_star, Catch::Matchers::WithinAbs(35.78e-3, 0.01e-3));
  for (const double hair : {1e-7, 1e-4}) {
    INFO("flat face, r0 = r0* (1 +- " << hair << "), r0* = " << number(r_star) << " m");
    RunResult r;
    const std::string inside = contour_of(lift + "base_radius: " + number(r_star * (1.0 + hair)) + " m", "{ type: follower.flat }", r);
    REQUIRE(inside.empty());
    CHECK_THAT(scalar_output(r, "cut.undercut_margin"), Catch::Matchers::WithinAbs(r_star * hair, 1e-9 * r_star));
    const std::string outside = contour_of(lift + "base_radius: " + number(r_star * (1.0 - hair)) + " m", "{ type: follower.flat }", r);
    INFO(outside);
    CHECK_THAT(outside, Catch::Contains("node 'cut'") && Catch::Contains("cannot follow this law"));
    std::smatch m;
    REQUIRE(std::regex_search(outside, m, std::regex("base_radius must be at least ([0-9.eE+-]+) mm")));
    // Printed to 6 digits; bisected to 1 um on the side that works.
    CHECK_THAT(std::stod(m[1]) * 1e-3, Catch::Matchers::WithinAbs(r_star, 1e-6 + 1e-5 * r_star));
  }
  // In-line roller on 17 mm: the pitch curve r = r0 + rr + h in polar form has the curvature
  // (r^2 + 2 r'^2 - r r'') / (r^2 + r'^2)^(3/2) (a formula the follower does not use); the roller
  // follows while rr times its largest value stays below 1. The largest roller rr* by bisection.
  const auto small = law_of(lift + "base_radius: 17 mm");
  const double r0 = 17e-3;
  const auto worst = [&](double rr) {
    return rr * law_max(*small, [&](const LiftDerivatives& d) {
             const double r = r0 + rr + d.lift, r1 = d.velocity, r2 = d.acceleration;
             return (r * r + 2 * r1 * r1 - r * r2) / std::pow(r * r + r1 * r1, 1.5);
           });
  };
  double lo = 1e-3, hi = 1.0;
  REQUIRE(worst(lo) < 1.0);
  REQUIRE(worst(hi) > 1.0);
  for (int i = 0; i < 60 && hi - lo > 1e-15; ++i) (worst(0.5 * (lo + hi)) < 1.0 ? lo : hi) = 0.5 * (lo + hi);
  const double rr_star = 0.5 * (lo + hi);
  for (const double hair : {1e-7, 1e-4}) {
    INFO("roller, rr = rr* (1 -+ " << hair << "), rr* = " << number(rr_star) << " m");
    RunResult r;
    const std::string inside =
        contour_of(lift + "base_radius: 17 mm", "{ type: follower.roller, params: { roller_radius: " + number(rr_star * (1.0 - hair)) + " m } }", r);
    INFO(inside);
    REQUIRE(inside.empty());
    CHECK(scalar_output(r, "cut.undercut_margin") > 0.0);
    const std::string outside =
        contour_of(lift + "base_radius: 17 mm", "{ type: follower.roller, params: { roller_radius: " + number(rr_star * (1.0 + hair)) + " m } }", r);
    INFO(outside);
    CHECK_THAT(outside, Catch::Contains("node 'cut'") && Catch::Contains("cannot follow this law") && Catch::Contains("roller_radius"));
  }
}
