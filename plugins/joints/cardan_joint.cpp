// joint.cardan: a cardan (universal) joint as the hinge to the movable part where the deflection
// exceeds what a spherical bearing tilts (methods/backlash.md; the source's figure 5).
//
// Free play (terms of `play`): each connected trunnion-bearing fit's diametral clearance (the
// fits of both trunnion pairs, in series), and the trunnions' axial end float as one
// deterministic term (end_float, when > 0).
//
// Kinematics (cardan_kinematics.hpp): output_angle t2, angular_error t2 - t1, speed_ratio w2/w1
// at input_angle t1, and its extremes cos b and 1/cos b.
//
// Effect `cardan_kinematics`: the joint's play is taken as play on its input side and reduced to
// the output through the joint's instantaneous transmission: a small input rotation d1 becomes
// d2 = (dt2/dt1) d1, so the angular play at the output = speed_ratio(t1) x the angular play at the
// input, and every term's sensitivity is multiplied by speed_ratio(t1). With the effect off the
// factor is 1 (pass-through). The factor used is output as play_scale.
#include "cardan_kinematics.hpp"
#include "node_types.hpp"

#include <cmath>
#include <numbers>
#include <sstream>

namespace mechgraph::joints {
namespace {

constexpr double deg = std::numbers::pi / 180.0;
constexpr const char* effect_name = "cardan_kinematics";
// 2^55 rad: from here on one ulp of the angle is 8 rad, more than a turn.
constexpr double max_input_angle = 36028797018963968.0;

class CardanJointType final : public NodeType {
 public:
  CardanJointType() {
    info_.type = "joint.cardan";
    info_.summary =
        "cardan (universal) joint: trunnion clearances and end float; output angle and speed ratio at a bend angle";
    info_.params = {
        // Any angle a double resolves within a turn: a shaft turns more than once, and sin and cos
        // reduce the double given exactly. From 2^55 rad on, neighbouring doubles lie 8 rad apart
        // (more than a turn): such an angle names no position in a turn, so it is refused.
        ParamSpec::number("input_angle", dim::angle,
                          "input yoke angle t1, measured from the plane of the bend; any number of turns either way "
                          "(the kinematics repeat every half turn), up to 2^55 rad = 2.06e18 deg, beyond which "
                          "neighbouring doubles lie more than a turn apart and the angle names no position in a turn",
                          "deg")
            .above(-max_input_angle)
            .below(max_input_angle)
            .because("within 2^55 rad either way: beyond, neighbouring doubles lie more than a turn apart and the angle names no position")
            .with_example(30.0 * deg),
        ParamSpec::number("bend_angle", dim::angle,
                          "bend angle b between the shafts, 0 <= b < 90 deg (at 90 deg the joint locks)", "deg")
            .non_negative()
            .below(0.5 * std::numbers::pi)
            .because(">= 0: an angle between shafts; < 90 deg: at 90 deg the joint locks (1/cos b grows without bound)")
            .with_example(20.0 * deg),
        ParamSpec::number("end_float", dim::length, "axial end float of the trunnions, added as one play term", "um")
            .with_default(0.0)
            .non_negative()
            .because(">= 0: a play"),
        joint_label_param(),
    };
    info_.inputs = {PortSpec::handle("fits", std::string(Fit::kind_name),
                                     "the trunnion-bearing fits of the two trunnion pairs; may be none")
                        .many()
                        .optional_port()};
    info_.outputs = joint_play_ports();
    info_.outputs.push_back(PortSpec::scalar("output_angle", dim::angle,
                                             "output yoke angle t2 = atan2(sin t1, cos t1 cos b), continuous in t1", "deg"));
    info_.outputs.push_back(PortSpec::scalar("angular_error", dim::angle, "t2 - t1", "deg"));
    info_.outputs.push_back(
        PortSpec::scalar("speed_ratio", dim::none, "w2/w1 = cos b / (1 - sin^2 b cos^2 t1) at input_angle"));
    info_.outputs.push_back(PortSpec::scalar("speed_ratio_min", dim::none, "cos b (at t1 = 90 deg)"));
    info_.outputs.push_back(PortSpec::scalar("speed_ratio_max", dim::none, "1/cos b (at t1 = 0)"));
    info_.outputs.push_back(PortSpec::scalar(
        "play_scale", dim::none, "factor applied to the play: speed_ratio with cardan_kinematics on, 1 with it off"));
    info_.effects = {{effect_name,
                      "reduce the cardan's play through its instantaneous speed ratio at input_angle "
                      "(angular play at the output = speed_ratio x angular play at the input); off: factor 1"}};
    info_.output_dependencies = {{"output_angle", {}},    {"angular_error", {}},   {"speed_ratio", {}},
                                 {"speed_ratio_min", {}}, {"speed_ratio_max", {}}, {"play_scale", {}}};
  }
  const NodeInfo& info() const override { return info_; }

  void evaluate(const ParamSet& p, const InputSet& in, OutputSet& out, EvalContext& ctx) const override {
    const CardanKinematics joint(p.number("bend_angle"));
    const double t1 = p.number("input_angle");
    // The declared range, again for callers that bypass the scene loader (the SDK's harness).
    if (!(std::abs(t1) < max_input_angle))
      throw NodeError("input_angle", "the input angle must lie below 2^55 rad = 2.06e18 deg either way: beyond it "
                                     "neighbouring doubles lie more than a turn apart");
    const double ratio = joint.speed_ratio(t1);
    const double scale = ctx.effect(effect_name) ? ratio : 1.0;

    std::vector<PlayTerm> terms;
    for (const auto& fit : connected_fits(in, "fits")) terms.push_back(scaled(fit->clearance_term(), scale));
    const double end_float = p.number("end_float");
    if (!(end_float >= 0.0)) throw NodeError("end_float", "the end float must be zero or positive");
    if (end_float > 0.0) {
      std::ostringstream label;
      label << "trunnion end float " << end_float * 1e6 << " um";
      terms.push_back({label.str(), {{label.str(), end_float, 0.0, scale, Distribution::normal}}});
    }
    std::string name = p.has("label") ? p.text("label") : [&] {
      std::ostringstream s;
      s << "cardan joint, bend " << joint.bend_angle() / deg << " deg";
      return s.str();
    }();
    set_joint_play(out, std::move(name), std::move(terms), "fits");

    out.set_scalar("output_angle", joint.output_angle(t1));
    out.set_scalar("angular_error", joint.angular_error(t1));
    out.set_scalar("speed_ratio", ratio);
    out.set_scalar("speed_ratio_min", joint.speed_ratio_min());
    out.set_scalar("speed_ratio_max", joint.speed_ratio_max());
    out.set_scalar("play_scale", scale);
  }

 private:
  NodeInfo info_;
};

}  // namespace

std::shared_ptr<const NodeType> make_cardan_joint_type() { return std::make_shared<const CardanJointType>(); }

}  // namespace mechgraph::joints
