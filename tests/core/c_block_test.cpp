// Blocks of cases through the SDK 1.x C boundary (sdk/include/mechgraph/c/node_block.h,
// mechgraph.node.block/1; detail/export_block.hpp in the plugin, core/src/c_block_node_type.cpp in
// the host). The built-in cams and valvetrain built on MECHGRAPH_PLUGIN_1 to keep to the C tables
// (test_plugins/builtin_sdk1) give the stage 1-3 sweep the very rows the shipped build gives (whose
// plugins share their C++ objects, c/object_cxx.h, and are called as themselves, c/node_cxx.h, or
// through C) and the pre-1.0 build (test_plugins/builtin_pre10) gives, in blocks and case by case; a
// case a node refuses is redone alone and carries its message; the conformance kit's block check
// runs through C; the objects of blocks (test_sdk1_objects_a/b) are released exactly once; a plugin
// written in C (test_plugins/c_blocks.c) offers blocks, and one that breaks the contract has every
// case run alone with the same rows.
#include "sweep_support.hpp"
#include "test_support.hpp"

#include <mechgraph/memo_cache.hpp>
#include <mechgraph/sweep/block_plan.hpp>
#include <mechgraph/sweep/sweep_runner.hpp>
#include <mechgraph/testing/node_conformance.hpp>

#include <catch2/catch.hpp>
#include <dlfcn.h>

#include <fstream>
#include <sstream>

using namespace mechgraph;
using namespace mechgraph::testing;
using Catch::Matchers::Contains;
using Catch::Matchers::WithinRel;

namespace {

// Every node type through C, so that the blocks and their objects cross the boundary
// (c/node_cxx.h: objsa's and objsb's types would otherwise be called as themselves).
const PluginRegistry& objects_registry() {
  static const PluginRegistry registry = [] {
    PluginRegistry r;
    r.set_node_types_through_c(true);
    r.load_file(test_plugin("test_sdk1_objects_a"));
    r.load_file(test_plugin("test_sdk1_objects_b"));
    r.load_file(test_plugin("test_sdk1_objects_c"));
    return r;
  }();
  return registry;
}

// How many laws and motions the plugin built as `name` has alive (its exported objects_live()).
long live_objects(const std::string& name) {
  objects_registry();
  void* handle = dlopen(test_plugin(name).c_str(), RTLD_NOW | RTLD_NOLOAD);
  REQUIRE(handle);
  auto* count = reinterpret_cast<long (*)()>(dlsym(handle, "objects_live"));
  REQUIRE(count);
  const long n = count();
  dlclose(handle);
  return n;
}

std::string stages123() { return source_file_text("bench/peers/stages123_study.yaml"); }

CaseTable hypercube(std::size_t n) {
  std::vector<SampleSpec> specs;
  for (const char* s : {"lift=7mm:9mm", "action=120deg:140deg", "accel=15deg:21deg", "r0=24mm:28mm", "rpm=4000rpm:7000rpm",
                        "lash=0.1mm:0.4mm", "rocker=1.2:1.8", "seat=30mm:38mm"})
    specs.push_back(parse_sample(s));
  return make_latin_hypercube(specs, n, 11);
}

}  // namespace

TEST_CASE("blocks through C: the stage 1-3 sweep gives the pre-1.0 build's rows, in blocks and alone", "[sweep][blocks][sdk1]") {
  const Prepared c = prepare(stages123(), hypercube(200), builtin_sdk1_registry());
  const Prepared pre = prepare(stages123(), hypercube(200), builtin_pre10_registry());
  const Prepared shipped = prepare(stages123(), hypercube(200), project_registry());
  const Prepared shipped_c = prepare(stages123(), hypercube(200), project_registry_through_c());
  const BlockPlan plan(c.graph, *c.binder);
  INFO(plan.why_not());
  REQUIRE(plan.usable());
  const Swept c_blocks = sweep(c, 1, 64);
  CHECK(c_blocks.summary.in_blocks == 200);
  CHECK(c_blocks.summary.failed == 0);
  const Swept c_alone = sweep(c, 1, 0);
  CHECK(c_alone.summary.in_blocks == 0);
  require_same_rows(c_blocks, c_alone);
  require_same_rows(c_blocks, sweep(pre, 1, 64));
  require_same_rows(c_blocks, sweep(shipped, 1, 64));
  require_same_rows(c_blocks, sweep(shipped, 1, 0));
  require_same_rows(c_blocks, sweep(shipped_c, 1, 64));
  require_same_rows(c_blocks, sweep(shipped_c, 1, 0));
  require_same_rows(c_blocks, sweep(c, 2, 16));  // two threads, smaller blocks
  // Only the speed varies: each cam's law block is one law for every case (object_count 1).
  const auto speeds = [] { return make_grid({parse_vary("rpm=3000rpm:8000rpm:11")}); };
  const Swept constant_cams = sweep(prepare(stages123(), speeds(), builtin_sdk1_registry()), 1, 4);
  CHECK(constant_cams.summary.in_blocks == 11);
  require_same_rows(constant_cams, sweep(prepare(stages123(), speeds(), builtin_pre10_registry()), 1, 0));
  require_same_rows(constant_cams, sweep(prepare(stages123(), speeds(), project_registry()), 1, 4));
}

TEST_CASE("blocks through C: a case a node refuses is redone alone and carries the per-case message", "[sweep][blocks][sdk1]") {
  // Lash beyond the lift (the valve motion refuses it), a lift out of range (the binder refuses
  // it) and an accel angle the three-arc cannot make, among good cases.
  const auto table = [] {
    return make_grid({parse_vary("lash=0.1mm,20mm,0.3mm"), parse_vary("lift=8mm,-1mm,9mm"), parse_vary("accel=18deg,1deg")});
  };
  const Prepared c = prepare(stages123(), table(), builtin_sdk1_registry());
  const Swept blocks = sweep(c, 1, 5);
  const Swept alone = sweep(c, 1, 0);
  require_same_rows(blocks, alone);
  REQUIRE(alone.summary.failed > 0);
  CHECK(blocks.summary.in_blocks == blocks.rows.size() - alone.summary.failed);
  bool valve_message = false;
  for (const CaseResult& r : blocks.rows) valve_message = valve_message || r.error.find("lash") != std::string::npos;
  CHECK(valve_message);
  // The same messages as the pre-1.0 build and the shipped one give.
  require_same_rows(blocks, sweep(prepare(stages123(), table(), builtin_pre10_registry()), 1, 5));
  require_same_rows(blocks, sweep(prepare(stages123(), table(), project_registry()), 1, 5));
}

TEST_CASE("blocks through C: the conformance kit's block check runs through the C boundary", "[sdk1][blocks][conformance]") {
  for (const char* type : {"cam.kurz", "cam.three_arc", "cam.polydyne"}) {
    INFO(type);
    const RegisteredType* registered = builtin_sdk1_registry().find(type);
    REQUIRE(registered);
    REQUIRE(dynamic_cast<const BlockEvaluation*>(registered->type.get()));
    const Report report = check_node_type(*registered->type);
    bool checked = false;
    for (const Check& c : report.checks())
      if (c.name == block_check) {
        INFO(c.detail);
        CHECK(c.status == Check::Status::passed);
        checked = true;
      }
    CHECK(checked);
  }
  // `plugin-test` on the plugin file: every check passes, the block check among them.
  const CommandResult r = run_cli("--only-plugin-dir '" + (std::filesystem::path(MECHGRAPH_TEST_PLUGIN_ROOT) / "builtin_sdk1").string() +
                                  "' plugin-test cam.kurz cam.polydyne");
  INFO(r.out << r.err);
  CHECK(r.exit_code == 0);
  CHECK_THAT(r.out, Contains(block_check));
}

TEST_CASE("blocks through C: objects in blocks cross plugins and are released exactly once", "[sweep][blocks][sdk1][objects]") {
  // objsa's laws through objsb's relay back to objsa's relay: each law is objsa's own C++ object
  // again there (native 1), as on the per-case path.
  const char* scene = R"(params: { lift: 8 mm }
nodes:
  law: { type: objsa.law, params: { lift: $lift, half_width: 1 rad } }
  b: { type: objsb.relay, inputs: { law: law.law } }
  a: { type: objsa.relay, inputs: { law: b.law } }
outputs: [ b.lift_at_half, a.lift_at_half, a.native, b.native, a.integral ]
)";
  {
    const Prepared p = prepare(scene, make_grid({parse_vary("lift=5mm,60mm,7mm,8mm,70mm,9mm")}), objects_registry());
    REQUIRE(BlockPlan(p.graph, *p.binder).usable());
    const Swept blocks = sweep(p, 1, 4);
    const Swept alone = sweep(p, 1, 0);
    require_same_rows(blocks, alone);
    CHECK(blocks.summary.in_blocks == 4);
    CHECK(blocks.summary.failed == 2);
    REQUIRE(blocks.rows.size() == 6);
    CHECK_THAT(blocks.rows[1].error, Contains("more than 50 mm lift") && Contains("law"));
    CHECK(blocks.rows[0].outputs[2].as_scalar() == 1.0);  // a.native
    CHECK(blocks.rows[0].outputs[3].as_scalar() == 0.0);  // b.native
    CHECK(live_objects("test_sdk1_objects_a") == 0);  // the sweeps' caches are gone
  }
  CHECK(live_objects("test_sdk1_objects_a") == 0);
  CHECK(live_objects("test_sdk1_objects_b") == 0);
}

TEST_CASE("blocks through C: a block crosses as its C++ block between libraries of one C++ layer, through C otherwise",
          "[sweep][blocks][sdk1][objects][cxx]") {
  // objsa and objsb share this project's C++ layer (one key, c/object_cxx.h, where the compiler's
  // build has one: detail/cxx_abi_key.hpp); objsc keeps to the C tables (MECHGRAPH_SDK_CXX_SHORTCUT 0).
  const char* scene = R"(params: { lift: 8 mm }
nodes:
  law: { type: objsa.law, params: { lift: $lift, half_width: 1 rad } }
  b: { type: objsb.relay, inputs: { law: law.law } }
  c: { type: objsc.relay, inputs: { law: b.law } }
  a: { type: objsa.relay, inputs: { law: c.law } }
outputs: [ b.view, c.view, a.view, a.native, b.lift_at_half, c.lift_at_half, c.integral ]
)";
  {
    const Prepared p = prepare(scene, make_grid({parse_vary("lift=5mm,7mm,8mm,9mm")}), objects_registry());
    REQUIRE(BlockPlan(p.graph, *p.binder).usable());
    const Swept blocks = sweep(p, 1, 4);
    const Swept alone = sweep(p, 1, 0);
    require_same_rows(blocks, alone);
    CHECK(blocks.summary.in_blocks == 4);
    REQUIRE(blocks.rows.size() == 4);
    const double lifts[] = {0.005, 0.007, 0.008, 0.009};
    for (const Swept* swept : {&blocks, &alone})
      for (std::size_t i = 0; i < 4; ++i) {
        const auto& row = swept->rows[i];
        CHECK(row.outputs[0].as_scalar() == (shares_cxx_layer ? 0.0 : 1.0));  // b.view: a's C++ laws themselves
        CHECK(row.outputs[1].as_scalar() == 1.0);  // c.view: views of the C tables
        CHECK(row.outputs[2].as_scalar() == 0.0);  // a.view: back home
        CHECK(row.outputs[3].as_scalar() == 1.0);  // a.native
        CHECK(row.outputs[4].as_scalar() == row.outputs[5].as_scalar());
        // the integral of H cos^2 over the event (-w, w) is H w, through objsc's C view
        CHECK_THAT(row.outputs[6].as_scalar(), WithinRel(lifts[i], 1e-12));
      }
  }
  CHECK(live_objects("test_sdk1_objects_a") == 0);
  CHECK(live_objects("test_sdk1_objects_b") == 0);
  CHECK(live_objects("test_sdk1_objects_c") == 0);
}

TEST_CASE("blocks through C: a plugin written in C offers blocks, one that breaks the contract runs case by case",
          "[sweep][blocks][sdk1]") {
  // b reads a's y as a column; x of a varies, x of b is fixed. x = 20 is refused by a.
  const char* scene = R"(params: { x: 2 }
nodes:
  a: { type: cblk.square, params: { x: $x } }
  b: { type: cblk.square, params: { x: 3 }, inputs: { offset: a.y } }
outputs: [ a.y, b.y ]
)";
  for (const char* plugin : {"test_c_blocks", "test_c_blocks_broken"}) {
    INFO(plugin);
    PluginRegistry registry;
    registry.load_file(test_plugin(plugin));
    const Prepared p = prepare(scene, make_grid({parse_vary("x=1,2,20,-4,5")}), registry);
    REQUIRE(BlockPlan(p.graph, *p.binder).usable());
    const Swept blocks = sweep(p, 1, 4);
    const Swept alone = sweep(p, 1, 0);
    require_same_rows(blocks, alone);
    CHECK(blocks.summary.failed == 1);
    REQUIRE(blocks.rows.size() == 5);
    CHECK_THAT(blocks.rows[2].error, Contains("x above 10 is refused here") && Contains("node 'a'"));
    CHECK(blocks.rows[3].outputs[1].as_scalar() == 16.0 + 9.0);
    // The broken one's blocks are dropped whole (a counter it does not declare): no case from a block.
    CHECK(blocks.summary.in_blocks == (std::string(plugin) == "test_c_blocks" ? 4u : 0u));
  }
}
