#pragma once
// Where a host finds its plugins: the folders given (--plugin-dir), MECHGRAPH_PLUGIN_PATH and the
// built-in folder, in that order (PluginRegistry::search_path), the same for every host.
#include <mechgraph/plugin_registry.hpp>
#include <mechgraph/scene.hpp>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace mechgraph::host {

struct PluginSearch {
  std::vector<std::string> plugin_dirs;  // --plugin-dir / --only-plugin-dir, in the order given
  bool only_plugin_dirs = false;          // --only-plugin-dir: no MECHGRAPH_PLUGIN_PATH, no built-ins
  /// Every SDK 1.x node type called through C (PluginRegistry::set_node_types_through_c): plugin-test.
  bool node_types_through_c = false;
};

/// Loads the plugins from the search path (--plugin-dir, MECHGRAPH_PLUGIN_PATH, the built-in folder).
/// `first` are plugin files loaded before the search path (plugin-test LIB.so): a copy of the same
/// plugin found later (an installed one) is then the one skipped. A refused `first` file throws.
/// With `needs`, files the probe cache knows to provide none of them stay unloaded
/// (PluginRegistry::load_directories): a command that runs one scene loads what the scene uses.
PluginRegistry load_plugins(const PluginSearch& options, const std::vector<std::filesystem::path>& first = {},
                            const PluginNeeds* needs = nullptr);

/// What a scene uses: its node types, the plugins its `requires:` names, and with an
/// `uncertainty:` block the node type of ISO 286 limits (iso286_node_type). Nothing (load every
/// plugin) for a scene with an `effects:` block, whose effects are known by the types that
/// implement them, and for a scene without nodes.
std::optional<PluginNeeds> scene_plugin_needs(const SceneSpec& scene);

}  // namespace mechgraph::host
