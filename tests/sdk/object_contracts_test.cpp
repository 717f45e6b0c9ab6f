// mg_check_object (libmechgraph_sdk.so.1) on objects of mechgraph.valve_motion/1,
// mechgraph.follower/1 and mechgraph.joint_play/1 written in C
// (tests/test_plugins/broken_contracts_objects.c): each broken point of a contract is refused with
// MG_ERR_BAD_ARGUMENT and a text naming it, a sound object passes.
#include "test_support.hpp"

#include <mechgraph/c/sdk_lib.h>

#include <catch2/catch.hpp>
#include <dlfcn.h>

#include <string>

namespace {

struct Case {
  int which;
  const char* interface;
  const char* problem;  // empty: keeps its contract
};

const Case cases[] = {
    {0, MG_VALVE_MOTION, ""},
    {1, MG_VALVE_MOTION, "mechgraph.valve_motion/1 table is incomplete"},
    {2, MG_VALVE_MOTION, "camshaft_speed() is 0 rad/s"},
    {3, MG_VALVE_MOTION, "rocker_ratio() is nan"},
    {4, MG_VALVE_MOTION, "lash() is -0.0001 m"},
    {5, MG_VALVE_MOTION, "its open period is empty"},
    {6, MG_VALVE_MOTION, "knots() does not run from the open period's begin"},
    {7, MG_VALVE_MOTION, "knots() are not ascending"},
    {8, MG_VALVE_MOTION, "cam() gives no object answering mechgraph.cam_law version 1"},
    {9, MG_VALVE_MOTION, "a NaN or infinite valve lift or derivative at"},
    {10, MG_VALVE_MOTION, "a negative valve lift (-0.001 m)"},
    {20, MG_FOLLOWER, ""},
    {21, MG_FOLLOWER, "mechgraph.follower/1 table is incomplete"},
    {22, MG_FOLLOWER, "type_name() gives no name"},
    {23, MG_FOLLOWER, "roller_radius() is -0.004 m"},
    {24, MG_FOLLOWER, "pivoted() is 2, not 0 or 1"},
    {30, MG_JOINT_PLAY, ""},
    {31, MG_JOINT_PLAY, "mechgraph.joint_play/1 table is incomplete"},
    {32, MG_JOINT_PLAY, "its data names no joint"},
    {33, MG_JOINT_PLAY, "joint 'pin_in_hole' has no play terms"},
    {34, MG_JOINT_PLAY, "link 1 ('pin') of term 0 ('radial'): its half range is -2.5e-05"},
    {35, MG_JOINT_PLAY, "link 0 ('hole') of term 0 ('radial'): its mean or sensitivity is not finite"},
    {36, MG_JOINT_PLAY, "link 1 ('pin') of term 0 ('radial'): its distribution 7 is none of MG_DISTRIBUTION_*"},
    {37, MG_JOINT_PLAY, "link 1 of term 0 ('radial') has no label"},
};

}  // namespace

TEST_CASE("mg_check_object refuses valve motions, followers and joint plays that break their contract, naming what",
          "[sdk][sdk1][objects]") {
  void* library = dlopen(mechgraph::testing::test_plugin("test_broken_contracts").c_str(), RTLD_NOW | RTLD_LOCAL);
  REQUIRE(library);
  auto* object_of = reinterpret_cast<const mg_object* (*)(int)>(dlsym(library, "broken_contracts_object"));
  REQUIRE(object_of);
  for (const Case& c : cases) {
    INFO("object " << c.which << " (" << c.interface << "): " << c.problem);
    std::string problem;
    const mg_text_sink sink{&problem, [](void* self, const char* text, size_t size) {
                              static_cast<std::string*>(self)->append(text, size);
                            }};
    const mg_status status = mg_check_object(object_of(c.which), c.interface, 1, sink);
    INFO("mg_check_object: " << mg_status_name(status) << " " << problem);
    if (*c.problem == '\0') {
      CHECK(status == MG_OK);
      CHECK(problem.empty());
    } else {
      CHECK(status == MG_ERR_BAD_ARGUMENT);
      CHECK(problem.find(c.problem) != std::string::npos);
    }
  }
  // Asked for an interface it does not answer: missing, not broken.
  std::string problem;
  const mg_text_sink sink{&problem, [](void* self, const char* text, size_t size) { static_cast<std::string*>(self)->append(text, size); }};
  CHECK(mg_check_object(object_of(0), MG_FOLLOWER, 1, sink) == MG_ERR_MISSING_FEATURE);
  dlclose(library);
}
