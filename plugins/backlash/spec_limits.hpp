#pragma once
// A result against its specification (docs/methods/backlash.md, "Against the specification"):
// `spec: { lower, upper }` (either may be left out) on a stack or chain gives
//  - from the normal model of the RSS result (mean mu, sigma):
//      Cp = (USL - LSL) / (6 sigma)                      (both limits)
//      Cpk = min(USL - mu, mu - LSL) / (3 sigma)          (the limits given)
//      ppm = 1e6 (Phi((LSL - mu)/sigma) + 1 - Phi((USL - mu)/sigma))
//  - from Monte Carlo (N samples, k outside): ppm = 1e6 k/N with standard error
//      1e6 sqrt(p (1 - p) / N), and Cp, Cpk from the sample mean and sigma.
#include "stacking.hpp"

#include <mechgraph/node.hpp>

#include <optional>
#include <string>
#include <vector>

namespace mechgraph::backlash {

struct SpecLimits {
  std::optional<double> lower, upper;
  bool given() const { return lower || upper; }
  SampleLimits sample_limits(double scale = 1.0) const;  // limits * scale (e.g. an angle to a rod play)
};

/// The `spec` parameter: one record { lower, upper } of dimension `d` shown in `unit`.
ParamSpec spec_param(Dimension d, const std::string& unit, const std::string& what);
/// Reads `spec` (absent: no limits); throws NodeError("spec", ...) when lower >= upper or neither is given.
SpecLimits read_spec(const ParamSet& p);

struct Capability {
  std::optional<double> cp;  // both limits
  double cpk = 0.0;
  double ppm = 0.0;
};
/// The normal model's capability; sigma > 0 (with sigma = 0: Cp/Cpk infinite, so an error naming spec).
Capability normal_capability(double mean, double sigma, const SpecLimits& spec);

/// The output ports a stack or chain adds for its spec.
std::vector<PortSpec> spec_outputs(bool monte_carlo);
/// Sets cp, cpk, out_of_spec (a share, shown in ppm) from the RSS model and, with a Monte Carlo summary,
/// mc_out_of_spec, mc_out_of_spec_error, mc_cp, mc_cpk; the summary's counts must have been made with spec.sample_limits(scale).
void set_spec_outputs(OutputSet& out, const SpecLimits& spec, double mean, double sigma, const SampleSummary* mc,
                      double mc_scale = 1.0);
/// The Monte Carlo note's addition: "k of N outside spec" (with the 95 % bound 3/N when k = 0).
std::string spec_note(const SampleSummary& mc);

}  // namespace mechgraph::backlash
