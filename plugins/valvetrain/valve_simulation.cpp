#include "valve_simulation.hpp"

#include <mechgraph/errors.hpp>
#include <mechgraph/printf_number.hpp>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <numbers>

namespace mechgraph::valvetrain {

namespace {

// K and M of the chain (positions only), valve off the seat, cam in contact; with `damping` the
// damping matrix B in place of K (the links' b_j, the coil elements' c_e, the massless spring none).
void chain_matrices(const ChainParams& c, Eigen::MatrixXd& K, Eigen::VectorXd& m, bool damping = false) {
  const std::size_t n = c.mass.size(), P = n + static_cast<std::size_t>(c.coils);
  K = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(P), static_cast<Eigen::Index>(P));
  m.resize(static_cast<Eigen::Index>(P));
  auto spring = [&](std::size_t a, long b, double k) {  // b < 0: to ground
    const auto ia = static_cast<Eigen::Index>(a);
    K(ia, ia) += k;
    if (b >= 0) {
      K(b, b) += k;
      K(ia, b) -= k;
      K(b, ia) -= k;
    }
  };
  const std::vector<double>& link = damping ? c.link_damping : c.link_stiffness;
  spring(0, -1, link[0]);  // the cam holds the first mass (bilateral)
  for (std::size_t j = 1; j < n; ++j) spring(j, static_cast<long>(j - 1), link[j]);
  if (c.coils == 0) {
    spring(n - 1, -1, damping ? 0.0 : c.spring_rate);
  } else {
    const double k_e = damping ? c.coil_damping : (c.coils + 1) * c.spring_rate;
    spring(n - 1, static_cast<long>(n), k_e);
    for (int e = 1; e < c.coils; ++e) spring(n + static_cast<std::size_t>(e) - 1, static_cast<long>(n) + e, k_e);
    spring(n + static_cast<std::size_t>(c.coils) - 1, -1, k_e);
  }
  for (std::size_t i = 0; i < P; ++i) m(static_cast<Eigen::Index>(i)) = i < n ? c.mass[i] : c.coil_mass;
}

// The links' damping b_j = beta k_j (stiffness-proportional, the spring undamped), beta such that
// the drive's first mode phi_1 (mass-normalised) has the damping ratio zeta:
//   zeta = phi_1' B phi_1 / (2 omega_1) = beta phi_1' K_links phi_1 / (2 omega_1).
// For one mass this is b = 2 zeta sqrt((k_d + c_s) M).
double link_damping_factor(const ChainParams& drive_alone, double zeta) {
  Eigen::MatrixXd K, K_links;
  Eigen::VectorXd m;
  chain_matrices(drive_alone, K, m);
  ChainParams links_only = drive_alone;
  links_only.spring_rate = 0.0;
  chain_matrices(links_only, K_links, m);
  const Eigen::VectorXd r = m.cwiseSqrt().cwiseInverse();
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(r.asDiagonal() * K * r.asDiagonal());
  const double omega_1 = std::sqrt(std::max(0.0, solver.eigenvalues()(0)));
  const Eigen::VectorXd phi = r.asDiagonal() * solver.eigenvectors().col(0);  // phi' M phi = 1
  return 2.0 * zeta * omega_1 / phi.dot(K_links * phi);
}

// The largest eigenvalue of the symmetric M^-1/2 A M^-1/2 bounded by Gershgorin's circles (the
// greatest absolute row sum): tight for a chain, where the fastest mode alternates mass by mass.
double scaled_row_sum_bound(const Eigen::MatrixXd& A, const Eigen::VectorXd& m) {
  const Eigen::VectorXd r = m.cwiseSqrt().cwiseInverse();
  return (r.asDiagonal() * A.cwiseAbs() * r.asDiagonal()).rowwise().sum().maxCoeff();
}

}  // namespace

IntegratorChoice choose_integrator(const ChainParams& chain, double step) {
  Eigen::MatrixXd K, B;
  Eigen::VectorXd m;
  chain_matrices(chain, K, m);
  chain_matrices(chain, B, m, true);
  IntegratorChoice choice;
  // Each mode of M x'' + B x' + K x = 0 has the eigenvalues of lambda^2 + d lambda + w^2 = 0: |lambda| = w
  // while underdamped, at most d when overdamped (stiffness-proportional damping overdamps the
  // fastest modes); both bounded from the matrices.
  const double omega = std::sqrt(std::max(0.0, scaled_row_sum_bound(K, m)));
  const double decay = scaled_row_sum_bound(B, m);
  choice.fastest_rate = std::max(omega, decay);
  choice.stiffness_ratio = choice.fastest_rate * step;
  choice.overdamped = decay >= omega;
  // Work per step cap, in multiply-adds of N = 2 P states: the explicit method needs ratio / limit
  // steps of 6 right-hand sides (O(N) each); BDF one step of a dense solve (N^2) and, every few
  // tens of steps, a dense LU (N^3 / 3). BDF only takes long steps over fast modes that decay
  // (real eigenvalues); a lightly damped fast oscillation must be resolved by both.
  const double N = 2.0 * static_cast<double>(m.size());
  const double explicit_work = std::max(1.0, choice.stiffness_ratio / IntegratorChoice::explicit_limit) * 6.0 * N;
  const double implicit_work = N * N + N * N * N / 60.0;
  choice.stiff = choice.stiffness_ratio > IntegratorChoice::explicit_limit && choice.overdamped && explicit_work > implicit_work;
  return choice;
}

std::string IntegratorChoice::reason() const {
  return "the fastest mode (|lambda| <= " + printf_g(fastest_rate, 3) + " 1/s, " +
         (overdamped ? "overdamped" : "oscillating") + ") times the step cap is " + printf_g(stiffness_ratio, 3) + ", " +
         (stiffness_ratio > explicit_limit ? "beyond" : "inside") + " dopri5's stability interval (" +
         printf_g(explicit_limit, 3) + "): " +
         (stiff ? "stiff, implicit BDF (cvode)" : "not stiff, explicit Dormand-Prince 5(4) (dopri5)");
}

std::vector<double> natural_frequencies(const ChainParams& chain) {
  Eigen::MatrixXd K;
  Eigen::VectorXd m;
  chain_matrices(chain, K, m);
  // M^-1/2 K M^-1/2 is symmetric with the same eigenvalues omega^2.
  const Eigen::VectorXd r = m.cwiseSqrt().cwiseInverse();
  const Eigen::MatrixXd A = r.asDiagonal() * K * r.asDiagonal();
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(A, Eigen::EigenvaluesOnly);
  std::vector<double> w;
  for (Eigen::Index i = 0; i < solver.eigenvalues().size(); ++i) w.push_back(std::sqrt(std::max(0.0, solver.eigenvalues()(i))));
  return w;
}

ChainParams build_chain(const SpringDesign& design, const DriveSettings& drive) {
  const double c_s = design.spring->stiffness(0.0);
  ChainParams c;
  c.preload = design.spring->preload();
  c.spring_rate = c_s;
  // The valve carries a third of the spring's mass unless the spring's coils are masses of their own.
  const double spring_share = drive.coils > 0 ? design.spring->effective_mass() : 0.0;
  if (!drive.multi_mass) {
    c.mass = {design.reduced_mass - spring_share};
    c.link_stiffness = {drive.stiffness};
  } else {
    const TrainMasses& m = *design.masses;
    const double back = m.arm_pushrod / m.arm_valve;
    c.mass = {m.tappet * back * back, m.pushrod * back * back, m.rocker_inertia / (m.arm_valve * m.arm_valve),
              design.reduced_mass - (m.tappet + m.pushrod) * back * back - m.rocker_inertia / (m.arm_valve * m.arm_valve) -
                  spring_share};
    const char* names[] = {"tappet_mass", "pushrod_mass", "rocker_inertia", "valve_mass"};
    for (int i = 0; i < 4; ++i)
      if (!(c.mass[static_cast<std::size_t>(i)] > 1e-6 * design.reduced_mass))
        throw NodeError("design", std::string("multi_mass needs every moving part: ") + names[i] +
                                      " is (nearly) 0 in the masses node (or use the single mass)");
    if (drive.stiffnesses.size() != 4)
      throw NodeError("stiffnesses", "multi_mass needs four stiffnesses (valve side): cam-tappet, tappet-pushrod, "
                                     "pushrod-rocker, rocker-valve");
    c.link_stiffness = drive.stiffnesses;
  }
  if (drive.coils > 0) {
    c.coils = drive.coils;
    // The coil masses are set so that the chain of p masses and p + 1 elements k_e = (p + 1) c_s,
    // held at both ends, has its first mode at the spring's surge frequency: that mode is
    // w_1 = 2 sqrt(k_e / m_e) sin(pi / (2 (p + 1))), so m_e = 4 k_e sin^2(pi / (2 (p + 1))) / w_s^2
    // (p m_e tends to the active coils' mass c_s / (2 f1)^2 as p grows).
    const double omega_s = 2.0 * std::numbers::pi * design.spring->surge_frequency();
    const double half_angle = std::sin(std::numbers::pi / (2.0 * (drive.coils + 1)));
    c.coil_mass = 4.0 * (drive.coils + 1) * c_s * half_angle * half_angle / (omega_s * omega_s);
    // Stiffness-proportional damping of the coils: the first surge mode at surge_damping_ratio.
    const double omega_surge = 2.0 * std::numbers::pi * design.spring->surge_frequency();
    c.coil_damping = 2.0 * drive.surge_damping_ratio / omega_surge * (drive.coils + 1) * c_s;
  }
  {
    // Stiffness-proportional damping of the drive's links, the spring undamped, the drive's first
    // mode at damping_ratio (link_damping_factor; for one mass b = 2 zeta sqrt((k_d + c_s) M)).
    c.link_damping.assign(c.link_stiffness.size(), 0.0);
    ChainParams drive_alone = c;  // the drive's first mode, not the spring's surge
    drive_alone.coils = 0;
    const double beta = link_damping_factor(drive_alone, drive.damping_ratio);
    for (std::size_t j = 0; j < c.link_stiffness.size(); ++j)
      c.link_damping[j] = beta * c.link_stiffness[j];
  }
  return c;
}

ValveSimulation simulate_valve(const ValveMotion& motion, const SpringDesign& design, const DriveSettings& drive,
                               const std::vector<double>& cam_angles, const std::vector<Monitor>& monitors) {
  constexpr double pi = std::numbers::pi;
  const double w = motion.camshaft_speed();
  ChainParams mp = build_chain(design, drive);
  mp.contact_loss = drive.contact_loss;
  mp.seat_impact = drive.seat_impact;
  mp.restitution = drive.restitution;
  mp.seating_speed = drive.seating_speed;
  // The lift limits act on the valve, the last mass of the chain.
  const double solid_lift = drive.coil_bind ? design.spring->solid_deflection() : std::numeric_limits<double>::infinity();
  if (drive.coil_bind && std::isfinite(solid_lift)) {
    if (!(solid_lift > 0.0))
      throw NodeError("design", "the spring is solid at the installed length (solid deflection " +
                                    printf_g(solid_lift * 1e3) + " mm): the valve cannot open");
    mp.limits.push_back({solid_lift, drive.coil_bind_stiffness,
                         restitution_damping(drive.coil_bind_restitution, drive.coil_bind_stiffness, mp.mass.back()), true,
                         "coil_bind"});
  }
  if (drive.stop)
    mp.limits.push_back({drive.stop_lift, drive.stop_stiffness,
                         restitution_damping(drive.stop_restitution, drive.stop_stiffness, mp.mass.back()), false, "stop"});
  // t = 0 at cam angle -pi (the base circle, valve seated).
  ValveSimulation sim{ChainModel(std::move(mp),
                                      [&motion, w](double t) {
                                        const LiftDerivatives d = motion.drive(-pi + w * t);
                                        return DriveValue{d.lift, w * d.velocity, w * w * d.acceleration};
                                      }),
                      {}, 2.0 * pi / w, 0.0, {}, {}, solid_lift};
  sim.last_start = (drive.revolutions - 1) * sim.period;
  const double h_max = motion.rocker_ratio() * motion.cam().max_lift() - motion.lash();
  SimulationOptions options;
  options.max_step = sim.period / 720.0;  // half a cam degree: no two events hide inside one step
  // `auto`: explicit where the chain is not stiff at that step, implicit where it is.
  sim.choice = choose_integrator(sim.model.params(), options.max_step);
  options.integrator = drive.integrator != "auto" ? drive.integrator : sim.choice.stiff ? "cvode" : "dopri5";
  sim.integrator = options.integrator;
  options.rtol = drive.tolerance;
  options.atol_x = drive.tolerance * h_max;
  options.atol_v = drive.tolerance * h_max * w;
  options.scan_step = sim.period / 720.0;  // half a cam degree: the seated valve's lift-off cannot hide
  // The excitation is not smooth at the cam's event ends and breakpoints: restart there.
  std::vector<double> cam_knots{motion.cam().event_begin(), motion.cam().event_end()};
  for (double b : motion.cam().breakpoints()) cam_knots.push_back(b);
  std::vector<double> knots;
  for (int r = 0; r < drive.revolutions; ++r)
    for (double k : cam_knots) knots.push_back((r + (k + pi) / (2.0 * pi)) * sim.period);
  std::sort(knots.begin(), knots.end());
  // The base circle (outside the cam's event the lift is 0 by the CamLaw contract): the drive stands
  // at -lash there, from each event's end to the next one's beginning (same times as the knots).
  const auto at_angle = [&](int r, double angle) { return (r + (angle + pi) / (2.0 * pi)) * sim.period; };
  const double event_begin = motion.cam().event_begin(), event_end = motion.cam().event_end();
  options.quiet.push_back({0.0, at_angle(0, event_begin)});
  for (int r = 0; r < drive.revolutions; ++r)
    options.quiet.push_back({at_angle(r, event_end), r + 1 < drive.revolutions ? at_angle(r + 1, event_begin)
                                                                               : drive.revolutions * sim.period});
  std::vector<double> times;
  const double end = drive.revolutions * sim.period;
  for (double a : cam_angles) times.push_back(std::min(end, sim.last_start + (a + pi) / w));  // phi = pi: the very end
  try {
    sim.run = simulate(sim.model, 0.0, end, times, knots, options, monitors);
  } catch (const std::runtime_error& e) {
    throw NodeError("tolerance", std::string("the simulation failed: ") + e.what() + " (loosen tolerance, or try integrator: " +
                                     (options.integrator == "cvode" ? "dopri5" : "cvode") + ")");
  }
  return sim;
}

}  // namespace mechgraph::valvetrain
