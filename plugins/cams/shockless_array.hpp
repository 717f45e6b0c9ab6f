#pragma once
// Shockless laws over the cases of a block (mechgraph/domain/cam_law_array.hpp): lane k holds the
// pieces and breakpoints of case k's ShocklessLaw, and every answer comes from the functions that
// law answers by (shockless_point, shockless_monotone_breaks, shockless_lift_integrals), so lane k
// gives the bits of the scalar law of case k. For laws whose shapes outlive every law (the Kurz
// law's, never destroyed): the array keeps no shape alive.
#include "shockless.hpp"

#include <mechgraph/domain/cam_law_array.hpp>

#include <cstddef>
#include <vector>

namespace mechgraph::cams {

class ShocklessArray final : public CamLawArray {
 public:
  /// `lanes` lanes, each to be set (set()) before a law of it is made.
  explicit ShocklessArray(std::size_t lanes);
  /// Lane k as `law`, whose numbers are copied; once per lane, only while the array is being made.
  /// Throws std::invalid_argument for a law that keeps its shapes alive (the array would not), a
  /// lane set already or past the array.
  void set(std::size_t k, const ShocklessLaw& law);

  std::size_t lanes() const override { return half_action_.size(); }
  CamLawColumns columns() const override;
  void evaluate(const std::uint32_t* lane, const double* phi, std::size_t n, LiftDerivatives* out) const override;
  LiftDerivatives evaluate_one(std::size_t lane, double phi) const override {
    return shockless_point(pieces_.data() + piece_from_[lane], piece_count_[lane], half_action_[lane], phi);
  }
  std::span<const double> breakpoints(std::size_t lane) const override {
    return {breaks_.data() + break_from_[lane], break_count_[lane]};
  }
  bool higher_derivatives(std::size_t, double, double&, double&) const override { return false; }
  bool monotone_breaks(std::size_t lane, int order, std::vector<double>& breaks) const override {
    return shockless_monotone_breaks(pieces_of(lane), breakpoints(lane), order, breaks);
  }
  bool lift_integrals(std::size_t lane, double a, double b, double& integral, double& integral_of_square) const override {
    return shockless_lift_integrals(pieces_of(lane), half_action_[lane], a, b, integral, integral_of_square);
  }

 private:
  std::span<const ShocklessPiece> pieces_of(std::size_t lane) const {
    return {pieces_.data() + piece_from_[lane], piece_count_[lane]};
  }

  // The figures as columns (the event is -phi_p to phi_p; no roller).
  std::vector<double> event_begin_, half_action_, max_lift_, base_radius_, roller_radius_;
  // Lane k's pieces are piece_count_[k] from pieces_[piece_from_[k]], its breakpoints likewise (a
  // lane not set holds none).
  std::vector<ShocklessPiece> pieces_;
  std::vector<double> breaks_;
  std::vector<std::size_t> piece_from_, piece_count_, break_from_, break_count_;
};

}  // namespace mechgraph::cams
