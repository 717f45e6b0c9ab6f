#include "valve_simulation.hpp"

#include <mechgraph/errors.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace mechgraph::valvetrain {

ValveSimulation simulate_valve(const ValveMotion& motion, const SpringDesign& design, const DriveSettings& drive,
                               const std::vector<double>& cam_angles) {
  constexpr double pi = std::numbers::pi;
  const double w = motion.camshaft_speed();
  const double c_s = design.spring->stiffness(0.0);
  SingleMassParams mp;
  mp.mass = design.reduced_mass;
  mp.drive_stiffness = drive.stiffness;
  mp.drive_damping = 2.0 * drive.damping_ratio * std::sqrt((drive.stiffness + c_s) * design.reduced_mass);
  mp.preload = design.spring->preload();
  mp.spring_rate = c_s;
  mp.contact_loss = drive.contact_loss;
  mp.seat_impact = drive.seat_impact;
  mp.restitution = drive.restitution;
  mp.seating_speed = drive.seating_speed;
  // t = 0 at cam angle -pi (the base circle, valve seated).
  ValveSimulation sim{SingleMassModel(mp,
                                      [&motion, w](double t, double& y, double& dy) {
                                        const LiftDerivatives d = motion.drive(-pi + w * t);
                                        y = d.lift;
                                        dy = w * d.velocity;
                                      }),
                      {}, 2.0 * pi / w, 0.0};
  sim.last_start = (drive.revolutions - 1) * sim.period;
  const double h_max = motion.rocker_ratio() * motion.cam().max_lift() - motion.lash();
  SimulationOptions options;
  options.integrator = drive.integrator;
  options.rtol = drive.tolerance;
  options.atol_x = drive.tolerance * h_max;
  options.atol_v = drive.tolerance * h_max * w;
  options.max_step = sim.period / 720.0;  // half a cam degree: no two events hide inside one step
  // The excitation is not smooth at the cam's event ends and breakpoints: restart there.
  std::vector<double> cam_knots{motion.cam().event_begin(), motion.cam().event_end()};
  for (double b : motion.cam().breakpoints()) cam_knots.push_back(b);
  std::vector<double> knots;
  for (int r = 0; r < drive.revolutions; ++r)
    for (double k : cam_knots) knots.push_back((r + (k + pi) / (2.0 * pi)) * sim.period);
  std::sort(knots.begin(), knots.end());
  std::vector<double> times;
  for (double a : cam_angles) times.push_back(sim.last_start + (a + pi) / w);
  try {
    sim.run = simulate(sim.model, 0.0, drive.revolutions * sim.period, times, knots, options);
  } catch (const std::runtime_error& e) {
    throw NodeError("tolerance", std::string("the simulation failed: ") + e.what() + " (loosen tolerance, or try integrator: " +
                                     (options.integrator == "cvode" ? "dopri5" : "cvode") + ")");
  }
  return sim;
}

}  // namespace mechgraph::valvetrain
