#pragma once
#include <mechgraph/node.hpp>

namespace mechgraph::springs {

std::shared_ptr<const NodeType> make_helical_spring_type();
std::shared_ptr<const NodeType> make_dual_spring_type();

}  // namespace mechgraph::springs
