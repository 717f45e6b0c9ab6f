#include "shockless_array.hpp"

#include <algorithm>
#include <cstddef>
#include <stdexcept>
#include <string>

namespace mechgraph::cams {

// A law of n pieces has at most 2 (n - 1) junctions and the nose as breakpoints.
ShocklessArray::ShocklessArray(std::size_t lanes, std::size_t max_pieces)
    : max_pieces_(max_pieces), max_breaks_(max_pieces > 0 ? 2 * max_pieces - 1 : 0), pieces_(lanes * max_pieces_),
      breaks_(lanes * max_breaks_), views_(lanes), break_count_(lanes), event_begin_(lanes), event_end_(lanes),
      max_lift_(lanes), base_radius_(lanes), roller_radius_(lanes) {}

void ShocklessArray::set(std::size_t k, const ShocklessLaw& law) {
  if (law.owns_shapes()) throw std::invalid_argument("ShocklessArray: the law keeps its shapes alive; an array keeps none");
  if (law.pieces().size() > max_pieces_ || law.breakpoint_list().size() > max_breaks_)
    throw std::invalid_argument("ShocklessArray: a law of " + std::to_string(law.pieces().size()) +
                                " pieces in an array of at most " + std::to_string(max_pieces_));
  if (k >= lanes() || views_[k].count != 0)
    throw std::invalid_argument("ShocklessArray: lane " + std::to_string(k) + " of " + std::to_string(lanes()) +
                                (k < lanes() ? " is set already" : " is past the array"));
  ShocklessPiece* pieces = pieces_.data() + k * max_pieces_;
  std::copy(law.pieces().begin(), law.pieces().end(), pieces);
  std::copy(law.breakpoint_list().begin(), law.breakpoint_list().end(), breaks_.begin() + static_cast<std::ptrdiff_t>(k * max_breaks_));
  views_[k] = {pieces, law.pieces().size(), law.event_end()};
  break_count_[k] = law.breakpoint_list().size();
  event_begin_[k] = law.event_begin();
  event_end_[k] = law.event_end();
  max_lift_[k] = law.max_lift();
  base_radius_[k] = law.base_radius();
  roller_radius_[k] = law.roller_radius();
}

CamLawColumns ShocklessArray::columns() const {
  return {event_begin_.data(), event_end_.data(), max_lift_.data(), base_radius_.data(), roller_radius_.data()};
}

void ShocklessArray::evaluate(const std::uint32_t* lane, const double* phi, std::size_t n, LiftDerivatives* out) const {
  for (std::size_t i = 0; i < n; ++i) {
    const LaneView& v = views_[lane ? lane[i] : i];
    out[i] = shockless_point(v.pieces, v.count, v.half_action, phi[i]);
  }
}

}  // namespace mechgraph::cams
