#pragma once
// What the hybrid driver (single_mass_model.cpp) needs of an ODE integrator: restart in a mode,
// advance toward a time, stop at the first root of that mode's event functions. Two backends:
// SUNDIALS CVODE (BDF with Newton iterations and its own root finding) and Boost.Odeint's
// Dormand-Prince 5(4) with dense output, the roots bracketed per step and refined by TOMS 748.
#include "single_mass_model.hpp"

#include <map>
#include <memory>
#include <string>

namespace mechgraph::valvetrain {

enum class RootKind { lift_off, landing, contact_loss, contact_by_position, contact_by_force };
std::vector<RootKind> root_kinds(const SingleMassParams& p, Mode m);

struct BackendStep {
  double t = 0.0;
  OdeState state;
  int root = -1;  // index into root_kinds(mode) of the root that stopped the step, -1: none
};

class OdeBackend {
 public:
  virtual ~OdeBackend() = default;
  /// Starts afresh at (t, s) in mode m (after an event or at a kink of the excitation).
  virtual void restart(double t, const OdeState& s, Mode m) = 0;
  /// Advances to `target` (<= `limit`, the next time the solution must not be integrated past),
  /// or to the first root before it.
  virtual BackendStep advance(double target, double limit) = 0;
  /// Adds the work done so far to `work` (steps, rhs_evaluations, ...).
  virtual void add_work(std::map<std::string, double>& work) const = 0;
};

std::unique_ptr<OdeBackend> make_cvode_backend(const SingleMassModel& model, const SimulationOptions& options);
std::unique_ptr<OdeBackend> make_dopri5_backend(const SingleMassModel& model, const SimulationOptions& options);

}  // namespace mechgraph::valvetrain
