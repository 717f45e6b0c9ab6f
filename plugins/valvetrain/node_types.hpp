#pragma once
#include <mechgraph/node.hpp>

namespace mechgraph::valvetrain {

std::shared_ptr<const NodeType> make_valve_motion_type();
std::shared_ptr<const NodeType> make_time_area_type();
std::shared_ptr<const NodeType> make_masses_type();
std::shared_ptr<const NodeType> make_spring_design_type();
std::shared_ptr<const NodeType> make_resonance_type();
std::shared_ptr<const NodeType> make_dynamics_type();
std::shared_ptr<const NodeType> make_float_speed_type();
std::shared_ptr<const NodeType> make_polydyne_cam_type();

/// Every node type of the plugin, in the order it lists them.
inline NodeTypeList node_types() {
  return {make_valve_motion_type(), make_time_area_type(), make_masses_type(),    make_spring_design_type(),
          make_resonance_type(),    make_dynamics_type(),  make_float_speed_type(), make_polydyne_cam_type()};
}

}  // namespace mechgraph::valvetrain
