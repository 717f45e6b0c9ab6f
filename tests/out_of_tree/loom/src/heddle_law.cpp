// loom.heddle_law: a heddle lifted by a drum cam, rise and return as 3-4-5 polynomials (C2).
// Rise over beta = action_angle / 2 from -beta to 0, return mirrored from 0 to beta; on the rise,
// with u = (phi + beta) / beta in [0, 1]:
//   h = H (10u^3 - 15u^4 + 6u^5),  h' = 30 H u^2 (1-u)^2 / beta,  h'' = 60 H u (1-u)(1-2u) / beta^2,
//   h''' = 60 H (1 - 6u + 6u^2) / beta^3,
// even lift and acceleration, odd velocity and jerk about the top (phi = 0), where the jerk steps:
// the law's one breakpoint. Its angles count the drum's turn from mid-dwell at the top ("drum").
#include "loom_types.hpp"

#include <mechgraph/domain/cam_geometry.hpp>
#include <mechgraph/domain/cam_law.hpp>
#include <mechgraph/presentation.hpp>

#include <cmath>
#include <numbers>

namespace loom {
namespace {

using namespace mechgraph;
constexpr double pi = std::numbers::pi;

class HeddleLaw final : public CamLaw {
 public:
  HeddleLaw(double lift, double action_angle, double base_radius)
      : lift_(lift), beta_(0.5 * action_angle), base_radius_(base_radius) {}
  double event_begin() const override { return -beta_; }
  double event_end() const override { return beta_; }
  std::vector<double> breakpoints() const override { return {0.0}; }
  double max_lift() const override { return lift_; }
  double base_radius() const override { return base_radius_; }

  LiftDerivatives evaluate_in_event(double phi) const override {
    const double sign = phi > 0.0 ? -1.0 : 1.0;
    const double u = (sign * phi + beta_) / beta_, v = 1.0 - u;
    LiftDerivatives d;
    d.lift = lift_ * u * u * u * (10.0 - 15.0 * u + 6.0 * u * u);
    d.velocity = sign * 30.0 * lift_ * u * u * v * v / beta_;
    d.acceleration = 60.0 * lift_ * u * v * (1.0 - 2.0 * u) / (beta_ * beta_);
    d.jerk = sign * 60.0 * lift_ * (1.0 - 6.0 * u + 6.0 * u * u) / (beta_ * beta_ * beta_);
    return d;
  }

 private:
  double lift_, beta_, base_radius_;
};

// Where the heddle is, a row per station: the kind as a named code, the drum angle, the lift.
enum Station { rise_start = 1, top = 2, return_end = 3 };

class HeddleLawNode final : public NodeType {
 public:
  HeddleLawNode() {
    info_.type = "loom.heddle_law";
    info_.summary = "heddle lift of a loom's drum cam: 3-4-5 polynomial rise and return";
    info_.params = {
        ParamSpec::number("heddle_lift", dim::length, "heddle travel at the top", "mm").positive().with_default(60e-3),
        ParamSpec::number("action_angle", dim::angle, "drum angle of the whole lift", "deg")
            .at_least(1.0 * pi / 180.0)
            .below(2.0 * pi)
            .because("below 360 deg: the lift is one event of one drum turn")
            .with_default(160.0 * pi / 180.0),
        ParamSpec::number("drum_radius", dim::length, "radius of the drum's dwell", "mm").positive().with_default(90e-3),
        ParamSpec::integer("samples", "samples per smooth piece for the peak searches (then refined)")
            .with_default(16)
            .at_least(4)
            .at_most(1e6)
            .as_knob(),
        ParamSpec::integer("curve_points", "rows of the heddle motion table").with_default(121).at_least(8).at_most(1e5),
    };
    AngleFrame drum;
    drum.id = "drum";
    drum.label = "drum angle from the top";
    drum.unit_tag = "drum";
    drum.zero = "the heddle at the top of its lift";
    info_.frames = {drum};

    Presentation motion;
    motion.role = Role::derivative_family;
    motion.figure_title = "Heddle lift, lift rate and lift acceleration";
    motion.with_axis(ChannelDecl::of("drum_angle", dim::angle).in_frame("drum"));
    motion.with(ChannelDecl::of("heddle_lift", dim::length).derivative(0).labelled("heddle lift"));
    motion.with(ChannelDecl::of("lift_rate").derivative(1).in_frame("drum").labelled("lift rate"));
    motion.with(ChannelDecl::of("lift_accel").derivative(2).in_frame("drum").labelled("lift acceleration"));

    Presentation stations;
    stations.role = Role::events;
    stations.with_axis(ChannelDecl::of("station", dim::none));
    stations.with(ChannelDecl::of("kind").with_codes({{rise_start, "rise_start", "the heddle leaves the bottom dwell"},
                                                      {top, "top", "the heddle at the top"},
                                                      {return_end, "return_end", "the heddle back on the bottom dwell"}}));
    stations.with(ChannelDecl::of("angle", dim::angle).in_frame("drum").labelled("drum angle"));
    stations.with(ChannelDecl::of("lift", dim::length).labelled("heddle lift"));

    info_.outputs = {
        PortSpec::handle("law", std::string(CamLaw::kind_name), "the heddle's lift law"),
        PortSpec::scalar("max_lift", dim::length, "heddle travel at the top", "mm"),
        PortSpec::scalar("max_velocity", dim::length / dim::angle, "largest |dh/dphi|", "mm/deg").in_frame("drum"),
        PortSpec::scalar("max_acceleration", dim::length / (dim::angle * dim::angle), "largest d2h/dphi2", "mm/deg^2")
            .in_frame("drum"),
        PortSpec::scalar("rise_begins", dim::angle, "drum angle where the rise begins", "deg").in_frame("drum"),
        PortSpec::table("heddle_motion", "heddle lift and its derivatives over drum angle").presented(motion),
        PortSpec::table("stations", "where the heddle starts, tops and ends, a row per station").presented(stations),
    };
    info_.work_counters = {"evaluations"};
  }
  const NodeInfo& info() const override { return info_; }

  void evaluate(const ParamSet& p, const InputSet&, OutputSet& out, EvalContext& ctx) const override {
    const double lift = p.number("heddle_lift"), action = p.number("action_angle"), r0 = p.number("drum_radius");
    auto law = std::make_shared<const HeddleLaw>(lift, action, r0);
    const CamSummary s = summarize(*law, static_cast<int>(p.integer("samples")));
    ctx.report_work("evaluations", static_cast<double>(s.evaluations));
    out.set("law", Value::handle(law));
    out.set_scalar("max_lift", lift);
    out.set_scalar("max_velocity", s.max_velocity);
    out.set_scalar("max_acceleration", s.max_acceleration);
    out.set_scalar("rise_begins", law->event_begin());
    if (ctx.wanted("heddle_motion")) {
      const auto n = static_cast<std::size_t>(p.integer("curve_points"));
      Table t;
      t.axis = {"drum_angle", dim::angle, {}, "deg"};
      t.add_channel("heddle_lift", dim::length, "mm");
      t.add_channel("lift_rate", dim::length / dim::angle, "mm/deg");
      t.add_channel("lift_accel", dim::length / (dim::angle * dim::angle), "mm/deg^2");
      for (std::size_t i = 0; i < n; ++i) {
        const double phi = -pi + 2.0 * pi * static_cast<double>(i) / static_cast<double>(n - 1);
        const LiftDerivatives d = law->at(phi);
        t.axis.values.push_back(phi);
        t.channels[0].values.push_back(d.lift);
        t.channels[1].values.push_back(d.velocity);
        t.channels[2].values.push_back(d.acceleration);
      }
      out.set("heddle_motion", Value::table(std::move(t)));
    }
    if (ctx.wanted("stations")) {
      Table e;
      e.axis = {"station", dim::none, {1.0, 2.0, 3.0}, ""};
      e.add_channel("kind", dim::none).values = {rise_start, top, return_end};
      e.add_channel("angle", dim::angle, "deg").values = {law->event_begin(), 0.0, law->event_end()};
      e.add_channel("lift", dim::length, "mm").values = {0.0, lift, 0.0};
      out.set("stations", Value::table(std::move(e)));
    }
  }

 private:
  NodeInfo info_;
};

}  // namespace

std::shared_ptr<const NodeType> make_heddle_law() { return std::make_shared<const HeddleLawNode>(); }

}  // namespace loom
