// The valvetrain plugin: valve kinematics and gas exchange of the valve-train study.
#include "node_types.hpp"

#include <mechgraph/plugin_abi.hpp>

namespace {
mechgraph::NodeTypeList make_node_types() {
  return {mechgraph::valvetrain::make_valve_motion_type(), mechgraph::valvetrain::make_time_area_type()};
}
}  // namespace

MECHGRAPH_PLUGIN("valvetrain", "0.1.0", &make_node_types)
