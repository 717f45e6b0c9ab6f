#include "cli.hpp"

#include <mechgraph/shown_number.hpp>
#include <mechgraph/units.hpp>

#include <mechgraph/errors.hpp>

#include <spdlog/spdlog.h>

#include <cstdio>

namespace mechgraph::cli {

PluginRegistry load_plugins(const GlobalOptions& options, const std::vector<std::filesystem::path>& first) {
  PluginRegistry registry;
  for (const auto& file : first) registry.load_file(file);
  const std::vector<std::filesystem::path> given(options.plugin_dirs.begin(), options.plugin_dirs.end());
  for (const auto& folder : PluginRegistry::search_path(given, options.only_plugin_dirs)) {
    std::error_code ec;
    // Only the built-in folder may be missing (a program copied without its plugins); a folder the
    // user named must exist.
    if (folder == PluginRegistry::builtin_plugin_dir() && !std::filesystem::is_directory(folder, ec)) {
      spdlog::debug("no plugin folder {}", folder.string());
      continue;
    }
    spdlog::debug("loading plugins from {}", folder.string());
    registry.load_directory(folder);
  }
  if (registry.plugins().empty()) {
    std::string why;
    for (const SkippedPlugin& s : registry.skipped()) why += "\n  " + s.reason;
    throw PluginError("no plugins found (built-in folder: " + PluginRegistry::builtin_plugin_dir().string() + "); give a folder with --plugin-dir or MECHGRAPH_PLUGIN_PATH" +
                      (why.empty() ? std::string() : "; skipped:" + why));
  }
  return registry;
}

Graph load_graph(const std::string& scene_file, const std::vector<std::string>& sets, const PluginRegistry& registry) {
  std::vector<Override> overrides;
  for (const std::string& s : sets) overrides.push_back(parse_override(s));
  return build_graph(load_scene(scene_file), registry, overrides);
}

// Builds the graph to sweep: --outputs replace the scene's outputs and report; tables and
// handles (not one number per case) are left out of a scene's own outputs with a note.
Graph build_sweep_graph(SceneSpec& scene, const PluginRegistry& registry, const std::vector<Override>& overrides,
                        const std::optional<std::string>& outputs) {
  const bool chosen = outputs.has_value();
  if (chosen) {
    scene.outputs.clear();
    scene.report.clear();
    const std::string& list = *outputs;
    std::size_t start = 0;
    for (std::size_t comma;; start = comma + 1) {
      comma = list.find(',', start);
      const std::string item = list.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
      scene.outputs.push_back(parse_port_ref(item, {"--outputs " + item, 0, 0}));
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
      throw UsageError("--outputs: '" + o.label + "' is a " + std::string(to_string(o.spec->kind)) +
                       ", not one value per case; mechgraph run --out writes it for one design");
    spdlog::info("sweep: '{}' is a {}, not a column; left out (mechgraph run --out writes it)", o.label, to_string(o.spec->kind));
  }
  if (kept.size() != graph.scene_output_count) {
    scene.outputs = kept;
    graph = build_graph(scene, registry, overrides);
  }
  return graph;
}

std::string format_value(double si, Dimension dimension, const std::string& unit) {
  double shown = si;
  std::string label = unit;
  if (unit.empty()) {
    label = dimension.si_unit();
    if (label == "1") label.clear();
  } else {
    shown = to_unit(si, dimension, unit);
  }
  const std::string number = shown_number(shown, si, noise_floor(dimension, 0.0));
  return label.empty() ? number : number + " " + label;
}

}  // namespace mechgraph::cli
