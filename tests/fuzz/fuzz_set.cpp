// Fuzz target: a `--set NAME=VALUE` override applied to the valve-train study. It may be refused
// only with SceneError or PluginError, naming what was wrong.
#include "fuzz_support.hpp"

#include <mechgraph/errors.hpp>
#include <mechgraph/graph.hpp>
#include <mechgraph/scene.hpp>

#include <spdlog/spdlog.h>

#include <cstdint>
#include <string>

namespace {
const mechgraph::PluginRegistry& registry() { return mechgraph::fuzz::project_plugins(); }
const mechgraph::SceneSpec& study() {
  static const mechgraph::SceneSpec s = mechgraph::load_scene(std::string(MECHGRAPH_SOURCE_DIR) + "/scenes/valvetrain_cams.yaml");
  return s;
}
}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  spdlog::set_level(spdlog::level::off);
  registry();
  study();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const mechgraph::Graph graph = mechgraph::build_graph(study(), registry(), {mechgraph::parse_override(text)});
    (void)graph;
  } catch (const mechgraph::SceneError&) {
  } catch (const mechgraph::PluginError&) {
  }
  return 0;
}
