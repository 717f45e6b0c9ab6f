// What a report shows and how: the numbers on the page are the run's, the timing notes reach
// `run`'s text and `--json`, report rows keep one unit per dimension and name cam or crank degrees,
// the SVAJ panel, spring-over-lift and contour figures are there, and `report --pdf` prints a PDF.
#include "file_support.hpp"
#include "test_support.hpp"

#include <catch2/catch.hpp>

#include <fstream>
#include <regex>

#include <unistd.h>

using namespace mechgraph::testing;
using Catch::Matchers::Contains;

namespace {

namespace fs = std::filesystem;

fs::path fresh_folder(const std::string& name) { return absent_dir("mg_present", name); }

std::string scene(const char* name) { return std::string(MECHGRAPH_SOURCE_DIR) + "/scenes/" + name; }

// The plot CSV whose name ends in `suffix` (plot numbers follow the order of the outputs).
std::string plot_csv(const fs::path& dir, const std::string& suffix) {
  for (const auto& entry : fs::directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind("plot_", 0) == 0 && name.size() >= suffix.size() && name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0)
      return slurp(entry.path());
  }
  return {};
}

}  // namespace

TEST_CASE("run prints the timing notes of installed lobes in its text and in --json", "[cli][report][notes]") {
  const auto text = run_cli("-q run '" + scene("valvetrain_cams.yaml") + "'");
  REQUIRE(text.exit_code == 0);
  // Opening at 1 mm valve lift: the nose at 108 deg ATDC less half the crank duration (quoted
  // to 0.1 deg, the same text the report page shows).
  CHECK_THAT(text.out, Contains("v_kurz: intake: opens 3.4 deg ATDC, closes 32.6 deg ABDC at 1 mm valve lift"));
  CHECK_THAT(text.out, Contains("v_arc: intake: opens 0.4 deg ATDC"));
  const auto json = run_cli("-q run --json '" + scene("valvetrain_cams.yaml") + "'");
  REQUIRE(json.exit_code == 0);
  CHECK_THAT(json.out, Contains("\"notes\":{\"v_arc\":[\"intake: opens 0.4 deg ATDC, closes 35.6 deg ABDC at 1 mm valve lift\"]"));
  CHECK_THAT(json.out, Contains("\"v_kurz\":[\"intake: opens 3.4 deg ATDC, closes 32.6 deg ABDC at 1 mm valve lift\"]"));
  // The events table the notes come from is not an output the scene asked for.
  CHECK_THAT(json.out, !Contains("\"v_kurz.events\""));
}

TEST_CASE("report rows: one unit per dimension without a units: block, degrees say cam or crank", "[cli][report][units]") {
  const fs::path dir = fresh_folder("units");
  fs::create_directories(dir);
  const fs::path file = dir / "rows.yaml";
  // The first row names its unit, the second does not: both show mm/deg^2 (not m/rad^2 under
  // mm/deg^2); the third, without a unit and a port unit, shows the reader's mm/deg^3.
  std::ofstream(file) << R"(title: units by dimension
nodes:
  cam: { type: cam.kurz, params: { max_lift: 9 mm, action_angle: 130 deg, accel_angle: 18 deg, base_radius: 17 mm } }
  valve: { type: valvetrain.valve_motion, inputs: { cam: cam.law }, params: { rpm: 5600 rpm, nose_timing: 108 deg } }
  ta: { type: valvetrain.time_area, inputs: { valve: valve.motion }, params: { seat_diameter: 34 mm } }
outputs: []
report:
- columns: { kurz: { cam: cam, valve: valve, ta: ta } }
  rows:
    - [ peak acceleration, cam.max_acceleration, mm/deg^2 ]
    - [ least acceleration, cam.min_acceleration ]
    - [ angle-area, ta.angle_area ]
    - [ crank duration, valve.crank_duration ]
    - [ open angle, valve.open_angle ]
)";
  const auto r = run_cli("-q run '" + file.string() + "'");
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  const std::regex least(R"(least acceleration\s+mm/deg\^2\s+(-?[0-9.e+-]+))");
  std::smatch m;
  REQUIRE(std::regex_search(r.out, m, least));
  // Kurz's least acceleration over cam angle is of the order h / phi^2: thousandths of mm/deg^2,
  // not the tens of m/rad^2 SI would print.
  CHECK(std::abs(std::stod(m[1])) < 0.1);
  CHECK(std::abs(std::stod(m[1])) > 1e-4);
  CHECK_THAT(r.out, Contains("mm^2*deg (cam)"));
  CHECK_THAT(r.out, Contains("deg (crank)"));
  CHECK_THAT(r.out, !Contains("m/rad^2"));

  // The outputs run prints one by one: the same reader's units, and which angle.
  const fs::path listed = dir / "listed.yaml";
  std::ofstream(listed) << R"(title: outputs in the reader's units
nodes:
  cam: { type: cam.kurz, params: { max_lift: 9 mm, action_angle: 130 deg, accel_angle: 18 deg, base_radius: 17 mm } }
  valve: { type: valvetrain.valve_motion, inputs: { cam: cam.law }, params: { rpm: 5600 rpm } }
  ta: { type: valvetrain.time_area, inputs: { valve: valve.motion }, params: { seat_diameter: 34 mm } }
outputs: [ cam.max_acceleration, ta.angle_area ]
)";
  const auto plain = run_cli("-q run '" + listed.string() + "'");
  INFO(plain.err);
  REQUIRE(plain.exit_code == 0);
  const std::regex peak(R"(cam.max_acceleration = ([0-9.e+-]+) mm/deg\^2)");
  REQUIRE(std::regex_search(plain.out, m, peak));
  // Against the same value in SI from --json: m/rad^2 x 1000 / (180/pi)^2.
  const auto json = run_cli("-q run --json '" + listed.string() + "'");
  const std::regex si(R"("cam.max_acceleration":\{"value":([0-9.e+-]+))");
  std::smatch n;
  REQUIRE(std::regex_search(json.out, n, si));
  const double deg = 180.0 / 3.14159265358979323846;
  CHECK(std::stod(m[1]) == Approx(std::stod(n[1]) * 1e3 / (deg * deg)).epsilon(1e-5).margin(1e-12));
  CHECK_THAT(plain.out, Contains("mm^2*deg (cam)"));
}

TEST_CASE("report: the page's numbers and notes are the run's, with the panel, spring and contour figures", "[cli][report]") {
  const fs::path dir = fresh_folder("cams");
  const auto report = run_cli("-q report '" + scene("valvetrain_cams.yaml") + "' --out '" + dir.string() + "'");
  INFO(report.err);
  REQUIRE(report.exit_code == 0);
  const auto json = run_cli("-q run --json '" + scene("valvetrain_cams.yaml") + "'");
  REQUIRE(json.exit_code == 0);
  const fs::path run_json = dir.parent_path() / "cams_run.json";
  std::ofstream(run_json) << json.out;
  const auto check = run_command("/usr/bin/python3 '" + std::string(MECHGRAPH_SOURCE_DIR) + "/tests/cli/check_report_numbers.py' '" +
                                 dir.string() + "' '" + run_json.string() + "'" +
                                 " 'peak valve velocity=v_arc.max_velocity,v_kurz.max_velocity,v_poly.max_velocity'"
                                 " 'min. valve acceleration=v_arc.min_acceleration,v_kurz.min_acceleration,v_poly.min_acceleration'"
                                 " 'angle-area=ta_arc.angle_area,ta_kurz.angle_area,ta_poly.angle_area'"
                                 " 'time-area=ta_arc.time_area,ta_kurz.time_area,ta_poly.time_area'"
                                 " 'valve open (cam angle)=v_arc.open_angle,v_kurz.open_angle,v_poly.open_angle'"
                                 " 'min. radius of curvature=arc.min_curvature_radius,kurz.min_curvature_radius,poly.min_curvature_radius'");
  INFO(check.out << check.err);
  CHECK(check.exit_code == 0);

  const std::string page = slurp(dir / "report.html");
  // One SVAJ panel per port group (cams over cam angle, valves over crank angle after TDC), with
  // the legends by the report's column names, not node ids.
  CHECK_THAT(page, Contains("Lift, velocity, acceleration and jerk of three-arc, Kurz, polydyne (kinematic) (arc, kurz, poly)"));
  CHECK_THAT(page, Contains("crank angle after the overlap TDC [deg (crank)]"));
  CHECK_THAT(page, Contains("events at 1 mm lift: three-arc opens 0.4 ATDC, closes 35.6 ABDC"));
  // The events are drawn too: the legend entry of their points in the panel's SVG.
  CHECK_THAT(page, Contains("<text>events at 1 mm lift</text>"));
  CHECK_THAT(page, !Contains("axis [rad]"));
  CHECK_THAT(page, !Contains("length [mm]"));
  std::size_t panels = 0;
  for (const auto& entry : fs::directory_iterator(dir))
    if (entry.path().filename().string().find("_svaj.csv") != std::string::npos) ++panels;
  CHECK(panels == 2);
  // Spring force over valve lift with its marks; the spring line starts at the free-length point.
  CHECK_THAT(page, Contains("Spring force over valve lift of Kurz (sd_kurz)"));
  for (const char* mark : {"free length", "installed", "full lift", "solid"}) CHECK_THAT(page, Contains(mark));
  const std::string spring_csv = plot_csv(dir, "_sd_kurz.force_curve_over_lift.csv");
  REQUIRE(!spring_csv.empty());
  // First data row: the spring line's free-length point, lift -f0 (f0 = 2 h_max = 23.5 mm), force 0.
  const std::string row = spring_csv.substr(spring_csv.find('\n') + 1, spring_csv.find('\n', spring_csv.find('\n') + 1) - spring_csv.find('\n') - 1);
  CHECK(std::stod(row.substr(0, row.find(','))) == Approx(-23.5).epsilon(1e-9).margin(1e-9));
  CHECK(std::stod(row.substr(row.find(',') + 1)) == Approx(0.0).epsilon(1e-12).margin(1e-9));
  // Event tables: narrow headers with units, angles in degrees saying cam or crank.
  CHECK_THAT(page, Contains("opening after TDC<br><span class=\"u\">[deg (crank)]</span>"));
  CHECK_THAT(page, Contains("opening<br><span class=\"u\">[deg (cam)]</span>"));
  CHECK_THAT(page, Contains("<div class=\"scroll\">"));
}

TEST_CASE("report: contour with its least circle, follower and rotation, curvature as 1/rho", "[cli][report]") {
  const fs::path dir = fresh_folder("contour");
  const auto r = run_cli("-q report '" + scene("cam_contour.yaml") + "' --out '" + dir.string() + "'");
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  const std::string page = slurp(dir / "report.html");
  CHECK_THAT(page, Contains("least circle r = 17 mm"));
  CHECK_THAT(page, Contains("follower at the nose"));
  CHECK_THAT(page, Contains("rotation (counter-clockwise)"));
  // Curvature: 1/rho; on the base circle 1/17 mm, the least radius in the title equals the run's.
  CHECK_THAT(page, Contains("Curvature 1/rho of flat tappet (0 at an inflection; least radius 3.096 mm)"));
  const std::string csv = plot_csv(dir, "_contact_flat_curvature.csv");
  REQUIRE(!csv.empty());
  const std::string first = csv.substr(csv.find('\n') + 1);
  CHECK(std::stod(first.substr(first.find(',') + 1)) == Approx(1.0 / 17.0).epsilon(1e-9).margin(1e-12));
}

TEST_CASE("report --pdf prints the page through headless chromium", "[cli][report][pdf]") {
  // scripts/install-deps.sh installs chromium: without it the test fails rather than passing unchecked.
  if (mechgraph::testing::run_command("command -v chromium").exit_code != 0)
    FAIL("chromium is not installed (scripts/install-deps.sh installs it): the PDF cannot be checked");
  // A folder name a URL would misread (a fragment, a query, an escape, a space): the page is
  // still found, because its path goes to chromium percent-encoded.
  const fs::path parent = fresh_folder("pdf");
  fs::create_directories(parent);
  const fs::path dir = parent / "a #b?c%d";
  const auto r = run_cli("-q report '" + scene("cam_contour.yaml") + "' --out '" + dir.string() + "' --pdf");
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  REQUIRE(fs::exists(dir / "report.pdf"));
  CHECK_THAT(r.out, Contains((dir / "report.pdf").string()));  // it says where the PDF is
  std::ifstream pdf(dir / "report.pdf", std::ios::binary);
  char magic[5] = {};
  pdf.read(magic, 4);
  CHECK(std::string(magic, 4) == "%PDF");
  CHECK(fs::file_size(dir / "report.pdf") > 10000);
  // Whole or not at all: no chromium profile left behind in the report.
  for (const auto& entry : fs::directory_iterator(dir)) CHECK(entry.path().extension() != ".log");
}

TEST_CASE("describe cam.program says its lift and event come from the segments", "[cli][describe]") {
  const auto r = run_cli("describe cam.program");
  REQUIRE(r.exit_code == 0);
  CHECK_THAT(r.out, Contains("taken from the segments"));
  CHECK_THAT(r.out, !Contains("taken from the data"));
  const auto table = run_cli("describe cam.table");
  CHECK_THAT(table.out, Contains("taken from the data"));
}

TEST_CASE("report --pdf without chromium: exit 5 naming the package, nothing written", "[cli][report][pdf]") {
  const fs::path dir = fresh_folder("no_chromium");
  // A PATH with neither chromium nor gnuplot: the PDF printer is asked for first, before the run.
  const auto r = run_command("env PATH=/nonexistent '" + std::string(MECHGRAPH_CLI) + "' -q report '" + scene("cam_contour.yaml") +
                             "' --out '" + dir.string() + "' --pdf");
  CHECK(r.exit_code == 5);
  CHECK_THAT(r.err, Contains("apt-get install chromium"));
  CHECK(!fs::exists(dir));
}

TEST_CASE("report draws only the nodes the scene needs: a culled node stays culled", "[cli][report]") {
  // culling_demo.yaml keeps an undercut cycloidal cam that nothing asks for: run culls it, and so
  // must the report (drawing its curves would evaluate it and fail on the undercut).
  const fs::path dir = fresh_folder("culled");
  const auto r = run_cli("-q report '" + scene("culling_demo.yaml") + "' --out '" + dir.string() + "'");
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  const std::string json = slurp(dir / "results.json");
  CHECK_THAT(json, !Contains("\"cyc."));
  CHECK_THAT(json, Contains("\"kurz.svaj\""));
}

TEST_CASE("report: one installed exhaust valve's events labelled from the dead centres", "[cli][report]") {
  const fs::path dir = fresh_folder("exhaust");
  fs::create_directories(dir.parent_path());
  const fs::path file = dir.parent_path() / "exhaust.yaml";
  std::ofstream(file) << R"(title: one exhaust valve
nodes:
  cam: { type: cam.kurz, params: { max_lift: 9 mm, action_angle: 130 deg, accel_angle: 18 deg, base_radius: 17 mm } }
  valve: { type: valvetrain.valve_motion, inputs: { cam: cam.law }, params: { rpm: 5600 rpm, nose_timing: -112 deg } }
outputs: [ valve.max_lift ]
)";
  const auto r = run_cli("-q report '" + file.string() + "' --out '" + dir.string() + "'");
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  const std::string page = slurp(dir / "report.html");
  // The plot's labels (quoted by the report from the events table) agree with the node's own note
  // (quoted by the SDK from its events): the same angles, the same dead centres.
  CHECK_THAT(page, Contains("valve: exhaust: opens 35.9 deg BBDC, closes 8.1 deg BTDC at 1 mm valve lift"));
  CHECK_THAT(page, Contains("<text>opens 35.9 BBDC</text>"));
  CHECK_THAT(page, Contains("<text>closes 8.1 BTDC</text>"));
  CHECK_THAT(page, Contains("<text>BDC</text>"));
  CHECK_THAT(page, Contains("<text>TDC</text>"));
}

TEST_CASE("report and run: a symmetric lobe's centreline reads 0, not its rounding noise", "[cli][report][shown_number]") {
  const fs::path dir = fresh_folder("symmetric");
  const fs::path file = dir.parent_path() / "symmetric.yaml";
  std::ofstream(file) << R"(title: a symmetric lobe
nodes:
  cam: { type: cam.polydyne, params: { max_lift: 8 mm, action_angle: 130 deg, base_radius: 17 mm, exponents: [2, 14, 26, 38, 50] } }
  valve: { type: valvetrain.valve_motion, inputs: { cam: cam.law }, params: { rpm: 5600 rpm, rocker_ratio: 1.5 } }
outputs: [ cam.events, valve.events, valve.centreline ]
)";
  // The CSV keeps the node's digits: the centreline is rounding noise, not exactly 0 (else this
  // test would not test anything).
  const auto data = run_cli("-q run '" + file.string() + "' --json");
  REQUIRE(data.exit_code == 0);
  const std::regex noise_in_json(R"("centreline"[^\]]*[0-9]e-1[0-9])");
  const bool json_has_noise = std::regex_search(data.out, noise_in_json);
  const auto r = run_cli("-q report '" + file.string() + "' --out '" + dir.string() + "'");
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  const std::string page = slurp(dir / "report.html");
  const auto text = run_cli("-q run '" + file.string() + "'");
  REQUIRE(text.exit_code == 0);
  INFO(text.out);
  // No cell of the page or line of the terminal shows a number at rounding level (e-10 and below).
  CHECK_FALSE(std::regex_search(page, std::regex(R"(<td class="n">-?[0-9.]+e-(1[0-9]|[2-9][0-9]))")));
  CHECK_FALSE(std::regex_search(text.out, std::regex(R"([0-9]e-(1[0-9]|[2-9][0-9]))")));
  CHECK_THAT(text.out, Contains("valve.centreline = 0 deg"));
  if (!json_has_noise) WARN("the centreline came out exactly 0 here: only the formatting of 0 was tested");
}
