// The cams plugin: every cam law of mechgraph behind the CamLaw interface. Through the SDK 1.x C
// boundary (MECHGRAPH_PLUGIN_1): its laws cross as mechgraph.cam_law/1, in blocks of cases as
// c/node_block.h says, and as their C++ objects to a consumer of the same C++ layer (c/object_cxx.h).
#include "registration.hpp"

#include <mechgraph/plugin_sdk1.hpp>

MECHGRAPH_PLUGIN_1("cams", MECHGRAPH_SDK_VERSION, &mechgraph::cams::node_types)
