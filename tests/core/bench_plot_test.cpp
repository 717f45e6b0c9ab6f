// The work-precision plot of mechgraph bench: every text literal (no gnuplot markup), in the
// script and, when gnuplot is installed, in the SVG it draws.
#include "test_support.hpp"
#include "hostile/hostile_support.hpp"

#include <mechgraph/bench_plot.hpp>

#include <catch2/catch.hpp>

#include <fstream>
#include <iterator>

using namespace mechgraph;
using namespace mechgraph::testing;
using Catch::Matchers::Contains;

namespace {
KnobBench two_settings(const std::string& node, const std::string& knob) {
  KnobBench bench;
  KnobStudy k;
  k.node = node;
  k.knob = knob;
  k.trial_count = 2;
  bench.knobs.push_back(k);
  for (int i = 0; i < 2; ++i) {
    KnobTrial t;
    t.node = node;
    t.knob = knob;
    t.setting = std::to_string(100 * (i + 1));
    t.seconds = 1e-3 * (i + 1);
    t.max_relative_error = 1e-4 / (i + 1);
    t.is_default = i == 0;
    bench.trials.push_back(t);
  }
  return bench;
}
}  // namespace

TEST_CASE("bench plot: titles are literal: curve_points is no subscript, ^ { @ and quotes no markup", "[bench]") {
  const std::string node = "n_1 ^2 {x} @a \"q\" 's' <&>";
  const BenchPlot plot = bench_plot(two_settings(node, "curve_points"));
  // The script: the title single-quoted (a quote doubled, '@' as its look-alike U+FF20, see
  // text_escape.hpp), drawn noenhanced; the other texts too.
  const std::string quoted = "'n_1 ^2 {x} \xEF\xBC\xA0" "a \"q\" ''s'' <&>.curve_points'";
  CHECK_THAT(plot.script, Contains("title " + quoted + " noenhanced"));
  CHECK_THAT(plot.script, Contains("set key outside right noenhanced"));
  CHECK_THAT(plot.script, Contains("set xlabel 'time of the node [s]' noenhanced"));
  CHECK_THAT(plot.data, Contains("0.001 0.0001 0 1\n0.002 5e-05 0 0\n"));
  const auto gnuplot = find_on_path("gnuplot");
  if (gnuplot.empty()) FAIL("gnuplot is not installed (scripts/install-deps.sh installs gnuplot-nox): the script cannot be drawn");
  const auto dir = scratch_dir("mechgraph_bench_plot");
  std::ofstream(dir / "bench.dat") << plot.data;
  std::ofstream(dir / "bench.gp") << plot.script;
  REQUIRE(hostile::run_argv(gnuplot.string(), {"bench.gp"}, dir).exit_code == 0);
  std::ifstream svg(dir / "bench.svg");
  const std::string text((std::istreambuf_iterator<char>(svg)), {});
  // The legend's text as one run of characters: no <tspan> shifting "points" down as a subscript.
  CHECK_THAT(text, Contains("<text>n_1 ^2 {x} \xEF\xBC\xA0" "a \"q\" 's' &lt;&amp;>.curve_points</text>"));
  CHECK_THAT(text, Contains("<text>time of the node [s]</text>"));
  CHECK_FALSE(text.find("dy=\"3.30px\">p") != std::string::npos);
  std::filesystem::remove_all(dir);
}

TEST_CASE("bench plot: a setting below the reference's floor sits at the floor, failed ones and unmeasured knobs are left out", "[bench]") {
  KnobBench bench = two_settings("n", "tolerance");
  bench.trials[1].reference_floor = 3e-4;
  bench.trials[1].below_floor = true;
  bench.trials[0].failure = "did not converge";
  KnobStudy off;
  off.node = "n";
  off.knob = "coils";
  off.not_measured = "not measured: coils belongs to the effect spring_surge, which is off for this node";
  off.first_trial = 2;
  bench.knobs.push_back(off);
  const BenchPlot plot = bench_plot(bench);
  CHECK(plot.data == "0.002 0.0003 0 0\n");
  CHECK_THAT(plot.script, Contains("'n.tolerance'"));
  CHECK_FALSE(plot.script.find("coils") != std::string::npos);
  KnobBench nothing;
  nothing.knobs.push_back(off);
  CHECK(bench_plot(nothing).script.empty());
}
