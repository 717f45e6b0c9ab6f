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

TEST_CASE("bench advice: Pareto front, the cheapest setting within the tolerance, a default far off the front", "[bench]") {
  auto trial = [](const std::string& setting, double seconds, double error, bool is_default = false) {
    KnobTrial t;
    t.node = "n";
    t.type = "t";
    t.knob = "samples";
    t.setting = setting;
    t.seconds = seconds;
    t.max_relative_error = error;
    t.is_default = is_default;
    return t;
  };
  std::vector<KnobTrial> trials = {trial("8", 1.0, 1e-6), trial("16", 2.0, 1e-10), trial("32", 4.0, 1e-10, true),
                                   trial("64", 8.0, 1e-14), trial("128", 9.0, 1e-12)};
  trials.push_back(trial("256", 0.0, 0.0));
  trials.back().failure = "did not converge";
  const auto advice = advise_knobs(trials, 1e-9);
  REQUIRE(advice.size() == 1);
  CHECK(trials[0].on_front);
  CHECK(trials[1].on_front);
  CHECK_FALSE(trials[2].on_front);  // as accurate as 16 and slower
  CHECK(trials[3].on_front);
  CHECK_FALSE(trials[4].on_front);  // 64 is faster and more accurate
  CHECK_FALSE(trials[5].on_front);  // failed
  REQUIRE(advice[0].recommended);
  CHECK(*advice[0].recommended == 1);
  CHECK(advice[0].current_off_front);  // 16 is as accurate in half the time
  CHECK_THAT(advice[0].text, Contains("within 1e-09: samples = 16") && Contains("far off the front"));
  const auto strict = advise_knobs(trials, 1e-15);
  CHECK_FALSE(strict[0].recommended);
  CHECK_THAT(strict[0].text, Contains("no setting reaches 1e-15; the most accurate is samples = 64"));
}

TEST_CASE("mechgraph bench on a Monte Carlo scene: error of the estimate, advice, SVG plot", "[bench][cli]") {
  const std::string scene = "'" + std::string(MECHGRAPH_SOURCE_DIR) + "/scenes/backlash_chain.yaml'";
  const std::string plugins = "--plugin-dir '" + std::string(MECHGRAPH_PLUGIN_DIR) + "' ";
  const auto dir = std::filesystem::temp_directory_path() / ("mechgraph_bench_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  const auto r = run_cli(plugins + "bench " + scene + " --steps 1 --repeats 1 --set chain.samples=20000 --out '" + dir.string() + "'");
  REQUIRE(r.exit_code == 0);
  CHECK_THAT(r.out, Contains("knob samples") && Contains("-> "));
  CHECK_THAT(r.err, Contains("bench: node 1 of"));
  const YAML::Node json = YAML::LoadFile((dir / "bench.json").string());
  bool chain_seen = false;
  for (const auto& t : json["trials"]) {
    if (t["node"].as<std::string>() != "chain") continue;
    chain_seen = true;
    // The estimates against 8x the samples: a few standard errors of 2e4 samples, not a ratio of
    // them (the share out of spec, a rare event, has a larger relative error: 1/sqrt(k) for k hits).
    for (const auto& e : t["errors"]) {
      const std::string output = e.first.as<std::string>();
      INFO(output);
      if (output.find("out_of_spec") == std::string::npos) CHECK(e.second.as<double>() < 0.05);
      else CHECK(e.second.as<double>() < 0.3);
    }
    CHECK_FALSE(t["errors"]["chain.mc_mean_error"]);
  }
  CHECK(chain_seen);
  CHECK(json["advice"].size() > 0);
  if (std::system("command -v gnuplot >/dev/null 2>&1") == 0) {
    std::ifstream svg(dir / "bench.svg");
    const std::string text((std::istreambuf_iterator<char>(svg)), {});
    CHECK_THAT(text, Contains("<svg") && Contains("chain.samples"));
  }
  std::filesystem::remove_all(dir);
}
