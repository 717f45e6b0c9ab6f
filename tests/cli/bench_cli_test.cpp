// `mechgraph bench` end to end on the project's scenes: the table names the worst output and the
// reference, knobs that cannot act are named with the reason, JSON and the --out folder.
#include "test_support.hpp"

#include <yaml-cpp/yaml.h>

#include <catch2/catch.hpp>

#include <fstream>
#include <iterator>

using namespace mechgraph::testing;
using Catch::Matchers::Contains;

namespace {
std::string plugins() { return "--plugin-dir '" + std::string(MECHGRAPH_PLUGIN_DIR) + "' "; }
std::string scene(const std::string& name) { return "'" + std::string(MECHGRAPH_SOURCE_DIR) + "/scenes/" + name + "' "; }
}  // namespace

TEST_CASE("mechgraph bench prints a table with the reference and the worst output, and JSON", "[bench][cli]") {
  const auto table = run_cli(plugins() + "bench " + scene("culling_demo.yaml") + "--node ta_kurz --repeats 1");
  REQUIRE(table.exit_code == 0);
  CHECK_THAT(table.out, Contains("knob method") && Contains("error") && Contains("worst output"));
  // The exact method's step is the rectangle sum's: it cannot act; nor can its tolerance on the
  // Kurz law, whose pieces the quadrature integrates to rounding at any admissible tolerance.
  CHECK_THAT(table.out, Contains("knob step: not measured: step does not change any output or the work in this scene"));
  CHECK_THAT(table.out, Contains("knob tolerance: not measured: tolerance does not change any output or the work"));
  CHECK_THAT(table.out, Contains("reference: method = exact; the first choice"));
  CHECK_THAT(table.out, Contains("ta_kurz.time_area") || Contains("ta_kurz.angle_area") || Contains("ta_kurz.mean_flow_area"));
  const auto json = run_cli(plugins() + "-q bench " + scene("culling_demo.yaml") + "--json --steps 1 --repeats 1");
  REQUIRE(json.exit_code == 0);
  const YAML::Node parsed = YAML::Load(json.out);
  CHECK(parsed["trials"].size() > 5);
  CHECK(parsed["knobs"].size() == parsed["advice"].size());
  for (const auto& k : parsed["knobs"]) {
    if (!k["measured"].as<bool>()) {
      CHECK_THAT(k["not_measured"].as<std::string>(), Contains("not measured: "));
      continue;
    }
    if (!k["monte_carlo"].as<bool>()) CHECK(k["reference"].IsDefined());
  }
  CHECK(run_cli(plugins() + "bench " + scene("culling_demo.yaml") + "--node nope").exit_code == 2);
  CHECK(run_cli(plugins() + "bench " + scene("culling_demo.yaml") + "--seeds 1").exit_code == 2);
  CHECK(run_cli(plugins() + "bench " + scene("culling_demo.yaml") + "--reference-steps -1").exit_code == 2);
}

TEST_CASE("mechgraph bench on the dynamics: the tolerance ladder falls, spring_surge's coils are not measured", "[bench][cli]") {
  const auto r = run_cli(plugins() + "bench " + scene("valvetrain_dynamics.yaml") + "--node elastic --steps 1 --repeats 1 --tol 1e-4");
  REQUIRE(r.exit_code == 0);
  CHECK_THAT(r.out, Contains("elastic (valvetrain.dynamics) knob coils: not measured: coils belongs to the effect "
                             "spring_surge, which is off for this node"));
  // Converged to 1e-3 x --tol long before the knob's range ends.
  CHECK_THAT(r.out, Contains("reference: tolerance = ") && Contains("steps tighter); converged: three successive values agree to"));
  // Each setting's line names the output its error is in.
  std::istringstream lines(r.out);
  std::string line;
  int rows = 0;
  while (std::getline(lines, line))
    if (line.find("steps=") != std::string::npos) {
      ++rows;
      CHECK_THAT(line, Contains(" elastic."));
    }
  CHECK(rows >= 6);
  CHECK_THAT(r.out, Contains("-> within 0.0001: tolerance = "));
}

TEST_CASE("mechgraph bench on a Monte Carlo scene: the spread over seeds, advice, SVG plot", "[bench][cli]") {
  const auto dir = scratch_dir("mechgraph_bench") / "out";
  std::filesystem::remove_all(dir);
  const auto r = run_cli(plugins() + "bench " + scene("backlash_chain.yaml") +
                         "--steps 1 --repeats 1 --seeds 8 --tol 0.05 --set chain.samples=20000 --out '" + dir.string() + "'");
  REQUIRE(r.exit_code == 0);
  CHECK_THAT(r.out, Contains("knob samples") && Contains("over 8 independent seeds") && Contains(" +- ") && Contains("-> "));
  CHECK_THAT(r.err, Contains("bench: node 1 of"));
  const YAML::Node json = YAML::LoadFile((dir / "bench.json").string());
  bool chain_seen = false;
  for (const auto& t : json["trials"]) {
    if (t["node"].as<std::string>() != "chain") continue;
    chain_seen = true;
    const double error = t["max_relative_error"].as<double>();
    CHECK(error > 0.0);
    CHECK(t["error_uncertainty"].as<double>() > 0.0);
    CHECK(t["errors"]["chain.rod_backlash_max"].as<double>() == 0.0);  // not random
    CHECK_FALSE(t["errors"]["chain.mc_mean_error"]);
  }
  CHECK(chain_seen);
  CHECK(json["advice"].size() > 0);
  std::ifstream csv(dir / "bench.csv");
  std::string header;
  std::getline(csv, header);
  CHECK_THAT(header, Contains("max_relative_error,error_uncertainty,reference_floor,below_floor,worst_output"));
  // bench draws its SVG with gnuplot, which scripts/install-deps.sh installs (gnuplot-nox).
  REQUIRE_FALSE(find_on_path("gnuplot").empty());
  std::ifstream svg(dir / "bench.svg");
  const std::string text((std::istreambuf_iterator<char>(svg)), {});
  CHECK_THAT(text, Contains("<svg") && Contains("<text>chain.samples</text>"));
  std::filesystem::remove_all(dir.parent_path());
}

TEST_CASE("mechgraph bench refuses a ladder over the work budget before it runs", "[bench][cli]") {
  const auto r = run_cli(plugins() + "bench " + scene("backlash_chain.yaml") + "--max-work 5e6");
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err, Contains("chain.samples = 200000 x") && Contains("--max-work"));
}
