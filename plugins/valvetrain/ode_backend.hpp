#pragma once
// What the hybrid driver (hybrid_simulation.cpp) needs of an ODE integrator: restart in a mode,
// take one step (never past a limit), and give the state anywhere inside that step from its dense
// output. The driver locates the events and extremes on that dense output itself, the same way for
// both backends: SUNDIALS CVODE (BDF with Newton iterations; the Nordsieck history through
// CVodeGetDky) and Boost.Odeint's Dormand-Prince 5(4) with its continuous extension.
#include "hybrid_simulation.hpp"

#include <map>
#include <memory>
#include <string>

namespace mechgraph::valvetrain {

class OdeBackend {
 public:
  virtual ~OdeBackend() = default;
  /// Starts afresh at (t, s) in mode m (after an event or at a kink of the excitation).
  virtual void restart(double t, const ChainState& s, const Mode& m) = 0;
  /// Takes one step from the current time, ending at or before `limit` (the next time the solution
  /// must not be integrated past); returns the step's end.
  virtual double step(double limit) = 0;
  /// The start of the last step.
  virtual double step_begin() const = 0;
  /// The state at t in [step_begin(), end of the last step], from the dense output.
  virtual void state_at(double t, ChainState& s) = 0;
  /// The state at an event at t inside the last step, where the integration restarts: as accurate
  /// as the step itself (by default the dense output, already of the method's order).
  virtual void state_at_event(double t, ChainState& s) { state_at(t, s); }
  /// The snapshot at the end of the last step when the integrator has it already (an explicit
  /// method's last stage there), else false: the driver then makes its own.
  virtual bool end_snapshot(Snapshot&) const { return false; }
  /// Adds the work done so far to `work` (steps, rhs_evaluations, ...).
  virtual void add_work(std::map<std::string, double>& work) const = 0;
};

std::unique_ptr<OdeBackend> make_cvode_backend(const ChainModel& model, const SimulationOptions& options);
std::unique_ptr<OdeBackend> make_dopri5_backend(const ChainModel& model, const SimulationOptions& options);

}  // namespace mechgraph::valvetrain
