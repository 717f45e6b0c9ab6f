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
  /// `lanes` lanes of laws of at most `max_pieces` pieces (the Kurz law's three), each to be set
  /// (set()) before a law of it is made.
  ShocklessArray(std::size_t lanes, std::size_t max_pieces);
  /// Lane k as `law`, whose numbers are copied; once per lane, only while the array is being made.
  /// Throws std::invalid_argument for a law that keeps its shapes alive (the array would not) or
  /// has more pieces than the array holds, a lane set already or past the array.
  void set(std::size_t k, const ShocklessLaw& law);

  std::size_t lanes() const override { return views_.size(); }
  CamLawColumns columns() const override;
  void evaluate(const std::uint32_t* lane, const double* phi, std::size_t n, LiftDerivatives* out) const override;
  Point point(std::size_t lane) const override {
    return {[](const void* data, double phi) {
              const auto& v = *static_cast<const LaneView*>(data);
              return shockless_point(v.pieces, v.count, v.half_action, phi);
            },
            &views_[lane]};
  }
  std::span<const double> breakpoints(std::size_t lane) const override {
    return {breaks_.data() + lane * max_breaks_, break_count_[lane]};
  }
  bool higher_derivatives(std::size_t, double, double&, double&) const override { return false; }
  bool monotone_breaks(std::size_t lane, int order, std::vector<double>& breaks) const override {
    return shockless_monotone_breaks({views_[lane].pieces, views_[lane].count}, breakpoints(lane), order, breaks);
  }
  bool lift_integrals(std::size_t lane, double a, double b, double& integral, double& integral_of_square) const override {
    return shockless_lift_integrals({views_[lane].pieces, views_[lane].count}, views_[lane].half_action, a, b, integral,
                                    integral_of_square);
  }

 private:
  // What a point of a lane reads: its pieces (in pieces_, which never moves) and phi_p.
  struct LaneView {
    const ShocklessPiece* pieces = nullptr;
    std::size_t count = 0;  // 0: a lane not set
    double half_action = 0.0;
  };
  std::size_t max_pieces_, max_breaks_;
  // Lane k's pieces from pieces_[k * max_pieces_], its breakpoints from breaks_[k * max_breaks_].
  std::vector<ShocklessPiece> pieces_;
  std::vector<double> breaks_;
  std::vector<LaneView> views_;
  std::vector<std::size_t> break_count_;
  // The figures as columns (the event is -phi_p to phi_p; no roller).
  std::vector<double> event_begin_, event_end_, max_lift_, base_radius_, roller_radius_;
};

}  // namespace mechgraph::cams
