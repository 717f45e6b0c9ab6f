#pragma once
// A fit between a hole and a shaft of one nominal size (docs/methods/backlash.md, steps 1-2):
// each part's limit deviations; the clearance S = hole - shaft, its limits and mean; and the
// clearance as a PlayTerm for stacking (hole +1, shaft -1, each with its distribution).
// Preconditions: nominal > 0; each part's upper deviation >= its lower one, all finite. The fit's
// node checks them (a table look-up, an explicit pair); the conformance kit checks them and the
// clearance term's consistency on any fit a plugin makes.
#include <mechgraph/domain/tolerance.hpp>

#include <string>

namespace mechgraph {

struct LimitPair {
  double upper = 0.0;  // deviation from nominal, m (ES / es)
  double lower = 0.0;  // (EI / ei)
  double mean() const { return 0.5 * (upper + lower); }        // the source's (dB + dH) / 2
  double half_range() const { return 0.5 * (upper - lower); }  // the source's dA = (dB - dH) / 2
};

class MECHGRAPH_INTERFACE Fit final : public DomainObject {
 public:
  ~Fit() override;  // out of line (key function, sdk/src/interfaces.cpp)
  static constexpr std::string_view kind_name = "fit";
  std::string_view kind() const override { return kind_name; }

  Fit(std::string designation, double nominal, LimitPair hole, LimitPair shaft, Distribution hole_distribution,
      Distribution shaft_distribution)
      : designation_(std::move(designation)),
        nominal_(nominal),
        hole_(hole),
        shaft_(shaft),
        hole_distribution_(hole_distribution),
        shaft_distribution_(shaft_distribution) {}

  const std::string& designation() const { return designation_; }  // "20 H11/d11" or "20 explicit"
  double nominal() const { return nominal_; }
  const LimitPair& hole() const { return hole_; }
  const LimitPair& shaft() const { return shaft_; }
  Distribution hole_distribution() const { return hole_distribution_; }
  Distribution shaft_distribution() const { return shaft_distribution_; }
  double clearance_min() const { return hole_.lower - shaft_.upper; }
  double clearance_max() const { return hole_.upper - shaft_.lower; }
  double clearance_mean() const { return hole_.mean() - shaft_.mean(); }

  /// The clearance as a play term: hole diameter (+1) minus shaft diameter (-1). The links hold
  /// the deviations from nominal (the nominal cancels, and leaving it out keeps the digits).
  PlayTerm clearance_term() const {
    return {designation_,
            {{designation_ + " hole", hole_.mean(), hole_.half_range(), +1.0, hole_distribution_},
             {designation_ + " shaft", shaft_.mean(), shaft_.half_range(), -1.0, shaft_distribution_}}};
  }

 private:
  std::string designation_;
  double nominal_;
  LimitPair hole_, shaft_;
  Distribution hole_distribution_, shaft_distribution_;
};

}  // namespace mechgraph
