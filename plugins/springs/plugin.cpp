// The springs plugin: spring models that valvetrain.spring_design sizes for a required line.
// Through the SDK 1.x C boundary (MECHGRAPH_PLUGIN_1): its models cross as mechgraph.spring_model/1
// and the springs they size as mechgraph.spring/1.
#include "node_types.hpp"

#include <mechgraph/plugin_sdk1.hpp>

namespace {
mechgraph::NodeTypeList make_node_types() {
  return {mechgraph::springs::make_helical_spring_type(), mechgraph::springs::make_dual_spring_type()};
}
}  // namespace

MECHGRAPH_PLUGIN_1("springs", MECHGRAPH_SDK_VERSION, &make_node_types)
