// The plugin's entry: its id, its semantic version and its node types. MECHGRAPH_PLUGIN_1 exports
// them through the SDK 1.x C boundary (mechgraph/plugin_sdk1.hpp): the host sees C tables only,
// so it loads the plugin whichever compiler built either side.
#include "example_types.hpp"

#include <mechgraph/plugin_sdk1.hpp>

namespace {
mechgraph::NodeTypeList make_node_types() { return {example::make_parabolic_cam(), example::make_slot_joint()}; }
}  // namespace

MECHGRAPH_PLUGIN_1("example", EXAMPLE_PLUGIN_VERSION, &make_node_types)
