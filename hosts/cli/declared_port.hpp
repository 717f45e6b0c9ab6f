#pragma once
// The declarations behind a result (presentation.hpp): the node type's description of the port an
// output label ("node.port") names, its presentation and the angle frames. Hosts present results
// from these only, never from names (docs/design/sdk-1.0.md, sections 1.6 and 5).
#include <mechgraph/graph.hpp>
#include <mechgraph/host/angle_reference.hpp>
#include <mechgraph/node.hpp>

#include <string>

namespace mechgraph::cli {

struct DeclaredPort {
  const GraphNode* node = nullptr;
  const NodeInfo* info = nullptr;
  const PortSpec* port = nullptr;

  /// The port's presentation; a plain one when nothing is declared.
  const Presentation& presentation() const {
    static const Presentation plain;
    return port ? port->presentation : plain;
  }
  /// The declaration of channel (or axis) `name`, or nullptr.
  const ChannelDecl* channel(const std::string& name) const { return presentation().find(name); }
  /// The frame `id` of the node type, or nullptr.
  const AngleFrame* frame(const std::string& id) const { return info ? info->find_frame(id) : nullptr; }
  /// The tag a unit of degrees carries for frame `id` ("shaft" -> "deg (shaft)"), "" for none.
  std::string tag(const std::string& id) const {
    const AngleFrame* f = frame(id);
    return f ? f->unit_tag : std::string();
  }
  /// The tag of table column `c` (its channel's or axis' declared frame): "shaft" makes a column
  /// of degrees "opening [deg (shaft)]" (angle_reference.hpp); "" when it declares none.
  std::string column_tag(const Table::Column& c) const {
    return info && port ? host::column_angle_reference(*info, *port, c.name, c.dimension) : std::string();
  }
  /// The tags of a series' values and of its axis (the port's frame).
  std::string values_tag(const Dimension& d) const { return info && port ? host::angle_reference(*info, port->angle_frame, d) : std::string(); }
  /// The label a reader sees for a channel: its declared label, else its name with '_' as ' '.
  std::string label(const std::string& name) const {
    if (const ChannelDecl* c = channel(name)) return c->shown_label();
    return ChannelDecl::of(name).shown_label();
  }
};

/// The declarations behind output `label` ("node.port"); empty members when the graph has no such
/// node or port.
inline DeclaredPort declared_port(const Graph& graph, const std::string& label) {
  DeclaredPort d;
  const auto dot = label.find('.');
  const auto n = graph.find(label.substr(0, dot));
  if (!n) return d;
  d.node = &graph.nodes[*n];
  d.info = &d.node->info();
  if (dot != std::string::npos) d.port = d.info->find_output(label.substr(dot + 1));
  return d;
}

}  // namespace mechgraph::cli
