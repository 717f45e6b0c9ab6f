#include "polydyne_array.hpp"

namespace mechgraph::cams {

PolydyneArray::PolydyneArray(std::size_t lanes, std::shared_ptr<const PolydyneSeries> series)
    : series_(std::move(series)), lanes_(lanes), event_begin_(lanes), event_end_(lanes), max_lift_(lanes),
      base_radius_(lanes), roller_radius_(lanes) {}

void PolydyneArray::set(std::size_t k, double max_lift, double action_angle, double base_radius) {
  // As PolydyneLaw's constructor: phi_p = action_angle / 2.
  const double half_action = 0.5 * action_angle;
  lanes_.at(k) = {half_action, max_lift, series_.get()};
  event_begin_[k] = -half_action;
  event_end_[k] = half_action;
  max_lift_[k] = max_lift;
  base_radius_[k] = base_radius;
}

CamLawColumns PolydyneArray::columns() const {
  return {event_begin_.data(), event_end_.data(), max_lift_.data(), base_radius_.data(), roller_radius_.data()};
}

void PolydyneArray::evaluate(const std::uint32_t* lane, const double* phi, std::size_t n, LiftDerivatives* out) const {
  for (std::size_t i = 0; i < n; ++i) out[i] = polydyne_point(lanes_[lane ? lane[i] : i], phi[i]);
}

}  // namespace mechgraph::cams
