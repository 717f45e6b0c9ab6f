#include "single_mass_model.hpp"

#include "ode_backend.hpp"

#include <boost/math/tools/roots.hpp>

#include <algorithm>
#include <cmath>
#include <optional>
#include <limits>
#include <stdexcept>

namespace mechgraph::valvetrain {

double SingleMassModel::drive_force(double t, const OdeState& s) const {
  double y = 0.0, dy = 0.0;
  y_(t, y, dy);
  return p_.drive_stiffness * (y - s.x) + p_.drive_damping * (dy - s.v);
}

void SingleMassModel::rhs(Mode m, double t, const OdeState& s, OdeState& ds) const {
  switch (m) {
    case Mode::seated: ds = {0.0, 0.0}; return;
    case Mode::attached: ds = {s.v, (drive_force(t, s) - p_.preload - p_.spring_rate * s.x) / p_.mass}; return;
    case Mode::flight: ds = {s.v, -(p_.preload + p_.spring_rate * s.x) / p_.mass}; return;
  }
}

void SingleMassModel::jacobian(Mode m, double& a_x, double& a_v) const {
  switch (m) {
    case Mode::seated: a_x = a_v = 0.0; return;
    case Mode::attached:
      a_x = -(p_.drive_stiffness + p_.spring_rate) / p_.mass;
      a_v = -p_.drive_damping / p_.mass;
      return;
    case Mode::flight:
      a_x = -p_.spring_rate / p_.mass;
      a_v = 0.0;
      return;
  }
}

std::vector<RootKind> root_kinds(const SingleMassParams& p, Mode m) {
  switch (m) {
    case Mode::seated: return {RootKind::lift_off};
    case Mode::attached: {
      std::vector<RootKind> k;
      if (p.seat) k.push_back(RootKind::landing);
      if (p.contact_loss) k.push_back(RootKind::contact_loss);
      return k;
    }
    case Mode::flight: {
      std::vector<RootKind> k{RootKind::contact_by_position, RootKind::contact_by_force};
      if (p.seat) k.insert(k.begin(), RootKind::landing);
      return k;
    }
  }
  return {};
}

int SingleMassModel::root_count(Mode m) const { return static_cast<int>(root_kinds(p_, m).size()); }

void SingleMassModel::roots(Mode m, double t, const OdeState& s, double* g) const {
  const auto kinds = root_kinds(p_, m);
  for (std::size_t i = 0; i < kinds.size(); ++i) {
    switch (kinds[i]) {
      case RootKind::lift_off: g[i] = drive_force(t, {0.0, 0.0}) - p_.preload; break;
      case RootKind::landing: g[i] = s.x; break;
      case RootKind::contact_loss: g[i] = drive_force(t, s); break;
      case RootKind::contact_by_position: {
        double y = 0.0, dy = 0.0;
        y_(t, y, dy);
        g[i] = y - s.x;
        break;
      }
      case RootKind::contact_by_force: g[i] = drive_force(t, s); break;
    }
  }
}

std::vector<int> SingleMassModel::root_directions(Mode m) const {
  std::vector<int> d;
  for (RootKind k : root_kinds(p_, m))
    d.push_back(k == RootKind::landing || k == RootKind::contact_loss ? -1 : +1);
  return d;
}

namespace {

// The hybrid automaton: what an event does to the mode and the state.
class EventHandler {
 public:
  EventHandler(const SingleMassModel& model, SimulationResult& result) : model_(model), p_(model.params()), result_(result) {}

  void handle(RootKind kind, double t, Mode& mode, OdeState& s) {
    switch (kind) {
      case RootKind::lift_off:
        result_.events.push_back({t, "lift_off", 0.0});
        mode = Mode::attached;
        s = {0.0, 0.0};
        bounces_ = 0;
        return;
      case RootKind::landing: land(t, mode, s); return;
      case RootKind::contact_loss:
        result_.events.push_back({t, "contact_loss", 0.0});
        mode = Mode::flight;
        return;
      case RootKind::contact_by_position:
        result_.events.push_back({t, "contact_regain", 0.0});
        mode = Mode::attached;
        return;
      case RootKind::contact_by_force: {
        // The force turns positive while the cam is still clear of the valve: no contact yet.
        double y = 0.0, dy = 0.0;
        model_.excitation(t, y, dy);
        if (y - s.x > 0.0) {
          result_.events.push_back({t, "contact_regain", 0.0});
          mode = Mode::attached;
        }
        return;
      }
    }
  }

 private:
  void land(double t, Mode& mode, OdeState& s) {
    const double speed = std::abs(s.v);
    s.x = 0.0;
    if (p_.seat_impact && speed >= p_.seating_speed && bounces_ < p_.max_bounces) {
      ++bounces_;
      result_.events.push_back({t, "bounce", speed});
      s.v = p_.restitution * speed;
      return;  // off the seat again, in the same contact mode
    }
    result_.events.push_back({t, "landing", speed});
    bounces_ = 0;
    s.v = 0.0;
    // Seated, unless the drive already pushes harder than the preload (then it carries the valve on).
    mode = model_.drive_force(t, s) - p_.preload > 0.0 ? Mode::attached : Mode::seated;
  }

  const SingleMassModel& model_;
  const SingleMassParams& p_;
  SimulationResult& result_;
  int bounces_ = 0;
};

// While the valve is seated nothing moves: the lift-off is a root of N(t) - P0 (x = x' = 0), a
// function of the excitation alone, found by sampling at `step` and TOMS 748, no integration.
std::optional<double> lift_off_between(const SingleMassModel& model, double t0, double t1, double step, long& evaluations) {
  auto g = [&](double t) {
    double v = 0.0;
    model.roots(Mode::seated, t, {0.0, 0.0}, &v);
    ++evaluations;
    return v;
  };
  const long n = std::max(1L, static_cast<long>(std::ceil((t1 - t0) / step)));
  double a = t0, ga = g(t0);
  if (ga > 0.0) return t0;  // the drive already holds more than the preload
  for (long i = 1; i <= n; ++i) {
    const double b = i == n ? t1 : t0 + (t1 - t0) * static_cast<double>(i) / static_cast<double>(n);
    const double gb = g(b);
    if (gb > 0.0) {
      if (ga == 0.0) return a;
      boost::uintmax_t iterations = 100;
      const auto bracket = boost::math::tools::toms748_solve(g, a, b, ga, gb, boost::math::tools::eps_tolerance<double>(50),
                                                             iterations);
      return bracket.second;  // the side where the drive has overcome the preload
    }
    a = b;
    ga = gb;
  }
  return std::nullopt;
}

}  // namespace

SimulationResult simulate(const SingleMassModel& model, double t0, double t1, const std::vector<double>& output_times,
                          const std::vector<double>& knots, const SimulationOptions& options) {
  std::unique_ptr<OdeBackend> backend;
  if (options.integrator == "cvode") backend = make_cvode_backend(model, options);
  else if (options.integrator == "dopri5") backend = make_dopri5_backend(model, options);
  else throw std::invalid_argument("unknown integrator '" + options.integrator + "'");

  SimulationResult result;
  EventHandler events(model, result);
  Mode mode = model.params().seat ? Mode::seated : Mode::attached;
  OdeState s;
  double t = t0;
  backend->restart(t, s, mode);

  // Every time the integration must reach: the outputs, the knots (restart there), the end.
  std::vector<double> stops;
  for (double k : knots)
    if (k > t0 && k < t1) stops.push_back(k);
  stops.push_back(t1);
  std::sort(stops.begin(), stops.end());
  std::size_t next_stop = 0, next_output = 0;
  while (next_output < output_times.size() && output_times[next_output] <= t0) {
    result.t.push_back(t0);
    result.state.push_back(s);
    result.mode.push_back(mode);
    ++next_output;
  }
  long event_count = 0, seated_evaluations = 0;
  const double seated_step = options.max_step > 0.0 ? options.max_step : (t1 - t0) / 1000.0;
  while (next_stop < stops.size()) {
    const double limit = stops[next_stop];
    const bool output_first = next_output < output_times.size() && output_times[next_output] < limit;
    const double target = output_first ? output_times[next_output] : limit;
    while (t < target) {
      if (target - t <= 8.0 * std::numeric_limits<double>::epsilon() * std::max(1.0, std::abs(t))) {
        t = target;  // an event fell within rounding of the target: the state is the same
        break;
      }
      if (mode == Mode::seated) {
        const auto lift_off = lift_off_between(model, t, target, seated_step, seated_evaluations);
        if (!lift_off) {
          t = target;  // still seated: the state is (0, 0)
          break;
        }
        t = *lift_off;
        if (++event_count > options.max_events)
          throw std::runtime_error("more than " + std::to_string(options.max_events) + " contact events (chattering)");
        events.handle(RootKind::lift_off, t, mode, s);
        backend->restart(t, s, mode);
        continue;
      }
      const BackendStep step = backend->advance(target, limit);
      t = step.t;
      s = step.state;
      if (step.root >= 0) {
        if (++event_count > options.max_events)
          throw std::runtime_error("more than " + std::to_string(options.max_events) + " contact events (chattering)");
        events.handle(root_kinds(model.params(), mode)[static_cast<std::size_t>(step.root)], t, mode, s);
        backend->restart(t, s, mode);
      }
    }
    if (output_first || (next_output < output_times.size() && output_times[next_output] == limit)) {
      result.t.push_back(t);
      result.state.push_back(s);
      result.mode.push_back(mode);
      ++next_output;
    }
    if (!output_first) {
      ++next_stop;
      if (next_stop < stops.size()) backend->restart(t, s, mode);  // a kink of the excitation
    }
  }
  backend->add_work(result.work);
  result.work["events"] = static_cast<double>(event_count);
  result.work["root_evaluations"] += static_cast<double>(seated_evaluations);
  return result;
}

}  // namespace mechgraph::valvetrain
