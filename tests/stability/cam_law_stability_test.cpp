// Stability table of the CamLaw interface: every cam type at tiny, huge and badly conditioned
// inputs. Independent values: a cam law scales exactly with its size (lift, base radius and the
// peaks in length are homogeneous of degree 1 in them), and its nose lift is max_lift.
#include "test_support.hpp"

#include <mechgraph/errors.hpp>
#include <mechgraph/sweep/sweep_runner.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <string>

using namespace mechgraph;
using namespace mechgraph::testing;
using Catch::Matchers::Contains;
using Catch::Matchers::WithinRel;

namespace {

struct CamRow {
  const char* type;
  const char* extra;  // the type's own parameters
  double r0_mm;       // a base circle that does not undercut at 8 mm lift
};

const CamRow cams[] = {
    {"cam.three_arc", ", accel_angle: 18 deg", 17.0},
    {"cam.kurz", ", accel_angle: 18 deg", 17.0},
    {"cam.polydyne", ", exponents: [2, 14, 26, 38, 50]", 17.0},
    {"cam.cycloidal", "", 40.0},
};

std::string cam_scene(const CamRow& c, double lift_mm, double r0_mm) {
  char sizes[128];
  std::snprintf(sizes, sizeof sizes, "max_lift: %.17g mm, base_radius: %.17g mm", lift_mm, r0_mm);
  return std::string("nodes:\n  c: { type: ") + c.type + ", params: { " + sizes + ", action_angle: 130 deg" + c.extra +
         " } }\noutputs: [c.max_lift, c.max_velocity, c.max_acceleration, c.min_acceleration, c.min_curvature_radius]\n";
}

}  // namespace

TEST_CASE("stability: every cam law scales exactly with its size, 1 um to 1 m", "[stability][cams]") {
  for (const CamRow& c : cams) {
    if (!project_registry().find(c.type)) continue;
    const RunResult ref = run_yaml(cam_scene(c, 8.0, c.r0_mm), project_registry());
    for (double scale : {1.25e-4, 1e-2, 10.0, 125.0}) {  // lift 1 um ... 1 m
      INFO(c.type << " at " << scale << " x the example size");
      const RunResult r = run_yaml(cam_scene(c, 8.0 * scale, c.r0_mm * scale), project_registry());
      CHECK_THAT(scalar_output(r, "c.max_lift"), WithinRel(8e-3 * scale, 1e-14));
      for (const char* out : {"c.max_velocity", "c.max_acceleration", "c.min_acceleration", "c.min_curvature_radius"})
        CHECK_THAT(scalar_output(r, out), WithinRel(scale * scalar_output(ref, out), 1e-12));
    }
  }
}

TEST_CASE("stability: badly conditioned polydyne exponents keep the law's digits or are refused", "[stability][cams]") {
  // [2, 994, 996, 998, 1000]: coefficients of size 1e11 with alternating signs; the factored
  // evaluation keeps the lift monotone and the nose exact.
  const RunResult r = run_yaml(
      "nodes:\n  c: { type: cam.polydyne, params: { max_lift: 8 mm, base_radius: 60 mm, action_angle: 130 deg, "
      "exponents: [2, 994, 996, 998, 1000] } }\noutputs: [c.max_lift, c.max_velocity, c.accel_angle]\n",
      project_registry());
  CHECK_THAT(scalar_output(r, "c.max_lift"), WithinRel(8e-3, 1e-14));
  CHECK(std::isfinite(scalar_output(r, "c.max_velocity")));
  CHECK(scalar_output(r, "c.accel_angle") > 0.0);
  // Beyond the exact-integer limit, and exponents that cannot give a monotone lift: named errors.
  CHECK_THROWS_WITH(run_yaml("nodes:\n  c: { type: cam.polydyne, params: { max_lift: 8 mm, base_radius: 17 mm, "
                             "action_angle: 130 deg, exponents: [2, 6, 10, 14, 1002] } }\noutputs: [c.max_lift]\n",
                             project_registry()),
                    Contains("exponents") && Contains("1000"));
}

TEST_CASE("stability: shapes out of reach are refused naming the parameter and the limit", "[stability][cams]") {
  struct Row {
    const char* scene;
    const char* expect;
  };
  const Row rows[] = {
      // Kurz: the positive-acceleration phase cannot take half the action angle.
      {"nodes:\n  c: { type: cam.kurz, params: { max_lift: 8 mm, base_radius: 17 mm, action_angle: 130 deg, "
       "accel_angle: 65 deg } }\noutputs: [c.max_lift]\n",
       "accel_angle"},
      // A base circle far too small for the lift: the flat follower undercuts (refused by the pair).
      {"nodes:\n  k: { type: cam.kurz, params: { max_lift: 8 mm, base_radius: 0.5 mm, action_angle: 130 deg, "
       "accel_angle: 18 deg } }\n  c: { type: cam.contour, inputs: { cam: k.law } }\noutputs: [c.max_pressure_angle]\n",
       "base_radius must be at least"},
      // An action angle a hair below a full turn leaves no base circle to rest on.
      {"nodes:\n  c: { type: cam.three_arc, params: { max_lift: 8 mm, base_radius: 17 mm, action_angle: 359.999 deg, "
       "accel_angle: 18 deg } }\noutputs: [c.max_lift]\n",
       "c"},
  };
  for (const Row& row : rows) {
    INFO(row.scene);
    try {
      run_yaml(row.scene, project_registry());
      FAIL("no error");
    } catch (const std::exception& e) {
      CHECK_THAT(std::string(e.what()), Contains(row.expect));
      CHECK_THAT(std::string(e.what()), Contains("node 'c'"));
    }
  }
}

TEST_CASE("stability: the default extremum sampling agrees with 200x denser sampling across designs", "[stability][cams]") {
  // A Latin hypercube over lift, base radius, action and positive-acceleration angles of the
  // three example cams; every peak, phase and time-area at the default samples (16 per piece)
  // against 3200 per piece. Designs that undercut fail the same way at both.
  SceneSpec scene = load_scene(std::string(MECHGRAPH_SOURCE_DIR) + "/scenes/valvetrain_cams.yaml");
  scene.report.clear();
  scene.outputs.clear();
  for (const std::string c : {"arc", "kurz", "poly"})
    for (const std::string& port : {c + ".accel_angle", c + ".min_curvature_radius", c + ".max_velocity", "v_" + c + ".max_velocity",
                                   "v_" + c + ".max_acceleration", "v_" + c + ".min_acceleration", "v_" + c + ".open_angle",
                                   "ta_" + c + ".time_area"})
      scene.outputs.push_back(parse_port_ref(port, {}));
  const CaseTable cases = make_latin_hypercube({parse_sample("lift=6mm:10mm"), parse_sample("r0=14mm:22mm"),
                                                parse_sample("action=110deg:160deg"), parse_sample("accel=14deg:24deg")},
                                               60, 11);
  auto sweep = [&](const std::vector<Override>& overrides) {
    const Graph g = build_graph(scene, project_registry(), overrides);
    const CaseBinder binder(g, scene, project_registry(), overrides, cases.variables);
    SweepOptions options;
    options.threads = 2;
    for (std::size_t i = 0; i < cases.size(); ++i) options.cases.push_back(i);
    MemoCache cache;
    std::vector<CaseResult> rows;
    run_sweep(g, binder, cases, cache, options, [&](CaseResult&& r) { rows.push_back(std::move(r)); });
    return rows;
  };
  std::vector<Override> dense;
  for (const char* n : {"arc", "kurz", "poly", "v_arc", "v_kurz", "v_poly"})
    dense.push_back(parse_override(std::string(n) + ".samples=3200"));
  const auto normal = sweep({}), tight = sweep(dense);
  std::size_t compared = 0;
  for (std::size_t i = 0; i < normal.size(); ++i) {
    INFO("case " << i << ": " << normal[i].error);
    REQUIRE(normal[i].failure == tight[i].failure);
    if (normal[i].failure != CaseFailure::none) continue;
    for (std::size_t j = 0; j < normal[i].outputs.size(); ++j) {
      INFO("output " << j);
      CHECK_THAT(normal[i].outputs[j].as_scalar(), WithinRel(tight[i].outputs[j].as_scalar(), 1e-12));
    }
    ++compared;
  }
  CHECK(compared > 20);
}
