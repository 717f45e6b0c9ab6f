// The follower node types: each gives a `follower` handle that cam.contour and follower.valve_lift
// take (docs/methods/followers.md). Lengths are checked here; whether the follower fits a given
// cam (reaches its base circle, follows its contour) is checked where cam and follower meet.
#include "follower_types.hpp"

#include <functional>
#include <numbers>

namespace mechgraph::followers {
namespace {

using Make = std::function<std::shared_ptr<const Follower>(const ParamSet&)>;

class FollowerType final : public NodeType {
 public:
  FollowerType(std::string type, std::string summary, std::vector<ParamSpec> params, Make make) : make_(std::move(make)) {
    info_.type = std::move(type);
    info_.summary = std::move(summary);
    info_.params = std::move(params);
    info_.outputs = {PortSpec::handle("follower", std::string(Follower::kind_name),
                                      "the follower, for cam.contour and follower.valve_lift")};
  }
  const NodeInfo& info() const override { return info_; }
  void evaluate(const ParamSet& p, const InputSet&, OutputSet& out, EvalContext&) const override {
    out.set("follower", Value::handle(make_(p)));
  }

 private:
  NodeInfo info_;
  Make make_;
};

ParamSpec roller_radius() {
  return ParamSpec::number("roller_radius", dim::length, "roller radius", "mm").at_least(1e-6).at_most(1.0).because("1 um to 1 m: a roller (a knife edge is a flat follower's limit, not a roller)").with_example(10e-3);
}
ParamSpec pivot(const char* axis, double example) {
  return ParamSpec::number(std::string("pivot_") + axis, dim::length,
                           std::string("pivot position, ") + axis +
                               " from the cam centre in the drawing (follower on +y; a pivot left of the axis, x <= 0, "
                               "turns counterclockwise to lift)",
                           "mm")
      .at_least(-10.0)
      .at_most(10.0)
      .because("within 10 m either way: far past any cam follower's pivot")
      .with_example(example);
}

}  // namespace

void add_follower_types(NodeTypeList& out) {
  out.push_back(std::make_shared<const FollowerType>(
      "follower.flat", "flat-faced (mushroom) tappet translating along its axis through the cam centre", std::vector<ParamSpec>{},
      [](const ParamSet&) { return make_flat(); }));
  out.push_back(std::make_shared<const FollowerType>(
      "follower.roller", "in-line roller follower translating along its axis through the cam centre",
      std::vector<ParamSpec>{roller_radius()}, [](const ParamSet& p) { return make_roller(p.number("roller_radius"), 0.0); }));
  out.push_back(std::make_shared<const FollowerType>(
      "follower.offset_roller", "roller follower translating on a line beside the cam centre",
      std::vector<ParamSpec>{roller_radius(),
                             ParamSpec::number("offset", dim::length,
                                               "distance of the roller's line of motion from the cam centre, positive "
                                               "to the side that lowers the pressure angle on the rise",
                                               "mm")
                                 .at_least(-1.0)
                                 .at_most(1.0)
                                 .because("within 1 m either way: far past any cam")
                                 .with_example(3e-3)},
      [](const ParamSet& p) { return make_roller(p.number("roller_radius"), p.number("offset")); }));
  out.push_back(std::make_shared<const FollowerType>(
      "follower.pivoted_flat",
      "finger or rocker follower with a flat pad, turning about a pivot; the cam lift is the arc its base-circle contact "
      "travels (the arm turns by lift / lever)",
      std::vector<ParamSpec>{pivot("x", -35e-3), pivot("y", 30e-3),
                             ParamSpec::number("face_offset", dim::length,
                                               "distance of the pad's face from the pivot, on the cam's side (0: the "
                                               "face passes through the pivot)",
                                               "mm")
                                 .with_default(0.0)
                                 .at_least(-1.0)
                                 .at_most(1.0)
                                 .because("within 1 m either way: far past any cam")},
      [](const ParamSet& p) { return make_pivoted_flat(p.number("pivot_x"), p.number("pivot_y"), p.number("face_offset")); }));
  out.push_back(std::make_shared<const FollowerType>(
      "follower.pivoted_roller",
      "finger or rocker follower with a roller, turning about a pivot; the cam lift is the arc the roller centre "
      "travels (the arm turns by lift / arm_length)",
      std::vector<ParamSpec>{pivot("x", -35e-3), pivot("y", 30e-3),
                             ParamSpec::number("arm_length", dim::length, "pivot to roller centre", "mm")
                                 .at_least(1e-4)
                                 .at_most(10.0)
                                 .because("0.1 mm to 10 m: a follower arm (the lever divides by it)")
                                 .with_example(35e-3),
                             roller_radius()},
      [](const ParamSet& p) {
        return make_pivoted_roller(p.number("pivot_x"), p.number("pivot_y"), p.number("arm_length"), p.number("roller_radius"));
      }));
  out.push_back(make_valve_lift_type());
}

}  // namespace mechgraph::followers
