#pragma once
// The Follower conformance suite (the contract of mechgraph/domain/follower.hpp), for any follower
// on any cam law that it can follow: every value finite; on the base circle the contact at the base
// radius (and a roller's centre at base + roller radius); a roller's contact a roller radius from
// its centre; the contour's radius of curvature the follower states against the circumradius of
// three neighbouring contact points (a second method); the contour tangent perpendicular to the
// roller's normal; a roller's pressure angle against the path of its centre; the pressure angle
// within +-90 deg; the arm's turn h / cam_lever on a pivoted one.
// Header-only: a plugin's own tests run it on their own cams; `mechgraph plugin-test` runs it on
// every follower a node outputs, paired with the reference cam below (check_follower_on_reference).
#include <mechgraph/domain/cam_law.hpp>
#include <mechgraph/domain/follower.hpp>
#include <mechgraph/testing/report.hpp>

#include <cmath>
#include <numbers>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace mechgraph::testing {

struct FollowerCheckOptions {
  int samples = 720;                      // cam angles over the turn
  double curvature_tolerance = 1e-4;      // relative, stated radius against the circumradius
  double curvature_floor = 1e-7;          // m, absolute floor of that (where the radius nears zero)
  double position_tolerance = 1e-9;       // m, base circle and roller distances
  double step = 1e-5;                     // rad, neighbours for the circumradius and tangent
};

/// `law` and `follower` must make a pair that can be followed (cam.contour accepts it).
inline Report check_follower(const Follower& follower, const CamLaw& law, bool clockwise,
                             const std::string& suite = "follower", FollowerCheckOptions o = {}) {
  Report r;
  const std::string name = suite + " " + std::string(follower.type_name());
  const double r0 = law.base_radius(), rr = follower.roller_radius();
  const double pi = std::numbers::pi;
  auto at = [&](double phi) { return follower.contact(phi, law.at(phi), r0, clockwise); };
  bool finite = true, base_ok = true, roller_ok = true, pressure_ok = true, turn_ok = true;
  double worst_curvature = 0.0, worst_curvature_at = 0.0, worst_tangent = 0.0, worst_pressure = 0.0;
  std::ostringstream where;
  const double lever = follower.pivoted() ? follower.cam_lever(r0) : 0.0;
  for (int i = 0; i < o.samples; ++i) {
    const double phi = -pi + 2.0 * pi * (i + 0.5) / o.samples;
    const FollowerContact c = at(phi);
    const double values[] = {c.x, c.y, c.pitch_x, c.pitch_y, c.pressure_angle, c.curvature_radius, c.face_position,
                             c.follower_angle};
    for (double v : values) finite = finite && std::isfinite(v);
    const bool on_base = phi <= law.event_begin() || phi >= law.event_end();
    if (on_base) {
      base_ok = base_ok && std::abs(std::hypot(c.x, c.y) - r0) <= o.position_tolerance &&
                std::abs(std::hypot(c.pitch_x, c.pitch_y) - (r0 + rr)) <= o.position_tolerance;
      if (!base_ok && where.str().empty()) where << "base circle at " << phi * 180.0 / pi << " deg";
    }
    if (rr > 0.0)
      roller_ok = roller_ok && std::abs(std::hypot(c.pitch_x - c.x, c.pitch_y - c.y) - rr) <= o.position_tolerance;
    pressure_ok = pressure_ok && std::abs(c.pressure_angle) < 0.5 * pi;
    if (follower.pivoted()) turn_ok = turn_ok && std::abs(c.follower_angle - law.at(phi).lift / lever) <= 1e-12;
    // Circumradius of the contact points at phi - step, phi, phi + step (away from the event's ends
    // and breakpoints, where the curvature may jump).
    bool smooth = std::abs(phi - law.event_begin()) > 3.0 * o.step && std::abs(phi - law.event_end()) > 3.0 * o.step;
    for (double b : law.breakpoints()) smooth = smooth && std::abs(phi - b) > 3.0 * o.step;
    if (!smooth) continue;
    const FollowerContact a = at(phi - o.step), b = at(phi + o.step);
    const double ab = std::hypot(b.x - a.x, b.y - a.y), ac = std::hypot(c.x - a.x, c.y - a.y), cb = std::hypot(b.x - c.x, b.y - c.y);
    const double area2 = std::abs((c.x - a.x) * (b.y - a.y) - (c.y - a.y) * (b.x - a.x));
    if (area2 > 0.0 && ab > 0.0) {
      const double circum = ab * ac * cb / (2.0 * area2);
      const double err = std::abs(std::abs(c.curvature_radius) - circum) / (o.curvature_tolerance * circum + o.curvature_floor);
      if (err > worst_curvature) {
        worst_curvature = err;
        worst_curvature_at = phi;
      }
    }
    if (rr > 0.0 && ab > 0.0) {
      // The contour's tangent is perpendicular to the line from the contact to the roller centre.
      const double nx = c.pitch_x - c.x, ny = c.pitch_y - c.y;
      worst_tangent = std::max(worst_tangent, std::abs(((b.x - a.x) * nx + (b.y - a.y) * ny) / (ab * rr)));
      // The pressure angle against the roller centre's own path in the fixed frame (the cam's frame
      // turned back by sigma phi): the angle between that path, the way the lift grows, and the
      // contact normal, where the follower moves (|h'| not small).
      const double velocity = law.at(phi).velocity;
      if (std::abs(velocity) > 1e-3 * law.max_lift()) {
        const double sigma = clockwise ? -1.0 : 1.0;
        auto fixed = [&](double x, double y, double angle) {
          const double co = std::cos(sigma * angle), si = std::sin(sigma * angle);
          return std::pair<double, double>{x * co - y * si, x * si + y * co};
        };
        const auto [ax, ay] = fixed(a.pitch_x, a.pitch_y, phi - o.step);
        const auto [bx, by] = fixed(b.pitch_x, b.pitch_y, phi + o.step);
        const double sign = velocity > 0.0 ? 1.0 : -1.0;
        const double mx = sign * (bx - ax), my = sign * (by - ay);
        const auto [fx, fy] = fixed(nx, ny, phi);
        const double expected = std::atan2(std::abs(mx * fy - my * fx), mx * fx + my * fy);
        worst_pressure = std::max(worst_pressure, std::abs(expected - std::abs(c.pressure_angle)));
      }
    }
  }
  r.add(name, "every value finite", finite);
  r.add(name, "contact on the base circle (roller centre at base + roller radius)", base_ok, where.str());
  if (rr > 0.0) {
    r.add(name, "contact a roller radius from the roller centre", roller_ok);
    r.add(name, "contour tangent perpendicular to the roller's normal", worst_tangent <= 1e-6,
          "worst cosine " + std::to_string(worst_tangent));
    r.add(name, "pressure angle against the roller centre's path", worst_pressure <= 1e-6,
          "worst difference " + std::to_string(worst_pressure) + " rad");
  }
  r.add(name, "radius of curvature against three neighbouring contact points", worst_curvature <= 1.0,
        "worst error " + std::to_string(worst_curvature) + " of the tolerance, at cam angle " +
            std::to_string(worst_curvature_at * 180.0 / pi) + " deg");
  r.add(name, "pressure angle within +-90 deg", pressure_ok);
  if (follower.pivoted()) r.add(name, "the arm turns by h / cam_lever", turn_ok);
  return r;
}

/// The reference cam of `mechgraph plugin-test`: a gentle cosine lobe, 2 mm over +-70 deg, on a
/// 20 mm base circle, h = H (1 + cos(pi phi / 70 deg)) / 2 (its acceleration steps at the ends,
/// which the suite leaves out).
class ReferenceCam final : public CamLaw {
 public:
  double event_begin() const override { return -half_; }
  double event_end() const override { return half_; }
  std::vector<double> breakpoints() const override { return {}; }
  double max_lift() const override { return lift_; }
  double base_radius() const override { return 20e-3; }
  LiftDerivatives evaluate_in_event(double phi) const override {
    const double w = std::numbers::pi / half_, c = std::cos(w * phi), s = std::sin(w * phi);
    return {0.5 * lift_ * (1.0 + c), -0.5 * lift_ * w * s, -0.5 * lift_ * w * w * c, 0.5 * lift_ * w * w * w * s};
  }

 private:
  double lift_ = 2e-3, half_ = 70.0 * std::numbers::pi / 180.0;
};

/// The suite on the reference cam, both ways round; skipped (with the follower's own words) when
/// the follower cannot sit on a 20 mm base circle or cannot follow that lobe.
inline Report check_follower_on_reference(const Follower& follower, const std::string& suite = "follower") {
  Report r;
  const ReferenceCam cam;
  try {
    bool follows = true;
    for (int i = 0; i < 720 && follows; ++i) {
      const double phi = -std::numbers::pi + std::numbers::pi * i / 360.0;
      follows = follower.follow_margin(follower.contact(phi, cam.at(phi), cam.base_radius(), false)) < 0.0;
    }
    if (!follows) {
      r.skip(suite + " " + std::string(follower.type_name()), "interface suite",
             "the follower cannot follow the reference cam (2 mm cosine lobe over 140 deg on 20 mm)");
      return r;
    }
  } catch (const std::exception& e) {
    r.skip(suite + " " + std::string(follower.type_name()), "interface suite",
           std::string("the follower cannot sit on the reference cam's 20 mm base circle: ") + e.what());
    return r;
  }
  r.append(check_follower(follower, cam, false, suite));
  r.append(check_follower(follower, cam, true, suite + " (cw)"));
  return r;
}

}  // namespace mechgraph::testing
