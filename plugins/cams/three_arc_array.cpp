#include "three_arc_array.hpp"

namespace mechgraph::cams {

ThreeArcArray::ThreeArcArray(std::size_t lanes)
    : lanes_(lanes), event_begin_(lanes), event_end_(lanes), max_lift_(lanes), base_radius_(lanes), roller_radius_(lanes),
      breaks_(2 * lanes) {}

void ThreeArcArray::set(std::size_t k, const ThreeArcLane& lane) {
  // The figures ThreeArcLaw gives: the event -phi_p to phi_p, breakpoints at the flank/nose switches.
  lanes_.at(k) = lane;
  event_begin_[k] = -lane.half_action;
  event_end_[k] = lane.half_action;
  max_lift_[k] = lane.max_lift;
  base_radius_[k] = lane.base_radius;
  roller_radius_[k] = lane.roller_radius;
  breaks_[2 * k] = -lane.switch_angle;
  breaks_[2 * k + 1] = lane.switch_angle;
}

CamLawColumns ThreeArcArray::columns() const {
  return {event_begin_.data(), event_end_.data(), max_lift_.data(), base_radius_.data(), roller_radius_.data()};
}

void ThreeArcArray::evaluate(const std::uint32_t* lane, const double* phi, std::size_t n, LiftDerivatives* out) const {
  for (std::size_t k = 0; k < n; ++k) out[k] = three_arc_point(lanes_[lane ? lane[k] : k], phi[k]);
}

}  // namespace mechgraph::cams
