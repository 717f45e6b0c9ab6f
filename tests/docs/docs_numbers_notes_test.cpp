// The results quoted by the smaller notes, recomputed: docs/methods/followers.md (the arm's turn,
// the window of base radii), docs/methods/numerics.md (where the polydyne's radius is least, the
// narrow three-arc flank), docs/methods/uncertainty.md (the Ishigami indices, the rule for zero
// events), docs/bench.md (the spread's uncertainty over seeds) and docs/reports.md (an event quote).
#include "docs/doc_numbers.hpp"

#include <mechgraph/domain/cam_law.hpp>
#include <mechgraph/uncertainty/study_statistics.hpp>

#include <cmath>
#include <cstdio>

using namespace mechgraph;
using namespace mechgraph::testing;
using namespace mechgraph::testing::docs;

namespace {

constexpr double pi = 3.14159265358979323846;
constexpr double deg = pi / 180;
const std::string n = number;

RunResult run(const std::string& yaml) { return run_yaml(yaml, project_registry()); }

}  // namespace

TEST_CASE("docs: followers.md, the arm's turn and the window of base radii of a pivoted flat pad", "[docs][followers]") {
  const std::string doc = doc_text("docs/methods/followers.md");
  const auto turn = quoted(doc, "a cam law of " + n + " mm on a " + n + " mm lever turns the arm " + n + " rad");
  check_quote("the arm's turn h / L, rad", turn[2], std::stod(turn[0]) / std::stod(turn[1]));

  // "(a harmonic lift of 8 mm over 140 deg under a pad 2 mm from a pivot at (-60 mm, 50 mm) on a
  // 10 mm base circle: "only base radii from 20.29 mm to 73.25 mm work")": the message cam.contour gives.
  const auto w = quoted(doc, "\\(a harmonic lift of ([0-9]+) mm over ([0-9]+) deg under a pad ([0-9]+) mm from a pivot at \\(" + n + " mm, " + n +
                                 " mm\\) on a ([0-9]+) mm base circle: \"only base radii from " + n + " mm to " + n + " mm work\"; the suggestion \"take e\\.g\\. " +
                                 n + " mm\"");
  const std::string scene = "nodes:\n  cam: { type: cam.harmonic, params: { max_lift: " + w[0] + " mm, action_angle: " + w[1] + " deg, base_radius: " + w[5] +
                            " mm } }\n  finger: { type: follower.pivoted_flat, params: { pivot_x: " + w[3] + " mm, pivot_y: " + w[4] + " mm, face_offset: " + w[2] +
                            " mm } }\n  cut: { type: cam.contour, inputs: { cam: cam.law, follower: finger.follower } }\noutputs: [ cut.max_pressure_angle ]\n";
  std::string message;
  try {
    run(scene);
  } catch (const std::exception& e) {
    message = e.what();
  }
  INFO("cam.contour says: " << message);
  const auto said = quoted(message, "only base radii from " + n + " mm to " + n + " mm work for this follower \\(it is [0-9.]+ mm\\); take e\\.g\\. " + n + " mm");
  check_quote("smallest base radius, mm", w[6], std::stod(said[0]));
  check_quote("largest base radius, mm", w[7], std::stod(said[1]));
  check_quote("suggested base radius, mm", w[8], std::stod(said[2]));
  // The suggestion's rule: the limit plus 1 %, rounded up to 0.1 mm.
  check_quote("the limit plus 1 %, rounded up to 0.1 mm", w[8], std::ceil(std::stod(said[0]) * 1.01 * 10) / 10);
}

TEST_CASE("docs: numerics.md, the polydyne's least radius at +-7.026 deg and the narrow three-arc flank", "[docs][numerics]") {
  const std::string doc = doc_text("docs/methods/numerics.md");
  const auto p = quoted(doc, "A polydyne cam \\[2, 6, 10, 14, 18\\] of ([0-9]+) mm over ([0-9]+) deg has its smallest radius of curvature twice, at "
                             "\\+-" + n + " deg, with a local maximum at the nose between them");
  const RunResult r = run("nodes:\n  poly: { type: cam.polydyne, params: { max_lift: " + p[0] + " mm, action_angle: " + p[1] +
                          " deg, base_radius: 30 mm } }\noutputs: [ poly.law ]\n");
  const auto law_handle = std::dynamic_pointer_cast<const CamLaw>(output(r, "poly.law").as_handle());
  REQUIRE(law_handle);
  const CamLaw& law = *law_handle;
  auto rho = [&](double phi) {  // the flat follower's radius less r0: h + h''
    const LiftDerivatives d = law.at(phi);
    return d.lift + d.acceleration;
  };
  // Golden-section search for the minimum on each side of the nose, then the nose's local maximum.
  auto minimum = [&](double a, double b) {
    const double g = (std::sqrt(5.0) - 1) / 2;
    for (int i = 0; i < 200; ++i) {
      const double c = b - g * (b - a), d = a + g * (b - a);
      if (rho(c) < rho(d))
        b = d;
      else
        a = c;
    }
    return (a + b) / 2;
  };
  const double right = minimum(0.5 * deg, 30 * deg), left = minimum(-30 * deg, -0.5 * deg);
  check_quote("the least radius's angle, deg", p[2], right / deg);
  check_quote("the least radius's angle (mirrored), deg", p[2], -left / deg);
  CHECK(rho(0.0) > rho(right));

  // "(a three-arc flank of 0.037 deg gave a maximum acceleration of 0)": issue 29's cam, max_lift
  // 9 mm, action_angle 120 deg, base_radius 18 mm, nose_radius 8.99 mm; its flank is that wide.
  const auto f = quoted(doc, "\\(a three-arc flank of " + n + " deg gave a maximum acceleration of 0\\)");
  const RunResult arc = run("nodes:\n  arc: { type: cam.three_arc, params: { max_lift: 9 mm, action_angle: 120 deg, base_radius: 18 mm, "
                            "nose_radius: 8.99 mm } }\noutputs: [ arc.accel_angle, arc.max_acceleration ]\n");
  check_quote("flank width, deg", f[0], scalar_output(arc, "arc.accel_angle") / deg);
  CHECK(scalar_output(arc, "arc.max_acceleration") > 0);
}

TEST_CASE("docs: uncertainty.md, the Ishigami indices and zero events in 1000 samples", "[docs][uncertainty]") {
  const std::string doc = doc_text("docs/methods/uncertainty.md");
  const auto q = quoted(doc, "the Ishigami function \\(a = " + n + ", b = " + n + ", x_i uniform on \\[-pi, pi\\]: S = " + n + ", " + n + ", " + n +
                                 "; ST = " + n + ", " + n + ", " + n + "\\)");
  // Closed forms (Sobol' and Levitan 1999): V = a^2/8 + b pi^4/5 + b^2 pi^8/18 + 1/2,
  // V1 = 1/2 (1 + b pi^4/5)^2, V2 = a^2/8, V13 = b^2 pi^8 (1/18 - 1/50).
  const double a = std::stod(q[0]), b = std::stod(q[1]);
  const double pi4 = std::pow(pi, 4), pi8 = std::pow(pi, 8);
  const double V = a * a / 8 + b * pi4 / 5 + b * b * pi8 / 18 + 0.5;
  const double V1 = 0.5 * (1 + b * pi4 / 5) * (1 + b * pi4 / 5), V2 = a * a / 8, V13 = b * b * pi8 * (1.0 / 18 - 1.0 / 50);
  check_quote("S1", q[2], V1 / V);
  check_quote("S2", q[3], V2 / V);
  check_quote("S3", q[4], 0.0);
  check_quote("ST1", q[5], (V1 + V13) / V);
  check_quote("ST2", q[6], V2 / V);
  check_quote("ST3", q[7], V13 / V);

  const auto z = quoted(doc, "0 events in ([0-9]+) samples say the probability is below " + n + " % at ([0-9]+) %");
  const Proportion p = proportion(0, std::stoul(z[0]), std::stod(z[2]) / 100);
  REQUIRE(p.clopper_pearson.upper);
  check_quote("Clopper-Pearson upper end, %", z[1], 100 * *p.clopper_pearson.upper);
}

TEST_CASE("docs: bench.md, the uncertainty of a spread over 8 and 16 seeds", "[docs][bench]") {
  const auto q = quoted(doc_text("docs/bench.md"), "s / sqrt\\(2 \\(K - 1\\)\\) \\(" + n + " % for ([0-9]+) seeds, " + n + " % for ([0-9]+)\\)");
  check_quote("relative uncertainty, 8 seeds, %", q[0], 100 / std::sqrt(2.0 * (std::stoi(q[1]) - 1)));
  check_quote("relative uncertainty, 16 seeds, %", q[2], 100 / std::sqrt(2.0 * (std::stoi(q[3]) - 1)));
}

TEST_CASE("docs: reports.md, the valve event quote is the valve-train study's", "[docs][reports]") {
  const auto q = quoted(doc_text("docs/reports.md"), "\\(\"opens " + n + " ATDC, closes " + n + " ABDC\"\\)");
  const CommandResult r = run_cli("--plugin-dir '" + std::string(MECHGRAPH_PLUGIN_DIR) + "' -q run '" + std::string(MECHGRAPH_SOURCE_DIR) +
                                  "/scenes/valvetrain_cams.yaml'");
  REQUIRE(r.exit_code == 0);
  const auto said = quoted(r.out, "v_kurz: intake: opens " + n + " deg ATDC, closes " + n + " deg ABDC");
  check_quote("opens, deg ATDC", q[0], std::stod(said[0]));
  check_quote("closes, deg ABDC", q[1], std::stod(said[1]));
}

TEST_CASE("docs: bench.md, the tolerance listing and the integrators' floor on the elastic drive", "[docs][bench]") {
  const CommandResult r = run_cli("--plugin-dir '" + std::string(MECHGRAPH_PLUGIN_DIR) + "' -q bench '" + std::string(MECHGRAPH_SOURCE_DIR) +
                                  "/scenes/valvetrain_dynamics.yaml' --node elastic --tol 1e-5");
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  // The times, the Pareto marks they set and the advice (the cheapest setting) are measurements:
  // masked on both sides; the settings, errors, worst outputs, work and the reference are results.
  auto without_times = [](const std::string& text) {
    std::string kept;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) {
      if (line.rfind("  ->", 0) == 0) continue;
      kept += std::regex_replace(line, std::regex("^(\\s+[0-9.e+-]+\\s+)(\\*?)P?(\\s+)[0-9.e+-]+"), "$1$2$3time") + "\n";
    }
    return kept;
  };
  const std::vector<std::string> problems =
      block_mismatches(without_times(fenced_block("docs/bench.md", "elastic (valvetrain.dynamics) knob tolerance")), without_times(r.out));
  std::string all;
  for (const std::string& p : problems) all += p + "\n";
  INFO("docs/bench.md's tolerance listing, lines the tool no longer prints so (times masked):\n" << all);
  CHECK(problems.empty());

  const auto q = quoted(doc_text("docs/bench.md"), "moves the `cvode` reference by " + n + " \\(most in `residual_amplitude`\\): `cvode` itself then reads \"< " + n +
                                                       "\", `dopri5` " + n);
  const CommandResult all_knobs = run_cli("--plugin-dir '" + std::string(MECHGRAPH_PLUGIN_DIR) + "' -q bench '" + std::string(MECHGRAPH_SOURCE_DIR) +
                                          "/scenes/valvetrain_dynamics.yaml' --node elastic");
  REQUIRE(all_knobs.exit_code == 0);
  const auto floor = quoted(all_knobs.out, "knob integrator\\s+reference: integrator = cvode;[^\\n]*moves it by " + n + " in all \\(most in elastic\\.residual_amplitude\\)");
  check_quote("the integrator reference's floor", q[0], std::stod(floor[0]));
  const auto cvode = quoted(all_knobs.out, "\\n  cvode +\\*?P? +[0-9.e+-]+ +< " + n + " ");
  check_quote("cvode's error, below the floor", q[1], std::stod(cvode[0]));
  const auto dopri5 = quoted(all_knobs.out, "\\n  dopri5 +\\*?P? +[0-9.e+-]+ +" + n + " ");
  check_quote("dopri5's error", q[2], std::stod(dopri5[0]));
}

TEST_CASE("docs: scenes.md, a lift table of 65000 rows is refused by the memory budget, naming its rows", "[docs][scenes]") {
  // "So a table of 65000 rows, 0.9 MB, rounded to 1 um, is refused by the memory budget, naming
  // `t.file (about 65013 rows, smoothing none)`": a cycloidal lift of 8 mm over 130 deg every
  // 0.002 deg (5 rows of base circle each side), as tests/hostile/hostile_bounds_test.cpp writes it.
  const auto q = quoted(doc_text("docs/scenes.md"), "So a table of ([0-9]+) rows, " + n + " MB, rounded to 1 um, is refused by the memory budget, "
                                                   "naming `t\\.file \\(about ([0-9]+) rows, smoothing none\\)`");
  const long rows = std::stol(q[0]);
  std::string text = "angle,lift\n";
  char row[64];
  for (long i = -5; i <= rows + 5; ++i) {
    const double a = static_cast<double>(i) * 130.0 / static_cast<double>(rows), x = std::min(a, 130.0 - a) / 130.0;
    const double h = a <= 0.0 || a >= 130.0 ? 0.0 : 8.0 * (x - std::sin(2.0 * pi * x) / (2.0 * pi));
    std::snprintf(row, sizeof row, "%.4f,%.3f\n", a, h);
    text += row;
  }
  check_quote("the file's size, MB", q[1], static_cast<double>(text.size()) / 1e6);
  const TempFile table("docs_fine_table.csv", text);
  const TempFile scene("docs_fine_table.yaml", "nodes:\n  t: { type: cam.table, params: { file: '" + table.path() +
                                                   "', angle_origin: start_of_lift, base_radius: 35 mm } }\noutputs: [ t.max_lift ]\n");
  const CommandResult r = run_cli("--plugin-dir '" + std::string(MECHGRAPH_PLUGIN_DIR) + "' run '" + scene.path() + "'");
  INFO(r.err);
  CHECK(r.exit_code == 2);
  CHECK(r.err.find("--max-memory") != std::string::npos);
  CHECK(r.err.find("t.file (about " + q[2] + " rows, smoothing none)") != std::string::npos);
}
