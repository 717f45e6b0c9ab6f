#include "cardan_kinematics.hpp"

#include <mechgraph/errors.hpp>

#include <cmath>
#include <iomanip>
#include <numbers>
#include <sstream>

namespace mechgraph::joints {

double CardanKinematics::bend_limit() { return std::acos(1.0 / max_secant); }

CardanKinematics::CardanKinematics(double bend_angle) : b_(bend_angle) {
  constexpr double deg = std::numbers::pi / 180.0;
  if (!(b_ >= 0.0)) throw NodeError("bend_angle", "the bend angle must be zero or positive");
  if (!(b_ <= bend_limit())) {
    std::ostringstream msg;
    msg << std::setprecision(10) << "bend_angle = " << b_ / deg
        << " deg: a cardan joint locks as the bend angle approaches 90 deg (its speed ratio reaches 1/cos b); "
           "bend angles are evaluated up to acos(1e-6) = "
        << bend_limit() / deg << " deg (1/cos b <= 1e6)";
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
