#include <mechgraph/host/scene_loading.hpp>

#include <mechgraph/host/exit_codes.hpp>
#include <mechgraph/host/usage_error.hpp>

#include <spdlog/spdlog.h>

namespace mechgraph::host {

Graph load_graph(const SceneSpec& scene, const std::vector<std::string>& sets, const PluginRegistry& registry) {
  std::vector<Override> overrides;
  for (const std::string& s : sets) overrides.push_back(parse_override(s));
  return build_graph(scene, registry, overrides);
}

// Builds the graph to sweep: --outputs replace the scene's outputs and report; tables and
// handles (not one number per case) are left out of a scene's own outputs with a note.
Graph build_sweep_graph(SceneSpec& scene, const PluginRegistry& registry, const std::vector<Override>& overrides,
                        const std::optional<std::string>& outputs, const OptionNames& option) {
  const bool chosen = outputs.has_value();
  if (chosen) {
    scene.outputs.clear();
    scene.report.clear();
    const std::string& list = *outputs;
    std::size_t start = 0;
    for (std::size_t comma;; start = comma + 1) {
      comma = list.find(',', start);
      const std::string item = list.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
      PortRef ref = parse_port_ref(item, {std::string(option.outputs) + " " + item, 0, 0});
      if (listed_before(scene.outputs, ref))
        throw UsageError(std::string(option.outputs) + ": '" + ref.str() + "' is listed twice; each output is one column: list it once");
      scene.outputs.push_back(std::move(ref));
      if (comma == std::string::npos) break;
    }
  }
  Graph graph = build_graph(scene, registry, overrides);
  std::vector<PortRef> kept;
  for (std::size_t j = 0; j < graph.scene_output_count; ++j) {
    const RequestedOutput& o = graph.outputs[j];
    if (o.spec->kind == ValueKind::scalar || o.spec->kind == ValueKind::series) {
      kept.push_back(scene.outputs[j]);
      continue;
    }
    if (chosen)
      throw UsageError(std::string(option.outputs) + ": '" + o.label + "' is a " + std::string(to_string(o.spec->kind)) +
                       ", not one value per case; " + option.one_design);
    spdlog::info("sweep: '{}' is a {}, not a column; left out ({})", o.label, to_string(o.spec->kind), option.one_design);
  }
  if (kept.size() != graph.scene_output_count) {
    scene.outputs = kept;
    graph = build_graph(scene, registry, overrides);
  }
  return graph;
}

}  // namespace mechgraph::host
