#pragma once
// The work-precision plot of `mechgraph bench` (docs/bench.md): the data and the gnuplot script
// that draws it as SVG, one line per measured knob, error over time on log axes. The host runs
// gnuplot on them (the script reads `bench.dat` and writes `bench.svg` in its folder).
//
// Every text that reaches the plot passes through gnuplot_string and is drawn `noenhanced`, so
// `curve_points` is not a subscript and `^ { } @` are not markup (text_escape.hpp says which
// characters gnuplot_string replaces by look-alikes).
#include <mechgraph/knob_bench.hpp>

#include <string>

namespace mechgraph {

struct BenchPlot {
  std::string data;    // bench.dat: per knob a block "seconds error uncertainty is_default"
  std::string script;  // bench.gp
};

/// A setting's point: at its error, or at the reference's floor when the error is below it (the
/// error is then not known better); errors of exactly zero at 1e-17, below double precision. A
/// Monte Carlo error carries its uncertainty as an error bar. Failed settings are left out.
BenchPlot bench_plot(const KnobBench& bench);

}  // namespace mechgraph
