// mechgraph validate SCENE: load and check everything, evaluate nothing.
#include "cli.hpp"
#include "options.hpp"

#include <iostream>

namespace mechgraph::cli {

int validate_command(const GlobalOptions& g, const std::vector<std::string>& args) {
  po::options_description visible("validate options");
  visible.add_options()("help,h", "this text")("set", po::value<std::vector<std::string>>()->composing(),
                                                "override a parameter, as for run");
  po::options_description all;
  all.add(visible).add_options()("scene", po::value<std::string>()->required(), "scene file");
  po::positional_options_description positional;
  positional.add("scene", 1);
  po::variables_map vm;
  if (!parse_options(args, visible, all, positional, vm, "mechgraph validate SCENE [--set NAME=VALUE ...]")) return ok;
  const auto sets = vm.count("set") ? vm["set"].as<std::vector<std::string>>() : std::vector<std::string>{};
  const PluginRegistry registry = load_plugins(g);
  const Graph graph = load_graph(vm["scene"].as<std::string>(), sets, registry);
  std::cout << vm["scene"].as<std::string>() << ": valid; " << graph.nodes.size() << " nodes, " << graph.order.size()
            << " needed for " << graph.outputs.size() << " outputs\n";
  return ok;
}

}  // namespace mechgraph::cli
