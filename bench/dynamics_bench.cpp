// What the valve train's dynamic simulation costs: the elastic node of scenes/valvetrain_dynamics.yaml
// (two cam revolutions, 1441 curve points), its upstream served from the memo cache, per
// integrator and tolerance. bench/peers/ runs the same model in scipy for comparison.
//   build/bench/mechgraph_bench --benchmark_filter=Dynamics
#include <mechgraph/evaluator.hpp>
#include <mechgraph/graph.hpp>
#include <mechgraph/plugin_registry.hpp>
#include <mechgraph/scene.hpp>

#include "bench_support.hpp"

#include <benchmark/benchmark.h>

#include <string>
#include <vector>

namespace {

using namespace mechgraph;

const PluginRegistry& plugins() { return bench::project_plugins(); }

void run_dynamics(benchmark::State& state, const std::string& node, const std::string& integrator, const std::string& tolerance,
                  const std::string& scene_file = "/scenes/valvetrain_dynamics.yaml", const std::string& curve_points = "") {
  const SceneSpec scene = load_scene(std::string(MECHGRAPH_SOURCE_DIR) + scene_file);
  SceneSpec one = scene;
  one.outputs = {PortRef{node, "curves", {}}};
  one.report.clear();
  std::vector<Override> overrides{parse_override(node + ".integrator=" + integrator), parse_override(node + ".tolerance=" + tolerance)};
  if (!curve_points.empty()) overrides.push_back(parse_override(node + ".curve_points=" + curve_points));
  const Graph g = build_graph(one, plugins(), overrides);
  const std::uint64_t key = node_hashes(g)[*g.find(node)];
  MemoCache cache;
  evaluate(g, cache);
  double steps = 0;
  for (auto _ : state) {
    cache.erase(key);  // everything upstream stays cached: only the simulation runs
    const RunResult r = evaluate(g, cache);
    steps = r.runs.back().work.at("steps");
  }
  state.counters["steps"] = steps;
}

void BM_DynamicsElastic(benchmark::State& state, const char* integrator, const char* tolerance) {
  run_dynamics(state, "elastic", integrator, tolerance);
}
BENCHMARK_CAPTURE(BM_DynamicsElastic, cvode_1e-6, "cvode", "1e-6")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_DynamicsElastic, cvode_1e-8, "cvode", "1e-8")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_DynamicsElastic, cvode_1e-10, "cvode", "1e-10")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_DynamicsElastic, dopri5_1e-6, "dopri5", "1e-6")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_DynamicsElastic, dopri5_1e-8, "dopri5", "1e-8")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_DynamicsElastic, dopri5_1e-10, "dopri5", "1e-10")->Unit(benchmark::kMillisecond);

// The peer comparison's case (bench/peers/valvetrain_dynamics.yaml: cycloidal cam, zero lash, single
// mass); the peer script times the same node through the CLI, where it runs once per process.
void BM_DynamicsPeer(benchmark::State& state, const char* integrator, const char* tolerance) {
  run_dynamics(state, "dyn", integrator, tolerance, "/bench/peers/valvetrain_dynamics.yaml");
}
BENCHMARK_CAPTURE(BM_DynamicsPeer, cvode_1e-7, "cvode", "1e-7")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_DynamicsPeer, dopri5_1e-7, "dopri5", "1e-7")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_DynamicsPeer, auto_1e-7, "auto", "1e-7")->Unit(benchmark::kMillisecond);
// 200001 curve points: outputs of megabytes, where buffers freed and mapped again each run would show.
void BM_DynamicsPeerDense(benchmark::State& state) {
  run_dynamics(state, "dyn", "auto", "1e-7", "/bench/peers/valvetrain_dynamics.yaml", "200001");
}
BENCHMARK(BM_DynamicsPeerDense)->Unit(benchmark::kMillisecond);

// Float, bounces and three revolutions at 7500 rpm.
void BM_DynamicsOverspeed(benchmark::State& state, const char* integrator) {
  run_dynamics(state, "overspeed", integrator, "1e-8");
}
BENCHMARK_CAPTURE(BM_DynamicsOverspeed, cvode, "cvode")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_DynamicsOverspeed, dopri5, "dopri5")->Unit(benchmark::kMillisecond);

}  // namespace
