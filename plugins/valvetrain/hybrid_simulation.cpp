// The hybrid driver (hybrid_simulation.hpp): steps, events, outputs and extremes on the dense output.
#include "hybrid_simulation.hpp"

#include "dense_search.hpp"
#include "extremum_tracker.hpp"
#include "ode_backend.hpp"

#include <mechgraph/printf_number.hpp>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <optional>
#include <stdexcept>

namespace mechgraph::valvetrain {

namespace {

// The hybrid automaton: what an event does to the mode and the state.
class EventHandler {
 public:
  EventHandler(const ChainModel& model, SimulationResult& result) : model_(model), p_(model.params()), result_(result) {}

  void handle(RootKind kind, int limit, double t, Mode& mode, ChainState& s) {
    const bool contact_before = mode.contact;
    const std::size_t events_before = result_.events.size();
    const std::size_t v = model_.valve(), P = model_.positions();
    const DriveValue drive = model_.excitation(t);
    switch (kind) {
      case RootKind::lift_off:
        result_.events.push_back({t, "lift_off", 0.0});
        mode.seated = false;
        if (model_.rigid_when_seated()) mode.contact = true;  // it lifts because the cam pushes
        bounces_ = 0;
        break;
      case RootKind::landing: land(t, mode, s); break;
      case RootKind::contact_loss:
        result_.events.push_back({t, "contact_loss", std::abs(drive.rate - s[P])});
        mode.contact = false;
        break;
      case RootKind::contact_by_position:
        result_.events.push_back({t, "contact_regain", std::abs(drive.rate - s[P])});
        mode.contact = true;
        break;
      case RootKind::contact_by_force:
        // The force turns positive while the cam is still clear of the chain: no contact yet.
        if (drive.y - s[0] > 0.0) {
          result_.events.push_back({t, "contact_regain", std::abs(drive.rate - s[P])});
          mode.contact = true;
        }
        break;
      case RootKind::limit_engage:
      case RootKind::limit_release: {
        const bool engage = kind == RootKind::limit_engage;
        const std::string& name = p_.limits[static_cast<std::size_t>(limit)].name;
        result_.events.push_back({t, engage ? name : name + "_release", std::abs(s[P + v])});
        result_.events.back().limit = limit;
        if (engage) mode.engaged |= 1u << limit;
        else mode.engaged &= ~(1u << limit);
        break;
      }
    }
    for (std::size_t j = events_before; j < result_.events.size(); ++j) {
      EventRecord& e = result_.events[j];
      e.cam_contact = contact_before;
      e.cam_force = mode.contact ? model_.force_after_event(drive, s) : 0.0;  // the post-event side
    }
  }

 private:
  void land(double t, Mode& mode, ChainState& s) {
    const std::size_t v = model_.valve(), P = model_.positions();
    const double speed = std::abs(s[P + v]);
    s[v] = 0.0;
    // A bounce that would leave slower than the seating speed (e = 0 included) seats the valve.
    if (p_.seat_impact && p_.restitution * speed >= p_.seating_speed && bounces_ < p_.max_bounces) {
      ++bounces_;
      result_.events.push_back({t, "bounce", speed});
      s[P + v] = p_.restitution * speed;
      return;  // off the seat again
    }
    result_.events.push_back({t, "landing", speed});
    bounces_ = 0;
    s[P + v] = 0.0;
    // Seated, unless the chain already pushes harder than the spring (then it carries the valve on).
    mode.seated = !(model_.force_on_valve(t, s) > 0.0);
  }

  const ChainModel& model_;
  const ChainParams& p_;
  SimulationResult& result_;
  int bounces_ = 0;
};

// The state at rest at t0 with the valve seated: the masses between cam and valve where their
// links balance (bilateral contact), or untouched where the cam is clear of the chain (contact loss).
ChainState rest_state(const ChainModel& model, double t0, Mode& mode) {
  const ChainParams& p = model.params();
  ChainState s(2 * model.positions(), 0.0);
  const double y = model.excitation(t0).y;
  mode.contact = true;
  if (!p.seat) return s;
  if (p.contact_loss && y < 0.0) {
    mode.contact = false;
    return s;
  }
  // Free masses 0..n-2 between y (through k_0) and the seated valve at 0 (through k_{n-1}):
  // k_j (x_{j-1} - x_j) = k_{j+1} (x_j - x_{j+1}), a tridiagonal system solved by elimination.
  const std::size_t free = p.mass.size() - 1;
  if (free == 0) return s;
  std::vector<double> diag(free), upper(free), rhs(free);
  for (std::size_t j = 0; j < free; ++j) {
    diag[j] = p.link_stiffness[j] + p.link_stiffness[j + 1];
    upper[j] = -p.link_stiffness[j + 1];
    rhs[j] = j == 0 ? p.link_stiffness[0] * y : 0.0;
  }
  for (std::size_t j = 1; j < free; ++j) {
    const double w = upper[j - 1] / diag[j - 1];
    diag[j] -= w * upper[j - 1];
    rhs[j] -= w * rhs[j - 1];
  }
  for (std::size_t j = free; j-- > 0;) s[j] = (rhs[j] - (j + 1 < free ? upper[j] * s[j + 1] : 0.0)) / diag[j];
  return s;
}

bool within_rounding(double a, double b) {
  return std::abs(b - a) <= 8.0 * std::numeric_limits<double>::epsilon() * std::max(1.0, std::abs(a));
}

// The buffers of the last result recycle() was given on this thread.
thread_local SimulationResult spare_result;

// A result to fill: the spare one emptied, its capacity kept.
SimulationResult fresh_result() {
  SimulationResult r = std::move(spare_result);
  spare_result = SimulationResult{};
  r.t.clear();
  r.mode.clear();
  r.state.reset(0, 0);
  r.events.clear();
  r.extremes.clear();
  r.work.clear();
  return r;
}

class Driver {
 public:
  Driver(const ChainModel& model, const SimulationOptions& options, const std::vector<Monitor>& monitors)
      : model_(model), options_(options), monitors_(monitors), search_(options.rtol), result_(fresh_result()),
        events_(model, result_) {
    if (options.integrator == "cvode") backend_ = make_cvode_backend(model, options);
    else if (options.integrator == "dopri5") backend_ = make_dopri5_backend(model, options);
    else throw std::invalid_argument("unknown integrator '" + options.integrator + "'");
    result_.extremes.resize(monitors.size());
    for (const Monitor& m : monitors) trackers_.emplace_back(m, search_);
  }

  SimulationResult run(double t0, double t1, const std::vector<double>& output_times, const std::vector<double>& knots) {
    Mode mode{model_.params().seat, true};
    ChainState s = rest_state(model_, t0, mode);
    double t = t0;
    backend_->restart(t, s, mode);
    set_current(t, s, mode);

    // Every time the integration must stop and restart: the knots (kinks of the excitation), the end.
    std::vector<double> stops;
    for (double k : knots)
      if (k > t0 && k < t1) stops.push_back(k);
    stops.push_back(t1);
    std::sort(stops.begin(), stops.end());
    std::size_t next_stop = 0;
    outputs_ = &output_times;
    result_.t.reserve(output_times.size());
    result_.mode.reserve(output_times.size());
    result_.state.reset(s.size(), output_times.size());
    while (next_output_ < output_times.size() && output_times[next_output_] <= t0) record(t0, s, mode);

    const double seated_step = options_.scan_step > 0.0  ? options_.scan_step
                               : options_.max_step > 0.0 ? options_.max_step
                                                         : (t1 - t0) / 1000.0;
    while (next_stop < stops.size()) {
      const double limit = stops[next_stop];
      if (t >= limit || within_rounding(t, limit)) {
        t = limit;
        ++next_stop;
        if (next_stop < stops.size() && !rigid_seated()) backend_->restart(t, current_.state, current_.mode);
        continue;
      }
      // The drive already pushes a seated valve harder than its spring: it lifts off now.
      if (current_.mode.seated && !g_.empty() && g_[0] > 0.0) {
        fire(RootKind::lift_off, t);
        continue;
      }
      double end = limit;
      if (rigid_seated()) {
        // Nothing moves while a one-mass valve sits: the lift-off is looked for in pieces of the
        // scan step on the excitation alone, nothing integrated.
        // Over a stretch where the drive stands still the force on the valve is constant: one piece.
        const double pieces = quiet(t, limit) ? 1.0 : std::ceil((limit - t) / seated_step);
        if (pieces > 1.0) end = t + (limit - t) / pieces;
        rest_ = current_.state;
      } else {
        end = std::min(backend_->step(limit), limit);
        if (within_rounding(end, limit)) end = limit;
      }
      t = interval(t, end);
    }
    // An event at the very end leaves the outputs there to the state after it.
    while (next_output_ < output_times.size() && within_rounding(output_times[next_output_], t))
      record(output_times[next_output_], current_.state, current_.mode);
    if (next_output_ < output_times.size())
      throw std::logic_error("simulate: output times after the end of the run (" + printf_g(output_times[next_output_]) +
                             " s > " + printf_g(t1) + " s)");
    for (std::size_t k = 0; k < trackers_.size(); ++k) trackers_[k].finish(result_.extremes[k]);
    backend_->add_work(result_.work);
    result_.work["events"] = static_cast<double>(event_count_);
    result_.work["root_evaluations"] += static_cast<double>(root_work_.evaluations + seated_evaluations_);
    result_.work["monitor_evaluations"] = static_cast<double>(monitor_work_.evaluations);
    result_.work["refinements"] = static_cast<double>(root_work_.refinements + monitor_work_.refinements);
    return std::move(result_);
  }

 private:
  bool rigid_seated() const { return current_.mode.seated && model_.rigid_when_seated(); }
  // Is [a, b] inside one of the stretches where the excitation is constant?
  // (options.quiet is sorted and its stretches do not overlap: the last one beginning at or before a.)
  bool quiet(double a, double b) const {
    const auto& q = options_.quiet;
    auto after = std::upper_bound(q.begin(), q.end(), a, [](double t, const auto& stretch) { return t < stretch.first; });
    return after != q.begin() && b <= std::prev(after)->second;
  }

  // The state at t inside the interval being looked at: the dense output, or the seated valve's rest.
  void state_at(double t, ChainState& s) {
    if (rigid_seated()) s = rest_;
    else backend_->state_at(t, s);
  }
  // The snapshot at t; without `full_` only its state (enough for an event function of the state
  // alone, when no monitor looks): the drive and the rates are not computed.
  void snapshot_at(double t, Snapshot& x, bool at_event = false) {
    if (at_event && !rigid_seated()) backend_->state_at_event(t, scratch_state_);
    else state_at(t, scratch_state_);
    if (full_) {
      model_.snapshot(t, scratch_state_, current_.mode, x);
      return;
    }
    x.t = t;
    x.mode = current_.mode;
    x.state = scratch_state_;
  }
  bool roots_need_snapshot(const Mode& m) const {
    for (RootKind k : model_.root_kinds(m))
      if (!ChainModel::state_only(k)) return true;
    return false;
  }

  void set_current(double t, const ChainState& s, const Mode& m) {
    model_.snapshot(t, s, m, current_);
    current_full_ = true;
    read_roots(current_, g_, dg_);
  }
  void read_roots(const Snapshot& x, std::vector<double>& g, std::vector<double>& dg) {
    const std::size_t n = model_.root_kinds(x.mode).size();
    g.resize(n);
    dg.resize(n);
    if (n) model_.roots(x, g.data(), dg.data());
  }

  // Looks at [ta, tb] of the current step: the first event in it, the outputs, the monitors. Returns
  // where the interval ended (the event's time, or tb).
  double interval(double ta, double tb) {
    full_ = roots_need_snapshot(current_.mode);
    for (const Monitor& m : monitors_) full_ = full_ || ((m.least || m.greatest) && m.from < tb && m.to > ta);
    Snapshot& end = end_;
    if (!(full_ && !rigid_seated() && backend_->end_snapshot(end) && end.t == tb)) snapshot_at(tb, end);
    read_roots(end, g_end_, dg_end_);
    if (rigid_seated()) ++seated_evaluations_;
    else if (!g_end_.empty()) ++root_work_.evaluations;

    // The earliest event: each event function's first crossing in its direction.
    const std::vector<int>& direction = model_.root_directions(current_.mode);
    std::optional<double> event_time;
    int event = -1;
    for (std::size_t i = 0; i < g_.size(); ++i) {
      const double d = direction[i] < 0 ? 1.0 : -1.0;  // the crossing as a fall of d g
      const Sample a{ta, d * g_[i], d * dg_[i]}, b{tb, d * g_end_[i], d * dg_end_[i]};
      const auto event_function = [&, i, d](double t) {
        snapshot_at(t, probe_);
        read_roots(probe_, probe_g_, probe_dg_);
        return Sample{t, d * probe_g_[i], d * probe_dg_[i]};
      };
      const auto found = search_.first_fall(a, b, Probe(event_function), root_work_);
      if (found && (!event_time || *found < *event_time)) {
        event_time = found;
        event = static_cast<int>(i);
      }
    }
    const double t_end = event_time ? *event_time : tb;
    if (event_time) snapshot_at(t_end, end, true);

    // Outputs inside (an output at the event's time takes the state after it).
    while (next_output_ < outputs_->size() &&
           (event_time ? (*outputs_)[next_output_] < t_end : (*outputs_)[next_output_] <= t_end)) {
      const double t = (*outputs_)[next_output_];
      state_at(t, scratch_state_);
      record(t, scratch_state_, current_.mode);
    }

    follow_monitors(ta, t_end, end);

    current_full_ = full_;
    if (!event_time) {
      std::swap(current_, end_);
      std::swap(g_, g_end_);
      std::swap(dg_, dg_end_);
      return tb;
    }
    std::swap(current_, end_);  // the state just before the event
    fire(model_.root_kinds(current_.mode)[static_cast<std::size_t>(event)], t_end,
         model_.root_limits(current_.mode)[static_cast<std::size_t>(event)]);
    return t_end;
  }

  // Handles an event at t on the current state: the monitors' segments end, the backend restarts.
  void fire(RootKind kind, double t, int limit = -1) {
    if (++event_count_ > options_.max_events)
      throw std::runtime_error("more than " + std::to_string(options_.max_events) + " contact events (chattering)");
    for (std::size_t k = 0; k < trackers_.size(); ++k) trackers_[k].finish(result_.extremes[k]);
    ChainState s = current_.state;
    Mode mode = current_.mode;
    events_.handle(kind, limit, t, mode, s);
    backend_->restart(t, s, mode);
    set_current(t, s, mode);
  }

  void follow_monitors(double ta, double tb, const Snapshot& end) {
    for (std::size_t k = 0; k < monitors_.size(); ++k) {
      const Monitor& m = monitors_[k];
      if (!m.least && !m.greatest) continue;  // nothing asked of it
      ExtremumTracker& tracker = trackers_[k];
      const double from = std::max(ta, m.from), to = std::min(tb, m.to);
      if (!(to > from)) {
        if (tb >= m.to) tracker.finish(result_.extremes[k]);
        continue;
      }
      const Reading last = read(m, to == tb ? end : (snapshot_at(to, probe_), probe_));
      if (!last.defined) {
        tracker.finish(result_.extremes[k]);
        continue;
      }
      if (!tracker.is_open()) {
        if (from == ta && !current_full_) {
          model_.snapshot(ta, current_.state, current_.mode, current_);
          current_full_ = true;
        }
        const Reading first = read(m, from == ta ? current_ : (snapshot_at(from, probe_), probe_));
        if (!first.defined) continue;
        tracker.begin({from, first.value, first.rate});
      }
      const auto quantity = [&](double t) {
        snapshot_at(t, probe_);
        const Reading r = read(m, probe_);
        return Sample{t, r.value, r.rate};
      };
      tracker.extend({to, last.value, last.rate}, Probe(quantity), monitor_work_);
      if (to >= m.to) tracker.finish(result_.extremes[k]);
    }
  }
  Reading read(const Monitor& m, const Snapshot& x) {
    ++monitor_work_.evaluations;
    return m.read(model_, x);
  }

  void record(double t, const ChainState& s, const Mode& m) {
    result_.t.push_back(t);
    result_.state.push_back(s);
    result_.mode.push_back(m);
    ++next_output_;
  }

  const ChainModel& model_;
  const SimulationOptions& options_;
  const std::vector<Monitor>& monitors_;
  DenseSearch search_;
  SimulationResult result_;
  EventHandler events_;
  std::unique_ptr<OdeBackend> backend_;
  std::vector<ExtremumTracker> trackers_;
  const std::vector<double>* outputs_ = nullptr;
  std::size_t next_output_ = 0;
  Snapshot current_, end_, probe_;  // at the interval's start, its end, a probe inside
  std::vector<double> g_, dg_, g_end_, dg_end_, probe_g_, probe_dg_;
  ChainState rest_, scratch_state_;
  SearchWork root_work_, monitor_work_;
  long event_count_ = 0, seated_evaluations_ = 0;
  bool full_ = true, current_full_ = true;  // snapshots with the drive and the rates (see snapshot_at)
};

}  // namespace

SimulationResult simulate(const ChainModel& model, double t0, double t1, const std::vector<double>& output_times,
                          const std::vector<double>& knots, const SimulationOptions& options,
                          const std::vector<Monitor>& monitors) {
  Driver driver(model, options, monitors);
  return driver.run(t0, t1, output_times, knots);
}

void recycle(SimulationResult&& used) { spare_result = std::move(used); }

Extremum least_of(const std::vector<MonitorSegment>& segments, double from) {
  Extremum e{0.0, std::numeric_limits<double>::infinity()};
  for (const MonitorSegment& s : segments)
    if (s.begin >= from && s.least.value < e.value) e = s.least;
  return e;
}

Extremum greatest_of(const std::vector<MonitorSegment>& segments, double from) {
  Extremum e{0.0, -std::numeric_limits<double>::infinity()};
  for (const MonitorSegment& s : segments)
    if (s.begin >= from && s.greatest.value > e.value) e = s.greatest;
  return e;
}

}  // namespace mechgraph::valvetrain
