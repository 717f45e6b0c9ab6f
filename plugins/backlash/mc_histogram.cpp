#include "mc_histogram.hpp"

namespace mechgraph::backlash {

ParamSpec histogram_bins_param() {
  return ParamSpec::integer("histogram_bins", "bins of the Monte Carlo histogram (mc_histogram) across the samples' range (a streamed run of "
                            "more than 131072 samples lays them across a pilot's range: up to half as many again)")
      .with_default(40.0)
      .at_least(2)
      .at_most(1e5)
      .because("2 to 100,000 bins: a histogram needs two, more than a sample fills");
}

PortSpec mc_histogram_port(const std::string& what) {
  return PortSpec::table("mc_histogram", "Monte Carlo samples of " + what +
                                             " counted in histogram_bins equal bins (axis: the bins' centres), the spec "
                                             "limits marked (with monte_carlo)");
}

Table mc_histogram_table(const Histogram& h, const std::string& axis_name, Dimension d, const std::string& unit,
                         const SpecLimits& spec, OutputSet& out, double scale) {
  Table t;
  t.histogram = true;
  t.axis = {axis_name, d, {}, unit};
  Table::Column& count = t.add_channel("count", dim::none);
  for (std::size_t k = 0; k < h.counts.size(); ++k) {
    t.axis.values.push_back((h.low + (static_cast<double>(k) + 0.5) * h.width) / scale);
    count.values.push_back(static_cast<double>(h.counts[k]));
  }
  if (spec.lower) t.axis_marks.push_back({"LSL", *spec.lower});
  if (spec.upper) t.axis_marks.push_back({"USL", *spec.upper});
  if (h.under + h.over > 0)
    out.note("mc_histogram: " + std::to_string(h.under) + " samples below and " + std::to_string(h.over) +
             " above its bins (laid over the range of a pilot of the first samples)");
  return t;
}

}  // namespace mechgraph::backlash
