#pragma once
#include <mechgraph/node.hpp>

namespace mechgraph::valvetrain {

std::shared_ptr<const NodeType> make_valve_motion_type();
std::shared_ptr<const NodeType> make_time_area_type();

}  // namespace mechgraph::valvetrain
