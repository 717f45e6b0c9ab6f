// mechgraph validate SCENE: load and check everything, evaluate nothing.
#include "cli.hpp"
#include "options.hpp"

#include <iostream>

namespace mechgraph::cli {

int validate_command(const GlobalOptions& g, const std::vector<std::string>& args) {
  po::options_description visible("validate options");
  add_scene_options(visible);
  po::variables_map vm;
  if (!parse_scene_command(args, visible, vm, "mechgraph validate SCENE [--set NAME=VALUE ...]")) return ok;
  const PluginRegistry registry = load_plugins(g);
  const Graph graph = load_scene_graph(vm, registry);
  std::cout << vm["scene"].as<std::string>() << ": valid; " << graph.nodes.size() << " nodes, " << graph.order.size()
            << " needed for " << graph.outputs.size() << " outputs\n";
  return ok;
}

}  // namespace mechgraph::cli
