#include "shockless_array.hpp"

#include <stdexcept>
#include <string>

namespace mechgraph::cams {

ShocklessArray::ShocklessArray(std::size_t lanes)
    : event_begin_(lanes), half_action_(lanes), max_lift_(lanes), base_radius_(lanes), roller_radius_(lanes),
      piece_from_(lanes), piece_count_(lanes), break_from_(lanes), break_count_(lanes) {
  pieces_.reserve(3 * lanes);  // the Kurz law's three pieces and four breakpoints a lane
  breaks_.reserve(4 * lanes);
}

void ShocklessArray::set(std::size_t k, const ShocklessLaw& law) {
  if (law.owns_shapes()) throw std::invalid_argument("ShocklessArray: the law keeps its shapes alive; an array keeps none");
  if (k >= lanes() || piece_count_[k] != 0)
    throw std::invalid_argument("ShocklessArray: lane " + std::to_string(k) + " of " + std::to_string(lanes()) +
                                (k < lanes() ? " is set already" : " is past the array"));
  event_begin_[k] = law.event_begin();
  half_action_[k] = law.event_end();
  max_lift_[k] = law.max_lift();
  base_radius_[k] = law.base_radius();
  roller_radius_[k] = law.roller_radius();
  piece_from_[k] = pieces_.size();
  piece_count_[k] = law.pieces().size();
  pieces_.insert(pieces_.end(), law.pieces().begin(), law.pieces().end());
  break_from_[k] = breaks_.size();
  break_count_[k] = law.breakpoint_list().size();
  breaks_.insert(breaks_.end(), law.breakpoint_list().begin(), law.breakpoint_list().end());
}

CamLawColumns ShocklessArray::columns() const {
  return {event_begin_.data(), half_action_.data(), max_lift_.data(), base_radius_.data(), roller_radius_.data()};
}

void ShocklessArray::evaluate(const std::uint32_t* lane, const double* phi, std::size_t n, LiftDerivatives* out) const {
  for (std::size_t i = 0; i < n; ++i) out[i] = evaluate_one(lane ? lane[i] : i, phi[i]);
}

}  // namespace mechgraph::cams
