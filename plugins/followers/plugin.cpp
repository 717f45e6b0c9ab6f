// The followers plugin: every follower behind the Follower interface, any cam law with any follower.
// Through the SDK 1.x C boundary (MECHGRAPH_PLUGIN_1): its followers cross as mechgraph.follower/1.
#include "follower_types.hpp"

#include <mechgraph/plugin_sdk1.hpp>

namespace {
mechgraph::NodeTypeList make_node_types() {
  mechgraph::NodeTypeList types;
  mechgraph::followers::add_follower_types(types);
  return types;
}
}  // namespace

MECHGRAPH_PLUGIN_1("followers", MECHGRAPH_SDK_VERSION, &make_node_types)
