// loom.lever_pivot: the pivot of a treadle lever, a pin in a bushing. Its diametral clearance c in
// [c_min, c_max] (a chosen distribution) lets the lever tip move by k c, k = tip arm / pin arm:
// the joint's play is one term with one link, mean k (c_min + c_max) / 2, half range
// k (c_max - c_min) / 2 (mechgraph/domain/tolerance.hpp). Swung by theta from its centre, the tip
// moves along its arc: the play seen along the heddle's line is k c / cos(theta), tabulated over
// the lever's swing in its own angle frame ("swing").
#include "loom_types.hpp"

#include <mechgraph/domain/tolerance.hpp>
#include <mechgraph/errors.hpp>
#include <mechgraph/presentation.hpp>

#include <cmath>
#include <numbers>

namespace loom {
namespace {

using namespace mechgraph;
constexpr double pi = std::numbers::pi;

class LeverPivot final : public NodeType {
 public:
  LeverPivot() {
    info_.type = "loom.lever_pivot";
    info_.summary = "a treadle lever's pivot pin: its clearance as play at the lever tip";
    info_.params = {
        ParamSpec::number("clearance_min", dim::length, "least diametral clearance of the pin", "um").non_negative().with_default(10e-6),
        ParamSpec::number("clearance_max", dim::length, "greatest diametral clearance of the pin", "um").non_negative().with_default(40e-6),
        distribution_param("distribution", "how the clearance is spread over its range"),
        ParamSpec::number("arm_ratio", dim::none, "tip arm over pin arm", "1").with_default(6.0).above(0.0),
        ParamSpec::number("swing", dim::angle, "the lever's swing either side of its centre", "deg")
            .positive()
            .below(0.5 * pi)
            .because("below 90 deg: at 90 deg the tip moves across the heddle's line")
            .with_default(25.0 * pi / 180.0),
    };
    AngleFrame swing;
    swing.id = "swing";
    swing.label = "lever swing from its centre";
    swing.unit_tag = "swing";
    swing.zero = "the lever square to the heddle's line";
    info_.frames = {swing};
    Presentation over_swing;
    over_swing.figure_title = "Play at the lever tip over its swing";
    over_swing.with_axis(ChannelDecl::of("swing_angle", dim::angle).in_frame("swing"));
    over_swing.with(ChannelDecl::of("tip_play_max", dim::length).labelled("greatest tip play"));
    over_swing.with(ChannelDecl::of("tip_play_min", dim::length).labelled("least tip play"));
    info_.outputs = {
        PortSpec::handle("play", std::string(JointPlay::kind_name), "the pivot's free play at the lever tip, for the stack-up"),
        PortSpec::scalar("play_min", dim::length, "least play at the tip", "um"),
        PortSpec::scalar("play_max", dim::length, "greatest play at the tip", "um"),
        PortSpec::scalar("swing_limit", dim::angle, "the swing's end", "deg").in_frame("swing"),
        PortSpec::table("tip_play", "play along the heddle's line over the lever's swing").presented(over_swing),
    };
  }
  const NodeInfo& info() const override { return info_; }

  void evaluate(const ParamSet& p, const InputSet&, OutputSet& out, EvalContext& ctx) const override {
    const double c_min = p.number("clearance_min"), c_max = p.number("clearance_max"), k = p.number("arm_ratio");
    const double swing = p.number("swing");
    if (c_max < c_min) throw NodeError("clearance_max", "clearance_max must not be below clearance_min");
    const ToleranceLink link{"pivot clearance", 0.5 * k * (c_min + c_max), 0.5 * k * (c_max - c_min), 1.0,
                             distribution_from(p.text("distribution"), "distribution")};
    auto play = std::make_shared<const JointPlay>("lever pivot", std::vector<PlayTerm>{{"pivot clearance", {link}}});
    out.set("play", Value::handle(play));
    out.set_scalar("play_min", play->play_min());
    out.set_scalar("play_max", play->play_max());
    out.set_scalar("swing_limit", swing);
    if (ctx.wanted("tip_play")) {
      Table t;
      t.axis = {"swing_angle", dim::angle, {}, "deg"};
      t.add_channel("tip_play_max", dim::length, "um");
      t.add_channel("tip_play_min", dim::length, "um");
      constexpr int n = 41;
      for (int i = 0; i < n; ++i) {
        const double theta = -swing + 2.0 * swing * i / (n - 1);
        t.axis.values.push_back(theta);
        t.channels[0].values.push_back(play->play_max() / std::cos(theta));
        t.channels[1].values.push_back(play->play_min() / std::cos(theta));
      }
      out.set("tip_play", Value::table(std::move(t)));
    }
  }

 private:
  NodeInfo info_;
};

}  // namespace

std::shared_ptr<const NodeType> make_lever_pivot() { return std::make_shared<const LeverPivot>(); }

}  // namespace loom
