// follower.valve_lift: the valve side of a pivoted follower (docs/methods/followers.md, "Valve
// side"). The arm turns by psi = h / L (L the cam-side lever); the pad at valve_arm Lv from the pivot
// pushes a flat valve tip whose axis stands square to the arm when psi = a (valve_arm_angle), so
//   v = Lv (sin(psi - a) + sin a),   dv/dh = (Lv / L) cos(psi - a)   (the ratio varies with lift),
// whatever the pad's radius. Its derivatives over cam angle by the chain rule, exactly:
//   v' = Lv cos q psi', v'' = Lv (cos q psi'' - sin q psi'^2),
//   v''' = Lv (cos q psi''' - 3 sin q psi' psi'' - cos q psi'^3),  q = psi - a.
// The output is a cam_law of the valve lift, for valvetrain.valve_motion (rocker_ratio 1). A
// translating follower acts on the valve directly (a bucket tappet): the valve lift is the cam lift.
#include "follower_types.hpp"

#include <mechgraph/domain/cam_curves.hpp>
#include <mechgraph/errors.hpp>

#include <array>
#include <cmath>
#include <functional>
#include <numbers>
#include <sstream>

namespace mechgraph::followers {
namespace {

constexpr double pi = std::numbers::pi;

class ValveSideLaw final : public CamLaw {
 public:
  ValveSideLaw(std::shared_ptr<const CamLaw> cam, double lever, double valve_arm, double square_at)
      : cam_(std::move(cam)), lever_(lever), valve_arm_(valve_arm), square_at_(square_at) {}
  double event_begin() const override { return cam_->event_begin(); }
  double event_end() const override { return cam_->event_end(); }
  std::vector<double> breakpoints() const override { return cam_->breakpoints(); }
  double base_radius() const override { return cam_->base_radius(); }
  double max_lift() const override { return valve_lift(cam_->max_lift()); }
  LiftDerivatives evaluate_in_event(double phi) const override {
    const LiftDerivatives h = cam_->evaluate_in_event(phi);
    const double psi1 = h.velocity / lever_, psi2 = h.acceleration / lever_, psi3 = h.jerk / lever_;
    const double q = h.lift / lever_ - square_at_;
    const double c = std::cos(q), s = std::sin(q);
    LiftDerivatives v;
    v.lift = valve_lift(h.lift);
    v.velocity = valve_arm_ * c * psi1;
    v.acceleration = valve_arm_ * (c * psi2 - s * psi1 * psi1);
    v.jerk = valve_arm_ * (c * psi3 - 3.0 * s * psi1 * psi2 - c * psi1 * psi1 * psi1);
    return v;
  }
  // The valve lift rises with the cam lift (cos q > 0 is checked by the node): same monotone runs.
  bool monotone_breaks(int order, std::vector<double>& breaks) const override {
    return order == 0 && cam_->monotone_breaks(0, breaks);
  }
  double valve_lift(double h) const {
    // The difference of sines as a product, so a lift of 1e-12 m is not lost to cancellation.
    const double psi = h / lever_;
    return std::max(0.0, 2.0 * valve_arm_ * std::cos(0.5 * psi - square_at_) * std::sin(0.5 * psi));
  }

 private:
  std::shared_ptr<const CamLaw> cam_;
  double lever_, valve_arm_, square_at_;
};

class ValveLiftType final : public NodeType {
 public:
  ValveLiftType() {
    info_.type = "follower.valve_lift";
    info_.summary = "valve lift of a pivoted (finger or rocker) follower over cam angle: the ratio to the cam lift varies "
                    "with the arm's turn";
    info_.inputs = {PortSpec::handle("cam", std::string(CamLaw::kind_name), "the cam law (lift on the cam side)"),
                    PortSpec::handle("follower", std::string(Follower::kind_name), "a pivoted follower")};
    info_.params = {
        ParamSpec::number("valve_arm", dim::length,
                          "pivoted follower: pivot to the centre of the pad on the valve tip (a translating follower "
                          "acts on the valve directly and takes none)",
                          "mm")
            .optional()
            .at_least(1e-4)
            .at_most(10.0)
            .because("0.1 mm to 10 m: a rocker arm (the ratio divides by it)"),
        ParamSpec::number("valve_arm_angle", dim::angle,
                          "turn of the arm from the valve closed at which it stands square to the valve axis (the valve "
                          "lift ratio is largest there); 0: square at the seat",
                          "deg")
            .with_default(0.0)
            .above(-pi / 2.0)
            .at_most(pi / 2.0)
            .because("> -90 and <= 90 deg: the valve must rise with the arm's turn psi, cos(psi - angle) > 0 from psi = 0"),
        ParamSpec::integer("curve_points", "points of the curve table over the event widened by a tenth each side")
            .with_default(361.0)
            .at_least(3)
            .at_most(1e6)
            .because(">= 3: a curve needs its two ends and a point between; <= 1e6: bounded in memory"),
    };
    info_.outputs = {
        PortSpec::handle("law", std::string(CamLaw::kind_name), "valve lift over cam angle (for valvetrain.valve_motion, "
                                                                "rocker_ratio 1)"),
        PortSpec::scalar("max_lift", dim::length, "valve lift at the nose", "mm"),
        PortSpec::scalar("max_follower_angle", dim::angle, "turn of the arm at the nose", "deg"),
        PortSpec::scalar("cam_lever", dim::length, "pivot to the base-circle contact (cam side)", "mm"),
        PortSpec::scalar("ratio_closed", dim::none, "valve lift / cam lift for a small lift, valve_arm cos(a) / cam_lever"),
        PortSpec::scalar("ratio_at_nose", dim::none, "d(valve lift) / d(cam lift) at the nose"),
        PortSpec::table("curve", "follower_angle, valve_lift and ratio (d valve lift / d cam lift) over cam angle")
            .presented(over_cam_angle()),
    };
    info_.frames = cam_angle_frames(false);
  }
  const NodeInfo& info() const override { return info_; }

  void evaluate(const ParamSet& p, const InputSet& in, OutputSet& out, EvalContext& ctx) const override {
    const auto cam = in.handle<CamLaw>("cam");
    const auto follower = in.handle<Follower>("follower");
    if (!follower->pivoted()) {
      if (p.has("valve_arm"))
        throw NodeError("valve_arm", "the " + follower->named() +
                                         " translates and acts on the valve directly: the valve lift is the cam lift; "
                                         "leave valve_arm out (a rocker is valvetrain.valve_motion's rocker_ratio)");
      out.set("law", Value::handle(cam));
      out.set_scalar("max_lift", cam->max_lift());
      out.set_scalar("max_follower_angle", 0.0);
      out.set_scalar("ratio_closed", 1.0);
      out.set_scalar("ratio_at_nose", 1.0);
      if (ctx.wanted("curve")) out.set("curve", Value::table(curve(*cam, p, [](double h) { return std::array{0.0, h, 1.0}; })));
      return;
    }
    if (!p.has("valve_arm")) throw NodeError("valve_arm", "the " + follower->named() + " needs valve_arm (pivot to the valve pad)");
    // The follower must sit on this cam's base circle at all (throws naming its parameter if not).
    follower->contact(0.0, cam->at(0.0), cam->base_radius(), false);
    const double lever = follower->cam_lever(cam->base_radius());
    const double valve_arm = p.number("valve_arm"), square_at = p.number("valve_arm_angle");
    const double psi_max = cam->max_lift() / lever;
    // The valve must rise with the arm's turn all the way: cos(psi - a) > 0 on [0, psi_max].
    if (!(psi_max - square_at < 0.5 * pi && -square_at < 0.5 * pi)) {
      std::ostringstream m;
      m << "the arm turns " << psi_max * 180.0 / pi << " deg (cam lift " << mm(cam->max_lift()) << " over the lever "
        << mm(lever) << "): with valve_arm_angle " << square_at * 180.0 / pi
        << " deg it passes 90 deg from square to the valve axis and the valve would fall back";
      throw NodeError("valve_arm_angle", m.str());
    }
    const auto law = std::make_shared<const ValveSideLaw>(cam, lever, valve_arm, square_at);
    out.set("law", Value::handle(law));
    out.set_scalar("max_lift", law->max_lift());
    out.set_scalar("max_follower_angle", psi_max);
    out.set_scalar("cam_lever", lever);
    out.set_scalar("ratio_closed", valve_arm * std::cos(square_at) / lever);
    out.set_scalar("ratio_at_nose", valve_arm * std::cos(psi_max - square_at) / lever);
    if (ctx.wanted("curve"))
      out.set("curve", Value::table(curve(*cam, p, [&](double h) {
                return std::array{h / lever, law->valve_lift(h), valve_arm * std::cos(h / lever - square_at) / lever};
              })));
  }

 private:
  // follower_angle, valve_lift and ratio over cam angle, from the cam lift h by `row(h)`.
  static Table curve(const CamLaw& cam, const ParamSet& p, const std::function<std::array<double, 3>(double)>& row) {
    const auto n = static_cast<std::size_t>(p.integer("curve_points"));
    const double width = cam.event_end() - cam.event_begin();
    const double from = std::max(-pi, cam.event_begin() - 0.1 * width), to = std::min(pi, cam.event_end() + 0.1 * width);
    Table t;
    t.axis = {"cam_angle", dim::angle, std::vector<double>(n), "deg"};
    t.add_channel("follower_angle", dim::angle, "deg");
    t.add_channel("valve_lift", dim::length, "mm");
    t.add_channel("ratio", dim::none);
    for (std::size_t i = 0; i < n; ++i) {
      const double phi = i + 1 == n ? to : from + (to - from) * static_cast<double>(i) / static_cast<double>(n - 1);
      t.axis.values[i] = phi;
      const std::array<double, 3> r = row(cam.at(phi).lift);
      for (std::size_t k = 0; k < 3; ++k) t.channels[k].values.push_back(r[k]);
    }
    return t;
  }

  NodeInfo info_;
};

}  // namespace

std::shared_ptr<const NodeType> make_valve_lift_type() { return std::make_shared<const ValveLiftType>(); }

}  // namespace mechgraph::followers
