#pragma once
// The Monte Carlo histogram of a stack or chain's result (docs/methods/backlash.md, "Against the
// specification"): the counts of the samples in equal bins, the spec limits marked on its axis.
#include "spec_limits.hpp"
#include "stacking.hpp"

#include <mechgraph/node.hpp>

#include <string>

namespace mechgraph::backlash {

/// `histogram_bins`: bins across the samples' range (default 40).
ParamSpec histogram_bins_param();
/// The `mc_histogram` table output of a node whose result is `what`.
PortSpec mc_histogram_port(const std::string& what);

/// The histogram as a table: axis `axis_name` (the bins' centres, divided by `scale`, of dimension
/// `d` shown in `unit`), channel count; Table::histogram set, the spec limits as axis marks LSL and
/// USL. A note says how many samples fell beyond the bins, when any did.
Table mc_histogram_table(const Histogram& h, const std::string& axis_name, Dimension d, const std::string& unit,
                         const SpecLimits& spec, OutputSet& out, double scale = 1.0);

}  // namespace mechgraph::backlash
