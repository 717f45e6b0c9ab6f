// Each side of each declared limit: every numeric parameter with a finite bound, of every node of
// the example scenes, of tests/stability/walk_scenes/ (the types no example uses) and of
// tests/stability/witness_scenes/ (the witnesses below). Just inside the bound (the bound itself
// when it is included, else the next double or whole number inward) some node of the type must
// compute finite outputs: a range limit belongs only where the mathematics or the range of a double
// demands it, so a value it admits is a valid input, for some values of the node's other
// parameters. Just outside, every node must refuse it with a message naming the node, the parameter
// and the limit. Accuracy knobs are checked outside only. (parameter_walk_test.cpp goes further
// out, to the huge and the tiny.)
#include "test_support.hpp"

#include <mechgraph/errors.hpp>
#include <mechgraph/graph_cut.hpp>
#include <mechgraph/node.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <limits>
#include <map>
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

// The bounds no witness reaches yet (each refused by its own node over its own parameter), each with why: the range is right, but a node computing the
// inside value needs other nodes (a spring model, a table) to make a design they cannot make.
// None may be added; each is to be witnessed or its range or code fixed.
const std::map<std::string, std::string> unwitnessed = {
    {"valvetrain.polydyne_cam.ramp_angle at its maximum",
     "needs a valve law of 0.1 deg action through a spring design that can be sized"},
    {"valvetrain.polydyne_cam.rocker_ratio at its minimum",
     "needs the design's arms 1:100 and a spring the helical model sizes for them"},
    {"valvetrain.polydyne_cam.rocker_ratio at its maximum",
     "needs the design's arms 100:1 and a spring the helical model sizes for them"},
    {"valvetrain.spring_design.preload at its maximum",
     "needs P_max above 1 MN and a spring model that sizes such a spring"},
    {"valvetrain.float_speed.rpm_max at its minimum",
     "1 rpm: no valve floats below it, and a float speed not found is refused"},
};

bool simulates(const std::string& type) { return type == "valvetrain.dynamics" || type == "valvetrain.float_speed"; }

// The scene's graph cut to node `node` and its producers, which compute what they computed in the
// whole scene (the same wanted outputs). The walk asks whether the node itself computes or refuses
// a value; its consumers cannot change the answer (a consumer's refusal counted as accepted, as
// the node computing does), so they are not run: every bound upstream of the dynamics would
// otherwise integrate it once more. What consumers do with the values a node makes at its ends is
// the property walk's question (parameter_walk_test.cpp).
Graph cut_graph(const SceneSpec& scene, const Override& set, std::size_t node) {
  Graph g = build_graph(scene, project_registry(), {set});
  cut_to_producers(g, node);
  return g;
}

// The type, parameter and side of each bound whose inside value its node refuses in every scene
// that holds the type. A value the other parameters of one node make infeasible (a ramp_length
// no action angle of that node leaves room for, a checking lift above that cam's lift) is valid
// when some node of the type computes it: tests/stability/witness_scenes/ holds those witnesses.
void walk_limits(bool simulating, std::set<std::string>& contradictions) {
  std::set<std::string> walked, computed, refused, accepted;
  std::map<std::string, std::string> refusal;  // the last refusal of each bound not computed
  std::vector<std::filesystem::path> files;
  for (const char* folder : {"/scenes", "/tests/stability/walk_scenes", "/tests/stability/witness_scenes"})
    for (const auto& entry : std::filesystem::directory_iterator(std::string(MECHGRAPH_SOURCE_DIR) + folder))
      if (entry.path().extension() == ".yaml") files.push_back(entry.path());
  int limits = 0;
  for (const std::filesystem::path& file : files) {
    const SceneSpec scene = load_scene(file);
    const Graph base = build_graph(scene, project_registry());
    {
      // The scene itself computes: else every step's refusal would pass for another node's.
      INFO(file.filename().string() << " as written");
      Graph g = build_graph(scene, project_registry());
      MemoCache cache;
      REQUIRE_NOTHROW(evaluate(g, cache));
    }
    for (std::size_t i : base.order) {
      const GraphNode& node = base.nodes[i];
      if (simulates(node.info().type) != simulating) continue;
      for (const ParamSpec& p : node.info().params) {
        if (p.kind != ParamKind::number && p.kind != ParamKind::integer) continue;
        for (const bool lower : {true, false}) {
          if (!std::isfinite(lower ? p.min : p.max)) continue;
          ++limits;
          const Side side = either_side(p, lower);
          const std::string bound = node.info().type + "." + p.name + (lower ? " at its minimum" : " at its maximum");
          const std::string inside = node.name + "." + p.name + "=" + text_of(side.inside, p);
          const std::string outside = node.name + "." + p.name + "=" + text_of(side.outside, p);
          // An accuracy knob at its end costs time, not correctness (mechgraph bench walks them):
          // only its outside is checked.
          if (!p.knob) {
            walked.insert(bound);
            try {
              const Graph g = cut_graph(scene, parse_override(inside), i);
              MemoCache cache;
              (void)evaluate(g, cache);  // the evaluator's guard checks every value is finite
              computed.insert(bound);
              accepted.insert(bound);
            } catch (const std::exception& e) {
              // The node may refuse the design the value makes over another of its parameters or
              // inputs (a checking lift above that cam's lift, a contour that undercuts): feasibility,
              // not a range. This node refusing this very parameter inside its declared range is the
              // contradiction looked for, unless a witness elsewhere computes the value.
              const std::string what = e.what();
              refusal[bound] = file.filename().string() + ": --set " + inside + ": " + what;
              const bool same = what.find("node '" + node.name + "'") != std::string::npos &&
                                what.find("parameter '" + p.name + "'") != std::string::npos;
              (same ? refused : accepted).insert(bound);
            }
          }
          {
            INFO(file.filename().string() << ": " << node.info().type << ": --set " << outside << " (just outside)");
            try {
              const Graph g = cut_graph(scene, parse_override(outside), i);
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
  for (const std::string& b : refused)
    if (!accepted.count(b) && !unwitnessed.count(b)) contradictions.insert(b);
  // A listed bound that is now witnessed leaves the list.
  for (const auto& [b, why] : unwitnessed) {
    INFO(b << " is accepted by some node now: remove it from `unwitnessed`");
    CHECK(!accepted.count(b));
  }
  // Stricter, for the record (not yet required): the bounds no node of the type computes, where
  // every refusal was over another parameter or input (a design the other values of the walk's
  // scenes cannot make). Consumers do not run (cut_to_producers), so a design only a consumer
  // refuses (a spring that no longer fits) counts as computed.
  std::size_t uncomputed = 0;
  for (const std::string& b : walked)
    if (!computed.count(b)) {
      ++uncomputed;
      std::cout << "no node computes " << b << " (" << refusal[b] << ")\n";
    }
  std::cout << uncomputed << " of " << walked.size() << " bounds are computed by no node of their type\n";
  INFO(limits << " limits checked");
  CHECK(limits > (simulating ? 10 : 40));
}

}  // namespace

// Outside every bound: refused by name, without exception. Inside: no declared bound is refused
// by its own node in every scene (the list printed names any that is), but the few `unwitnessed`.
TEST_CASE("each side of each declared limit: inside computes, outside is refused naming node, parameter and limit",
          "[stability][limits]") {
  std::set<std::string> contradictions;
  walk_limits(false, contradictions);
  for (const std::string& c : contradictions) std::cout << "declared range contradicted by its node: " << c << "\n";
  CHECK(contradictions.empty());
}

TEST_CASE("each side of each declared limit of the simulating nodes (dynamics, float speed)", "[stability][limits][slow]") {
  std::set<std::string> contradictions;
  walk_limits(true, contradictions);
  for (const std::string& c : contradictions) std::cout << "declared range contradicted by its node: " << c << "\n";
  CHECK(contradictions.empty());
}

namespace {

// Each finite bound of `params` (and of record fields) without a reason, as "type.param".
void unexplained(const std::string& where, const std::vector<ParamSpec>& params, std::vector<std::string>& out) {
  for (const ParamSpec& p : params) {
    if ((std::isfinite(p.min) || std::isfinite(p.max)) && p.range_reason.empty()) out.push_back(where + "." + p.name);
    if (!p.fields.empty()) unexplained(where + "." + p.name, p.fields, out);
  }
}

}  // namespace

// `describe` states why each range is what it is: every finite bound of every built-in node type
// carries a reason, which describe prints and an out-of-range message quotes.
TEST_CASE("every finite bound of every built-in parameter says why", "[stability][limits][describe]") {
  std::vector<std::string> missing;
  int bounded = 0;
  for (const std::string& type : project_registry().type_names()) {
    const NodeInfo& info = project_registry().find(type)->type->info();
    unexplained(type, info.params, missing);
    for (const ParamSpec& p : info.params) bounded += std::isfinite(p.min) || std::isfinite(p.max);
  }
  for (const std::string& m : missing) std::cout << "no range_reason: " << m << "\n";
  CHECK(bounded > 100);
  CHECK(missing.empty());
  // The reason reaches the user: in the out-of-range message.
  const NodeInfo& cardan = project_registry().find("joint.cardan")->type->info();
  const ParamSpec* bend = cardan.find_param("bend_angle");
  REQUIRE(bend != nullptr);
  CHECK_THAT(bend->value_problem(2.0), Catch::Matchers::Contains(bend->range_reason));
}
