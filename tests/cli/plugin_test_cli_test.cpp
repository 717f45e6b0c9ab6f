// `mechgraph plugin-test` (the conformance suites as a product) and the host's enforcement of the
// CamLaw contract on every law a node outputs (sdk/src/cam_law.cpp).
#include "test_support.hpp"

#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

using namespace mechgraph::testing;
using Catch::Matchers::Contains;

namespace {

std::string bad_laws() { return "--only-plugin-dir '" + test_plugin("test_bad_laws").parent_path().string() + "' "; }

std::string skewed_scene(const std::string& name, const std::string& params) {
  const auto path = std::filesystem::temp_directory_path() / ("mg_skewed_" + std::to_string(::getpid()) + "_" + name + ".yaml");
  std::ofstream(path) << "nodes:\n  c: { type: test.skewed_cam, params: { " << params << " } }\noutputs: [c.max_lift]\n";
  return path.string();
}

}  // namespace

TEST_CASE("plugin-test passes every built-in plugin with its declared defaults and examples", "[plugins][sdk][cli]") {
  for (const auto& entry : std::filesystem::directory_iterator(MECHGRAPH_PLUGIN_DIR)) {
    if (entry.path().extension() != ".so") continue;
    INFO(entry.path().string());
    const auto r = run_cli("plugin-test --threads 2 '" + entry.path().string() + "'");
    INFO(r.out << r.err);
    CHECK(r.exit_code == 0);
    CHECK_THAT(r.out, Contains("PASS") && !Contains("FAIL"));
  }
  // The cam laws the issue names, with the derivatives they promise continuous at their breakpoints.
  const auto r = run_cli("plugin-test --continuity cam.cycloidal=2 --continuity cam.poly345=2 --continuity cam.poly4567=3 "
                         "cam.cycloidal cam.poly345 cam.poly4567");
  INFO(r.out << r.err);
  CHECK(r.exit_code == 0);
  CHECK_THAT(r.out, Contains("PASS  cam_law cam.cycloidal.law: continuous at breakpoints and event ends up to the acceleration") &&
                        Contains("PASS  cam_law cam.poly4567.law: velocity is the derivative of the lift") &&
                        Contains("PASS  node cam.poly345: thread-safe"));
}

TEST_CASE("plugin-test feeds handle inputs from other loaded types and reports per check", "[plugins][sdk][cli]") {
  const auto r = run_cli("plugin-test --threads 2 valvetrain.valve_motion --set valvetrain.valve_motion.rpm=6000rpm");
  INFO(r.out << r.err);
  CHECK(r.exit_code == 0);
  CHECK_THAT(r.err, Contains("input 'cam' (cam_law) from cam."));
  CHECK_THAT(r.out, Contains("PASS  node valvetrain.valve_motion: evaluates with its defaults") &&
                        Contains("PASS  node valvetrain.valve_motion: reports its work on declared counters (evaluations"));
  const auto json = run_cli("plugin-test --json --threads 0 cam.harmonic");
  CHECK(json.exit_code == 0);
  CHECK_THAT(json.out, Contains("\"type\":\"cam.harmonic\"") && Contains("\"status\":\"passed\"") && Contains("\"failed\":0"));
}

TEST_CASE("plugin-test fails a law the host cannot catch cheaply, refuses a plugin it cannot load", "[plugins][sdk][cli]") {
  const auto wrong = run_cli(bad_laws() + "plugin-test --threads 0 --set test.skewed_cam.defect=wrong_velocity '" +
                             test_plugin("test_bad_laws").string() + "'");
  INFO(wrong.out << wrong.err);
  CHECK(wrong.exit_code == 6);
  CHECK_THAT(wrong.out, Contains("FAIL  cam_law test.skewed_cam.law: velocity is the derivative of the lift (at "));
  CHECK_THAT(wrong.out, Contains("FAIL  cam_law test.skewed_cam.law: acceleration is the derivative of the velocity"));
  CHECK_THAT(wrong.out, Contains("PASS  cam_law test.skewed_cam.law: jerk is the derivative of the acceleration") &&
                            Contains("PASS  cam_law test.skewed_cam.law: continuous at breakpoints and event ends up to the lift"));
  const auto foreign = run_cli("plugin-test '" + test_plugin("test_fingerprint").string() + "'");
  CHECK(foreign.exit_code == 4);
  CHECK_THAT(foreign.err, Contains("C++ standard: plugin C++23"));
  const auto unknown = run_cli("plugin-test cam.cycloidl");
  CHECK(unknown.exit_code == 2);
  CHECK_THAT(unknown.err, Contains("cam.cycloidal"));
}

TEST_CASE("the host refuses a cam law that breaks its contract, naming the node type, nothing is wrapped", "[plugins][sdk][cli]") {
  struct Case {
    const char* params;
    const char* expected;
  };
  const Case cases[] = {
      {"rise: 250 deg, return: 50 deg", "event begins at -250 deg, at or before -180 deg"},
      {"rise: 50 deg, return: 200 deg", "event ends at 200 deg, at or after 180 deg"},
      {"defect: unsorted_breakpoints", "breakpoints are not sorted ascending"},
      {"defect: breakpoint_outside", "breakpoint -120 deg is not strictly inside the event"},
      {"defect: negative_lift", "a negative lift (-0.00185336 m) at -56.25 deg"},
      {"defect: nan", "a NaN or infinite lift or derivative at"},
  };
  int i = 0;
  for (const Case& c : cases) {
    const auto r = run_cli(bad_laws() + "run '" + skewed_scene(std::to_string(i++), c.params) + "'");
    INFO(c.params << "\n" << r.err);
    CHECK(r.exit_code == 3);
    CHECK_THAT(r.err, Contains("node 'c' (test.skewed_cam) produced a cam_law at output 'law' that breaks the cam_law contract") &&
                          Contains(c.expected));
  }
  const auto fine = run_cli(bad_laws() + "run '" + skewed_scene("fine", "rise: 100 deg, return: 60 deg") + "'");
  CHECK(fine.exit_code == 0);
}
