// The joints plugin: the hinge types of the steering-drive backlash study (methods/backlash.md):
// joint.pin, joint.spherical, joint.cardan.
// Through the SDK 1.x C boundary (MECHGRAPH_PLUGIN_1): fits come in as mechgraph.fit/1, plays go out
// as mechgraph.joint_play/1.
#include "node_types.hpp"

#include <mechgraph/plugin_sdk1.hpp>

namespace {
mechgraph::NodeTypeList make_node_types() {
  return {mechgraph::joints::make_pin_joint_type(), mechgraph::joints::make_spherical_joint_type(),
          mechgraph::joints::make_cardan_joint_type()};
}
}  // namespace

MECHGRAPH_PLUGIN_1("joints", MECHGRAPH_SDK_VERSION, &make_node_types)
