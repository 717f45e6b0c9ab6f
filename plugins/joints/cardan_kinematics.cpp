#include "cardan_kinematics.hpp"

#include <mechgraph/errors.hpp>

#include <cmath>
#include <iomanip>
#include <numbers>
#include <sstream>

namespace mechgraph::joints {

CardanKinematics::CardanKinematics(double bend_angle) : b_(bend_angle) {
  constexpr double deg = std::numbers::pi / 180.0;
  if (!(b_ >= 0.0)) throw NodeError("bend_angle", "the bend angle must be zero or positive");
  // The joint locks at 90 deg (its speed ratio 1/cos b grows without bound), the one limit the
  // mathematics sets. "90 deg" reads as the double nearest pi/2, which is refused as the locked
  // joint; every double below it has cos b >= 1.6e-16, so 1/cos b <= 6.2e15 stays finite.
  if (!(b_ < 0.5 * std::numbers::pi)) {
    std::ostringstream msg;
    msg << std::setprecision(10) << "bend_angle = " << b_ / deg
        << " deg: a cardan joint locks at a bend of 90 deg (its speed ratio 1/cos b grows without bound); the bend "
           "angle must stay below 90 deg";
    throw NodeError("bend_angle", msg.str());
  }
  cos_b_ = std::cos(b_);
  const double s = std::sin(0.5 * b_);
  one_minus_cos_b_ = 2.0 * s * s;
}

double CardanKinematics::angular_error(double t1) const {
  const double s = std::sin(t1), c = std::cos(t1);
  return std::atan2(s * c * one_minus_cos_b_, s * s + c * c * cos_b_);
}

double CardanKinematics::speed_ratio(double t1) const {
  const double s = std::sin(t1), c = std::cos(t1);
  return cos_b_ / (s * s + c * c * cos_b_ * cos_b_);
}

}  // namespace mechgraph::joints
