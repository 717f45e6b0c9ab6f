// The valvetrain plugin: valve kinematics and gas exchange of the valve-train study.
#include "node_types.hpp"

#include <mechgraph/plugin_abi.hpp>

namespace {
mechgraph::NodeTypeList make_node_types() {
  using namespace mechgraph::valvetrain;
  return {make_valve_motion_type(), make_time_area_type(), make_masses_type(), make_spring_design_type(),
          make_resonance_type(), make_dynamics_type(), make_float_speed_type(),
          make_polydyne_cam_type()};
}
}  // namespace

MECHGRAPH_PLUGIN("valvetrain", MECHGRAPH_SDK_VERSION, &make_node_types)
