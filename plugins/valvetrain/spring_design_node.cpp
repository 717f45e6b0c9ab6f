// valvetrain.spring_design: the valve spring's line against the inertia force, the spring sized by
// a spring model, and the reduced mass iterated to a fixed point (docs/methods/valvetrain.md,
// stage 4a-e).
//
// With a(h) the valve's acceleration in time where the lift is h, the spring must hold
//   F(h) = P0 + c h  >=  K M_red |a(h)|   over the negative-acceleration phase (a < 0).
// rule source:      P_max = K M_red |a_min|, P0 given (or a ratio of P_max), c = (P_max - P0) / h_max;
//                   the line is not checked away from the top: envelope_margin reports it.
// rule free_length: the line through the free-length point (-f0, 0) lowest above the requirement,
//                   c = K M_red max |a(h)| / (f0 + h), P0 = c f0, P_max = c (f0 + h_max).
// In both, P0 >= min_seat_force. M_red = M_ws + m_s/3 depends on the spring: repeat to a fixed point.
#include "node_types.hpp"
#include "train_masses.hpp"

#include <mechgraph/domain/cam_curves.hpp>
#include <mechgraph/domain/valve_motion.hpp>
#include <mechgraph/numerics/piecewise.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace mechgraph::valvetrain {
namespace {

// The force curve drawn over valve lift: the spring line straight from the free-length mark, the
// rule's requirement where it asks anything, the inertia force only in the numbers.
Presentation force_over_lift() {
  Presentation p = over_cam_angle("cam_angle", Role::curve_over_channel);
  p.x_channel = "valve_lift";
  p.figure_title = "Spring force over valve lift";
  p.caption = "lift measured from the installed height; free length and solid height at the lifts where the spring "
              "would reach them";
  p.with(ChannelDecl::of("crank_angle", dim::angle).in_frame("crank").flag(channel_flag::alt_axis));
  // The working range is what the valve travels; the free-length point lies far below it and is
  // named at the plot's edge, the spring line cut there.
  p.with(ChannelDecl::of("valve_lift", dim::length).flag(channel_flag::range_of_rows));
  p.with(ChannelDecl::of("spring_force", dim::force).line_from("free length"));
  p.with(ChannelDecl::of("inertia_force", dim::force).flag(channel_flag::not_drawn));
  p.with(ChannelDecl::of("required_force", dim::force).flag(channel_flag::positive_only));
  return p;
}

constexpr int max_iterations = 200;

std::string fmt(double v) {
  std::ostringstream s;
  s.precision(6);
  s << v;
  return s.str();
}

class SpringDesignType final : public NodeType {
 public:
  SpringDesignType() {
    info_.type = "valvetrain.spring_design";
    info_.version = 2;  // 2: force_curve
    info_.summary = "valve spring line against K times the inertia force, sized by a spring model; reduced mass to a fixed point";
    info_.params = {
        ParamSpec::number("safety_factor", dim::none, "K: spring force over inertia force (1.3-2.0 usual)")
            .with_default(1.5)
            .at_least(1.0)
            .at_most(10.0)
            .because("1 to 10: at least the inertia force (1), the usual 1.3 to 2 well inside"),
        ParamSpec::number("min_seat_force", dim::force, "least spring force on the closed valve (P0 >= this)", "N")
            .with_default(0.0)
            .non_negative()
            .at_most(1e6)
            .because(">= 0: a force; <= 1 MN: far past any valve spring"),
        ParamSpec::choice("rule", {"free_length", "source"},
                          "free_length: the line from the free-length point tangent to K times the inertia force "
                          "(always holds the valve); source: P_max = K M_red |a_min| at full lift, preload given")
            .with_default("free_length"),
        ParamSpec::number("preload", dim::force, "P0 (rule source; or preload_ratio)", "N").optional().positive().at_most(1e6).because("> 0: a spring that holds the valve; <= 1 MN: far past any valve spring"),
        ParamSpec::number("preload_ratio", dim::none, "P0 / P_max (rule source; or preload)").optional().positive().below(1.0).because("> 0 and < 1: the preload is below P_max, or the rate would be zero or less"),
        ParamSpec::number("preload_deflection", dim::length,
                          "f0, spring deflection from free length to installed (rule free_length); default 2 h_max", "mm")
            .optional()
            .positive()
            .at_most(1.0)
            .because("> 0: a deflection; <= 1 m: far past any valve spring"),
        ParamSpec::number("tolerance", dim::none, "relative tolerance of the reduced-mass fixed point")
            .with_default(1e-12)
            .at_least(1e-15)
            .at_most(1e-2)
            .because("1e-15 to 1e-2: a double's rounding to loose")
            .as_knob(),
        ParamSpec::integer("samples", "samples per smooth piece for the searches over the negative-acceleration phase")
            .with_default(100.0)
            .at_least(8)
            .at_most(1e6)
            .because(">= 8: fewer cannot certify a piece's interpolant; <= 1e6: more only costs time")
            .as_knob(),
        ParamSpec::integer("curve_points", "points of the force_curve table, evenly spaced over the open period")
            .with_default(361.0)
            .at_least(3)
            .at_most(1e6)
            .because(">= 3: a curve needs its two ends and a point between; <= 1e6: bounded in memory"),
    };
    info_.inputs = {
        PortSpec::handle("valve", std::string(ValveMotion::kind_name), "the valve's motion at the design speed"),
        PortSpec::handle("spring", std::string(SpringModel::kind_name), "the spring model to size (spring.*)"),
        PortSpec::handle("masses", std::string(TrainMasses::kind_name), "the moving parts (valvetrain.masses)"),
    };
    info_.outputs = {
        PortSpec::handle("spring", std::string(Spring::kind_name), "the sized spring with its line"),
        PortSpec::handle("design", std::string(SpringDesign::kind_name), "spring, masses and reduced mass, for resonance and dynamics"),
        PortSpec::scalar("max_force", dim::force, "P_max, spring force at full lift", "N"),
        PortSpec::scalar("preload", dim::force, "P0, spring force on the closed valve", "N"),
        PortSpec::scalar("stiffness", dim::stiffness, "c_s, spring rate", "N/mm"),
        PortSpec::scalar("preload_deflection", dim::length, "f0 = P0 / c_s", "mm"),
        PortSpec::scalar("wire_diameter", dim::length, "d of the (outer) coil", "mm"),
        PortSpec::scalar("coil_diameter", dim::length, "mean diameter D of the (outer) coil", "mm"),
        PortSpec::scalar("active_coils", dim::none, "active coils i of the (outer) coil"),
        PortSpec::scalar("free_length", dim::length, "free length of the (outer) coil", "mm"),
        PortSpec::scalar("solid_length", dim::length, "solid length of the (outer) coil", "mm"),
        PortSpec::scalar("spring_mass", dim::mass, "m_s, whole spring", "g"),
        PortSpec::scalar("reduced_mass", dim::mass, "M_red = M_ws + m_s/3, valve side", "g"),
        PortSpec::scalar("surge_frequency", dim::frequency, "lowest surge frequency of the spring", "Hz"),
        PortSpec::scalar("max_stress", dim::stress, "highest corrected shear stress at full lift", "MPa"),
        PortSpec::scalar("iterations", dim::none, "fixed-point iterations for M_red"),
        PortSpec::scalar("envelope_margin", dim::force,
                         "least P0 + c h - K M_red |a(h)| over the negative-acceleration phase (negative: the line "
                         "dips below the requirement)", "N"),
        PortSpec::scalar("min_safety_factor", dim::none, "least (P0 + c h) / (M_red |a(h)|) over the negative phase"),
        PortSpec::table("force_curve", "over cam angle through the open period: valve lift, the spring line P0 + c h, the "
                                       "inertia force M_red a, the requirement K M_red |a| where the valve decelerates, and "
                                       "the contact force P0 + c h + M_red a the drive carries (valve side; for cam.contour); "
                                       "marked on the lift: free length, installed, full lift and solid")
            .presented(force_over_lift()),
    };
    info_.work_counters = {"iterations", "evaluations"};
    info_.frames = cam_angle_frames(false);
  }
  const NodeInfo& info() const override { return info_; }

  void evaluate(const ParamSet& p, const InputSet& in, OutputSet& out, EvalContext& ctx) const override {
    const auto motion = in.handle<ValveMotion>("valve");
    const auto model = in.handle<SpringModel>("spring");
    const auto masses = in.handle<TrainMasses>("masses");
    const double rocker = motion->rocker_ratio();
    if (std::abs(masses->rocker_ratio() - rocker) > 1e-9 * rocker)
      throw NodeError("masses", "the valve motion's rocker ratio " + fmt(rocker) + " and the masses' arms l_v / l_p = " +
                                    fmt(masses->arm_valve * 1e3) + " mm / " + fmt(masses->arm_pushrod * 1e3) +
                                    " mm = " + fmt(masses->rocker_ratio()) + " disagree: make them the same rocker");
    const double K = p.number("safety_factor");
    const double min_seat = p.number("min_seat_force");
    const double w = motion->camshaft_speed();
    const double h_max = rocker * motion->cam().max_lift() - motion->lash();  // full valve lift
    const int samples = static_cast<int>(p.integer("samples"));
    long evaluations = 0;
    const bool source_rule = p.text("rule") == "source";

    // |a| where the valve decelerates, 0 elsewhere (the requirement is K M |a| there). The searches
    // split where the acceleration changes sign, so that each piece is smooth (the certified
    // searches need smooth pieces: max(0, .) has a kink there).
    std::vector<double> knots = motion->knots();
    for (double x : numerics::all_sign_changes([&](double phi) { return motion->at(phi).acceleration; }, knots, samples,
                                               evaluations))
      knots.push_back(x);
    std::sort(knots.begin(), knots.end());
    knots.erase(std::unique(knots.begin(), knots.end()), knots.end());
    auto deceleration = [&](double phi) { return std::max(0.0, -w * w * motion->at(phi).acceleration); };

    // The line per unit of K M_red: both rules scale linearly with the mass, so the searches run once.
    double f0 = 0.0, rate_per_mass = 0.0, preload_given = 0.0, preload_ratio = 0.0;
    if (source_rule) {
      if (p.has("preload_deflection"))
        throw NodeError("preload_deflection", "preload_deflection belongs to rule free_length; rule source takes preload or preload_ratio");
      if (p.has("preload") == p.has("preload_ratio"))
        throw NodeError("preload", "rule source needs exactly one of preload (P0) and preload_ratio (P0 / P_max)");
      const auto top = numerics::maximize_piecewise(deceleration, knots, samples, evaluations);
      rate_per_mass = top.value;  // |a_min|: P_max = K M |a_min|
      if (p.has("preload")) preload_given = p.number("preload");
      else preload_ratio = p.number("preload_ratio");
    } else {
      for (const char* name : {"preload", "preload_ratio"})
        if (p.has(name))
          throw NodeError(name, std::string(name) + " belongs to rule source; rule free_length sets the preload from preload_deflection");
      f0 = p.has("preload_deflection") ? p.number("preload_deflection") : 2.0 * h_max;
      const auto top = numerics::maximize_piecewise(
          [&](double phi) { return deceleration(phi) / (f0 + motion->at(phi).lift); }, knots, samples, evaluations);
      rate_per_mass = top.value;  // c = K M max |a| / (f0 + h)
    }
    if (!(rate_per_mass > 0.0)) throw NodeError("valve", "the valve never decelerates: there is nothing for a spring to hold");

    auto line_for = [&](double M) {
      SpringLine line;
      line.stroke = h_max;
      if (source_rule) {
        const double p_max = K * M * rate_per_mass;
        line.preload = p.has("preload") ? preload_given : preload_ratio * p_max;
        if (line.preload < min_seat)
          throw NodeError(p.has("preload") ? "preload" : "preload_ratio",
                          "the preload " + fmt(line.preload) + " N is below min_seat_force " + fmt(min_seat) + " N");
        if (!(line.preload < p_max))
          throw NodeError("preload", "the preload " + fmt(line.preload) + " N is not below P_max = K M_red |a_min| = " +
                                         fmt(p_max) + " N: the spring would need a rate of zero or less");
        line.rate = (p_max - line.preload) / h_max;
      } else {
        line.rate = std::max(K * M * rate_per_mass, min_seat / f0);
        line.preload = line.rate * f0;
      }
      return line;
    };

    const double m_ws = masses->without_spring();
    const double tolerance = p.number("tolerance");
    double M = m_ws;
    std::shared_ptr<const Spring> spring;
    int iterations = 0;
    // A model's refusal names the model's own parameter; the message says so, the location is the input.
    auto size = [&](const SpringLine& l) {
      try {
        return model->size(l);
      } catch (const NodeError& e) {
        std::string context;
        if (iterations > 1)
          context = " (at iteration " + std::to_string(iterations) + " of the reduced mass, M_red = " + fmt(M * 1e3) +
                    " g from " + fmt(masses->without_spring() * 1e3) + " g without the spring: a spring this heavy for "
                    "its load may have no fixed point)";
        throw NodeError("spring", std::string(model->type_name()) + ", parameter '" + e.parameter() + "': " + e.what() + context);
      }
    };

    // M_red = M_ws + m_s(M_red)/3 by direct iteration. The spring's moving mass grows about as fast as
    // the mass it holds, so a spring that is heavy for its load has no fixed point: refused.
    for (;;) {
      if (++iterations > max_iterations)
        throw NodeError("tolerance", "the reduced mass did not settle to " + fmt(tolerance) + " in " +
                                         std::to_string(max_iterations) + " iterations (last " + fmt(M * 1e3) + " g)");
      spring = size(line_for(M));
      const double next = m_ws + spring->effective_mass();
      if (!(next < 1e3 * m_ws))
        throw NodeError("spring", "the reduced mass runs away (" + fmt(next * 1e3) + " g from " + fmt(m_ws * 1e3) +
                                      " g without the spring): the spring's own moving mass outgrows the load it holds; "
                                      "lower the safety factor or the speed, or use a lighter spring model");
      const bool settled = std::abs(next - M) <= tolerance * next;
      M = next;
      if (settled) break;
    }
    const SpringLine line = line_for(M);
    spring = size(line);
    if (spring->stress(h_max) > spring->allowable_stress() * (1.0 + 1e-9))
      throw NodeError("spring", std::string(model->type_name()) + " gave a spring stressed to " +
                                    fmt(spring->stress(h_max) * 1e-6) + " MPa at full lift, over its allowable " +
                                    fmt(spring->allowable_stress() * 1e-6) + " MPa");

    // How the line stands against the requirement over the whole negative phase.
    auto margin = [&](double phi) {
      return line.preload + line.rate * motion->at(phi).lift - K * M * deceleration(phi);
    };
    // The least safety force / (M |a|) is the inverse of the most the deceleration asks per unit of
    // spring force, M |a| / force: smooth, and zero where the valve accelerates (no requirement).
    auto demand = [&](double phi) {
      const double force = line.preload + line.rate * motion->at(phi).lift;
      return M * deceleration(phi) / force;
    };
    const auto least_margin = numerics::minimize_piecewise(margin, knots, samples, evaluations);
    const auto most_demand = numerics::maximize_piecewise(demand, knots, samples, evaluations);
    const numerics::Extremum least_safety{most_demand.x, most_demand.value > 0.0 ? 1.0 / most_demand.value : 1e300};

    ctx.report_work("iterations", iterations);
    ctx.report_work("evaluations", static_cast<double>(evaluations));
    const CoilGeometry outer = spring->coils().front();
    out.set_scalar("max_force", line.max_force());
    out.set_scalar("preload", line.preload);
    out.set_scalar("stiffness", line.rate);
    out.set_scalar("preload_deflection", line.preload / line.rate);
    out.set_scalar("wire_diameter", outer.wire_diameter);
    out.set_scalar("coil_diameter", outer.mean_diameter);
    out.set_scalar("active_coils", outer.active_coils);
    out.set_scalar("free_length", outer.free_length);
    out.set_scalar("solid_length", outer.solid_length);
    out.set_scalar("spring_mass", spring->mass());
    out.set_scalar("reduced_mass", M);
    out.set_scalar("surge_frequency", spring->surge_frequency());
    out.set_scalar("max_stress", spring->stress(h_max));
    out.set_scalar("iterations", iterations);
    // The free-length rule makes the line touch the requirement: its least margin is zero up to
    // the rounding of the forces it is the difference of, reported as the zero it is (a
    // "-1e-13 N" would read as a violated requirement).
    const double rounding = 64.0 * std::numeric_limits<double>::epsilon() * line.max_force();
    out.set_scalar("envelope_margin", std::abs(least_margin.value) <= rounding ? 0.0 : least_margin.value);
    out.set_scalar("min_safety_factor", least_safety.value);
    auto design = std::make_shared<SpringDesign>();
    design->spring = spring;
    design->masses = masses;
    design->reduced_mass = M;
    design->safety_factor = K;
    if (ctx.wanted("force_curve")) {
      const auto n = static_cast<std::size_t>(p.integer("curve_points"));
      Table t;
      t.axis = {"cam_angle", dim::angle, std::vector<double>(n), "deg"};
      t.add_channel("crank_angle", dim::angle, "deg");
      t.add_channel("valve_lift", dim::length, "mm");
      for (const char* name : {"spring_force", "inertia_force", "required_force", "contact_force"}) t.add_channel(name, dim::force, "N");
      for (auto& c : t.channels) c.values.resize(n);
      const double from = motion->open_begin(), to = motion->open_end();
      for (std::size_t i = 0; i < n; ++i) {
        const double phi = i + 1 == n ? to : from + (to - from) * static_cast<double>(i) / static_cast<double>(n - 1);
        const LiftDerivatives x = motion->at(phi);
        t.axis.values[i] = phi;
        t.channels[0].values[i] = 2.0 * phi;
        t.channels[1].values[i] = x.lift;
        t.channels[2].values[i] = line.preload + line.rate * x.lift;
        t.channels[3].values[i] = M * w * w * x.acceleration;
        t.channels[4].values[i] = K * M * std::max(0.0, -w * w * x.acceleration);
        t.channels[5].values[i] = t.channels[2].values[i] + t.channels[3].values[i];  // what the cam carries, valve side
      }
      ctx.report_work("evaluations", static_cast<double>(n));
      // The lifts where the spring would stand at its free length and go solid, measured like
      // valve_lift from the installed height; the straight spring line is drawn from the first.
      const double f0 = line.preload / line.rate, top = *std::max_element(t.channels[1].values.begin(), t.channels[1].values.end());
      const CoilGeometry coil = spring->coils().front();
      t.axis_marks = {{"free length", -f0}, {"installed", 0.0}, {"full lift", top}, {"solid", coil.free_length - coil.solid_length - f0}};
      out.set("force_curve", Value::table(std::move(t)));
    }
    out.set("spring", Value::handle(spring));
    out.set("design", Value::handle(std::shared_ptr<const SpringDesign>(std::move(design))));
  }

 private:
  NodeInfo info_;
};

}  // namespace

std::shared_ptr<const NodeType> make_spring_design_type() { return std::make_shared<const SpringDesignType>(); }

}  // namespace mechgraph::valvetrain
