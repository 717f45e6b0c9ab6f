#pragma once
// The valve train's simulation set up from a valve motion and a spring design: the piece
// valvetrain.dynamics and valvetrain.float_speed share (chain_model.hpp has the model).
#include "hybrid_simulation.hpp"
#include "train_masses.hpp"

#include <mechgraph/domain/valve_motion.hpp>

#include <string>
#include <vector>

namespace mechgraph::valvetrain {

struct DriveSettings {
  double stiffness = 0.0;      // k_d, N/m, valve side (single mass)
  double damping_ratio = 0.0;  // of the first mode (single mass: of critical on k_d + c_s)
  bool multi_mass = false;     // tappet, pushrod, rocker, valve: `stiffnesses` from the cam to the valve
  std::vector<double> stiffnesses;
  int coils = 0;               // spring_surge: coil masses of the spring (0: massless spring)
  double surge_damping_ratio = 0.0;
  int revolutions = 2;         // results from the last
  double tolerance = 1e-8;     // relative; absolute: times the full lift (and x w_k for speed)
  std::string integrator = "auto";  // "auto", "cvode" or "dopri5"
  bool contact_loss = false;
  bool seat_impact = false;
  double restitution = 0.0;
  double seating_speed = 0.0;
  // Lift limits (chain_model.hpp): the spring's coil bind at its solid deflection, a travel stop.
  bool coil_bind = false;
  double coil_bind_stiffness = 0.0;    // N/m
  double coil_bind_restitution = 1.0;  // (0, 1]
  bool stop = false;
  double stop_lift = 0.0;              // m, valve lift
  double stop_stiffness = 0.0;         // N/m
  double stop_restitution = 1.0;
};

/// How stiff the chain is at the integration's step cap, and so which integrator `auto` takes
/// (docs/methods/valvetrain.md, "Integrators"): the explicit one unless the cap step is beyond its
/// stability interval over fast modes that decay, and BDF's linear algebra is the cheaper.
struct IntegratorChoice {
  /// dopri5's stability interval on the negative real axis reaches about -3.3; a little inside it.
  static constexpr double explicit_limit = 3.0;
  double fastest_rate = 0.0;     // 1/s: bound on the largest |eigenvalue| of the free chain (valve off its seat)
  double stiffness_ratio = 0.0;  // fastest_rate x the step cap
  bool overdamped = false;       // the fastest modes decay without oscillating (BDF's case)
  /// stiffness_ratio > explicit_limit, the fast modes overdamped, and the explicit steps that
  /// stability then needs cost more than BDF's dense linear algebra on the chain's states.
  bool stiff = false;
  /// One line: the figures and the choice they make.
  std::string reason() const;
};

/// The estimate for a chain at the step `step` (s).
IntegratorChoice choose_integrator(const ChainParams& chain, double step);

struct ValveSimulation {
  ChainModel model;
  SimulationResult run;  // states at the requested cam angles of the last revolution
  double period = 0.0;   // s, one cam revolution
  double last_start = 0.0;  // s, start of the last revolution
  IntegratorChoice choice;  // the chain's stiffness at the step cap
  std::string integrator;   // the one that ran: "cvode" or "dopri5" (`auto` resolved)
  double solid_lift = 0.0;  // m, valve lift at coil bind (+inf: no coil bind modelled)
};

/// The chain of masses, stiffnesses and damping the settings describe (valve side). Throws
/// NodeError naming the parameter when a part needed has no mass or stiffness.
ChainParams build_chain(const SpringDesign& design, const DriveSettings& drive);

/// Natural frequencies (rad/s, ascending) of the chain with the valve off its seat and the cam in contact.
std::vector<double> natural_frequencies(const ChainParams& chain);

/// Simulates `revolutions` cam revolutions from the base circle (t = 0 at cam angle -pi, valve
/// seated) and records the state at `cam_angles` (in [-pi, pi], ascending) of the last one, and
/// the extremes of the `monitors` (their windows in that time: the last revolution starts at
/// (revolutions - 1) 2 pi / w_k). Throws NodeError("tolerance") if the integrator fails.
ValveSimulation simulate_valve(const ValveMotion& motion, const SpringDesign& design, const DriveSettings& drive,
                               const std::vector<double>& cam_angles, const std::vector<Monitor>& monitors = {});

/// The same valve motion at another camshaft speed (the motion over cam angle does not depend on it).
class RespeededMotion final : public ValveMotion {
 public:
  RespeededMotion(const ValveMotion& base, double camshaft_speed) : base_(base), speed_(camshaft_speed) {}
  LiftDerivatives at(double phi) const override { return base_.at(phi); }
  double camshaft_speed() const override { return speed_; }
  double open_begin() const override { return base_.open_begin(); }
  double open_end() const override { return base_.open_end(); }
  const std::vector<double>& knots() const override { return base_.knots(); }
  double rocker_ratio() const override { return base_.rocker_ratio(); }
  double lash() const override { return base_.lash(); }
  const CamLaw& cam() const override { return base_.cam(); }

 private:
  const ValveMotion& base_;
  double speed_;
};

}  // namespace mechgraph::valvetrain
