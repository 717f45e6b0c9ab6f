#pragma once
// The cam node types of this plugin, by family.
#include <mechgraph/node.hpp>

namespace mechgraph::cams {

/// The profiles of the source study: cam.three_arc, cam.kurz, cam.polydyne.
void add_source_profile_types(NodeTypeList& out);
/// The textbook laws, ramps and tabulated lift: cam.cycloidal, cam.harmonic, cam.poly345,
/// cam.poly4567, cam.modified_trapezoid, cam.modified_sine, cam.table.
void add_standard_law_types(NodeTypeList& out);
/// cam.contour: the contour, pressure angle and contact stress for any cam law.
void add_contour_type(NodeTypeList& out);
/// cam.program: a cam from rise, dwell and return segments (tests/plugins/cams/program_law_test.cpp).
void add_program_type(NodeTypeList& out);

/// Every node type of the plugin, in the order it lists them.
inline NodeTypeList node_types() {
  NodeTypeList types;
  add_source_profile_types(types);
  add_standard_law_types(types);
  add_contour_type(types);
  add_program_type(types);
  return types;
}

}  // namespace mechgraph::cams
