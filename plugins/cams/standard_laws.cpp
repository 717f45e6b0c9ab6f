// Registration of the textbook laws and the tabulated lift: each is a CamLawDefinition handed to
// make_cam_node_type, which adds the common parameters (max_lift, action_angle, base_radius, the
// ramps, samples) and outputs.
#include "cam_node.hpp"
#include "registration.hpp"
#include "rise_law.hpp"
#include "table_law.hpp"

#include <string>

namespace mechgraph::cams {
namespace {

CamLawDefinition rise_return_definition(RiseShape shape, std::string summary) {
  CamLawDefinition d;
  d.type = "cam." + std::string(rise_shape_name(shape));
  d.version = 1;
  d.summary = std::move(summary);
  d.make = [shape](const CamBasics& b, const ParamSet&, OutputSet&) -> std::shared_ptr<const CamLaw> {
    return std::make_shared<const SymmetricRiseReturnLaw>(shape, b.max_lift, b.action_angle, b.base_radius);
  };
  return d;
}

}  // namespace

void add_standard_law_types(NodeTypeList& out) {
  const char* symmetric = ", rise over half the action angle and symmetric return";
  out.push_back(make_cam_node_type(rise_return_definition(
      RiseShape::cycloidal, std::string("cycloidal law (sine acceleration, jerk jumps at the ends)") + symmetric)));
  out.push_back(make_cam_node_type(rise_return_definition(
      RiseShape::harmonic, std::string("simple harmonic law (acceleration jumps at the ends)") + symmetric)));
  out.push_back(make_cam_node_type(
      rise_return_definition(RiseShape::poly345, std::string("3-4-5 polynomial law") + symmetric)));
  out.push_back(make_cam_node_type(rise_return_definition(
      RiseShape::poly4567, std::string("4-5-6-7 polynomial law (jerk continuous)") + symmetric)));
  out.push_back(make_cam_node_type(rise_return_definition(
      RiseShape::modified_trapezoid, std::string("modified trapezoidal acceleration law") + symmetric)));
  out.push_back(make_cam_node_type(
      rise_return_definition(RiseShape::modified_sine, std::string("modified sine law") + symmetric)));
  out.push_back(make_cam_node_type(table_law_definition()));
}

}  // namespace mechgraph::cams
