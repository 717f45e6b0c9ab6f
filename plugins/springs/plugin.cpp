// The springs plugin: spring models that valvetrain.spring_design sizes for a required line.
#include "node_types.hpp"

#include <mechgraph/plugin_abi.hpp>

namespace {
mechgraph::NodeTypeList make_node_types() {
  return {mechgraph::springs::make_helical_spring_type(), mechgraph::springs::make_dual_spring_type()};
}
}  // namespace

MECHGRAPH_PLUGIN("springs", MECHGRAPH_SDK_VERSION, &make_node_types)
