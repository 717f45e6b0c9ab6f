// Roller of radius rr translating on a line parallel to +y, `e` from the cam centre (positive: the
// side that lowers the pressure angle on the rise); docs/methods/followers.md, "Translating roller".
// Roller centre (pitch curve) C = (s0 + h) u + e t, s0 = sqrt((r0 + rr)^2 - e^2);
// C' = (h' - e) u + (s0 + h) t; the contour P = C - rr N, N = ((s0 + h) u - (h' - e) t) / |C'|;
// tan(alpha) = (h' - e) / (s0 + h); rho_pitch = |C'|^3 / ((h' - e)(2h' - e) + (s0 + h)^2 - (s0 + h) h''),
// contour rho = rho_pitch - rr.
#include "follower_types.hpp"

#include <mechgraph/errors.hpp>

#include <cmath>

namespace mechgraph::followers {
namespace {

class TranslatingRoller final : public Follower {
 public:
  TranslatingRoller(double rr, double e) : rr_(rr), e_(e) {}
  std::string_view type_name() const override { return e_ == 0.0 ? "follower.roller" : "follower.offset_roller"; }
  std::string describe() const override {
    return "roller " + mm(rr_) + (e_ == 0.0 ? std::string(" in line") : ", offset " + mm(e_));
  }
  double roller_radius() const override { return rr_; }
  bool pivoted() const override { return false; }
  double cam_lever(double) const override { return 0.0; }
  FollowerContact contact(double phi, const LiftDerivatives& d, double r0, bool clockwise) const override {
    const double R = r0 + rr_;
    if (!(std::abs(e_) < R))
      throw NodeError("offset", "the " + named() + " needs |offset| below base radius + roller radius " + mm(R));
    const double sigma = clockwise ? -1.0 : 1.0;
    const double ux = sigma * std::sin(phi), uy = std::cos(phi);
    const double tx = sigma * std::cos(phi), ty = -std::sin(phi);
    const double s = std::sqrt(R * R - e_ * e_) + d.lift;
    const double a = d.velocity - e_;  // C' = a u + s t
    const double speed = std::hypot(a, s);
    FollowerContact c;
    c.pitch_x = s * ux + e_ * tx;
    c.pitch_y = s * uy + e_ * ty;
    const double nx = (s * ux - a * tx) / speed, ny = (s * uy - a * ty) / speed;
    c.x = c.pitch_x - rr_ * nx;
    c.y = c.pitch_y - rr_ * ny;
    c.pressure_angle = std::atan2(a, s);
    const double cross = a * (2.0 * d.velocity - e_) + s * s - s * d.acceleration;
    c.curvature_radius = speed * speed * speed / cross - rr_;
    return c;
  }

 private:
  double rr_, e_;
};

}  // namespace

std::shared_ptr<const Follower> make_roller(double roller_radius, double offset) {
  return std::make_shared<const TranslatingRoller>(roller_radius, offset);
}

}  // namespace mechgraph::followers
