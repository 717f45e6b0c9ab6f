// The example scenes the README runs, end to end through the `mechgraph` command.
#include "test_support.hpp"

#include <yaml-cpp/yaml.h>

#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

using namespace mechgraph::testing;
using Catch::Matchers::Contains;
using Catch::Matchers::WithinRel;

namespace {
std::string scene(const std::string& name) { return "'" + std::string(MECHGRAPH_SOURCE_DIR) + "/scenes/" + name + "'"; }
std::string plugins() { return "--plugin-dir '" + std::string(MECHGRAPH_PLUGIN_DIR) + "' "; }
double value(const YAML::Node& json, const std::string& label) { return json["outputs"][label]["value"].as<double>(); }
}  // namespace

TEST_CASE("the valve-train study prints its comparison table", "[scenes]") {
  const auto r = run_cli(plugins() + "run " + scene("valvetrain_cams.yaml"));
  REQUIRE(r.exit_code == 0);
  CHECK_THAT(r.out, Contains("three-arc") && Contains("Kurz") && Contains("polydyne") && Contains("time-area") &&
                        Contains("peak valve velocity") && Contains("positive-acceleration angle"));
}

TEST_CASE("the valve-train study: equal lift and phi_y, exact time-area agrees with a fine rectangle sum", "[scenes]") {
  const auto exact = run_cli(plugins() + "-q run " + scene("valvetrain_cams.yaml") + " --json");
  REQUIRE(exact.exit_code == 0);
  const YAML::Node e = YAML::Load(exact.out);
  const double deg = std::numbers::pi / 180;
  for (const char* cam : {"arc", "kurz", "poly"}) {
    INFO(cam);
    CHECK_THAT(value(e, std::string(cam) + ".accel_angle"), WithinRel(18 * deg, 1e-3));
    CHECK_THAT(value(e, "v_" + std::string(cam) + ".max_lift"), WithinRel(1.5 * 8e-3 - 0.25e-3, 1e-12));
  }
  // Second method: the source's rectangle sum with a 0.01 deg step converges to the exact value.
  const auto fine = run_cli(plugins() + "-q run " + scene("valvetrain_cams.yaml") +
                            " --json --set ta_arc.method=rectangle --set ta_arc.step=0.01deg"
                            " --set ta_kurz.method=rectangle --set ta_kurz.step=0.01deg"
                            " --set ta_poly.method=rectangle --set ta_poly.step=0.01deg");
  REQUIRE(fine.exit_code == 0);
  const YAML::Node f = YAML::Load(fine.out);
  for (const char* ta : {"ta_arc.time_area", "ta_kurz.time_area", "ta_poly.time_area"}) {
    INFO(ta);
    CHECK_THAT(value(f, ta), WithinRel(value(e, ta), 1e-4));
  }
  // A higher speed shortens the open time: time-area scales as 1/rpm.
  const auto fast = run_cli(plugins() + "-q run " + scene("valvetrain_cams.yaml") + " --json --set rpm=11200rpm");
  REQUIRE(fast.exit_code == 0);
  CHECK_THAT(value(YAML::Load(fast.out), "ta_kurz.time_area"), WithinRel(value(e, "ta_kurz.time_area") / 2, 1e-12));
}

TEST_CASE("the culling demo evaluates only the requested branch", "[scenes]") {
  const auto r = run_cli(plugins() + "-q run " + scene("culling_demo.yaml") + " --json");
  REQUIRE(r.exit_code == 0);
  const YAML::Node json = YAML::Load(r.out);
  REQUIRE(json["evaluated"].size() == 3);
  CHECK(json["evaluated"][0].as<std::string>() == "kurz");
  CHECK(json["evaluated"][2].as<std::string>() == "ta_kurz");
  const auto dot = run_cli(plugins() + "graph " + scene("culling_demo.yaml"));
  REQUIRE(dot.exit_code == 0);
  CHECK_THAT(dot.out, Contains("cluster_culled") && Contains("\"cyc\""));
}
