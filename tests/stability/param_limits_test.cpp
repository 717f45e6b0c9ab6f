// Each side of each declared limit: every numeric parameter with a finite bound, of every node of
// the example scenes and of tests/stability/walk_scenes/ (which hold the types no example uses).
// Just inside the bound (the bound itself when it is included, else the next double or whole
// number inward) the scene must be accepted and compute finite outputs: a range limit belongs only
// where the mathematics or the range of a double demands it, so a value it admits is a valid
// input. Just outside, the scene must be refused with a message naming the node, the parameter
// and the limit. Accuracy knobs are checked outside only. (parameter_walk_test.cpp goes further
// out, to the huge and the tiny.)
#include "test_support.hpp"

#include <mechgraph/errors.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <limits>
#include <set>
#include <string>
#include <vector>

using namespace mechgraph;
using namespace mechgraph::testing;

namespace {

std::string text_of(double si, const ParamSpec& p) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.17g", si);
  const std::string unit = p.dimension.si_unit();
  return unit == "1" ? std::string(buffer) : std::string(buffer) + " " + unit;
}

struct Side {
  double inside, outside;
};

// The values either side of one bound; `lower` for the minimum.
Side either_side(const ParamSpec& p, bool lower) {
  const double bound = lower ? p.min : p.max;
  const bool exclusive = lower ? p.min_exclusive : p.max_exclusive;
  const double in_dir = lower ? INFINITY : -INFINITY, out_dir = -in_dir;
  if (p.kind == ParamKind::integer) {
    const double step = lower ? 1.0 : -1.0;
    const double inside = exclusive ? bound + step : bound;
    const double beyond = bound - step != bound ? bound - step : std::nextafter(bound, out_dir);  // 2^53 + 1 rounds back
    return {inside, exclusive ? bound : beyond};
  }
  return {exclusive ? std::nextafter(bound, in_dir) : bound, exclusive ? bound : std::nextafter(bound, out_dir)};
}

// 50: scenes/valve_timing_tolerances.yaml (a ramped cam with lash) brings
// valvetrain.valve_motion.checking_lift at its minimum: the smallest denormal checking lift is
// refused as "not below the valve's lift 11.75 mm" (issue 29's range work to settle).
constexpr std::size_t known_contradictions = 50, known_simulating_contradictions = 1;

bool simulates(const std::string& type) { return type == "valvetrain.dynamics" || type == "valvetrain.float_speed"; }

// The type, parameter and side of each bound whose inside value the node itself refuses.
void walk_limits(bool simulating, std::set<std::string>& contradictions) {
  std::vector<std::filesystem::path> files;
  for (const char* folder : {"/scenes", "/tests/stability/walk_scenes"})
    for (const auto& entry : std::filesystem::directory_iterator(std::string(MECHGRAPH_SOURCE_DIR) + folder))
      if (entry.path().extension() == ".yaml") files.push_back(entry.path());
  int limits = 0;
  for (const std::filesystem::path& file : files) {
    const SceneSpec scene = load_scene(file);
    const Graph base = build_graph(scene, project_registry());
    for (std::size_t i : base.order) {
      const GraphNode& node = base.nodes[i];
      if (simulates(node.info().type) != simulating) continue;
      for (const ParamSpec& p : node.info().params) {
        if (p.kind != ParamKind::number && p.kind != ParamKind::integer) continue;
        for (const bool lower : {true, false}) {
          if (!std::isfinite(lower ? p.min : p.max)) continue;
          ++limits;
          const Side side = either_side(p, lower);
          const std::string inside = node.name + "." + p.name + "=" + text_of(side.inside, p);
          const std::string outside = node.name + "." + p.name + "=" + text_of(side.outside, p);
          // An accuracy knob at its end costs time, not correctness (mechgraph bench walks them):
          // only its outside is checked.
          if (!p.knob) {
            INFO(file.filename().string() << ": " << node.info().type << ": --set " << inside << " (just inside)");
            try {
              Graph g = build_graph(scene, project_registry(), {parse_override(inside)});
              MemoCache cache;
              (void)evaluate(g, cache);  // the evaluator's guard checks every value is finite
            } catch (const std::exception& e) {
              // Another node, or this node over another parameter, may refuse the design the value
              // makes (a spring that no longer fits, a contour that undercuts): feasibility, not a
              // range. This node refusing this very parameter inside its declared range is the
              // contradiction looked for.
              const std::string what = e.what();
              const bool same = what.find("node '" + node.name + "'") != std::string::npos &&
                                what.find("parameter '" + p.name + "'") != std::string::npos;
              if (same) {
                contradictions.insert(node.info().type + "." + p.name + (lower ? " at its minimum" : " at its maximum"));
                WARN("refused by its own node over its own parameter: " << what);
              }
            }
          }
          {
            INFO(file.filename().string() << ": " << node.info().type << ": --set " << outside << " (just outside)");
            try {
              Graph g = build_graph(scene, project_registry(), {parse_override(outside)});
              MemoCache cache;
              (void)evaluate(g, cache);
              FAIL_CHECK("accepted");
            } catch (const std::exception& e) {
              const std::string what = e.what();
              CHECK_THAT(what, Catch::Matchers::Contains("'" + node.name + "'") || Catch::Matchers::Contains(node.name + "."));
              CHECK_THAT(what, Catch::Matchers::Contains(p.name));
              CHECK_THAT(what, Catch::Matchers::Contains(lower ? (p.min_exclusive ? ">" : ">=") : (p.max_exclusive ? "<" : "<=")) ||
                                   Catch::Matchers::Contains(lower ? "at least" : "at most") ||
                                   Catch::Matchers::Contains(lower ? "above" : "below") ||
                                   Catch::Matchers::Contains("range"));
            }
          }
        }
      }
    }
  }
  INFO(limits << " limits checked");
  CHECK(limits > (simulating ? 10 : 40));
}

}  // namespace

// Outside every bound: refused by name, without exception. Inside: the bounds a node's own checks
// still contradict (a limit computed from the design or from a double, e.g. a wave narrower than
// one ulp, below a declared "> 0") are listed; their number may only fall (known at the time of
// writing: see the list this prints).
TEST_CASE("each side of each declared limit: inside computes, outside is refused naming node, parameter and limit",
          "[stability][limits]") {
  std::set<std::string> contradictions;
  walk_limits(false, contradictions);
  for (const std::string& c : contradictions) std::cout << "declared range contradicted by its node: " << c << "\n";
  CHECK(contradictions.size() <= known_contradictions);
}

TEST_CASE("each side of each declared limit of the simulating nodes (dynamics, float speed)", "[stability][limits][slow]") {
  std::set<std::string> contradictions;
  walk_limits(true, contradictions);
  for (const std::string& c : contradictions) std::cout << "declared range contradicted by its node: " << c << "\n";
  CHECK(contradictions.size() <= known_simulating_contradictions);
}
