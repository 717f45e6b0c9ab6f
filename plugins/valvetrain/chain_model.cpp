#include "chain_model.hpp"

#include "ode_backend.hpp"

#include <boost/math/tools/roots.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>

namespace mechgraph::valvetrain {

ChainModel::ChainModel(ChainParams p, Excitation y) : p_(std::move(p)), y_(std::move(y)) {
  positions_ = p_.mass.size() + static_cast<std::size_t>(p_.coils);
}

double ChainModel::cam_force(double t, const ChainState& s) const {
  double y = 0.0, dy = 0.0;
  y_(t, y, dy);
  return p_.link_stiffness[0] * (y - s[0]) + p_.link_damping[0] * (dy - s[positions_]);
}

double ChainModel::pushing_force(double t, const ChainState& s) const {
  if (!p_.contact_loss) return cam_force(t, s);  // bilateral: the drive may pull
  double y = 0.0, dy = 0.0;
  y_(t, y, dy);
  // Unilateral: nothing across an open gap, and the damper cannot pull.
  return y > s[0] ? std::max(0.0, cam_force(t, s)) : 0.0;
}

void ChainModel::forces(const Mode& m, double t, const ChainState& s, std::vector<double>& f) const {
  const std::size_t n = p_.mass.size(), P = positions_, v = valve();
  f.assign(P, 0.0);
  if (m.contact) f[0] += pushing_force(t, s);
  for (std::size_t j = 1; j < n; ++j) {
    const double link = p_.link_stiffness[j] * (s[j - 1] - s[j]) + p_.link_damping[j] * (s[P + j - 1] - s[P + j]);
    f[j - 1] -= link;
    f[j] += link;
  }
  f[v] -= p_.preload;  // every element of the spring carries the preload; on the coils it cancels
  if (p_.coils == 0) {
    f[v] -= p_.spring_rate * s[v];
  } else {
    // Elements e = 0..p: from the valve (e = 0) through the coils to the head (fixed).
    const double k_e = (p_.coils + 1) * p_.spring_rate, c_e = p_.coil_damping;
    for (int e = 0; e <= p_.coils; ++e) {
      const std::size_t a = e == 0 ? v : n + static_cast<std::size_t>(e) - 1;
      const bool to_head = e == p_.coils;
      const std::size_t b = n + static_cast<std::size_t>(e);
      const double compression = k_e * (s[a] - (to_head ? 0.0 : s[b])) + c_e * (s[P + a] - (to_head ? 0.0 : s[P + b]));
      f[a] -= compression;
      if (!to_head) f[b] += compression;
    }
  }
  if (m.seated) f[v] = 0.0;  // the seat takes whatever pushes the valve down
}

double ChainModel::force_on_valve(double t, const ChainState& s) const {
  thread_local std::vector<double> f;  // scratch: called in the integrators' inner loops
  forces(Mode{false, true}, t, s, f);
  return f[valve()];
}

void ChainModel::rhs(const Mode& m, double t, const ChainState& s, ChainState& ds) const {
  const std::size_t P = positions_, n = p_.mass.size();
  thread_local std::vector<double> f;  // scratch: called in the integrators' inner loops
  forces(m, t, s, f);
  ds.resize(2 * P);
  for (std::size_t i = 0; i < P; ++i) {
    const bool frozen = m.seated && i == valve();
    ds[i] = frozen ? 0.0 : s[P + i];
    ds[P + i] = frozen ? 0.0 : f[i] / (i < n ? p_.mass[i] : p_.coil_mass);
  }
}

std::vector<RootKind> ChainModel::root_kinds(const Mode& m) const {
  std::vector<RootKind> k;
  if (p_.seat) k.push_back(m.seated ? RootKind::lift_off : RootKind::landing);
  if (p_.contact_loss && !(m.seated && rigid_when_seated())) {
    if (m.contact) {
      k.push_back(RootKind::contact_loss);
    } else {
      k.push_back(RootKind::contact_by_position);
      k.push_back(RootKind::contact_by_force);
    }
  }
  return k;
}

std::vector<int> ChainModel::root_directions(const Mode& m) const {
  std::vector<int> d;
  for (RootKind k : root_kinds(m)) d.push_back(k == RootKind::landing || k == RootKind::contact_loss ? -1 : +1);
  return d;
}

void ChainModel::roots(const Mode& m, double t, const ChainState& s, double* g) const {
  const auto kinds = root_kinds(m);
  for (std::size_t i = 0; i < kinds.size(); ++i) {
    switch (kinds[i]) {
      case RootKind::lift_off: g[i] = force_on_valve(t, s); break;
      case RootKind::landing: g[i] = s[valve()]; break;
      case RootKind::contact_loss:
      case RootKind::contact_by_force: g[i] = cam_force(t, s); break;
      case RootKind::contact_by_position: {
        double y = 0.0, dy = 0.0;
        y_(t, y, dy);
        g[i] = y - s[0];
        break;
      }
    }
  }
}

std::vector<double> ChainModel::jacobian(const Mode& m) const {
  // Within a mode the right-hand side is affine in the state: column i is rhs(e_i) - rhs(0).
  const std::size_t N = 2 * positions_;
  std::vector<double> J(N * N, 0.0);
  ChainState zero(N, 0.0), unit(N, 0.0), base, col;
  rhs(m, 0.0, zero, base);
  for (std::size_t i = 0; i < N; ++i) {
    unit[i] = 1.0;
    rhs(m, 0.0, unit, col);
    unit[i] = 0.0;
    for (std::size_t r = 0; r < N; ++r) J[r * N + i] = col[r] - base[r];
  }
  return J;
}

namespace {

// The hybrid automaton: what an event does to the mode and the state.
class EventHandler {
 public:
  EventHandler(const ChainModel& model, SimulationResult& result) : model_(model), p_(model.params()), result_(result) {}

  void handle(RootKind kind, double t, Mode& mode, ChainState& s) {
    switch (kind) {
      case RootKind::lift_off:
        result_.events.push_back({t, "lift_off", 0.0});
        mode.seated = false;
        if (model_.rigid_when_seated()) mode.contact = true;  // it lifts because the cam pushes
        bounces_ = 0;
        return;
      case RootKind::landing: land(t, mode, s); return;
      case RootKind::contact_loss:
        result_.events.push_back({t, "contact_loss", 0.0});
        mode.contact = false;
        return;
      case RootKind::contact_by_position:
        result_.events.push_back({t, "contact_regain", 0.0});
        mode.contact = true;
        return;
      case RootKind::contact_by_force: {
        // The force turns positive while the cam is still clear of the chain: no contact yet.
        double y = 0.0, dy = 0.0;
        model_.excitation(t, y, dy);
        if (y - s[0] > 0.0) {
          result_.events.push_back({t, "contact_regain", 0.0});
          mode.contact = true;
        }
        return;
      }
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

// While a one-mass valve is seated nothing moves: the lift-off is a root of the force on it, a
// function of the excitation alone, found by sampling at `step` and TOMS 748, no integration.
std::optional<double> lift_off_between(const ChainModel& model, double t0, double t1, double step, long& evaluations) {
  const ChainState rest(2 * model.positions(), 0.0);
  auto g = [&](double t) {
    ++evaluations;
    return model.force_on_valve(t, rest);
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

// The state at rest at t0 with the valve seated: the masses between cam and valve where their
// links balance (bilateral contact), or untouched where the cam is clear of the chain (contact loss).
ChainState rest_state(const ChainModel& model, double t0, Mode& mode) {
  const ChainParams& p = model.params();
  ChainState s(2 * model.positions(), 0.0);
  double y = 0.0, dy = 0.0;
  model.excitation(t0, y, dy);
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

}  // namespace

SimulationResult simulate(const ChainModel& model, double t0, double t1, const std::vector<double>& output_times,
                          const std::vector<double>& knots, const SimulationOptions& options) {
  std::unique_ptr<OdeBackend> backend;
  if (options.integrator == "cvode") backend = make_cvode_backend(model, options);
  else if (options.integrator == "dopri5") backend = make_dopri5_backend(model, options);
  else throw std::invalid_argument("unknown integrator '" + options.integrator + "'");

  SimulationResult result;
  EventHandler events(model, result);
  Mode mode{model.params().seat, true};
  ChainState s = rest_state(model, t0, mode);
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
  const double seated_step = options.scan_step > 0.0  ? options.scan_step
                             : options.max_step > 0.0 ? options.max_step
                                                      : (t1 - t0) / 1000.0;
  auto count_event = [&] {
    if (++event_count > options.max_events)
      throw std::runtime_error("more than " + std::to_string(options.max_events) + " contact events (chattering)");
  };
  while (next_stop < stops.size()) {
    const double limit = stops[next_stop];
    const bool output_first = next_output < output_times.size() && output_times[next_output] < limit;
    const double target = output_first ? output_times[next_output] : limit;
    while (t < target) {
      if (target - t <= 8.0 * std::numeric_limits<double>::epsilon() * std::max(1.0, std::abs(t))) {
        t = target;  // an event fell within rounding of the target: the state is the same
        break;
      }
      if (mode.seated && model.rigid_when_seated()) {
        const auto lift_off = lift_off_between(model, t, target, seated_step, seated_evaluations);
        if (!lift_off) {
          t = target;  // still seated: nothing moved
          break;
        }
        t = *lift_off;
        count_event();
        events.handle(RootKind::lift_off, t, mode, s);
        backend->restart(t, s, mode);
        continue;
      }
      const BackendStep step = backend->advance(target, limit);
      t = step.t;
      s = step.state;
      if (step.root >= 0) {
        count_event();
        events.handle(model.root_kinds(mode)[static_cast<std::size_t>(step.root)], t, mode, s);
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
  if (next_output < output_times.size())
    throw std::logic_error("simulate: output times after the end of the run (" + std::to_string(output_times[next_output]) +
                           " s > " + std::to_string(t1) + " s)");
  backend->add_work(result.work);
  result.work["events"] = static_cast<double>(event_count);
  result.work["root_evaluations"] += static_cast<double>(seated_evaluations);
  return result;
}

}  // namespace mechgraph::valvetrain
