// C++ node types exported through the SDK 1.x C boundary (mechgraph/plugin_sdk1.hpp), built by
// the project's compiler and by clang++ (tests/test_plugins/sdk1_cxx_plugin.cpp), loaded into this
// host beside a pre-1.0 plugin: the two paths meet in one scene.
#include "test_support.hpp"

#include <mechgraph/c/base.h>
#include <mechgraph/errors.hpp>
#include <mechgraph/work_estimate.hpp>

#include <catch2/catch.hpp>

using namespace mechgraph;
using namespace mechgraph::testing;
using Catch::Matchers::Contains;

namespace {

std::vector<std::string> builds() {
  std::vector<std::string> out{"test_sdk1_cxx"};
  if (std::filesystem::exists(test_plugin("test_sdk1_other"))) out.push_back("test_sdk1_other");
  return out;
}

// The compiler a build's fingerprint names: test_sdk1_cxx is built by this host's compiler,
// test_sdk1_other by the other one (tests/CMakeLists.txt).
std::string compiler_of(const std::string& build) {
#if defined(__clang__)
  const bool host_is_clang = true;
#else
  const bool host_is_clang = false;
#endif
  return (build == "test_sdk1_other") != host_is_clang ? "; clang" : "; gcc";
}

const char* scene = R"(nodes:
  k: { type: test.constant, params: { value: 3 mm } }
  s: { type: cxx1.scale, params: { gain: 4 }, inputs: { in: k.out } }
  c: { type: cxx1.curve, params: { a: 2 mm, points: 3 } }
outputs: [ s.out, c.table, c.series ]
)";

}  // namespace

TEST_CASE("C++ node types behind the C boundary run beside a pre-1.0 plugin, whichever compiler built them",
          "[plugins][sdk1]") {
  REQUIRE(std::filesystem::exists(test_plugin("test_sdk1_other")));  // clang++ and g++ are dependencies (install-deps.sh)
  for (const std::string& build : builds()) {
    INFO(build);
    PluginRegistry r;
    r.load_file(test_plugin("test_arith"));
    r.load_file(test_plugin(build));
    REQUIRE(r.plugins().size() == 2);
    CHECK_THAT(r.plugins()[1].fingerprint,
               Contains("sdk1." + std::to_string(MG_SDK_MINOR) + compiler_of(build)));
    const RunResult run = run_yaml(scene, r);
    CHECK(scalar_output(run, "s.out") == Approx(0.012).epsilon(1e-12).margin(1e-15));
    const Table& t = output(run, "c.table").as_table();
    REQUIRE(t.channels.size() == 1);
    CHECK(t.channels[0].display_unit == "mm");
    CHECK(t.channels[0].values[1] == Approx(0.0005).epsilon(1e-12).margin(1e-15));
    CHECK(output(run, "c.series").as_series().values.back() == Approx(0.002).epsilon(1e-12).margin(1e-15));
    CHECK(run.runs[1].notes == std::vector<std::string>{"scaled in C++ behind the C boundary"});
    CHECK(run.runs[1].work.at("products") == 1.0);
    // NodeType::forecast crosses as mechgraph.node.forecast/1 (SDK 1.1); a type without one (scale)
    // is counted by the conventions.
    const WorkEstimate estimate = estimate_work(graph_from(scene, r));
    const auto term = [&](const std::string& what) -> const WorkEstimate::Term* {
      for (const WorkEstimate::Term& t : estimate.terms)
        if (t.what == what) return &t;
      return nullptr;
    };
    const WorkEstimate::Term* curve = term("c.points = 3 (cxx1.curve)");
    REQUIRE(curve != nullptr);
    CHECK(curve->work == 1500.0);
    CHECK(curve->memory == 192.0);
    // A NodeError thrown in the plugin crosses as MG_ERR_NODE and names the node and the parameter.
    CHECK_THROWS_MATCHES(run_yaml(R"(nodes:
  c: { type: cxx1.curve, params: { a: -1 mm } }
outputs: [ c.series ]
)", r),
                         EvaluationError,
                         Catch::Matchers::Message("scene.yaml:2:39: node 'c' (cxx1.curve), parameter 'a': a negative a "
                                                  "would dig below the axis"));
  }
}

TEST_CASE("a plugin built by the other compiler passes plugin-test in this host", "[plugins][sdk1][cli]") {
  const CommandResult r = run_cli("plugin-test '" + test_plugin("test_sdk1_other").string() + "'");
  INFO(r.out << r.err);
  CHECK(r.exit_code == 0);
  CHECK_THAT(r.out, Contains("cxx1.curve: ") && Contains(" passed, 0 failed"));
  CHECK_THAT(r.out, !Contains("FAIL "));
}

// What is read downstream (mg_eval_args::wanted, SDK 1.4) reaches a C++ node behind the C boundary:
// from the graph node's mask when the evaluator calls it, and from any other context output by
// output. A node that leaves out what nobody reads (cxx1.curve's table) must then be run again
// for a graph that reads it, even through a memo cache the first graph filled.
TEST_CASE("the outputs read downstream reach a C++ node behind the C boundary by mask or asked one by one",
          "[plugins][sdk1]") {
  struct SeriesOnly final : EvalContext {
    bool effect(std::string_view) const override { return false; }
    void log(LogLevel, std::string_view) override {}
    void report_work(std::string_view, double) override {}
    bool wanted(std::string_view output) const override { return output == "series"; }
  };
  for (const std::string& build : builds()) {
    INFO(build);
    PluginRegistry r;
    r.load_file(test_plugin(build));
    const RegisteredType* curve = r.find("cxx1.curve");
    REQUIRE(curve);
    const ParamSet p = defaults_of(curve->type->info(), {{"a", ParamValue::of_number(0.002)}, {"points", ParamValue::of_integer(3)}});
    OutputSet some;
    SeriesOnly series_only;
    curve->type->evaluate(p, InputSet{}, some, series_only);
    CHECK(some.all().count("table") == 0);
    CHECK(some.all().count("series") == 1);
    OutputSet every;
    RecordingContext everything;
    curve->type->evaluate(p, InputSet{}, every, everything);
    CHECK(every.all().count("table") == 1);

    MemoCache cache;
    const std::string node = "nodes:\n  c: { type: cxx1.curve, params: { a: 2 mm, points: 3 } }\n";
    (void)evaluate(graph_from(node + "outputs: [ c.series ]\n", r), cache);
    const RunResult both = evaluate(graph_from(node + "outputs: [ c.series, c.table ]\n", r), cache);
    const Table& t = output(both, "c.table").as_table();
    REQUIRE(t.channels.size() == 1);
    CHECK(t.channels[0].values[1] == Approx(0.0005).epsilon(1e-12).margin(1e-15));
  }
}
