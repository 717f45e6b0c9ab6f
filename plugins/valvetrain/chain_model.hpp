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
//   lift limits   the spring's coil bind and an optional travel stop: stiff one-sided contacts on
//                 the valve at lift a_i, engaged while x_v > a_i (entered when x_v - a_i rises
//                 through 0, left when it falls through 0), pushing back with
//                   F_i = k_i (x_v - a_i) + c_i x_v'
//                 c_i from the contact's restitution e_i (a free mass entering at speed v leaves
//                 at e_i v: c_i = 2 zeta_i sqrt(k_i m_v), zeta_i = -ln e_i / sqrt(pi^2 + ln^2 e_i)).
//                 The coil bind's force goes through the solid spring: it counts as spring force.
// hybrid_simulation.hpp integrates it; the event functions and the forces come with their exact
// time derivatives, so extremes and crossings can be refined inside a step.
#include <functional>
#include <string>
#include <vector>

namespace mechgraph::valvetrain {

/// A stiff one-sided contact that stops the valve at a lift (the spring's coil bind, a travel stop).
struct LiftLimit {
  double lift = 0.0;       // a_i, m (valve side, > 0)
  double stiffness = 0.0;  // k_i, N/m
  double damping = 0.0;    // c_i, N*s/m
  bool in_spring = false;  // its force goes through the spring (coil bind): part of spring_force()
  std::string name;        // for the events: "coil_bind", "stop"
};

/// c_i of a contact of stiffness k on mass m whose rebound speed is e times the impact speed
/// (0 < e <= 1; e = 1: no damping).
double restitution_damping(double restitution, double stiffness, double mass);

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
  std::vector<LiftLimit> limits;       // at most max_limits
  static constexpr std::size_t max_limits = 2;
};

/// The drive's displacement y, velocity y' and acceleration y'' at one time.
struct DriveValue {
  double y = 0.0;             // m
  double rate = 0.0;          // m/s
  double acceleration = 0.0;  // m/s^2
};

/// The drive's motion y(t), smooth between the knots given to simulate().
using Excitation = std::function<DriveValue(double t)>;

/// The discrete state: is the valve on its seat, is the cam touching the first mass.
struct Mode {
  bool seated = true;
  bool contact = true;
  unsigned engaged = 0;  // bit i: lift limit i engaged
  friend bool operator==(const Mode&, const Mode&) = default;
};

enum class RootKind { lift_off, landing, contact_loss, contact_by_position, contact_by_force, limit_engage, limit_release };

/// Positions then velocities: x_0..x_{n-1}, z_1..z_p, x_0'..., z_p'.
using ChainState = std::vector<double>;

/// The state at one time with what the event functions and watched quantities are made of: its
/// rate of change in the mode, and the drive's motion.
struct Snapshot {
  double t = 0.0;
  Mode mode;
  ChainState state;
  ChainState rate;  // d(state)/dt in `mode`
  DriveValue drive;
};

class ChainModel {
 public:
  ChainModel(ChainParams p, Excitation y);
  const ChainParams& params() const { return p_; }
  std::size_t positions() const { return positions_; }   // n + p
  std::size_t valve() const { return p_.mass.size() - 1; }
  /// True when nothing moves while the valve is seated (one mass, massless spring).
  bool rigid_when_seated() const { return p_.mass.size() == 1 && p_.coils == 0; }

  DriveValue excitation(double t) const { return y_(t); }
  double cam_force(double t, const ChainState& s) const { return cam_force(y_(t), s); }
  double cam_force(const DriveValue& e, const ChainState& s) const;
  /// The cam force as it acts: cam_force, or with contact_loss only while the cam touches and pushes.
  double pushing_force(double t, const ChainState& s) const { return pushing_force(y_(t), s); }
  double pushing_force(const DriveValue& e, const ChainState& s) const;
  /// The force the cam carries just after an event, the cam touching (s the post-event state): as
  /// pushing_force, but on the post-event side of the event's root. At a regain the gap y - x_0 is
  /// the located root, zero to rounding, and its sign there says nothing (pushing_force read 0 on
  /// one side of it); just after, the gap closes into compression, so the force is the damper's
  /// c_0 (y' - x_0') plus k_0 times the gap at most rounding, and never a pull.
  double force_after_event(const DriveValue& e, const ChainState& s) const;
  /// Net force on the valve from the chain and the spring (without the seat's reaction).
  double force_on_valve(double t, const ChainState& s) const { return force_on_valve(y_(t), s); }
  double force_on_valve(const DriveValue& e, const ChainState& s) const;
  /// The spring's force on the valve: P0 + c_s x_v, or the first coil element's with spring_surge;
  /// plus the coil bind's while it is engaged (bit i of `engaged`: lift limit i).
  double spring_force(const ChainState& s, unsigned engaged = 0) const;
  void rhs(const Mode& m, double t, const ChainState& s, ChainState& ds) const;
  /// The same, and the drive's motion at t that it used.
  void rhs(const Mode& m, double t, const ChainState& s, ChainState& ds, DriveValue& drive) const;
  /// The same with the drive's motion already known (an integrator's stages that share a time).
  void rhs(const Mode& m, const DriveValue& drive, const ChainState& s, ChainState& ds) const { rates(m, drive, s, ds); }
  /// The state's rate and the drive's motion at (t, s) in mode m, into `out` (its buffers reused).
  void snapshot(double t, const ChainState& s, const Mode& m, Snapshot& out) const;
  /// Time derivatives of the forces above along the motion, from a snapshot (exact: the model is
  /// affine in the state and the drive within a mode).
  double cam_force_rate(const Snapshot& x) const;
  double pushing_force_rate(const Snapshot& x) const;
  double force_on_valve_rate(const Snapshot& x) const;
  double spring_force_rate(const Snapshot& x) const;
  const std::vector<RootKind>& root_kinds(const Mode& m) const { return kinds_[index(m)]; }
  /// For each root of root_kinds(m): the lift limit it concerns (limit_engage, limit_release), else -1.
  const std::vector<int>& root_limits(const Mode& m) const { return limit_of_root_[index(m)]; }
  /// Lift limit i's force on the valve while engaged, and its time derivative from a snapshot.
  double limit_force(std::size_t i, const ChainState& s) const;
  double limit_force_rate(std::size_t i, const Snapshot& x) const;
  /// True for roots that read the state alone (no drive, no rates): landing and the lift limits.
  static bool state_only(RootKind k) { return k == RootKind::landing || k == RootKind::limit_engage || k == RootKind::limit_release; }
  /// +1: the event is the function's rise through 0, -1: its fall.
  const std::vector<int>& root_directions(const Mode& m) const { return directions_[index(m)]; }
  /// The event functions of the snapshot's mode, and their rates when `dg` is not null.
  void roots(const Snapshot& x, double* g, double* dg) const;
  /// d(rhs)/d(state), row-major (the model is linear in the state within a mode).
  std::vector<double> jacobian(const Mode& m) const;

 private:
  // The forces on each position for state s and drive (y, y'); with `rates`, s is the state's rate,
  // (y, y') the drive's (y', y''), and the constant preload left out: the forces' time derivative.
  // `pushing` says whether the cam's force acts (contact, and with contact_loss: touching and pushing).
  // f: room for positions() values.
  void forces(const Mode& m, double y, double dy, const ChainState& s, bool pushing, bool rates, double* f) const;
  bool pushes(const DriveValue& e, const ChainState& s) const;
  void rates(const Mode& m, const DriveValue& e, const ChainState& s, ChainState& ds) const;
  void list_roots();
  static int index(const Mode& m) { return (m.seated ? 1 : 0) + (m.contact ? 2 : 0) + 4 * static_cast<int>(m.engaged); }
  static constexpr int modes = 4 << ChainParams::max_limits;
  ChainParams p_;
  Excitation y_;
  std::size_t positions_;
  std::vector<RootKind> kinds_[modes];  // per mode (index())
  std::vector<int> directions_[modes];
  std::vector<int> limit_of_root_[modes];
};

}  // namespace mechgraph::valvetrain
