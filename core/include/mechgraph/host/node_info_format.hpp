#pragma once
// How `plugins` and `describe` show a node type: as text for people, as JSON for tools.
#include <mechgraph/json_writer.hpp>
#include <mechgraph/node.hpp>

#include <ostream>

namespace mechgraph::host {

/// Text for people, through terminal_text (a plugin's words hold no control sequence when shown).
void write_node_info_text(std::ostream& os, const NodeInfo& info);
void write_node_info_json(JsonWriter& json, const NodeInfo& info);

}  // namespace mechgraph::host
