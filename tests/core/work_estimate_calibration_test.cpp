// The work estimate against what evaluation costs (issue 28): every node type (the example scenes
// and tests/stability/walk_scenes/ hold them all) is evaluated at its scene's values and with each
// of its counts (points, samples, bins, revolutions, a table's smoothing) raised, each accuracy
// knob made finer (a tolerance, a step: a hundredth) and each method of a choice knob, and the
// seconds each node took are compared with its estimate (work_estimate.hpp), a work item being
// counted as one microsecond:
//
//   - never under: measured <= under_factor x estimate (a node that costs more than its estimate
//     says can pass the budget and run for an hour);
//   - not absurdly over: estimate <= over_factor(type) x measured, the factor stated per type below
//     (an estimate far above the cost refuses scenes that would run).
//
// Both sides are floored at floor_seconds, below which a time says nothing (timer, caches) and a
// refusal never happens. Sizes are small, so the test takes a few seconds.
#include "test_support.hpp"

#include <mechgraph/work_estimate.hpp>

#include <catch2/catch.hpp>

#include <cstdio>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>

using namespace mechgraph;
using namespace mechgraph::testing;

namespace {

constexpr double seconds_per_item = 1e-6;
constexpr double floor_seconds = 2e-3;
constexpr double under_factor = 10.0;
// A point is measured only when its estimate is below this: the test stays fast.
constexpr double most_items_measured = 2e5;

// How far above the measured cost each type's estimate may lie. The conventions (points, samples,
// bins) are within 30 of the cost; the cam laws count every piece at the worst case of the
// certified searches (a piece halved 4 times); cam.table counts 16 such pieces per row (a rough,
// finely rounded table does reach it; a smooth one costs a hundredth).
double over_factor(const std::string& type) {
  if (type == "cam.table") return 1000.0;
  // cam.contour counts the traced contour, which only a requested contour (or its DXF) costs.
  if (type == "cam.contour") return 1000.0;
  // A Monte Carlo sample of a linear stack is a few multiplications a link (10 ns), counted as an item.
  if (type == "stack.linear") return 300.0;
  if (type.rfind("cam.", 0) == 0 || type.rfind("follower.", 0) == 0) return 300.0;
  if (type == "valvetrain.valve_motion" || type == "valvetrain.time_area" || type == "valvetrain.resonance" ||
      type == "valvetrain.spring_design" || type == "valvetrain.polydyne_cam")
    return 300.0;
  return 100.0;
}

struct Point {
  std::string scene, set, node, type;
  double measured = 0, estimated = 0;
};

bool is_count(const std::string& name) {
  const auto ends = [&](const char* tail) {
    const std::string t(tail);
    return name.size() >= t.size() && name.compare(name.size() - t.size(), t.size(), t) == 0;
  };
  return ends("points") || ends("samples") || ends("bins") || name == "revolutions";
}

bool within(const Point& p) {
  const double measured = std::max(p.measured, floor_seconds), estimated = std::max(p.estimated, floor_seconds);
  return measured <= under_factor * estimated && estimated <= over_factor(p.type) * measured;
}

// Every node of `graph` that ran, with its estimate in the same graph (sizes propagated). A graph
// with a node outside its factors is run twice more and each node keeps its least time: a machine
// busy with something else makes a node slow, never fast.
void measure(const std::string& scene, const std::string& set, const Graph& graph, std::vector<Point>& points) {
  const std::vector<char> writing = writing_nodes(graph);
  std::vector<double> sizes(graph.nodes.size(), 1.0);
  std::map<std::string, double> estimate;
  for (std::size_t i : graph.order) {
    const NodeEstimate e = estimate_node(graph, i, sizes, writing[i] != 0, false);
    sizes[i] = e.output_size;
    estimate[graph.nodes[i].name] = e.work;
  }
  std::vector<Point> mine;
  for (int attempt = 0; attempt < 3; ++attempt) {
    MemoCache cache;
    const RunResult r = evaluate(graph, cache);
    std::map<std::string, double> seconds;
    for (const NodeRun& run : r.runs)
      if (!run.reused) seconds[run.node] = run.seconds;
    if (attempt == 0) {
      for (const NodeRun& run : r.runs)
        if (!run.reused) mine.push_back({scene, set, run.node, run.type, run.seconds, estimate[run.node] * seconds_per_item});
    } else {
      for (Point& p : mine) p.measured = std::min(p.measured, seconds[p.node]);
    }
    if (std::all_of(mine.begin(), mine.end(), within)) break;
  }
  points.insert(points.end(), mine.begin(), mine.end());
}

std::vector<std::filesystem::path> scenes() {
  std::vector<std::filesystem::path> files;
  for (const char* folder : {"/scenes", "/tests/stability/walk_scenes"})
    for (const auto& entry : std::filesystem::directory_iterator(std::string(MECHGRAPH_SOURCE_DIR) + folder))
      if (entry.path().extension() == ".yaml") files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  return files;
}

}  // namespace

TEST_CASE("work estimate: every node type's estimate is within its stated factor of the measured cost",
          "[work_estimate][calibration]") {
  std::vector<Point> points;
  std::set<std::string> types_seen;
  for (const std::filesystem::path& file : scenes()) {
    const SceneSpec scene = load_scene(file);
    const Graph base = build_graph(scene, project_registry());
    std::vector<std::string> sets{""};
    for (std::size_t i : base.order) {
      const GraphNode& node = base.nodes[i];
      types_seen.insert(node.info().type);
      for (const ParamSpec& p : node.info().params) {
        if (!node.params.has(p.name)) continue;
        const ParamValue& value = node.params.get(p.name);
        if (p.kind == ParamKind::integer && (is_count(p.name) || p.knob)) {
          for (const double factor : {4.0, 32.0}) {  // a count raised towards the end of its range
            const double raised = std::min(std::round(value.number * factor), p.max);
            if (raised > value.number) sets.push_back(node.name + "." + p.name + "=" + std::to_string(static_cast<long>(raised)));
          }
        } else if (p.knob && p.kind == ParamKind::number) {
          for (const double factor : {1e-2}) {  // a tolerance or step made finer, within its range
            const double finer = value.number * factor;
            if (!p.admits(finer)) continue;
            char text[64];
            std::snprintf(text, sizeof text, "%.17g", finer);
            const std::string unit = p.dimension.si_unit();
            sets.push_back(node.name + "." + p.name + "=" + text + (unit == "1" ? "" : " " + unit));
          }
        } else if (p.knob && p.kind == ParamKind::choice) {
          for (const std::string& choice : p.choices)  // every method
            if (choice != value.text) sets.push_back(node.name + "." + p.name + "=" + choice);
        }
      }
      if (node.info().type == "cam.table")
        for (const char* smoothing : {"none", "resolution", "gcv"}) sets.push_back(node.name + ".smoothing=" + smoothing);
    }
    for (const std::string& set : sets) {
      Graph g = set.empty() ? base : build_graph(scene, project_registry(), {parse_override(set)});
      // The scene as written always runs; a raised count only while it stays small (the test stays fast).
      if (!set.empty() && estimate_work(g).work > most_items_measured * 20) continue;
      bool small = true;
      std::vector<double> sizes(g.nodes.size(), 1.0);
      const std::vector<char> writing = writing_nodes(g);
      for (std::size_t i : g.order) {
        const NodeEstimate e = estimate_node(g, i, sizes, writing[i] != 0, false);
        sizes[i] = e.output_size;
        small = small && e.work <= most_items_measured * 4;
      }
      if (!small && !set.empty()) continue;
      try {
        measure(file.filename().string(), set, g, points);
      } catch (const std::exception&) {
        // A raised count the node refuses (an error naming it) costs nothing to calibrate.
      }
    }
  }
  // Every registered node type was measured.
  std::set<std::string> measured_types;
  for (const Point& p : points) measured_types.insert(p.type);
  for (const auto& type : project_registry().type_names()) {
    INFO("node type " << type);
    CHECK(measured_types.count(type) == 1);
  }
  for (const Point& p : points) {
    const double measured = std::max(p.measured, floor_seconds), estimated = std::max(p.estimated, floor_seconds);
    INFO(p.scene << (p.set.empty() ? "" : " --set " + p.set) << ": node " << p.node << " (" << p.type << ") took "
                 << p.measured << " s, estimated " << p.estimated << " s");
    CHECK(measured <= under_factor * estimated);
    CHECK(estimated <= over_factor(p.type) * measured);
  }
}
