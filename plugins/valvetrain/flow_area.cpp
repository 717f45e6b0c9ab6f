#include "flow_area.hpp"

#include <mechgraph/errors.hpp>

#include <cmath>
#include <numbers>
#include <sstream>

namespace mechgraph::valvetrain {

FlowArea::FlowArea(const SeatGeometry& seat) : seat_(seat) {
  if (!seat.three_stage) return;
  const double a = seat.seat_angle, w = seat.seat_width;
  mean_diameter_ = seat.inner_diameter + w;
  port_area_ = std::numbers::pi / 4.0 * (seat.port_diameter * seat.port_diameter - seat.stem_diameter * seat.stem_diameter);
  if (!(seat.port_diameter > seat.stem_diameter))
    throw NodeError("stem_diameter", "the stem diameter must be smaller than the port diameter");
  lift_1_ = w / (std::sin(a) * std::cos(a));
  const double q = (seat.port_diameter * seat.port_diameter - seat.stem_diameter * seat.stem_diameter) / (4.0 * mean_diameter_);
  if (!(q > w)) {
    std::ostringstream msg;
    msg << "the port (" << seat.port_diameter * 1e3 << " mm, stem " << seat.stem_diameter * 1e3
        << " mm) is too small for the seat: its area must exceed pi*Dm*w = " << std::numbers::pi * mean_diameter_ * w * 1e6
        << " mm^2";
    throw NodeError("port_diameter", msg.str());
  }
  lift_2_ = std::sqrt(q * q - w * w) + w * std::tan(a);
  if (lift_2_ < lift_1_) lift_2_ = lift_1_;
  stage_lifts_ = {lift_1_, lift_2_};
}

double FlowArea::operator()(double lift) const {
  const double a = seat_.seat_angle;
  if (lift <= 0.0) return 0.0;
  if (!seat_.three_stage || lift <= lift_1_)
    return std::numbers::pi * lift * (seat_.inner_diameter * std::cos(a) + lift * std::sin(a) * std::cos(a) * std::cos(a));
  if (lift <= lift_2_) {
    const double w = seat_.seat_width;
    const double s = lift - w * std::tan(a);
    return std::numbers::pi * mean_diameter_ * std::sqrt(s * s + w * w);
  }
  return port_area_;
}

}  // namespace mechgraph::valvetrain

namespace mechgraph::valvetrain {

bool FlowArea::quadratic(double& k1, double& k2) const {
  if (seat_.three_stage) return false;
  const double a = seat_.seat_angle;
  k1 = std::numbers::pi * seat_.inner_diameter * std::cos(a);
  k2 = std::numbers::pi * std::sin(a) * std::cos(a) * std::cos(a);
  return true;
}

}  // namespace mechgraph::valvetrain
