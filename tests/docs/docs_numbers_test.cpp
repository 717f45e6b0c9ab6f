// Numbers quoted in docs/ are recomputed by the tool, and the doc must still quote them: a drift of
// either side fails. Each case reads the .md file, finds the sentence by a pattern that captures
// the numbers, runs the example scene the sentence speaks of and prints the results as the doc
// does. (The measured-table paragraph of valvetrain.md is checked in table_smoothing_test.cpp.)
#include "test_support.hpp"

#include <catch2/catch.hpp>

#include <cstdio>
#include <fstream>
#include <iterator>
#include <regex>
#include <string>
#include <vector>

using namespace mechgraph;
using namespace mechgraph::testing;

namespace {

// The doc's text with its line breaks made spaces, so a pattern may span lines.
std::string doc_text(const std::string& relative) {
  std::ifstream in(std::string(MECHGRAPH_SOURCE_DIR) + "/" + relative);
  REQUIRE(in);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  for (char& c : text)
    if (c == '\n') c = ' ';
  return std::regex_replace(text, std::regex(" +"), " ");
}

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
