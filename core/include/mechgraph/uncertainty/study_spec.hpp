#pragma once
// A scene's `uncertainty:` block read into a study: which parameters are uncertain and how they
// are spread, how they are sampled, and what the answers are checked against (spec limits,
// events). Names and shape follow the scene's rules: every value with its unit, every error with
// file:line:column and, for an unknown key, the valid ones. The scene format is in
// docs/scenes.md ("Uncertainty"), the method in docs/methods/uncertainty.md.
//
//   uncertainty:
//     method: sobol            # monte_carlo | latin_hypercube (default) | sobol
//     samples: 1024            # N; with sensitivity: N (d + 2) evaluations
//     seed: 1
//     sensitivity: true        # Sobol' indices (Saltelli design)
//     parameters:
//       gap:           { normal: { nominal: 0.25 mm, tolerance: 0.03 mm, cp: 1.33 } }
//       arm.ratio:     { uniform: { lower: 1.48, upper: 1.52 } }
//       part.stiffness: { triangular: { lower: 30 N/mm, mode: 32 N/mm, upper: 33 N/mm } }
//       part.length:   { normal: { mean: 8 mm, sigma: 0.01 mm }, truncate: { lower: 7.98 mm } }
//       bore:          { iso286: { size: 20 mm, class: H7 } }
//     correlations: [ [gap, arm.ratio, 0.3] ]
//     limits: { out.angle: { lower: -60 deg, upper: -50 deg } }
//     events: { contact: { output: sim.contacts, above: 0 }, refused: { failure: evaluation } }
#include <mechgraph/scene.hpp>
#include <mechgraph/uncertainty/distribution.hpp>

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace mechgraph {

enum class SamplingMethod { monte_carlo, latin_hypercube, sobol };
std::string to_string(SamplingMethod m);

struct UncertainParameter {
  std::string name;       // as --set names it: "gap" (a scene parameter), "part.length"
  Marginal marginal;
  std::string unit;       // the unit it was written in ("" for SI or dimensionless)
  std::string written;    // the distribution as written, for tables and provenance
  SourceLocation where;
};

struct ParameterCorrelation {
  std::size_t first = 0, second = 0;  // indices into StudySpec::parameters
  double rho = 0.0;                    // Gaussian copula correlation, -1 < rho < 1
  SourceLocation where;
};

struct SpecLimits {
  std::string output;                  // "node.port"
  std::optional<double> lower, upper;  // SI
  Dimension dimension;                 // of the limits as written (dimensionless for bare numbers)
  SourceLocation where;
  bool lower_bare = false, upper_bare = false;  // written without a unit (a plain number)
};

struct StudyEvent {
  std::string name;
  enum class Kind { above, below, failure } kind = Kind::above;
  std::string output;       // above/below: "node.port"
  double threshold = 0.0;   // SI
  Dimension dimension;      // of the threshold as written (dimensionless for a bare number)
  enum class Failure { any, scene, evaluation } failure = Failure::any;
  SourceLocation where;
  bool bare = false;        // the threshold written without a unit (a plain number)
};

struct StudySpec {
  std::vector<UncertainParameter> parameters;
  std::vector<ParameterCorrelation> correlations;
  SamplingMethod method = SamplingMethod::latin_hypercube;
  std::size_t samples = 1000;
  std::uint64_t seed = 1;
  bool sensitivity = false;
  std::size_t bootstrap = 200;    // bootstrap resamples of the Sobol' indices (0: none)
  double confidence = 0.95;       // of every interval
  std::vector<double> quantiles{0.01, 0.05, 0.5, 0.95, 0.99};
  std::size_t bins = 20;          // histogram bins
  std::vector<SpecLimits> limits;
  std::vector<StudyEvent> events;

  /// How many evaluations the design asks for: N, or N (d + 2) with sensitivity.
  std::size_t evaluations() const;
};

/// The most base samples of a study (max_sweep_cases, 2.5 x 10^8, a sweep's case limit; with
/// sensitivity the evaluations N (d + 2) must stay within it too, and the design's table within
/// max_design_values) and the most uncertain parameters (1000).
inline constexpr std::size_t max_study_parameters = 1000;

/// ISO 286 limits of `tolerance_class` (H7, g6) at nominal `size` (SI): {lower, upper} deviation
/// in SI. The host answers it with the fits plugin (fit.iso286); throws std::exception when it cannot.
using Iso286Limits = std::function<std::pair<double, double>(double size, const std::string& tolerance_class)>;

/// Reads `block` (the scene's `uncertainty:`). Throws SceneError "file:line:column: ...".
StudySpec parse_study(const RawValue& block, const Iso286Limits& iso286);

/// One distribution as YAML would write it, e.g. from Python: {normal: {mean: ..., sigma: ...}}.
UncertainParameter parse_uncertain_parameter(const std::string& name, const RawValue& value, const Iso286Limits& iso286);

}  // namespace mechgraph
