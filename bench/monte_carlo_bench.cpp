// Monte Carlo of the steering-drive chain (scenes/backlash_chain.yaml, node `chain`: five hinges,
// seven play terms and the actuator, eight normals per sample), the chain node alone re-run with
// its fits and joints cached, on one thread and on two (`chain.threads`). The counter samples/s is
// the figure to set beside the numpy peer's.
//   build/bench/mechgraph_bench --benchmark_filter=MonteCarlo
#include <mechgraph/evaluator.hpp>
#include <mechgraph/graph.hpp>
#include <mechgraph/memo_cache.hpp>
#include <mechgraph/scene.hpp>

#include "bench_support.hpp"

#include <benchmark/benchmark.h>

#include <string>

namespace {

using namespace mechgraph;

// Args: samples, threads.
void BM_MonteCarloFused(benchmark::State& state) {
  SceneSpec scene = load_scene(std::string(MECHGRAPH_SOURCE_DIR) + "/scenes/backlash_chain.yaml");
  scene.report.clear();
  scene.outputs = {parse_port_ref("chain.rod_backlash_mc_q999", {})};
  const long samples = state.range(0), threads = state.range(1);
  const Graph g = build_graph(scene, bench::project_plugins(),
                              {parse_override("chain.samples=" + std::to_string(samples)),
                               parse_override("chain.threads=" + std::to_string(threads))});
  MemoCache cache;
  evaluate(g, cache);
  const std::uint64_t chain = node_hashes(g)[*g.find("chain")];
  for (auto _ : state) {
    cache.erase(chain);  // the fits and joints stay cached: the chain alone runs
    benchmark::DoNotOptimize(evaluate(g, cache));
  }
  state.counters["samples/s"] = benchmark::Counter(static_cast<double>(samples) * state.iterations(), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_MonteCarloFused)
    ->Args({1000000, 1})
    ->Args({10000000, 1})
    ->Args({10000000, 2})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
