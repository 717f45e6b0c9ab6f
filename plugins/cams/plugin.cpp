// The cams plugin: every cam law of mechgraph behind the CamLaw interface.
#include "registration.hpp"

#include <mechgraph/plugin_abi.hpp>

namespace {
mechgraph::NodeTypeList make_node_types() {
  mechgraph::NodeTypeList types;
  mechgraph::cams::add_source_profile_types(types);
  mechgraph::cams::add_standard_law_types(types);
  mechgraph::cams::add_contour_type(types);
  mechgraph::cams::add_program_type(types);
  return types;
}
}  // namespace

MECHGRAPH_PLUGIN("cams", MECHGRAPH_SDK_VERSION, &make_node_types)
