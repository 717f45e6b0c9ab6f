#pragma once
// Three-arc laws over the cases of a block (mechgraph/domain/cam_law_array.hpp): one follower kind
// (flat or roller, the same for every case of a block), each lane the constants of one case's law
// (ThreeArcLane). Every answer comes from the functions ThreeArcLaw answers by
// (three_arc_kernel.hpp), so lane k gives the bits of the scalar law of case k.
#include "three_arc_kernel.hpp"

#include <mechgraph/domain/cam_law_array.hpp>

#include <cstddef>
#include <vector>

namespace mechgraph::cams {

class ThreeArcArray final : public CamLawArray {
 public:
  /// `lanes` lanes, each to be set (set()) before a law of it is made.
  explicit ThreeArcArray(std::size_t lanes);
  /// Lane k's constants. Only while the array is being made: the columns never move.
  void set(std::size_t k, const ThreeArcLane& lane);

  std::size_t lanes() const override { return lanes_.size(); }
  CamLawColumns columns() const override;
  void evaluate(const std::uint32_t* lane, const double* phi, std::size_t n, LiftDerivatives* out) const override;
  Point point(std::size_t lane) const override {
    return {[](const void* data, double phi) { return three_arc_point(*static_cast<const ThreeArcLane*>(data), phi); }, &lanes_[lane]};
  }
  std::span<const double> breakpoints(std::size_t lane) const override { return {&breaks_[2 * lane], 2}; }
  bool higher_derivatives(std::size_t, double, double&, double&) const override { return false; }
  bool monotone_breaks(std::size_t lane, int order, std::vector<double>& breaks) const override {
    return three_arc_monotone_breaks(lanes_[lane], order, breaks);
  }
  bool lift_integrals(std::size_t lane, double a, double b, double& integral, double& integral_of_square) const override {
    return three_arc_lift_integrals(lanes_[lane], a, b, integral, integral_of_square);
  }

 private:
  std::vector<ThreeArcLane> lanes_;
  // The figures as columns, and the breakpoints -switch_angle, switch_angle of each lane.
  std::vector<double> event_begin_, event_end_, max_lift_, base_radius_, roller_radius_, breaks_;
};

}  // namespace mechgraph::cams
