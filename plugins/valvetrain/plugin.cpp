// The valvetrain plugin: valve kinematics and gas exchange of the valve-train study. Through the
// SDK 1.x C boundary (MECHGRAPH_PLUGIN_1): cam laws, followers and springs come in as the SDK's
// interfaces from whatever plugin made them; its valve motions go out as mechgraph.valve_motion/1.
#include "node_types.hpp"

#include <mechgraph/plugin_sdk1.hpp>

namespace {
mechgraph::NodeTypeList make_node_types() {
  using namespace mechgraph::valvetrain;
  return {make_valve_motion_type(), make_time_area_type(), make_masses_type(), make_spring_design_type(),
          make_resonance_type(), make_dynamics_type(), make_float_speed_type(),
          make_polydyne_cam_type()};
}
}  // namespace

MECHGRAPH_PLUGIN_1("valvetrain", MECHGRAPH_SDK_VERSION, &make_node_types)
