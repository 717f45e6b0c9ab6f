// mechgraph plugins [--json]: the loaded plugins and their node types.
#include "cli.hpp"
#include <mechgraph/host/node_info_format.hpp>
#include "options.hpp"
#include <mechgraph/host/terminal_output.hpp>

#include <mechgraph/text_escape.hpp>

#include <iostream>
#include <sstream>

namespace mechgraph::cli {

int plugins_command(const GlobalOptions& g, const std::vector<std::string>& args) {
  po::options_description visible("plugins options");
  visible.add_options()("help,h", "this text")("json", "full descriptions as JSON");
  po::positional_options_description none;
  po::variables_map vm;
  if (!parse_options(args, visible, visible, none, vm, "mechgraph plugins [--json]")) return ok;
  const PluginRegistry registry = load_plugins(g);
  if (vm.count("json")) {
    std::ostringstream text;  // built whole: a failure leaves stdout empty, not half a document
    JsonWriter json(text);
    json.begin_object().key("plugins").begin_array();
    for (const PluginInfo& p : registry.plugins()) {
      json.begin_object().key("id").value(p.id).key("version").value(p.version).key("path").value(p.path.string());
      json.key("fingerprint").value(p.fingerprint).key("node_types").begin_array();
      for (const auto& t : p.node_types) write_node_info_json(json, registry.find(t)->type->info());
      json.end_array().end_object();
    }
    json.end_array().key("skipped").begin_array();
    for (const SkippedPlugin& s : registry.skipped())
      json.begin_object().key("path").value(s.path.string()).key("reason").value(s.reason).end_object();
    json.end_array().end_object();
    std::cout << text.str() << "\n";
    return ok;
  }
  // Ids, paths, summaries and reasons are the plugins' and the file system's text: shown through
  // terminal_text, one line each.
  std::ostringstream text;
  const auto line = [](const std::string& s) { return terminal_text(s, TerminalLines::one); };
  for (const PluginInfo& p : registry.plugins()) {
    text << line(p.id) << " " << line(p.version) << "  (" << line(p.path.string()) << ")\n";
    for (const auto& t : p.node_types) {
      const NodeInfo& info = registry.find(t)->type->info();
      text << "  " << line(t) << std::string(t.size() < 30 ? 30 - t.size() : 1, ' ') << line(info.summary) << "\n";
    }
  }
  for (const SkippedPlugin& s : registry.skipped()) text << "skipped  " << line(s.reason) << "\n";
  print_text(text.str());
  return ok;
}

}  // namespace mechgraph::cli
