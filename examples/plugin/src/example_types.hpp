#pragma once
// The node types of the example plugin.
#include <mechgraph/node.hpp>

#include <memory>

namespace example {

/// example.parabolic_cam: a constant-acceleration (parabolic) rise and return.
std::shared_ptr<const mechgraph::NodeType> make_parabolic_cam();
/// example.slot_joint: a pin in a slot; its free play as a joint_play term for the stack-up.
std::shared_ptr<const mechgraph::NodeType> make_slot_joint();

}  // namespace example
