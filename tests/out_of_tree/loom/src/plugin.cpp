// The loom plugin through the SDK 1.x C boundary: one exported C entry, nothing of the host's.
#include "loom_types.hpp"

#include <mechgraph/plugin_sdk1.hpp>

namespace {
mechgraph::NodeTypeList make_node_types() { return {loom::make_heddle_law(), loom::make_lever_pivot()}; }
}  // namespace

MECHGRAPH_PLUGIN_1("loom", LOOM_PLUGIN_VERSION, &make_node_types)
