#pragma once
// The two translating followers every cam contour can fall back on, as header-only reference
// implementations of the Follower interface (mechgraph/domain/follower.hpp): the flat-faced tappet
// and the roller on a line at an offset from the cam centre (docs/methods/followers.md,
// "Translating flat face" and "Translating roller"). They compile into the plugin that uses them:
// the followers plugin's follower.flat, follower.roller and follower.offset_roller are these, and
// cam.contour builds its default follower from them without linking another plugin.
//
// The cam's frame: u(phi) = (sigma sin phi, cos phi), t = du/dphi = (sigma cos phi, -sin phi),
// sigma = +1 counterclockwise, -1 clockwise.
#include <mechgraph/domain/follower.hpp>
#include <mechgraph/errors.hpp>

#include <cmath>
#include <memory>
#include <sstream>
#include <string>

namespace mechgraph::reference {

/// "12.5 mm", for messages.
inline std::string millimetres(double metres) {
  std::ostringstream s;
  s << metres * 1e3 << " mm";
  return s.str();
}

/// Flat face on the fixed axis +y: the face at s = r0 + h from the cam centre along u(phi); the
/// contour is the envelope of the faces, P = s u + h' t, the contact h' from the axis along the
/// face; rho = r0 + h + h''.
class TranslatingFlat final : public Follower {
 public:
  std::string_view type_name() const override { return "follower.flat"; }
  std::string describe() const override { return "flat-faced tappet"; }
  double roller_radius() const override { return 0.0; }
  bool pivoted() const override { return false; }
  double cam_lever(double) const override { return 0.0; }
  FollowerContact contact(double phi, const LiftDerivatives& d, double r0, bool clockwise) const override {
    const double sigma = clockwise ? -1.0 : 1.0;
    const double ux = sigma * std::sin(phi), uy = std::cos(phi);
    const double tx = sigma * std::cos(phi), ty = -std::sin(phi);
    const double s = r0 + d.lift;
    FollowerContact c;
    c.x = c.pitch_x = s * ux + d.velocity * tx;
    c.y = c.pitch_y = s * uy + d.velocity * ty;
    c.curvature_radius = s + d.acceleration;
    c.face_position = d.velocity;
    return c;
  }
};

/// Roller of radius rr translating on a line parallel to +y, e from the cam centre (positive: the
/// side that lowers the pressure angle on the rise). Roller centre (pitch curve)
/// C = (s0 + h) u + e t, s0 = sqrt((r0 + rr)^2 - e^2); C' = (h' - e) u + (s0 + h) t; the contour
/// P = C - rr N, N = ((s0 + h) u - (h' - e) t) / |C'|; tan(alpha) = (h' - e) / (s0 + h);
/// rho_pitch = |C'|^3 / ((h' - e)(2h' - e) + (s0 + h)^2 - (s0 + h) h''), contour rho = rho_pitch - rr.
class TranslatingRoller final : public Follower {
 public:
  TranslatingRoller(double roller_radius, double offset) : rr_(roller_radius), e_(offset) {}
  std::string_view type_name() const override { return e_ == 0.0 ? "follower.roller" : "follower.offset_roller"; }
  std::string describe() const override {
    return "roller " + millimetres(rr_) + (e_ == 0.0 ? std::string(" in line") : ", offset " + millimetres(e_));
  }
  double roller_radius() const override { return rr_; }
  bool pivoted() const override { return false; }
  double cam_lever(double) const override { return 0.0; }
  FollowerContact contact(double phi, const LiftDerivatives& d, double r0, bool clockwise) const override {
    const double R = r0 + rr_;
    if (!(std::abs(e_) < R))
      throw NodeError("offset", "the " + named() + " needs |offset| below base radius + roller radius " + millimetres(R));
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

}  // namespace mechgraph::reference
