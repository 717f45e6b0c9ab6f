#pragma once
// What the benchmark programs share: the project's plugins, loaded once.
#include <mechgraph/plugin_registry.hpp>

namespace mechgraph::bench {

inline const PluginRegistry& project_plugins() {
  static const PluginRegistry r = [] {
    PluginRegistry loaded;
    loaded.load_directory(MECHGRAPH_PLUGIN_DIR);
    return loaded;
  }();
  return r;
}

}  // namespace mechgraph::bench
