#pragma once
// An SDK 1.x node type's C description (mg_node_desc, sdk/include/mechgraph/c/node.h) turned into
// the host's NodeInfo, once, at load time. Every field is read only when the plugin's struct holds
// it (MG_HAS_FIELD; an older 1.x plugin's structs are shorter) and arrays are strided by their
// elements' struct_size. A malformed description is a PluginError naming the type and the field.
// Private to libmechgraph.
#include <mechgraph/c/node.h>
#include <mechgraph/node.hpp>

#include <string>
#include <vector>

namespace mechgraph::detail {

/// What the host keeps of a C node type's declaration beside its NodeInfo.
struct CNodeDeclaration {
  NodeInfo info;
  std::vector<std::uint32_t> input_interface_versions;   // per input (objects), 0 otherwise
  std::vector<std::uint32_t> output_interface_versions;  // per output (objects), 0 otherwise
};

/// Converts and checks `type->desc`; `where` names the plugin ("plugin '/x.so' ('id')").
CNodeDeclaration c_node_declaration(const mg_node_type& type, const std::string& where);

/// The host's dimension as the C boundary carries it, and back (PluginError naming `what` when a
/// C dimension uses an exponent this host does not know: current, amount, luminous intensity).
mg_dim to_c_dim(const Dimension& d);
Dimension from_c_dim(const mg_dim& d, const std::string& what);

}  // namespace mechgraph::detail
