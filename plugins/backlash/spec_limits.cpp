#include "spec_limits.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace mechgraph::backlash {

SampleLimits SpecLimits::sample_limits(double scale) const {
  SampleLimits l;
  if (lower) l.lower = *lower * scale;
  if (upper) l.upper = *upper * scale;
  return l;
}

ParamSpec spec_param(Dimension d, const std::string& unit, const std::string& what) {
  return ParamSpec::record_list("spec",
                                {ParamSpec::number("lower", d, "lower specification limit LSL", unit).optional(),
                                 ParamSpec::number("upper", d, "upper specification limit USL", unit).optional()},
                                "specification limits of " + what +
                                    ", e.g. spec: { upper: 0.5 mm } or { lower: .., upper: .. }: adds Cp, Cpk and the share "
                                    "out of spec (ppm), from the RSS model and from Monte Carlo")
      .optional();
}

SpecLimits read_spec(const ParamSet& p) {
  SpecLimits s;
  if (!p.has("spec")) return s;
  const auto& records = p.records("spec");
  if (records.size() != 1) throw NodeError("spec", "spec is one record { lower, upper }, not a list of " + std::to_string(records.size()));
  const Record& r = records.front();
  if (auto it = r.find("lower"); it != r.end()) s.lower = it->second.number;
  if (auto it = r.find("upper"); it != r.end()) s.upper = it->second.number;
  if (!s.given()) throw NodeError("spec", "spec needs a lower or an upper limit (or both)");
  if (s.lower && s.upper && !(*s.lower < *s.upper)) {
    std::ostringstream m;
    m << "spec lower " << *s.lower << " must be below upper " << *s.upper << " (SI)";
    throw NodeError("spec", m.str());
  }
  return s;
}

Capability normal_capability(double mean, double sigma, const SpecLimits& spec) {
  if (!(sigma > 0.0))
    throw NodeError("spec", "the result has no spread (sigma = 0): Cp and Cpk are infinite; a spec needs toleranced links");
  Capability c;
  // P(X < LSL) = erfc((mu - LSL) / (sigma sqrt 2)) / 2, P(X > USL) = erfc((USL - mu) / (sigma sqrt 2)) / 2.
  double cpk = std::numeric_limits<double>::infinity();
  if (spec.lower) {
    cpk = std::min(cpk, (mean - *spec.lower) / (3.0 * sigma));
    c.ppm += 0.5e6 * std::erfc((mean - *spec.lower) / (sigma * std::sqrt(2.0)));
  }
  if (spec.upper) {
    cpk = std::min(cpk, (*spec.upper - mean) / (3.0 * sigma));
    c.ppm += 0.5e6 * std::erfc((*spec.upper - mean) / (sigma * std::sqrt(2.0)));
  }
  if (spec.lower && spec.upper) c.cp = (*spec.upper - *spec.lower) / (6.0 * sigma);
  c.cpk = cpk;
  return c;
}

std::vector<PortSpec> spec_outputs(bool monte_carlo) {
  std::vector<PortSpec> ports{
      PortSpec::scalar("cp", dim::none, "(USL - LSL)/(6 sigma), RSS model (with spec, both limits)"),
      PortSpec::scalar("cpk", dim::none, "min(USL - mean, mean - LSL)/(3 sigma), RSS model (with spec)"),
      PortSpec::scalar("out_of_spec", dim::none, "share outside spec, normal RSS model (with spec)", "ppm"),
  };
  if (monte_carlo) {
    ports.push_back(PortSpec::scalar("mc_out_of_spec", dim::none, "share of Monte Carlo samples outside spec (with spec and monte_carlo)", "ppm"));
    ports.push_back(PortSpec::scalar("mc_out_of_spec_error", dim::none, "standard error of mc_out_of_spec, sqrt(p(1-p)/N) (with spec and monte_carlo)", "ppm"));
    ports.push_back(PortSpec::scalar("mc_cp", dim::none, "Cp from the Monte Carlo sigma (with spec, both limits, and monte_carlo)"));
    ports.push_back(PortSpec::scalar("mc_cpk", dim::none, "Cpk from the Monte Carlo mean and sigma (with spec and monte_carlo)"));
  }
  return ports;
}

void set_spec_outputs(OutputSet& out, const SpecLimits& spec, double mean, double sigma, const SampleSummary* mc,
                      double mc_scale) {
  if (!spec.given()) return;
  const Capability c = normal_capability(mean, sigma, spec);
  if (c.cp) out.set_scalar("cp", *c.cp);
  out.set_scalar("cpk", c.cpk);
  out.set_scalar("out_of_spec", 1e-6 * c.ppm);
  if (!mc) return;
  const double n = static_cast<double>(mc->count);
  const double p = static_cast<double>(mc->below + mc->above) / n;
  out.set_scalar("mc_out_of_spec", p);
  out.set_scalar("mc_out_of_spec_error", std::sqrt(p * (1.0 - p) / n));
  const Capability m = normal_capability(mc->mean / mc_scale, mc->sigma / mc_scale, spec);
  if (m.cp) out.set_scalar("mc_cp", *m.cp);
  out.set_scalar("mc_cpk", m.cpk);
}

std::string spec_note(const SampleSummary& mc) {
  std::ostringstream s;
  const std::size_t k = mc.below + mc.above;
  s << k << " of " << mc.count << " samples outside spec (" << mc.below << " below, " << mc.above << " above)";
  if (k == 0) s << "; at 95 % confidence the share is below 3/N = " << 3e6 / static_cast<double>(mc.count) << " ppm";
  return s.str();
}

}  // namespace mechgraph::backlash
