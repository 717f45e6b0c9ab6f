// The SDK 1.x bridge (mechgraph/detail/export_node.hpp) hands a C++ node the parameters and inputs
// the host hands it on the pre-1.0 path, value for value: one node type that reads every kind
// (tests/test_plugins/param_echo_plugin.cpp) built with either entry, run on the same scenes. The
// bridge reuses its sets from one evaluation to the next (no allocation per call), so the scenes
// run one after another in one registry: what one evaluation left must never show in the next.
#include "test_support.hpp"

#include <mechgraph/evaluator.hpp>

#include <catch2/catch.hpp>

#include <string>
#include <vector>

using namespace mechgraph;
using namespace mechgraph::testing;

namespace {

// Every kind given: numbers, an integer, a choice, a text longer than a short string's buffer,
// a number list, a record list with an absent optional field and a defaulted one, the optionals
// present; three values on the multiple input (one twice) and a series.
const char* everything = R"(nodes:
  k1: { type: echo.constant, params: { value: 2 mm } }
  k2: { type: echo.constant, params: { value: 3 mm } }
  s: { type: echo.curve }
  e:
    type: echo.params
    params:
      length: 5 mm
      count: 7
      mode: exact
      label: a label longer than any short string buffer
      steps: [1 mm, 2 mm, 4 mm]
      links:
        - { size: 1 mm, n: 2, fit: slot, name: first }
        - { size: 2.5 mm }
      extra: 9 mm
      remark: hi
      weights: [0.25, 0.75]
    inputs: { in: [k1.out, k2.out, k1.out], curve: s.curve }
outputs: [ e.seen ]
)";

// Defaults only, the optionals absent, nothing connected.
const char* defaults = R"(nodes:
  e: { type: echo.params }
outputs: [ e.seen ]
)";

// Shorter lists, one record, other texts, one input: what a longer evaluation left must go.
const char* smaller = R"(nodes:
  k1: { type: echo.constant, params: { value: 4 mm } }
  e:
    type: echo.params
    params:
      label: x
      steps: [3 mm]
      links: [ { size: 3 mm, name: only } ]
      remark: a remark longer than any short string buffer
    inputs: { in: [k1.out] }
outputs: [ e.seen ]
)";

struct Seen {
  std::vector<std::string> labels;
  std::vector<double> values;
};

Seen seen(const PluginRegistry& r, const char* scene) {
  const RunResult run = run_yaml(scene, r);
  const Series& s = output(run, "e.seen").as_series();
  return {s.labels, s.values};
}

const PluginRegistry& registry_of(const std::string& plugin) {
  static std::map<std::string, PluginRegistry> registries;
  auto [it, fresh] = registries.try_emplace(plugin);
  if (fresh) it->second.load_file(test_plugin(plugin));
  return it->second;
}

void check_same(const Seen& pre_1_0, const Seen& sdk1) {
  REQUIRE(pre_1_0.labels.size() > 10);
  CHECK(sdk1.labels == pre_1_0.labels);
  REQUIRE(sdk1.values.size() == pre_1_0.values.size());
  for (std::size_t i = 0; i < pre_1_0.values.size(); ++i) {
    INFO(pre_1_0.labels[i]);
    CHECK(sdk1.values[i] == pre_1_0.values[i]);  // the same double: nothing is converted on the way
  }
}

}  // namespace

TEST_CASE("the SDK 1.x bridge hands a C++ node every kind of parameter and input as the pre-1.0 path does",
          "[plugins][sdk1][bridge]") {
  const PluginRegistry& pre_1_0 = registry_of("test_echo");
  const PluginRegistry& sdk1 = registry_of("test_echo_sdk1");
  REQUIRE(sdk1.plugins().at(0).fingerprint.find("sdk1.") != std::string::npos);
  // One after another, and back: each evaluation sees only its own parameters and inputs.
  for (const char* scene : {everything, defaults, smaller, everything, smaller, defaults, everything}) {
    INFO(scene);
    check_same(seen(pre_1_0, scene), seen(sdk1, scene));
  }
  // What the echo reads is what the scene says (the comparison above is not between two empties).
  const Seen all = seen(sdk1, everything);
  const auto value_of = [&](const std::string& label) {
    for (std::size_t i = 0; i < all.labels.size(); ++i)
      if (all.labels[i] == label) return all.values[i];
    FAIL("no '" << label << "' in what the node saw");
    return 0.0;
  };
  CHECK(value_of("number length") == Approx(0.005).epsilon(1e-12).margin(1e-15));
  CHECK(value_of("integer count") == 7.0);
  CHECK(value_of("text mode 'exact'") == 5.0);
  CHECK(value_of("numbers steps size") == 3.0);
  CHECK(value_of("records links size") == 2.0);
  CHECK(value_of("record 1 has name") == 0.0);
  CHECK(value_of("has extra") == 1.0);
  CHECK(value_of("count in") == 3.0);
  CHECK(value_of("count curve") == 1.0);
  CHECK(value_of("count undeclared") == 0.0);
  const Seen none = seen(sdk1, defaults);
  CHECK(std::find(none.labels.begin(), none.labels.end(), "has extra") != none.labels.end());
  CHECK(std::find(none.labels.begin(), none.labels.end(),
                  "get extra threw for 'extra': parameter 'extra' is not set") != none.labels.end());
}

TEST_CASE("the SDK 1.x bridge keeps each thread's evaluations apart", "[plugins][sdk1][bridge]") {
  // Nodes of one type with different parameters, run at once on several threads.
  std::string scene = "nodes:\n";
  std::string outputs = "outputs: [";
  for (int i = 0; i < 16; ++i) {
    const std::string n = std::to_string(i);
    scene += "  e" + n + ": { type: echo.params, params: { length: " + n + " mm, label: " + std::string(i + 1, 'x') +
             ", steps: [" + n + " mm" + (i % 2 ? ", 1 mm" : "") + "] } }\n";
    outputs += (i ? ", e" : "e") + n + ".seen";
  }
  scene += outputs + "]\n";
  const auto run = [&](const std::string& plugin, unsigned threads) {
    MemoCache cache;
    return evaluate(graph_from(scene, registry_of(plugin)), cache, threads);
  };
  const RunResult pre_1_0 = run("test_echo", 1);
  for (int round = 0; round < 5; ++round) {
    const RunResult sdk1 = run("test_echo_sdk1", 4);
    for (int i = 0; i < 16; ++i) {
      const std::string label = "e" + std::to_string(i) + ".seen";
      INFO(label);
      CHECK(output(sdk1, label).as_series().labels == output(pre_1_0, label).as_series().labels);
      CHECK(output(sdk1, label).as_series().values == output(pre_1_0, label).as_series().values);
    }
  }
}
