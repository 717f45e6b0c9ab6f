// mechgraph describe TYPE [--json]: one node type in full.
#include "cli.hpp"
#include <mechgraph/host/node_info_format.hpp>
#include "options.hpp"
#include <mechgraph/host/terminal_output.hpp>

#include <mechgraph/did_you_mean.hpp>

#include <iostream>
#include <sstream>

namespace mechgraph::cli {

int describe_command(const GlobalOptions& g, const std::vector<std::string>& args) {
  po::options_description visible("describe options");
  visible.add_options()("help,h", "this text")("json", "as JSON");
  po::options_description all;
  all.add(visible).add_options()("type", po::value<std::string>()->required(), "node type");
  po::positional_options_description positional;
  positional.add("type", 1);
  po::variables_map vm;
  if (!parse_options(args, visible, all, positional, vm, "mechgraph describe TYPE [--json]")) return ok;
  const PluginRegistry registry = load_plugins(g);
  const std::string type = vm["type"].as<std::string>();
  const RegisteredType* t = registry.find(type);
  if (!t) throw UsageError(unknown_name_message("node type", type, registry.type_names()));
  if (vm.count("json")) {
    std::ostringstream text;  // built whole: a failure leaves stdout empty, not half a document
    JsonWriter json(text);
    write_node_info_json(json, t->type->info());
    std::cout << text.str() << "\n";
  } else {
    std::ostringstream text;  // a plugin's words: shown through terminal_text
    write_node_info_text(text, t->type->info());
    print_text(text.str());
  }
  return ok;
}

}  // namespace mechgraph::cli
