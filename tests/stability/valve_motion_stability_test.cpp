// Stability table of the ValveMotion interface and the time-area: speeds from 1 to 1e6 rpm and
// lashes at the edge of the valve's travel. Independent values: in time the valve's velocity
// scales as w, its acceleration as w^2 and its time-area as 1/w (the motion over cam angle does
// not depend on speed).
#include "test_support.hpp"

#include <mechgraph/errors.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <string>

using namespace mechgraph;
using namespace mechgraph::testing;
using Catch::Matchers::Contains;
using Catch::Matchers::WithinRel;

namespace {

std::string valve_scene(const std::string& rpm, const std::string& lash) {
  return "nodes:\n"
         "  c:  { type: cam.kurz, params: { max_lift: 8 mm, base_radius: 17 mm, action_angle: 130 deg, accel_angle: 18 deg } }\n"
         "  v:  { type: valvetrain.valve_motion, inputs: { cam: c.law }, params: { rpm: " + rpm + ", rocker_ratio: 1.5, lash: " + lash + " } }\n"
         "  ta: { type: valvetrain.time_area, inputs: { valve: v.motion }, params: { seat_diameter: 34 mm } }\n"
         "outputs: [v.max_lift, v.max_velocity, v.max_acceleration, v.min_acceleration, v.open_angle, ta.time_area, ta.angle_area]\n";
}

}  // namespace

TEST_CASE("stability: valve motion from 1 to 1e6 rpm scales as w, w^2 and 1/w", "[stability][valvetrain]") {
  const RunResult ref = run_yaml(valve_scene("5600 rpm", "0.25 mm"), project_registry());
  for (double rpm : {1.0, 10.0, 1e5, 1e6}) {
    INFO(rpm << " rpm");
    const double k = rpm / 5600.0;
    const RunResult r = run_yaml(valve_scene(std::to_string(rpm) + " rpm", "0.25 mm"), project_registry());
    CHECK_THAT(scalar_output(r, "v.max_lift"), WithinRel(scalar_output(ref, "v.max_lift"), 1e-15));
    CHECK_THAT(scalar_output(r, "v.open_angle"), WithinRel(scalar_output(ref, "v.open_angle"), 1e-15));
    CHECK_THAT(scalar_output(r, "v.max_velocity"), WithinRel(k * scalar_output(ref, "v.max_velocity"), 1e-14));
    CHECK_THAT(scalar_output(r, "v.max_acceleration"), WithinRel(k * k * scalar_output(ref, "v.max_acceleration"), 1e-14));
    CHECK_THAT(scalar_output(r, "v.min_acceleration"), WithinRel(k * k * scalar_output(ref, "v.min_acceleration"), 1e-14));
    CHECK_THAT(scalar_output(r, "ta.time_area"), WithinRel(scalar_output(ref, "ta.time_area") / k, 1e-13));
    CHECK_THAT(scalar_output(r, "ta.angle_area"), WithinRel(scalar_output(ref, "ta.angle_area"), 1e-13));
  }
}

TEST_CASE("stability: a lash at the edge of the valve's travel", "[stability][valvetrain]") {
  // Full valve travel: 1.5 x 8 mm = 12 mm. A hair below it the valve opens for a sliver whose
  // lift is the excess; at it and above it the valve never opens: an error naming the lash.
  const RunResult sliver = run_yaml(valve_scene("5600 rpm", "11.999999 mm"), project_registry());
  CHECK_THAT(scalar_output(sliver, "v.max_lift"), WithinRel(1e-9, 1e-6));
  CHECK(scalar_output(sliver, "v.open_angle") > 0.0);
  CHECK(scalar_output(sliver, "v.open_angle") < 1e-2);
  CHECK(scalar_output(sliver, "ta.time_area") > 0.0);
  for (const char* lash : {"12 mm", "12.5 mm"}) {
    INFO("lash " << lash);
    CHECK_THROWS_WITH(run_yaml(valve_scene("5600 rpm", lash), project_registry()),
                      Contains("node 'v'") && Contains("'lash'") && Contains("never opens"));
  }
}
