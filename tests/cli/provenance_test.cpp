// Runs that record themselves: results.json and `run --json` carry the program version, the scene's
// SHA-1 (checked against sha1sum), every --set override, each node's inputs as written and as used,
// seeds and sample counts, and the plugins with their versions; contributions by link name in percent.
#include "test_support.hpp"

#include <mechgraph/version.hpp>

#include <yaml-cpp/yaml.h>

#include <catch2/catch.hpp>

#include <cstdio>
#include <fstream>

#include <unistd.h>

using namespace mechgraph::testing;

namespace {

std::string sha1sum(const std::string& file) {
  const std::string command = "sha1sum '" + file + "'";
  FILE* pipe = ::popen(command.c_str(), "r");
  REQUIRE(pipe);
  char buffer[128] = {};
  const std::size_t n = std::fread(buffer, 1, sizeof buffer - 1, pipe);
  ::pclose(pipe);
  return std::string(buffer, n).substr(0, 40);
}

}  // namespace

TEST_CASE("results.json and run --json record inputs, overrides, seeds, plugins and the scene's hash", "[cli][provenance]") {
  namespace fs = std::filesystem;
  const std::string scene = std::string(MECHGRAPH_SOURCE_DIR) + "/scenes/backlash_chain.yaml";
  const fs::path dir = fs::temp_directory_path() / ("mg_provenance_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  const auto r = run_cli("-q run '" + scene + "' --set chain.seed=7 --set chain.samples=5000 --set nozzle_deflection=4deg --json --out '" +
                         dir.string() + "'");
  REQUIRE(r.exit_code == 0);
  std::ifstream file(dir / "results.json");
  const std::string saved((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  for (const std::string& text : {r.out, saved}) {
    const YAML::Node j = YAML::Load(text);
    const YAML::Node p = j["provenance"];
    REQUIRE(p);
    CHECK(p["program"]["version"].as<std::string>() == MECHGRAPH_SDK_VERSION);
    CHECK(p["scene"]["sha1"].as<std::string>() == sha1sum(scene));
    REQUIRE(p["overrides"].size() == 3);
    CHECK(p["overrides"][0].as<std::string>() == "chain.seed=7");
    CHECK(p["overrides"][2].as<std::string>() == "nozzle_deflection=4deg");
    CHECK(p["scene_params"]["nozzle_deflection"].as<std::string>() == "5 deg");  // as written in the file
    CHECK(p["random"]["chain"]["seed"].as<long>() == 7);
    CHECK(p["random"]["chain"]["samples"].as<long>() == 5000);
    CHECK(p["nodes"]["f1"]["given"]["hole"].as<std::string>() == "$seat_grade_hole");
    CHECK(p["nodes"]["f1"]["used_si"]["hole"].as<std::string>() == "H11");
    CHECK(p["nodes"]["f1"]["used_si"]["size"].as<double>() == Approx(0.02).epsilon(1e-15).margin(1e-18));
    CHECK(p["nodes"]["f1"]["plugin"].as<std::string>() == "fits");
    CHECK(p["plugins"]["fits"]["version"].as<std::string>().size() >= 5);
    CHECK(p["plugins"]["backlash"]["file"].as<std::string>().find("mechgraph_backlash") != std::string::npos);
    // Contributions by link name, in percent (the joints' shares of the variance; the rest is the
    // chain's other links, so they sum to less than 100).
    const YAML::Node c = j["outputs"]["chain.joint_contribution_rss"];
    REQUIRE(c["by_label"]);
    CHECK(c["by_label_unit"].as<std::string>() == "%");
    double sum = 0.0;
    for (const auto& kv : c["by_label"]) sum += kv.second.as<double>();
    CHECK(sum > 50.0);
    CHECK(sum <= 100.0 + 1e-9);
    CHECK(c["by_label"]["h2 rod-end bearing"]);
  }
}
