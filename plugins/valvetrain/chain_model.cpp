// The chain model's forces, rates and event functions (chain_model.hpp).
#include "chain_model.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace mechgraph::valvetrain {

// A linear spring-damper contact entered at speed v by a free mass: delta'' + 2 zeta w delta' +
// w^2 delta = 0 from delta = 0, delta' = v; it leaves at delta = 0 after half a damped period with
// speed v exp(-pi zeta / sqrt(1 - zeta^2)) = e v, so zeta = -ln e / sqrt(pi^2 + ln^2 e), c = 2 zeta sqrt(k m).
double restitution_damping(double restitution, double stiffness, double mass) {
  const double log_e = std::log(restitution);
  const double zeta = -log_e / std::sqrt(std::numbers::pi * std::numbers::pi + log_e * log_e);
  return 2.0 * zeta * std::sqrt(stiffness * mass);
}

ChainModel::ChainModel(ChainParams p, Excitation y) : p_(std::move(p)), y_(std::move(y)) {
  positions_ = p_.mass.size() + static_cast<std::size_t>(p_.coils);
  if (p_.limits.size() > ChainParams::max_limits)
    throw std::invalid_argument("ChainModel: at most " + std::to_string(ChainParams::max_limits) + " lift limits");
  list_roots();
}

double ChainModel::cam_force(const DriveValue& e, const ChainState& s) const {
  return p_.link_stiffness[0] * (e.y - s[0]) + p_.link_damping[0] * (e.rate - s[positions_]);
}

bool ChainModel::pushes(const DriveValue& e, const ChainState& s) const {
  // Unilateral: nothing across an open gap, and the damper cannot pull.
  return !p_.contact_loss || (e.y > s[0] && cam_force(e, s) > 0.0);
}

double ChainModel::pushing_force(const DriveValue& e, const ChainState& s) const {
  return pushes(e, s) ? cam_force(e, s) : 0.0;
}

double ChainModel::force_after_event(const DriveValue& e, const ChainState& s) const {
  if (!p_.contact_loss) return cam_force(e, s);  // bilateral: the force as it is, a pull included
  return std::max(0.0, cam_force(e, s));
}

void ChainModel::forces(const Mode& m, double y, double dy, const ChainState& s, bool pushing, bool rates, double* f) const {
  const std::size_t n = p_.mass.size(), P = positions_, v = valve();
  std::fill(f, f + P, 0.0);
  if (m.contact && pushing) f[0] += p_.link_stiffness[0] * (y - s[0]) + p_.link_damping[0] * (dy - s[P]);
  for (std::size_t j = 1; j < n; ++j) {
    const double link = p_.link_stiffness[j] * (s[j - 1] - s[j]) + p_.link_damping[j] * (s[P + j - 1] - s[P + j]);
    f[j - 1] -= link;
    f[j] += link;
  }
  if (!rates) f[v] -= p_.preload;  // every element of the spring carries the preload; on the coils it cancels
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
  for (std::size_t i = 0; i < p_.limits.size(); ++i)
    if (m.engaged & (1u << i)) {
      const LiftLimit& l = p_.limits[i];
      f[v] -= l.stiffness * (s[v] - (rates ? 0.0 : l.lift)) + l.damping * s[P + v];
    }
  if (m.seated) f[v] = 0.0;  // the seat takes whatever pushes the valve down
}

double ChainModel::limit_force(std::size_t i, const ChainState& s) const {
  const LiftLimit& l = p_.limits[i];
  return l.stiffness * (s[valve()] - l.lift) + l.damping * s[positions_ + valve()];
}

double ChainModel::limit_force_rate(std::size_t i, const Snapshot& x) const {
  const LiftLimit& l = p_.limits[i];
  return l.stiffness * x.rate[valve()] + l.damping * x.rate[positions_ + valve()];
}

double ChainModel::force_on_valve(const DriveValue& e, const ChainState& s) const {
  thread_local std::vector<double> f;  // scratch: called in the integrators' inner loops
  f.resize(positions_);
  forces(Mode{false, true}, e.y, e.rate, s, pushes(e, s), false, f.data());
  return f[valve()];
}

double ChainModel::spring_force(const ChainState& s, unsigned engaged) const {
  const std::size_t v = valve(), P = positions_, z = p_.mass.size();
  double bind = 0.0;
  for (std::size_t i = 0; i < p_.limits.size(); ++i)
    if ((engaged & (1u << i)) && p_.limits[i].in_spring) bind += limit_force(i, s);
  if (p_.coils == 0) return p_.preload + p_.spring_rate * s[v] + bind;
  return p_.preload + (p_.coils + 1) * p_.spring_rate * (s[v] - s[z]) + p_.coil_damping * (s[P + v] - s[P + z]) + bind;
}

void ChainModel::rhs(const Mode& m, double t, const ChainState& s, ChainState& ds) const { rates(m, y_(t), s, ds); }

void ChainModel::rhs(const Mode& m, double t, const ChainState& s, ChainState& ds, DriveValue& drive) const {
  drive = y_(t);
  rates(m, drive, s, ds);
}

void ChainModel::rates(const Mode& m, const DriveValue& e, const ChainState& s, ChainState& ds) const {
  const std::size_t P = positions_, n = p_.mass.size();
  ds.resize(2 * P);
  if (P == 1) {
    // The single mass, forces() written out (the integrators' inner loop; same operations, same
    // order): M x'' = F_c - P0 - c_s x, F_c = k_d (y - x) + b_d (y' - x') while the cam pushes.
    if (m.seated) {
      ds[0] = ds[1] = 0.0;
      return;
    }
    double f = m.contact && pushes(e, s) ? p_.link_stiffness[0] * (e.y - s[0]) + p_.link_damping[0] * (e.rate - s[1]) : 0.0;
    f -= p_.preload;
    f -= p_.spring_rate * s[0];
    if (m.engaged)
      for (std::size_t i = 0; i < p_.limits.size(); ++i)
        if (m.engaged & (1u << i)) f -= p_.limits[i].stiffness * (s[0] - p_.limits[i].lift) + p_.limits[i].damping * s[1];
    ds[0] = s[1];
    ds[1] = f / p_.mass[0];
    return;
  }
  forces(m, e.y, e.rate, s, pushes(e, s), false, ds.data() + P);  // the forces, then / mass
  for (std::size_t i = 0; i < P; ++i) {
    const bool frozen = m.seated && i == valve();
    ds[i] = frozen ? 0.0 : s[P + i];
    ds[P + i] = frozen ? 0.0 : ds[P + i] / (i < n ? p_.mass[i] : p_.coil_mass);
  }
}

void ChainModel::snapshot(double t, const ChainState& s, const Mode& m, Snapshot& out) const {
  out.t = t;
  out.mode = m;
  out.state = s;
  out.drive = y_(t);
  rates(m, out.drive, s, out.rate);
}

// Rates: d/dt F_c = k_0 (y' - x_0') + c_0 (y'' - x_0''), the others through forces() applied to
// the state's rate and the drive's (y', y'') without the constant preload.
double ChainModel::cam_force_rate(const Snapshot& x) const {
  const std::size_t P = positions_;
  return p_.link_stiffness[0] * (x.drive.rate - x.state[P]) + p_.link_damping[0] * (x.drive.acceleration - x.rate[P]);
}

double ChainModel::pushing_force_rate(const Snapshot& x) const {
  return pushes(x.drive, x.state) ? cam_force_rate(x) : 0.0;
}

double ChainModel::force_on_valve_rate(const Snapshot& x) const {
  thread_local std::vector<double> f;
  f.resize(positions_);
  forces(Mode{false, true}, x.drive.rate, x.drive.acceleration, x.rate, pushes(x.drive, x.state), true, f.data());
  return f[valve()];
}

double ChainModel::spring_force_rate(const Snapshot& x) const {
  const std::size_t v = valve(), P = positions_, z = p_.mass.size();
  double bind = 0.0;
  for (std::size_t i = 0; i < p_.limits.size(); ++i)
    if ((x.mode.engaged & (1u << i)) && p_.limits[i].in_spring) bind += limit_force_rate(i, x);
  if (p_.coils == 0) return p_.spring_rate * x.rate[v] + bind;
  return (p_.coils + 1) * p_.spring_rate * (x.rate[v] - x.rate[z]) + p_.coil_damping * (x.rate[P + v] - x.rate[P + z]) + bind;
}

// The event functions of each mode, listed once (they are asked for at every step).
void ChainModel::list_roots() {
  const unsigned limit_states = 1u << p_.limits.size();
  for (unsigned engaged = 0; engaged < limit_states; ++engaged)
    for (int i = 0; i < 4; ++i) {
      const Mode m{(i & 1) != 0, (i & 2) != 0, engaged};
      if (m.seated && engaged) continue;  // the limits sit above the seat
      const int at = index(m);
      std::vector<RootKind>& k = kinds_[at];
      std::vector<int>& limit = limit_of_root_[at];
      if (p_.seat) k.push_back(m.seated ? RootKind::lift_off : RootKind::landing);
      if (p_.contact_loss && !(m.seated && rigid_when_seated())) {
        if (m.contact) {
          k.push_back(RootKind::contact_loss);
        } else {
          k.push_back(RootKind::contact_by_position);
          k.push_back(RootKind::contact_by_force);
        }
      }
      limit.assign(k.size(), -1);
      if (!m.seated)
        for (std::size_t j = 0; j < p_.limits.size(); ++j) {
          k.push_back((engaged & (1u << j)) ? RootKind::limit_release : RootKind::limit_engage);
          limit.push_back(static_cast<int>(j));
        }
      for (RootKind r : k)
        directions_[at].push_back(r == RootKind::landing || r == RootKind::contact_loss || r == RootKind::limit_release ? -1 : +1);
    }
}

void ChainModel::roots(const Snapshot& x, double* g, double* dg) const {
  const std::vector<RootKind>& kinds = root_kinds(x.mode);
  const std::size_t v = valve(), P = positions_;
  for (std::size_t i = 0; i < kinds.size(); ++i) {
    switch (kinds[i]) {
      case RootKind::lift_off:
        g[i] = force_on_valve(x.drive, x.state);
        if (dg) dg[i] = force_on_valve_rate(x);
        break;
      case RootKind::landing:
        g[i] = x.state[v];
        if (dg) dg[i] = x.state[P + v];
        break;
      case RootKind::contact_loss:
      case RootKind::contact_by_force:
        g[i] = cam_force(x.drive, x.state);
        if (dg) dg[i] = cam_force_rate(x);
        break;
      case RootKind::contact_by_position:
        g[i] = x.drive.y - x.state[0];
        if (dg) dg[i] = x.drive.rate - x.state[P];
        break;
      case RootKind::limit_engage:
      case RootKind::limit_release: {
        const double lift = p_.limits[static_cast<std::size_t>(root_limits(x.mode)[i])].lift;
        g[i] = x.state[v] - lift;
        if (dg) dg[i] = x.state[P + v];
        break;
      }
    }
  }
}

std::vector<double> ChainModel::jacobian(const Mode& m) const {
  // Within a mode the right-hand side is affine in the state: column i is its linear part applied
  // to e_i (the cam's force counted wherever the mode has contact).
  const std::size_t N = 2 * positions_, P = positions_, n = p_.mass.size();
  std::vector<double> J(N * N, 0.0), f(P);
  ChainState unit(N, 0.0);
  for (std::size_t i = 0; i < N; ++i) {
    unit[i] = 1.0;
    forces(m, 0.0, 0.0, unit, true, true, f.data());
    for (std::size_t r = 0; r < P; ++r) {
      const bool frozen = m.seated && r == valve();
      J[r * N + i] = frozen ? 0.0 : unit[P + r];
      J[(P + r) * N + i] = frozen ? 0.0 : f[r] / (r < n ? p_.mass[r] : p_.coil_mass);
    }
    unit[i] = 0.0;
  }
  return J;
}

}  // namespace mechgraph::valvetrain
