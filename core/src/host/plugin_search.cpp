#include <mechgraph/host/plugin_search.hpp>

#include <mechgraph/errors.hpp>
#include <mechgraph/host/study_run.hpp>

#include <spdlog/spdlog.h>

#include <algorithm>

namespace mechgraph::host {

PluginRegistry load_plugins(const PluginSearch& options, const std::vector<std::filesystem::path>& first,
                            const PluginNeeds* needs) {
  PluginRegistry registry;
  registry.set_node_types_through_c(options.node_types_through_c);
  for (const auto& file : first) registry.load_file(file);
  const std::vector<std::filesystem::path> given(options.plugin_dirs.begin(), options.plugin_dirs.end());
  std::vector<std::filesystem::path> folders;
  for (const auto& folder : PluginRegistry::search_path(given, options.only_plugin_dirs)) {
    std::error_code ec;
    // Only the built-in folder may be missing (a program copied without its plugins); a folder the
    // user named must exist.
    if (folder == PluginRegistry::builtin_plugin_dir() && !std::filesystem::is_directory(folder, ec)) {
      spdlog::debug("no plugin folder {}", folder.string());
      continue;
    }
    spdlog::debug("loading plugins from {}", folder.string());
    folders.push_back(folder);
  }
  registry.load_directories(folders, needs);
  if (registry.plugins().empty()) {
    std::string why;
    for (const SkippedPlugin& s : registry.skipped()) why += "\n  " + s.reason;
    throw PluginError("no plugins found (built-in folder: " + PluginRegistry::builtin_plugin_dir().string() + "); give a folder with --plugin-dir or MECHGRAPH_PLUGIN_PATH" +
                      (why.empty() ? std::string() : "; skipped:" + why));
  }
  return registry;
}

std::optional<PluginNeeds> scene_plugin_needs(const SceneSpec& scene) {
  if (!scene.effects.empty() || scene.nodes.empty()) return std::nullopt;
  PluginNeeds needs;
  for (const NodeSpec& n : scene.nodes)
    if (std::find(needs.node_types.begin(), needs.node_types.end(), n.type) == needs.node_types.end())
      needs.node_types.push_back(n.type);
  for (const PluginRequirement& r : scene.requirements) needs.plugin_ids.push_back(r.plugin);
  // A study's iso286: parameters are answered by a node type no node of the scene names.
  if (scene.uncertainty) needs.node_types.push_back(iso286_node_type);
  return needs;
}

}  // namespace mechgraph::host
