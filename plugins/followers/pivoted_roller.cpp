// Roller of radius rr on an arm of length L turning about the pivot P (docs/methods/followers.md,
// "Pivoted roller"). Roller centre (fixed frame) C = P + L e(psi).
//  - On the base circle |C| = r0 + rr: with P = |P| (cos beta, sin beta) and
//    c = ((r0 + rr)^2 - |P|^2 - L^2) / (2 L |P|), psi0 = beta - pi + k acos(-c), taken as
//    atan2(sqrt((1 - c)(1 + c)), -c) with 1 +- c in factors (no digits lost near the reach's ends).
//  - The pitch curve in the cam's frame, C_cam = R(-sigma phi) C; with A and B its first and
//    second derivatives over phi written in the fixed frame:
//    A = -sigma J C + L J e psi', B = -C + 2 sigma L e psi' - L e psi'^2 + L J e psi''.
//    Outward normal N = sigma J A / |A| (the pitch curve runs clockwise for a cam turning ccw);
//    contact = C - rr N; pitch radius rho_p = |A|^3 / (-sigma A x B), contour rho = rho_p - rr.
//  - Pressure angle: between N and the roller centre's motion k J e.
#include "follower_types.hpp"
#include "pivoted_frame.hpp"

#include <mechgraph/errors.hpp>

#include <cmath>
#include <numbers>

namespace mechgraph::followers {
namespace {

class PivotedRoller final : public Follower {
 public:
  PivotedRoller(double px, double py, double arm, double rr)
      : pivot_{px, py}, arm_(arm), rr_(rr), k_(px <= 0.0 ? 1.0 : -1.0) {}
  std::string_view type_name() const override { return "follower.pivoted_roller"; }
  std::string describe() const override {
    return "pivoted roller " + mm(rr_) + ", pivot (" + mm(pivot_.x) + ", " + mm(pivot_.y) + "), arm " + mm(arm_);
  }
  double roller_radius() const override { return rr_; }
  bool pivoted() const override { return true; }
  double cam_lever(double) const override { return arm_; }
  FollowerContact contact(double phi, const LiftDerivatives& d, double r0, bool clockwise) const override {
    const double sigma = clockwise ? -1.0 : 1.0;
    const double a_pivot = norm(pivot_), reach = r0 + rr_;
    // 1 + c and 1 - c factored (the law of cosines by Kahan): as the arm nears either end of its
    // reach, c = (reach^2 - |P|^2 - L^2) / (2 L |P|) from the squares would lose the digits that
    // acos(-c) needs there.
    const double one_plus = (reach - a_pivot + arm_) * (reach + a_pivot - arm_) / (2.0 * arm_ * a_pivot);
    const double one_minus = (a_pivot + arm_ - reach) * (a_pivot + arm_ + reach) / (2.0 * arm_ * a_pivot);
    if (!(one_plus > 0.0 && one_minus > 0.0))
      throw NodeError("arm_length", "the " + named() + " cannot reach the base circle: the roller centre must sit " +
                                        mm(r0 + rr_) + " from the cam centre, the pivot is " + mm(a_pivot) +
                                        " from it; the arm must lie between " + mm(std::abs(a_pivot - r0 - rr_)) +
                                        " and " + mm(a_pivot + r0 + rr_));
    // acos(-c) = atan2(sqrt((1 - c)(1 + c)), -c).
    const double psi0 = std::atan2(pivot_.y, pivot_.x) - std::numbers::pi +
                        k_ * std::atan2(std::sqrt(one_minus * one_plus), 0.5 * (one_minus - one_plus));
    const ArmTurn t = arm_turn(psi0, k_, arm_, d);
    const Vec2 e{std::cos(t.psi), std::sin(t.psi)};
    const Vec2 je = quarter_turn(e);
    const Vec2 centre = pivot_ + arm_ * e;
    const Vec2 A = -sigma * quarter_turn(centre) + (arm_ * t.dpsi) * je;
    const Vec2 B = -1.0 * centre + (2.0 * sigma * arm_ * t.dpsi - arm_ * t.dpsi * t.dpsi) * e + (arm_ * t.d2psi) * je;
    const double speed = norm(A);
    const Vec2 normal = (sigma / speed) * quarter_turn(A);
    const Vec2 contact = centre - rr_ * normal;
    FollowerContact c;
    const Vec2 pc = into_cam_frame(centre, phi, sigma), xc = into_cam_frame(contact, phi, sigma);
    c.pitch_x = pc.x;
    c.pitch_y = pc.y;
    c.x = xc.x;
    c.y = xc.y;
    c.curvature_radius = speed * speed * speed / (-sigma * cross(A, B)) - rr_;
    c.follower_angle = d.lift / arm_;
    c.pressure_angle = pressure_angle(k_ * je, normal, sigma);
    return c;
  }

 private:
  Vec2 pivot_;
  double arm_, rr_, k_;
};

}  // namespace

std::shared_ptr<const Follower> make_pivoted_roller(double pivot_x, double pivot_y, double arm_length, double roller_radius) {
  return std::make_shared<const PivotedRoller>(pivot_x, pivot_y, arm_length, roller_radius);
}

}  // namespace mechgraph::followers
