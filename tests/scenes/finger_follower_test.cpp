// scenes/finger_follower.yaml (the README's finger-follower study) end to end through the command:
// its numbers recomputed from the geometry by hand (docs/methods/followers.md), its contour against
// the roller's positions.
#include "test_support.hpp"

#include <yaml-cpp/yaml.h>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <vector>
#include <numbers>

using namespace mechgraph::testing;
using Catch::Matchers::Contains;
using Catch::Matchers::WithinAbs;
using Catch::Matchers::WithinRel;

namespace {
std::string scene() { return "'" + std::string(MECHGRAPH_SOURCE_DIR) + "/scenes/finger_follower.yaml'"; }
std::string plugins() { return "--plugin-dir '" + std::string(MECHGRAPH_PLUGIN_DIR) + "' "; }
double value(const YAML::Node& json, const std::string& label) { return json["outputs"][label]["value"].as<double>(); }
}  // namespace

TEST_CASE("finger follower scene: turn, ratio and valve lift from the arm geometry", "[scenes][followers]") {
  const auto r = run_cli(plugins() + "-q run " + scene() + " --json");
  REQUIRE(r.exit_code == 0);
  const YAML::Node j = YAML::Load(r.out);
  const double deg = std::numbers::pi / 180;
  // Cam lift 6.5 mm on a 36 mm arm; valve pad 50 mm from the pivot, square to the valve at 4 deg.
  const double psi = 6.5 / 36.0, a = 4 * deg, ratio = 50.0 / 36.0;
  CHECK_THAT(value(j, "cam.max_lift"), WithinRel(6.5e-3, 1e-12));
  CHECK_THAT(value(j, "valve_side.max_follower_angle"), WithinRel(psi, 1e-12));
  CHECK_THAT(value(j, "valve_side.ratio_closed"), WithinRel(ratio * std::cos(a), 1e-12));
  CHECK_THAT(value(j, "valve_side.ratio_at_nose"), WithinRel(ratio * std::cos(psi - a), 1e-12));
  const double valve = 50e-3 * (std::sin(psi - a) + std::sin(a));
  CHECK_THAT(value(j, "valve_side.max_lift"), WithinRel(valve, 1e-12));
  CHECK_THAT(value(j, "valve.max_lift"), WithinRel(valve - 0.05e-3, 1e-12));
  // The contour: every roller centre (pitch point) 9 mm from the contour polyline, to the chord error.
  const YAML::Node contour = j["outputs"]["contour.contour"]["value"]["columns"];
  REQUIRE(contour);
  auto column = [&](const char* name) { return contour[name]["values"].as<std::vector<double>>(); };
  const auto x = column("x"), y = column("y"), px = column("pitch_x"), py = column("pitch_y");
  REQUIRE(x.size() == px.size());
  for (std::size_t i = 0; i < px.size(); i += 5) {
    double nearest = 1.0;
    for (std::size_t k = 0; k < x.size(); ++k) {
      const std::size_t m = (k + 1) % x.size();
      const double dx = x[m] - x[k], dy = y[m] - y[k];
      const double t = std::clamp(((px[i] - x[k]) * dx + (py[i] - y[k]) * dy) / (dx * dx + dy * dy), 0.0, 1.0);
      nearest = std::min(nearest, std::hypot(px[i] - x[k] - t * dx, py[i] - y[k] - t * dy));
    }
    CHECK_THAT(nearest, WithinAbs(9e-3, 1e-6 + 1e-12));
  }
  // The table the README shows, with the events quoted from TDC.
  const auto text = run_cli(plugins() + "run " + scene());
  REQUIRE(text.exit_code == 0);
  CHECK_THAT(text.out, Contains("finger turn at the nose") && Contains("10.3451") && Contains("1.38551") &&
                           Contains("intake: opens"));
}
