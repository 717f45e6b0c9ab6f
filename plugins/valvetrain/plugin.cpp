// The valvetrain plugin: valve kinematics and gas exchange of the valve-train study. Through the
// SDK 1.x C boundary (MECHGRAPH_PLUGIN_1): cam laws, followers and springs come in as the SDK's
// interfaces from whatever plugin made them; its valve motions go out as mechgraph.valve_motion/1.
#include "node_types.hpp"

#include <mechgraph/plugin_sdk1.hpp>

MECHGRAPH_PLUGIN_1("valvetrain", MECHGRAPH_SDK_VERSION, &mechgraph::valvetrain::node_types)
