// Numbers quoted in docs/ are recomputed by the tool, and the doc must still quote them: a drift of
// either side fails. Each case reads the .md file, finds the sentence by a pattern that captures
// the numbers, runs the example scene the sentence speaks of and prints the results as the doc
// does. This file: docs/methods/backlash.md.
#include "backlash/variates.hpp"
#include "docs/doc_numbers.hpp"
#include "test_support.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <regex>
#include <string>
#include <vector>

using namespace mechgraph;
using namespace mechgraph::testing;
using namespace mechgraph::testing::docs;
namespace docs = mechgraph::testing::docs;

namespace {

std::string fixed(double v, int digits) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", digits, v);
  return text;
}

// The example scene `scene_file` run for `outputs` ("node.port") instead of its own; the values in
// the order asked.
std::vector<double> values_of(const std::string& scene_file, const std::vector<std::string>& outputs) {
  SceneSpec scene = load_scene(std::string(MECHGRAPH_SOURCE_DIR) + "/" + scene_file);
  scene.outputs.clear();
  for (const std::string& o : outputs) {
    PortRef ref;
    ref.node = o.substr(0, o.find('.'));
    ref.port = o.substr(o.find('.') + 1);
    scene.outputs.push_back(ref);
  }
  Graph g = build_graph(scene, project_registry());
  MemoCache cache;
  const RunResult r = evaluate(g, cache);
  std::vector<double> values;
  for (const std::string& o : outputs) values.push_back(scalar_output(r, o));
  return values;
}

// The ziggurat's strip area for a tail start r: v = r f(r) + sqrt(pi/2) erfc(r / sqrt(2)).
double strip_area(double r) { return r * std::exp(-0.5 * r * r) + std::sqrt(3.14159265358979323846 / 2) * std::erfc(r / std::sqrt(2.0)); }

// The strips x[i+1] = f^-1(f(x[i]) + v / x[i]) from x[1] = r up to x[1023], and the top strip's
// area x[1023] (1 - f(x[1023])) over v, less 1 (backlash.md, "Monte Carlo sampler").
double top_strip_residual(double r) {
  const double v = strip_area(r);
  double x = r;
  for (int i = 2; i < 1024; ++i) x = std::sqrt(-2.0 * std::log(v / x + std::exp(-0.5 * x * x)));
  return x * (1 - std::exp(-0.5 * x * x)) / v - 1;
}

constexpr double arcmin = 3.14159265358979323846 / (180.0 * 60.0);

}  // namespace

TEST_CASE("docs: backlash.md quotes the example chain's mean, worst-case and statistical backlash", "[docs]") {
  const std::string doc = doc_text("docs/methods/backlash.md");
  std::smatch m;
  REQUIRE(std::regex_search(doc, m, std::regex("gives a mean of ([0-9.]+) arcmin and a worst-case maximum of ([0-9.]+) "
                                               "arcmin; the statistical maxima \\(below\\) are about ([0-9.]+) arcmin")));
  const std::vector<double> v =
      values_of("scenes/backlash_chain.yaml", {"chain.angular_backlash_mean", "chain.angular_backlash_max",
                                              "chain.angular_backlash_rss_max", "chain.angular_backlash_mc_q999"});
  CHECK(m[1].str() == fixed(v[0] / arcmin, 1));
  CHECK(m[2].str() == fixed(v[1] / arcmin, 1));
  // "about": the RSS and Monte Carlo maxima both round to it.
  CHECK(m[3].str() == fixed(v[2] / arcmin, 1));
  CHECK(m[3].str() == fixed(v[3] / arcmin, 1));
}

TEST_CASE("docs: backlash.md, the arc-minute, the cardan's largest speed ratio and the spec figures", "[docs][backlash]") {
  const std::string doc = doc_text("docs/methods/backlash.md");
  const auto am = quoted(doc, "1 rad = " + std::string(docs::number) + " arcmin");
  docs::check_quote("arc-minutes in a radian", am[0], 180 * 60 / 3.14159265358979323846);

  // "every bend below 90 deg is accepted (the double below 90 deg has 1 / cos b = 3.5e15, finite)":
  // joint.cardan at the largest double below pi/2 (the double nearest pi/2 is refused as 90 deg).
  const auto c = quoted(doc, "\\(the double below 90 deg has `1 / cos b` = " + std::string(docs::number) + ", finite\\)");
  char bend[64];
  std::snprintf(bend, sizeof bend, "%.17g rad", std::nextafter(0.5 * 3.14159265358979323846, 0.0));
  const RunResult r = run_yaml(std::string("nodes:\n  j: { type: joint.cardan, params: { input_angle: 0 deg, bend_angle: ") + bend +
                                   " } }\noutputs: [ j.speed_ratio_max ]\n",
                               project_registry());
  docs::check_quote("1 / cos b below 90 deg", c[0], scalar_output(r, "j.speed_ratio_max"));
  CHECK_THROWS(run_yaml("nodes:\n  j: { type: joint.cardan, params: { input_angle: 0 deg, bend_angle: 90 deg } }\noutputs: [ j.speed_ratio_max ]\n", project_registry()));

  // "(+-3 sigma: 2700 ppm; a mean 1.5 sigma off centre inside +-6 sigma: Cpk = 1.5, 3.4 ppm)"
  const auto s = quoted(doc, "\\(\\+-3 sigma: " + std::string(docs::number) + " ppm; a mean 1.5 sigma off centre inside \\+-6 sigma: Cpk = " +
                                 docs::number + ", " + docs::number + " ppm\\)");
  auto Phi = [](double z) { return 0.5 * std::erfc(-z / std::sqrt(2.0)); };
  docs::check_quote("ppm outside +-3 sigma", s[0], 1e6 * 2 * Phi(-3));
  docs::check_quote("Cpk, mean 1.5 sigma off, limits at +-6 sigma", s[1], (6 - 1.5) / 3);
  docs::check_quote("ppm, mean 1.5 sigma off, limits at +-6 sigma", s[2], 1e6 * (Phi(-4.5) + Phi(-7.5)));
  // "its own quantiles at 4 Phi(-3) and 1 - 4 Phi(-3) ... about 0.54 % of them each side"
  const auto t = quoted(doc, "about " + std::string(docs::number) + " % of them each side");
  docs::check_quote("tail kept each side, %", t[0], 100 * 4 * Phi(-3));
}

TEST_CASE("docs: backlash.md, the ziggurat's r, its closure and the share of draws on the fast path", "[docs][backlash]") {
  const std::string doc = doc_text("docs/methods/backlash.md");
  const auto z = quoted(doc, "of 1024 strips of equal area `v` under `f\\(x\\) = exp\\(-x\\^2/2\\)`: `r = " + std::string(docs::number) +
                                 "` is where the tail starts.*?which is " + docs::number + " % of the draws.*?A lane that misses \\(" + docs::number + " %\\)");
  const backlash::ZigguratTable& table = backlash::ziggurat_table;
  // The doc's r is the sampler's, and it is the root of the closure: the top strip [0, x[1023]]
  // has area v at r to within a double's step of r (the residual changes sign at the next double,
  // and no neighbour does better; the recursion over 1023 strips amplifies a step of r to ~1e-11).
  CHECK(std::stod(z[0]) == backlash::ZigguratTable::r);
  const double r = std::stod(z[0]);
  CHECK(std::abs(strip_area(r) / backlash::ZigguratTable::v - 1) < 1e-14);
  const double below = top_strip_residual(std::nextafter(r, 0.0)), at = top_strip_residual(r),
               above = top_strip_residual(std::nextafter(r, 10.0));
  INFO("top strip's residual at r - ulp, r, r + ulp: " << below << ", " << at << ", " << above);
  CHECK(((at <= 0 && above > 0) || (below < 0 && at >= 0)));
  CHECK(std::abs(at) <= std::min(std::abs(below), std::abs(above)));
  CHECK(std::abs(at) < 1e-11);
  // A draw's strip is uniform over the 1024, and within it |u| < x[i+1]/x[i] is the fast path.
  double fast = 0;
  for (double ratio : table.ratio) fast += ratio / 1024;
  docs::check_quote("draws on the fast path, %", z[1], 100 * fast);
  docs::check_quote("draws that miss, %", z[2], 100 * (1 - fast));
}
