// A series' CSV from `run --out` (hosts/cli/result_files.cpp, write_series_rows): its axis column
// names the unit and, in degrees, the angle frame its port declares ("axis [deg (cam)]"), as a
// table's column and a sweep's header name theirs (host/angle_reference.hpp: one rule); in SI
// (radians) no frame is named. The series is valvetrain.valve_motion's lift_curve (frame "cam").
#include "file_support.hpp"
#include "test_support.hpp"

#include <catch2/catch.hpp>

#include <numbers>
#include <sstream>
#include <string>
#include <vector>

using namespace mechgraph::testing;
using Catch::Matchers::WithinAbs;
using Catch::Matchers::WithinRel;

namespace {

namespace fs = std::filesystem;

const char* valve = R"(title: a valve's lift curve
nodes:
  kurz: { type: cam.kurz, params: { max_lift: 8 mm, action_angle: 130 deg, base_radius: 26 mm, accel_angle: 18 deg } }
  v: { type: valvetrain.valve_motion, inputs: { cam: kurz.law }, params: { rpm: 5600 rpm, rocker_ratio: 1.5, lash: 0.25 mm, curve_points: 41 } }
outputs: [v.lift_curve, v.svaj, v.open_angle]
)";

// "name [unit]" -> "unit".
std::string unit_of(const std::string& header) {
  const auto open = header.find(" [");
  return open == std::string::npos || header.back() != ']' ? std::string() : header.substr(open + 2, header.size() - open - 3);
}

}  // namespace

TEST_CASE("run --out: a series' CSV header tags its degrees with the port's frame, as tables and sweeps do", "[cli][presentation]") {
  const fs::path dir = scratch_dir("series_csv_frame");
  const std::string in_degrees = write_file(dir / "deg.yaml", std::string("units: { length: mm, angle: deg }\n") + valve);
  const std::string in_si = write_file(dir / "si.yaml", valve);
  const fs::path deg_out = absent_dir("series_csv_frame", "deg"), si_out = absent_dir("series_csv_frame", "si");
  const auto a = run_cli("-q run '" + in_degrees + "' --out '" + deg_out.string() + "'");
  const auto b = run_cli("-q run '" + in_si + "' --out '" + si_out.string() + "'");
  INFO(a.err << b.err);
  REQUIRE(a.exit_code == 0);
  REQUIRE(b.exit_code == 0);

  const auto curve = csv_cells(deg_out / "v.lift_curve.csv");
  const auto curve_si = csv_cells(si_out / "v.lift_curve.csv");
  REQUIRE(curve.size() == 42);
  REQUIRE(curve_si.size() == 42);
  CHECK(curve[0] == std::vector<std::string>{"axis [deg (cam)]", "v.lift_curve [mm]"});
  // Radians carry no frame tag (the rule tags degrees only).
  CHECK(curve_si[0] == std::vector<std::string>{"axis [rad]", "v.lift_curve [m]"});

  // The same frame tag as the table of the same node (its cam_angle column) ...
  const auto svaj = csv_cells(deg_out / "v.svaj.csv");
  REQUIRE_FALSE(svaj.empty());
  REQUIRE_FALSE(svaj[0].empty());
  CHECK(svaj[0][0] == "cam_angle [deg (cam)]");
  CHECK(unit_of(curve[0][0]) == unit_of(svaj[0][0]));

  // ... and as a sweep's header for the node's scalar angle in the same frame.
  const fs::path rows = dir / "rows.csv";
  fs::remove(rows);
  const auto s = run_cli("-q sweep '" + in_degrees + "' --vary v.rpm=5000rpm:6000rpm:2 --outputs v.open_angle --out '" + rows.string() + "'");
  INFO(s.err);
  REQUIRE(s.exit_code == 0);
  const auto swept = csv_cells(rows);
  REQUIRE(swept.size() == 3);
  REQUIRE(swept[0].size() >= 3);
  CHECK(swept[0][2] == "v.open_angle [deg (cam)]");
  CHECK(unit_of(curve[0][0]) == unit_of(swept[0][2]));

  // The numbers under the headers: degrees and millimetres are the SI file's radians and metres,
  // and the axis spans the open angle the sweep reports (the lift curve covers the open period).
  const double deg = std::numbers::pi / 180.0;
  for (std::size_t row = 1; row < curve.size(); ++row) {
    INFO("row " << row);
    const double angle = std::stod(curve[row][0]), angle_si = std::stod(curve_si[row][0]);
    const double lift = std::stod(curve[row][1]), lift_si = std::stod(curve_si[row][1]);
    CHECK_THAT(angle, WithinRel(angle_si / deg, 1e-14) || WithinAbs(angle_si / deg, 1e-12));
    CHECK_THAT(lift, WithinRel(lift_si * 1e3, 1e-14) || WithinAbs(lift_si * 1e3, 1e-12));
  }
  const double span = std::stod(curve.back()[0]) - std::stod(curve[1][0]);
  const double open_angle = std::stod(swept[1][2]);
  CHECK(open_angle > 100.0);
  CHECK_THAT(span, WithinRel(open_angle, 1e-12) || WithinAbs(open_angle, 1e-10));
}
