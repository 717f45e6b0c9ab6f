// The joints plugin: the hinge types of the steering-drive backlash study (methods/backlash.md):
// joint.pin, joint.spherical, joint.cardan.
#include "node_types.hpp"

#include <mechgraph/plugin_abi.hpp>

namespace {
mechgraph::NodeTypeList make_node_types() {
  return {mechgraph::joints::make_pin_joint_type(), mechgraph::joints::make_spherical_joint_type(),
          mechgraph::joints::make_cardan_joint_type()};
}
}  // namespace

MECHGRAPH_PLUGIN("joints", MECHGRAPH_SDK_VERSION, &make_node_types)
