// valvetrain.time_area: the valve's time-area and angle-area (methods/valvetrain.md, stage 3).
//   A = integral f_v(h_v(phi)) dphi / w_k over the open period.
// `exact` takes the law's closed-form integrals of h and h^2 where it gives them and the seat is
// conical (the area is then a quadratic in the lift), else integrates piece by piece between the
// law's breakpoints (and the flow-area stage changes) with adaptive Gauss-Kronrod; `rectangle` is
// the source's sum (dphi/w_k) sum f_v,i on a grid of `step`, kept so its error can be shown.
#include "flow_area.hpp"
#include "node_types.hpp"
#include "valve_motion.hpp"

#include <mechgraph/block.hpp>
#include <mechgraph/domain/valve_motion_block.hpp>

#include <mechgraph/domain/cam_curves.hpp>
#include <mechgraph/numerics/piecewise.hpp>
#include <mechgraph/printf_number.hpp>

#include <algorithm>
#include <optional>
#include <string>
#include <cmath>
#include <numbers>
#include <sstream>

namespace mechgraph::valvetrain {
namespace {

constexpr double max_rectangles = 1e8;  // a rectangle sum finer than this is a mistake, not a method

// The seat of the parameters (the three-stage passage checked for its dimensions).
SeatGeometry seat_of(const ParamSet& p) {
  SeatGeometry seat{p.number("seat_diameter"), p.number("seat_angle")};
  if (p.text("flow_area") == "three_stage") {
    for (const char* name : {"seat_width", "port_diameter"})
      if (!p.has(name)) throw NodeError(name, std::string("flow_area: three_stage needs ") + name);
    seat.three_stage = true;
    seat.seat_width = p.number("seat_width");
    seat.port_diameter = p.number("port_diameter");
    seat.stem_diameter = p.number("stem_diameter");
  }
  return seat;
}

// Closed form (the law's integrals I1 of h and I2 of h^2 over the open period of width L): with
// the valve lift x = i h - lash and f = k1 x + k2 x^2, int f = k1 int x + k2 int x^2,
// int x = i I1 - lash L, int x^2 = i^2 I2 - 2 i lash I1 + lash^2 L.
double closed_form_angle_area(double k1, double k2, double i, double lash, double L, double I1, double I2) {
  return k1 * (i * I1 - lash * L) + k2 * (i * i * I2 - 2.0 * i * lash * I1 + lash * lash * L);
}

// The exact angle-area in closed form, where the seat is conical and the law gives its integrals
// over the open period [ob, oe] (closed_form_angle_area); false otherwise (integrated_angle_area).
bool closed_form_area_of(const CamLaw& cam, const FlowArea& area, double rocker_ratio, double lash, double ob, double oe,
                         double& angle_area, long& evaluations) {
  double k1 = 0.0, k2 = 0.0, I1 = 0.0, I2 = 0.0;
  if (!area.quadratic(k1, k2) || !cam.lift_integrals(ob, oe, I1, I2)) return false;
  evaluations += 2;  // the law's two primitives, at both ends
  angle_area = closed_form_angle_area(k1, k2, rocker_ratio, lash, oe - ob, I1, I2);
  return true;
}

bool exact_method(const ParamSet& p) { return p.text("method") == "exact"; }

// The angle-area of `motion` through `area` by quadrature: `exact`, adaptive Gauss-Kronrod between
// the breakpoints, else the source's rectangle sum. Where the closed form applies
// (closed_form_area_of) the callers take it first.
double integrated_angle_area(const ValveMotion& motion, const FlowArea& area, const ParamSet& p, bool exact, long& evaluations) {
  auto f = [&](double phi) { return area(motion.at(phi).lift); };
  const double ob = motion.open_begin(), oe = motion.open_end();
  if (exact) {
    // Split also where the flow-area formula changes stage, so every piece is smooth. The top of
    // the lift joins the search knots: a stage lift just below it is crossed twice close together,
    // and the top keeps those two crossings in different pieces.
    std::vector<double> knots = motion.knots();
    if (!area.stage_lifts().empty()) {
      // Every crossing of every stage lift, from one certified interpolation of the lift.
      numerics::SmoothPieces lift([&](double x, double* v, double*) { v[0] = motion.at(x).lift; }, 1, knots, 16);
      for (double stage_lift : area.stage_lifts())
        for (double x : lift.crossings(0, stage_lift)) knots.push_back(x);
      evaluations += lift.work().evaluations;
    }
    std::sort(knots.begin(), knots.end());
    return numerics::integrate_piecewise(f, knots, p.number("tolerance"), evaluations);
  }
  const double step = p.number("step");
  const double span = oe - ob;
  if (step > span / 2.0) throw NodeError("step", "the rectangle step must be at most half the open period");
  // The source's sum over phi_i = begin + i step, counted by index so a tiny step cannot stall.
  const double count = std::floor(span / step);
  if (count > max_rectangles) {
    std::ostringstream msg;
    msg << "a step of " << step * 180.0 / std::numbers::pi << " deg needs " << count << " rectangles over the "
        << span * 180.0 / std::numbers::pi << " deg open period; at most " << max_rectangles
        << " are allowed (use method: exact for a tight answer)";
    throw NodeError("step", msg.str());
  }
  double sum = 0.0;
  const long n = static_cast<long>(count);
  for (long i = 0; i <= n; ++i) sum += f(ob + static_cast<double>(i) * step);
  evaluations += n + 1;
  return sum * step;
}

// The flow area grows as the square of the lift: a lift too large for that square (far beyond
// any valve, but a law can be given one) overflows; refused, naming the input.
void require_finite_area(double angle_area, double camshaft_speed, const CamLaw& cam, double rocker_ratio) {
  if (!std::isfinite(angle_area) || !std::isfinite(angle_area / camshaft_speed))
    throw NodeError("valve", "the time-area of this valve motion (cam lift " + printf_g(cam.max_lift()) +
                                 " m, rocker ratio " + printf_g(rocker_ratio) + ") is beyond the range of a double");
}

class TimeAreaType final : public NodeType, public BlockEvaluation {
 public:
  TimeAreaType() {
    info_.type = "valvetrain.time_area";
    info_.summary = "time-area, angle-area and mean flow area of the valve over its open period";
    info_.params = {
        ParamSpec::number("seat_diameter", dim::length, "inner seat diameter d0", "mm").positive().because("> 0: a diameter").with_example(35e-3),
        ParamSpec::number("seat_angle", dim::angle, "seat cone angle a (45 deg usual)", "deg")
            .with_default(std::numbers::pi / 4.0)
            .positive()
            .below(std::numbers::pi / 2.0)
            .because("> 0 and < 90 deg: a conical seat (0 and 90 would be a flat ring or a tube)"),
        ParamSpec::choice("flow_area", {"conical", "three_stage"},
                          "conical: the source's seat-cone formula; three_stage: seat cone, then seat-to-port "
                          "transition, then the port (needs seat_width, port_diameter, stem_diameter)")
            .with_default("conical"),
        ParamSpec::number("seat_width", dim::length, "seat width w (three_stage)", "mm").optional().positive().because("> 0: a width"),
        ParamSpec::number("port_diameter", dim::length, "port diameter Dp (three_stage)", "mm").optional().positive().because("> 0: a diameter"),
        ParamSpec::number("stem_diameter", dim::length, "valve stem diameter Ds (three_stage)", "mm")
            .with_default(0.0)
            .non_negative()
            .because(">= 0: a diameter (0: no stem in the port)"),
        ParamSpec::choice("method", {"exact", "rectangle"},
                          "exact: adaptive Gauss-Kronrod between breakpoints; rectangle: the source's sum with `step`")
            .with_default("exact")
            .as_knob(),
        ParamSpec::number("step", dim::angle, "cam-angle step of the rectangle sum", "deg")
            .with_default(std::numbers::pi / 180.0)
            .positive()
            .because("> 0: a step")
            .as_knob(),
        ParamSpec::number("tolerance", dim::none,
                          "relative tolerance of the exact quadrature; below 1e-13 round-off, not the rule, "
                          "sets the error and the subdivision cannot stop (1e-14 took 2e6 evaluations for the "
                          "value 1e-13 gives in 75), so it is refused")
            .with_default(1e-10)
            .at_least(1e-13)
            .because(">= 1e-13: tighter than a double's rounding of the integral cannot be met")
            .as_knob(),
    };
    info_.inputs = {PortSpec::handle("valve", std::string(ValveMotion::kind_name), "the valve's motion at one speed")};
    info_.outputs = {
        PortSpec::scalar("time_area", dim::area * dim::time, "integral of the flow area over time", "mm^2*s"),
        PortSpec::scalar("angle_area", dim::area * dim::angle, "integral of the flow area over cam angle (rpm-free)",
                         "mm^2*deg")
            .in_frame("cam"),
        PortSpec::scalar("mean_flow_area", dim::area, "angle_area / open cam angle", "mm^2"),
        PortSpec::scalar("open_duration", dim::time, "time the valve is open", "ms"),
    };
    info_.work_counters = {"evaluations"};
    info_.frames = cam_angle_frames(false);
  }
  const NodeInfo& info() const override { return info_; }

  void evaluate(const ParamSet& p, const InputSet& in, OutputSet& out, EvalContext& ctx) const override {
    const auto motion = in.handle<ValveMotion>("valve");
    const FlowArea area(seat_of(p));
    long evaluations = 0;
    const bool exact = exact_method(p);
    double angle_area = 0.0;
    if (!exact || !closed_form_area_of(motion->cam(), area, motion->rocker_ratio(), motion->lash(), motion->open_begin(),
                                       motion->open_end(), angle_area, evaluations))
      angle_area = integrated_angle_area(*motion, area, p, exact, evaluations);
    ctx.report_work("evaluations", static_cast<double>(evaluations));
    const double open_angle = motion->open_end() - motion->open_begin();
    require_finite_area(angle_area, motion->camshaft_speed(), motion->cam(), motion->rocker_ratio());
    out.set_scalar("angle_area", angle_area);
    out.set_scalar("time_area", angle_area / motion->camshaft_speed());
    out.set_scalar("mean_flow_area", angle_area / open_angle);
    out.set_scalar("open_duration", open_angle / motion->camshaft_speed());
  }

  // Blocks: every method and seat (only numbers vary from case to case), each case as evaluate()
  // takes it: the closed form from the block's columns and the case's law, else
  // integrated_angle_area on the case's ValveMotion made from them. The method (a choice, the same
  // for every case) is read once.
  bool block_supported(const BlockRequest&) const override { return true; }

  void evaluate_block(const BlockParams& p, const BlockInputs& in, BlockOutputs& out, BlockCases& cases,
                      EvalContext& ctx) const override {
    const auto& motions = in.handle<ValveMotionBlock>("valve");
    double* time_area = out.scalar("time_area");
    double* angle_area_out = out.scalar("angle_area");
    double* mean_flow_area = out.scalar("mean_flow_area");
    double* open_duration = out.scalar("open_duration");
    long evaluations = 0;
    // The seat is read once for the block when no case changes it (a refusal stays per case).
    bool seat_varies = false;
    for (const char* name : {"seat_diameter", "seat_angle", "seat_width", "port_diameter", "stem_diameter"})
      seat_varies = seat_varies || p.varies(name);
    std::optional<FlowArea> block_area;
    const bool exact = exact_method(p.fixed());
    for_each_live_case(cases, [&](std::size_t k) {
      const std::size_t r = motions.row(k);
      const double w = motions.camshaft_speed[r], i = motions.rocker_ratio[r], lash = motions.lash[r];
      const double ob = motions.open_begin[r], oe = motions.open_end[r];
      const ParamSet& params = p.of_case(k);
      std::optional<FlowArea> own_area;
      if (!seat_varies && !block_area) block_area.emplace(seat_of(params));
      const FlowArea& area = seat_varies ? own_area.emplace(seat_of(params)) : *block_area;
      const CamLaw& cam = motions.cam(k);
      double angle_area = 0.0;
      if (!exact || !closed_form_area_of(cam, area, i, lash, ob, oe, angle_area, evaluations)) {
        const CamValveMotion motion(motions.shared_cam(k), w, i, lash, OpenPeriod{ob, oe});
        angle_area = integrated_angle_area(motion, area, params, exact, evaluations);
      }
      require_finite_area(angle_area, w, cam, i);
      const double open_angle = oe - ob;
      if (angle_area_out) angle_area_out[k] = angle_area;
      if (time_area) time_area[k] = angle_area / w;
      if (mean_flow_area) mean_flow_area[k] = angle_area / open_angle;
      if (open_duration) open_duration[k] = open_angle / w;
    });
    ctx.report_work("evaluations", static_cast<double>(evaluations));
  }

 private:
  NodeInfo info_;
};

}  // namespace

std::shared_ptr<const NodeType> make_time_area_type() { return std::make_shared<const TimeAreaType>(); }

}  // namespace mechgraph::valvetrain
