// mechgraph graph SCENE: the graph as Graphviz DOT. Needed nodes are solid; culled nodes (not
// needed for any requested output) sit in a grey dashed cluster; requested outputs are bold.
#include "cli.hpp"
#include "options.hpp"

#include <mechgraph/text_escape.hpp>

#include <iostream>
#include <map>
#include <set>

namespace mechgraph::cli {
namespace {

void write_dot(std::ostream& os, const Graph& graph) {
  std::set<std::size_t> requested;
  for (const RequestedOutput& o : graph.outputs) requested.insert(o.node);
  os << "digraph mechgraph {\n  rankdir=LR;\n  node [shape=box, fontname=\"Helvetica\"];\n";
  if (!graph.title.empty()) os << "  label=" << dot_string(graph.title) << ";\n  labelloc=t;\n";
  auto node_line = [&](std::size_t i) {
    const GraphNode& n = graph.nodes[i];
    os << "    " << dot_string(n.name) << " [label=" << dot_string(n.name + "\n" + n.info().type);
    if (requested.count(i)) os << ", penwidth=2";
    os << "];\n";
  };
  os << "  subgraph cluster_needed {\n    label=\"evaluated\";\n    style=solid;\n";
  for (std::size_t i = 0; i < graph.nodes.size(); ++i)
    if (graph.nodes[i].needed) node_line(i);
  os << "  }\n";
  bool any_culled = false;
  for (const GraphNode& n : graph.nodes) any_culled |= !n.needed;
  if (any_culled) {
    os << "  subgraph cluster_culled {\n    label=\"culled (not needed)\";\n    style=dashed;\n    color=grey;\n"
          "    fontcolor=grey;\n    node [color=grey, fontcolor=grey, style=dashed];\n";
    for (std::size_t i = 0; i < graph.nodes.size(); ++i)
      if (!graph.nodes[i].needed) node_line(i);
    os << "  }\n";
  }
  for (const GraphNode& n : graph.nodes)
    for (const GraphNode::Input& in : n.inputs)
      for (const GraphNode::Source& s : in.sources) {
        os << "  " << dot_string(graph.nodes[s.node].name) << " -> " << dot_string(n.name) << " [label="
           << dot_string(s.port + " -> " + in.port);
        if (!n.needed) os << ", style=dashed, color=grey, fontcolor=grey";
        os << "];\n";
      }
  // One box per node listing what is requested of it, so many outputs don't bury the graph.
  std::map<std::size_t, std::string> requested_ports;
  for (const RequestedOutput& o : graph.outputs) {
    std::string& ports = requested_ports[o.node];
    ports += (ports.empty() ? "" : "\n") + o.port;
  }
  for (const auto& [node, ports] : requested_ports) {
    const std::string id = "out:" + graph.nodes[node].name;
    os << "  " << dot_string(id) << " [shape=note, fontsize=10, label=" << dot_string(ports) << "];\n";
    os << "  " << dot_string(graph.nodes[node].name) << " -> " << dot_string(id) << " [style=bold, arrowhead=none];\n";
  }
  os << "}\n";
}

}  // namespace

int graph_command(const GlobalOptions& g, const std::vector<std::string>& args) {
  po::options_description visible("graph options");
  add_scene_options(visible);
  po::variables_map vm;
  if (!parse_scene_command(args, visible, vm, "mechgraph graph SCENE [--set NAME=VALUE ...] | dot -Tsvg"))
    return ok;
  const SceneSpec scene = load_scene(vm["scene"].as<std::string>());
  const PluginRegistry registry = plugins_for_scene(g, scene);
  write_dot(std::cout, load_scene_graph(vm, scene, registry));
  return ok;
}

}  // namespace mechgraph::cli
