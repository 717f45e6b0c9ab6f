// Domain objects crossing the SDK 1.x C boundary from C++ (docs/design/sdk-1.0.md, 3.3-3.4;
// mechgraph/detail/object_bridge.hpp): two plugins built from tests/test_plugins/sdk1_objects_plugin.cpp
// (objsa, objsb, and objsc that keeps to the C tables), the C plugin c_objects.c, the built-in
// plugins and their pre-1.0 builds (test_plugins/builtin_pre10) pass cam laws and
// valve motions to each other. A law that comes back to its maker is its own C++ object again
// (no wrapper of a wrapper), every reference is returned when the results go, and an exception
// thrown in a C++ node becomes an error naming the node.
#include "test_support.hpp"

#include <mechgraph/errors.hpp>
#include <followers/follower_types.hpp>

#include <catch2/catch.hpp>
#include <dlfcn.h>

#include <cmath>
#include <numbers>

using namespace mechgraph;
using namespace mechgraph::testing;
using Catch::Matchers::Contains;

namespace {

// Every node type through C, so that the objects cross the boundary between the nodes (called as
// themselves, objsa's and objsb's nodes would pass C++ objects with no boundary between them:
// c/node_cxx.h, tests/core/node_cxx_test.cpp).
const PluginRegistry& objects_registry() {
  static const PluginRegistry registry = [] {
    PluginRegistry r;
    r.set_node_types_through_c(true);
    r.load_directory(MECHGRAPH_PLUGIN_DIR);
    r.load_file(test_plugin("test_sdk1_objects_a"));
    r.load_file(test_plugin("test_sdk1_objects_b"));
    r.load_file(test_plugin("test_sdk1_objects_c"));
    r.load_file(test_plugin("test_c_objects"));
    return r;
  }();
  return registry;
}

// The same with cams and valvetrain on the pre-1.0 entry (test_plugins/builtin_pre10).
const PluginRegistry& pre10_objects_registry() {
  static const PluginRegistry registry = [] {
    PluginRegistry r;
    r.set_node_types_through_c(true);
    load_builtin_pre10(r);
    r.load_file(test_plugin("test_sdk1_objects_a"));
    r.load_file(test_plugin("test_sdk1_objects_b"));
    r.load_file(test_plugin("test_c_objects"));
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

// h = H cos^2(pi phi / (2 w)), the law of both test plugins and of cobj.law
double cosine_lift(double lift, double w, double phi) {
  const double c = std::cos(std::numbers::pi * phi / (2.0 * w));
  return lift * c * c;
}

}  // namespace

TEST_CASE("a C++ law goes A -> B -> A and comes back as A's own object, a valve motion carries it on",
          "[plugins][sdk1][objects]") {
  {
    const RunResult run = run_yaml(R"(nodes:
  law: { type: objsa.law, params: { lift: 8 mm, half_width: 1 rad } }
  b: { type: objsb.relay, inputs: { law: law.law } }
  a: { type: objsa.relay, inputs: { law: b.law } }
  m: { type: objsb.motion, params: { ratio: 1.5 }, inputs: { law: a.law } }
  r: { type: objsa.read_motion, inputs: { motion: m.motion } }
outputs: [ a.law, b.native, a.native, b.lift_at_half, a.lift_at_half, b.integral, r.lift, r.cam_lift, r.ratio, r.knots, r.native, r.cam_native ]
)",
                                   objects_registry());
    CHECK(scalar_output(run, "b.native") == 0.0);  // foreign to b: read through the C tables
    CHECK(scalar_output(run, "a.native") == 1.0);  // back home: b passed the original object on
    const double half = cosine_lift(0.008, 1.0, 0.5);
    CHECK(scalar_output(run, "b.lift_at_half") == Approx(half).epsilon(1e-14).margin(1e-18));
    CHECK(scalar_output(run, "a.lift_at_half") == Approx(half).epsilon(1e-14).margin(1e-18));
    // The optional closed form crosses too: the integral of H cos^2 over the event is H w.
    CHECK(scalar_output(run, "b.integral") == Approx(0.008).epsilon(1e-12).margin(1e-18));
    // b's motion over a's law, read by a: the motion is foreign, its cam is a's own law again.
    CHECK(scalar_output(run, "r.native") == 0.0);
    CHECK(scalar_output(run, "r.cam_native") == 1.0);
    CHECK(scalar_output(run, "r.lift") == Approx(1.5 * cosine_lift(0.008, 1.0, 0.3)).epsilon(1e-14).margin(1e-18));
    CHECK(scalar_output(run, "r.cam_lift") == Approx(cosine_lift(0.008, 1.0, 0.3)).epsilon(1e-14).margin(1e-18));
    CHECK(scalar_output(run, "r.ratio") == 1.5);
    CHECK(scalar_output(run, "r.knots") == 2.0);
    CHECK(live_objects("test_sdk1_objects_a") == 1);  // the law a.law holds; b's motion is gone
  }
  // The results are gone: every reference either side took has been returned.
  CHECK(live_objects("test_sdk1_objects_a") == 0);
  CHECK(live_objects("test_sdk1_objects_b") == 0);
}

TEST_CASE("a law crosses as its C++ object between libraries of one C++ layer, as a view of its C tables otherwise",
          "[plugins][sdk1][objects][cxx]") {
  // objsa and objsb are built by this project's compiler from these headers (one key, where the
  // compiler's build has one: detail/cxx_abi_key.hpp); objsc keeps to the C tables
  // (MECHGRAPH_SDK_CXX_SHORTCUT 0), and so does the C plugin.
  const char* scene = R"(nodes:
  law: { type: objsa.law, params: { lift: 8 mm, half_width: 1 rad } }
  b: { type: objsb.relay, inputs: { law: law.law } }
  c: { type: objsc.relay, inputs: { law: b.law } }
  a: { type: objsa.relay, inputs: { law: c.law } }
  claw: { type: cobj.law, params: { lift: 9 mm, half_width: 1.2 rad } }
  cb: { type: objsb.relay, inputs: { law: claw.law } }
outputs: [ b.view, b.native, c.view, a.view, a.native, cb.view, b.lift_at_half, c.lift_at_half, b.integral, c.integral ]
)";
  {
    {
      const RunResult run = run_yaml(scene, objects_registry());
      CHECK(scalar_output(run, "b.view") == (shares_cxx_layer ? 0.0 : 1.0));  // a's C++ law itself
      CHECK(scalar_output(run, "b.native") == 0.0);  // (not b's own class)
      CHECK(scalar_output(run, "c.view") == 1.0);    // no key: through the C tables
      CHECK(scalar_output(run, "a.view") == 0.0);    // back home as its own object
      CHECK(scalar_output(run, "a.native") == 1.0);
      CHECK(scalar_output(run, "cb.view") == 1.0);   // a law written in C has no C++ object
      const double half = cosine_lift(0.008, 1.0, 0.5);
      CHECK(scalar_output(run, "b.lift_at_half") == Approx(half).epsilon(1e-14).margin(1e-18));
      CHECK(scalar_output(run, "c.lift_at_half") == scalar_output(run, "b.lift_at_half"));
      CHECK(scalar_output(run, "b.integral") == Approx(0.008).epsilon(1e-12).margin(1e-18));
      CHECK(scalar_output(run, "c.integral") == scalar_output(run, "b.integral"));
    }
    CHECK(live_objects("test_sdk1_objects_a") == 0);
    CHECK(live_objects("test_sdk1_objects_b") == 0);
    CHECK(live_objects("test_sdk1_objects_c") == 0);
  }
}

TEST_CASE("laws cross between a C plugin, C++ SDK 1.x plugins and pre-1.0 plugins both ways", "[plugins][sdk1][objects]") {
  {
    const RunResult run = run_yaml(R"(nodes:
  c: { type: cobj.law, params: { lift: 9 mm, half_width: 1.2 rad } }
  a: { type: objsa.relay, inputs: { law: c.law } }
  peak: { type: cobj.peak, inputs: { law: a.law } }
  own: { type: objsa.law, params: { lift: 7 mm } }
  cpeak: { type: cobj.peak, inputs: { law: own.law } }
  cyc: { type: cam.cycloidal, params: { max_lift: 9 mm, action_angle: 130 deg, base_radius: 40 mm } }
  b: { type: objsb.relay, inputs: { law: cyc.law } }
  valve: { type: valvetrain.valve_motion, params: { rpm: 6000 rpm, rocker_ratio: 1.5 }, inputs: { cam: b.law } }
  valve2: { type: valvetrain.valve_motion, params: { rpm: 6000 rpm, rocker_ratio: 1.5 }, inputs: { cam: own.law } }
  r: { type: objsb.read_motion, inputs: { motion: valve2.motion } }
outputs: [ a.native, a.lift_at_half, a.integral, peak.lift, cpeak.lift, b.native, b.lift_at_half, cyc.max_lift, valve.max_lift, r.cam_lift, r.ratio ]
)",
                                   pre10_objects_registry());
    // C law -> C++ plugin (a view over the C table, no closed form) -> C consumer (the original).
    CHECK(scalar_output(run, "a.native") == 0.0);
    CHECK(scalar_output(run, "a.lift_at_half") == Approx(cosine_lift(0.009, 1.2, 0.6)).epsilon(1e-14).margin(1e-18));
    CHECK(scalar_output(run, "a.integral") == -1.0);
    CHECK(scalar_output(run, "peak.lift") == Approx(0.009).epsilon(1e-14).margin(1e-18));
    // C++ law -> C consumer.
    CHECK(scalar_output(run, "cpeak.lift") == Approx(0.007).epsilon(1e-14).margin(1e-18));
    // A pre-1.0 plugin's law -> SDK 1.x plugin -> pre-1.0 valve motion, which gets it back as its C++ law.
    CHECK(scalar_output(run, "b.native") == 0.0);
    CHECK(scalar_output(run, "b.lift_at_half") > 0.0);
    CHECK(scalar_output(run, "valve.max_lift") == Approx(1.5 * scalar_output(run, "cyc.max_lift")).epsilon(1e-9).margin(1e-12));
    // An SDK 1.x law -> a pre-1.0 valve motion -> an SDK 1.x reader of mechgraph.valve_motion.
    CHECK(scalar_output(run, "r.cam_lift") == Approx(cosine_lift(0.007, 1.0, 0.3)).epsilon(1e-14).margin(1e-18));
    CHECK(scalar_output(run, "r.ratio") == 1.5);
  }
  CHECK(live_objects("test_sdk1_objects_a") == 0);
  CHECK(live_objects("test_sdk1_objects_b") == 0);
  const RunResult after = run_yaml("nodes:\n  live: { type: cobj.live }\noutputs: [ live.count ]\n", objects_registry());
  CHECK(scalar_output(after, "live.count") == 0.0);
}

TEST_CASE("a joint play crosses as plain data into a pre-1.0 stack-up", "[plugins][sdk1][objects]") {
  const RunResult run = run_yaml(R"(nodes:
  p: { type: objsa.play }
  chain:
    type: backlash.chain
    inputs: { joints: [p.play] }
    params: { transfer_ratios: [1], actuator_backlash: 0 um, actuator_backlash_limit: 0 um, lever_arm: 100 mm }
outputs: [ p.play_max, chain.rod_backlash_limit, chain.rod_backlash_mean ]
)",
                                 objects_registry());
  // play = bore + 2 pin: worst case (40 + 10) + 2 (10 + 5) um = 80 um; mean 40 + 2 * 10 = 60 um.
  CHECK(scalar_output(run, "p.play_max") == Approx(80e-6).epsilon(1e-12).margin(1e-15));
  CHECK(scalar_output(run, "chain.rod_backlash_mean") == Approx(60e-6).epsilon(1e-12).margin(1e-15));
}

TEST_CASE("a fit made in C crosses as mechgraph.fit/1 into the joints plugin and on into a stack-up",
          "[plugins][sdk1][objects][fit]") {
  {
    const RunResult run = run_yaml(R"(nodes:
  cf: { type: cobj.fit }
  pin: { type: joint.pin, inputs: { fits: [cf.fit] }, params: { label: c pin } }
  chain:
    type: backlash.chain
    inputs: { joints: [pin.play] }
    params: { transfer_ratios: [1], actuator_backlash: 0 um, actuator_backlash_limit: 0 um, lever_arm: 100 mm }
outputs: [ pin.play_min, pin.play_max, pin.play_mean, chain.rod_backlash_limit, chain.rod_backlash_mean ]
)",
                                   objects_registry());
    // cobj.fit: hole +21/0 um, shaft -7/-20 um: clearance 7 .. 41 um, mean 10.5 + 13.5 = 24 um.
    CHECK(scalar_output(run, "pin.play_min") == Approx(7e-6).epsilon(1e-12).margin(1e-15));
    CHECK(scalar_output(run, "pin.play_max") == Approx(41e-6).epsilon(1e-12).margin(1e-15));
    CHECK(scalar_output(run, "pin.play_mean") == Approx(24e-6).epsilon(1e-12).margin(1e-15));
    CHECK(scalar_output(run, "chain.rod_backlash_mean") == Approx(24e-6).epsilon(1e-12).margin(1e-15));
  }
  // The host copied the fit's data on import and released the C object once.
  const RunResult after = run_yaml("nodes:\n  live: { type: cobj.live }\noutputs: [ live.count ]\n", objects_registry());
  CHECK(scalar_output(after, "live.count") == 0.0);
}

TEST_CASE("an exception thrown in a C++ node crosses the C boundary as an error naming the node", "[plugins][sdk1]") {
  const auto message = [](int what) {
    try {
      run_yaml("nodes:\n  t: { type: objsa.throws, params: { what: " + std::to_string(what) + " } }\noutputs: [ t.out ]\n",
               objects_registry());
    } catch (const std::exception& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  CHECK_THAT(message(0), Contains("node 't' (objsa.throws)") && Contains("not a std::exception"));
  CHECK_THAT(message(1), Contains("node 't' (objsa.throws)") && Contains("memory"));
  CHECK_THAT(message(2), Contains("node 't' (objsa.throws)") && Contains("a runtime_error from the plugin"));
}

TEST_CASE("followers cross: a test plugin's follower rides the built-in contour, a built-in follower is read by a test plugin",
          "[plugins][sdk1][objects][follower]") {
  const RunResult run = run_yaml(R"(nodes:
  kurz: { type: cam.kurz, params: { max_lift: 9 mm, action_angle: 130 deg, accel_angle: 18 deg, base_radius: 20 mm } }
  theirs: { type: objsa.follower, params: { roller_radius: 8 mm, offset: 3 mm } }
  ours: { type: follower.offset_roller, params: { roller_radius: 8 mm, offset: 3 mm } }
  c_theirs: { type: cam.contour, inputs: { cam: kurz.law, follower: theirs.follower } }
  c_ours: { type: cam.contour, inputs: { cam: kurz.law, follower: ours.follower } }
  arm: { type: follower.pivoted_roller, params: { pivot_x: -35 mm, pivot_y: 30 mm, arm_length: 35 mm, roller_radius: 10 mm } }
  read_arm: { type: objsb.read_follower, inputs: { follower: arm.follower } }
  read_home: { type: objsa.read_follower, inputs: { follower: theirs.follower } }
  read_away: { type: objsb.read_follower, inputs: { follower: theirs.follower } }
  read_c: { type: objsc.read_follower, inputs: { follower: theirs.follower } }
  read_ours: { type: objsb.read_follower, inputs: { follower: ours.follower } }
outputs: [ c_theirs.max_pressure_angle, c_ours.max_pressure_angle, c_theirs.undercut_margin, c_ours.undercut_margin,
           read_arm.x, read_arm.y, read_arm.pressure_angle, read_arm.curvature_radius, read_arm.follower_angle,
           read_arm.cam_lever, read_arm.roller_radius, read_arm.pivoted, read_arm.type_name_length, read_arm.native,
           read_home.native, read_away.native, read_away.x, read_away.curvature_radius, read_ours.x, read_ours.curvature_radius,
           read_c.native, read_c.x, read_c.curvature_radius ]
)",
                                 objects_registry());
  // The contour through the C table computes what it computes with the built-in follower: the same
  // mathematics (the SDK's reference roller) on either side of the boundary.
  CHECK(scalar_output(run, "c_theirs.max_pressure_angle") ==
        Approx(scalar_output(run, "c_ours.max_pressure_angle")).epsilon(1e-13).margin(1e-16));
  CHECK(scalar_output(run, "c_theirs.undercut_margin") ==
        Approx(scalar_output(run, "c_ours.undercut_margin")).epsilon(1e-13).margin(1e-16));
  // The followers plugin's pivoted roller read by a test plugin: every field of the contact and the
  // fixed figures, against the follower's own C++ answer.
  const auto arm = followers::make_pivoted_roller(-0.035, 0.030, 0.035, 0.010);
  const FollowerContact c = arm->contact(0.3, {0.002, 0.005, -0.010, 0.0}, 0.02, false);
  CHECK(scalar_output(run, "read_arm.x") == Approx(c.x).epsilon(1e-14).margin(1e-18));
  CHECK(scalar_output(run, "read_arm.y") == Approx(c.y).epsilon(1e-14).margin(1e-18));
  CHECK(scalar_output(run, "read_arm.pressure_angle") == Approx(c.pressure_angle).epsilon(1e-14).margin(1e-18));
  CHECK(scalar_output(run, "read_arm.curvature_radius") == Approx(c.curvature_radius).epsilon(1e-14).margin(1e-18));
  CHECK(scalar_output(run, "read_arm.follower_angle") == Approx(c.follower_angle).epsilon(1e-14).margin(1e-18));
  CHECK(c.follower_angle != 0.0);
  CHECK(scalar_output(run, "read_arm.cam_lever") == Approx(arm->cam_lever(0.02)).epsilon(1e-14).margin(1e-18));
  CHECK(scalar_output(run, "read_arm.roller_radius") == 0.010);
  CHECK(scalar_output(run, "read_arm.pivoted") == 1.0);
  CHECK(scalar_output(run, "read_arm.type_name_length") == static_cast<double>(std::string("follower.pivoted_roller").size()));
  CHECK(scalar_output(run, "read_arm.native") == 0.0);
  // Home again it is its maker's own object. objsb shares objsa's C++ layer (c/object_cxx.h) where
  // this compiler's build has a key, so it gets the very object, of the SDK's reference class;
  // objsc (no key) a view of the C table that computes the same.
  CHECK(scalar_output(run, "read_home.native") == 1.0);
  CHECK(scalar_output(run, "read_away.native") == (shares_cxx_layer ? 1.0 : 0.0));
  CHECK(scalar_output(run, "read_c.native") == 0.0);
  CHECK(scalar_output(run, "read_c.x") == Approx(scalar_output(run, "read_ours.x")).epsilon(1e-14).margin(1e-18));
  CHECK(scalar_output(run, "read_c.curvature_radius") ==
        Approx(scalar_output(run, "read_ours.curvature_radius")).epsilon(1e-14).margin(1e-18));
  CHECK(scalar_output(run, "read_away.x") == Approx(scalar_output(run, "read_ours.x")).epsilon(1e-14).margin(1e-18));
  CHECK(scalar_output(run, "read_away.curvature_radius") ==
        Approx(scalar_output(run, "read_ours.curvature_radius")).epsilon(1e-14).margin(1e-18));
}

TEST_CASE("a follower that cannot sit on the base circle says so across the boundary, naming its parameter",
          "[plugins][sdk1][objects][follower]") {
  std::string message;
  try {
    run_yaml(R"(nodes:
  kurz: { type: cam.kurz, params: { max_lift: 9 mm, action_angle: 130 deg, accel_angle: 18 deg, base_radius: 20 mm } }
  theirs: { type: objsa.follower, params: { roller_radius: 8 mm, offset: 30 mm } }
  contour: { type: cam.contour, inputs: { cam: kurz.law, follower: theirs.follower } }
outputs: [ contour.max_pressure_angle ]
)",
             objects_registry());
  } catch (const std::exception& e) {
    message = e.what();
  }
  // Thrown in objsa as NodeError("offset"), carried as MG_ERR_NODE with the parameter, thrown again
  // in the cams plugin and named with the node by the evaluator.
  CHECK_THAT(message, Contains("contour") && Contains("offset") && Contains("below base radius + roller radius 28 mm"));
}
