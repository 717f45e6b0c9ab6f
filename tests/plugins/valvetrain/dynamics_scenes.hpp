#pragma once
// Scenes for the valve train's dynamics tests: the study's cam, valve, masses, spring and spring
// design with a dynamics (or float speed) node that the test varies.
#include "test_support.hpp"

#include <stdexcept>
#include <string>
#include <vector>

namespace mechgraph::testing::dynamics {

inline RunResult run_scene(const std::string& yaml, const std::vector<Override>& overrides = {}) {
  return run_yaml(yaml, project_registry(), overrides);
}

inline double num(const RunResult& r, const std::string& label) { return scalar_output(r, label); }

inline const NodeRun& node_run(const RunResult& r, const std::string& name) {
  for (const NodeRun& n : r.runs)
    if (n.node == name) return n;
  throw std::runtime_error("no run of " + name);
}

// A cam, valve, masses, spring and spring design as in the study; `cam` and `dyn` vary.
inline std::string dynamics_scene(const std::string& cam, const std::string& dyn, const std::string& outputs,
                                  const std::string& rpm = "5600 rpm", const std::string& lash = "0.25 mm",
                                  const std::string& extra_nodes = "") {
  return "nodes:\n" + extra_nodes + "  cam: " + cam + R"(
  v:      { type: valvetrain.valve_motion, inputs: { cam: cam.law }, params: { rpm: )" + rpm + ", rocker_ratio: 1.5, lash: " + lash + R"( } }
  train:  { type: valvetrain.masses, params: { valve_mass: 55 g, retainer_mass: 18 g, tappet_mass: 60 g, pushrod_mass: 50 g,
                                               rocker_inertia: 4e-5 kg*m^2, arm_valve: 45 mm, arm_pushrod: 30 mm } }
  spring: { type: spring.helical }
  sd:     { type: valvetrain.spring_design, inputs: { valve: v.motion, spring: spring.model, masses: train.masses } }
  dyn: )" + dyn + R"(
outputs: [ )" + outputs + " ]\n";
}

inline const std::string kurz = "{ type: cam.kurz, params: { max_lift: 8 mm, action_angle: 130 deg, accel_angle: 18 deg, base_radius: 17 mm } }";

// A second valve motion `fast` of the same cam at another crank speed (the spring stays designed for `v`).
inline std::string fast_valve(double rpm) {
  return "  fast: { type: valvetrain.valve_motion, inputs: { cam: cam.law }, params: { rpm: " + std::to_string(rpm) +
         " rpm, rocker_ratio: 1.5, lash: 0.25 mm } }\n";
}

}  // namespace mechgraph::testing::dynamics
