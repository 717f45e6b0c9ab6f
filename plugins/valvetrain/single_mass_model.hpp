#pragma once
// The valve train as one mass on an elastic drive, with the seat and the cam contact as events
// (docs/methods/valvetrain.md, "dynamic simulation"). Everything is on the valve side.
//
//   drive force   N = k_d (y - x) + c (y' - x')        y(t): the cam's displacement reduced to the
//                                                      valve (negative while the lash is open)
//   attached      M x'' = N - (P0 + c_s x)             valve moves with the drive
//   flight        M x'' = -(P0 + c_s x)                contact lost (only with contact_loss): N < 0
//   seated        x = 0, x' = 0                        until N > P0 (lift-off)
// Events, each located by root finding:
//   seated   -> attached   N - P0 crosses 0 upward (with x = x' = 0: N = k_d y + c y')
//   attached -> flight     N crosses 0 downward (contact_loss)
//   flight   -> attached   y - x crosses 0 upward (the cam catches the valve)
//   landing                x crosses 0 downward: seated, or with seat_impact a bounce
//                          x'+ = -e x'- that seats the valve once slower than the seating speed.
// Without a seat (for tests of the drive alone) the valve is always attached.
#include <functional>
#include <map>
#include <string>
#include <vector>

namespace mechgraph::valvetrain {

struct SingleMassParams {
  double mass = 0.0;             // M_red, kg
  double drive_stiffness = 0.0;  // k_d, N/m
  double drive_damping = 0.0;    // c, N*s/m
  double preload = 0.0;          // P0, N
  double spring_rate = 0.0;      // c_s, N/m
  bool seat = true;
  bool contact_loss = false;
  bool seat_impact = false;
  double restitution = 0.0;      // e
  double seating_speed = 0.0;    // m/s: a landing slower than this seats the valve
  int max_bounces = 100;         // per landing: then the valve is seated
};

/// The drive's displacement y(t) and velocity y'(t), smooth between `knots`.
using Excitation = std::function<void(double t, double& y, double& dy)>;

enum class Mode { seated, attached, flight };

struct OdeState {
  double x = 0.0;  // valve lift, m
  double v = 0.0;  // valve velocity, m/s
};

/// The equations and events of the model in one mode; what the ODE backends integrate.
class SingleMassModel {
 public:
  SingleMassModel(const SingleMassParams& p, Excitation y) : p_(p), y_(std::move(y)) {}
  const SingleMassParams& params() const { return p_; }
  double drive_force(double t, const OdeState& s) const;
  void rhs(Mode m, double t, const OdeState& s, OdeState& ds) const;
  /// d(rhs)/d(x, v) as [[0, 1], [a_x, a_v]].
  void jacobian(Mode m, double& a_x, double& a_v) const;
  /// The root functions of a mode and the direction each counts (+1 up, -1 down).
  int root_count(Mode m) const;
  void roots(Mode m, double t, const OdeState& s, double* g) const;
  std::vector<int> root_directions(Mode m) const;
  void excitation(double t, double& y, double& dy) const { y_(t, y, dy); }

 private:
  SingleMassParams p_;
  Excitation y_;
};

/// Accuracy and limits of a simulation.
struct SimulationOptions {
  std::string integrator = "cvode";  // "cvode" (BDF, Newton, root finding) or "dopri5" (explicit RK 5(4))
  double rtol = 1e-8;
  double atol_x = 1e-10;             // m
  double atol_v = 1e-8;              // m/s
  double max_step = 0.0;             // s, 0: none
  long max_steps = 2000000;          // over the whole run
  long max_events = 100000;
};

struct EventRecord {
  double t = 0.0;
  std::string kind;    // lift_off, landing, bounce, contact_loss, contact_regain
  double speed = 0.0;  // |x'| at a landing or bounce
};

struct SimulationResult {
  std::vector<double> t;  // at the output times asked for
  std::vector<OdeState> state;
  std::vector<Mode> mode;
  std::vector<EventRecord> events;
  std::map<std::string, double> work;  // steps, rhs_evaluations, jacobian_evaluations, root_evaluations, rejected_steps, events
};

/// Integrates from t0 (seated at rest, or attached without a seat) to t1. `output_times` and
/// `knots` (where the excitation is not smooth) are sorted and inside (t0, t1]. Throws
/// std::runtime_error with the integrator's message if it fails, or when steps or events exceed
/// their limits.
SimulationResult simulate(const SingleMassModel& model, double t0, double t1, const std::vector<double>& output_times,
                          const std::vector<double>& knots, const SimulationOptions& options);

}  // namespace mechgraph::valvetrain
