// The backlash plugin: tolerance stacks and the free play of the steering drive's kinematic
// chain (docs/methods/backlash.md).
#include "node_types.hpp"

#include <mechgraph/plugin_abi.hpp>

namespace {
mechgraph::NodeTypeList make_node_types() {
  return {mechgraph::backlash::make_stack_linear_type(), mechgraph::backlash::make_backlash_chain_type(),
          mechgraph::backlash::make_two_axis_type()};
}
}  // namespace

MECHGRAPH_PLUGIN("backlash", MECHGRAPH_SDK_VERSION, &make_node_types)
