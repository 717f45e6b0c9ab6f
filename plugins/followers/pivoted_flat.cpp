// Flat-faced arm (finger follower with a flat pad) turning about the pivot P (docs/methods/
// followers.md, "Pivoted flat face"). Its face is the line at face_offset f from the pivot on the
// cam's side, along the arm e(psi); its outward normal (away from the cam) m = k J e.
//  - The face's distance from the cam centre is p = m.P - f. On the base circle p = r0:
//    with P = |P| (cos beta, sin beta), psi0 = beta - pi + k asin((r0 + f) / |P|), and the lever
//    (pivot to the base-circle contact, along the face) L = sqrt(|P|^2 - (r0 + f)^2).
//  - In the cam's frame the face's normal turns to the angle theta = angle(m) - sigma phi, so the
//    contour is the envelope of lines m(theta).x = p(theta): its support function. Contact
//    x = p m + p_theta J m and rho = p + p_theta_theta, with (primes over phi)
//    p' = -k (e.P) psi', p'' = -k (J e.P) psi'^2 - k (e.P) psi'', theta' = psi' - sigma,
//    p_theta = p' / theta', p_theta_theta = (p'' theta' - p' theta'') / theta'^3.
//  - Pressure angle: between m and the motion k J (x - P) of the arm's point at the contact.
#include "follower_types.hpp"
#include "pivoted_frame.hpp"

#include <mechgraph/errors.hpp>

#include <cmath>
#include <numbers>

namespace mechgraph::followers {
namespace {

class PivotedFlat final : public Follower {
 public:
  PivotedFlat(double px, double py, double f) : pivot_{px, py}, f_(f), k_(px <= 0.0 ? 1.0 : -1.0) {}
  std::string_view type_name() const override { return "follower.pivoted_flat"; }
  std::string describe() const override {
    return "pivoted flat face, pivot (" + mm(pivot_.x) + ", " + mm(pivot_.y) + "), face " + mm(f_) + " from the pivot";
  }
  double roller_radius() const override { return 0.0; }
  bool pivoted() const override { return true; }
  double cam_lever(double r0) const override {
    check(r0);
    return std::sqrt(dot(pivot_, pivot_) - (r0 + f_) * (r0 + f_));
  }
  FollowerContact contact(double phi, const LiftDerivatives& d, double r0, bool clockwise) const override {
    const double sigma = clockwise ? -1.0 : 1.0;
    const double lever = cam_lever(r0);
    const double beta = std::atan2(pivot_.y, pivot_.x);
    const double psi0 = beta - std::numbers::pi + k_ * std::asin((r0 + f_) / norm(pivot_));
    const ArmTurn a = arm_turn(psi0, k_, lever, d);
    const Vec2 e{std::cos(a.psi), std::sin(a.psi)};
    const Vec2 m = k_ * quarter_turn(e);
    const double p = dot(m, pivot_) - f_;
    const double dp = -k_ * dot(e, pivot_) * a.dpsi;
    const double d2p = -k_ * dot(quarter_turn(e), pivot_) * a.dpsi * a.dpsi - k_ * dot(e, pivot_) * a.d2psi;
    const double dtheta = a.dpsi - sigma, d2theta = a.d2psi;
    if (!(std::abs(dtheta) > 1e-9))
      throw NodeError("pivot_x", "the " + named() + " turns with the cam (d psi / d phi = " + std::to_string(a.dpsi) +
                                     "): no contour can drive it");
    const double p_theta = dp / dtheta;
    const double p_theta_theta = (d2p * dtheta - dp * d2theta) / (dtheta * dtheta * dtheta);
    const Vec2 x = p * m + p_theta * quarter_turn(m);  // fixed frame
    FollowerContact c;
    const Vec2 xc = into_cam_frame(x, phi, sigma);
    c.x = c.pitch_x = xc.x;
    c.y = c.pitch_y = xc.y;
    c.curvature_radius = p + p_theta_theta;
    c.face_position = dot(e, x - pivot_);
    c.follower_angle = d.lift / lever;
    c.pressure_angle = pressure_angle(k_ * quarter_turn(x - pivot_), m, sigma);
    return c;
  }

 private:
  void check(double r0) const {
    if (!(norm(pivot_) > std::abs(r0 + f_)))
      throw NodeError("pivot_y", "the " + named() + ": the pivot must lie farther than base radius + face_offset " +
                                     mm(r0 + f_) + " from the cam centre (it is " + mm(norm(pivot_)) + ")");
  }
  Vec2 pivot_;
  double f_, k_;
};

}  // namespace

std::shared_ptr<const Follower> make_pivoted_flat(double pivot_x, double pivot_y, double face_offset) {
  return std::make_shared<const PivotedFlat>(pivot_x, pivot_y, face_offset);
}

}  // namespace mechgraph::followers
