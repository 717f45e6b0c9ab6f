#pragma once
// Calling the cam node types directly, as the evaluator would (defaults filled in).
#include "registration.hpp"
#include "test_support.hpp"

#include <catch2/catch.hpp>

#include <map>
#include <string>

namespace mechgraph::cams::testing {

/// Every cam node type of the plugin, from its two registration functions.
inline const NodeTypeList& all_cam_types() {
  static const NodeTypeList types = [] {
    NodeTypeList list;
    add_source_profile_types(list);
    add_standard_law_types(list);
    return list;
  }();
  return types;
}

inline const NodeType& cam_type(const std::string& name) {
  for (const auto& t : all_cam_types())
    if (t->info().type == name) return *t;
  FAIL(name << " is not registered");
  throw std::logic_error("unreachable");
}

/// The cam.contour node type (registered apart from the cam laws).
inline const NodeType& contour_type() {
  static const NodeTypeList types = [] {
    NodeTypeList list;
    add_contour_type(list);
    return list;
  }();
  return *types.front();
}

/// Evaluates cam node `type` with `given` parameters on top of the ParamSpec defaults.
inline OutputSet run_cam(const std::string& type, const std::map<std::string, ParamValue>& given) {
  const NodeType& node = cam_type(type);
  OutputSet out;
  mechgraph::testing::RecordingContext ctx;
  node.evaluate(mechgraph::testing::defaults_of(node.info(), given), InputSet{}, out, ctx);
  return out;
}

}  // namespace mechgraph::cams::testing
