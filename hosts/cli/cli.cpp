#include "cli.hpp"

#include <mechgraph/units.hpp>

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

std::string format_value(double si, Dimension dimension, const std::string& unit) {
  double shown = si;
  std::string label = unit;
  if (unit.empty()) {
    label = dimension.si_unit();
    if (label == "1") label.clear();
  } else {
    shown = to_unit(si, dimension, unit);
  }
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.6g", shown);
  return label.empty() ? std::string(buffer) : std::string(buffer) + " " + label;
}

}  // namespace mechgraph::cli
