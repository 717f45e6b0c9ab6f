// valvetrain.float_speed: the lowest crank speed in a range at which the valve floats, i.e. loses
// cam contact (docs/methods/valvetrain.md, "dynamic simulation"). Each trial speed runs the
// single-mass simulation with unilateral contact (valve_simulation.hpp); the range is scanned
// upward on `scan_points` speeds, and the first floating speed is bisected against the last
// speed that held, to `speed_tolerance`. Float is "lost contact while off the seat during the last
// of `revolutions` revolutions". A range in which the valve never floats is an error that says
// so (and up to which speed it was checked).
#include "node_types.hpp"
#include "valve_simulation.hpp"

#include <cmath>
#include <numbers>
#include <sstream>

namespace mechgraph::valvetrain {
namespace {

constexpr double rpm = 2.0 * std::numbers::pi / 60.0;  // rad/s per rpm

class FloatSpeedType final : public NodeType {
 public:
  FloatSpeedType() {
    info_.type = "valvetrain.float_speed";
    info_.summary = "lowest crank speed in a range at which the valve loses cam contact (valve float)";
    info_.params = {
        ParamSpec::number("rpm_min", dim::angular_speed, "lowest crank speed tried", "rpm").at_least(rpm).at_most(1e6 * rpm).with_example(3000 * rpm),
        ParamSpec::number("rpm_max", dim::angular_speed, "highest crank speed tried", "rpm").at_least(rpm).at_most(1e6 * rpm).with_example(9000 * rpm),
        ParamSpec::number("drive_stiffness", dim::stiffness, "k_d: the drive's stiffness reduced to the valve", "N/mm")
            .positive()
            .at_most(1e13)
            .with_example(4e6),
        ParamSpec::number("damping_ratio", dim::none, "damping of the drive's first mode, share of critical")
            .with_default(0.06)
            .non_negative()
            .at_most(2.0),
        ParamSpec::integer("revolutions", "cam revolutions simulated per speed; float is read in the last")
            .with_default(3.0)
            .at_least(1)
            .at_most(1000),
        ParamSpec::integer("scan_points", "speeds tried across the range before bisecting")
            .with_default(12.0)
            .at_least(2)
            .at_most(10000)
            .as_knob(),
        ParamSpec::number("speed_tolerance", dim::angular_speed, "width of the final bracket", "rpm")
            .with_default(1.0 * rpm)
            .at_least(1e-6 * rpm)
            .as_knob(),
        ParamSpec::number("tolerance", dim::none, "relative tolerance of each simulation")
            .with_default(1e-8)
            .at_least(1e-13)
            .at_most(1e-2)
            .as_knob(),
        ParamSpec::choice("integrator", {"cvode", "dopri5"}, "as in valvetrain.dynamics").with_default("cvode").as_knob(),
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
    };
    info_.work_counters = {"simulations", "steps", "rhs_evaluations"};
  }
  const NodeInfo& info() const override { return info_; }

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
    long simulations = 0;
    auto floats = [&](double crank_speed) {
      const RespeededMotion at_speed(*motion, crank_speed / 2.0);
      const ValveSimulation sim = simulate_valve(at_speed, *design, drive, {});
      ++simulations;
      for (const auto& [counter, amount] : sim.run.work)
        if (counter == "steps" || counter == "rhs_evaluations") ctx.report_work(counter, amount);
      for (const EventRecord& e : sim.run.events)
        if (e.t >= sim.last_start && e.kind == "contact_loss") return true;
      return false;
    };
    // Scan upward for the first speed that floats.
    const long n = p.integer("scan_points");
    double held = lo, floating = 0.0;
    bool found = false;
    for (long i = 0; i < n && !found; ++i) {
      const double speed = lo + (hi - lo) * static_cast<double>(i) / static_cast<double>(n - 1);
      if (floats(speed)) {
        floating = speed;
        found = true;
      } else {
        held = speed;
      }
    }
    if (!found) {
      std::ostringstream msg;
      msg << "the valve does not float between rpm_min " << lo / rpm << " rpm and rpm_max " << hi / rpm << " rpm ("
          << n << " speeds checked): raise rpm_max";
      throw NodeError("rpm_max", msg.str());
    }
    if (floating == lo) {
      ctx.log(LogLevel::warn, "the valve floats already at rpm_min: the float speed is at or below it");
      held = lo;
    } else {
      const double tol = p.number("speed_tolerance");
      while (floating - held > tol) {
        const double mid = 0.5 * (held + floating);
        if (mid <= held || mid >= floating) break;  // adjacent doubles: as narrow as it gets
        (floats(mid) ? floating : held) = mid;
      }
    }
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
