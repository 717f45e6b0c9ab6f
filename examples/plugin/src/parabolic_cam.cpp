// example.parabolic_cam: the constant-acceleration cam law. Rise over beta = action_angle / 2 from
// -beta to 0, return mirrored from 0 to beta. With u = (phi + beta) / beta in [0, 1] on the rise:
//   u <= 1/2:  h = 2 H u^2,          h' = 4 H u / beta,        h'' =  4 H / beta^2
//   u >  1/2:  h = H (1 - 2(1-u)^2), h' = 4 H (1 - u) / beta,  h'' = -4 H / beta^2
// and h''' = 0 inside each piece. The acceleration steps at -beta, -beta/2, beta/2 and beta (the
// law's breakpoints); the velocity is continuous everywhere, so the law is C1.
#include "example_types.hpp"

#include <mechgraph/domain/cam_geometry.hpp>
#include <mechgraph/domain/cam_law.hpp>
#include <mechgraph/errors.hpp>

#include <numbers>

namespace example {
namespace {

using namespace mechgraph;

class ParabolicLaw final : public CamLaw {
 public:
  ParabolicLaw(double lift, double action_angle, double base_radius)
      : lift_(lift), beta_(0.5 * action_angle), base_radius_(base_radius) {}
  double event_begin() const override { return -beta_; }
  double event_end() const override { return beta_; }
  std::vector<double> breakpoints() const override { return {-0.5 * beta_, 0.5 * beta_}; }
  double max_lift() const override { return lift_; }
  double base_radius() const override { return base_radius_; }

  LiftDerivatives evaluate_in_event(double phi) const override {
    // The return is the rise mirrored about the nose: even lift and acceleration, odd velocity.
    const double sign = phi > 0.0 ? -1.0 : 1.0;
    const double u = (sign * phi + beta_) / beta_;
    LiftDerivatives d;
    if (u <= 0.5) {
      d.lift = 2.0 * lift_ * u * u;
      d.velocity = 4.0 * lift_ * u / beta_;
      d.acceleration = 4.0 * lift_ / (beta_ * beta_);
    } else {
      d.lift = lift_ * (1.0 - 2.0 * (1.0 - u) * (1.0 - u));
      d.velocity = 4.0 * lift_ * (1.0 - u) / beta_;
      d.acceleration = -4.0 * lift_ / (beta_ * beta_);
    }
    d.velocity *= sign;
    return d;
  }

 private:
  double lift_, beta_, base_radius_;
};

class ParabolicCam final : public NodeType {
 public:
  ParabolicCam() {
    info_.type = "example.parabolic_cam";
    info_.summary = "constant-acceleration (parabolic) rise and return: the smallest peak acceleration of any C1 law";
    info_.params = {
        ParamSpec::number("max_lift", dim::length, "follower lift at the nose", "mm").positive().with_example(9e-3),
        ParamSpec::number("action_angle", dim::angle, "cam angle of the whole event", "deg")
            .at_least(1.0 * std::numbers::pi / 180.0)
            .below(2.0 * std::numbers::pi)
            .with_example(130.0 * std::numbers::pi / 180.0),
        ParamSpec::number("base_radius", dim::length, "base-circle radius", "mm").positive().with_example(30e-3),
        ParamSpec::integer("samples", "samples per smooth piece for the extremum searches (then refined)")
            .with_default(16)
            .at_least(4)
            .at_most(1e6)
            .as_knob(),
    };
    info_.outputs = {
        PortSpec::handle("law", std::string(CamLaw::kind_name), "the cam law"),
        PortSpec::scalar("max_lift", dim::length, "lift at the nose", "mm"),
        PortSpec::scalar("max_velocity", dim::length / dim::angle, "largest |dh/dphi|", "mm/deg").in_frame("cam"),
        PortSpec::scalar("max_acceleration", dim::length / (dim::angle * dim::angle), "largest d2h/dphi2", "mm/deg^2")
            .in_frame("cam"),
        PortSpec::scalar("min_curvature_radius", dim::length, "smallest radius of curvature of the contour", "mm"),
    };
    // How hosts show its angles (docs/writing-plugins.md, "Presentation"): its rates count cam
    // degrees, so reports and `run` say "mm/deg^2 (cam)".
    AngleFrame cam;
    cam.id = "cam";
    cam.label = "cam angle from the nose";
    cam.unit_tag = "cam";
    cam.zero = "the nose";
    info_.frames = {cam};
    info_.work_counters = {"evaluations"};
  }
  const NodeInfo& info() const override { return info_; }

  void evaluate(const ParamSet& p, const InputSet&, OutputSet& out, EvalContext& ctx) const override {
    const double lift = p.number("max_lift"), action = p.number("action_angle"), r0 = p.number("base_radius");
    const int samples = static_cast<int>(p.integer("samples"));
    auto law = std::make_shared<const ParabolicLaw>(lift, action, r0);
    // The SDK's cam geometry: the same figures and the same undercut refusal as the built-in cams.
    const CamSummary s = summarize(*law, samples);
    ctx.report_work("evaluations", static_cast<double>(s.evaluations));
    refuse_undercut(s, r0, [&](double r) { return std::make_shared<const ParabolicLaw>(lift, action, r); }, samples);
    out.set("law", Value::handle(law));
    out.set_scalar("max_lift", law->max_lift());
    out.set_scalar("max_velocity", s.max_velocity);
    out.set_scalar("max_acceleration", s.max_acceleration);
    out.set_scalar("min_curvature_radius", s.min_curvature_radius);
  }

 private:
  NodeInfo info_;
};

}  // namespace

std::shared_ptr<const NodeType> make_parabolic_cam() { return std::make_shared<const ParabolicCam>(); }

}  // namespace example
