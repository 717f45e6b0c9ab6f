// The built-in plugins `cams` (BUILTIN_PRE10_CAMS) and `valvetrain` (BUILTIN_PRE10_VALVETRAIN),
// built from their own node types on the pre-1.0 entry (MECHGRAPH_PLUGIN, plugin_abi.hpp), where
// C++ objects cross as they are: the tests that read valvetrain's private objects (a spring
// design) out of a run, and those of the pre-1.0 entry's interplay with SDK 1.x plugins, load
// these in place of the shipped ones (test_support.hpp, builtin_pre10_registry).
#include <mechgraph/plugin_abi.hpp>

#if defined(BUILTIN_PRE10_CAMS)
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

MECHGRAPH_PLUGIN("cams", MECHGRAPH_SDK_VERSION, &make_node_types)
#elif defined(BUILTIN_PRE10_VALVETRAIN)
#include "node_types.hpp"

namespace {
mechgraph::NodeTypeList make_node_types() {
  using namespace mechgraph::valvetrain;
  return {make_valve_motion_type(), make_time_area_type(), make_masses_type(), make_spring_design_type(),
          make_resonance_type(),    make_dynamics_type(),  make_float_speed_type(), make_polydyne_cam_type()};
}
}  // namespace

MECHGRAPH_PLUGIN("valvetrain", MECHGRAPH_SDK_VERSION, &make_node_types)
#endif
