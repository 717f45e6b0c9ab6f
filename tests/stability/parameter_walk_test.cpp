// Property walk: every numeric parameter of every node of the example scenes (and of
// tests/stability/walk_scenes/, which holds the node types no example uses), set to the ends of
// its declared range and beyond them into the huge and the tiny, must give finite results or an
// error that names the node — never a NaN or infinity caught only by the evaluator's guard, never
// another kind of failure. Accuracy knobs are left out: at their ends they cost time, not
// correctness (mechgraph bench walks them). A parameter with an unbounded side is tried at 1e300
// (or 1e-300 above an open zero).
#include "test_support.hpp"

#include <mechgraph/errors.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <set>

using namespace mechgraph;
using namespace mechgraph::testing;

namespace {

std::vector<double> values_to_try(const ParamSpec& p) {
  std::vector<double> v;
  const double lo = std::isfinite(p.min) ? (p.min_exclusive ? std::nextafter(p.min, INFINITY) : p.min) : -1e300;
  const double hi = std::isfinite(p.max) ? (p.max_exclusive ? std::nextafter(p.max, -INFINITY) : p.max) : 1e300;
  v.push_back(lo);
  v.push_back(hi);
  if (p.min == 0.0 && p.min_exclusive) v.push_back(1e-300);
  if (lo < 1.0 && hi > 1.0) v.push_back(1.0);
  if (p.kind == ParamKind::integer)
    for (double& x : v) x = p.min_exclusive || x < p.min ? std::ceil(x) : std::round(x);
  return v;
}

std::string text_of(double si, const ParamSpec& p) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.17g", si);
  const std::string unit = p.dimension.si_unit();
  return unit == "1" ? std::string(buffer) : std::string(buffer) + " " + unit;
}

// Walks the nodes of the example scenes whose type `include` accepts; returns the parameters walked.
std::set<std::string> walk(bool (*include)(const std::string& type)) {
  std::set<std::string> covered;
  std::size_t runs = 0;
  std::vector<std::filesystem::path> files;
  for (const char* folder : {"/scenes", "/tests/stability/walk_scenes"})  // the examples, then the types they lack
    for (const auto& entry : std::filesystem::directory_iterator(std::string(MECHGRAPH_SOURCE_DIR) + folder))
      if (entry.path().extension() == ".yaml") files.push_back(entry.path());
  for (const std::filesystem::path& file : files) {
    const auto entry = std::filesystem::directory_entry(file);
    const SceneSpec scene = load_scene(entry.path());
    const Graph base = build_graph(scene, project_registry());
    // One memo cache for the scene's runs: a node the changed parameter does not reach has the
    // memo key it had in the run before (its parameters and its producers' keys are the same), so
    // its outputs, checked when first made, are taken as they are instead of made again (the
    // dynamics of a branch the parameter is not on). Every node the parameter reaches runs.
    MemoCache cache(1024);
    for (std::size_t i : base.order) {
      const GraphNode& node = base.nodes[i];
      if (!include(node.info().type)) continue;
      for (const ParamSpec& p : node.info().params) {
        if (p.knob || (p.kind != ParamKind::number && p.kind != ParamKind::integer)) continue;
        covered.insert(node.info().type + "." + p.name);
        for (double value : values_to_try(p)) {
          const std::string set = node.name + "." + p.name + "=" + text_of(value, p);
          INFO(entry.path().filename().string() << ": --set " << set);
          ++runs;
          try {
            Graph g = build_graph(scene, project_registry(), {parse_override(set)});
            const RunResult r = evaluate(g, cache);
            (void)r;  // the evaluator's guard has checked every value is finite
          } catch (const SceneError& e) {
            CHECK_THAT(std::string(e.what()), Catch::Matchers::Contains("'" + p.name + "'"));
          } catch (const EvaluationError& e) {
            const std::string what = e.what();
            CHECK_THAT(what, Catch::Matchers::Contains("node '"));
            CHECK_THAT(what, !Catch::Matchers::Contains("produced a NaN or infinite value"));
          }
        }
      }
    }
  }
  INFO(runs << " runs over " << covered.size() << " parameters");
  return covered;
}

bool simulates(const std::string& type) { return type == "valvetrain.dynamics" || type == "valvetrain.float_speed"; }

}  // namespace

TEST_CASE("property walk: every numeric parameter at its range's ends gives finite results or a named error",
          "[stability][walk]") {
  CHECK(walk([](const std::string& type) { return !simulates(type); }).size() > 60);
}

// The simulations apart: each run integrates, so this walk takes most of a minute.
TEST_CASE("property walk of the simulating nodes (dynamics, float speed)", "[stability][walk]") {
  CHECK(walk([](const std::string& type) { return simulates(type); }).size() > 10);
}

TEST_CASE("property walk covers every node type of the project's plugins", "[stability][walk]") {
  std::set<std::string> used;
  for (const char* folder : {"/scenes", "/tests/stability/walk_scenes"})
    for (const auto& entry : std::filesystem::directory_iterator(std::string(MECHGRAPH_SOURCE_DIR) + folder))
      if (entry.path().extension() == ".yaml")
        for (const NodeSpec& n : load_scene(entry.path()).nodes) used.insert(n.type);
  for (const std::string& type : project_registry().type_names()) {
    INFO(type << " is in no example scene and not in tests/stability/walk_scenes/: add it there");
    CHECK(used.count(type) == 1);
  }
}
