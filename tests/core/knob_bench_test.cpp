// mechgraph bench's engine: the knob ladders, the reference, the error and the work reported.
#include "test_support.hpp"

#include <mechgraph/errors.hpp>
#include <mechgraph/knob_bench.hpp>

#include <yaml-cpp/yaml.h>

#include <catch2/catch.hpp>

#include <set>

using namespace mechgraph;
using namespace mechgraph::testing;
using Catch::Matchers::Contains;

namespace {
Graph study(const std::vector<Override>& overrides) {
  return build_graph(load_scene(std::string(MECHGRAPH_SOURCE_DIR) + "/scenes/valvetrain_cams.yaml"), project_registry(),
                     overrides);
}
}  // namespace

TEST_CASE("bench: the rectangle sum converges at second order against the exact reference", "[bench]") {
  KnobBenchOptions options;
  options.node = "ta_arc";
  options.repeats = 1;
  const auto trials = bench_knobs(study({parse_override("ta_arc.method=rectangle")}), options);
  std::vector<double> step_errors;
  int defaults = 0;
  for (const KnobTrial& t : trials) {
    CHECK(t.failure.empty());
    CHECK(t.node == "ta_arc");
    if (t.knob == "step") {
      step_errors.push_back(t.max_relative_error);
      defaults += t.is_default ? 1 : 0;
      CHECK(t.work.at("evaluations") > 0);
    }
    if (t.knob == "method" && t.setting == "exact") CHECK(t.max_relative_error < 1e-12);
  }
  CHECK(defaults == 1);
  REQUIRE(step_errors.size() == 7);  // default x 2^-3 .. x 2^3
  // The three-arc law with lash has kinks in the flow area's slope: the sum is second order.
  for (std::size_t i = 1; i < step_errors.size(); ++i) {
    const double ratio = step_errors[i - 1] / step_errors[i];
    CHECK(ratio > 2.5);
    CHECK(ratio < 6.0);
  }
}

TEST_CASE("bench: knobs that do not matter show no error; every needed node with knobs is covered", "[bench]") {
  KnobBenchOptions options;
  options.repeats = 1;
  options.steps = 1;
  const Graph graph = study({});
  const auto trials = bench_knobs(graph, options);
  std::set<std::string> nodes;
  for (const KnobTrial& t : trials) {
    nodes.insert(t.node);
    // The exact time-area integrates piece by piece: its tolerance barely moves the result.
    if (t.knob == "tolerance" && t.type == "valvetrain.time_area") CHECK(t.max_relative_error < 1e-12);
  }
  std::size_t with_knobs = 0;
  for (std::size_t i : graph.order)
    for (const ParamSpec& p : graph.nodes[i].info().params)
      if (p.knob && graph.nodes[i].params.has(p.name)) {
        ++with_knobs;
        break;
      }
  CHECK(with_knobs == 21);
  CHECK(nodes.size() == with_knobs);
}

TEST_CASE("bench: unknown nodes and nodes without knobs are errors", "[bench]") {
  KnobBenchOptions options;
  options.node = "ta_kurtz";
  CHECK_THROWS_WITH(bench_knobs(study({}), options), Contains("did you mean 'ta_kurz'"));
  options.node = "a";
  CHECK_THROWS_WITH(bench_knobs(graph_from("nodes: { a: { type: test.constant, params: { value: 1 mm } } }\noutputs: [a.out]\n"),
                                options),
                    Contains("has no accuracy knobs"));
}

TEST_CASE("mechgraph bench prints a table and JSON", "[bench][cli]") {
  const std::string scene = "'" + std::string(MECHGRAPH_SOURCE_DIR) + "/scenes/culling_demo.yaml'";
  const std::string plugins = "--plugin-dir '" + std::string(MECHGRAPH_PLUGIN_DIR) + "' ";
  const auto table = run_cli(plugins + "bench " + scene + " --node ta_kurz --repeats 1");
  REQUIRE(table.exit_code == 0);
  CHECK_THAT(table.out, Contains("knob method") && Contains("knob step") && Contains("max rel. error"));
  const auto json = run_cli(plugins + "-q bench " + scene + " --json --steps 1 --repeats 1");
  REQUIRE(json.exit_code == 0);
  const YAML::Node parsed = YAML::Load(json.out);
  CHECK(parsed["trials"].size() > 5);
  CHECK(run_cli(plugins + "bench " + scene + " --node nope").exit_code == 2);
}
