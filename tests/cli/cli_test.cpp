// The `mechgraph` command end to end: exit codes, JSON on stdout, logs on stderr.
#include "test_support.hpp"

#include <yaml-cpp/yaml.h>

#include <catch2/catch.hpp>

#include <unistd.h>

using namespace mechgraph::testing;
using Catch::Matchers::Contains;

namespace {
std::string arith_dir() { return "--only-plugin-dir '" + test_plugin("test_arith").parent_path().string() + "'"; }

// Each test process writes into its own folder: ctest runs test cases in parallel processes.
std::string write_scene(const std::string& name, const std::string& yaml) {
  const auto dir = std::filesystem::temp_directory_path() / ("mechgraph_cli_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const auto file = dir / name;
  std::ofstream(file) << yaml;
  return "'" + file.string() + "'";
}

const char* culling_scene = R"(title: culling
params: { len: 2 mm }
nodes:
  a:    { type: test.constant, params: { value: $len } }
  s:    { type: test.add, inputs: { a: a.out, b: a.out } }
  c:    { type: test.constant, params: { value: 7 mm } }
  lone: { type: test.add, inputs: { a: c.out, b: c.out } }
outputs: [ s.sum ]
)";
}  // namespace

TEST_CASE("mechgraph --version and --help", "[cli]") {
  const auto v = run_cli("--version");
  CHECK(v.exit_code == 0);
  CHECK_THAT(v.out, Contains("mechgraph") && Contains("plugin ABI"));
  const auto top = run_cli("--help");
  CHECK(top.exit_code == 0);
  // Every subcommand's --help in one style: the synopsis, then "CMD options:" listing every option
  // the synopsis names; the top-level help lists every subcommand.
  for (const std::string cmd : {"run", "validate", "graph", "plugins", "describe", "bench", "sweep", "merge", "plugin-test", "report"}) {
    INFO(cmd);
    CHECK_THAT(top.out, Contains("  " + cmd + " "));
    const auto h = run_cli(arith_dir() + " " + cmd + " --help");
    CHECK(h.exit_code == 0);
    CHECK_THAT(h.out, Contains("usage: mechgraph " + cmd) && Contains(cmd + " options:") && Contains("-h [ --help ]"));
    const std::string synopsis = h.out.substr(0, h.out.find("\n\n"));
    const std::string options = h.out.substr(h.out.find("\n\n"));
    for (std::size_t at = synopsis.find("--"); at != std::string::npos; at = synopsis.find("--", at + 2)) {
      std::size_t end = at + 2;
      while (end < synopsis.size() && (std::isalnum(static_cast<unsigned char>(synopsis[end])) || synopsis[end] == '-')) ++end;
      const std::string option = synopsis.substr(at, end - at);
      if (option.size() > 2) CHECK_THAT(options, Contains("--" + option.substr(2) + " "));
    }
  }
  const auto bad = run_cli("frobnicate");
  CHECK(bad.exit_code == 2);
  CHECK_THAT(bad.err, Contains("unknown command 'frobnicate'"));
}

TEST_CASE("run --json prints outputs, units, evaluated nodes and work, logs go to stderr", "[cli]") {
  const auto r = run_cli(arith_dir() + " run " + write_scene("mg_cull.yaml", culling_scene) + " --json --set len=5mm");
  REQUIRE(r.exit_code == 0);
  const YAML::Node json = YAML::Load(r.out);  // JSON is YAML
  CHECK(json["outputs"]["s.sum"]["value"].as<double>() == Approx(0.01).epsilon(1e-15).margin(0));
  CHECK(json["outputs"]["s.sum"]["unit"].as<std::string>() == "m");
  REQUIRE(json["evaluated"].size() == 2);
  CHECK(json["evaluated"][0].as<std::string>() == "a");
  CHECK(json["evaluated"][1].as<std::string>() == "s");
  CHECK(json["nodes"]["s"]["work"]["calls"].as<double>() == 1.0);
  CHECK(json["nodes"]["s"]["seconds"].as<double>() >= 0.0);
  CHECK_THAT(r.err, Contains("evaluated 2 of 4 nodes"));
  const auto quiet = run_cli("-q " + arith_dir() + " run " + write_scene("mg_cull.yaml", culling_scene) + " --json");
  CHECK(quiet.err.empty());
}

TEST_CASE("exit codes: 2 scene, 3 evaluation, 4 plugins", "[cli]") {
  const auto scene_error = run_cli(arith_dir() + " run " + write_scene("mg_bad.yaml", "nodes: { a: { type: test.nope } }\noutputs: [a.x]\n"));
  CHECK(scene_error.exit_code == 2);
  CHECK_THAT(scene_error.err, Contains("mg_bad.yaml:1:21: unknown node type 'test.nope'"));
  const auto eval_error = run_cli(arith_dir() + " run " + write_scene("mg_nan.yaml", "nodes: { n: { type: test.nan } }\noutputs: [n.out]\n"));
  CHECK(eval_error.exit_code == 3);
  CHECK_THAT(eval_error.err, Contains("node 'n' (test.nan)"));
  const auto plugin_error = run_cli("--only-plugin-dir '" + test_plugin("test_abi_mismatch").parent_path().string() + "' plugins");
  CHECK(plugin_error.exit_code == 4);
  CHECK_THAT(plugin_error.err, Contains("ABI version"));
  const auto no_plugins = run_cli("--plugin-dir /nonexistent plugins");
  CHECK(no_plugins.exit_code == 4);
  CHECK_THAT(no_plugins.err, Contains("/nonexistent") && Contains("does not exist"));
  const auto usage = run_cli(arith_dir() + " run");
  CHECK(usage.exit_code == 2);
  const auto bad_set = run_cli(arith_dir() + " run " + write_scene("mg_cull.yaml", culling_scene) + " --set nope=1mm");
  CHECK(bad_set.exit_code == 2);
  CHECK_THAT(bad_set.err, Contains("unknown scene parameter 'nope'"));
  const auto missing = run_cli(arith_dir() + " run /nonexistent/scene.yaml");
  CHECK(missing.exit_code == 2);
  CHECK_THAT(missing.err, Contains("cannot open"));
}

TEST_CASE("validate, graph, plugins and describe", "[cli]") {
  const std::string scene = write_scene("mg_cull.yaml", culling_scene);
  const auto v = run_cli(arith_dir() + " validate " + scene);
  CHECK(v.exit_code == 0);
  CHECK_THAT(v.out, Contains("valid; 4 nodes, 2 needed"));
  const auto g = run_cli(arith_dir() + " graph " + scene);
  CHECK(g.exit_code == 0);
  CHECK_THAT(g.out, Contains("digraph mechgraph") && Contains("cluster_culled") && Contains("\"lone\"") &&
                        Contains("\"a\" -> \"s\""));
  const auto p = run_cli(arith_dir() + " plugins");
  CHECK(p.exit_code == 0);
  CHECK_THAT(p.out, Contains("test_arith 1.2.3") && Contains("test.add"));
  const auto pj = run_cli(arith_dir() + " plugins --json");
  REQUIRE(pj.exit_code == 0);
  const YAML::Node plugins = YAML::Load(pj.out);
  CHECK(plugins["plugins"][0]["id"].as<std::string>() == "test_arith");
  const auto d = run_cli(arith_dir() + " describe test.series");
  CHECK(d.exit_code == 0);
  CHECK_THAT(d.out, Contains("points") && Contains("accuracy knob") && Contains("work counters: calls"));
  const auto dj = run_cli(arith_dir() + " describe test.add --json");
  REQUIRE(dj.exit_code == 0);
  const YAML::Node add = YAML::Load(dj.out);
  CHECK(add["output_dependencies"]["twice"][0].as<std::string>() == "a");
  const auto unknown = run_cli(arith_dir() + " describe test.ad");
  CHECK(unknown.exit_code == 2);
  CHECK_THAT(unknown.err, Contains("did you mean 'test.add'"));
}

TEST_CASE("describe states why each range is what it is, in text and --json", "[cli][limits]") {
  const auto d = run_cli("describe joint.cardan");
  REQUIRE(d.exit_code == 0);
  CHECK_THAT(d.out, Contains("range: >= 0: an angle between shafts; < 90 deg: at 90 deg the joint locks"));
  const auto dj = run_cli("describe joint.cardan --json");
  REQUIRE(dj.exit_code == 0);
  const YAML::Node cardan = YAML::Load(dj.out);
  bool found = false;
  for (const auto& p : cardan["params"])
    if (p["name"].as<std::string>() == "bend_angle") {
      found = true;
      CHECK_THAT(p["range_reason"].as<std::string>(), Contains("the joint locks"));
      CHECK(p["below"].as<double>() == 0.5 * 3.14159265358979323846);
    }
  CHECK(found);
}

TEST_CASE("run --out writes results.json and a CSV per series", "[cli]") {
  const auto dir = std::filesystem::temp_directory_path() / "mg_out_test";
  std::filesystem::remove_all(dir);
  const auto r = run_cli(arith_dir() + " run " +
                         write_scene("mg_series.yaml", "nodes: { s: { type: test.series, params: { points: 3 } } }\noutputs: [s.curve]\n") +
                         " --out '" + dir.string() + "'");
  REQUIRE(r.exit_code == 0);
  CHECK(std::filesystem::exists(dir / "results.json"));
  std::ifstream csv(dir / "s.curve.csv");
  std::string header, row1;
  std::getline(csv, header);
  std::getline(csv, row1);
  CHECK_THAT(header, Contains("s.curve [m]"));
  CHECK(row1 == "0,0");
}

TEST_CASE("run --out: an existing folder needs --force, I/O failures exit 5, results appear whole or not at all", "[cli][out]") {
  namespace fs = std::filesystem;
  const fs::path base = fs::temp_directory_path() / ("mg_atomic_" + std::to_string(::getpid()));
  fs::remove_all(base);
  fs::create_directories(base);
  const std::string scene = write_scene("mg_atomic.yaml", "nodes: { s: { type: test.series, params: { points: 2000 } } }\noutputs: [s.curve]\n");
  const fs::path dir = base / "results";
  REQUIRE(run_cli(arith_dir() + " -q run " + scene + " --out '" + dir.string() + "'").exit_code == 0);
  // Again without --force: refused before anything runs, the old results untouched.
  const auto again = run_cli(arith_dir() + " run " + scene + " --out '" + dir.string() + "'");
  CHECK(again.exit_code == 2);
  CHECK_THAT(again.err, Contains("exists already") && Contains("--force"));
  CHECK(again.out.empty());
  CHECK(run_cli(arith_dir() + " -q run " + scene + " --out '" + dir.string() + "' --force").exit_code == 0);
  // A path that cannot be a folder: exit 5, naming it and the reason.
  std::ofstream(base / "a_file") << "x";
  const auto io = run_cli(arith_dir() + " -q run " + scene + " --out '" + (base / "a_file" / "sub").string() + "'");
  CHECK(io.exit_code == 5);
  CHECK_THAT(io.err, Contains("a_file") && Contains("Not a directory"));
  // Killed at random points while replacing: the folder always holds one complete set of results.
  const std::string command = std::string("'") + MECHGRAPH_CLI + "' " + arith_dir() + " -q run " + scene + " --out '" +
                              dir.string() + "' --force >/dev/null 2>&1";
  std::uint64_t state = 42;
  for (int trial = 0; trial < 25; ++trial) {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    const int delay_us = static_cast<int>((state >> 33) % 60000);  // 0 .. 60 ms
    const std::string killer = "( " + command + " & pid=$!; sleep " + std::to_string(delay_us / 1e6) +
                               "; kill -9 $pid 2>/dev/null; wait $pid 2>/dev/null ) >/dev/null 2>&1";
    std::system(killer.c_str());
    INFO("trial " << trial << ", killed after " << delay_us << " us");
    REQUIRE(fs::exists(dir / "results.json"));
    std::ifstream json(dir / "results.json");
    const std::string text((std::istreambuf_iterator<char>(json)), {});
    REQUIRE(!text.empty());
    CHECK(text.back() == '\n');  // the JSON writer's last character: the file is whole
    std::ifstream csv(dir / "s.curve.csv");
    long lines = 0;
    for (std::string line; std::getline(csv, line);) ++lines;
    CHECK(lines == 2001);
  }
  fs::remove_all(base);
}
