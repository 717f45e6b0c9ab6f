#include <mechgraph/bench_plot.hpp>

#include <mechgraph/text_escape.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

namespace mechgraph {

BenchPlot bench_plot(const KnobBench& bench) {
  BenchPlot plot;
  std::vector<std::string> titles;
  for (const KnobStudy& study : bench.knobs) {
    std::string block;
    for (std::size_t i = study.first_trial; i < study.first_trial + study.trial_count; ++i) {
      const KnobTrial& t = bench.trials[i];
      if (!t.failure.empty() || !(t.seconds > 0)) continue;
      double error = t.max_relative_error;
      if (t.below_floor) error = t.reference_floor;
      char line[96];
      std::snprintf(line, sizeof line, "%.6g %.6g %.6g %d\n", t.seconds, std::max(error, 1e-17), t.error_uncertainty,
                    t.is_default ? 1 : 0);
      block += line;
    }
    if (block.empty()) continue;
    if (!titles.empty()) plot.data += "\n\n";
    plot.data += block;
    titles.push_back(study.node + "." + study.knob);
  }
  if (titles.empty()) return plot;  // nothing to draw
  plot.script =
      "set terminal svg size 900,600 dynamic enhanced font 'sans,11'\n"
      "set output 'bench.svg'\n"
      "set logscale xy\nset format x '10^{%L}'\nset format y '10^{%L}'\n"
      "set xlabel 'time of the node [s]' noenhanced\n"
      "set ylabel 'relative error (below the reference''s floor: at the floor)' noenhanced\n"
      "set title 'Work-precision of the accuracy knobs (filled: the scene''s setting; bars: Monte Carlo uncertainty)' noenhanced\n"
      "set key outside right noenhanced\nset grid\n"
      "plot";
  for (std::size_t i = 0; i < titles.size(); ++i) {
    const std::string index = std::to_string(i), colour = std::to_string(i + 1);
    plot.script += (i ? ", \\\n    " : " ") + std::string("'bench.dat' index ") + index + " using 1:2:3 with yerrorlines lc " +
                   colour + " pt 6 title " + gnuplot_string(titles[i]) + " noenhanced, '' index " + index +
                   " using 1:($4 > 0 ? $2 : 1/0) with points lc " + colour + " pt 7 ps 1.5 notitle";
  }
  plot.script += "\n";
  return plot;
}

}  // namespace mechgraph
