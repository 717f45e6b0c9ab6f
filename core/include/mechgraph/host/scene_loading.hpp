#pragma once
// A scene made into a graph the way every host does it: --set overrides applied, and for a sweep
// the outputs it can write a column of.
#include <mechgraph/graph.hpp>
#include <mechgraph/plugin_registry.hpp>

#include <optional>
#include <string>
#include <vector>

namespace mechgraph::host {

/// Applies --set overrides to a scene read already and builds the graph against the loaded plugins.
Graph load_graph(const SceneSpec& scene, const std::vector<std::string>& sets, const PluginRegistry& registry);

/// How a host names its options in messages: the command line's flags, or Python's keywords
/// (python_option_names).
struct OptionNames {
  const char* outputs = "--outputs";
  const char* one_design = "mechgraph run --out writes it for one design";  // where a table or handle goes
  const char* samples = "--samples";
  const char* seed = "--seed";
  const char* method = "--method";
};
inline constexpr OptionNames python_option_names{"outputs", "Scene.run(outputs=[...]) gives it for one design", "samples",
                                                 "seed", "method"};

/// The graph a sweep runs: `outputs` ("a.b,c.d", --outputs) replace the scene's outputs and report;
/// without them, tables and handles (not one number per case) are left out of the scene's own
/// outputs with a note. Updates `scene.outputs` to what the graph requests. Throws UsageError for
/// a chosen output that is not a scalar or a series, or one listed twice (named as `option` names them).
Graph build_sweep_graph(SceneSpec& scene, const PluginRegistry& registry, const std::vector<Override>& overrides,
                        const std::optional<std::string>& outputs, const OptionNames& option = {});

}  // namespace mechgraph::host
