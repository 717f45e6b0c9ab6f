// The backlash plugin: tolerance stacks and the free play of the steering drive's kinematic
// chain (docs/methods/backlash.md). Through the SDK 1.x C boundary (MECHGRAPH_PLUGIN_1): the first
// built-in plugin on it, and the real plugin scripts/test-sdk-compat.sh builds from sdk-1.0.
#include "node_types.hpp"

#include <mechgraph/plugin_sdk1.hpp>

namespace {
mechgraph::NodeTypeList make_node_types() {
  return {mechgraph::backlash::make_stack_linear_type(), mechgraph::backlash::make_backlash_chain_type(),
          mechgraph::backlash::make_two_axis_type()};
}
}  // namespace

MECHGRAPH_PLUGIN_1("backlash", MECHGRAPH_SDK_VERSION, &make_node_types)
