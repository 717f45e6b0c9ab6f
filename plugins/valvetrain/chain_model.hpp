#pragma once
// The valve train as a chain of masses driven by the cam, with the seat and the cam contact as
// events (docs/methods/valvetrain.md, "dynamic simulation"). Everything is reduced to the valve.
//
//   cam y(t) --k_0,c_0-- m_0 --k_1,c_1-- m_1 ... --k_{n-1}-- m_{n-1} (the valve) --spring-- head
//
// One mass (the default) is the single-mass model: M_red on the drive stiffness k_d. With the
// multi_mass effect the masses are tappet, pushrod, rocker and valve with their own stiffnesses.
// The valve spring is massless (P0 + c_s x, its moving mass in the valve's), or, with the
// spring_surge effect, p coil masses m_s/p joined by p + 1 elements of stiffness (p + 1) c_s,
// fixed to the head at the far end (the first surge mode near f1 = 1/2 sqrt(c_s / m_s)).
//
//   cam force     F_c = k_0 (y - x_0) + c_0 (y' - x_0')      y: the cam's displacement at the
//                                                          valve (negative while lash is open)
//   link j        F_j = k_j (x_{j-1} - x_j) + c_j (x_{j-1}' - x_j')
//   spring        F_s = P0 + c_s x_v    or    P0 + k_e (x_v - z_1) + c_e (x_v' - z_1')
// Hybrid states and their events (each located by root finding):
//   valve seated  x_v = x_v' = 0 while the force on it from the chain is below the spring's;
//                 lift-off when it exceeds it. Landing: x_v crosses 0 downward: seated, or with
//                 seat_impact a bounce x_v'+ = -e x_v'- until a landing slower than the seating speed.
//   cam contact   bilateral unless contact_loss: then contact is lost when F_c falls to 0 and
//                 regained when the cam catches up (y - x_0 crosses 0 upward, or F_c turns
//                 positive while y > x_0).
#include <functional>
#include <map>
#include <string>
#include <vector>

namespace mechgraph::valvetrain {

struct ChainParams {
  std::vector<double> mass;            // m_0 .. m_{n-1}, cam side first; the last is the valve
  std::vector<double> link_stiffness;  // k_0 (cam to m_0) .. k_{n-1}
  std::vector<double> link_damping;    // c_0 .. c_{n-1}
  double preload = 0.0;                // P0, N
  double spring_rate = 0.0;            // c_s, N/m
  int coils = 0;                       // spring_surge: coil masses (0: massless spring)
  double coil_mass = 0.0;              // each, kg
  double coil_damping = 0.0;           // per element, N*s/m
  bool seat = true;
  bool contact_loss = false;
  bool seat_impact = false;
  double restitution = 0.0;
  double seating_speed = 0.0;          // m/s
  int max_bounces = 100;               // per landing: then the valve is seated
};

/// The drive's displacement y(t) and velocity y'(t), smooth between the knots given to simulate().
using Excitation = std::function<void(double t, double& y, double& dy)>;

/// The discrete state: is the valve on its seat, is the cam touching the first mass.
struct Mode {
  bool seated = true;
  bool contact = true;
  friend bool operator==(const Mode&, const Mode&) = default;
};

enum class RootKind { lift_off, landing, contact_loss, contact_by_position, contact_by_force };

/// Positions then velocities: x_0..x_{n-1}, z_1..z_p, x_0'..., z_p'.
using ChainState = std::vector<double>;

class ChainModel {
 public:
  ChainModel(ChainParams p, Excitation y);
  const ChainParams& params() const { return p_; }
  std::size_t positions() const { return positions_; }   // n + p
  std::size_t valve() const { return p_.mass.size() - 1; }
  /// True when nothing moves while the valve is seated (one mass, massless spring).
  bool rigid_when_seated() const { return p_.mass.size() == 1 && p_.coils == 0; }

  double cam_force(double t, const ChainState& s) const;
  /// The cam force as it acts: cam_force, or with contact_loss only while the cam touches and pushes.
  double pushing_force(double t, const ChainState& s) const;
  /// Net force on the valve from the chain and the spring (without the seat's reaction).
  double force_on_valve(double t, const ChainState& s) const;
  void rhs(const Mode& m, double t, const ChainState& s, ChainState& ds) const;
  std::vector<RootKind> root_kinds(const Mode& m) const;
  std::vector<int> root_directions(const Mode& m) const;
  void roots(const Mode& m, double t, const ChainState& s, double* g) const;
  /// d(rhs)/d(state), row-major (the model is linear in the state within a mode).
  std::vector<double> jacobian(const Mode& m) const;
  void excitation(double t, double& y, double& dy) const { y_(t, y, dy); }

 private:
  void forces(const Mode& m, double t, const ChainState& s, std::vector<double>& f) const;
  ChainParams p_;
  Excitation y_;
  std::size_t positions_;
};

struct SimulationOptions {
  std::string integrator = "cvode";  // "cvode" (BDF, Newton, root finding) or "dopri5" (explicit RK 5(4))
  double rtol = 1e-8;
  double atol_x = 1e-10;             // m
  double atol_v = 1e-8;              // m/s
  double max_step = 0.0;             // s, 0: none; the integrators' largest step
  double scan_step = 0.0;            // s: sampling of a seated valve's lift-off search (0: max_step)
  long max_steps = 2000000;
  long max_events = 100000;
};

struct EventRecord {
  double t = 0.0;
  std::string kind;    // lift_off, landing, bounce, contact_loss, contact_regain
  double speed = 0.0;  // |x_v'| at a landing or bounce
};

struct SimulationResult {
  std::vector<double> t;  // at the output times asked for
  std::vector<ChainState> state;
  std::vector<Mode> mode;
  std::vector<EventRecord> events;
  std::map<std::string, double> work;  // steps, rhs_evaluations, jacobian_evaluations, root_evaluations, rejected_steps, events
};

/// Integrates from t0 (at rest: valve seated, cam in contact, or valve free without a seat) to t1.
/// `output_times` and `knots` are sorted, inside [t0, t1]. Throws std::runtime_error with the
/// integrator's message when it fails, or when steps or events exceed their limits.
SimulationResult simulate(const ChainModel& model, double t0, double t1, const std::vector<double>& output_times,
                          const std::vector<double>& knots, const SimulationOptions& options);

}  // namespace mechgraph::valvetrain
