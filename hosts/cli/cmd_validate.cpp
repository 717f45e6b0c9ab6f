// mechgraph validate SCENE: load and check everything, evaluate nothing.
#include "cli.hpp"
#include "options.hpp"
#include <mechgraph/host/terminal_output.hpp>

#include <mechgraph/text_escape.hpp>

#include <sstream>

namespace mechgraph::cli {

int validate_command(const GlobalOptions& g, const std::vector<std::string>& args) {
  po::options_description visible("validate options");
  add_scene_options(visible);
  po::variables_map vm;
  if (!parse_scene_command(args, visible, vm, "mechgraph validate SCENE [--set NAME=VALUE ...]")) return ok;
  const SceneSpec scene = load_scene(vm["scene"].as<std::string>());
  const PluginRegistry registry = plugins_for_scene(g, scene);
  const Graph graph = load_scene_graph(vm, scene, registry);
  std::ostringstream text;  // the scene's path is the user's text: shown through terminal_text
  text << terminal_text(vm["scene"].as<std::string>(), TerminalLines::one) << ": valid; " << graph.nodes.size() << " nodes, "
       << graph.order.size() << " needed for " << graph.outputs.size() << " outputs\n";
  print_text(text.str());
  return ok;
}

}  // namespace mechgraph::cli
