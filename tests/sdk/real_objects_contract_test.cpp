// Every domain object the shipped scenes make keeps its interface's contract as mg_check_object
// (libmechgraph_sdk.so.1) checks it: cam laws, valve motions, followers and joint plays from the
// real plugins, through the same C tables a plugin of another compiler would read. Objects of the
// SDK 1.x plugins are their own C exports; those of the pre-1.0 built-ins are exported as the
// host exports them to a C node (and, for the stage 1-3 scene of bench/peers, also made by the
// SDK 1.x builds of cams and valvetrain). tests/sdk/object_contracts_test.cpp shows each check refusing what
// breaks it.
#include "test_support.hpp"

#include <mechgraph/c/sdk_lib.h>
#include <mechgraph/detail/object_bridge.hpp>

#include <catch2/catch.hpp>

#include <filesystem>
#include <map>
#include <string>

using namespace mechgraph;
using namespace mechgraph::testing;

namespace {

// The scene with every handle output of every node requested, evaluated; each handle checked.
// Returns how many objects were checked by interface name.
std::map<std::string, int> check_scene_objects(const std::string& scene_file, const PluginRegistry& registry) {
  SceneSpec scene = load_scene(std::string(MECHGRAPH_SOURCE_DIR) + "/" + scene_file);
  scene.outputs.clear();
  for (const NodeSpec& node : scene.nodes) {
    const auto* type = registry.find(node.type);
    REQUIRE(type);
    for (const PortSpec& port : type->type->info().outputs)
      if (port.kind == ValueKind::handle) scene.outputs.push_back(PortRef{node.name, port.name, node.where});
  }
  MemoCache cache;
  const RunResult run = evaluate(build_graph(scene, registry), cache);
  std::map<std::string, int> checked;
  for (const OutputValue& o : run.outputs) {
    if (o.value.kind() != ValueKind::handle) continue;
    const auto& object = o.value.as_handle();
    const detail::SdkInterface* interface = detail::sdk_interface_of_kind(object->kind());
    if (!interface) continue;  // a kind with no C interface of the SDK (it crosses as opaque)
    const mg_object* c_object = detail::export_object(object, "test", {});
    std::string problem;
    const mg_text_sink sink{&problem, [](void* self, const char* text, size_t size) {
                              static_cast<std::string*>(self)->append(text, size);
                            }};
    const mg_status status = mg_check_object(c_object, interface->name, interface->version, sink);
    INFO(scene_file << ": " << o.label << " (" << interface->name << "): " << problem);
    CHECK(status == MG_OK);
    c_object->vtbl->release(c_object);
    ++checked[interface->name];
  }
  return checked;
}

}  // namespace

TEST_CASE("the objects of every shipped scene pass mg_check_object", "[sdk][sdk1][objects]") {
  std::map<std::string, int> all;
  for (const auto& entry : std::filesystem::directory_iterator(std::filesystem::path(MECHGRAPH_SOURCE_DIR) / "scenes")) {
    if (entry.path().extension() != ".yaml") continue;
    for (const auto& [name, count] : check_scene_objects("scenes/" + entry.path().filename().string(), project_registry()))
      all[name] += count;
  }
  // What the scenes make today; a scene losing all of one kind would leave its check untested.
  CHECK(all[MG_CAM_LAW] >= 5);
  CHECK(all[MG_VALVE_MOTION] >= 3);
  CHECK(all[MG_FOLLOWER] >= 1);
  CHECK(all[MG_JOINT_PLAY] >= 3);
}

TEST_CASE("the laws and valve motions of the SDK 1.x builds of cams and valvetrain pass mg_check_object",
          "[sdk][sdk1][objects]") {
  const std::map<std::string, int> checked = check_scene_objects("bench/peers/stages123_study.yaml", builtin_sdk1_registry());
  CHECK(checked.at(MG_CAM_LAW) >= 3);
  CHECK(checked.at(MG_VALVE_MOTION) >= 3);
}
