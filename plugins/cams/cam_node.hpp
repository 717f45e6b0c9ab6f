#pragma once
// One NodeType for every cam law: the law-specific part is a description of its own parameters
// and a factory that builds the CamLaw from them; the common parameters (max_lift,
// action_angle, base_radius, ramp, ramp_height, ramp_length, samples) and the common outputs (law, max_velocity,
// max_acceleration, min_acceleration, accel_angle, min_curvature_radius) are added here, so a new
// law is a law class plus a few lines of registration.
#include <mechgraph/block.hpp>
#include <mechgraph/domain/cam_law.hpp>
#include <mechgraph/node.hpp>

#include <cstddef>
#include <functional>
#include <memory>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace mechgraph::cams {

/// The smallest action_angle, 0.1 deg: below it the derivatives (h / phi^2, h / phi^3) leave the
/// range of a double for any lift. Laws derive the least widths of their pieces from it: a piece
/// starting at the start of lift (-action_angle / 2) needs two ulps of that angle to hold a double
/// of its own, and at 0.05 deg (in [2^-11, 2^-10) rad) an ulp is 2^-63 rad.
inline constexpr double min_action_angle = 0.1 * 3.14159265358979323846 / 180.0;
/// One ulp of the start-of-lift angle at the smallest action angle, 2^-63 rad.
inline constexpr double min_start_of_lift_ulp = 0x1p-63;

/// The common cam parameters, already in SI, handed to each law's factory.
struct CamBasics {
  double max_lift = 0.0;      // m
  double action_angle = 0.0;  // rad, total event (cam degrees)
  double base_radius = 0.0;   // m
  /// With CamLawDefinition::derives_lift_and_action the law takes max_lift and action_angle from
  /// its own data; these say whether the scene gave them anyway (to be checked against the data).
  bool has_max_lift = true;
  bool has_action_angle = true;
  /// The node's inputs (CamLawDefinition::extra_inputs) and context (its extra_work_counters).
  const InputSet* inputs = nullptr;
  EvalContext* context = nullptr;
};

/// Builds the law; may also set law-specific outputs (e.g. three-arc radii) in `extra`.
/// Throws NodeError naming the parameter when a request is infeasible.
using CamLawFactory =
    std::function<std::shared_ptr<const CamLaw>(const CamBasics&, const ParamSet&, OutputSet& extra)>;

/// What a law costs to make and how many smooth pieces it has, said from the parameters before
/// anything runs (NodeType::forecast): every search over the law (this node's summary, the valve
/// motion's, a contour's) resolves each piece.
struct CamLawCost {
  double pieces = 16.0;  // smooth pieces of the law (a closed form: a handful); what downstream searches resolve
  /// How many pieces a search may cut each into before it resolves it (a rough table's: 16, the
  /// certified searches' 4 halvings): this node's own summary is counted at that worst case.
  double search_factor = 1.0;
  double items = 0.0;    // work items of making it (reading and fitting a table)
  double memory = 0.0;   // bytes held while making it and by the law
  std::string driver;    // the parameter behind a large cost: "file (about 80000 rows, smoothing none)"
};
using CamLawCostFunction = std::function<CamLawCost(const ParamSet&)>;

/// Case k's law of a block (CamLawDefinition::prepare_block): from its basics, its parameters
/// (the varied ones as case k has them) and k, the index into the block's columns.
using CamLawCaseFactory =
    std::function<std::shared_ptr<const CamLaw>(const CamBasics&, const ParamSet&, std::size_t k, OutputSet& extra)>;
/// Reads, checks and computes once for a block of cases what no case of it changes (choices,
/// lists, which optional parameters are given: only numbers vary in a block) and returns the
/// factory of its cases, which must give each case the very law and extras `make` gives it. An
/// empty function, or a NodeError, where it cannot: then `make` runs per case and says why.
using CamLawBlockFactory = std::function<CamLawCaseFactory(const BlockParams&)>;

struct CamLawDefinition {
  std::string type;     // "cam.kurz"
  int version = 1;
  std::string summary;
  std::vector<ParamSpec> params;        // law-specific parameters only
  std::vector<PortSpec> extra_outputs;  // law-specific outputs only
  std::vector<PortSpec> extra_inputs;   // law-specific inputs (CamBasics::inputs)
  /// Outputs made only when these inputs are connected (NodeInfo::output_dependencies).
  std::map<std::string, std::vector<std::string>> output_dependencies;
  std::vector<std::string> extra_work_counters;
  CamLawFactory make;
  /// The law's cost (absent: a closed form of at most CamLawCost{}.pieces pieces, cheap to make).
  CamLawCostFunction cost;
  /// The law-specific parameters `cost` reads (ForecastReads); absent with a cost: it may read any.
  std::optional<std::vector<std::string>> cost_reads;
  /// Optional: the law's factory for a block of cases (absent: `make` for each case).
  CamLawBlockFactory prepare_block;
  /// The law's data fix its lift and event (a table): max_lift and action_angle become optional.
  bool derives_lift_and_action = false;
  /// Where such a law's lift and event come from, for the parameters' descriptions ("the data",
  /// "the segments").
  std::string derived_from = "the data";
};

std::shared_ptr<const NodeType> make_cam_node_type(CamLawDefinition definition);

}  // namespace mechgraph::cams
