// valvetrain.valve_motion: valve kinematics at one engine speed (methods/valvetrain.md, stage 2),
// with the curves and events at the valve ("Cam curves and events"): lift, velocity, acceleration
// and jerk in time (w_k^k times the derivatives over cam angle), events at a checking valve lift.
#include "node_types.hpp"
#include "valve_motion.hpp"

#include <mechgraph/block.hpp>
#include <mechgraph/domain/cam_curves.hpp>
#include <mechgraph/domain/valve_motion_block.hpp>
#include <mechgraph/domain/cam_law_runs.hpp>
#include <mechgraph/numerics/piecewise.hpp>

#include <cmath>
#include <numbers>

namespace mechgraph::valvetrain {
namespace {

class ValveMotionType final : public NodeType, public BlockEvaluation {
 public:
  ValveMotionType() {
    info_.type = "valvetrain.valve_motion";
    info_.summary = "valve lift, velocity and acceleration over cam angle and time at one engine speed";
    info_.params = {
        ParamSpec::number("rpm", dim::angular_speed, "crank speed; the camshaft turns at half of it (four-stroke)", "rpm")
            .at_least(2.0 * std::numbers::pi / 60.0)       // 1 rpm
            .at_most(1e6 * 2.0 * std::numbers::pi / 60.0)
            .because("1 to 1e6 rpm: a turning engine, far past any")
            .with_example(6000.0 * 2.0 * std::numbers::pi / 60.0),
        ParamSpec::number("rocker_ratio", dim::none, "valve lift / tappet lift, l_v / l_p")
            .with_default(1.0)
            .at_least(0.01)
            .at_most(100.0)
            .because("0.01 to 100: a rocker (an arm 100 times the other)"),
        ParamSpec::number("lash", dim::length, "valve lash (cold clearance), taken up before the valve moves", "mm")
            .with_default(0.0)
            .non_negative()
            .because(">= 0: a gap"),
        ParamSpec::integer("samples", "samples per smooth piece for the extremum searches (each extremum then refined to full precision, by the root of its derivative or Brent; 16 agree with 3200 to 1e-13 on every example cam and 8 already do, mechgraph bench shows it)")
            .with_default(16.0)
            .at_least(8)
            .at_most(1e6)
            .because(">= 8: fewer cannot certify a piece's interpolant; <= 1e6: more only costs time")
            .as_knob(),
        ParamSpec::integer("curve_points", "points of the lift_curve series over the open period, and of the svaj "
                                           "table over it widened by a tenth of its width each side")
            .with_default(361.0)
            .at_least(3)
            .at_most(1e6)
            .because(">= 3: a curve needs its two ends and a point between; <= 1e6: bounded in memory"),
        checking_lift_param("valve"),
        nose_timing_param(),
    };
    info_.inputs = {PortSpec::handle("cam", std::string(CamLaw::kind_name), "the cam's follower lift law")};
    info_.outputs = {
        PortSpec::handle("motion", std::string(ValveMotion::kind_name), "valve lift over cam angle at this speed"),
        PortSpec::scalar("max_lift", dim::length, "maximum valve lift", "mm"),
        PortSpec::scalar("max_velocity", dim::velocity, "maximum |valve velocity|", "m/s"),
        PortSpec::scalar("max_acceleration", dim::acceleration, "maximum valve acceleration", "m/s^2"),
        PortSpec::scalar("min_acceleration", dim::acceleration, "most negative valve acceleration (j_min)", "m/s^2"),
        PortSpec::scalar("open_angle", dim::angle, "cam angle over which the valve is open", "deg").in_frame("cam"),
        PortSpec::series("lift_curve", dim::length, "valve lift over cam angle (axis: rad from the nose)", "mm").in_frame("cam"),
        svaj_port("svaj", "valve lift, velocity, acceleration and jerk in time over cam angle (and crank angle), "
                          "curve_points rows"),
    };
    info_.frames = cam_angle_frames();
    info_.notes = {timing_note()};
    for (PortSpec& port : lift_event_ports("valve")) info_.outputs.push_back(std::move(port));
    info_.work_counters = {"evaluations"};
  }
  const NodeInfo& info() const override { return info_; }

  void evaluate(const ParamSet& p, const InputSet& in, OutputSet& out, EvalContext& ctx) const override {
    const double camshaft_speed = p.number("rpm") / 2.0;  // w_k = w / 2
    long evaluations = 0;
    const int samples = static_cast<int>(p.integer("samples"));
    auto motion = std::make_shared<const CamValveMotion>(in.handle<CamLaw>("cam"), camshaft_speed, p.number("rocker_ratio"),
                                                      p.number("lash"), samples, evaluations);
    const std::vector<double>& knots = motion->knots();
    // The valve's full lift is the cam's declared one through the rocker, less the lash (the
    // CamLaw contract: max_lift() is the law's maximum, checked against dense sampling by the kit).
    const numerics::Extremum lift{0.0, motion->rocker_ratio() * motion->cam().max_lift() - motion->lash()};
    const ValvePeaks peaks = find_valve_peaks(motion->cam(), {motion->open_begin(), motion->open_end()}, motion->rocker_ratio(),
                                              motion->lash(), samples, evaluations);
    const numerics::Extremum velocity = peaks.velocity, acc_max = peaks.max_acceleration, acc_min = peaks.min_acceleration;
    const double w = camshaft_speed;
    if (ctx.wanted("lift_curve")) {  // a few hundred evaluations: only when something reads it
      Series curve;
      curve.axis_dimension = dim::angle;
      const long n = p.integer("curve_points");
      for (long i = 0; i < n; ++i) {
        const double phi = motion->open_begin() + (motion->open_end() - motion->open_begin()) * static_cast<double>(i) / (n - 1);
        curve.axis.push_back(phi);
        curve.values.push_back(motion->at(phi).lift);
      }
      evaluations += n;
      out.set("lift_curve", Value::series(std::move(curve)));
    }
    if (ctx.wanted("svaj")) {
      const auto n = static_cast<int>(p.integer("curve_points"));
      Table t = svaj_table([&](double phi) { return motion->at(phi); }, motion->open_begin(), motion->open_end(), n);
      // Over cam angle to over time: d/dt = w_k d/dphi.
      const char* names[3] = {"velocity", "acceleration", "jerk"};
      const Dimension dims[3] = {dim::velocity, dim::acceleration, dim::length / dim::time.pow(3)};
      const char* units[3] = {"m/s", "m/s^2", "m/s^3"};
      double scale = 1.0;
      for (int k = 0; k < 3; ++k) {
        scale *= w;
        Table::Column& c = t.channels[static_cast<std::size_t>(k + 2)];
        if (c.name != names[k]) throw std::logic_error("svaj_table's channel order changed");
        c.dimension = dims[k];
        c.display_unit = units[k];
        for (double& v : c.values) v *= scale;
      }
      evaluations += n;
      out.set("svaj", Value::table(std::move(t)));
    }
    if (lift_events_wanted(ctx))
      set_lift_events(out, ctx, p, [&](double phi) { return motion->at(phi).lift; }, knots, lift.value, "valve", samples,
                      evaluations);
    ctx.report_work("evaluations", static_cast<double>(evaluations));
    out.set_scalar("max_lift", lift.value);
    out.set_scalar("max_velocity", w * velocity.value);
    out.set_scalar("max_acceleration", w * w * acc_max.value);
    out.set_scalar("min_acceleration", w * w * acc_min.value);
    out.set_scalar("open_angle", motion->open_end() - motion->open_begin());
    out.set("motion", Value::handle(std::move(motion)));
  }

  // Blocks: the motion and its scalars, by the same functions as evaluate() (the curves, the
  // svaj table and the events stay with single evaluations).
  bool block_supported(const BlockRequest& request) const override {
    for (const std::string& output : request.wanted)
      if (output != "motion" && output != "max_lift" && output != "max_velocity" && output != "max_acceleration" &&
          output != "min_acceleration" && output != "open_angle")
        return false;
    for (const std::string& name : request.varied)
      if (name == "samples" || name == "curve_points") return false;
    return true;
  }

  void evaluate_block(const BlockParams& p, const BlockInputs& in, BlockOutputs& out, BlockCases& cases,
                      EvalContext& ctx) const override {
    const auto& cams = in.handle<CamLawBlock>("cam");
    const BlockColumn rpm = p.number("rpm"), rocker = p.number("rocker_ratio"), lash = p.number("lash");
    const int samples = static_cast<int>(p.fixed().integer("samples"));
    auto motions = std::make_shared<ValveMotionBlock>(in.shared_handle<CamLawBlock>("cam"),
                                                      cases.size());
    double* max_lift = out.scalar("max_lift");
    double* max_velocity = out.scalar("max_velocity");
    double* max_acceleration = out.scalar("max_acceleration");
    double* min_acceleration = out.scalar("min_acceleration");
    double* open_angle = out.scalar("open_angle");
    const bool peaks_wanted = max_velocity || max_acceleration || min_acceleration;
    long evaluations = 0;
    ValveSearchScratch scratch;  // the runs and crossings, their storage reused from case to case
    for_each_live_case(cases, [&](std::size_t k) {
      const CamLaw& cam = cams.law(k);
      const double w = rpm[k] / 2.0, i = rocker[k], e = lash[k];  // w_k = w / 2
      const OpenPeriod open = find_open_period(cam, i, e, samples, evaluations, scratch);
      motions->open_begin[k] = open.begin;
      motions->open_end[k] = open.end;
      motions->rocker_ratio[k] = i;
      motions->lash[k] = e;
      motions->camshaft_speed[k] = w;
      if (max_lift) max_lift[k] = i * cam.max_lift() - e;
      if (open_angle) open_angle[k] = open.end - open.begin;
      if (peaks_wanted) {
        const ValvePeaks peaks = find_valve_peaks(cam, open, i, e, samples, evaluations, scratch, max_velocity != nullptr);
        if (max_velocity) max_velocity[k] = w * peaks.velocity.value;
        if (max_acceleration) max_acceleration[k] = w * w * peaks.max_acceleration.value;
        if (min_acceleration) min_acceleration[k] = w * w * peaks.min_acceleration.value;
      }
    });
    ctx.report_work("evaluations", static_cast<double>(evaluations));
    out.set_handle("motion", std::move(motions));
  }

 private:
  NodeInfo info_;
};

}  // namespace

std::shared_ptr<const NodeType> make_valve_motion_type() { return std::make_shared<const ValveMotionType>(); }

}  // namespace mechgraph::valvetrain
