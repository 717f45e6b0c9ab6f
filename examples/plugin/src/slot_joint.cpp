// example.slot_joint: a pin guided in a slot. Its radial clearance c lies in [c_min, c_max] with a
// chosen distribution; along the line of action it reaches the output through the lever ratio k,
// so the joint's play is one term, max(0, k c), with one link: mean k (c_min + c_max) / 2, half range
// (c_max - c_min) / 2 (mechgraph/domain/tolerance.hpp).
#include "example_types.hpp"

#include <mechgraph/domain/tolerance.hpp>
#include <mechgraph/errors.hpp>

namespace example {
namespace {

using namespace mechgraph;

class SlotJoint final : public NodeType {
 public:
  SlotJoint() {
    info_.type = "example.slot_joint";
    info_.summary = "a pin in a slot: its clearance as free play along the line of action";
    info_.params = {
        ParamSpec::number("clearance_min", dim::length, "least clearance between pin and slot", "um").non_negative().with_example(20e-6),
        ParamSpec::number("clearance_max", dim::length, "greatest clearance between pin and slot", "um").non_negative().with_example(80e-6),
        distribution_param("distribution", "how the clearance is spread over its range"),
        ParamSpec::number("lever_ratio", dim::none, "play at the output per unit of clearance", "1").with_default(1.0).above(0.0),
    };
    info_.outputs = {
        PortSpec::handle("play", std::string(JointPlay::kind_name), "the joint's free play, for the stack-up"),
        PortSpec::scalar("play_min", dim::length, "least play", "um"),
        PortSpec::scalar("play_max", dim::length, "greatest play", "um"),
    };
  }
  const NodeInfo& info() const override { return info_; }

  void evaluate(const ParamSet& p, const InputSet&, OutputSet& out, EvalContext&) const override {
    const double c_min = p.number("clearance_min"), c_max = p.number("clearance_max"), k = p.number("lever_ratio");
    if (c_max < c_min) throw NodeError("clearance_max", "clearance_max must not be below clearance_min");
    const ToleranceLink link{"slot clearance", 0.5 * (c_min + c_max), 0.5 * (c_max - c_min), k,
                             distribution_from(p.text("distribution"), "distribution")};
    auto play = std::make_shared<const JointPlay>("slot joint", std::vector<PlayTerm>{{"slot clearance", {link}}});
    out.set("play", Value::handle(play));
    out.set_scalar("play_min", play->play_min());
    out.set_scalar("play_max", play->play_max());
  }

 private:
  NodeInfo info_;
};

}  // namespace

std::shared_ptr<const NodeType> make_slot_joint() { return std::make_shared<const SlotJoint>(); }

}  // namespace example
