// Work and memory bounded by the input before any work (issue 28, class 2): each case passed
// `validate` and the old estimate, then ran for minutes or was killed. Each runs the real command.
#include "hostile/hostile_support.hpp"

#include <catch2/catch.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>

using Catch::Matchers::Contains;
using namespace mechgraph::hostile;

namespace {

// A cycloidal-like lift of 4 mm over 130 deg every `step` deg, rounded to 1 um: `step` 0.002 gives
// 65000 rows, some 0.9 MB, whose interpolant the certified searches resolve piece by rough piece.
std::string fine_table(double step) {
  std::string text = "angle,lift\n";
  const long n = std::lround(130.0 / step);
  char row[64];
  for (long i = -5; i <= n + 5; ++i) {
    const double a = static_cast<double>(i) * step, x = std::min(a, 130.0 - a) / 130.0;
    const double h = a <= 0.0 || a >= 130.0 ? 0.0 : 8.0 * (x - std::sin(2.0 * M_PI * x) / (2.0 * M_PI));
    std::snprintf(row, sizeof row, "%.4f,%.3f\n", a, h);
    text += row;
  }
  return text;
}

std::string table_scene(const std::string& smoothing) {
  return "nodes:\n  t: { type: cam.table, params: { file: fine.csv, angle_origin: start_of_lift, base_radius: 35 mm, "
         "smoothing: " + smoothing + " } }\noutputs: [ t.max_lift, t.max_acceleration, t.min_curvature_radius ]\n";
}

}  // namespace

TEST_CASE("hostile bounds: a finely sampled lift table is refused before work, naming the node, its file and the budget",
          "[hostile][bounds]") {
  Scratch s("bounds_table");
  s.write("fine.csv", fine_table(0.002));
  for (const char* smoothing : {"none", "gcv"}) {
    INFO("smoothing " << smoothing);
    const auto scene = s.write("t.yaml", table_scene(smoothing));
    const auto start = std::chrono::steady_clock::now();
    const Outcome o = run_mechgraph({"run", scene.string()}, s.dir);
    CHECK(std::chrono::steady_clock::now() - start < std::chrono::seconds(10));
    CHECK(o.exit_code == 2);
    CHECK_THAT(o.err, Contains("the biggest term is t.file (about 650"));
    CHECK_THAT(o.err, Contains(std::string("smoothing ") + smoothing));
    CHECK_THAT(o.err, Contains("(cam.table)"));
    CHECK_THAT(o.err, Contains("--max-"));
    CHECK(o.out.empty());
  }
  // The same table given as a budget allows: a coarser one (650 rows) runs.
  s.write("fine.csv", fine_table(0.2));
  const Outcome ok = run_mechgraph({"run", s.write("t.yaml", table_scene("gcv")).string()}, s.dir);
  CHECK(ok.exit_code == 0);
}

TEST_CASE("hostile bounds: the shipped lift-table scenes run within the budget", "[hostile][bounds]") {
  for (const char* scene : {"scenes/cam_table.yaml", "scenes/cam_table_measured.yaml"}) {
    INFO(scene);
    const Outcome o = run_mechgraph({"run", source_file(scene)});
    CHECK(o.exit_code == 0);
    CHECK_THAT(o.err, !Contains("[error]"));
  }
}

TEST_CASE("hostile bounds: run --json counts its curves against --max-output as --out does", "[hostile][bounds]") {
  Scratch s("bounds_json");
  const auto scene = s.write("big.yaml",
                             "nodes:\n  k: { type: cam.kurz, params: { max_lift: 8 mm, action_angle: 130 deg, accel_angle: 18 deg, "
                             "base_radius: 17 mm, curve_points: 1000000 } }\noutputs: [ k.svaj ]\n");
  const Outcome json = run_mechgraph({"run", scene.string(), "--json", "--max-output", "1e7"});
  CHECK(json.exit_code == 2);
  CHECK_THAT(json.err, Contains("the biggest term is k's curves (1e+06 rows)"));
  CHECK_THAT(json.err, Contains("--max-output"));
  CHECK(json.out.empty());
  const Outcome out = run_mechgraph({"run", scene.string(), "--out", (s.dir / "o").string(), "--max-output", "1e7"});
  CHECK(out.exit_code == 2);
  // Printed as text, a curve is one line ("table of 5 curves over N points"): no bound to keep.
  CHECK(run_mechgraph({"validate", scene.string(), "--max-output", "1e7"}).exit_code == 0);
}

TEST_CASE("hostile bounds: float_speed counts simulated revolutions, not scan points", "[hostile][bounds]") {
  const std::string scene = source_file("scenes/valvetrain_dynamics.yaml");
  // 10000 speeds x 1000 revolutions: once 1e7 "items" admitted, some 1.5 hours of simulation.
  const Outcome o = run_mechgraph({"validate", scene, "--set", "float.scan_points=10000", "--set", "float.revolutions=1000"});
  CHECK(o.exit_code == 2);
  CHECK_THAT(o.err, Contains("the biggest term is float.scan_points = 10000"));
  CHECK_THAT(o.err, Contains("revolutions"));
  CHECK(run_mechgraph({"validate", scene}).exit_code == 0);
}

TEST_CASE("hostile bounds: a cases file's values are estimated as --set's are", "[hostile][bounds]") {
  Scratch s("bounds_cases");
  const auto scene = s.write("k.yaml",
                             "nodes:\n  k: { type: cam.kurz, params: { max_lift: 8 mm, action_angle: 130 deg, accel_angle: 18 deg, "
                             "base_radius: 17 mm } }\noutputs: [ k.max_velocity ]\n");
  std::string cases = "k.curve_points\n";
  for (int i = 0; i < 1000; ++i) cases += "1000000\n";
  const auto file = s.write("cases.csv", cases);
  // The scene's own value (361 points) x 1000 cases is within 1e8; each case's 10^6 points are not.
  const Outcome o = run_mechgraph({"sweep", scene.string(), "--cases", file.string(), "--max-work", "1e8", "--out",
                                   (s.dir / "rows.csv").string()});
  CHECK(o.exit_code == 2);
  CHECK_THAT(o.err, Contains("over 1000 cases, more than the budget of 1e+08"));
  CHECK_THAT(o.err, Contains("curve_points = 1000000"));
  CHECK_FALSE(std::filesystem::exists(s.dir / "rows.csv"));
  const Outcome set = run_mechgraph({"validate", scene.string(), "--set", "k.curve_points=1000000", "--max-work", "1e5"});
  CHECK(set.exit_code == 2);
  // Few cases of the same values are admitted.
  const auto few = s.write("few.csv", "k.curve_points\n1000\n2000\n");
  CHECK(run_mechgraph({"sweep", scene.string(), "--cases", few.string(), "--max-work", "1e8"}).exit_code == 0);
}

TEST_CASE("hostile bounds: a cases header of 300000 columns is checked in linear time", "[hostile][bounds]") {
  Scratch s("bounds_header");
  std::string header, row;
  for (int i = 0; i < 300000; ++i) {
    header += (i ? ",c" : "c") + std::to_string(i);
    row += i ? ",1" : "1";
  }
  const auto repeated = s.write("repeated.csv", header + ",c299999\n" + row + ",1\n");
  const auto start = std::chrono::steady_clock::now();
  const Outcome o = run_mechgraph({"sweep", source_file("scenes/valvetrain_cams.yaml"), "--cases", repeated.string()});
  CHECK(std::chrono::steady_clock::now() - start < std::chrono::seconds(10));  // 110 s when quadratic
  CHECK(o.exit_code == 2);
  CHECK_THAT(o.err, Contains("column 'c299999' appears twice"));
}
