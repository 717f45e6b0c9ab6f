// The built-in plugins that evaluate blocks of cases, `cams` (BUILTIN_SDK1_CAMS) and `valvetrain`
// (BUILTIN_SDK1_VALVETRAIN), built from their own node types on the SDK 1.x entry
// (MECHGRAPH_PLUGIN_1), so that a test can run the same sweep through the C boundary
// (c/node_block.h) and through the pre-1.0 C++ entry of the built-in plugins, and compare.
#include <mechgraph/plugin_sdk1.hpp>

#if defined(BUILTIN_SDK1_CAMS)
#include "registration.hpp"

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

MECHGRAPH_PLUGIN_1("cams", MECHGRAPH_SDK_VERSION, &make_node_types)
#elif defined(BUILTIN_SDK1_VALVETRAIN)
#include "node_types.hpp"

namespace {
mechgraph::NodeTypeList make_node_types() {
  using namespace mechgraph::valvetrain;
  return {make_valve_motion_type(), make_time_area_type(), make_masses_type(), make_spring_design_type(),
          make_resonance_type(),    make_dynamics_type(),  make_float_speed_type(), make_polydyne_cam_type()};
}
}  // namespace

MECHGRAPH_PLUGIN_1("valvetrain", MECHGRAPH_SDK_VERSION, &make_node_types)
#endif
