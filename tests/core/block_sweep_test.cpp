// The block path of sweeps (core/include/mechgraph/sweep/block_plan.hpp, sdk block.hpp): the same
// rows as the per-case path, case for case, for the stage 1-3 study of the peers over a Latin
// hypercube of every parameter that changes a law's shape; failed cases redone alone with the
// per-case message; the same rows on any number of threads; no blocks where a node has none.
#include "sweep_support.hpp"
#include "test_support.hpp"

#include <mechgraph/memo_cache.hpp>
#include <mechgraph/scene.hpp>
#include <mechgraph/sweep/block_plan.hpp>
#include <mechgraph/sweep/sweep_runner.hpp>

#include <catch2/catch.hpp>

#include <memory>

using namespace mechgraph;
using namespace mechgraph::testing;

namespace {

// The peers' stage 1-3 study (bench/peers/stages123_study.yaml), inline: three cams, each through
// valve motion and time-area, eight outputs.
const char* stages123 = R"(title: stages 1-3
params: { lift: 8 mm, action: 130 deg, accel: 18 deg, r0: 26 mm, rpm: 5600 rpm, rocker: 1.5, lash: 0.25 mm, seat: 34 mm }
nodes:
  arc:   { type: cam.three_arc, params: { max_lift: $lift, action_angle: $action, base_radius: $r0, accel_angle: $accel } }
  kurz:  { type: cam.kurz,      params: { max_lift: $lift, action_angle: $action, base_radius: $r0, accel_angle: $accel } }
  poly:  { type: cam.polydyne,  params: { max_lift: $lift, action_angle: $action, base_radius: $r0, exponents: [2, 14, 26, 38, 50] } }
  v_arc:  { type: valvetrain.valve_motion, inputs: { cam: arc.law },  params: { rpm: $rpm, rocker_ratio: $rocker, lash: $lash } }
  v_kurz: { type: valvetrain.valve_motion, inputs: { cam: kurz.law }, params: { rpm: $rpm, rocker_ratio: $rocker, lash: $lash } }
  v_poly: { type: valvetrain.valve_motion, inputs: { cam: poly.law }, params: { rpm: $rpm, rocker_ratio: $rocker, lash: $lash } }
  ta_arc:  { type: valvetrain.time_area, inputs: { valve: v_arc.motion },  params: { seat_diameter: $seat } }
  ta_kurz: { type: valvetrain.time_area, inputs: { valve: v_kurz.motion }, params: { seat_diameter: $seat } }
  ta_poly: { type: valvetrain.time_area, inputs: { valve: v_poly.motion }, params: { seat_diameter: $seat } }
outputs: [ ta_arc.time_area, ta_kurz.time_area, ta_poly.time_area,
           v_arc.max_acceleration, v_kurz.max_acceleration, v_poly.max_acceleration,
           v_arc.min_acceleration, v_poly.min_acceleration, v_kurz.max_velocity, v_poly.open_angle,
           arc.max_lift, arc.nose_radius ]
)";

CaseTable peers_hypercube(std::size_t n) {
  std::vector<SampleSpec> specs;
  for (const char* s : {"lift=7mm:9mm", "action=120deg:140deg", "accel=15deg:21deg", "r0=24mm:28mm", "rpm=4000rpm:7000rpm",
                        "lash=0.1mm:0.4mm", "rocker=1.2:1.8", "seat=30mm:38mm"})
    specs.push_back(parse_sample(s));
  return make_latin_hypercube(specs, n, 7);
}

}  // namespace

TEST_CASE("block path: the stage 1-3 study's rows equal the per-case path's over a Latin hypercube", "[sweep][blocks]") {
  const Prepared p = prepare(stages123, peers_hypercube(300), project_registry());
  REQUIRE(BlockPlan(p.graph, *p.binder).usable());
  const Swept alone = sweep(p, 1, 0);
  CHECK(alone.summary.in_blocks == 0);
  for (const auto& [threads, block_size] : {std::pair{1u, 256u}, std::pair{1u, 7u}, std::pair{2u, 64u}}) {
    INFO(threads << " threads, blocks of " << block_size);
    const Swept blocks = sweep(p, threads, block_size);
    CHECK(blocks.summary.in_blocks == 300);
    CHECK(blocks.summary.failed == 0);
    require_same_rows(blocks, alone);
  }
}

TEST_CASE("block path: a case a node refuses is redone alone and carries the per-case message", "[sweep][blocks]") {
  // Lash beyond the lift (the valve never opens: the valve motion refuses it), a lift out of range
  // (the binder refuses it) and an accel angle the three-arc cannot make, among good cases.
  CaseTable table = make_grid({parse_vary("lash=0.1mm,20mm,0.3mm"), parse_vary("lift=8mm,-1mm,9mm"), parse_vary("accel=18deg,1deg")});
  const Prepared p = prepare(stages123, std::move(table), project_registry());
  const Swept alone = sweep(p, 1, 0);
  const Swept blocks = sweep(p, 1, 5);
  require_same_rows(blocks, alone);
  CHECK(alone.summary.failed > 0);
  CHECK(blocks.summary.failed == alone.summary.failed);
  // Every case the per-case path computes came from a block; only the refused ones were redone.
  CHECK(blocks.summary.in_blocks == blocks.rows.size() - alone.summary.failed);
}

TEST_CASE("block path: an output beyond a double in its shown unit fails its case as alone", "[sweep][blocks]") {
  // A seat of 3e307 mm through a rocker of 100: time-areas finite in SI, beyond a double in mm^2*s.
  // The per-case path refuses such a case (the evaluator's check of what a run shows); the block
  // path must not write it as "inf" with exit 0. With a scene's units: (length in nm) the check is
  // in those units, on both paths.
  for (const std::string& units : {std::string(), std::string("units: { length: nm }\n")}) {
    INFO(units);
    CaseTable table = make_grid({parse_vary("seat=34mm,3e307mm,1e295mm"), parse_vary("rocker=1.5,100")});
    const Prepared p = prepare(units + stages123, std::move(table), project_registry());
    const Swept alone = sweep(p, 1, 0);
    const Swept blocks = sweep(p, 1, 256);
    require_same_rows(blocks, alone);
    CHECK(alone.summary.failed >= 1);
    CHECK(alone.summary.failed < 6);
    CHECK(blocks.summary.failed == alone.summary.failed);
    CHECK(blocks.summary.in_blocks == 6 - alone.summary.failed);
  }
}

TEST_CASE("block path: a node parameter varied beside the scene parameter that feeds it wins, as case by case", "[sweep][blocks]") {
  // arc.max_lift listed before lift, which feeds it: the node's own value wins on both paths,
  // whatever the order of the columns (CaseBinder::apply_order).
  for (const bool node_first : {true, false}) {
    INFO(node_first);
    std::vector<VarySpec> vary{parse_vary("arc.max_lift=7mm,9mm"), parse_vary("lift=8mm,8.5mm")};
    if (!node_first) std::swap(vary[0], vary[1]);
    const Prepared p = prepare(stages123, make_grid(vary), project_registry());
    REQUIRE(BlockPlan(p.graph, *p.binder).usable());
    const Swept alone = sweep(p, 1, 0);
    const Swept blocks = sweep(p, 1, 256);
    CHECK(blocks.summary.in_blocks == 4);
    require_same_rows(blocks, alone);
  }
}

TEST_CASE("block path: nodes no case changes are made once and shared by every case", "[sweep][blocks]") {
  // Only the speed varies: the cams are the same for every case.
  const Prepared p = prepare(stages123, make_grid({parse_vary("rpm=3000rpm:8000rpm:11")}), project_registry());
  const Swept alone = sweep(p, 1, 0);
  const Swept blocks = sweep(p, 2, 4);
  CHECK(blocks.summary.in_blocks == 11);
  require_same_rows(blocks, alone);
}

TEST_CASE("block path: a node without blocks keeps the sweep case by case", "[sweep][blocks]") {
  const char* yaml = R"(title: no blocks
params: { len: 2 mm }
nodes:
  a: { type: test.constant, params: { value: $len } }
  s: { type: test.add, inputs: { a: a.out, b: a.out }, params: { gain: 2 } }
outputs: [ s.sum ]
)";
  const Prepared p = prepare(yaml, make_grid({parse_vary("len=1mm:5mm:5")}), arith_registry());
  const BlockPlan plan(p.graph, *p.binder);
  CHECK_FALSE(plan.usable());
  CHECK_THAT(plan.why_not(), Catch::Matchers::Contains("does not evaluate blocks"));
  const Swept s = sweep(p, 1, 64);
  CHECK(s.summary.in_blocks == 0);
  REQUIRE(s.rows.size() == 5);
  CHECK(s.rows[4].outputs[0].as_scalar() == 2.0 * (5e-3 + 5e-3));
}

TEST_CASE("block path: a varied choice or a series output keeps the sweep case by case", "[sweep][blocks]") {
  std::string yaml = stages123;
  const std::string scalars = "arc.max_lift, arc.nose_radius";
  yaml.replace(yaml.find(scalars), scalars.size(), "arc.max_lift, v_arc.lift_curve");
  const Prepared series = prepare(yaml, make_grid({parse_vary("rpm=3000rpm:8000rpm:3")}), project_registry());
  CHECK_FALSE(BlockPlan(series.graph, *series.binder).usable());
  const Prepared knob = prepare(stages123, make_grid({parse_vary("v_arc.samples=8,16")}), project_registry());
  CHECK_FALSE(BlockPlan(knob.graph, *knob.binder).usable());
}
