// How fast the framework evaluates the valve-train study, cold and through the memo cache, and
// what a sweep over engine speed costs when only the speed-dependent nodes re-run.
//   build/bench/mechgraph_bench --benchmark_min_time=0.2
#include <mechgraph/bounded_read.hpp>
#include <mechgraph/domain/cam_law.hpp>
#include <mechgraph/evaluator.hpp>
#include <mechgraph/graph.hpp>
#include <mechgraph/host/study_run.hpp>
#include <mechgraph/plugin_registry.hpp>
#include <mechgraph/scene.hpp>
#include <mechgraph/sweep/sweep_runner.hpp>
#include <mechgraph/work_estimate.hpp>

#include "bench_support.hpp"

#include <benchmark/benchmark.h>

#include <string>

namespace {

using namespace mechgraph;

const PluginRegistry& registry() { return bench::project_plugins(); }

const SceneSpec& study() {
  static const SceneSpec s = load_scene(std::string(MECHGRAPH_SOURCE_DIR) + "/scenes/valvetrain_cams.yaml");
  return s;
}

// Load + check the scene against the plugins (no evaluation).
void BM_BuildGraph(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(build_graph(study(), registry()));
}
BENCHMARK(BM_BuildGraph);

// Every node evaluated: a fresh cache each time.
void BM_EvaluateCold(benchmark::State& state) {
  const Graph g = build_graph(study(), registry());
  for (auto _ : state) {
    MemoCache cache;
    benchmark::DoNotOptimize(evaluate(g, cache));
  }
}
BENCHMARK(BM_EvaluateCold)->Unit(benchmark::kMicrosecond);

// Every node found in the cache: the cost of hashing and lookup.
void BM_EvaluateWarm(benchmark::State& state) {
  const Graph g = build_graph(study(), registry());
  MemoCache cache;
  evaluate(g, cache);
  for (auto _ : state) benchmark::DoNotOptimize(evaluate(g, cache));
}
BENCHMARK(BM_EvaluateWarm)->Unit(benchmark::kMicrosecond);

// A sweep over 50 engine speeds sharing one cache: the cams run once, the rest 50 times.
void BM_SweepRpm50(benchmark::State& state) {
  const SceneSpec& scene = study();
  const Graph g = build_graph(scene, registry());
  const CaseTable cases = make_grid({parse_vary("rpm=3000rpm:7900rpm:50")});
  const CaseBinder binder(g, scene, registry(), {}, cases.variables);
  SweepOptions options;
  for (std::size_t i = 0; i < cases.size(); ++i) options.cases.push_back(i);
  for (auto _ : state) {
    MemoCache cache;
    run_sweep(g, binder, cases, cache, options, [](CaseResult&& r) { benchmark::DoNotOptimize(r); });
  }
}
BENCHMARK(BM_SweepRpm50)->Unit(benchmark::kMillisecond);

// Stages 1-3 of the three cams (profile summary, valve kinematics, time-area) over a Latin
// hypercube of lift, action and accel angle, base radius, rpm and lash: every node runs for every
// case. One "design" is one cam
// through the three stages, so a case is three designs; designs/s is the figure the issue's goal
// and bench/peers compare. Args: threads, cases per block (0: every case alone, the per-case
// path; 256: the default block path).
void BM_SweepStages123(benchmark::State& state) {
  SceneSpec scene = study();
  scene.report.clear();
  scene.outputs.clear();
  for (const char* cam : {"arc", "kurz", "poly"}) {
    const std::string c(cam), v = "v_" + c, ta = "ta_" + c;
    for (const std::string& port : {c + ".accel_angle", c + ".min_curvature_radius", c + ".max_velocity", v + ".max_lift",
                                    v + ".max_velocity", v + ".max_acceleration", v + ".min_acceleration",
                                    ta + ".time_area", ta + ".angle_area", ta + ".mean_flow_area"})
      scene.outputs.push_back(parse_port_ref(port, {}));
  }
  const Graph g = build_graph(scene, registry());
  // Every law changes shape from case to case (bench/peers/ draws the same box).
  const CaseTable cases = make_latin_hypercube({parse_sample("lift=7mm:9mm"), parse_sample("action=120deg:140deg"),
                                                parse_sample("accel=15deg:21deg"), parse_sample("r0=24mm:28mm"),
                                                parse_sample("rpm=4000rpm:7000rpm"), parse_sample("lash=0.1mm:0.4mm")},
                                               1000, 1);
  const CaseBinder binder(g, scene, registry(), {}, cases.variables);
  SweepOptions options;
  options.threads = static_cast<unsigned>(state.range(0));
  options.block_size = static_cast<std::size_t>(state.range(1));
  for (std::size_t i = 0; i < cases.size(); ++i) options.cases.push_back(i);
  std::size_t failed = 0;
  for (auto _ : state) {
    MemoCache cache;
    run_sweep(g, binder, cases, cache, options, [&](CaseResult&& r) { failed += r.failure != CaseFailure::none; });
  }
  state.counters["designs/s"] = benchmark::Counter(3.0 * cases.size() * state.iterations(), benchmark::Counter::kIsRate);
  state.counters["failed"] = static_cast<double>(failed) / state.iterations();
}
BENCHMARK(BM_SweepStages123)->Args({1, 0})->Args({1, 256})->Args({2, 0})->Args({2, 256})->Unit(benchmark::kMillisecond)->UseRealTime();

// An uncertainty study of the stage 1-3 graph (bench/peers/stages123_study.yaml): six uniform
// parameters, scrambled Sobol' points with Saltelli's design (8 evaluations a base sample) and
// Sobol' indices with 200 bootstrap resamples, everything a `mechgraph study` does but reading the
// scene and printing. Args: threads, base samples. evaluations/s counts the study's cases.
void BM_StudyStages123(benchmark::State& state) {
  const std::string samples = std::to_string(state.range(1));
  std::string yaml = read_bounded_file(std::string(MECHGRAPH_SOURCE_DIR) + "/bench/peers/stages123_study.yaml");
  yaml.replace(yaml.find("\nnodes:"), 7, R"(
uncertainty:
  method: sobol
  samples: )" + samples + R"(
  seed: 1
  sensitivity: true
  parameters:
    lift:   { uniform: { lower: 7 mm, upper: 9 mm } }
    action: { uniform: { lower: 120 deg, upper: 140 deg } }
    accel:  { uniform: { lower: 15 deg, upper: 21 deg } }
    r0:     { uniform: { lower: 24 mm, upper: 28 mm } }
    rpm:    { uniform: { lower: 4000 rpm, upper: 7000 rpm } }
    lash:   { uniform: { lower: 0.1 mm, upper: 0.4 mm } }
nodes:)");
  const SceneSpec scene = parse_scene(yaml, "stages123_study.yaml");
  WorkBudget budget;  // a study's, as `mechgraph study` sets it
  budget.max_work = sweep_default_max_work;
  std::size_t cases = 0;
  for (auto _ : state) {
    const auto outcome = host::run_scene_study(scene, registry(), {}, std::nullopt, "", "", "", std::nullopt, budget,
                                               static_cast<unsigned>(state.range(0)), nullptr);
    cases = outcome->answers.cases;
    benchmark::DoNotOptimize(outcome->answers.outputs.data());
  }
  state.counters["evaluations/s"] = benchmark::Counter(static_cast<double>(cases * state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_StudyStages123)->Args({1, 2500})->Args({2, 2500})->Args({2, 125000})->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);

// The time-area knob: exact quadrature against the source's rectangle sum.
void BM_TimeAreaMethod(benchmark::State& state) {
  const std::string method = state.range(0) == 0 ? "exact" : "rectangle";
  const Graph g = build_graph(study(), registry(),
                              {parse_override("ta_kurz.method=" + method), parse_override("ta_arc.method=" + method),
                               parse_override("ta_poly.method=" + method)});
  MemoCache warm;
  evaluate(g, warm);
  for (auto _ : state) {
    MemoCache cache;
    benchmark::DoNotOptimize(evaluate(g, cache));
  }
  state.SetLabel(method);
}
BENCHMARK(BM_TimeAreaMethod)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

}  // namespace

// A scene of N independent cams, each output requested: graph building must not be quadratic in N.
void BM_BuildLargeGraph(benchmark::State& state) {
  std::string yaml = "nodes:\n";
  std::string outputs = "outputs: [";
  for (long i = 0; i < state.range(0); ++i) {
    yaml += "  c" + std::to_string(i) + ": { type: cam.cycloidal, params: { max_lift: 8 mm, action_angle: 130 deg, base_radius: 40 mm } }\n";
    outputs += (i ? ", c" : "c") + std::to_string(i) + ".max_lift";
  }
  const SceneSpec scene = parse_scene(yaml + outputs + "]\n", "large.yaml");
  for (auto _ : state) benchmark::DoNotOptimize(build_graph(scene, registry()));
  state.SetComplexityN(state.range(0));
}
BENCHMARK(BM_BuildLargeGraph)->Arg(1000)->Arg(2000)->Arg(4000)->Unit(benchmark::kMillisecond)->Complexity();

#ifdef MECHGRAPH_TEST_ARITH_PLUGIN
// The bare cost of one node call through the host: a graph of one node with one scalar output
// (test.constant), evaluated cold. What the plugin boundary adds per node is measured here (the
// SDK 1.0 budget: docs/design/sdk-1.0.md, section 4.1).
void BM_NodeCallOverhead(benchmark::State& state) {
  static const PluginRegistry arith = [] {
    PluginRegistry r;
    r.load_file(MECHGRAPH_TEST_ARITH_PLUGIN);
    return r;
  }();
  const Graph g = build_graph(parse_scene("title: one node\nnodes:\n  a: { type: test.constant, params: { value: 1 mm } }\n"
                                          "outputs: [ a.out ]\n",
                                          "node_call.yaml"),
                             arith);
  for (auto _ : state) {
    MemoCache cache;
    benchmark::DoNotOptimize(evaluate(g, cache));
  }
}
BENCHMARK(BM_NodeCallOverhead)->Unit(benchmark::kNanosecond);
#endif

#if defined(MECHGRAPH_TEST_ARITH_PLUGIN) && defined(MECHGRAPH_TEST_ARITH_SDK1_PLUGIN)
// One C++ node type through both entries, side by side ("no loss of speed"): the test plugin's
// test.constant feeding a chain of `adds` test.add nodes, built with the pre-1.0 entry (entry 0)
// and with MECHGRAPH_PLUGIN_1, called as itself (entry 1: one C++ layer, c/node_cxx.h) or through
// the C boundary and the SDK's bridge (entry 2, mechgraph/detail/export_node.hpp, as a host of
// another compiler calls it). What one test.add costs through an entry is
// (time at adds:8 - time at adds:0) / 8; compare the entries with the fastest of several
// interleaved runs (--benchmark_repetitions, --benchmark_enable_random_interleaving).
void BM_NodeCallEntries(benchmark::State& state) {
  static const PluginRegistry pre_1_0 = [] {
    PluginRegistry r;
    r.load_file(MECHGRAPH_TEST_ARITH_PLUGIN);
    return r;
  }();
  static const PluginRegistry sdk1 = [] {
    PluginRegistry r;
    r.load_file(MECHGRAPH_TEST_ARITH_SDK1_PLUGIN);
    return r;
  }();
  static const PluginRegistry sdk1_c = [] {
    PluginRegistry r;
    r.set_node_types_through_c(true);
    r.load_file(MECHGRAPH_TEST_ARITH_SDK1_PLUGIN);
    return r;
  }();
  const PluginRegistry* registries[] = {&pre_1_0, &sdk1, &sdk1_c};
  const long adds = state.range(1);
  std::string yaml = "title: a chain of adds\nnodes:\n  k: { type: test.constant, params: { value: 1 mm } }\n";
  std::string last = "k.out";
  for (long i = 0; i < adds; ++i) {
    const std::string name = "a" + std::to_string(i);
    yaml += "  " + name + ": { type: test.add, inputs: { a: " + last + ", b: [ k.out ] } }\n";
    last = name + ".sum";
  }
  yaml += "outputs: [ " + last + " ]\n";
  const Graph g = build_graph(parse_scene(yaml, "node_calls.yaml"), *registries[state.range(0)]);
  for (auto _ : state) {
    MemoCache cache;
    benchmark::DoNotOptimize(evaluate(g, cache));
  }
  const char* labels[] = {"pre-1.0 entry", "MECHGRAPH_PLUGIN_1, as itself", "MECHGRAPH_PLUGIN_1, through C"};
  state.SetLabel(labels[state.range(0)]);
}
BENCHMARK(BM_NodeCallEntries)->ArgNames({"entry", "adds"})->ArgsProduct({{0, 1, 2}, {0, 8}})->Unit(benchmark::kNanosecond);
#endif

#if defined(MECHGRAPH_TEST_STROKE_PLUGIN) && defined(MECHGRAPH_TEST_STROKE_SDK1_PLUGIN)
// A node that makes tables (pump.stroke: a 181-row motion table, port events, seal gaps and a scalar), through
// the pre-1.0 entry (0) and MECHGRAPH_PLUGIN_1 through C (1; test_stroke_sdk1 is built without the shortcut
// of c/node_cxx.h): what the boundary costs a node with real output.
void BM_StrokeEntries(benchmark::State& state) {
  static const PluginRegistry pre_1_0 = [] {
    PluginRegistry r;
    r.load_file(MECHGRAPH_TEST_STROKE_PLUGIN);
    return r;
  }();
  static const PluginRegistry sdk1 = [] {
    PluginRegistry r;
    r.load_file(MECHGRAPH_TEST_STROKE_SDK1_PLUGIN);
    return r;
  }();
  const PluginRegistry* registries[] = {&pre_1_0, &sdk1};
  const Graph g = build_graph(parse_scene("title: a pump\nnodes:\n  p: { type: pump.stroke, params: { phase: 30 deg } }\n"
                                          "outputs: [ p.motion, p.gaps, p.port_events, p.peak_angle ]\n",
                                          "stroke.yaml"),
                             *registries[state.range(0)]);
  for (auto _ : state) {
    MemoCache cache;
    benchmark::DoNotOptimize(evaluate(g, cache));
  }
  const char* labels[] = {"pre-1.0 entry", "MECHGRAPH_PLUGIN_1, through C"};
  state.SetLabel(labels[state.range(0)]);
}
BENCHMARK(BM_StrokeEntries)->ArgName("entry")->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);
#endif

BENCHMARK_MAIN();

namespace {
using namespace mechgraph;

// One law evaluation (lift and three derivatives) of each example cam, at 1000 angles across the
// event: the unit cost everything in stages 1-3 is made of.
void BM_LawEvaluation(benchmark::State& state) {
  static const char* cams[] = {"arc", "kurz", "poly"};
  const std::string cam = cams[state.range(0)];
  SceneSpec scene = study();
  scene.report.clear();
  scene.outputs = {parse_port_ref(cam + ".max_lift", {})};
  const Graph g = build_graph(scene, registry());
  MemoCache cache;
  evaluate(g, cache);
  const auto outputs = cache.find(node_hashes(g)[*g.find(cam)]);
  const auto law = std::dynamic_pointer_cast<const CamLaw>(outputs->all().at("law").as_handle());
  std::vector<double> angles(1000);
  for (std::size_t i = 0; i < angles.size(); ++i)
    angles[i] = law->event_begin() + (law->event_end() - law->event_begin()) * (static_cast<double>(i) + 0.5) / angles.size();
  for (auto _ : state)
    for (double phi : angles) benchmark::DoNotOptimize(law->at(phi));
  state.SetItemsProcessed(state.iterations() * static_cast<long>(angles.size()));
  state.SetLabel(cam);
}
BENCHMARK(BM_LawEvaluation)->DenseRange(0, 2);

}  // namespace
