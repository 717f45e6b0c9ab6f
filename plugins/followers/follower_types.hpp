#pragma once
// The followers of this plugin (docs/methods/followers.md), each in its own file, and their node
// types. Lengths in metres; the pivot in the drawn fixed frame (cam centre at the origin, the
// follower on +y).
#include <mechgraph/domain/follower.hpp>
#include <mechgraph/node.hpp>

#include <memory>

namespace mechgraph::followers {

/// Flat-faced tappet translating along +y (translating_flat.cpp).
std::shared_ptr<const Follower> make_flat();
/// Roller of radius rr translating along a line `offset` from the cam centre (translating_roller.cpp);
/// offset 0 is the in-line roller.
std::shared_ptr<const Follower> make_roller(double roller_radius, double offset);
/// Flat-faced arm turning about (pivot_x, pivot_y); its face a line at face_offset from the pivot on
/// the cam's side (pivoted_flat.cpp).
std::shared_ptr<const Follower> make_pivoted_flat(double pivot_x, double pivot_y, double face_offset);
/// Roller of radius rr at arm_length from the pivot (pivoted_roller.cpp).
std::shared_ptr<const Follower> make_pivoted_roller(double pivot_x, double pivot_y, double arm_length, double roller_radius);

/// follower.flat, follower.roller, follower.offset_roller, follower.pivoted_flat,
/// follower.pivoted_roller (follower_nodes.cpp) and follower.valve_lift (valve_lift_node.cpp).
void add_follower_types(NodeTypeList& out);
std::shared_ptr<const NodeType> make_valve_lift_type();

/// "12.5 mm", for messages.
std::string mm(double metres);

}  // namespace mechgraph::followers
