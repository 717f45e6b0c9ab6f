// The report's figures as a reader sees them, read from the SVG and CSV the report writes (issue
// 32, items 8 and 9): a dynamics channel compared across many runs as small multiples, curves that
// jump drawn in pieces (no line across a jump), legends and titles by the report's column names,
// the spring figure over its working range with the free length named at the edge, a flat face
// drawn at its min_face_width and pivoted followers with their pivot.
#include "file_support.hpp"
#include "test_support.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>
#include <sstream>

#include <unistd.h>

using namespace mechgraph::testing;
using Catch::Matchers::Contains;

namespace {

namespace fs = std::filesystem;

fs::path fresh_folder(const std::string& name) { return absent_dir("mg_figures", name); }

std::string scene(const char* name) { return std::string(MECHGRAPH_SOURCE_DIR) + "/scenes/" + name; }

fs::path report_of(const std::string& scene_file, const std::string& folder) {
  const fs::path dir = fresh_folder(folder);
  const auto r = run_cli("-q report '" + scene_file + "' --out '" + dir.string() + "'");
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  return dir;
}

// The inline SVG of the page's figure whose text holds `title` ("" when there is none).
std::string figure_svg(const std::string& page, const std::string& title) {
  const auto at = page.find(">" + title + "<");
  if (at == std::string::npos) return {};
  const auto begin = page.rfind("<svg", at), end = page.find("</svg>", at);
  return begin == std::string::npos || end == std::string::npos ? std::string() : page.substr(begin, end + 6 - begin);
}

// The `d` attributes of the paths in the gnuplot_plot_N group that starts at `group`.
std::vector<std::string> group_paths(const std::string& svg, std::size_t group) {
  int depth = 1;
  std::size_t i = group;
  while (depth > 0) {
    const auto open = svg.find("<g", i + 1), close = svg.find("</g>", i + 1);
    if (close == std::string::npos) break;
    if (open != std::string::npos && open < close) {
      ++depth;
      i = open;
    } else {
      --depth;
      i = close;
    }
  }
  const std::string body = svg.substr(group, i - group);
  std::vector<std::string> paths;
  for (auto p = body.find("d='"); p != std::string::npos; p = body.find("d='", p + 3))
    paths.push_back(body.substr(p + 3, body.find('\'', p + 3) - p - 3));
  return paths;
}

// The paths of each plot's curves, a list per gnuplot_plot_N group in the order of the SVG (small
// multiples: a group per panel; the border and grid lie outside the groups).
std::vector<std::vector<std::string>> curve_paths(const std::string& svg) {
  std::vector<std::vector<std::string>> groups;
  for (auto group = svg.find("<g id=\"gnuplot_plot_"); group != std::string::npos; group = svg.find("<g id=\"gnuplot_plot_", group + 1))
    groups.push_back(group_paths(svg, group));
  return groups;
}

// The curve paths of the small-multiples panel named `label` (gnuplot writes a panel's label after
// its plot group), empty if there is none.
std::vector<std::string> panel_paths(const std::string& svg, const std::string& label) {
  const auto at = svg.find("<text>" + label + "</text>");
  if (at == std::string::npos) return {};
  const auto group = svg.rfind("<g id=\"gnuplot_plot_", at);
  return group == std::string::npos ? std::vector<std::string>{} : group_paths(svg, group);
}

// The points of the paths, in px, with whether a line joins each to the point before it.
struct PathPoint {
  double x = 0.0, y = 0.0;
  bool joined = false;
};
std::vector<PathPoint> path_points(const std::vector<std::string>& paths) {
  std::vector<PathPoint> points;
  for (const std::string& d : paths) {
    std::istringstream in(d);
    std::string token;
    bool have = false;
    while (in >> token) {
      const auto comma = token.find(',');
      if (comma == std::string::npos || (token[0] != 'M' && token[0] != 'L')) {
        have = false;
        continue;
      }
      points.push_back({std::stod(token.substr(1, comma - 1)), std::stod(token.substr(comma + 1)), token[0] == 'L' && have});
      have = true;
    }
  }
  return points;
}

// The lines of a curve over the cam angle from -180 to 180 deg (its first and last points, the
// ends of the axis) that cross the cam angle `deg`: their two points lie on both sides of it.
int lines_across(const std::vector<PathPoint>& points, double deg) {
  double lo = INFINITY, hi = -INFINITY;
  for (const PathPoint& p : points) lo = std::min(lo, p.x), hi = std::max(hi, p.x);
  const double x = lo + (deg + 180.0) / 360.0 * (hi - lo), rounding = 0.02;  // px, the SVG's 2 decimals
  int across = 0;
  for (std::size_t i = 1; i < points.size(); ++i)
    if (points[i].joined && std::min(points[i - 1].x, points[i].x) < x - rounding && std::max(points[i - 1].x, points[i].x) > x + rounding)
      ++across;
  return across;
}

// The greatest vertical step between two points a path joins with a line (a move starts afresh).
double greatest_joined_step(const std::vector<std::string>& paths) {
  double greatest = 0.0;
  for (const std::string& d : paths) {
    std::istringstream in(d);
    std::string token;
    bool have = false;
    double last_y = 0.0;
    while (in >> token) {
      const char command = token[0];
      const std::string xy = token.substr(1);
      const auto comma = xy.find(',');
      if (comma == std::string::npos) continue;
      const double y = std::stod(xy.substr(comma + 1));
      if (command == 'L' && have) greatest = std::max(greatest, std::abs(y - last_y));
      have = command == 'M' || command == 'L';
      last_y = y;
    }
  }
  return greatest;
}

// Rows of a plot CSV as numbers, empty cells NaN.
std::vector<std::vector<double>> csv_rows(const std::string& csv) {
  std::vector<std::vector<double>> rows;
  std::istringstream in(csv);
  std::string line;
  std::getline(in, line);  // header
  while (std::getline(in, line)) {
    std::vector<double> row;
    std::string cell;
    std::istringstream cells(line);
    while (std::getline(cells, cell, ',')) row.push_back(cell.empty() ? std::nan("") : std::stod(cell));
    if (!line.empty() && line.back() == ',') row.push_back(std::nan(""));
    rows.push_back(std::move(row));
  }
  return rows;
}

// The plot CSV whose name ends in `suffix`.
std::string plot_csv(const fs::path& dir, const std::string& suffix) {
  for (const auto& entry : fs::directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind("plot_", 0) == 0 && name.size() >= suffix.size() && name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0)
      return slurp(entry.path());
  }
  return {};
}

// The header's column index whose name starts with `prefix`, or -1.
int column_of(const std::string& csv, const std::string& prefix) {
  std::istringstream header(csv.substr(0, csv.find('\n')));
  std::string name;
  for (int k = 0; std::getline(header, name, ','); ++k)
    if (name.rfind(prefix, 0) == 0) return k;
  return -1;
}

// An events CSV beside the report as (cam angle in deg, event name) rows.
std::vector<std::pair<double, std::string>> event_rows(const std::string& csv) {
  const int angle = column_of(csv, "cam_angle ["), name = column_of(csv, "event_name");
  std::vector<std::pair<double, std::string>> rows;
  if (angle < 0 || name < 0) return rows;
  std::istringstream in(csv);
  std::string line;
  std::getline(in, line);  // header
  while (std::getline(in, line)) {
    std::vector<std::string> cells;
    std::istringstream row(line);
    for (std::string cell; std::getline(row, cell, ',');) cells.push_back(cell);
    if (static_cast<int>(cells.size()) > std::max(angle, name))
      rows.emplace_back(std::stod(cells[static_cast<std::size_t>(angle)]), cells[static_cast<std::size_t>(name)]);
  }
  return rows;
}

double scalar_from_json(const std::string& json, const std::string& label) {
  const auto at = json.find("\"" + label + "\"");
  REQUIRE(at != std::string::npos);
  const auto value = json.find("\"value\":", at);
  return std::stod(json.substr(value + 8));
}

}  // namespace

TEST_CASE("report: dynamics across five runs as small multiples, jumps never joined", "[cli][report][figures]") {
  const fs::path dir = report_of(scene("valvetrain_dynamics.yaml"), "dynamics");
  const std::string page = slurp(dir / "report.html");
  // Five runs' velocity: a panel per run, each named by its report column.
  const std::string velocity = figure_svg(page, "velocity, a panel per node");
  REQUIRE(!velocity.empty());
  for (const char* column : {"rigid (5600 rpm)", "elastic, bilateral (5600 rpm)", "elastic, contacts (5600 rpm)",
                             "same, with ramps (5600 rpm)", "elastic, contacts (7500 rpm)"})
    CHECK_THAT(velocity, Contains("<text>" + std::string(column) + "</text>"));
  // The velocity turns round at every impact of the runs that lose the cam (panels 2 to 4: 8 m/s
  // and more at 7500 rpm): within a piece of a curve no step between neighbouring points (0.25 deg
  // apart) is an eighth of a panel's 150 px; drawn across the impacts they were 40 to 140 px.
  const auto panels = curve_paths(velocity);
  REQUIRE(panels.size() == 5);
  for (std::size_t p = 1; p <= 3; ++p) {
    INFO("panel " << p + 1);
    CHECK(greatest_joined_step(panels[p]) < 20.0);
  }
  // Legends and titles by column: a valve motion only one column's run reads is that column's; a
  // name list with commas inside its names is separated by ';'.
  CHECK_THAT(page, Contains("Lift, velocity, acceleration and jerk of v; same, with ramps (5600 rpm); elastic, contacts (7500 rpm) "
                            "(v, v_ramp, v_fast)"));
}

TEST_CASE("report: the seating and the rigid drive's lash take-up are not joined either", "[cli][report][figures]") {
  // A jump is broken at its node's events rows; two had none and were drawn as steep lines: the
  // rigid drive's lash take-up (it had no events table) and the landing on the seat with the cam
  // in contact (the bilateral drive never leaves it). Their rows now name them; no line of a
  // velocity panel crosses any row of its run.
  const fs::path dir = report_of(scene("valvetrain_dynamics.yaml"), "dynamics_seating");
  const std::string velocity = figure_svg(slurp(dir / "report.html"), "velocity, a panel per node");
  REQUIRE(!velocity.empty());
  struct Run {
    const char* node;
    const char* column;
    std::vector<std::string> events;  // the rows' names, where the test knows them all
  };
  for (const Run& run : {Run{"rigid", "rigid (5600 rpm)", {"lash_taken_up", "seated_on_cam"}},
                         Run{"elastic", "elastic, bilateral (5600 rpm)", {"seated_on_cam", "seated_on_cam"}},
                         Run{"contacts", "elastic, contacts (5600 rpm)", {}}, Run{"with_ramp", "same, with ramps (5600 rpm)", {}},
                         Run{"overspeed", "elastic, contacts (7500 rpm)", {}}}) {
    INFO(run.node);
    const auto rows = event_rows(slurp(dir / (std::string(run.node) + ".events.csv")));
    REQUIRE(!rows.empty());
    if (!run.events.empty()) {
      std::vector<std::string> names;
      for (const auto& row : rows) names.push_back(row.second);
      CHECK(names == run.events);
    }
    const std::vector<PathPoint> points = path_points(panel_paths(velocity, run.column));
    REQUIRE(points.size() > 1000);  // the curve's 1441 points
    for (const auto& [angle, name] : rows) {
      INFO(name << " at " << angle << " deg");
      CHECK(lines_across(points, angle) == 0);
    }
  }
}

TEST_CASE("report: the spring figure spans the working range, the free length named at its edge", "[cli][report][figures]") {
  const fs::path dir = report_of(scene("valvetrain_cams.yaml"), "spring");
  const std::string page = slurp(dir / "report.html");
  const std::string spring = figure_svg(page, "Spring force over valve lift of Kurz (sd_kurz)");
  REQUIRE(!spring.empty());
  // The page names the plugins its nodes come from, as results.json does, not every one loaded.
  CHECK_THAT(page, Contains("Plugins: cams ") && Contains(" valvetrain "));
  CHECK_THAT(page, !Contains(" backlash ") && !Contains(" joints "));
  // f0 = 2 h_max = 23.5 mm below the installed height: named, not on the axis.
  CHECK_THAT(spring, Contains("&lt;- free length at -23.5 mm"));
  for (const char* mark : {">installed<", ">full lift<", ">solid<"}) CHECK_THAT(spring, Contains(mark));
  // No tic of the x axis below -5 mm (the axis used to run from -25 mm); the forces are >= 0.
  std::size_t at = 0;
  while ((at = spring.find("<text>", at)) != std::string::npos) {
    at += 6;
    const std::string text = spring.substr(at, spring.find("</text>", at) - at);
    char* end = nullptr;
    const double v = std::strtod(text.c_str(), &end);
    if (end && *end == '\0' && end != text.c_str()) CHECK(v > -5.0);
  }
  // The CSV keeps the whole spring line, from the free-length point.
  const std::string csv = plot_csv(dir, "_sd_kurz.force_curve_over_lift.csv");
  REQUIRE(!csv.empty());
  CHECK(csv_rows(csv).front().front() == Approx(-23.5).epsilon(1e-9).margin(1e-9));
}

TEST_CASE("report: a flat face at its min_face_width, a pivoted roller with its arm and pivot", "[cli][report][figures]") {
  SECTION("translating flat face") {
    const fs::path dir = report_of(scene("cam_contour.yaml"), "flat");
    const std::string page = slurp(dir / "report.html");
    CHECK_THAT(page, Contains("contour of flat tappet (flat) (to scale)"));
    const auto json = run_cli("-q run --json '" + scene("cam_contour.yaml") + "'");
    REQUIRE(json.exit_code == 0);
    // The face: its ends are the least and greatest x of the drawn follower (the stem stands between).
    const std::string csv = plot_csv(dir, "_flat.contour.csv");
    const int x = column_of(csv, "follower at the nose x");
    REQUIRE(x >= 0);
    double lo = INFINITY, hi = -INFINITY;
    for (const auto& row : csv_rows(csv))
      if (static_cast<int>(row.size()) > x && std::isfinite(row[static_cast<std::size_t>(x)]))
        lo = std::min(lo, row[static_cast<std::size_t>(x)]), hi = std::max(hi, row[static_cast<std::size_t>(x)]);
    const double width_mm = scalar_from_json(json.out, "flat.min_face_width") * 1e3;
    CHECK(hi - lo == Approx(width_mm).epsilon(1e-9).margin(1e-9));
  }
  SECTION("pivoted roller (finger follower): the pivot at (-36, 24) mm is drawn") {
    const fs::path dir = report_of(scene("finger_follower.yaml"), "finger");
    const std::string csv = plot_csv(dir, "_contour.contour.csv");
    const int x = column_of(csv, "follower at the nose x"), y = column_of(csv, "follower at the nose y");
    REQUIRE(x >= 0);
    REQUIRE(y >= 0);
    double nearest = INFINITY;
    for (const auto& row : csv_rows(csv))
      if (static_cast<int>(row.size()) > y && std::isfinite(row[static_cast<std::size_t>(x)]))
        nearest = std::min(nearest, std::hypot(row[static_cast<std::size_t>(x)] + 36.0, row[static_cast<std::size_t>(y)] - 24.0));
    CHECK(nearest < 1e-6);  // mm
  }
  SECTION("pivoted flat face: the pivot is drawn, the face at min_face_width") {
    const fs::path file = fresh_folder("pivoted_flat.yaml");
    std::ofstream(file) << R"(title: Pivoted flat face
units: { length: mm }
nodes:
  cam:   { type: cam.kurz, params: { max_lift: 6 mm, action_angle: 150 deg, accel_angle: 20 deg, base_radius: 20 mm } }
  arm:   { type: follower.pivoted_flat, params: { pivot_x: -45 mm, pivot_y: 30 mm, face_offset: 4 mm } }
  cut:   { type: cam.contour, inputs: { cam: cam.law, follower: arm.follower } }
outputs: [ cut.contour, cut.min_face_width ]
)";
    const fs::path dir = report_of(file.string(), "pivoted_flat");
    const std::string csv = plot_csv(dir, "_cut.contour.csv");
    const int x = column_of(csv, "follower at the nose x"), y = column_of(csv, "follower at the nose y");
    REQUIRE(x >= 0);
    double nearest = INFINITY;
    for (const auto& row : csv_rows(csv))
      if (static_cast<int>(row.size()) > y && std::isfinite(row[static_cast<std::size_t>(x)]))
        nearest = std::min(nearest, std::hypot(row[static_cast<std::size_t>(x)] + 45.0, row[static_cast<std::size_t>(y)] - 30.0));
    CHECK(nearest < 1e-6);  // mm
  }
}
