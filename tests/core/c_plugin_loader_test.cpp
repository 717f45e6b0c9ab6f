// The second loader path: plugins of the SDK 1.x C boundary (mechgraph_plugin_entry_1), written
// in C (tests/test_plugins/c_minimal.c and its variants), beside the pre-1.0 C++ plugins.
#include "sweep_support.hpp"
#include "test_support.hpp"
#include "../../core/src/c_node_type.hpp"  // forecast_reads

#include <mechgraph/c/base.h>
#include <mechgraph/cancellation.hpp>
#include <mechgraph/errors.hpp>
#include <mechgraph/sweep/case_estimate.hpp>
#include <mechgraph/work_estimate.hpp>

#include <catch2/catch.hpp>

#include <dlfcn.h>
#include <fstream>
#include <numeric>

using namespace mechgraph;
using namespace mechgraph::testing;
using Catch::Matchers::Contains;

namespace {

const PluginRegistry& c_registry() {
  static const PluginRegistry r = [] {
    PluginRegistry registry;
    registry.load_file(test_plugin("test_c_minimal"));
    return registry;
  }();
  return r;
}

const char* parabola_scene = R"(nodes:
  p: { type: cmin.parabola, params: { height: 20 mm, points: 3 } }
outputs: [ p.curve, p.peak ]
)";

}  // namespace

TEST_CASE("a plugin written in C loads through mechgraph_plugin_entry_1 with its description", "[plugins][sdk1]") {
  const PluginRegistry& r = c_registry();
  REQUIRE(r.plugins().size() == 1);
  CHECK(r.plugins()[0].id == "cmin");
  CHECK(r.plugins()[0].version == "1.0.0");
  CHECK(r.plugins()[0].fingerprint == "sdk1." + std::to_string(MG_SDK_MINOR) + "; C");
  const RegisteredType* t = r.find("cmin.parabola");
  REQUIRE(t != nullptr);
  const NodeInfo& info = t->type->info();
  CHECK(info.summary == "a parabola as a table (a plugin written in C)");
  REQUIRE(info.params.size() == 3);
  CHECK(info.params[0].kind == ParamKind::integer);
  CHECK(info.params[0].knob);
  CHECK(info.params[1].name == "height");
  CHECK(info.params[1].dimension == dim::length);
  CHECK(info.params[1].display_unit == "mm");
  CHECK(info.params[1].min_exclusive);
  CHECK_FALSE(info.params[1].required);
  REQUIRE(info.params[1].default_value);
  CHECK(info.params[1].default_value->number == Approx(0.01).epsilon(1e-12).margin(1e-15));
  REQUIRE(info.outputs.size() == 2);
  CHECK(info.outputs[0].kind == ValueKind::table);
  CHECK(info.outputs[1].display_unit == "mm");
  CHECK(info.work_counters == std::vector<std::string>{"points"});
}

TEST_CASE("a C node runs in a scene: a table adopted from the plugin, a scalar, a note, a work counter", "[plugins][sdk1]") {
  const RunResult r = run_yaml(parabola_scene, c_registry());
  const Table& curve = output(r, "p.curve").as_table();
  REQUIRE(curve.axis.values.size() == 3);
  CHECK(curve.axis.name == "x");
  REQUIRE(curve.channels.size() == 1);
  CHECK(curve.channels[0].name == "y");
  CHECK(curve.channels[0].display_unit == "mm");
  CHECK(curve.channels[0].values[1] == Approx(0.005).epsilon(1e-12).margin(1e-15));
  CHECK(curve.channels[0].values[2] == Approx(0.02).epsilon(1e-12).margin(1e-15));
  CHECK(scalar_output(r, "p.peak") == Approx(0.02).epsilon(1e-12).margin(1e-15));
  REQUIRE(r.runs.size() == 1);
  CHECK(r.runs[0].notes == std::vector<std::string>{"cmin: a parabola in C"});
  CHECK(r.runs[0].work.at("points") == 3.0);
}

TEST_CASE("a C node's MG_ERR_NODE names the node and the parameter, at its place in the scene", "[plugins][sdk1]") {
  CHECK_THROWS_MATCHES(run_yaml(R"(nodes:
  p: { type: cmin.parabola, params: { height: 20 mm, limit: 10 mm } }
outputs: [ p.peak ]
)", c_registry()),
                       EvaluationError,
                       Catch::Matchers::Message(
                           "scene.yaml:2:47: node 'p' (cmin.parabola), parameter 'height': a height above the limit "
                           "would not fit (height > limit)"));
}

TEST_CASE("a C plugin passes mechgraph plugin-test", "[plugins][sdk1][cli]") {
  const CommandResult r = run_cli("plugin-test '" + test_plugin("test_c_minimal").string() + "'");
  INFO(r.out << r.err);
  CHECK(r.exit_code == 0);
  CHECK_THAT(r.out, Contains("cmin.parabola"));
  CHECK_THAT(r.out, Contains("PASS  node cmin.parabola: its forecast reads only the parameters it names"));
}

TEST_CASE("an SDK 1.x plugin whose structs are shorter (an older 1.x) loads, absent fields taken as defaults",
          "[plugins][sdk1]") {
  PluginRegistry r;
  r.load_file(test_plugin("test_c_older"));
  const NodeInfo& info = r.find("cmin.parabola")->type->info();
  // Its output declarations end before display_unit: the array is strided by their size.
  REQUIRE(info.outputs.size() == 2);
  CHECK(info.outputs[0].name == "curve");
  CHECK(info.outputs[1].name == "peak");
  CHECK(info.outputs[1].kind == ValueKind::scalar);
  CHECK(info.outputs[1].display_unit.empty());
  CHECK(info.work_counters.empty());  // its mg_node_desc ends before the counters
  const RunResult run = run_yaml(parabola_scene, r);
  CHECK(scalar_output(run, "p.peak") == Approx(0.02).epsilon(1e-12).margin(1e-15));
  // A 1.0 plugin answers no node type interface: its work is counted by the conventions
  // (an integer parameter named points: one item a point).
  CHECK(estimate_work(graph_from(parabola_scene, r)).work == 3.0);
  CHECK_FALSE(mechgraph::detail::forecast_reads(*r.find("cmin.parabola")->type));  // nor what a forecast reads
}

TEST_CASE("the host asks a C node type for its own work forecast (mechgraph.node.forecast/1) by name and version",
          "[plugins][sdk1]") {
  const WorkEstimate estimate = estimate_work(graph_from(parabola_scene, c_registry()));
  CHECK(estimate.work == 3000.0);  // 1000 items a point, as cmin.parabola forecasts, not 3 by the conventions
  CHECK(estimate.memory == 48.0);
  REQUIRE_FALSE(estimate.terms.empty());
  CHECK(estimate.terms[0].what == "p.points (1000 items a point) (cmin.parabola)");
  // And what it reads (mechgraph.node.forecast_reads/1, SDK 1.3): the index of points, as its name.
  CHECK(mechgraph::detail::forecast_reads(*c_registry().find("cmin.parabola")->type) ==
        std::optional<std::vector<std::string>>(std::vector<std::string>{"points"}));
}

TEST_CASE("a sweep's budget asks a C forecast once while the cases change nothing it reads", "[plugins][sdk1][forecast]") {
  const PluginRegistry& r = c_registry();
  void* handle = dlopen(test_plugin("test_c_minimal").c_str(), RTLD_NOW | RTLD_NOLOAD);  // the registry's own
  REQUIRE(handle);
  const auto asked = reinterpret_cast<long (*)()>(dlsym(handle, "cmin_forecasts_asked"));
  REQUIRE(asked);
  const std::string scene = R"(params:
  height: 20 mm
  points: 3
nodes:
  p: { type: cmin.parabola, params: { height: $height, points: $points } }
outputs: [ p.peak ]
)";
  for (const char* variable : {"height", "points"}) {
    INFO("varying " << variable);
    CaseTable table;
    table.variables = {{variable, ""}};
    const bool height = std::string(variable) == "height";
    for (int k = 0; k < 100; ++k)
      table.cases.push_back({read_case_value(height ? std::to_string(10 + k % 7) + " mm" : std::to_string(3 + k % 5), variable)});
    const Prepared p = prepare(scene, table, r);
    std::vector<std::size_t> all(table.size());
    std::iota(all.begin(), all.end(), std::size_t{0});
    const long before = asked();
    const SweepEstimate e = estimate_cases(p.graph, *p.binder, p.table, all, 1);
    const long calls = asked() - before;
    // One worker: the first case, then the largest case once more for the message's terms.
    if (height) CHECK(calls <= 2);
    else CHECK(calls >= 100);
    double work = 0;
    for (const auto& values : table.cases) work += 1000.0 * (height ? 3.0 : *values[0].si);
    CHECK(e.total.work == work);
  }
  dlclose(handle);
}

TEST_CASE("SDK 1.x plugins that cannot load are refused with a precise reason", "[plugins][sdk1]") {
  SECTION("a newer minor than the host's: both versions named") {
    PluginRegistry r;
    CHECK_THROWS_WITH(r.load_file(test_plugin("test_c_newer")),
                      Contains("was built against mechgraph SDK 1." + std::to_string(MG_SDK_MINOR + 1)) &&
                          Contains("newer than SDK 1." + std::to_string(MG_SDK_MINOR)) && Contains("update mechgraph"));
    CHECK(r.plugins().empty());
  }
  SECTION("an entry that returns NULL: its own reason") {
    PluginRegistry r;
    CHECK_THROWS_WITH(r.load_file(test_plugin("test_c_refuses")),
                      Contains("its entry refused to load") && Contains("no licence for this machine (cmin refuses to load)"));
  }
  SECTION("a port naming an angle frame its type does not declare: the port and the reference named") {
    PluginRegistry r;
    CHECK_THROWS_WITH(r.load_file(test_plugin("test_c_bad_frame")),
                      Contains("node type 'cmin.parabola' output 'peak' names angle frame 1, but the type declares 0"));
    CHECK(r.plugins().empty());
  }
}

TEST_CASE("a C node polls the host's cancellation and stops", "[plugins][sdk1]") {
  PluginRegistry r;
  r.load_file(test_plugin("test_c_polls"));
  const char* scene = R"(nodes:
  w: { type: cmin.wait, params: { steps: 1000 } }
outputs: [ w.done ]
)";
  CHECK(scalar_output(run_yaml(scene, r), "w.done") == 1000.0);
  request_cancellation();
  CHECK_THROWS_MATCHES(run_yaml(scene, r), EvaluationError,
                       Catch::Matchers::Message("node 'w' (cmin.wait): stopped: the evaluation was cancelled"));
  clear_cancellation();
  CHECK(scalar_output(run_yaml(scene, r), "w.done") == 1000.0);
}

TEST_CASE("C objects cross between C nodes: the host checks their contract and releases each once", "[plugins][sdk1]") {
  PluginRegistry r;
  r.load_file(test_plugin("test_c_objects"));
  const char* live = R"(nodes:
  n: { type: cobj.live }
outputs: [ n.count ]
)";
  {
    const RunResult run = run_yaml(R"(nodes:
  law: { type: cobj.law, params: { lift: 9 mm } }
  peak: { type: cobj.peak, inputs: { law: law.law } }
outputs: [ peak.lift, law.law ]
)", r);
    CHECK(scalar_output(run, "peak.lift") == Approx(0.009).epsilon(1e-12).margin(1e-15));
    CHECK(output(run, "law.law").as_handle()->kind() == "cam_law");  // an SDK interface: carried as its C++ class
    CHECK(scalar_output(run_yaml(live, r), "n.count") == 1.0);  // held by the run's outputs
  }
  CHECK(scalar_output(run_yaml(live, r), "n.count") == 0.0);  // released once, by its creator's code
  // A law whose event reaches beyond +-180 deg is refused by the SDK library's checks
  // (mg_check_object), naming the node and the interface.
  CHECK_THROWS_WITH(run_yaml(R"(nodes:
  law: { type: cobj.law, params: { half_width: 1 rad, wide: 1 } }
outputs: [ law.law ]
)", r),
                    Contains("node 'law' (cobj.law) produced a cam_law at output 'law' that breaks the "
                             "cam_law contract: its event begins at -229.183 deg"));
  CHECK(scalar_output(run_yaml(live, r), "n.count") == 0.0);  // the refused one was released too
}

TEST_CASE("a producer of an older interface version than its consumer needs is refused at scene load", "[plugins][sdk1]") {
  // cobj.read_gauge needs the private interface cobj.gauge at version 2; cobj.gauge offers 2,
  // cobjold.gauge (another plugin) only 1.
  PluginRegistry r;
  r.load_file(test_plugin("test_c_objects"));
  r.load_file(test_plugin("test_c_old_gauge"));
  CHECK(r.find("cobj.read_gauge")->interface_version(false, 0) == 2);
  CHECK(r.find("cobjold.gauge")->interface_version(true, 0) == 1);
  CHECK(scalar_output(run_yaml(R"(nodes:
  g: { type: cobj.gauge }
  read: { type: cobj.read_gauge, inputs: { gauge: g.gauge } }
outputs: [ read.reading ]
)", r), "read.reading") == 42.0);
  CHECK_THROWS_WITH(graph_from(R"(nodes:
  g: { type: cobjold.gauge }
  read: { type: cobj.read_gauge, inputs: { gauge: g.gauge } }
outputs: [ read.reading ]
)", r),
                    Contains("scene.yaml:3:51: node 'read' (cobj.read_gauge), input 'gauge': 'g.gauge' of node 'g' "
                             "(cobjold.gauge, plugin 'cobjold') offers interface cobj.gauge version 1, but node 'read' "
                             "(cobj.read_gauge, plugin 'cobj') needs version 2 or later"));
  // A pre-1.0 C++ type's object ports count as the SDK interface version they are bridged as.
  const PluginRegistry& project = project_registry();
  const RegisteredType* law = nullptr;
  for (const auto& name : {"cam.kurz", "cam.cycloidal"})
    if (!law) law = project.find(name);
  REQUIRE(law != nullptr);
  const auto& outputs = law->type->info().outputs;
  const PortSpec* port = law->type->info().find_output("law");
  REQUIRE(port != nullptr);
  CHECK(law->interface_version(true, static_cast<std::size_t>(port - outputs.data())) == 1);
}

TEST_CASE("run refuses a too-old interface producer with exit 2, naming the place, both nodes and both versions",
          "[plugins][sdk1][cli]") {
  const auto dir = scratch_dir("old_gauge_scene");
  const auto scene = dir / "gauge.yaml";
  {
    std::ofstream out(scene);
    out << "nodes:\n  g: { type: cobjold.gauge }\n  read: { type: cobj.read_gauge, inputs: { gauge: g.gauge } }\n"
           "outputs: [ read.reading ]\n";
  }
  const CommandResult r = run_cli("--only-plugin-dir '" + test_plugin("test_c_objects").parent_path().string() +
                                  "' --plugin-dir '" + test_plugin("test_c_old_gauge").parent_path().string() + "' run '" +
                                  scene.string() + "'");
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err, Contains("gauge.yaml:3:51: node 'read' (cobj.read_gauge), input 'gauge'"));
  CHECK_THAT(r.err, Contains("offers interface cobj.gauge version 1, but node 'read' (cobj.read_gauge, plugin 'cobj') "
                             "needs version 2 or later"));
  std::filesystem::remove_all(dir);
}
