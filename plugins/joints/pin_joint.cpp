// joint.pin: a pin in one or more bores (methods/backlash.md, "The method", steps 2-3; source
// figures 1-3: a pin in the bores of a bracket, a clevis).
//
// Each connected fit is one sliding interface between the pin and a bore; the interfaces are in
// series along the load path (pin in the rod eye, pin in the clevis), so their clearances add:
//   play = sum_i max(0, k S_i),   S_i = hole_i - shaft_i (diametral clearance of fit i),
// with k = play_factor. k = 1 (the default) takes the whole diametral clearance as free play along
// the rod's line of action: the pin can move from one side of the bore to the other along that
// line, which is the case for a hinge whose line of action is radial to the pin. Use k < 1 for a
// hinge whose line of action is inclined to the bore's plane of play.
// Two bores that are line-bored together and hold the pin in parallel (both clevis cheeks) act
// as one interface: connect one fit for them, not two.
#include "node_types.hpp"

#include <sstream>

namespace mechgraph::joints {
namespace {

class PinJointType final : public NodeType {
 public:
  PinJointType() {
    info_.type = "joint.pin";
    info_.summary = "pin in one or more bores (clevis): the fits' diametral clearances in series along the line of action";
    info_.params = {
        ParamSpec::number("play_factor", dim::none,
                          "share of each fit's diametral clearance that appears as play along the line of action "
                          "(1: the line of action is radial to the pin; at most 100)")
            .with_default(1.0)
            .positive()
            .at_most(100.0)
            .because("> 0: a factor on a play; <= 100: far past any geometry"),
        joint_label_param(),
    };
    info_.inputs = {PortSpec::handle("fits", std::string(Fit::kind_name),
                                     "the pin's fits, one per sliding interface in series (at least one)")
                        .many()};
    info_.outputs = joint_play_ports();
  }
  const NodeInfo& info() const override { return info_; }

  void evaluate(const ParamSet& p, const InputSet& in, OutputSet& out, EvalContext&) const override {
    const auto fits = connected_fits(in, "fits");
    if (fits.empty()) throw NodeError("fits", "a pin joint needs at least one fit (pin in a bore)");
    const double k = p.number("play_factor");
    std::vector<PlayTerm> terms;
    for (const auto& fit : fits) terms.push_back(scaled(fit->clearance_term(), k));
    std::string joint;
    if (p.has("label")) {
      joint = p.text("label");
    } else {
      std::ostringstream s;
      s << "pin in " << fits.size() << (fits.size() == 1 ? " bore" : " bores") << " (" << fits.front()->designation();
      for (std::size_t i = 1; i < fits.size(); ++i) s << ", " << fits[i]->designation();
      s << ")";
      joint = s.str();
    }
    set_joint_play(out, std::move(joint), std::move(terms), "fits");
  }

 private:
  NodeInfo info_;
};

}  // namespace

std::shared_ptr<const NodeType> make_pin_joint_type() { return std::make_shared<const PinJointType>(); }

}  // namespace mechgraph::joints
