// The plugin's entry: its id, its semantic version and its node types.
#include "example_types.hpp"

#include <mechgraph/plugin_abi.hpp>

namespace {
mechgraph::NodeTypeList make_node_types() { return {example::make_parabolic_cam(), example::make_slot_joint()}; }
}  // namespace

MECHGRAPH_PLUGIN("example", EXAMPLE_PLUGIN_VERSION, &make_node_types)
