#pragma once
// What the hybrid driver (chain_model.cpp) needs of an ODE integrator: restart in a mode,
// advance toward a time, stop at the first root of that mode's event functions. Two backends:
// SUNDIALS CVODE (BDF with Newton iterations and its own root finding) and Boost.Odeint's
// Dormand-Prince 5(4) with dense output, the roots bracketed per step and refined by TOMS 748.
#include "chain_model.hpp"

#include <map>
#include <memory>
#include <string>

namespace mechgraph::valvetrain {

struct BackendStep {
  double t = 0.0;
  ChainState state;
  int root = -1;  // index into the model's root_kinds(mode) of the root that stopped the step, -1: none
};

class OdeBackend {
 public:
  virtual ~OdeBackend() = default;
  /// Starts afresh at (t, s) in mode m (after an event or at a kink of the excitation).
  virtual void restart(double t, const ChainState& s, const Mode& m) = 0;
  /// Advances to `target` (<= `limit`, the next time the solution must not be integrated past),
  /// or to the first root before it.
  virtual BackendStep advance(double target, double limit) = 0;
  /// Adds the work done so far to `work` (steps, rhs_evaluations, ...).
  virtual void add_work(std::map<std::string, double>& work) const = 0;
};

std::unique_ptr<OdeBackend> make_cvode_backend(const ChainModel& model, const SimulationOptions& options);
std::unique_ptr<OdeBackend> make_dopri5_backend(const ChainModel& model, const SimulationOptions& options);

}  // namespace mechgraph::valvetrain
