// The results docs/methods/valvetrain.md quotes, recomputed through the nodes: the measured-table
// paragraphs (the quartic raw and smoothed, the example scene), the dynamics' accuracy figures and
// integrator choices, the float speed search, the checks of the events from TDC and of the cam
// program's joints, the Hertz example and the constants of the method.
#include "docs/doc_numbers.hpp"

#include <mechgraph/domain/cam_law.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>

using namespace mechgraph;
using namespace mechgraph::testing;
using namespace mechgraph::testing::docs;

namespace {

constexpr double pi = 3.14159265358979323846;
constexpr double deg = pi / 180;
const std::string doc_name = "docs/methods/valvetrain.md";
const std::string n = number;  // a number's pattern, for building patterns with +

RunResult run(const std::string& yaml, const std::vector<std::string>& settings = {}) {
  std::vector<Override> overrides;
  for (const std::string& s : settings) overrides.push_back(parse_override(s));
  return run_yaml(yaml, project_registry(), overrides);
}

const NodeRun& node_run(const RunResult& r, const std::string& name) {
  for (const NodeRun& run : r.runs)
    if (run.node == name) return run;
  throw std::runtime_error("no run of " + name);
}

const Table& table_output(const RunResult& r, const std::string& label) { return output(r, label).as_table(); }

// The quartic of the measured-table paragraph, h = 7.5 (1 - (phi / 62 deg)^2)^2 mm, its closed forms.
struct Quartic {
  double H = 7.5e-3, P = 62 * deg, r0 = 24.5e-3;
  double lift(double phi) const {
    const double u = phi / P, q = 1 - u * u;
    return std::abs(u) < 1 ? H * q * q : 0.0;
  }
  double acceleration(double phi) const {
    const double u = phi / P;
    return std::abs(u) < 1 ? H * (12 * u * u - 4) / (P * P) : 0.0;
  }
  double min_curvature_radius() const { return r0 + H * (1 - 4 / (P * P)); }  // at the nose
  double peak_acceleration() const { return 8 * H / (P * P); }                // at the ends
  double peak_jerk() const { return 24 * H / (P * P * P); }
  double duration_at(double c) const { return 2 * P * std::sqrt(1 - std::sqrt(c / H)); }
};

// The quartic printed as a measuring machine would: every `step_deg` from 3 steps before the event
// to 3 after, the lift rounded to 1 um (the file's digits give the resolution).
std::string quartic_csv(double step_deg) {
  const Quartic q;
  std::string out = "angle [deg], lift [mm]\n";
  const long rows = std::lround(2 * (62 + 3 * step_deg) / step_deg);
  char line[96];
  for (long i = 0; i <= rows; ++i) {
    const double a = -62 - 3 * step_deg + i * step_deg;
    std::snprintf(line, sizeof line, "%.6f, %.3f\n", a, q.lift(a * deg) / 1e-3 + 0.0);
    out += line;
  }
  return out;
}

// The quartic table through cam.table at r0 24.5 mm (`smoothing` none, resolution or gcv).
RunResult quartic_table(const TempFile& file, const std::string& smoothing, const std::string& outputs) {
  return run("nodes:\n  t: { type: cam.table, params: { file: '" + file.path() + "', base_radius: 24.5 mm" +
             (smoothing.empty() ? "" : ", smoothing: " + smoothing) + " } }\noutputs: [ " + outputs + " ]\n");
}

double work(const RunResult& r, const std::string& node, const std::string& counter) { return node_run(r, node).work.at(counter); }

}  // namespace

TEST_CASE("docs: valvetrain.md, the raw quartic table (4.63 mm for 6.38, 17 %, four times)", "[docs][valvetrain]") {
  // "Measured lift tables": the quartic every 2 deg rounded to 1 um; the raw interpolant's
  // smallest flat-follower radius, its peak acceleration's excess and its jerk against the law's.
  // (The note once quoted 4.72 mm where the tool gives 4.63 mm.)
  const auto q = quoted(doc_text(doc_name), "r0 \\+ h \\+ h''` comes out " + n + " mm instead of " + n +
                                                " +\\(r0 = 24.5 mm\\), its peak acceleration ([0-9]+) % high and its jerk ([a-z]+) times the law's");
  const Quartic exact;
  const TempFile file("docs_quartic_2deg.csv", quartic_csv(2.0));
  const RunResult raw = quartic_table(file, "", "t.min_curvature_radius, t.max_acceleration, t.max_jerk");
  check_quote("raw min radius, mm", q[0], scalar_output(raw, "t.min_curvature_radius") / 1e-3);
  check_quote("exact min radius, mm", q[1], exact.min_curvature_radius() / 1e-3);
  check_quote("raw peak acceleration excess, %", q[2], 100 * (scalar_output(raw, "t.max_acceleration") / exact.peak_acceleration() - 1));
  const char* words[] = {"", "", "two", "three", "four", "five", "six", "seven", "eight"};
  const long times = std::lround(scalar_output(raw, "t.max_jerk") / exact.peak_jerk());
  REQUIRE(times < 9);
  CHECK(q[3] == words[times]);
}

TEST_CASE("docs: valvetrain.md, the smoothed quartic (6.400 mm, 1.7 %, 12.8 and 19.9 dof, solves)", "[docs][valvetrain]") {
  const std::string doc = doc_text(doc_name);
  const auto q = quoted(doc, "`resolution` gives the smallest radius of curvature " + n + " mm \\(exact " + n + ", " + n +
                                 " %\\), the peak acceleration " + n + " % low at the event's ends and within " + n +
                                 " % wherever the lift exceeds 20 um, the duration at 1 mm within " + n + " deg, " + n +
                                 " degrees of freedom for ([0-9]+) rows; `gcv` " + n + " mm, " + n + " % and " + n + " degrees of freedom");
  const Quartic exact;
  const TempFile file("docs_quartic_2deg.csv", quartic_csv(2.0));
  const std::string outputs = "t.min_curvature_radius, t.max_acceleration, t.duration, t.smoothing_dof, t.law";
  const RunResult res = quartic_table(file, "resolution", outputs);
  const RunResult gcv = quartic_table(file, "gcv", outputs);
  const double rho = scalar_output(res, "t.min_curvature_radius");
  check_quote("resolution: min radius, mm", q[0], rho / 1e-3);
  check_quote("exact min radius, mm", q[1], exact.min_curvature_radius() / 1e-3);
  check_quote("resolution: min radius error, %", q[2], 100 * (rho / exact.min_curvature_radius() - 1));
  check_quote("resolution: peak acceleration low by, %", q[3], 100 * (1 - scalar_output(res, "t.max_acceleration") / exact.peak_acceleration()));
  // Bounds the doc states: within 1 % where the lift exceeds 20 um, the duration within 0.01 deg.
  const auto law_handle = std::dynamic_pointer_cast<const CamLaw>(output(res, "t.law").as_handle());
  REQUIRE(law_handle);
  const CamLaw& law = *law_handle;
  double worst = 0;
  for (int i = 1; i < 4000; ++i) {
    const double phi = -exact.P + 2 * exact.P * i / 4000;
    if (exact.lift(phi) > 20e-6) worst = std::max(worst, std::abs(law.at(phi).acceleration - exact.acceleration(phi)));
  }
  CHECK(100 * worst / exact.peak_acceleration() <= std::stod(q[4]));
  CHECK(std::abs(scalar_output(res, "t.duration") - exact.duration_at(1e-3)) / deg <= std::stod(q[5]));
  check_quote("resolution: degrees of freedom", q[6], scalar_output(res, "t.smoothing_dof"));
  CHECK(std::stoi(q[7]) == 61);  // the inner rows: every 2 deg strictly inside -62 .. 62 deg
  check_quote("gcv: min radius, mm", q[8], scalar_output(gcv, "t.min_curvature_radius") / 1e-3);
  check_quote("gcv: peak acceleration low by, %", q[9], 100 * (1 - scalar_output(gcv, "t.max_acceleration") / exact.peak_acceleration()));
  check_quote("gcv: degrees of freedom", q[10], scalar_output(gcv, "t.smoothing_dof"));

  // "Penalising s'''' leaves acceleration and jerk free there (1.7 %)": the same figure.
  const auto free_ends = quoted(doc, "Penalising `s''''` leaves acceleration and jerk free there \\(" + n + " %\\)");
  check_quote("resolution: peak acceleration low by, %", free_ends[0],
              100 * (1 - scalar_output(res, "t.max_acceleration") / exact.peak_acceleration()));

  // The solves of the lambda search: 2 deg rows, then 0.1 deg rows (1241 in the event).
  const auto s = quoted(doc, "On the quartic every 2 deg a `resolution` smoothing takes ([0-9]+) solves \\(about [0-9]+ ms\\), `gcv` some ([0-9]+) "
                             "\\([0-9]+ ms\\); every 0.1 deg \\(([0-9]+) rows\\) ([0-9]+) and ([0-9]+) solves");
  const RunResult res_solves = quartic_table(file, "resolution", "t.min_curvature_radius");
  check_quote("resolution: solves, 2 deg rows", s[0], work(res_solves, "t", "solves"));
  check_about("gcv: solves, 2 deg rows", s[1], work(gcv, "t", "solves"), 0.1);
  CHECK(std::stoi(s[2]) == 1241);  // -62 .. 62 deg every 0.1 deg, both ends included
  const TempFile fine("docs_quartic_01deg.csv", quartic_csv(0.1));
  check_quote("resolution: solves, 0.1 deg rows", s[3], work(quartic_table(fine, "resolution", "t.min_curvature_radius"), "t", "solves"));
  check_quote("gcv: solves, 0.1 deg rows", s[4], work(quartic_table(fine, "gcv", "t.min_curvature_radius"), "t", "solves"));
}

TEST_CASE("docs: valvetrain.md, the measured-table example scene (5.86 for 17.25 mm, -4.14 mm, 17.20 and 17.08)", "[docs][valvetrain]") {
  const auto q = quoted(doc_text(doc_name),
                        "raw, the smallest radius of curvature is " + n + " mm for the design's " + n + " \\(the rounding noise in h'' costs " +
                            n + " mm; on a 30 mm base circle the raw spline is undercut, " + n +
                            " mm, and refused by cam.contour under a flat tappet\\); smoothed " + n + " and " + n +
                            "; the smoothed law lies " + n + " um RMS, " + n + " um at most, from the design");
  SceneSpec scene = load_scene(std::string(MECHGRAPH_SOURCE_DIR) + "/scenes/cam_table_measured.yaml");
  scene.outputs.clear();
  for (const char* o : {"raw.min_curvature_radius", "design.min_curvature_radius", "smoothed.min_curvature_radius",
                        "gcv.min_curvature_radius", "smoothed.master_deviation_rms", "smoothed.master_deviation_max"})
    scene.outputs.push_back(port_ref(o));
  MemoCache cache;
  const RunResult r = evaluate(build_graph(scene, project_registry()), cache);
  const double raw = scalar_output(r, "raw.min_curvature_radius") / 1e-3, design = scalar_output(r, "design.min_curvature_radius") / 1e-3;
  check_quote("raw min radius, mm", q[0], raw);
  check_quote("design min radius, mm", q[1], design);
  check_quote("what the rounding noise costs, mm", q[2], design - raw);
  check_quote("smoothed min radius, mm", q[4], scalar_output(r, "smoothed.min_curvature_radius") / 1e-3);
  check_quote("gcv min radius, mm", q[5], scalar_output(r, "gcv.min_curvature_radius") / 1e-3);
  check_quote("deviation from the design, RMS, um", q[6], scalar_output(r, "smoothed.master_deviation_rms") / 1e-6);
  check_quote("deviation from the design, largest, um", q[7], scalar_output(r, "smoothed.master_deviation_max") / 1e-6);

  // On a 30 mm base circle: the raw law's radius, and cam.contour refuses it under a flat tappet.
  const std::string at_30 = "nodes:\n  raw: { type: cam.table, params: { file: '" + std::string(MECHGRAPH_SOURCE_DIR) +
                            "/scenes/data/measured_polydyne_lift.csv', angle_origin: start_of_lift, base_radius: 30 mm } }\n";
  check_quote("raw min radius at r0 30 mm, mm", q[3], scalar_output(run(at_30 + "outputs: [ raw.min_curvature_radius ]\n"), "raw.min_curvature_radius") / 1e-3);
  CHECK_THROWS(run(at_30 + "  cut: { type: cam.contour, inputs: { cam: raw.law }, params: { follower: flat } }\noutputs: [ cut.points ]\n"));
}

TEST_CASE("docs: valvetrain.md, the Hertz example (E* 113.2 GPa, p0 849 MPa) through cam.contour", "[docs][valvetrain]") {
  const auto q = quoted(doc_text(doc_name), "Example: F = " + n + " N, L = " + n + " mm, R = " + n + " mm, two steels \\(E = " + n +
                                                " GPa, nu = " + n + ", E\\* = " + n + " GPa\\) give p0 = " + n + " MPa");
  const double R = std::stod(q[2]) * 1e-3, E = std::stod(q[3]) * 1e9, nu = std::stod(q[4]);
  check_quote("E*, GPa", q[5], 1 / (2 * (1 - nu * nu) / E) / 1e9);
  // Through the node: a flat face on a cam whose least radius of curvature is R (the base radius
  // moves the flat follower's radius rho = r0 + h + h'' by itself), under the load F over L.
  const std::string cam = "nodes:\n  cam: { type: cam.harmonic, params: { max_lift: 8 mm, action_angle: 130 deg, base_radius: ";
  const double rho_at_30 = scalar_output(run(cam + "30 mm } }\noutputs: [ cam.min_curvature_radius ]\n"), "cam.min_curvature_radius");
  char r0[64];
  std::snprintf(r0, sizeof r0, "%.17g mm", (30e-3 + R - rho_at_30) / 1e-3);
  const RunResult r = run(cam + r0 + " } }\n  cut: { type: cam.contour, inputs: { cam: cam.law }, params: { follower: flat, load: " + q[0] +
                          " N, contact_length: " + q[1] + " mm, youngs_modulus: " + q[3] + " GPa, poisson_ratio: " + q[4] +
                          " } }\noutputs: [ cam.min_curvature_radius, cut.max_contact_stress ]\n");
  REQUIRE(std::abs(scalar_output(r, "cam.min_curvature_radius") - R) < 1e-12);
  check_quote("p0, MPa", q[6], scalar_output(r, "cut.max_contact_stress") / 1e6);
}

TEST_CASE("docs: valvetrain.md, the checks of events from TDC and of a harmonic program's joint", "[docs][valvetrain]") {
  const std::string doc = doc_text(doc_name);
  // "a 250 crank-degree event with the intake nose at 110 deg ATDC opens 110 - 125 = -15 deg
  // (15 deg BTDC) and closes at 235 deg (55 deg ABDC)": the seat row of a 125 cam-degree lobe.
  const auto e = quoted(doc, "Check: a ([0-9]+) crank-degree event with the intake nose at ([0-9]+) deg ATDC opens [0-9]+ - [0-9]+ = " + n +
                                 " deg \\(([0-9]+) deg BTDC\\) and closes at ([0-9]+) deg \\(([0-9]+) deg ABDC\\)");
  const RunResult r = run("nodes:\n  cam: { type: cam.harmonic, params: { max_lift: 8 mm, action_angle: " + std::to_string(std::stoi(e[0]) / 2.0) +
                          " deg, base_radius: 20 mm, nose_timing: " + e[1] + " deg } }\noutputs: [ cam.events ]\n");
  const Table& events = table_output(r, "cam.events");
  const auto& lifts = events.axis.values;
  const std::size_t seat = static_cast<std::size_t>(std::find(lifts.begin(), lifts.end(), 0.0) - lifts.begin());
  REQUIRE(seat < lifts.size());
  const double opening = events.find("opening_atdc")->values[seat] / deg, closing = events.find("closing_atdc")->values[seat] / deg;
  check_quote("opening, deg ATDC", e[2], opening);
  check_quote("opening, deg BTDC", e[3], -opening);
  check_quote("closing, deg ATDC", e[4], closing);
  check_quote("closing, deg ABDC", e[5], closing - 180);

  // "a harmonic rise of 8 mm over 50 deg: at -60 deg (base circle / rise 1): the acceleration
  // jumps by 0.0157914 mm/deg^2", the node's own note, and pi^2/2 L/beta^2.
  const auto j = quoted(doc, "a harmonic rise of ([0-9]+) mm over ([0-9]+) deg: \"at " + n + " deg \\(base circle / rise 1\\): the acceleration jumps by " +
                                 n + " mm/deg\\^2\"");
  const RunResult p = run("nodes:\n  p: { type: cam.program, params: { base_radius: 40 mm, segments: [ { type: rise, angle: " + j[1] + " deg, lift: " +
                          j[0] + " mm, law: harmonic }, { type: dwell, angle: 20 deg }, { type: return, angle: " + j[1] + " deg, lift: " + j[0] +
                          " mm, law: harmonic } ] } }\noutputs: [ p.continuity_order ]\n");
  std::string note;
  for (const std::string& line : node_run(p, "p").notes)
    if (line.find("(base circle / rise 1)") != std::string::npos) note = line;
  INFO("the program's note: " << note);
  const auto in_note = quoted(note, "at " + n + " deg \\(base circle / rise 1\\): the acceleration jumps by " + n + " mm/deg\\^2");
  CHECK(in_note[0] == j[2]);
  CHECK(in_note[1] == j[3]);
  check_quote("acceleration jump, mm/deg^2", j[3], pi * pi / 2 * std::stod(j[0]) / (std::stod(j[1]) * std::stod(j[1])));
}

TEST_CASE("docs: valvetrain.md, constants of the method (zeta 0.0535, 1.103, the polydyne's coefficients)", "[docs][valvetrain]") {
  const std::string doc = doc_text(doc_name);
  const auto z = quoted(doc, "by default `xi = " + n + " M_red omega0`.*?\\(since `xi = 2 zeta M_red omega0`: `zeta = " + n + "`, about ([0-9]+) % of critical\\)");
  check_quote("zeta", z[1], std::stod(z[0]) / 2);
  check_about("zeta, % of critical", z[2], 100 * std::stod(z[0]) / 2, 0.1);
  // sigma* = 1 - pi^2 (phi_3 / phi_y)^2 / 12 is positive while phi_3 / phi_y < sqrt(12) / pi.
  const auto k = quoted(doc, "which exists only while `phi_3 < " + n + " phi_y`");
  check_quote("largest phi_3 / phi_y", k[0], std::sqrt(12.0) / pi);
  // C_i = - prod_{j != i} n_j / prod_{j != i} (n_i - n_j) for 2-6-10-14-18.
  const auto c = quoted(doc, "\\(2-6-10-14-18 gives `(-?[0-9]+)/([0-9]+), (-?[0-9]+)/([0-9]+), (-?[0-9]+)/([0-9]+), (-?[0-9]+)/([0-9]+), (-?[0-9]+)/([0-9]+)`\\)");
  const double e[5] = {2, 6, 10, 14, 18};
  for (int i = 0; i < 5; ++i) {
    double num = 1, den = 1;
    for (int jj = 0; jj < 5; ++jj)
      if (jj != i) {
        num *= e[jj];
        den *= e[i] - e[jj];
      }
    const double coefficient = -num / den;
    INFO("C_" << i + 1 << ": the doc says " << c[2 * i] << "/" << c[2 * i + 1] << ", the formula gives " << coefficient);
    CHECK(std::abs(std::stod(c[2 * i]) / std::stod(c[2 * i + 1]) - coefficient) < 1e-12);
  }
  // "the example scene matches 18 deg with [2, 14, 26, 38, 50]"
  const auto p = quoted(doc, "the example scene matches ([0-9]+) deg with `\\[2, 14, 26, 38, 50\\]`");
  const RunResult r = run("nodes:\n  poly: { type: cam.polydyne, params: { max_lift: 8 mm, action_angle: 130 deg, base_radius: 17 mm, "
                          "exponents: [2, 14, 26, 38, 50] } }\noutputs: [ poly.accel_angle ]\n");
  check_quote("polydyne's positive-acceleration angle, deg", p[0], scalar_output(r, "poly.accel_angle") / deg);
}
