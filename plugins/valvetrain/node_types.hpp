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

}  // namespace mechgraph::valvetrain
