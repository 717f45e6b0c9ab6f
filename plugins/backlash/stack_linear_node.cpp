// stack.linear: a one-dimensional tolerance stack Y = sum_i s_i X_i, by worst case, RSS and
// (with the monte_carlo effect) Monte Carlo (docs/methods/backlash.md, "Stacking: worst
// case, RSS, Monte Carlo"; the formulas are in stacking.hpp).
// A link is a part's size: nominal with its upper and lower limit deviations, so its mean is
// m = nominal + (upper + lower)/2 and its half tolerance h = (upper - lower)/2 (the source's
// A = A_nom + (dB + dH)/2, dA = (dB - dH)/2).
#include "node_types.hpp"
#include "mc_histogram.hpp"
#include "spec_limits.hpp"
#include "monte_carlo_sampler.hpp"
#include "stacking.hpp"

#include <mechgraph/domain/tolerance.hpp>

#include <cmath>
#include <optional>

namespace mechgraph::backlash {
namespace {

Series indexed_series(std::vector<double> values, std::vector<std::string> labels = {}) {
  Series s;
  for (std::size_t i = 0; i < values.size(); ++i) s.axis.push_back(static_cast<double>(i));
  s.values = std::move(values);
  s.axis_dimension = dim::none;
  s.labels = std::move(labels);
  return s;
}

class StackLinearType final : public NodeType {
 public:
  StackLinearType() {
    info_.type = "stack.linear";
    info_.version = 2;  // 2: the fused sampler (other samples for a seed)
    info_.summary = "one-dimensional tolerance stack sum s_i X_i: worst case, RSS and Monte Carlo, with each link's share";
    info_.params = {
        ParamSpec::record_list(
            "links",
            {
                // Ranges that keep every sum, square and sample of a stack finite (a km-sized part,
                // tolerances to 100 m, lever ratios to 1e6).
                ParamSpec::number("nominal", dim::length, "nominal size of the part", "mm").at_least(-1e3).at_most(1e3).because("within 1 km either way: far past any stack"),
                ParamSpec::number("upper", dim::length, "upper limit deviation of the part from nominal (es, ES)", "mm")
                    .at_least(-100.0)
                    .at_most(100.0)
                    .because("within 100 m either way: far past any tolerance"),
                ParamSpec::number("lower", dim::length, "lower limit deviation of the part from nominal (ei, EI)", "mm")
                    .at_least(-100.0)
                    .at_most(100.0)
                    .because("within 100 m either way: far past any tolerance"),
                ParamSpec::number("sensitivity", dim::none,
                                  "how much of the part reaches the result (+1 opens the gap, -1 closes it; a lever ratio)")
                    .with_default(1.0)
                    .at_least(-1e6)
                    .at_most(1e6)
                    .because("within 1e6 either way: far past any lever"),
                distribution_param("distribution",
                                   "spread over the tolerance: normal with T = 6 sigma, uniform, or symmetric triangular"),
                ParamSpec::text("label", "name of the link in reports").optional(),
            },
            "the parts of the stack, each { nominal, upper, lower, sensitivity, distribution, label }"),
        samples_param(),
        seed_param(),
        threads_param(),
        spec_param(dim::length, "mm", "the stack's result"),
        histogram_bins_param(),
    };
    const auto L = dim::length;
    info_.outputs = {
        PortSpec::scalar("mean", L, "mean of the stack, sum s_i (nominal_i + (upper_i + lower_i)/2)", "mm"),
        PortSpec::scalar("worst_case_min", L, "worst case minimum, mean - sum |s_i| T_i/2", "mm"),
        PortSpec::scalar("worst_case_max", L, "worst case maximum, mean + sum |s_i| T_i/2", "mm"),
        PortSpec::scalar("rss_sigma", L, "RSS standard deviation sqrt(sum s_i^2 sigma_i^2)", "mm"),
        PortSpec::scalar("rss_min", L, "mean - 3 rss_sigma", "mm"),
        PortSpec::scalar("rss_max", L, "mean + 3 rss_sigma", "mm"),
        PortSpec::series("contribution_worst_case", dim::none,
                         "share of each link in the worst case, |s_i| T_i/2 / sum (axis: link index; labelled by link)", "%"),
        PortSpec::series("contribution_rss", dim::none,
                         "share of each link in the RSS variance, s_i^2 sigma_i^2 / sum (axis: link index; labelled by link)",
                         "%"),
        PortSpec::scalar("mc_mean", L, "Monte Carlo mean (with monte_carlo)", "mm"),
        PortSpec::scalar("mc_sigma", L, "Monte Carlo standard deviation (with monte_carlo)", "mm"),
        PortSpec::scalar("mc_min", L, "smallest Monte Carlo sample (with monte_carlo)", "mm"),
        PortSpec::scalar("mc_max", L, "largest Monte Carlo sample (with monte_carlo)", "mm"),
        PortSpec::scalar("mc_q001", L, "Monte Carlo quantile at 0.135 %, the -3 sigma equivalent (with monte_carlo)", "mm"),
        PortSpec::scalar("mc_q999", L, "Monte Carlo quantile at 99.865 %, the +3 sigma equivalent (with monte_carlo)", "mm"),
        PortSpec::scalar("mc_mean_error", L, "standard error of mc_mean, mc_sigma/sqrt(N) (with monte_carlo)", "mm"),
        PortSpec::scalar("mc_sigma_error", L, "standard error of mc_sigma, mc_sigma/sqrt(2(N-1)) (with monte_carlo)", "mm"),
    };
    for (PortSpec& port : spec_outputs(true)) info_.outputs.push_back(std::move(port));
    info_.outputs.push_back(mc_histogram_port("the stack"));
    info_.effects = {{monte_carlo_effect, "sample every link from its distribution (samples, seed) and report the "
                                          "sample statistics with their standard errors and histogram",
                      {"mc_mean", "mc_sigma", "mc_min", "mc_max", "mc_q001", "mc_q999", "mc_mean_error", "mc_sigma_error",
                       "mc_out_of_spec", "mc_out_of_spec_error", "mc_cp", "mc_cpk", "mc_histogram"},
                      {"samples", "seed", "threads", "histogram_bins"}}};
    info_.work_counters = {"samples", "chunks"};
  }
  const NodeInfo& info() const override { return info_; }

  void evaluate(const ParamSet& p, const InputSet&, OutputSet& out, EvalContext& ctx) const override {
    const std::vector<ToleranceLink> links = read_links(p.records("links"));
    const LinearStack s = stack_linear(links);
    out.set_scalar("mean", s.mean);
    out.set_scalar("worst_case_min", s.mean - s.worst_case_half);
    out.set_scalar("worst_case_max", s.mean + s.worst_case_half);
    out.set_scalar("rss_sigma", s.rss_sigma);
    out.set_scalar("rss_min", s.mean - 3.0 * s.rss_sigma);
    out.set_scalar("rss_max", s.mean + 3.0 * s.rss_sigma);
    std::vector<std::string> names;
    for (std::size_t i = 0; i < links.size(); ++i)
      names.push_back(links[i].label.empty() ? "link " + std::to_string(i) : links[i].label);
    out.set("contribution_worst_case", Value::series(indexed_series(s.contribution_worst_case, names)));
    out.set("contribution_rss", Value::series(indexed_series(s.contribution_rss, names)));

    const SpecLimits spec = read_spec(p);
    if (!ctx.effect(monte_carlo_effect)) {
      set_spec_outputs(out, spec, s.mean, s.rss_sigma, nullptr);
      return;
    }
    const std::size_t n = read_samples(p);
    const std::uint64_t seed = read_seed(p);
    const std::size_t bins = ctx.wanted("mc_histogram") ? static_cast<std::size_t>(p.integer("histogram_bins")) : 0;
    SamplerWork work;
    const SampleSummary mc = monte_carlo(sampled_stack(links), n, seed, spec.sample_limits(), bins, read_threads(p), &work);
    if (bins) out.set("mc_histogram", Value::table(mc_histogram_table(mc.histogram, "stack", dim::length, "mm", spec, out)));
    ctx.report_work("samples", static_cast<double>(n));
    ctx.report_work("chunks", static_cast<double>(work.chunks));
    out.note(monte_carlo_note(n, seed, mc.mean_error));
    if (spec.given()) out.note(spec_note(mc));
    set_spec_outputs(out, spec, s.mean, s.rss_sigma, &mc);
    out.set_scalar("mc_mean", mc.mean);
    out.set_scalar("mc_sigma", mc.sigma);
    out.set_scalar("mc_min", mc.min);
    out.set_scalar("mc_max", mc.max);
    out.set_scalar("mc_q001", mc.q_low);
    out.set_scalar("mc_q999", mc.q_high);
    out.set_scalar("mc_mean_error", mc.mean_error);
    out.set_scalar("mc_sigma_error", mc.sigma_error);
  }

 private:
  static std::vector<ToleranceLink> read_links(const std::vector<Record>& records) {
    if (records.empty()) throw NodeError("links", "links is empty: a stack needs at least one link");
    std::vector<ToleranceLink> links;
    for (std::size_t i = 0; i < records.size(); ++i) {
      const Record& r = records[i];
      const std::string entry = "links entry " + std::to_string(i);
      auto number = [&](const char* field, std::optional<double> fallback) {
        const auto it = r.find(field);
        if (it == r.end()) {
          if (fallback) return *fallback;
          throw NodeError("links", entry + ": field '" + field + "' is required");
        }
        if (!std::isfinite(it->second.number))
          throw NodeError("links", entry + ": field '" + field + "' must be a finite number");
        return it->second.number;
      };
      ToleranceLink l;
      const double nominal = number("nominal", std::nullopt);
      const double upper = number("upper", std::nullopt);
      const double lower = number("lower", std::nullopt);
      l.sensitivity = number("sensitivity", 1.0);
      if (const auto it = r.find("label"); it != r.end()) l.label = it->second.text;
      if (const auto it = r.find("distribution"); it != r.end())
        l.distribution = distribution_from(it->second.text, "links", entry);
      if (upper < lower)
        throw NodeError("links", entry + (l.label.empty() ? "" : " ('" + l.label + "')") + ": upper deviation " +
                                     mm_text(upper) + " is below the lower deviation " + mm_text(lower) +
                                     " (upper must be >= lower)");
      l.mean = nominal + 0.5 * (upper + lower);
      l.half_range = 0.5 * (upper - lower);
      links.push_back(std::move(l));
    }
    return links;
  }

  NodeInfo info_;
};

}  // namespace

std::shared_ptr<const NodeType> make_stack_linear_type() { return std::make_shared<const StackLinearType>(); }

}  // namespace mechgraph::backlash
