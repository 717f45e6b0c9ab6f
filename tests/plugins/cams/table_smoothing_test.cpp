// cam.table on measured tables (plugins/cams/table_law.hpp, smoothing_spline.hpp): a known law
// sampled and rounded as a measuring machine prints it, read raw (the note that curvature and jerk
// are noise) and smoothed (curvature, acceleration, event and residual against the exact law's
// closed forms); GCV against the lambda that is best in hindsight; the resolution read from the
// file; the deviation from a connected master law; hard tables (six rows, a step, rows closer
// than the resolution); the example scene through the CLI. (What docs/methods/valvetrain.md quotes
// of these tables is recomputed in tests/docs/docs_numbers_valvetrain_test.cpp.)
#include "cam_conformance_cases.hpp"
#include "cam_test_support.hpp"
#include "registration.hpp"
#include "rise_law.hpp"
#include "smoothing_spline.hpp"
#include "table_law.hpp"
#include "test_support.hpp"

#include <mechgraph/testing/cam_law_conformance.hpp>

#include <yaml-cpp/yaml.h>

#include <catch2/catch.hpp>

#include <cstdio>
#include <fstream>
#include <iterator>
#include <regex>

#include <cmath>
#include <cstdio>
#include <numbers>

using namespace mechgraph;
using namespace mechgraph::cams;
using namespace mechgraph::cams::testing;
using Catch::Matchers::Contains;
using Catch::Matchers::WithinAbs;
using Catch::Matchers::WithinRel;

namespace {

constexpr double pi = std::numbers::pi;

// The quartic h = H (1 - (phi/P)^2)^2 over |phi| < P: closed forms for what the tests compare.
struct Quartic final : CamLaw {
  double H = 7.5 * mm, P = 62.0 * deg, r0 = 24.5 * mm;
  double event_begin() const override { return -P; }
  double event_end() const override { return P; }
  LiftDerivatives evaluate_in_event(double phi) const override {
    const double u = phi / P, q = 1 - u * u;
    return {H * q * q, -4 * H * u * q / P, H * (12 * u * u - 4) / (P * P), 24 * H * u / (P * P * P)};
  }
  std::vector<double> breakpoints() const override { return {}; }
  double max_lift() const override { return H; }
  double base_radius() const override { return r0; }
  // Flat follower: rho = r0 + h + h'' is smallest at the nose (its derivative, -4u(1-u^2) H +
  // 24 u H / P^2, vanishes only at u = 0 since 6 / P^2 > 1), r0 + H (1 - 4 / P^2).
  double min_curvature_radius() const { return r0 + H * (1 - 4 / (P * P)); }
  // h'' is largest at the ends, 8 H / P^2; h''' too, 24 H / P^3.
  double peak_acceleration() const { return 8 * H / (P * P); }
  double peak_jerk() const { return 24 * H / (P * P * P); }
  // Duration at lift c: (1 - u^2)^2 = c / H.
  double duration_at(double c) const { return 2 * P * std::sqrt(1 - std::sqrt(c / H)); }
};

// A law sampled every `step` from -180 deg .. 180 deg (zero outside its event), the lift printed
// with `decimals` digits of mm, as a measuring machine would (rows counted from the nose).
std::string measured_csv(const CamLaw& law, double step, int decimals) {
  std::string out = "# measured, table_smoothing_test\nangle [deg], lift [mm]\n";
  const double first = std::ceil((law.event_begin() - 3 * step) / step) * step;
  char line[96];
  for (double phi = first; phi <= law.event_end() + 3 * step; phi += step) {
    const double nearest = std::round(phi / step) * step;  // no drift of the angle
    std::snprintf(line, sizeof line, "%.6f, %.*f\n", nearest / deg, decimals, law.at(nearest).lift / mm + 0.0);
    out += line;
  }
  return out;
}

const NodeType& table_type() { return cam_type("cam.table"); }

bool has_note(const OutputSet& out, const std::string& text) {
  for (const std::string& n : out.notes())
    if (n.find(text) != std::string::npos) return true;
  return false;
}

double scalar(const Evaluation& e, const std::string& port) { return e.outputs.all().at(port).as_scalar(); }

}  // namespace

TEST_CASE("measured quartic, 2 deg rows rounded to 1 um: raw it is noise, smoothed it is the law", "[cams][table][smoothing]") {
  const Quartic exact;
  const TempFile file("quartic_2deg_1um.csv", measured_csv(exact, 2.0 * deg, 3));
  const std::map<std::string, std::string> common{{"file", file.path()}, {"base_radius", "24.5 mm"}};

  // Raw: the spline through the rounded rows. The resolution is read from the file (every lift a
  // whole multiple of 0.001 mm) and the note says curvature and jerk mean nothing.
  const Evaluation raw = evaluate_node(table_type(), common);
  CHECK_THAT(scalar(raw, "lift_resolution"), WithinRel(1e-6, 1e-12));
  CHECK(has_note(raw.outputs, "rounded to 1 um"));
  CHECK(has_note(raw.outputs, "not meaningful; set smoothing: resolution"));
  INFO("raw: min radius " << scalar(raw, "min_curvature_radius") / mm << " mm, peak acceleration "
                          << scalar(raw, "max_acceleration") / mm << " mm/rad^2, jerk " << scalar(raw, "max_jerk") / mm);
  CHECK(std::abs(scalar(raw, "min_curvature_radius") / exact.min_curvature_radius() - 1) > 0.1);
  CHECK(scalar(raw, "max_jerk") > 3 * exact.peak_jerk());
  // The noise estimate is of the size the raw figures are off by.
  CHECK(scalar(raw, "acceleration_noise") > 0.01 * exact.peak_acceleration());

  // Smoothed to the stated resolution.
  auto with = common;
  with["smoothing"] = "resolution";
  with["resolution"] = "1 um";
  const Evaluation s = evaluate_node(table_type(), with);
  INFO("smoothed: min radius " << scalar(s, "min_curvature_radius") / mm << " mm (exact "
                               << exact.min_curvature_radius() / mm << "), peak acceleration "
                               << scalar(s, "max_acceleration") / mm << " (exact " << exact.peak_acceleration() / mm
                               << "), jerk " << scalar(s, "max_jerk") / mm << " (exact " << exact.peak_jerk() / mm
                               << "), duration " << scalar(s, "duration") / deg << " deg, lambda "
                               << scalar(s, "smoothing_lambda") << ", dof " << scalar(s, "smoothing_dof"));
  CHECK_THAT(scalar(s, "min_curvature_radius"), WithinRel(exact.min_curvature_radius(), 0.01));
  // The peak acceleration lies at the ends of the event, where the fit has the fewest rows on
  // one side: 2 % there (1 % wherever the lift exceeds 20 um, below).
  CHECK_THAT(scalar(s, "max_acceleration"), WithinRel(exact.peak_acceleration(), 0.02));
  CHECK_THAT(scalar(s, "min_acceleration"), WithinRel(-4 * exact.H / (exact.P * exact.P), 0.01));
  CHECK_THAT(scalar(s, "duration"), WithinAbs(exact.duration_at(1 * mm), 0.01 * deg));  // checking_lift 1 mm
  CHECK_THAT(scalar(s, "max_jerk"), WithinRel(exact.peak_jerk(), 0.15));
  CHECK_THAT(s.law->max_lift(), WithinRel(exact.H, 2e-4));
  // Discrepancy principle: the residual RMS is the RMS of rounding to 1 um.
  CHECK_THAT(scalar(s, "residual_rms"), WithinRel(1e-6 / std::sqrt(12.0), 0.02));
  CHECK(scalar(s, "residual_max") < 1e-6);
  CHECK(scalar(s, "smoothing_dof") > 3.0);
  CHECK(scalar(s, "smoothing_dof") < 30.0);
  CHECK(scalar(s, "jerk_noise") < 0.05 * exact.peak_jerk());
  CHECK(has_note(s.outputs, "lift table smoothed (smoothing: resolution"));
  CHECK_FALSE(has_note(s.outputs, "not meaningful"));
  CHECK(s.context.work.at("solves") > 3);
  CHECK(s.context.work.at("iterations") > 3);
  double worst = 0.0;
  for (int i = 1; i < 4000; ++i) {
    const double phi = -exact.P + 2 * exact.P * i / 4000;
    if (exact.at(phi).lift > 20e-6)
      worst = std::max(worst, std::abs(s.law->at(phi).acceleration - exact.at(phi).acceleration));
  }
  CHECK(worst < 0.01 * exact.peak_acceleration());
  // The law keeps the CamLaw contract: the conformance kit finds nothing, the peaks agree.
  const auto report = mechgraph::testing::check_cam_law(*s.law, "smoothed");
  CHECK(report.count(mechgraph::testing::Check::Status::failed) == 0);
  const auto peaks = mechgraph::testing::check_cam_peaks(*s.law, s.outputs, "smoothed");
  CHECK(peaks.count(mechgraph::testing::Check::Status::failed) == 0);
}

TEST_CASE("GCV picks a lambda of the order that is best in hindsight", "[cams][table][smoothing]") {
  // Best in hindsight: the lambda whose fit is nearest the exact law (RMS of h'' over the event),
  // found on a fine grid; GCV does not know the law.
  for (const double step : {2.0 * deg, 1.0 * deg}) {
    const Quartic exact;
    const TempFile file("quartic_gcv.csv", measured_csv(exact, step, 3));
    const Evaluation g = evaluate_node(table_type(), {{"file", file.path()}, {"base_radius", "24.5 mm"}, {"smoothing", "gcv"}});
    const auto& law = dynamic_cast<const TableLaw&>(*g.law);
    const QuinticSmoother smoother(law.row_angles(), law.row_lifts());
    SmoothingWork work;
    double best_lambda = 0, best_error = 1e300;
    for (double l = -4; l <= 12; l += 0.125) {
      const QuinticPieces p = smoother.pieces(smoother.fit(std::pow(10.0, l), false, work).coefficients);
      double sum = 0;
      for (int i = 1; i < 1000; ++i) {
        const double phi = law.event_begin() + (law.event_end() - law.event_begin()) * i / 1000;
        sum += std::pow(p.at(phi)[2] - exact.at(phi).acceleration, 2);
      }
      if (sum < best_error) best_error = sum, best_lambda = std::pow(10.0, l);
    }
    const double lambda = scalar(g, "smoothing_lambda");
    INFO("step " << step / deg << " deg: GCV lambda " << lambda << ", best " << best_lambda << ", dof "
                 << scalar(g, "smoothing_dof") << ", residual RMS " << scalar(g, "residual_rms") / 1e-6 << " um");
    CHECK(lambda > best_lambda / 10);
    CHECK(lambda < best_lambda * 10);
    // Its residual is of the rounding's size.
    CHECK_THAT(scalar(g, "residual_rms"), WithinRel(1e-6 / std::sqrt(12.0), 0.4));
    CHECK_THAT(scalar(g, "min_curvature_radius"), WithinRel(exact.min_curvature_radius(), 0.01));
  }
}

TEST_CASE("measured harmonic law: 1 deg rows, 1 um, smoothed acceleration within 1 %", "[cams][table][smoothing]") {
  // Not a polynomial: the penalty's null space (cubics) does not hold it.
  const SymmetricRiseReturnLaw exact(RiseShape::harmonic, 8 * mm, 130 * deg, 30 * mm);
  const TempFile file("harmonic_1deg.csv", measured_csv(exact, 1.0 * deg, 3));
  const double peak = 8 * mm / 2 * std::pow(pi / (65 * deg), 2);  // H/2 (pi/P)^2
  for (const char* smoothing : {"resolution", "gcv"}) {
    INFO(smoothing);
    const Evaluation e = evaluate_node(table_type(), {{"file", file.path()}, {"base_radius", "30 mm"}, {"smoothing", smoothing}});
    CHECK_THAT(scalar(e, "max_acceleration"), WithinRel(peak, 0.015));
    CHECK_THAT(scalar(e, "min_acceleration"), WithinRel(-peak, 0.01));
    CHECK_THAT(scalar(e, "min_curvature_radius"), WithinRel(30 * mm + 8 * mm - peak, 0.01));
    CHECK_THAT(scalar(e, "max_velocity"), WithinRel(8 * mm / 2 * pi / (65 * deg), 1e-3));
  }
}

TEST_CASE("the resolution: read from the printed digits, stated, or an error naming it", "[cams][table][smoothing]") {
  const Quartic exact;
  auto quantum = [&](int decimals, double lift_scale) {
    LiftTable t = parse_lift_table(measured_csv(exact, 2.0 * deg, decimals), "q.csv", deg, lift_scale);
    return lift_quantum(t);
  };
  CHECK_THAT(quantum(3, mm), WithinRel(1e-6, 1e-12));
  CHECK_THAT(quantum(4, mm), WithinRel(1e-7, 1e-12));
  CHECK_THAT(quantum(1, mm), WithinRel(1e-4, 1e-12));
  CHECK(quantum(9, mm) == 0.0);  // finer than 1e-6 of the unit: as good as exact
  // Lifts in um printed as whole numbers: 1 um.
  std::string um = "angle,lift\n";
  for (int i = -10; i <= 10; ++i) um += std::to_string(i) + "," + std::to_string(i == -10 || i == 10 ? 0 : 1000 - 10 * i * i) + "\n";
  CHECK_THAT(lift_quantum(parse_lift_table(um, "um.csv", deg, 1e-6)), WithinRel(1e-6, 1e-12));
  // Fewer than 8 rows with lift: nothing to tell from.
  CHECK(lift_quantum(parse_lift_table("-4,0\n-2,1\n0,2\n2,1\n4,0\n", "few.csv", deg, mm)) == 0.0);

  // A table exported with 17 digits has no resolution to read: smoothing resolution then needs it
  // stated, and says so naming the parameter; gcv does not.
  const TempFile exported("quartic_exported.csv", measured_csv(exact, 2.0 * deg, 12));
  const std::map<std::string, std::string> base{{"file", exported.path()}, {"base_radius", "24.5 mm"}};
  auto with = base;
  with["smoothing"] = "resolution";
  try {
    evaluate_node(table_type(), with);
    FAIL("expected a NodeError");
  } catch (const NodeError& e) {
    CHECK(e.parameter() == "resolution");
    CHECK_THAT(e.what(), Contains("Set resolution") && Contains("smoothing: gcv"));
  }
  with["resolution"] = "0.1 um";
  const Evaluation stated = evaluate_node(table_type(), with);
  CHECK_THAT(scalar(stated, "lift_resolution"), WithinRel(1e-7, 1e-12));
  // Exact rows, no resolution: no note, no noise estimate, the residual of an interpolant.
  const Evaluation plain = evaluate_node(table_type(), base);
  CHECK(plain.outputs.notes().empty());
  CHECK(plain.outputs.all().count("lift_resolution") == 0);
  CHECK(plain.outputs.all().count("acceleration_noise") == 0);
  CHECK(scalar(plain, "residual_max") < 1e-15);
  // The host's range check: a resolution of 0 or of 2 mm is refused before the node runs.
  const ParamSpec* spec = table_type().info().find_param("resolution");
  REQUIRE(spec);
  CHECK_FALSE(spec->admits(0.0));
  CHECK_FALSE(spec->admits(2e-3));
  CHECK(spec->admits(1e-6));
}

TEST_CASE("a master law: the table's deviation from it at the table's angles", "[cams][table][smoothing]") {
  const SymmetricRiseReturnLaw design(RiseShape::poly4567, 8 * mm, 130 * deg, 60 * mm);
  const TempFile file("poly4567_1deg.csv", measured_csv(design, 1.0 * deg, 3));
  const std::map<std::string, std::string> params{{"file", file.path()}, {"base_radius", "60 mm"}, {"smoothing", "resolution"}};
  // Unconnected: no deviation outputs.
  CHECK(evaluate_node(table_type(), params).outputs.all().count("master_deviation_rms") == 0);
  InputSet inputs;
  inputs.add("master", Value::handle(std::make_shared<const SymmetricRiseReturnLaw>(design)));
  const Evaluation e = evaluate_node(table_type(), params, inputs);
  // The rows are the design rounded to 1 um: each row within 0.5 um of it (independent of the
  // smoothing), and the smoothed law within about a micrometre.
  const Table& t = e.outputs.all().at("master_deviation").as_table();
  REQUIRE(t.channels.size() == 2);
  const auto& rows = t.find("row_deviation")->values;
  const auto& smoothed = t.find("deviation")->values;
  REQUIRE(rows.size() == t.axis.values.size());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    CHECK(std::abs(rows[i]) <= 0.5e-6 * (1 + 1e-9));
    // The table's own check: the row's deviation is the row minus the design.
    CHECK_THAT(rows[i] + design.at(t.axis.values[i]).lift,
               WithinAbs(std::round(design.at(t.axis.values[i]).lift / 1e-6) * 1e-6, 1e-12));
  }
  CHECK(scalar(e, "master_deviation_rms") < 0.5e-6);
  CHECK(scalar(e, "master_deviation_max") < 1.5e-6);
  double largest = 0;
  for (double v : smoothed) largest = std::max(largest, std::abs(v));
  CHECK_THAT(scalar(e, "master_deviation_max"), WithinRel(largest, 1e-12));
  // A master 1 % higher: the table lies 1 % of its lift below it, 80 um at the nose.
  InputSet higher;
  higher.add("master", Value::handle(std::make_shared<const SymmetricRiseReturnLaw>(RiseShape::poly4567, 8.08 * mm, 130 * deg, 60 * mm)));
  const Evaluation h = evaluate_node(table_type(), params, higher);
  CHECK_THAT(scalar(h, "master_deviation_max"), WithinRel(0.08 * mm, 0.02));
  // A handle of another kind is refused naming the input.
  InputSet wrong;
  struct NotALaw final : DomainObject {
    std::string_view kind() const override { return "spring"; }
  };
  wrong.add("master", Value::handle(std::make_shared<const NotALaw>()));
  try {
    evaluate_node(table_type(), params, wrong);
    FAIL("expected a NodeError");
  } catch (const NodeError& err) {
    CHECK(err.parameter() == "master");
  }
}

TEST_CASE("measured tables, hard cases: six rows, a step, rows closer than the resolution", "[cams][table][smoothing]") {
  // Six rows, the fewest the event takes: smoothing still gives a law within the contract.
  const std::string six = "-60,0\n-40,1.000\n-20,3.000\n0,4.000\n20,3.000\n40,1.000\n60,0\n";
  for (const char* smoothing : {"resolution", "gcv"}) {
    INFO(smoothing);
    const TempFile file("six_rows.csv", six);
    const Evaluation e =
        evaluate_node(table_type(), {{"file", file.path()}, {"base_radius", "60 mm"}, {"smoothing", smoothing}, {"resolution", "1 um"}});
    CHECK(mechgraph::testing::check_cam_law(*e.law, "six").count(mechgraph::testing::Check::Status::failed) == 0);
    CHECK(std::isfinite(scalar(e, "smoothing_dof")));
  }
  // A step: one row 20 um too high. The resolution smoothing cannot reach the rounding's RMS
  // without following it; the residual and a note name the row.
  const Quartic exact;
  std::string text = measured_csv(exact, 2.0 * deg, 3);
  const auto at = text.find("\n10.000000, ");
  REQUIRE(at != std::string::npos);
  const auto end = text.find('\n', at + 1);
  const double lift = std::stod(text.substr(at + 12, end - at - 12));
  char row[64];
  std::snprintf(row, sizeof row, "\n10.000000, %.3f", lift + 0.020);
  text.replace(at, end - at, row);
  const TempFile stepped("quartic_step.csv", text);
  const Evaluation s =
      evaluate_node(table_type(), {{"file", stepped.path()}, {"base_radius", "24.5 mm"}, {"smoothing", "gcv"}});
  INFO("residual max " << scalar(s, "residual_max") / 1e-6 << " um");
  CHECK(scalar(s, "residual_max") > 5e-6);
  CHECK(has_note(s.outputs, "the row at 10 deg"));
  CHECK(has_note(s.outputs, "times the resolution"));
  // Rows closer than 1 um tells apart (0.02 deg): a note says the rounding is a staircase. Raw,
  // the spline through them undercuts a flat tappet's contour: the notes say why and what to set
  // (the law is made; cam.contour refuses it under a flat face).
  const TempFile fine("quartic_fine.csv", measured_csv(exact, 0.02 * deg, 3));
  const Evaluation raw = evaluate_node(table_type(), {{"file", fine.path()}, {"base_radius", "24.5 mm"}});
  CHECK(scalar(raw, "min_curvature_radius") < 0.0);
  CHECK(has_note(raw.outputs, "neighbouring rows have the same lift"));
  CHECK(has_note(raw.outputs, "set smoothing: resolution"));
  const Evaluation f =
      evaluate_node(table_type(), {{"file", fine.path()}, {"base_radius", "24.5 mm"}, {"smoothing", "resolution"}});
  CHECK(has_note(f.outputs, "neighbouring rows have the same lift"));
  CHECK(scalar(f, "min_curvature_radius") > 0.5 * exact.min_curvature_radius());
}

TEST_CASE("the measured-table scene through the CLI: raw, smoothed and GCV against the design", "[scenes][cams][table]") {
  const std::string scene = "'" + std::string(MECHGRAPH_SOURCE_DIR) + "/scenes/cam_table_measured.yaml'";
  const std::string plugins = "--plugin-dir '" + std::string(MECHGRAPH_PLUGIN_DIR) + "' ";
  const auto text = mechgraph::testing::run_cli(plugins + "run " + scene);
  REQUIRE(text.exit_code == 0);
  CHECK_THAT(text.out, Contains("raw: ") && Contains("not meaningful; set smoothing: resolution"));
  CHECK_THAT(text.out, Contains("smoothed: ") && Contains("lift table smoothed (smoothing: resolution"));
  const auto json = mechgraph::testing::run_cli(plugins + "-q run " + scene + " --json");
  REQUIRE(json.exit_code == 0);
  const YAML::Node j = YAML::Load(json.out);
  auto value = [&](const std::string& label) { return j["outputs"][label]["value"].as<double>(); };
  // The smoothed table's deviation from the design is of the rounding's size.
  CHECK(value("smoothed.master_deviation_rms") < 0.5e-6);
  CHECK_THAT(value("smoothed.residual_rms"), WithinRel(1e-6 / std::sqrt(12.0), 0.02));
  CHECK(value("raw.max_jerk") > 5 * value("smoothed.max_jerk"));
  CHECK_THAT(value("smoothed.max_jerk"), WithinRel(value("gcv.max_jerk"), 0.05));
}
