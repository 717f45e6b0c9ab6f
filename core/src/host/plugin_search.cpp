#include <mechgraph/host/plugin_search.hpp>

#include <mechgraph/errors.hpp>

#include <spdlog/spdlog.h>

namespace mechgraph::host {

PluginRegistry load_plugins(const PluginSearch& options, const std::vector<std::filesystem::path>& first) {
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

}  // namespace mechgraph::host
