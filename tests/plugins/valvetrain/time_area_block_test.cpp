// valvetrain.time_area's block path where it has no closed form (plugins/valvetrain/time_area_node.cpp):
// the three-stage seat (quadrature split at the stage crossings), the rectangle sum (either seat)
// and a conical seat on a law without lift_integrals (a ramped law, a rise-return law). Over a
// Latin hypercube of every number the node and its laws read, the block rows equal the per-case
// path's (evaluate()) bit for bit, as the node intends: both run integrated_angle_area on the same
// motion. The closed-form route is compared in core/block_sweep_test.cpp.
#include "core/sweep_support.hpp"
#include "plugins/cams/cam_test_support.hpp"
#include "test_support.hpp"

#include <mechgraph/domain/cam_law.hpp>
#include <mechgraph/memo_cache.hpp>
#include <mechgraph/sweep/block_plan.hpp>
#include <mechgraph/sweep/sweep_runner.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <map>
#include <numbers>
#include <set>
#include <string>
#include <vector>

using namespace mechgraph;
using namespace mechgraph::testing;

namespace {

// Three laws: Kurz (closed-form integrals, so only the seat or the method leaves the closed form),
// a ramped three-arc and a cycloidal rise-return (neither gives lift_integrals). Seven time-areas:
//   staged        three_stage, exact, every seat number varied (a FlowArea per case)
//   staged_fixed  three_stage, exact, the seat fixed (one FlowArea for the block)
//   staged_cyclo  three_stage, exact, on the law without integrals, tolerance varied
//   rect_cone     conical, rectangle, step varied
//   rect_staged   three_stage, rectangle, on the ramped law
//   cone_ramped   conical, exact, on the ramped law (no closed form: quadrature)
//   cone_cyclo    conical, exact, on the cycloidal law
const char* scene = R"(title: time-area blocks without a closed form
params: { lift: 8 mm, action: 130 deg, accel: 18 deg, r0: 26 mm, rpm: 5600 rpm, rocker: 1.5, lash: 0.25 mm,
          seat: 34 mm, width: 1.8 mm, port: 31 mm, stem: 7 mm, step: 0.5 deg, tol: 1e-10 }
nodes:
  kurz:   { type: cam.kurz,      params: { max_lift: $lift, action_angle: $action, base_radius: $r0, accel_angle: $accel } }
  ramped: { type: cam.three_arc, params: { max_lift: $lift, action_angle: $action, base_radius: $r0, accel_angle: $accel,
                                           ramp: cosine, ramp_height: 0.15 mm, ramp_length: 20 deg } }
  cyclo:  { type: cam.cycloidal, params: { max_lift: $lift, action_angle: $action, base_radius: $r0 } }
  v_kurz:   { type: valvetrain.valve_motion, inputs: { cam: kurz.law },   params: { rpm: $rpm, rocker_ratio: $rocker, lash: $lash } }
  v_ramped: { type: valvetrain.valve_motion, inputs: { cam: ramped.law }, params: { rpm: $rpm, rocker_ratio: $rocker, lash: $lash } }
  v_cyclo:  { type: valvetrain.valve_motion, inputs: { cam: cyclo.law },  params: { rpm: $rpm, rocker_ratio: $rocker, lash: $lash } }
  staged:       { type: valvetrain.time_area, inputs: { valve: v_kurz.motion },
                  params: { flow_area: three_stage, seat_diameter: $seat, seat_width: $width, port_diameter: $port, stem_diameter: $stem } }
  staged_fixed: { type: valvetrain.time_area, inputs: { valve: v_kurz.motion },
                  params: { flow_area: three_stage, seat_diameter: 33 mm, seat_width: 1.6 mm, port_diameter: 30 mm, stem_diameter: 6.5 mm } }
  staged_cyclo: { type: valvetrain.time_area, inputs: { valve: v_cyclo.motion },
                  params: { flow_area: three_stage, seat_diameter: $seat, seat_width: $width, port_diameter: $port, tolerance: $tol } }
  rect_cone:    { type: valvetrain.time_area, inputs: { valve: v_kurz.motion },   params: { seat_diameter: $seat, method: rectangle, step: $step } }
  rect_staged:  { type: valvetrain.time_area, inputs: { valve: v_ramped.motion },
                  params: { flow_area: three_stage, seat_diameter: $seat, seat_width: $width, port_diameter: $port, method: rectangle, step: $step } }
  cone_ramped:  { type: valvetrain.time_area, inputs: { valve: v_ramped.motion }, params: { seat_diameter: $seat, tolerance: $tol } }
  cone_cyclo:   { type: valvetrain.time_area, inputs: { valve: v_cyclo.motion },  params: { seat_diameter: $seat } }
outputs: [ staged.angle_area, staged.time_area, staged.mean_flow_area, staged.open_duration,
           staged_fixed.angle_area, staged_fixed.time_area, staged_cyclo.angle_area, staged_cyclo.time_area,
           rect_cone.angle_area, rect_cone.time_area, rect_staged.angle_area, rect_staged.mean_flow_area,
           cone_ramped.angle_area, cone_ramped.time_area, cone_cyclo.angle_area, cone_cyclo.open_duration ]
)";
constexpr std::size_t outputs = 16;

// Every output of every case finite (no case of this sweep is refused).
void require_finite(const Swept& swept) {
  for (const CaseResult& r : swept.rows)
    for (std::size_t j = 0; j < r.outputs.size(); ++j) {
      INFO("case " << r.index << ", output " << j);
      CHECK(std::isfinite(r.outputs[j].as_scalar()));
    }
}

CaseTable hypercube(std::size_t n) {
  std::vector<SampleSpec> specs;
  for (const char* s : {"lift=7mm:9mm", "action=120deg:140deg", "accel=15deg:21deg", "r0=24mm:28mm", "rpm=4000rpm:7000rpm",
                        "lash=0.1mm:0.4mm", "rocker=1.2:1.8", "seat=30mm:36mm", "width=1.2mm:2.2mm", "port=29mm:33mm",
                        "stem=6mm:8mm", "step=0.3deg:1deg", "tol=1e-11:1e-9"})
    specs.push_back(parse_sample(s));
  return make_latin_hypercube(specs, n, 11);
}

}  // namespace

TEST_CASE("time-area blocks: the laws chosen leave the closed form where the test says", "[valvetrain][blocks]") {
  // The premise of the next case: cam.kurz gives lift_integrals, the ramped three-arc and the
  // cycloidal law do not (a conical seat on them is integrated, not taken in closed form).
  using cams::testing::run_cam;
  const auto law = [](const OutputSet& o) -> const CamLaw& { return dynamic_cast<const CamLaw&>(*o.all().at("law").as_handle()); };
  const std::map<std::string, ParamValue> common{{"max_lift", ParamValue::of_number(8e-3)},
                                                 {"action_angle", ParamValue::of_number(130 * std::numbers::pi / 180)},
                                                 {"base_radius", ParamValue::of_number(26e-3)}};
  auto with_accel = common;
  with_accel["accel_angle"] = ParamValue::of_number(18 * std::numbers::pi / 180);
  auto ramped = with_accel;
  ramped["ramp"] = ParamValue::of_choice("cosine");
  ramped["ramp_height"] = ParamValue::of_number(0.15e-3);
  ramped["ramp_length"] = ParamValue::of_number(20 * std::numbers::pi / 180);
  double i1 = 0.0, i2 = 0.0;
  const OutputSet kurz = run_cam("cam.kurz", with_accel), three_arc = run_cam("cam.three_arc", ramped),
                  cyclo = run_cam("cam.cycloidal", common);
  CHECK(law(kurz).lift_integrals(law(kurz).event_begin(), law(kurz).event_end(), i1, i2));
  CHECK_FALSE(law(three_arc).lift_integrals(law(three_arc).event_begin(), law(three_arc).event_end(), i1, i2));
  CHECK_FALSE(law(cyclo).lift_integrals(law(cyclo).event_begin(), law(cyclo).event_end(), i1, i2));
}

TEST_CASE("time-area blocks: three-stage seat, rectangle sum and a law without integrals equal the per-case path",
          "[valvetrain][blocks]") {
  const std::size_t n = 60;
  const Prepared p = prepare(scene, hypercube(n), project_registry());
  REQUIRE(BlockPlan(p.graph, *p.binder).usable());
  const Swept alone = sweep(p, 1, 0);
  REQUIRE(alone.summary.in_blocks == 0);
  REQUIRE(alone.rows.size() == n);
  // Every case is a valve that opens, every seat a consistent one: none refused.
  CHECK(alone.summary.failed == 0);
  // The varied numbers reach each time-area: no column is the same number case after case.
  for (std::size_t j = 0; j < outputs; ++j) {
    std::set<double> seen;
    for (const CaseResult& r : alone.rows)
      if (r.failure == CaseFailure::none) seen.insert(r.outputs[j].as_scalar());
    INFO("output " << j);
    CHECK(seen.size() > n / 2);
  }
  for (const auto& [threads, block_size] : {std::pair{1u, 256u}, std::pair{1u, 7u}, std::pair{2u, 16u}}) {
    INFO(threads << " threads, blocks of " << block_size);
    const Swept blocks = sweep(p, threads, block_size);
    CHECK(blocks.summary.in_blocks == n - alone.summary.failed);
    CHECK(blocks.summary.failed == alone.summary.failed);
    require_same_rows(blocks, alone);
    require_finite(blocks);
  }
}
