#pragma once
// Polydyne laws of one exponent set over the cases of a block (mechgraph/domain/cam_law_array.hpp):
// lane k is case k's half action angle and lift, the series shared by every lane. Every answer
// comes from the functions PolydyneLaw answers by (polydyne_point and its neighbours), so lane k
// gives the bits of the scalar law of case k.
#include "polydyne.hpp"

#include <mechgraph/domain/cam_law_array.hpp>

#include <cstddef>
#include <memory>
#include <vector>

namespace mechgraph::cams {

class PolydyneArray final : public CamLawArray {
 public:
  /// `lanes` lanes of the exponent set of `series`, each to be set (set()) before a law of it is made.
  PolydyneArray(std::size_t lanes, std::shared_ptr<const PolydyneSeries> series);
  /// Lane k: the law PolydyneLaw(max_lift, action_angle, base_radius, series) would be. Only while
  /// the array is being made: the columns never move.
  void set(std::size_t k, double max_lift, double action_angle, double base_radius);

  std::size_t lanes() const override { return lanes_.size(); }
  CamLawColumns columns() const override;
  void evaluate(const std::uint32_t* lane, const double* phi, std::size_t n, LiftDerivatives* out) const override;
  Point point(std::size_t lane) const override {
    return {[](const void* data, double phi) { return polydyne_point(*static_cast<const PolydyneLane*>(data), phi); }, &lanes_[lane]};
  }
  std::span<const double> breakpoints(std::size_t) const override { return {}; }
  bool higher_derivatives(std::size_t lane, double phi, double& d4, double& d5) const override {
    polydyne_higher_derivatives(lanes_[lane], phi, d4, d5);
    return true;
  }
  bool monotone_breaks(std::size_t lane, int order, std::vector<double>& breaks) const override {
    return polydyne_monotone_breaks(lanes_[lane], order, breaks);
  }
  bool lift_integrals(std::size_t lane, double a, double b, double& integral, double& integral_of_square) const override {
    polydyne_lift_integrals(lanes_[lane], a, b, integral, integral_of_square);
    return true;
  }

 private:
  std::shared_ptr<const PolydyneSeries> series_;  // what every lane points at
  std::vector<PolydyneLane> lanes_;
  // The figures as columns (the event is -phi_p to phi_p; no roller).
  std::vector<double> event_begin_, event_end_, max_lift_, base_radius_, roller_radius_;
};

}  // namespace mechgraph::cams
