#pragma once
// What the fuzz targets share: the project's plugins, loaded once per fuzzing process.
#include <mechgraph/plugin_registry.hpp>

namespace mechgraph::fuzz {

inline const PluginRegistry& project_plugins() {
  static const PluginRegistry r = [] {
    PluginRegistry loaded;
    loaded.load_directory(MECHGRAPH_PLUGIN_DIR);
    return loaded;
  }();
  return r;
}

}  // namespace mechgraph::fuzz
