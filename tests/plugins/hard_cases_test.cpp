// Hard cases found in review: inputs at the edge of what the nodes accept must give a clear error
// naming the parameter, or a finite right answer; never a hang, a wrap-around or a silent wrong value.
#include "test_support.hpp"

#include <mechgraph/errors.hpp>

#include <yaml-cpp/yaml.h>

#include <catch2/catch.hpp>

#include <chrono>

using namespace mechgraph;
using namespace mechgraph::testing;
using Catch::Matchers::Contains;

namespace {

RunResult run(const std::string& yaml) { return run_yaml(yaml, project_registry()); }

std::string cam(const std::string& type, const std::string& extra) {
  return "  c: { type: " + type + ", params: { max_lift: 8 mm, action_angle: 130 deg, base_radius: 17 mm" + extra + " } }\n";
}

const std::string valve = "  v: { type: valvetrain.valve_motion, inputs: { cam: c.law }, params: { rpm: 5600 rpm } }\n";

}  // namespace

TEST_CASE("hard case: three-arc with a nose arc past 90 deg is refused, not built with another phi_y", "[hard][three_arc]") {
  CHECK_THROWS_WITH(run("nodes:\n  c: { type: cam.three_arc, params: { max_lift: 8 mm, action_angle: 250 deg, base_radius: 17 mm, "
                        "accel_angle: 18 deg } }\noutputs: [c.accel_angle]\n"),
                    Contains("parameter 'accel_angle'") && Contains("past 90 deg"));
  // Just inside the limit the requested phase is achieved.
  const RunResult ok = run(
      "nodes:\n  c: { type: cam.three_arc, params: { max_lift: 8 mm, action_angle: 210 deg, base_radius: 17 mm, "
      "accel_angle: 18 deg } }\noutputs: [c.accel_angle]\n");
  CHECK(output(ok, "c.accel_angle").as_scalar() == Approx(18 * std::numbers::pi / 180).epsilon(1e-9).margin(1e-12));
}

TEST_CASE("hard case: a Kurz positive phase too short to resolve is refused", "[hard][kurz]") {
  CHECK_THROWS_WITH(run("nodes:\n" + cam("cam.kurz", ", accel_angle: 1e-100 deg") + "outputs: [c.accel_angle]\n"),
                    Contains("parameter 'accel_angle'") && Contains("out of range") && Contains("ulps of the start"));
}

TEST_CASE("hard case: a rectangle sum finer than 1e8 steps is refused at once", "[hard][valvetrain]") {
  const auto start = std::chrono::steady_clock::now();
  CHECK_THROWS_WITH(run("nodes:\n" + cam("cam.kurz", ", accel_angle: 18 deg") + valve +
                        "  t: { type: valvetrain.time_area, inputs: { valve: v.motion }, params: { seat_diameter: 34 mm, "
                        "method: rectangle, step: 1e-20 deg } }\noutputs: [t.time_area]\n"),
                    Contains("parameter 'step'") && Contains("method: exact"));
  CHECK(std::chrono::steady_clock::now() - start < std::chrono::seconds(5));
}

TEST_CASE("hard case: whole numbers beyond range and speeds beyond reason are scene errors", "[hard][graph]") {
  CHECK_THROWS_WITH(graph_from("nodes: { s: { type: test.series, params: { points: 1e19 } } }\noutputs: [s.curve]\n"),
                    Contains("scene.yaml:1:52:") && Contains("too large for a whole number"));
  CHECK_THROWS_WITH(graph_from("nodes:\n" + cam("cam.kurz", ", accel_angle: 18 deg, samples: 3e9") + "outputs: [c.accel_angle]\n",
                               project_registry()),
                    Contains("out of range"));
  CHECK_THROWS_WITH(graph_from("nodes:\n" + cam("cam.kurz", ", accel_angle: 18 deg") +
                                   "  v: { type: valvetrain.valve_motion, inputs: { cam: c.law }, params: { rpm: 1e160 rpm } }\n"
                                   "outputs: [v.max_velocity]\n",
                               project_registry()),
                    Contains("parameter 'rpm'") && Contains("out of range"));
}

TEST_CASE("hard case: the valve open for a sliver still reports its (negative) acceleration", "[hard][valvetrain]") {
  const RunResult r = run("nodes:\n" + cam("cam.kurz", ", accel_angle: 18 deg") +
                          "  v: { type: valvetrain.valve_motion, inputs: { cam: c.law }, params: { rpm: 5600 rpm, "
                          "lash: 7.9999999 mm } }\noutputs: [v.max_acceleration, v.min_acceleration, c.min_acceleration]\n");
  // Right at the nose the valve decelerates as the cam does: w_k^2 h''(0) < 0, both extremes.
  const double wk = 5600 * std::numbers::pi / 60;
  const double nose = wk * wk * output(r, "c.min_acceleration").as_scalar();
  CHECK(output(r, "v.max_acceleration").as_scalar() < 0.0);
  CHECK(output(r, "v.min_acceleration").as_scalar() == Approx(nose).epsilon(1e-3).margin(0));
}

TEST_CASE("hard case: stacks of huge sizes keep finite RSS shares, compliance overflow is an error", "[hard][backlash]") {
  const RunResult r = run(R"(nodes:
  s: { type: stack.linear, params: { links: [ { nominal: 1000 m, upper: 100 m, lower: 0 mm },
                                              { nominal: 1 mm, upper: 1 um, lower: 0 mm } ] } }
outputs: [s.rss_sigma, s.contribution_rss]
)");
  // The largest link the ranges allow beside a micrometre one: shares 1 - 1e-16 and 1e-16.
  const auto& shares = output(r, "s.contribution_rss").as_series().values;
  REQUIRE(shares.size() == 2);
  CHECK(shares[0] == Approx(1.0).epsilon(1e-12).margin(0));
  CHECK(shares[1] == Approx(1e-16).epsilon(1e-9).margin(0));
  CHECK(output(r, "s.rss_sigma").as_scalar() == Approx(100.0 / 6).epsilon(1e-12).margin(0));
  CHECK_THROWS_WITH(run(R"(nodes:
  f: { type: fit.iso286, params: { size: 20 mm, hole: H11, shaft: h11 } }
  h: { type: joint.pin, inputs: { fits: [f.fit] } }
  c: { type: backlash.chain, inputs: { joints: [h.play] },
       params: { transfer_ratios: [1], actuator_backlash: 0 um, actuator_backlash_limit: 0 um, lever_arm: 500 mm,
                 load: 1e300 N, stiffness: 1e-300 N/mm } }
effects: [compliance]
outputs: [c.rod_total_under_load]
)"),
                    Contains("parameter 'stiffness'"));
}

TEST_CASE("stack.linear at the edges of its ranges stays finite, beyond them the scene names the field", "[hard][backlash]") {
  // 50 links at the largest size, tolerance and lever ratio the ranges allow, with Monte Carlo.
  std::string links;
  for (int i = 0; i < 50; ++i)
    links += std::string(i ? ", " : "") + "{ nominal: 1000 m, upper: 100 m, lower: -100 m, sensitivity: " +
             (i % 2 ? "-1e6" : "1e6") + ", distribution: " + (i % 3 ? "uniform" : "normal") + " }";
  const RunResult r = run("nodes: { s: { type: stack.linear, effects: [monte_carlo], params: { samples: 2000, links: [ " + links +
                          " ] } } }\noutputs: [ s.mean, s.worst_case_max, s.rss_sigma, s.mc_mean, s.mc_sigma, s.mc_q999 ]\n");
  for (const auto& o : r.outputs) CHECK(std::isfinite(o.value.as_scalar()));
  CHECK_THAT([] {
    try {
      run("nodes: { s: { type: stack.linear, params: { links: [ { nominal: 1e300 mm, upper: 1 mm, lower: 0 mm } ] } } }\n"
          "outputs: [ s.mean ]\n");
    } catch (const SceneError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  }(), Contains("scene.yaml:1:") && Contains("'nominal'") && Contains("out of range"));
}

TEST_CASE("backlash.chain at the edges of its ranges stays finite", "[hard][backlash]") {
  // Explicit fits of a metre's deviation, the largest transfer ratio and actuator backlash, the
  // shortest lever arm that is not singular, with Monte Carlo.
  const RunResult r = run(R"(
nodes:
  f: { type: fit.explicit, params: { size: 3150 mm, hole_upper: 1000000 um, hole_lower: -1000000 um,
                                     shaft_upper: 1000000 um, shaft_lower: -1000000 um } }
  h: { type: joint.pin, inputs: { fits: [f.fit, f.fit] } }
  chain: { type: backlash.chain, inputs: { joints: [h.play, h.play] }, effects: [monte_carlo],
           params: { transfer_ratios: [1e6, 1e6], actuator_backlash: 1 m, actuator_backlash_limit: 1 m,
                     lever_arm: 1 mm, samples: 2000 } }
outputs: [ chain.rod_backlash_max, chain.angular_backlash_max, chain.rod_backlash_rss_max, chain.rod_backlash_mc_q999 ]
)");
  for (const auto& o : r.outputs) CHECK(std::isfinite(o.value.as_scalar()));
}
