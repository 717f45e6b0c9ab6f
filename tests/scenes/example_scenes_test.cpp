// The example scenes the README runs, end to end through the `mechgraph` command.
#include "test_support.hpp"

#include <yaml-cpp/yaml.h>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <unistd.h>
#include <numbers>

using namespace mechgraph::testing;
using Catch::Matchers::Contains;
using Catch::Matchers::WithinRel;

namespace {
std::string scene(const std::string& name) { return "'" + std::string(MECHGRAPH_SOURCE_DIR) + "/scenes/" + name + "'"; }
std::string plugins() { return "--plugin-dir '" + std::string(MECHGRAPH_PLUGIN_DIR) + "' "; }
double value(const YAML::Node& json, const std::string& label) { return json["outputs"][label]["value"].as<double>(); }
}  // namespace

TEST_CASE("the valve-train study prints its comparison table", "[scenes]") {
  const auto r = run_cli(plugins() + "run " + scene("valvetrain_cams.yaml"));
  REQUIRE(r.exit_code == 0);
  CHECK_THAT(r.out, Contains("three-arc") && Contains("Kurz") && Contains("polydyne") && Contains("time-area") &&
                        Contains("peak valve velocity") && Contains("positive-acceleration angle"));
  // Both lifts, named for what they are: the title's 8 mm is the tappet's.
  CHECK_THAT(r.out, Contains("equal tappet lift (8 mm)") && Contains("tappet lift (cam)") &&
                        Contains("valve lift (1.5 x tappet - lash)"));
}

TEST_CASE("the valve-train study: equal lift and phi_y, exact time-area agrees with a fine rectangle sum", "[scenes]") {
  const auto exact = run_cli(plugins() + "-q run " + scene("valvetrain_cams.yaml") + " --json");
  REQUIRE(exact.exit_code == 0);
  const YAML::Node e = YAML::Load(exact.out);
  const double deg = std::numbers::pi / 180;
  for (const char* cam : {"arc", "kurz", "poly"}) {
    INFO(cam);
    CHECK_THAT(value(e, std::string(cam) + ".accel_angle"), WithinRel(18 * deg, 1e-3));
    CHECK_THAT(value(e, "v_" + std::string(cam) + ".max_lift"), WithinRel(1.5 * 8e-3 - 0.25e-3, 1e-12));
    CHECK_THAT(value(e, std::string(cam) + ".max_lift"), WithinRel(8e-3, 1e-12));
  }
  // Second method: the source's rectangle sum with a 0.01 deg step converges to the exact value.
  const auto fine = run_cli(plugins() + "-q run " + scene("valvetrain_cams.yaml") +
                            " --json --set ta_arc.method=rectangle --set ta_arc.step=0.01deg"
                            " --set ta_kurz.method=rectangle --set ta_kurz.step=0.01deg"
                            " --set ta_poly.method=rectangle --set ta_poly.step=0.01deg");
  REQUIRE(fine.exit_code == 0);
  const YAML::Node f = YAML::Load(fine.out);
  for (const char* ta : {"ta_arc.time_area", "ta_kurz.time_area", "ta_poly.time_area"}) {
    INFO(ta);
    CHECK_THAT(value(f, ta), WithinRel(value(e, ta), 1e-4));
  }
  // A higher speed shortens the open time: time-area scales as 1/rpm.
  // (half the speed: at twice the speed the study's spring would have no fixed point)
  const auto fast = run_cli(plugins() + "-q run " + scene("valvetrain_cams.yaml") + " --json --set rpm=2800rpm");
  REQUIRE(fast.exit_code == 0);
  CHECK_THAT(value(YAML::Load(fast.out), "ta_kurz.time_area"), WithinRel(value(e, "ta_kurz.time_area") * 2, 1e-12));
}

TEST_CASE("the culling demo evaluates only the requested branch", "[scenes]") {
  const auto r = run_cli(plugins() + "-q run " + scene("culling_demo.yaml") + " --json");
  REQUIRE(r.exit_code == 0);
  const YAML::Node json = YAML::Load(r.out);
  REQUIRE(json["evaluated"].size() == 3);
  CHECK(json["evaluated"][0].as<std::string>() == "kurz");
  CHECK(json["evaluated"][2].as<std::string>() == "ta_kurz");
  const auto dot = run_cli(plugins() + "graph " + scene("culling_demo.yaml"));
  REQUIRE(dot.exit_code == 0);
  CHECK_THAT(dot.out, Contains("cluster_culled") && Contains("\"cyc\""));
}

TEST_CASE("the backlash study: per-hinge play, totals by three methods, hinge shares", "[scenes]") {
  const auto r = run_cli(plugins() + "run " + scene("backlash_chain.yaml"));
  REQUIRE(r.exit_code == 0);
  CHECK_THAT(r.out, Contains("h5 bearing") && Contains("worst case") && Contains("RSS") && Contains("Monte Carlo") &&
                        Contains("arcmin") && Contains("share of the worst case"));
  const auto j = run_cli(plugins() + "-q run " + scene("backlash_chain.yaml") + " --json");
  REQUIRE(j.exit_code == 0);
  const YAML::Node json = YAML::Load(j.out);
  // The source's worst case: rod maximum = actuator (25 + 25 um) + the sum of the hinges' greatest
  // play (all transfer ratios 1), over the 500 mm moment arm for the nozzle.
  double hinges = 0.0;
  for (const char* h : {"h1", "h2", "h3", "h4", "h5"}) hinges += value(json, std::string(h) + ".play_max");
  CHECK_THAT(value(json, "chain.rod_backlash_max"), WithinRel(50e-6 + hinges, 1e-12));
  CHECK_THAT(value(json, "chain.angular_backlash_max"), WithinRel((50e-6 + hinges) / 0.5, 1e-12));
  // Statistics are tighter than the worst case; RSS and Monte Carlo agree within a few %.
  CHECK(value(json, "chain.rod_backlash_rss_max") < value(json, "chain.rod_backlash_max"));
  // The 99.865 % quantile of 2e5 samples has a standard error of about 0.2 % here
  // (sqrt(p (1 - p) / n) / density at the quantile): 1 % is five of them.
  CHECK_THAT(value(json, "chain.rod_backlash_mc_q999"), WithinRel(value(json, "chain.rod_backlash_rss_max"), 1e-2));
  // Seeded: the same run gives the same Monte Carlo numbers.
  const auto again = run_cli(plugins() + "-q run " + scene("backlash_chain.yaml") + " --json");
  CHECK(value(YAML::Load(again.out), "chain.rod_backlash_mc_mean") == value(json, "chain.rod_backlash_mc_mean"));
}

TEST_CASE("the tolerance-stack scene reproduces the printed worst case", "[scenes]") {
  const auto j = run_cli(plugins() + "-q run " + scene("tolerance_stack.yaml") + " --json");
  REQUIRE(j.exit_code == 0);
  const YAML::Node json = YAML::Load(j.out);
  CHECK_THAT(value(json, "gap.mean"), WithinRel(0.4e-3, 1e-9));
  CHECK_THAT(value(json, "gap.worst_case_min"), WithinRel(0.017e-3, 1e-6));
  CHECK_THAT(value(json, "gap.worst_case_max"), WithinRel(0.783e-3, 1e-9));
  // MITCalc's printed RSS, +-0.17825 mm, with every part normal (T = 6 sigma) ...
  CHECK_THAT(value(json, "mitcalc.rss_max") - value(json, "mitcalc.mean"), WithinRel(0.17825e-3, 1e-4));
  // ... and with the case uniform, its sigma T / (2 sqrt 3): 3 sqrt(sum of the others' (T/6)^2 + (0.29/(2 sqrt 3))^2).
  const double others = (0.072 * 0.072 + 0.06 * 0.06 + 2 * 0.12 * 0.12 + 2 * 0.052 * 0.052) / 36;
  const double uniform_case = 0.29 * 0.29 / 12;
  CHECK_THAT(value(json, "gap.rss_max") - value(json, "gap.mean"), WithinRel(3e-3 * std::sqrt(others + uniform_case), 1e-12));
}

TEST_CASE("the backlash study's pin hinges carry the ISO 286 clearances of their seats", "[scenes]") {
  const auto j = run_cli(plugins() + "-q run " + scene("backlash_chain.yaml") + " --json");
  REQUIRE(j.exit_code == 0);
  const YAML::Node json = YAML::Load(j.out);
  // H11/h11: clearance from 0 to 2 x IT11; IT11 = 130 um over 18..30 mm, 110 um over 10..18 mm.
  CHECK_THAT(value(json, "h1.play_max"), Catch::Matchers::WithinAbs(260e-6, 1e-12));
  CHECK_THAT(value(json, "h3.play_max"), Catch::Matchers::WithinAbs(220e-6, 1e-12));
  CHECK_THAT(value(json, "h1.play_min"), Catch::Matchers::WithinAbs(0.0, 1e-15));
}

TEST_CASE("the backlash scene names of the contract load and give hand-computed values", "[scenes]") {
  const auto j = run_cli(plugins() + "-q run '" + std::string(MECHGRAPH_SOURCE_DIR) +
                         "/tests/scenes/data/backlash_contract.yaml' --json");
  REQUIRE(j.exit_code == 0);
  const YAML::Node json = YAML::Load(j.out);
  using Catch::Matchers::WithinAbs;
  // 20 H11/h11: clearance 0 .. 260 um (IT11 = 130 um).
  CHECK_THAT(value(json, "f1.clearance_max"), WithinAbs(260e-6, 1e-12));
  // L = L_act + S_pin + S_bearing (mean fit clearance 130 um + the bearing's mean internal clearance).
  // ISO 12240-1, normal group, bore over 12 up to 20 mm: radial internal clearance 40..82 um, mean 61 um.
  const double bearing_internal_mean = value(json, "chain.rod_backlash_mean") - 25e-6 - 130e-6 - 130e-6;
  CHECK_THAT(bearing_internal_mean, WithinAbs(61e-6, 1e-12));
  CHECK_THAT(value(json, "chain.angular_backlash_mean"), WithinAbs(value(json, "chain.rod_backlash_mean") / 0.5, 1e-15));
  CHECK_THAT(value(json, "chain.angular_backlash_max"),
             WithinAbs((value(json, "chain.rod_backlash_mean") + value(json, "chain.rod_backlash_limit")) / 0.5, 1e-15));
  // Cardan: atan2(sin 30, cos 30 cos 20) and cos b / (1 - sin^2 b cos^2 t1).
  const double pi = std::numbers::pi, t1 = 30 * pi / 180, b = 20 * pi / 180;
  CHECK_THAT(value(json, "uj.output_angle"), WithinAbs(std::atan2(std::sin(t1), std::cos(t1) * std::cos(b)), 1e-15));
  CHECK_THAT(value(json, "uj.speed_ratio"),
             WithinRel(std::cos(b) / (1 - std::sin(b) * std::sin(b) * std::cos(t1) * std::cos(t1)), 1e-14));
  // Stack: 120 +-0.05 minus 3.5 (+0/-0.04): mean 116.52, worst case +-0.07, RSS sigma sqrt((0.05/3)^2 + (0.02/3)^2).
  CHECK_THAT(value(json, "stack.mean"), WithinAbs(116.52e-3, 1e-12));
  CHECK_THAT(value(json, "stack.worst_case_min"), WithinAbs(116.45e-3, 1e-12));
  CHECK_THAT(value(json, "stack.worst_case_max"), WithinAbs(116.59e-3, 1e-12));
  CHECK_THAT(value(json, "stack.rss_sigma"), WithinRel(std::hypot(0.05e-3 / 3, 0.02e-3 / 3), 1e-12));
}

TEST_CASE("the valve-train study prints stage 4 by both spring rules", "[scenes]") {
  const auto r = run_cli(plugins() + "run " + scene("valvetrain_cams.yaml"));
  REQUIRE(r.exit_code == 0);
  CHECK_THAT(r.out, Contains("source's rule") && Contains("free-length rule") && Contains("reduced mass M_red") &&
                        Contains("harmonic k") && Contains("distortion, harmonic k+1, %") && Contains("least safety factor"));
  const auto j = run_cli(plugins() + "-q run " + scene("valvetrain_cams.yaml") + " --json");
  REQUIRE(j.exit_code == 0);
  const YAML::Node json = YAML::Load(j.out);
  for (const char* cam : {"arc", "kurz", "poly"}) {
    INFO(cam);
    // The free-length line touches K x the inertia force; the source's line may dip below it.
    CHECK_THAT(value(json, "sd_" + std::string(cam) + ".min_safety_factor"), WithinRel(1.5, 1e-9));
    CHECK(value(json, "src_" + std::string(cam) + ".min_safety_factor") <= 1.5 * (1 + 1e-9));
  }
}

TEST_CASE("the dynamics scene: effects side by side, curves as CSV with units", "[scenes]") {
  const auto dir = std::filesystem::temp_directory_path() / ("mechgraph_dyn_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  const auto r = run_cli(plugins() + "run " + scene("valvetrain_dynamics.yaml") + " --out '" + dir.string() + "'");
  REQUIRE(r.exit_code == 0);
  CHECK_THAT(r.out, Contains("rigid (5600 rpm)") && Contains("seating velocity") && Contains("float speed"));
  std::ifstream csv(dir / "elastic.curves.csv");
  std::string header;
  std::getline(csv, header);
  CHECK(header == "cam_angle [rad],lift [m],quasi_static_lift [m],kinematic_lift [m],drive_displacement [m],velocity [m/s],"
                  "contact_force [N],spring_force [N]");
  std::filesystem::remove_all(dir);
  // The rigid node integrates nothing; the elastic ones report their steps.
  const auto j = run_cli(plugins() + "-q run " + scene("valvetrain_dynamics.yaml") + " --json");
  REQUIRE(j.exit_code == 0);
  const YAML::Node json = YAML::Load(j.out);
  CHECK(json["nodes"]["rigid"]["work"]["steps"].as<double>() == 0);
  CHECK(json["nodes"]["elastic"]["work"]["steps"].as<double>() > 100);
  // What the scene's comments say its table shows: the bilateral drive pulls (and a note says a
  // real cam cannot); with contacts the valve floats already at 5600 rpm, thrown off on the opening
  // flank (before the nose) by the lash blow, and reaches coil bind; the ramped cam floats too.
  CHECK(value(json, "elastic.min_contact_force") < -1000.0);
  bool bilateral_note = false;
  for (const auto& n : json["notes"]["elastic"]) bilateral_note = bilateral_note || n.as<std::string>().find("no real cam") != std::string::npos;
  CHECK(bilateral_note);
  for (const char* node : {"contacts", "with_ramp", "overspeed"}) CHECK(value(json, std::string(node) + ".floats") == 1);
  for (const char* node : {"contacts.events", "overspeed.events"}) {
    INFO(node);
    const YAML::Node columns = json["outputs"][node]["value"]["columns"];
    const auto angles = columns["cam_angle"]["values"].as<std::vector<double>>();
    const auto codes = columns["event"]["values"].as<std::vector<double>>();
    REQUIRE(codes.size() >= 2);
    CHECK(codes[0] == 10.0);  // the cam takes up the lash with a blow ...
    CHECK(codes[1] == 1.0);   // ... and the first departure: contact lost ...
    CHECK(angles[1] < 0.0);   // ... on the opening flank
    CHECK(std::count(codes.begin(), codes.end(), 5.0) >= 1);  // coil bind
  }
}

TEST_CASE("the polydyne synthesis scene: exact at the design speed", "[scenes]") {
  const auto j = run_cli(plugins() + "-q run " + scene("polydyne_synthesis.yaml") + " --json");
  REQUIRE(j.exit_code == 0);
  const YAML::Node json = YAML::Load(j.out);
  CHECK(value(json, "d_5600.target_deviation") < 1e-9);
  CHECK(value(json, "d_4500.target_deviation") > 1e-5);
  CHECK(value(json, "damped.target_deviation") > 1e-6);  // the synthesis leaves damping out
}

TEST_CASE("the cam-table scene: lift and event from the file, angles from the start of lift", "[scenes]") {
  const auto j = run_cli(plugins() + "-q run " + scene("cam_table.yaml") + " --json");
  REQUIRE(j.exit_code == 0);
  const YAML::Node json = YAML::Load(j.out);
  // The table is the cycloidal law sampled every 0.5 deg: the spline through it gives the law's
  // figures back (a second method: the closed form).
  CHECK_THAT(value(json, "table.max_lift"), WithinRel(8e-3, 1e-9));
  CHECK_THAT(value(json, "ta_table.time_area"), WithinRel(value(json, "ta_cyc.time_area"), 1e-7));
  CHECK_THAT(value(json, "v_table.max_velocity"), WithinRel(value(json, "v_cyc.max_velocity"), 1e-6));
  CHECK_THAT(value(json, "table.accel_angle"), WithinRel(value(json, "cyc.accel_angle"), 1e-5));
  // Given anyway, max_lift and action_angle are checked against the file.
  const auto wrong = run_cli(plugins() + "-q run " + scene("cam_table.yaml") + " --set table.max_lift=9mm");
  CHECK(wrong.exit_code == 3);
  CHECK_THAT(wrong.err, Contains("maximum lift is 8") && Contains("max_lift asks for 9"));
  const auto right = run_cli(plugins() + "-q run " + scene("cam_table.yaml") + " --set table.action_angle=130deg");
  CHECK(right.exit_code == 0);
  // Read as angles from the nose, the same file lies outside -180..180 deg: the message says what to set.
  const auto nose = run_cli(plugins() + "-q run " + scene("cam_table.yaml") + " --set table.angle_origin=nose --set table.file=" +
                            std::string(MECHGRAPH_SOURCE_DIR) + "/tests/scenes/data/lift_from_start_wide.csv");
  CHECK(nose.exit_code == 3);
  CHECK_THAT(nose.err, Contains("angle_origin: start_of_lift"));
}

TEST_CASE("the polydyne synthesis also takes a polydyne made for an accel_angle", "[scenes]") {
  // (the real-exponent law once gave a NaN jerk at the nose, which the synthesis turned into a NaN cam)
  const auto j = run_cli(plugins() + "-q run " + scene("polydyne_synthesis.yaml") +
                         " --json --set poly.accel_angle=18deg --set d_5600.curve_points=1441");
  REQUIRE(j.exit_code == 0);
  CHECK(value(YAML::Load(j.out), "d_5600.target_deviation") < 1e-9);
}

TEST_CASE("Monte Carlo results say how they were made, contributions name their links", "[scenes]") {
  const auto r = run_cli(plugins() + "run " + scene("tolerance_stack.yaml"));
  REQUIRE(r.exit_code == 0);
  CHECK_THAT(r.out, Contains("gap: Monte Carlo: 1000000 samples, seed 1, standard error of the mean"));
  CHECK_THAT(r.out, Contains("gap.contribution_rss = shaft 1.7") && Contains("case 85.4"));
  const auto j = run_cli(plugins() + "-q run " + scene("tolerance_stack.yaml") + " --json");
  REQUIRE(j.exit_code == 0);
  const YAML::Node json = YAML::Load(j.out);
  CHECK(json["outputs"]["gap.contribution_worst_case"]["labels"][4].as<std::string>() == "case");
  CHECK_THAT(json["notes"]["gap"][0].as<std::string>(), Contains("1000000 samples, seed 1"));
  CHECK_FALSE(json["notes"]["mitcalc"]);  // no Monte Carlo there: its effect is the gap node's own
  const auto chain = run_cli(plugins() + "run " + scene("backlash_chain.yaml"));
  REQUIRE(chain.exit_code == 0);
  CHECK_THAT(chain.out, Contains("chain: Monte Carlo: 200000 samples, seed 1"));
}

TEST_CASE("notes stay with results taken from the memo cache", "[scenes][evaluator]") {
  const std::string yaml = R"(
nodes:
  s: { type: stack.linear, effects: [ monte_carlo ], params: { samples: 1000, seed: 7,
       links: [ { nominal: 10 mm, upper: 0.1 mm, lower: -0.1 mm, label: a } ] } }
outputs: [ s.mc_mean ]
)";
  mechgraph::MemoCache cache;
  const mechgraph::Graph g = graph_from(yaml, project_registry());
  const mechgraph::RunResult first = evaluate(g, cache);
  const mechgraph::RunResult again = evaluate(g, cache);
  REQUIRE(again.runs.at(0).reused);
  CHECK(again.runs.at(0).notes == first.runs.at(0).notes);
  CHECK_THAT(first.runs.at(0).notes.at(0), Contains("1000 samples, seed 7"));
}

TEST_CASE("the polydyne synthesis refuses another rocker than the design's and an undercut cam", "[scenes]") {
  const auto rocker = run_cli(plugins() + "-q run " + scene("polydyne_synthesis.yaml") + " --set synth.rocker_ratio=1.4");
  CHECK(rocker.exit_code == 3);
  CHECK_THAT(rocker.err, Contains("parameter 'rocker_ratio'") && Contains("1.4") && Contains("disagree"));
  // A soft drive asks for a cam that stretches it by its whole inertia force: its contour undercuts.
  const auto soft = run_cli(plugins() + "-q run " + scene("polydyne_synthesis.yaml") + " --set drive=300N/mm");
  CHECK(soft.exit_code == 3);
  CHECK_THAT(soft.err, Contains("parameter 'drive_stiffness'") && Contains("synthesised cam is undercut"));
}
