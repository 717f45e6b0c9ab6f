// Tables of curves (one axis, named channels with their own dimensions) and effects per node with
// the outputs and parameters they bring.
#include "test_support.hpp"

#include <mechgraph/errors.hpp>

#include <yaml-cpp/yaml.h>

#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <unistd.h>

using namespace mechgraph;
using namespace mechgraph::testing;
using Catch::Matchers::Contains;

namespace {
RunResult run(const std::string& yaml) { return run_yaml(yaml, arith_registry()); }
std::string failure(const std::string& yaml) {
  try {
    run(yaml);
  } catch (const std::exception& e) {
    return e.what();
  }
  return "no error";
}
}  // namespace

TEST_CASE("a table flows out of a node with its channels' dimensions", "[core][table]") {
  const RunResult r = run("nodes: { t: { type: test.table, params: { points: 5 } } }\noutputs: [t.curves]\n");
  const Table& t = output(r, "t.curves").as_table();
  CHECK(t.axis.name == "time");
  CHECK(t.axis.dimension == dim::time);
  REQUIRE(t.channels.size() == 2);
  CHECK(t.find("speed")->dimension == dim::velocity);
  CHECK(t.find("square")->values.at(2) == 0.25);
  CHECK(t.find("nope") == nullptr);
}

TEST_CASE("a table with a NaN, a short channel or a channel named twice is refused, naming node and port", "[core][table]") {
  CHECK_THAT(failure("nodes: { t: { type: test.table, params: { defect: nan } } }\noutputs: [t.curves]\n"),
             Contains("node 't' (test.table)") && Contains("NaN") && Contains("'curves'"));
  CHECK_THAT(failure("nodes: { t: { type: test.table, params: { defect: short } } }\noutputs: [t.curves]\n"),
             Contains("channel 'square' has 3 values for an axis of 4"));
  CHECK_THAT(failure("nodes: { t: { type: test.table, params: { defect: twice } } }\noutputs: [t.curves]\n"),
             Contains("channel 'square' twice"));
}

TEST_CASE("a table in a report cell is a load-time error", "[core][table]") {
  try {
    graph_from("nodes: { t: { type: test.table } }\nreport: { columns: [a], rows: [ [ x, [ t.curves ] ] ] }\n");
    FAIL("no error");
  } catch (const SceneError& e) {
    CHECK_THAT(e.what(), Contains("table of curves") && Contains("needs a number"));
  }
}

TEST_CASE("run --out writes a table as one CSV with name [unit] headers, --json as columns", "[core][table][cli]") {
  const auto dir = std::filesystem::temp_directory_path() / ("mechgraph_table_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "t.yaml") << "nodes: { t: { type: test.table, params: { points: 3 } } }\noutputs: [t.curves]\n";
  const std::string plugins = "--only-plugin-dir '" + test_plugin("test_arith").parent_path().string() + "' ";
  const auto r = run_cli(plugins + "-q run '" + (dir / "t.yaml").string() + "' --out '" + (dir / "out").string() + "'");
  REQUIRE(r.exit_code == 0);
  CHECK_THAT(r.out, Contains("t.curves = table of 2 curves over 3 points"));
  std::ifstream csv(dir / "out" / "t.curves.csv");
  std::string header, first, second;
  std::getline(csv, header);
  std::getline(csv, first);
  std::getline(csv, second);
  CHECK(header == "time [s],square [m],speed [m/s]");
  CHECK(first == "0,0,0");
  CHECK(second == "0.5,0.25,1");
  const auto j = run_cli(plugins + "-q run '" + (dir / "t.yaml").string() + "' --json");
  REQUIRE(j.exit_code == 0);
  const YAML::Node json = YAML::Load(j.out);
  const YAML::Node v = json["outputs"]["t.curves"]["value"];
  CHECK(v["axis"].as<std::string>() == "time");
  CHECK(v["columns"]["speed"]["unit"].as<std::string>() == "m/s");
  CHECK(v["columns"]["square"]["values"][2].as<double>() == 1.0);
  std::filesystem::remove_all(dir);
}

TEST_CASE("effects per node add to the scene's, for that node alone", "[core][effects]") {
  const std::string nodes = "nodes:\n  a: { type: test.effectful, params: { value: 1 mm }, effects: [ test_effect ] }\n"
                            "  b: { type: test.effectful, params: { value: 1 mm } }\noutputs: [a.out, b.out]\n";
  const RunResult own = run(nodes);
  CHECK(output(own, "a.out").as_scalar() == 2e-3);
  CHECK(output(own, "b.out").as_scalar() == 1e-3);
  const RunResult scene_wide = run(nodes + "effects: [ test_effect ]\n");
  CHECK(output(scene_wide, "b.out").as_scalar() == 2e-3);
  // The memo key follows the node's effects: the same node with and without differs.
  const Graph g = graph_from(nodes);
  const auto hashes = node_hashes(g);
  CHECK(hashes[*g.find("a")] != hashes[*g.find("b")]);
}

TEST_CASE("an effect the node type does not implement is named with the valid ones", "[core][effects]") {
  try {
    graph_from("nodes:\n  a: { type: test.effectful, params: { value: 1 mm }, effects: [ test_efect ] }\noutputs: [a.out]\n");
    FAIL("no error");
  } catch (const SceneError& e) {
    CHECK_THAT(e.what(), Contains("scene.yaml:2:") && Contains("unknown effect 'test_efect'") && Contains("test_effect"));
  }
  try {
    graph_from("nodes:\n  a: { type: test.constant, params: { value: 1 mm }, effects: [ test_effect ] }\noutputs: [a.out]\n");
    FAIL("no error");
  } catch (const SceneError& e) {
    CHECK_THAT(e.what(), Contains("implements no effects"));
  }
}

TEST_CASE("an output whose effect is off cannot be asked for: a load-time error naming the effect", "[core][effects]") {
  const std::string base = "nodes:\n  t: { type: test.table }\n";
  CHECK(run(base + "outputs: [t.extra]\neffects: [test_extra]\n").outputs.at(0).value.as_scalar() == 1.0);
  auto load_error = [](const std::string& yaml) {
    try {
      graph_from(yaml);
    } catch (const SceneError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  CHECK_THAT(load_error(base + "outputs: [t.extra]\n"),
             Contains("scene.yaml:3:11: output 't.extra' needs effect 'test_extra', which is off for node 't'"));
  CHECK_THAT(load_error(base + "  u: { type: test.add, inputs: { a: t.extra, b: [t.extra] } }\noutputs: [u.sum]\n"),
             Contains("input 'a': 't.extra' needs effect 'test_extra'"));
  CHECK_THAT(load_error(base + "report: { columns: [a], rows: [ [ x, [ t.extra ] ] ] }\n"), Contains("needs effect 'test_extra'"));
}

TEST_CASE("a parameter of an effect that is off is reported as unused", "[core][effects][cli]") {
  const auto dir = std::filesystem::temp_directory_path() / ("mechgraph_effects_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "t.yaml") << "nodes: { t: { type: test.table, params: { extra_gain: 3 } } }\noutputs: [t.curves]\n";
  const auto r = run_cli("--only-plugin-dir '" + test_plugin("test_arith").parent_path().string() + "' validate '" +
                         (dir / "t.yaml").string() + "'");
  CHECK(r.exit_code == 0);
  CHECK_THAT(r.err, Contains("t.yaml:1:55") && Contains("parameter 'extra_gain' is unused") && Contains("effect 'test_extra'"));
  std::filesystem::remove_all(dir);
}
