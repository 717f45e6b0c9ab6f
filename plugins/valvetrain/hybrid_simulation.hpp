#pragma once
// The chain model (chain_model.hpp) integrated through its modes: an ODE backend (ode_backend.hpp)
// takes the steps; between them, on the backend's dense output, the driver finds the events (the
// first crossing of an event function inside the step, also one that dips through zero and back
// between the step's ends), interpolates the output times, and follows watched quantities to their
// extremes (docs/methods/valvetrain.md, "Extremes and events from the dense output").
#include "chain_model.hpp"

#include <functional>
#include <limits>
#include <map>
#include <span>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace mechgraph::valvetrain {

struct SimulationOptions {
  std::string integrator = "cvode";  // "cvode" (BDF, Newton) or "dopri5" (explicit RK 5(4))
  double rtol = 1e-8;
  double atol_x = 1e-10;             // m
  double atol_v = 1e-8;              // m/s
  double max_step = 0.0;             // s, 0: none; the integrators' largest step
  double scan_step = 0.0;            // s: sampling of a seated valve's lift-off search (0: max_step)
  // Stretches of time [begin, end], sorted and apart, over which the excitation is constant
  // (y' = y'' = 0: the cam's base circle). A seated single mass cannot lift off inside one, so its
  // lift-off is not scanned for there.
  std::vector<std::pair<double, double>> quiet;
  long max_steps = 2000000;
  long max_events = 100000;
};

struct EventRecord {
  double t = 0.0;
  // lift_off, landing, bounce, contact_loss, contact_regain, and for each lift limit its name
  // (coil_bind, stop: the valve runs into it) and name + "_release" (it leaves it)
  std::string kind;
  // The approach or separation speed: |x_v'| at the seat and the lift limits, |y' - x_0'| between
  // cam and follower at contact loss and regain; 0 at lift-off.
  double speed = 0.0;
  double cam_force = 0.0;   // N, the cam's force on the follower just after the event
  bool cam_contact = true;  // the cam touched the follower just before the event
  int limit = -1;           // the lift limit of a limit event
};

/// A watched quantity's value and rate in a snapshot, or `defined = false` where it has none (in
/// that mode: e.g. a contact force while the valve is seated).
struct Reading {
  double value = 0.0;
  double rate = 0.0;  // d(value)/dt
  bool defined = true;
};

/// A quantity of the state whose least and greatest values the simulation finds on the dense
/// output, over a window of time.
struct Monitor {
  double from = -std::numeric_limits<double>::infinity();  // s
  double to = std::numeric_limits<double>::infinity();     // s
  bool least = true;     // look for its minima
  bool greatest = true;  // and its maxima
  std::function<Reading(const ChainModel&, const Snapshot&)> read;
};

struct Extremum {
  double t = 0.0;
  double value = 0.0;
};

/// A monitor's extremes over one stretch of the window between events (mode changes and bounces)
/// on which it is defined. Only the extremes asked for are searched inside the steps.
struct MonitorSegment {
  double begin = 0.0, end = 0.0;  // s
  Extremum least, greatest;
};

/// The states at the output times: one row of `width` values per time, in one block (one
/// allocation for all of them, reserved up front).
class StateRows {
 public:
  void reset(std::size_t width, std::size_t rows) {
    width_ = width;
    values_.clear();
    values_.reserve(width * rows);
  }
  void push_back(const ChainState& s) { values_.insert(values_.end(), s.begin(), s.begin() + static_cast<std::ptrdiff_t>(width_)); }
  std::size_t size() const { return width_ ? values_.size() / width_ : 0; }
  std::span<const double> operator[](std::size_t j) const { return {values_.data() + j * width_, width_}; }
  std::span<const double> at(std::size_t j) const {
    if (j >= size()) throw std::out_of_range("StateRows::at: row " + std::to_string(j) + " of " + std::to_string(size()));
    return (*this)[j];
  }

 private:
  std::size_t width_ = 0;
  std::vector<double> values_;
};

struct SimulationResult {
  std::vector<double> t;  // at the output times asked for
  StateRows state;
  std::vector<Mode> mode;
  std::vector<EventRecord> events;
  std::vector<std::vector<MonitorSegment>> extremes;  // per monitor, its segments in time order
  // steps, rhs_evaluations, jacobian_evaluations, root_evaluations, rejected_steps, events,
  // monitor_evaluations, refinements (turning points and crossings refined on the dense output)
  std::map<std::string, double> work;
};

/// Integrates from t0 (at rest: valve seated, cam in contact, or valve free without a seat) to t1.
/// `output_times` and `knots` are sorted, inside [t0, t1]. Throws std::runtime_error with the
/// integrator's message when it fails, or when steps or events exceed their limits.
SimulationResult simulate(const ChainModel& model, double t0, double t1, const std::vector<double>& output_times,
                          const std::vector<double>& knots, const SimulationOptions& options,
                          const std::vector<Monitor>& monitors = {});

/// Hands a result's buffers back to this thread's pool: the next simulate() on the same thread
/// fills them again instead of allocating (and, for large outputs, mapping fresh pages). Per thread,
/// so simulations on several threads share nothing.
void recycle(SimulationResult&& used);

/// The least of a monitor's minima over its segments (those starting at or after `from`), or
/// +inf if it has none.
Extremum least_of(const std::vector<MonitorSegment>& segments, double from = -std::numeric_limits<double>::infinity());
/// The greatest of its maxima, or -inf.
Extremum greatest_of(const std::vector<MonitorSegment>& segments, double from = -std::numeric_limits<double>::infinity());

}  // namespace mechgraph::valvetrain
