// The explicit backend: Boost.Odeint's Dormand-Prince 5(4) with step-size control and dense
// output (its continuous extension gives the state anywhere in the last step, which is where the
// driver looks for events and extremes). The state is integrated scaled by the absolute
// tolerances, so one tolerance fits lift and speed.
#include "ode_backend.hpp"

#include <boost/numeric/odeint.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace mechgraph::valvetrain {
namespace {

namespace odeint = boost::numeric::odeint;
using Scaled = std::vector<double>;

class Dopri5Backend final : public OdeBackend {
 public:
  Dopri5Backend(const ChainModel& model, const SimulationOptions& options)
      : model_(model), options_(options), positions_(model.positions()),
        dense_(odeint::make_dense_output(1.0, options.rtol, options.max_step, odeint::runge_kutta_dopri5<Scaled>())) {}

  void restart(double t, const ChainState& s, const Mode& m) override {
    mode_ = m;
    const double first = first_step_ > 0.0 ? first_step_ : 1e-9;
    scale(s, scaled_);
    dense_.initialize(scaled_, t, first);
    ++initialisations_;
  }

  double step(double limit) override {
    const double now = dense_.current_time();
    // Never step past `limit` (a kink of the excitation): shorten the next step to end there.
    if (now + dense_.current_time_step() > limit) {
      dense_.initialize(dense_.current_state(), now, limit - now);
      ++initialisations_;
    }
    dense_.do_step(System{this});
    ++steps_;
    first_step_ = dense_.current_time_step();
    if (steps_ > options_.max_steps)
      throw std::runtime_error("dopri5: more than " + std::to_string(options_.max_steps) + " steps");
    return dense_.current_time();
  }

  double step_begin() const override { return dense_.previous_time(); }

  // Dormand-Prince's last stage is the right-hand side at the step's end (first same as last): the
  // state, its rate and the drive there are still in the buffers of that call.
  bool end_snapshot(Snapshot& x) const override {
    if (!(last_t_ == dense_.current_time()) || steps_ == 0) return false;
    x.t = last_t_;
    x.mode = mode_;
    x.state = scratch_;
    x.rate = derivative_;
    x.drive = last_drive_;
    return true;
  }

  void state_at(double t, ChainState& s) override {
    scaled_.resize(2 * positions_);
    dense_.calc_state(t, scaled_);
    s.resize(scaled_.size());
    for (std::size_t i = 0; i < s.size(); ++i) s[i] = scaled_[i] * unit(i);
  }

  // Dormand-Prince's continuous extension is of order 4, one below its steps: where the integration
  // restarts after an event, the state comes from one step of the method itself from the last
  // step's beginning to the event (shorter than the accepted step, so within its error).
  void state_at_event(double t, ChainState& s) override {
    const double t0 = dense_.previous_time();
    if (!(t > t0 && t < dense_.current_time())) {
      state_at(t, s);
      return;
    }
    event_start_ = dense_.previous_state();
    System system{this};
    system(event_start_, event_rate_, t0);
    single_.do_step(system, event_start_, event_rate_, t0, scaled_, event_end_rate_, t - t0);
    ++event_steps_;
    s.resize(scaled_.size());
    for (std::size_t i = 0; i < s.size(); ++i) s[i] = scaled_[i] * unit(i);
  }

  void add_work(std::map<std::string, double>& work) const override {
    work["steps"] += static_cast<double>(steps_);
    work["rhs_evaluations"] += static_cast<double>(rhs_);
    // Each attempted step costs six new stages (the seventh is the next step's first: FSAL), and
    // every initialisation one more evaluation: what is left over are rejected attempts.
    const long attempts = (rhs_ - initialisations_ - 7 * event_steps_) / 6;
    work["rejected_steps"] += static_cast<double>(std::max(0L, attempts - steps_));
  }

 private:
  struct System {
    Dopri5Backend* self;
    void operator()(const Scaled& q, Scaled& dq, double t) const {
      ++self->rhs_;
      ChainState& s = self->scratch_;
      s.resize(q.size());
      for (std::size_t i = 0; i < q.size(); ++i) s[i] = q[i] * self->unit(i);
      // Dormand-Prince evaluates twice at the step's end (its sixth stage, c_6 = 1, and the FSAL
      // stage there): the drive's motion at that time is taken again, not recomputed.
      if (t == self->last_t_ && self->drive_known_) {
        self->model_.rhs(self->mode_, self->last_drive_, s, self->derivative_);
      } else {
        self->model_.rhs(self->mode_, t, s, self->derivative_, self->last_drive_);
        self->last_t_ = t;
        self->drive_known_ = true;
      }
      dq.resize(q.size());
      for (std::size_t i = 0; i < q.size(); ++i) dq[i] = self->derivative_[i] / self->unit(i);
    }
  };

  // Positions in units of atol_x, velocities in units of atol_v.
  double unit(std::size_t i) const { return i < positions_ ? options_.atol_x : options_.atol_v; }
  void scale(const ChainState& s, Scaled& q) const {
    q.resize(s.size());
    for (std::size_t i = 0; i < s.size(); ++i) q[i] = s[i] / unit(i);
  }

  const ChainModel& model_;
  SimulationOptions options_;
  std::size_t positions_;
  ChainState scratch_, derivative_;  // the right-hand side's buffers, kept across calls
  Scaled scaled_;
  Scaled event_start_, event_rate_, event_end_rate_;  // the step to an event (state_at_event)
  odeint::runge_kutta_dopri5<Scaled> single_;
  odeint::dense_output_runge_kutta<odeint::controlled_runge_kutta<odeint::runge_kutta_dopri5<Scaled>>> dense_;
  Mode mode_{};
  DriveValue last_drive_;  // of the last right-hand side, at last_t_
  double last_t_ = -1.0;
  bool drive_known_ = false;  // last_drive_ holds the drive at last_t_
  double first_step_ = 0.0;
  long steps_ = 0, rhs_ = 0, initialisations_ = 0, event_steps_ = 0;
};

}  // namespace

std::unique_ptr<OdeBackend> make_dopri5_backend(const ChainModel& model, const SimulationOptions& options) {
  return std::make_unique<Dopri5Backend>(model, options);
}

}  // namespace mechgraph::valvetrain
