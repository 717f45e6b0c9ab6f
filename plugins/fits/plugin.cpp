// The fits plugin: hole/shaft fits from ISO 286 designations or explicit deviations.
// Through the SDK 1.x C boundary (MECHGRAPH_PLUGIN_1): its fits cross as mechgraph.fit/1.
#include "fit_nodes.hpp"

#include <mechgraph/plugin_sdk1.hpp>

namespace {
mechgraph::NodeTypeList make_node_types() {
  return {mechgraph::fits::make_iso286_fit_type(), mechgraph::fits::make_explicit_fit_type()};
}
}  // namespace

MECHGRAPH_PLUGIN_1("fits", MECHGRAPH_SDK_VERSION, &make_node_types)
