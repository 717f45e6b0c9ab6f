// The fits plugin: hole/shaft fits from ISO 286 designations or explicit deviations.
#include "fit_nodes.hpp"

#include <mechgraph/plugin_abi.hpp>

namespace {
mechgraph::NodeTypeList make_node_types() {
  return {mechgraph::fits::make_iso286_fit_type(), mechgraph::fits::make_explicit_fit_type()};
}
}  // namespace

MECHGRAPH_PLUGIN("fits", MECHGRAPH_SDK_VERSION, &make_node_types)
