#pragma once
// Toleranced quantities and free play, as fits, joints and chains pass them on
// (docs/methods/backlash.md). Plain data: immutable once made, shared between nodes.
//
//  - A ToleranceLink is one toleranced size: mean value, half its tolerance (the source's limit
//    deviation dA = (dB - dH)/2), a distribution across that range, and a sensitivity (how much
//    of it reaches the stacked result; -1 for a shaft in a clearance, k_i for a lever ...).
//  - A PlayTerm is one source of free play: play = max(0, sum_j sensitivity_j * X_j), X_j drawn
//    from link j. A fit's clearance is [hole +1, shaft -1]; a bearing's internal clearance is one
//    link. Truncation at zero is why statistical stacking of play is not linear.
//  - JointPlay is what a joint passes on: its play terms along the joint's line of action.
// Preconditions: links finite, half ranges >= 0, at least one term. The joint's node makes them so;
// the conformance kit (check_joint_play) checks them; distributions are named and parsed in one place
// (distribution_param, distribution_from below).
#include <mechgraph/node.hpp>
#include <mechgraph/value.hpp>

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace mechgraph {

/// How a toleranced size is spread over its range [mean - half_range, mean + half_range]:
/// normal with the range = 6 sigma (the default), uniform, or symmetric triangular.
enum class Distribution { normal, uniform, triangular };

std::string_view to_string(Distribution d);
/// The one place distributions are named, in the order scenes list them: normal, uniform, triangular.
const std::vector<std::string>& distribution_names();
/// "normal", "uniform" or "triangular"; nullopt for anything else (names are exact, lower case).
std::optional<Distribution> parse_distribution(std::string_view name);
/// The parser every node uses: the distribution named `text`, else NodeError(parameter, "<context>:
/// distribution 'x' is not one of normal, uniform, triangular").
Distribution distribution_from(std::string_view text, const std::string& parameter, const std::string& context = {});
/// A choice parameter (or record field) naming a distribution, default normal.
ParamSpec distribution_param(std::string name, std::string doc);
/// The standard deviation of a link of half-range `half_range` under distribution `d`:
/// normal T/6 = half/3; uniform half/sqrt(3); triangular half/sqrt(6).
double standard_deviation(Distribution d, double half_range);

struct ToleranceLink {
  std::string label;
  double mean = 0.0;        // SI
  double half_range = 0.0;  // >= 0
  double sensitivity = 1.0;
  Distribution distribution = Distribution::normal;
};

struct PlayTerm {
  std::string label;
  std::vector<ToleranceLink> links;

  /// sum sensitivity * mean, not truncated (negative = interference).
  double mean() const;
  /// Worst-case limits of the untruncated sum: mean -+ sum |sensitivity| * half_range.
  double lower() const;
  double upper() const;
  /// Worst case of the play itself: max(0, lower()), max(0, upper()).
  double play_min() const;
  double play_max() const;
};

/// A joint's free play along its line of action.
class MECHGRAPH_INTERFACE JointPlay final : public DomainObject {
 public:
  ~JointPlay() override;  // out of line (key function, sdk/src/interfaces.cpp)
  static constexpr std::string_view kind_name = "joint_play";
  std::string_view kind() const override { return kind_name; }

  JointPlay(std::string joint, std::vector<PlayTerm> terms) : joint_(std::move(joint)), terms_(std::move(terms)) {}
  const std::string& joint() const { return joint_; }
  const std::vector<PlayTerm>& terms() const { return terms_; }
  double play_min() const;
  double play_max() const;

 private:
  std::string joint_;
  std::vector<PlayTerm> terms_;
};

}  // namespace mechgraph
