// valvetrain.polydyne_cam: the cam that makes the elastic drive deliver a given valve law at the
// design speed (Dudley's polydyne synthesis; docs/methods/valvetrain.md, stage 1 and "dynamic
// simulation"). The valve is to follow x(phi) = i p(phi), the given law p (e.g. cam.polydyne)
// times the rocker ratio, as it would on a rigid drive without lash. With the single-mass model
// (valve side) M x'' = k_d (y - x) - P0 - c_s x, the drive displacement that gives the valve lift
// x(phi) exactly at camshaft speed w_d is
//   y = x + (P0 + c_s x + M w_d^2 x_phiphi) / k_d,
// and the tappet (cam) lift is h = (y + lash) / i. Its derivatives need x up to the 5th order
// (CamLaw::higher_derivatives). At the ends of the valve law y = P0 / k_d: the drive must be
// pre-loaded to the spring's preload before the valve moves, so a cycloidal take-up ramp of
// `ramp_angle` lifts the cam from 0 to (P0 / k_d + lash) / i on each side (zero velocity and
// acceleration at both its ends). The synthesis ignores the drive's damping: with damping the
// delivered motion differs by the damping force's share.
#include "node_types.hpp"
#include "train_masses.hpp"

#include <mechgraph/domain/cam_law.hpp>
#include <mechgraph/numerics/piecewise.hpp>

#include <cmath>
#include <numbers>
#include <sstream>

namespace mechgraph::valvetrain {
namespace {

constexpr double pi = std::numbers::pi;

class SynthesizedCam final : public CamLaw {
 public:
  struct Drive {
    double mass, stiffness, preload, rate, speed, rocker, lash;
  };
  SynthesizedCam(std::shared_ptr<const CamLaw> valve_law, Drive d, double ramp)
      : law_(std::move(valve_law)), d_(d), ramp_(ramp) {
    take_up_ = (d_.preload / d_.stiffness + d_.lash) / d_.rocker;
    top_ = tappet(0.0).lift;
  }
  double event_begin() const override { return law_->event_begin() - ramp_; }
  double event_end() const override { return law_->event_end() + ramp_; }
  std::vector<double> breakpoints() const override { return law_->knots(); }  // the ramps' ends too
  double max_lift() const override { return top_; }
  double base_radius() const override { return law_->base_radius(); }
  double roller_radius() const override { return law_->roller_radius(); }

  LiftDerivatives evaluate_in_event(double phi) const override {
    if (phi <= law_->event_begin()) return ramp((phi - event_begin()) / ramp_, 1.0);
    if (phi >= law_->event_end()) return ramp((event_end() - phi) / ramp_, -1.0);
    return tappet(phi);
  }

 private:
  // h = (y + lash) / i with y = x + (P0 + c_s x + M w^2 x'') / k_d, and its derivatives.
  // With x = i p: h = a p + (b p'' + P0 / k_d + lash) / i ... the rocker cancels but in the constant.
  LiftDerivatives tappet(double phi) const {
    const LiftDerivatives p = law_->at(phi);
    double p4 = 0.0, p5 = 0.0;
    if (phi > law_->event_begin() && phi < law_->event_end()) law_->higher_derivatives(phi, p4, p5);
    const double a = 1.0 + d_.rate / d_.stiffness, b = d_.mass * d_.speed * d_.speed / d_.stiffness;
    return {a * p.lift + b * p.acceleration + (d_.preload / d_.stiffness + d_.lash) / d_.rocker, a * p.velocity + b * p.jerk,
            a * p.acceleration + b * p4, a * p.jerk + b * p5};
  }
  // The take-up ramp, cycloidal in s = 0..1 from the outer end; `direction` -1 mirrors it.
  LiftDerivatives ramp(double s, double direction) const {
    const double c = std::cos(2.0 * pi * s), sn = std::sin(2.0 * pi * s), r = ramp_;
    return {take_up_ * (s - sn / (2.0 * pi)), direction * take_up_ * (1.0 - c) / r, take_up_ * 2.0 * pi * sn / (r * r),
            direction * take_up_ * 4.0 * pi * pi * c / (r * r * r)};
  }

  std::shared_ptr<const CamLaw> law_;
  Drive d_;
  double ramp_;
  double take_up_ = 0.0;
  double top_ = 0.0;
};

class PolydyneCamType final : public NodeType {
 public:
  PolydyneCamType() {
    info_.type = "valvetrain.polydyne_cam";
    info_.summary = "synthesises the cam whose elastic drive delivers the given valve law exactly at the design speed";
    info_.params = {
        ParamSpec::number("design_rpm", dim::angular_speed, "crank speed the cam is made for (camshaft at half)", "rpm")
            .at_least(2.0 * pi / 60.0)
            .at_most(1e6 * 2.0 * pi / 60.0)
            .because("1 to 1e6 rpm: a turning engine, far past any")
            .with_example(6000.0 * 2.0 * pi / 60.0),
        ParamSpec::number("drive_stiffness", dim::stiffness,
                          "k_d: the drive's stiffness reduced to the valve (from 1 N/mm: softer, the synthesised "
                          "correction M a / k_d leaves any cam)",
                          "N/mm")
            .at_least(1e3)
            .at_most(1e13)
            .because("1 N/mm to 1e10 N/mm: softer, the correction M a / k_d leaves any cam; stiffer than any steel drive")
            .with_example(4e6),
        ParamSpec::number("rocker_ratio", dim::none, "valve lift / tappet lift, l_v / l_p").with_default(1.0).at_least(0.01).at_most(100.0).because("0.01 to 100: a rocker, as valve_motion's"),
        ParamSpec::number("lash", dim::length, "valve lash, taken up by the ramps", "mm").with_default(0.0).non_negative().at_most(0.1).because(">= 0: a gap; <= 0.1 m: far past any valve lash"),
        ParamSpec::number("ramp_angle", dim::angle, "cam angle of each take-up ramp", "deg")
            .with_default(20.0 * pi / 180.0)
            .positive()
            .below(pi)
            .because("> 0 and < 180 deg: the valve law's event plus two ramps fit in one turn"),
    };
    info_.inputs = {
        PortSpec::handle("law", std::string(CamLaw::kind_name),
                         "the law p(phi) the valve is to follow as i p (e.g. cam.polydyne), with 4th and 5th derivatives"),
        PortSpec::handle("design", std::string(SpringDesign::kind_name), "spring and reduced mass (valvetrain.spring_design)"),
    };
    info_.outputs = {
        PortSpec::handle("law", std::string(CamLaw::kind_name), "the synthesised cam (tappet lift over cam angle)"),
        PortSpec::scalar("max_lift", dim::length, "tappet lift at the nose", "mm"),
        PortSpec::scalar("take_up", dim::length, "tappet lift at the top of the ramps, (P0 / k_d + lash) / i", "mm"),
        PortSpec::scalar("correction", dim::length, "nose lift of the synthesised cam less the law's (positive: higher)", "mm"),
        PortSpec::scalar("min_curvature_radius", dim::length, "smallest radius of curvature of the synthesised contour (flat tappet)",
                         "mm"),
    };
  }
  const NodeInfo& info() const override { return info_; }

  void evaluate(const ParamSet& p, const InputSet& in, OutputSet& out, EvalContext&) const override {
    const auto law = in.handle<CamLaw>("law");
    const auto design = in.handle<SpringDesign>("design");
    double d4 = 0.0, d5 = 0.0;
    const double probe = 0.5 * (law->event_begin() + law->event_end());
    if (!law->higher_derivatives(probe, d4, d5))
      throw NodeError("law", "the valve law gives no 4th and 5th derivatives: synthesis needs them in closed form (cam.polydyne has them)");
    const double ramp = p.number("ramp_angle");
    if (law->event_end() - law->event_begin() + 2.0 * ramp >= 2.0 * pi)
      throw NodeError("ramp_angle", "the valve law's event plus two ramps exceeds a revolution");
    const double rocker = p.number("rocker_ratio");
    if (std::abs(design->masses->rocker_ratio() - rocker) > 1e-9 * rocker) {
      std::ostringstream msg;
      msg << "rocker_ratio " << rocker << " and the design's arms l_v / l_p = " << design->masses->rocker_ratio()
          << " disagree: make them the same rocker";
      throw NodeError("rocker_ratio", msg.str());
    }
    SynthesizedCam::Drive drive{design->reduced_mass, p.number("drive_stiffness"), design->spring->preload(),
                                design->spring->stiffness(0.0), p.number("design_rpm") / 2.0, rocker, p.number("lash")};
    auto cam = std::make_shared<const SynthesizedCam>(law, drive, ramp);
    // The synthesised contour must stay convex enough for the flat tappet: r0 + h + h'' > 0.
    const std::vector<double> knots = cam->knots();
    long evaluations = 0;
    const auto rho = numerics::minimize_piecewise(
        [&](double phi) {
          const LiftDerivatives h = cam->at(phi);
          return cam->base_radius() + h.lift + h.acceleration;
        },
        knots, 200, evaluations);
    if (!(rho.value > 0.0)) {
      std::ostringstream msg;
      msg << "the synthesised cam is undercut: its smallest radius of curvature is " << rho.value * 1e3 << " mm at "
          << rho.x * 180.0 / pi << " deg (base_radius " << cam->base_radius() * 1e3
          << " mm of the law): raise the law's base_radius, or the drive_stiffness";
      throw NodeError("drive_stiffness", msg.str());
    }
    const double take_up = (drive.preload / drive.stiffness + drive.lash) / drive.rocker;
    out.set_scalar("max_lift", cam->max_lift());
    out.set_scalar("take_up", take_up);
    out.set_scalar("correction", cam->max_lift() - law->max_lift());
    out.set_scalar("min_curvature_radius", rho.value);
    out.set("law", Value::handle(std::move(cam)));
  }

 private:
  NodeInfo info_;
};

}  // namespace

std::shared_ptr<const NodeType> make_polydyne_cam_type() { return std::make_shared<const PolydyneCamType>(); }

}  // namespace mechgraph::valvetrain
