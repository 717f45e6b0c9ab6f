// Fuzz target: a scene file's text, loaded and built against the project's plugins, its
// uncertainty block read (uncertainty/study_spec.hpp, without ISO 286 lookups). The loader may
// refuse it only with SceneError (file:line:column) or PluginError; it must never crash, hang or
// throw anything else.
#include "fuzz_support.hpp"

#include <mechgraph/errors.hpp>
#include <mechgraph/graph.hpp>
#include <mechgraph/scene.hpp>
#include <mechgraph/uncertainty/study_spec.hpp>

#include <spdlog/spdlog.h>

#include <cstdint>
#include <string_view>

namespace {
const mechgraph::PluginRegistry& registry() { return mechgraph::fuzz::project_plugins(); }
}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  spdlog::set_level(spdlog::level::off);  // warnings about odd scenes are expected, by the thousand
  registry();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const mechgraph::SceneSpec scene = mechgraph::parse_scene(text, "fuzz.yaml");
    if (scene.uncertainty) (void)mechgraph::parse_study(*scene.uncertainty, {});
    const mechgraph::Graph graph = mechgraph::build_graph(scene, registry());
    (void)graph;
  } catch (const mechgraph::SceneError&) {
  } catch (const mechgraph::PluginError&) {
  }
  return 0;
}
