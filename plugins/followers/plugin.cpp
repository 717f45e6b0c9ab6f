// The followers plugin: every follower behind the Follower interface, any cam law with any follower.
#include "follower_types.hpp"

#include <mechgraph/plugin_abi.hpp>

namespace {
mechgraph::NodeTypeList make_node_types() {
  mechgraph::NodeTypeList types;
  mechgraph::followers::add_follower_types(types);
  return types;
}
}  // namespace

MECHGRAPH_PLUGIN("followers", MECHGRAPH_SDK_VERSION, &make_node_types)
