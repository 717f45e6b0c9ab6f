// The explicit backend: Boost.Odeint's Dormand-Prince 5(4) with step-size control and dense
// output. The event functions are checked at the end of every step; a sign change (in the counted
// direction) is refined on the dense output with TOMS 748 and the earliest one stops the step.
// The state is integrated scaled by the absolute tolerances, so one tolerance fits lift and speed.
#include "ode_backend.hpp"

#include <boost/math/tools/roots.hpp>
#include <boost/numeric/odeint.hpp>

#include <algorithm>
#include <array>
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
    dense_.initialize(scale(s), t, first);
    ++initialisations_;
    stepped_ = false;
    root_ = -1;
    g_.assign(model_.root_kinds(m).size(), 0.0);
    bracket_from_ = t;
    if (g_.empty()) return;
    model_.roots(m, t, s, g_.data());
    // An event function that starts at zero (x = 0 right after a bounce) takes its sign from just
    // after the start, as CVODE does; its roots are searched from there, so a hop shorter than
    // one step is still found and the start itself is never taken for a root.
    if (std::find(g_.begin(), g_.end(), 0.0) != g_.end()) {
      bracket_from_ = t + nudge;
      ChainState ds, ahead_state = s;
      model_.rhs(m, t, s, ds);
      for (std::size_t i = 0; i < s.size(); ++i) ahead_state[i] += nudge * ds[i];
      std::vector<double> ahead(g_.size());
      model_.roots(m, bracket_from_, ahead_state, ahead.data());
      for (std::size_t i = 0; i < g_.size(); ++i)
        if (g_[i] == 0.0) g_[i] = ahead[i];
    }
  }

  BackendStep advance(double target, double limit) override {
    for (;;) {
      const double now = dense_.current_time();
      if (stepped_ && root_ >= 0 && root_time_ <= target) return {root_time_, state_at(root_time_), root_};
      if (stepped_ && target <= now) return {target, state_at(target), -1};
      if (target - now <= 4.0 * std::numeric_limits<double>::epsilon() * std::max(1.0, std::abs(now)))
        return {target, unscale(dense_.current_state()), -1};  // closer than rounding: there
      // Never step past `limit` (a kink of the excitation): shorten the next step to end there.
      if (now + dense_.current_time_step() > limit) {
        dense_.initialize(dense_.current_state(), now, limit - now);
        ++initialisations_;
      }
      dense_.do_step(System{this});
      ++steps_;
      stepped_ = true;
      first_step_ = dense_.current_time_step();
      find_root();
      if (++checked_ > options_.max_steps)
        throw std::runtime_error("dopri5: more than " + std::to_string(options_.max_steps) + " steps");
    }
  }

  void add_work(std::map<std::string, double>& work) const override {
    work["steps"] += static_cast<double>(steps_);
    work["rhs_evaluations"] += static_cast<double>(rhs_);
    work["root_evaluations"] += static_cast<double>(root_evaluations_);
    // Each attempted step costs six new stages (the seventh is the next step's first: FSAL), and
    // every initialisation one more evaluation: what is left over are rejected attempts.
    const long attempts = (rhs_ - initialisations_) / 6;
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
      self->model_.rhs(self->mode_, t, s, self->derivative_);
      dq.resize(q.size());
      for (std::size_t i = 0; i < q.size(); ++i) dq[i] = self->derivative_[i] / self->unit(i);
    }
  };

  // Positions in units of atol_x, velocities in units of atol_v.
  double unit(std::size_t i) const { return i < positions_ ? options_.atol_x : options_.atol_v; }
  Scaled scale(const ChainState& s) const {
    Scaled q(s.size());
    for (std::size_t i = 0; i < s.size(); ++i) q[i] = s[i] / (i < positions_ ? options_.atol_x : options_.atol_v);
    return q;
  }
  ChainState unscale(const Scaled& q) const {
    ChainState s(q.size());
    for (std::size_t i = 0; i < q.size(); ++i) s[i] = q[i] * (i < positions_ ? options_.atol_x : options_.atol_v);
    return s;
  }
  ChainState state_at(double t) {
    Scaled q(2 * positions_);
    dense_.calc_state(t, q);
    return unscale(q);
  }

  // The earliest event in the last step [t0, t1], to full precision in time.
  void find_root() {
    root_ = -1;
    if (g_.empty()) return;
    const double t0 = std::max(dense_.previous_time(), bracket_from_), t1 = dense_.current_time();
    if (t0 >= t1) return;
    std::vector<double> g1(g_.size());
    model_.roots(mode_, t1, unscale(dense_.current_state()), g1.data());
    ++root_evaluations_;
    const std::vector<int> direction = model_.root_directions(mode_);
    for (std::size_t i = 0; i < g_.size(); ++i) {
      const bool crosses = direction[i] > 0 ? (g_[i] < 0.0 && g1[i] >= 0.0) : (g_[i] > 0.0 && g1[i] <= 0.0);
      if (!crosses) continue;
      auto g = [&](double t) {
        std::vector<double> v(g_.size());
        model_.roots(mode_, t, state_at(t), v.data());
        ++root_evaluations_;
        return v[i];
      };
      boost::uintmax_t iterations = 100;
      const double g0 = t0 > dense_.previous_time() ? g(t0) : g_[i];
      if (g0 == 0.0 || (g0 > 0.0) == (g1[i] > 0.0)) continue;
      const auto bracket = boost::math::tools::toms748_solve(g, t0, t1, g0, g1[i],
                                                             boost::math::tools::eps_tolerance<double>(50), iterations);
      const double t = bracket.second;  // the side where the function has crossed
      if (root_ < 0 || t < root_time_) {
        root_ = static_cast<int>(i);
        root_time_ = t;
      }
    }
    g_ = std::move(g1);
  }

  const ChainModel& model_;
  SimulationOptions options_;
  std::size_t positions_;
  ChainState scratch_, derivative_;  // the right-hand side's buffers, kept across calls
  odeint::dense_output_runge_kutta<odeint::controlled_runge_kutta<odeint::runge_kutta_dopri5<Scaled>>> dense_;
  Mode mode_{};
  bool stepped_ = false;
  std::vector<double> g_;  // the event functions at the start of the next step
  int root_ = -1;
  double root_time_ = 0.0;
  double first_step_ = 0.0;
  double bracket_from_ = 0.0;             // roots are searched after this time (just after a restart)
  static constexpr double nudge = 1e-10;  // s
  long steps_ = 0, rhs_ = 0, root_evaluations_ = 0, initialisations_ = 0, checked_ = 0;
};

}  // namespace

std::unique_ptr<OdeBackend> make_dopri5_backend(const ChainModel& model, const SimulationOptions& options) {
  return std::make_unique<Dopri5Backend>(model, options);
}

}  // namespace mechgraph::valvetrain
