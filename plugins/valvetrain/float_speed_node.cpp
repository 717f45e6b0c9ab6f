// valvetrain.float_speed: the lowest crank speed in a range at which the valve floats, i.e. loses
// cam contact (docs/methods/valvetrain.md, "Float speed"). Each trial speed n runs the single-mass
// simulation with unilateral contact (valve_simulation.hpp) and reads its contact margin
//   m(n) = least cam force k_d (y - x) + b_d (y' - x') while the valve is off its seat in the last
//          of `revolutions` revolutions,
// found on the integrator's dense output (a brief dip below zero between steps counts): the valve
// floats at n when m(n) <= 0. The range is scanned on `scan_points` speeds; an interval between two
// speeds that hold is split again while the margin comes within its local variation of zero
// (min(m_a, m_b) <= the steepest slope of the interval and its neighbours times its width), so a
// window of float narrower than the scan is not stepped over; the first speed that floats is
// bisected against the last that held to `speed_tolerance`, the part below it searched first. A range in which the
// valve never floats is an error that says so (and up to which speed it was checked).
#include "node_types.hpp"
#include "valve_simulation.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <iterator>
#include <limits>
#include <map>
#include <numbers>
#include <optional>
#include <sstream>

namespace mechgraph::valvetrain {
namespace {

constexpr double rpm = 2.0 * std::numbers::pi / 60.0;  // rad/s per rpm
// The forecast's figures (checked by tests/core/work_estimate_calibration_test.cpp).
constexpr double items_per_revolution = 1000.0;
constexpr double items_per_law_piece = 20.0;
constexpr double bytes_per_item = 64.0;  // the dense output of one simulation, kept until it is read

class FloatSpeedType final : public NodeType, public ForecastReads {
 public:
  FloatSpeedType() {
    info_.type = "valvetrain.float_speed";
    info_.version = 2;
    info_.summary = "lowest crank speed in a range at which the valve loses cam contact (valve float)";
    info_.params = {
        ParamSpec::number("rpm_min", dim::angular_speed, "lowest crank speed tried", "rpm").at_least(rpm).at_most(1e6 * rpm).because("1 to 1e6 rpm: a turning engine, far past any").with_example(3000 * rpm),
        ParamSpec::number("rpm_max", dim::angular_speed, "highest crank speed tried", "rpm").at_least(rpm).at_most(1e6 * rpm).because("1 to 1e6 rpm: a turning engine, far past any (and above rpm_min)").with_example(9000 * rpm),
        ParamSpec::number("drive_stiffness", dim::stiffness, "k_d: the drive's stiffness reduced to the valve", "N/mm")
            .positive()
            .at_most(1e13)
            .because("> 0: a stiffness; <= 1e10 N/mm: stiffer than any steel drive")
            .with_example(4e6),
        ParamSpec::number("damping_ratio", dim::none, "damping of the drive's first mode, share of critical")
            .with_default(0.06)
            .non_negative()
            .at_most(2.0)
            .because(">= 0: damping takes energy; <= 2: past critical (1), overdamped"),
        ParamSpec::integer("revolutions", "cam revolutions simulated per speed; float is read in the last")
            .with_default(3.0)
            .at_least(1)
            .at_most(1000)
            .because("1 to 1000 camshaft turns per speed: 1000 bounds the time"),
        ParamSpec::integer("scan_points", "speeds tried evenly across the range first (refined where the margin could reach 0)")
            .with_default(12.0)
            .at_least(2)
            .at_most(10000)
            .because("2 to 10,000 speeds: the two ends at least")
            .as_knob(),
        ParamSpec::number("speed_tolerance", dim::angular_speed, "width of the final bracket", "rpm")
            .with_default(1.0 * rpm)
            .at_least(1e-6 * rpm)
            .because(">= 1e-6 rpm: finer than the simulations' own accuracy distinguishes")
            .as_knob(),
        ParamSpec::number("tolerance", dim::none, "relative tolerance of each simulation")
            .with_default(1e-8)
            .at_least(1e-13)
            .at_most(1e-2)
            .because("1e-13 to 1e-2: tighter than a double's rounding of the state cannot be met, looser says nothing")
            .as_knob(),
        ParamSpec::choice("integrator", {"cvode", "dopri5", "auto"}, "as in valvetrain.dynamics").with_default("auto").as_knob(),
    };
    info_.inputs = {
        PortSpec::handle("valve", std::string(ValveMotion::kind_name), "the valve's motion (its speed is replaced by each trial's)"),
        PortSpec::handle("design", std::string(SpringDesign::kind_name), "spring and reduced mass (valvetrain.spring_design)"),
    };
    info_.outputs = {
        PortSpec::scalar("float_speed", dim::angular_speed, "lowest crank speed at which the valve floats", "rpm"),
        PortSpec::scalar("held_speed", dim::angular_speed, "highest speed below it at which the valve held (bracket's lower end)",
                         "rpm"),
        PortSpec::scalar("simulations", dim::none, "simulations run"),
        PortSpec::table("contact_margin", "over the crank speeds tried: the least cam force while the valve is off its seat "
                                          "in the last revolution (<= 0: it floats)"),
    };
    info_.work_counters = {"simulations", "steps", "rhs_evaluations", "refined_intervals", "implicit_simulations"};
  }
  const NodeInfo& info() const override { return info_; }

  // Each simulation runs `revolutions` revolutions: the scan's speeds, then about two more per
  // halving of the range down to speed_tolerance (the bisection and the intervals split where the
  // margin could reach zero). A revolution costs some 1000 work items at tolerance 1e-8 (measured:
  // 340 steps of 7 right-hand sides, and the contact monitor), the steps growing as tolerance^(-1/5)
  // (dopri5's order), and a step at least per piece of the valve's law.
  std::optional<std::vector<std::string>> forecast_reads() const override {
    return std::vector<std::string>{"scan_points", "revolutions", "rpm_min", "rpm_max", "speed_tolerance", "tolerance"};
  }
  std::optional<WorkForecast> forecast(const ParamSet& p, const InputSizes& sizes) const override {
    const double scan = static_cast<double>(p.integer("scan_points"));
    const double revolutions = static_cast<double>(p.integer("revolutions"));
    const double range = std::max(p.number("rpm_max") - p.number("rpm_min"), 0.0);
    const double halvings = std::max(1.0, std::log2(std::max(range / p.number("speed_tolerance"), 2.0)));
    const double simulations = scan + 2.0 * halvings;
    const auto pieces = sizes.find("valve");
    const double per_revolution = items_per_revolution * std::pow(1e-8 / p.number("tolerance"), 0.2) +
                                  items_per_law_piece * (pieces == sizes.end() ? 1.0 : pieces->second);
    WorkForecast f;
    f.items = simulations * revolutions * per_revolution;
    f.memory = revolutions * per_revolution * bytes_per_item + scan * 64.0;
    f.output_size = 1.0;
    f.driver = "scan_points = " + std::to_string(static_cast<long>(scan)) + " (about " +
               std::to_string(static_cast<long>(simulations)) + " simulations of " + std::to_string(static_cast<long>(revolutions)) +
               " revolutions)";
    return f;
  }

  void evaluate(const ParamSet& p, const InputSet& in, OutputSet& out, EvalContext& ctx) const override {
    const auto motion = in.handle<ValveMotion>("valve");
    const auto design = in.handle<SpringDesign>("design");
    const double lo = p.number("rpm_min"), hi = p.number("rpm_max");
    if (!(hi > lo)) throw NodeError("rpm_max", "rpm_max must be above rpm_min");
    DriveSettings drive;
    drive.stiffness = p.number("drive_stiffness");
    drive.damping_ratio = p.number("damping_ratio");
    drive.revolutions = static_cast<int>(p.integer("revolutions"));
    drive.tolerance = p.number("tolerance");
    drive.integrator = p.text("integrator");
    drive.contact_loss = true;
    const int revolutions = drive.revolutions;
    long simulations = 0, refined = 0;
    std::map<double, double> margin;  // crank speed -> contact margin m(n), N
    auto margin_at = [&](double crank_speed) {
      const RespeededMotion at_speed(*motion, crank_speed / 2.0);
      const double period = 4.0 * std::numbers::pi / crank_speed;
      // The cam force, signed (negative while the cam is clear of the valve), off the seat.
      const Monitor cam_force{(revolutions - 1) * period, revolutions * period, true, false,
                              [](const ChainModel& model, const Snapshot& x) {
                                if (x.mode.seated) return Reading{0.0, 0.0, false};
                                return Reading{model.cam_force(x.drive, x.state), model.cam_force_rate(x)};
                              }};
      ValveSimulation sim = simulate_valve(at_speed, *design, drive, {}, {cam_force});
      ++simulations;
      for (const auto& [counter, amount] : sim.run.work)
        if (counter == "steps" || counter == "rhs_evaluations") ctx.report_work(counter, amount);
      ctx.report_work("implicit_simulations", sim.integrator == "cvode" ? 1.0 : 0.0);  // the rest ran dopri5
      const double m = least_of(sim.run.extremes[0]).value;  // +inf: the valve never lifted
      recycle(std::move(sim.run));
      margin[crank_speed] = m;
      return m;
    };
    auto floats = [](double m) { return m <= 0.0; };

    // Could the margin reach 0 between two speeds that hold? It is looked at again (the interval
    // split) when it comes within its local variation of zero: min(m_a, m_b) <= s (b - a), s the
    // steepest slope of the interval and the intervals next to it (margins below 0 counted as 0:
    // how deep a float is says nothing here).
    auto could_reach_zero = [&](double a, double b) {
      const auto ia = margin.find(a), ib = margin.find(b);
      if (!std::isfinite(ia->second) || !std::isfinite(ib->second)) return false;
      auto clipped = [](double m) { return std::max(0.0, m); };
      auto slope = [&](std::map<double, double>::const_iterator l, std::map<double, double>::const_iterator r) {
        const double d = std::abs(clipped(r->second) - clipped(l->second)) / (r->first - l->first);
        return std::isfinite(d) ? d : 0.0;
      };
      double steepest = slope(ia, ib);
      if (ia != margin.begin()) steepest = std::max(steepest, slope(std::prev(ia), ia));
      if (std::next(ib) != margin.end()) steepest = std::max(steepest, slope(ib, std::next(ib)));
      return std::min(ia->second, ib->second) <= steepest * (b - a);
    };
    const double tol = p.number("speed_tolerance");
    // The first float in [a, b] (a holds): a bracket (held, floating) no wider than tol.
    std::function<std::optional<std::pair<double, double>>(double, double)> first_float =
        [&](double a, double b) -> std::optional<std::pair<double, double>> {
      const bool b_floats = floats(margin.at(b));
      if (b - a <= tol) return b_floats ? std::optional(std::pair(a, b)) : std::nullopt;
      if (!b_floats) {
        if (!could_reach_zero(a, b)) return std::nullopt;
        ++refined;
      }
      const double c = 0.5 * (a + b);
      if (!(c > a && c < b)) return b_floats ? std::optional(std::pair(a, b)) : std::nullopt;  // adjacent doubles
      margin_at(c);
      if (auto below = first_float(a, c)) return below;
      return first_float(c, b);
    };

    const long n = p.integer("scan_points");
    std::vector<double> scan;
    for (long i = 0; i < n; ++i) scan.push_back(lo + (hi - lo) * static_cast<double>(i) / static_cast<double>(n - 1));
    scan.back() = hi;
    double held = lo, floating = 0.0;
    bool found = false;
    if (floats(margin_at(lo))) {
      ctx.log(LogLevel::warn, "the valve floats already at rpm_min: the float speed is at or below it");
      found = true;
      floating = lo;
    }
    // Upward, interval by interval: each scanned before the next speed is tried.
    for (std::size_t i = 1; i < scan.size() && !found; ++i) {
      margin_at(scan[i]);
      if (const auto bracket = first_float(scan[i - 1], scan[i])) {
        std::tie(held, floating) = *bracket;
        found = true;
      }
    }
    if (!found) {
      std::ostringstream msg;
      msg << "the valve does not float between rpm_min " << lo / rpm << " rpm and rpm_max " << hi / rpm << " rpm ("
          << simulations << " speeds checked): raise rpm_max";
      throw NodeError("rpm_max", msg.str());
    }
    Table table;
    std::vector<double> speeds, least;
    for (const auto& [speed, m] : margin)
      if (std::isfinite(m)) {
        speeds.push_back(speed);
        least.push_back(m);
      }
    table.axis = {"crank_speed", dim::angular_speed, speeds, "rpm"};
    table.add_channel("least_cam_force", dim::force, "N");
    table.channels.back().values = least;
    out.set("contact_margin", Value::table(std::move(table)));
    ctx.report_work("refined_intervals", static_cast<double>(refined));
    ctx.report_work("simulations", static_cast<double>(simulations));
    out.set_scalar("float_speed", floating);
    out.set_scalar("held_speed", held);
    out.set_scalar("simulations", static_cast<double>(simulations));
  }

 private:
  NodeInfo info_;
};

}  // namespace

std::shared_ptr<const NodeType> make_float_speed_type() { return std::make_shared<const FloatSpeedType>(); }

}  // namespace mechgraph::valvetrain
