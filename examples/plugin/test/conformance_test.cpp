// The example plugin's own test: the SDK's conformance suites on both node types, plus the closed
// form of the parabolic law (peak acceleration 4 H / beta^2 = 16 H / action_angle^2).
#include "../src/example_types.hpp"

#include <mechgraph/testing/node_conformance.hpp>

#include <cmath>
#include <iostream>
#include <numbers>

int main() {
  using namespace mechgraph::testing;
  int failures = 0;
  NodeCheckOptions cam;
  cam.cam_law.continuity = 1;  // the parabolic law is C1: velocity continuous, acceleration steps
  for (const auto& [type, options] : {std::pair{example::make_parabolic_cam(), cam}, {example::make_slot_joint(), NodeCheckOptions{}}}) {
    const Report report = check_node_type(*type, options);
    std::cout << report.str();
    failures += report.failed();
  }
  // The closed form, through the harness (parameters as scene text).
  const auto type = example::make_parabolic_cam();
  const auto run = run_node(*type, params_with_defaults(type->info(), {{"max_lift", "8 mm"}, {"action_angle", "120 deg"}}));
  const double expected = 16.0 * 8e-3 / std::pow(120.0 * std::numbers::pi / 180.0, 2);
  const double got = run.outputs.all().at("max_acceleration").as_scalar();
  if (std::abs(got - expected) > 1e-12 * expected) {
    std::cout << "FAIL  max_acceleration " << got << " m/rad^2, closed form " << expected << "\n";
    ++failures;
  }
  std::cout << (failures ? "FAILED\n" : "all passed\n");
  return failures ? 1 : 0;
}
