// The profiles of the source study (docs/methods/valvetrain.md, stage 1): three-arc convex,
// Kurz and polydyne. Each law's file pair describes its node; this file registers them.
#include "kurz.hpp"
#include "polydyne.hpp"
#include "registration.hpp"
#include "three_arc.hpp"

namespace mechgraph::cams {

void add_source_profile_types(NodeTypeList& out) {
  out.push_back(make_cam_node_type(three_arc_definition()));
  out.push_back(make_cam_node_type(kurz_definition()));
  out.push_back(make_cam_node_type(polydyne_definition()));
}

}  // namespace mechgraph::cams
