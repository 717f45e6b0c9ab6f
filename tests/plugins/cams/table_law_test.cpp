// cam.table (plugins/cams/table_law.hpp): the CSV reader and its file:line errors, the quintic
// interpolant (exact on polynomials of degree <= 5, convergent on an analytic law sampled into a
// CSV by the test), and the node's checks against max_lift and action_angle.
#include "cam_conformance_cases.hpp"
#include "registration.hpp"
#include "rise_law.hpp"
#include "table_law.hpp"

#include <catch2/catch.hpp>

#include <algorithm>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>

using namespace mechgraph;
using namespace mechgraph::cams;
using namespace mechgraph::cams::testing;

namespace {

constexpr double pi = std::numbers::pi;

// The NodeError a parse raises (parameter and message), or empty strings.
std::pair<std::string, std::string> parse_error(const std::string& text) {
  try {
    TableLaw(parse_lift_table(text, "t.csv", deg, mm), 0.02);
  } catch (const NodeError& e) {
    return {e.parameter(), e.what()};
  }
  return {};
}

// A CSV of a law sampled every `step` over its event (angles in deg, lift in mm).
std::string sampled_csv(const CamLaw& law, double step) {
  std::string out = "# sampled by table_law_test\nangle, lift\n";
  const int n = static_cast<int>(std::lround((law.event_end() - law.event_begin()) / step));
  char line[96];
  for (int i = 0; i <= n; ++i) {
    const double phi = i == n ? law.event_end() : law.event_begin() + i * step;
    const double lift = (i == 0 || i == n) ? 0.0 : law.at(phi).lift;
    std::snprintf(line, sizeof line, "%.17g, %.17g\n", phi / deg, lift / mm);
    out += line;
  }
  return out;
}

const NodeType& table_type() {
  static const NodeTypeList types = [] {
    NodeTypeList t;
    add_standard_law_types(t);
    return t;
  }();
  return *find_type(types, "cam.table");
}

std::string node_error(const std::map<std::string, std::string>& values) {
  try {
    evaluate_node(table_type(), values);
  } catch (const NodeError& e) {
    return e.parameter();
  }
  return "(no error)";
}

}  // namespace

TEST_CASE("lift table parsing: separators, comments, header, units", "[cams][table]") {
  const std::string text =
      "# a measured cam\n"
      "angle (deg), lift (mm)\n"
      "\n"
      "-3, 0\n"
      "-2; 0.5\n"
      "-1 1.0   # blank separated\n"
      "0,\t1.5\r\n"
      "+1, 1.0e0\n";
  const LiftTable t = parse_lift_table(text, "t.csv", deg, mm);
  REQUIRE(t.rows.size() == 5);
  CHECK(t.rows[0].line == 4);
  CHECK(t.rows[4].line == 8);
  CHECK(t.rows[1].angle == Approx(-2.0 * deg).epsilon(1e-15).margin(0.0));
  CHECK(t.rows[1].lift == Approx(0.5 * mm).epsilon(1e-15).margin(0.0));
  CHECK(t.rows[3].lift == Approx(1.5 * mm).epsilon(1e-15).margin(0.0));
  CHECK(t.rows[4].angle == Approx(1.0 * deg).epsilon(1e-15).margin(0.0));
}

TEST_CASE("lift table errors name file:line", "[cams][table]") {
  auto check = [](const std::string& text, const std::string& where, const std::string& what) {
    const auto [parameter, message] = parse_error(text);
    INFO(message);
    CHECK(parameter == "file");
    CHECK_THAT(message, Catch::Matchers::StartsWith(where));
    CHECK_THAT(message, Catch::Matchers::Contains(what));
  };
  const std::string head = "angle,lift\n-3,0\n-2,0.4\n";
  check(head + "-1,abc\n", "t.csv:4:", "expected two finite numbers");
  check(head + "-1,1,2\n", "t.csv:4:", "expected two finite numbers");
  check(head + "-1,nan\n", "t.csv:4:", "expected two finite numbers");
  check(head + "angle,lift\n", "t.csv:4:", "expected two finite numbers");  // one header only
  check(head + "-2,0.9\n", "t.csv:4:", "does not increase");
  check(head + "-2.5,0.9\n", "t.csv:4:", "does not increase");
  check(head + "-1,-0.1\n", "t.csv:4:", "negative lift");
  // The event: lift must start and end at zero, at least 6 rows, within +-180 deg.
  check("-3,0.1\n-2,1\n-1,2\n0,3\n1,2\n2,1\n3,0\n", "t.csv:1:", "must start from zero");
  check("-3,0\n-2,1\n-1,2\n0,3\n1,2\n2,1\n3,0.2\n", "t.csv:7:", "must return to zero");
  check("-2,0\n-1,1\n0,2\n1,1\n2,0\n", "t.csv:", "needs at least 6");
  check("-3,0\n-2,0\n3,0\n", "t.csv:", "no lift");
  check("-181,0\n-100,1\n-50,2\n0,3\n50,2\n100,1\n170,0\n", "t.csv:", "within -180 .. 180");
  // A missing file.
  try {
    read_lift_table("/nonexistent/lift.csv", deg, mm);
    FAIL("expected a NodeError");
  } catch (const NodeError& e) {
    CHECK(e.parameter() == "file");
    CHECK_THAT(e.what(), Catch::Matchers::Contains("/nonexistent/lift.csv"));
  }
}

TEST_CASE("lift table: base-circle rows are trimmed to one on each side", "[cams][table]") {
  const std::string text = "-90,0\n-60,0\n-30,0\n-20,1\n-10,3\n0,4\n10,3\n20,1\n30,0\n60,0\n";
  const TableLaw law(parse_lift_table(text, "t.csv", deg, mm), 0.02);
  CHECK(law.event_begin() == Approx(-30.0 * deg).epsilon(1e-15).margin(0.0));
  CHECK(law.event_end() == Approx(30.0 * deg).epsilon(1e-15).margin(0.0));
  CHECK(law.first_line() == 3);
  CHECK(law.last_line() == 9);
  // The spline's interior knots are the breakpoints (each quintic piece a smooth piece for the
  // searches): strictly inside the event, ascending.
  const std::vector<double> breaks = law.breakpoints();
  REQUIRE_FALSE(breaks.empty());
  CHECK(breaks.front() > law.event_begin());
  CHECK(breaks.back() < law.event_end());
  CHECK(std::is_sorted(breaks.begin(), breaks.end()));
  // The interpolant passes through every row.
  CHECK(law.at(-10.0 * deg).lift == Approx(3.0 * mm).epsilon(1e-13).margin(1e-18));
  CHECK(law.at(0.0).lift == Approx(4.0 * mm).epsilon(1e-13).margin(1e-18));
  CHECK(law.at(40.0 * deg).lift == 0.0);
}

TEST_CASE("quintic interpolation reproduces polynomials of degree <= 5 exactly", "[cams][table]") {
  // Uneven rows over [-P, P]; h = H q(u), u = phi/P.
  const double H = 9.0 * mm, P = 60.0 * deg;
  std::vector<double> u;
  for (int i = 0; i <= 40; ++i) {
    const double even = -1.0 + 2.0 * i / 40.0;
    u.push_back(i == 0 || i == 40 ? even : even + 0.012 * std::sin(7.3 * i));
  }
  struct Poly {
    const char* name;
    double (*q)(double), (*q1)(double), (*q2)(double), (*q3)(double);
  };
  const Poly polys[] = {
      // (1 - u^2)^2: symmetric, degree 4.
      {"(1-u^2)^2", [](double x) { return (1 - x * x) * (1 - x * x); }, [](double x) { return -4 * x * (1 - x * x); },
       [](double x) { return -4 + 12 * x * x; }, [](double x) { return 24 * x; }},
      // (1 - u^2)^2 (1 + 0.3 u) = 1 + 0.3u - 2u^2 - 0.6u^3 + u^4 + 0.3u^5: degree 5, asymmetric.
      {"(1-u^2)^2 (1+0.3u)", [](double x) { return (1 - x * x) * (1 - x * x) * (1 + 0.3 * x); },
       [](double x) { return 0.3 - 4 * x - 1.8 * x * x + 4 * x * x * x + 1.5 * x * x * x * x; },
       [](double x) { return -4 - 3.6 * x + 12 * x * x + 6 * x * x * x; },
       [](double x) { return -3.6 + 24 * x + 18 * x * x; }},
  };
  for (const Poly& p : polys) {
    INFO(p.name);
    LiftTable table;
    table.source = "poly";
    for (std::size_t i = 0; i < u.size(); ++i)
      table.rows.push_back({u[i] * P, (i == 0 || i + 1 == u.size()) ? 0.0 : H * p.q(u[i]), static_cast<int>(i + 1)});
    const TableLaw law(table, 0.02);
    for (int i = 1; i < 500; ++i) {
      const double x = -1.0 + 2.0 * i / 500.0;
      const LiftDerivatives d = law.at(x * P);
      INFO("u = " << x);
      CHECK(d.lift == Approx(H * p.q(x)).epsilon(1e-10).margin(1e-12 * H));
      CHECK(d.velocity == Approx(H * p.q1(x) / P).epsilon(1e-9).margin(1e-11 * H / P));
      CHECK(d.acceleration == Approx(H * p.q2(x) / (P * P)).epsilon(1e-8).margin(1e-10 * H / (P * P)));
      CHECK(d.jerk == Approx(H * p.q3(x) / (P * P * P)).epsilon(1e-7).margin(1e-9 * H / (P * P * P)));
    }
  }
}

TEST_CASE("cam.table against the harmonic law sampled into a CSV", "[cams][table][node]") {
  // h = H (1 + cos(pi phi/P))/2 on [-P, P]: analytic inside the event, so the quintic spline's
  // error falls like step^(6-k) for the k-th derivative.
  const double H = 9.0 * mm, action = 130.0 * deg, P = 0.5 * action;
  const SymmetricRiseReturnLaw exact(RiseShape::harmonic, H, action, 0.06);
  const double scale[4] = {H, H * pi / (2 * P), H * pi * pi / (2 * P * P), H * std::pow(pi, 3) / (2 * P * P * P)};
  auto max_errors = [&](double step) {
    const TempFile file("harmonic_" + std::to_string(step) + ".csv", sampled_csv(exact, step));
    const Evaluation e = evaluate_node(table_type(), {{"file", file.path()}, {"max_lift", "9 mm"}, {"action_angle", "130 deg"},
                                                      {"base_radius", "60 mm"}});
    std::array<double, 4> err{};
    for (int i = 1; i < 4000; ++i) {
      const double phi = -P + 2.0 * P * i / 4000.0;
      const LiftDerivatives a = e.law->at(phi), b = exact.at(phi);
      err[0] = std::max(err[0], std::abs(a.lift - b.lift) / scale[0]);
      err[1] = std::max(err[1], std::abs(a.velocity - b.velocity) / scale[1]);
      err[2] = std::max(err[2], std::abs(a.acceleration - b.acceleration) / scale[2]);
      err[3] = std::max(err[3], std::abs(a.jerk - b.jerk) / scale[3]);
    }
    const auto& out = e.outputs.all();
    CHECK(out.at("max_velocity").as_scalar() == Approx(scale[1]).epsilon(1e-7).margin(0.0));
    CHECK(out.at("max_acceleration").as_scalar() == Approx(scale[2]).epsilon(1e-4).margin(0.0));
    CHECK(out.at("min_acceleration").as_scalar() == Approx(-scale[2]).epsilon(1e-6).margin(0.0));
    CHECK(out.at("accel_angle").as_scalar() == Approx(0.5 * P).epsilon(1e-6).margin(0.0));
    CHECK(e.law->max_lift() == Approx(H).epsilon(1e-10).margin(0.0));
    return err;
  };
  const auto coarse = max_errors(1.0 * deg);
  const auto fine = max_errors(0.5 * deg);
  INFO("relative errors, 1 deg rows: " << coarse[0] << " " << coarse[1] << " " << coarse[2] << " " << coarse[3]);
  INFO("relative errors, 0.5 deg rows: " << fine[0] << " " << fine[1] << " " << fine[2] << " " << fine[3]);
  CHECK(fine[0] < 1e-9);
  CHECK(fine[1] < 1e-7);
  CHECK(fine[2] < 1e-5);
  CHECK(fine[3] < 1e-3);
  // Halving the step: at least 2^(5-k) smaller (the order is 6-k near the not-a-knot ends).
  for (int k = 0; k < 4; ++k) {
    INFO("derivative " << k);
    CHECK(coarse[k] / fine[k] > std::pow(2.0, 5 - k));
  }
}

TEST_CASE("cam.table checks the table against max_lift and action_angle, units", "[cams][table][node]") {
  const double H = 9.0 * mm, action = 130.0 * deg;
  const SymmetricRiseReturnLaw exact(RiseShape::poly4567, H, action, 0.06);
  const TempFile file("poly4567.csv", sampled_csv(exact, 1.0 * deg));
  const std::map<std::string, std::string> ok{
      {"file", file.path()}, {"max_lift", "9 mm"}, {"action_angle", "130 deg"}, {"base_radius", "60 mm"}};
  CHECK(node_error(ok) == "(no error)");
  auto with = [&](const std::string& key, const std::string& value) {
    auto v = ok;
    v[key] = value;
    return v;
  };
  CHECK(node_error(with("max_lift", "9.008 mm")) == "(no error)");  // within 0.1 %
  CHECK(node_error(with("max_lift", "9.1 mm")) == "max_lift");
  CHECK(node_error(with("action_angle", "131 deg")) == "action_angle");
  CHECK(node_error(with("lift_unit", "kg")) == "lift_unit");
  CHECK(node_error(with("lift_unit", "furlong")) == "lift_unit");
  CHECK(node_error(with("angle_unit", "mm")) == "angle_unit");
  CHECK(node_error(with("file", "/nonexistent/lift.csv")) == "file");
  // The same table in rad and inches.
  std::string text = "angle_rad lift_in\n";
  char line[96];
  for (int i = 0; i <= 130; ++i) {
    const double phi = i == 130 ? exact.event_end() : exact.event_begin() + i * deg;
    std::snprintf(line, sizeof line, "%.17g %.17g\n", phi, (i == 0 || i == 130) ? 0.0 : exact.at(phi).lift / 0.0254);
    text += line;
  }
  const TempFile imperial("poly4567_in.csv", text);
  auto v = ok;
  v["file"] = imperial.path();
  v["angle_unit"] = "rad";
  v["lift_unit"] = "in";
  const Evaluation e = evaluate_node(table_type(), v);
  CHECK(e.law->at(-20.0 * deg).lift == Approx(exact.at(-20.0 * deg).lift).epsilon(1e-9).margin(1e-15));
  // A ramp on a table: the table is the main law, max_lift the total.
  const RampSpec ramp{RampType::cosine, 0.3 * mm, 20.0 * deg};
  const double main = H - ramp_lift_at_nose(ramp, 0.5 * action);
  const SymmetricRiseReturnLaw smaller(RiseShape::poly4567, main, action, 0.06);
  const TempFile net("poly4567_net.csv", sampled_csv(smaller, 1.0 * deg));
  const Evaluation r = evaluate_node(table_type(), {{"file", net.path()}, {"max_lift", "9 mm"}, {"action_angle", "130 deg"},
                                                    {"base_radius", "60 mm"}, {"ramp", "cosine"}, {"ramp_height", "0.3 mm"},
                                                    {"ramp_length", "20 deg"}});
  CHECK(r.law->at(0.0).lift == Approx(H).epsilon(1e-9).margin(0.0));
  CHECK(r.law->event_end() == Approx(85.0 * deg).epsilon(1e-14).margin(0.0));
}

TEST_CASE("cam.table from lists (angles, lifts): the file's law and the file's checks", "[cams][table][node]") {
  // The rows of a file, parsed to SI, given instead as the lists the Python module passes: the same
  // rows make the same quintic spline, so the laws agree to rounding everywhere in the event.
  const SymmetricRiseReturnLaw exact(RiseShape::harmonic, 9.0 * mm, 130.0 * deg, 0.06);
  const std::string csv = sampled_csv(exact, 1.0 * deg);
  const TempFile file("listed_harmonic.csv", csv);
  const LiftTable rows = parse_lift_table(csv, "t.csv", deg, mm);
  std::vector<double> angles, lifts;
  for (const LiftTableRow& r : rows.rows) {
    angles.push_back(r.angle);
    lifts.push_back(r.lift);
  }
  auto evaluate_lists = [&](std::vector<double> a, std::vector<double> h, bool with_file = false) {
    ParamSet p = make_params(table_type().info(), with_file ? std::map<std::string, std::string>{{"base_radius", "60 mm"}, {"file", file.path()}}
                                                            : std::map<std::string, std::string>{{"base_radius", "60 mm"}});
    p.set("angles", ParamValue::of_list(std::move(a)));
    p.set("lifts", ParamValue::of_list(std::move(h)));
    Evaluation e;
    table_type().evaluate(p, {}, e.outputs, e.context);
    e.law = std::dynamic_pointer_cast<const CamLaw>(e.outputs.all().at("law").as_handle());
    return e;
  };
  auto error_of = [&](std::vector<double> a, std::vector<double> h, bool with_file = false) -> std::pair<std::string, std::string> {
    try {
      evaluate_lists(std::move(a), std::move(h), with_file);
    } catch (const NodeError& e) {
      return {e.parameter(), e.what()};
    }
    return {"(no error)", ""};
  };

  const Evaluation listed = evaluate_lists(angles, lifts);
  const Evaluation filed = evaluate_node(table_type(), {{"file", file.path()}, {"base_radius", "60 mm"}});
  for (int i = 1; i < 400; ++i) {
    const double phi = listed.law->event_begin() + (listed.law->event_end() - listed.law->event_begin()) * i / 400.0;
    const LiftDerivatives a = listed.law->at(phi), b = filed.law->at(phi);
    CHECK(a.lift == Approx(b.lift).epsilon(1e-14).margin(1e-18));
    CHECK(a.acceleration == Approx(b.acceleration).epsilon(1e-12).margin(1e-15));
  }
  CHECK(listed.law->max_lift() == Approx(9.0 * mm).epsilon(1e-10).margin(0.0));

  // The file's checks, naming the lists and the pair at fault ("lifts:N").
  auto reversed = angles;
  std::reverse(reversed.begin(), reversed.end());
  const auto decreasing = error_of(reversed, lifts);
  CHECK(decreasing.first == "lifts");
  CHECK_THAT(decreasing.second, Catch::Contains("lifts:2:") && Catch::Contains("increase"));
  auto negative = lifts;
  negative[10] = -1e-6;
  const auto below = error_of(angles, negative);
  CHECK(below.first == "lifts");
  CHECK_THAT(below.second, Catch::Contains("lifts:11:"));
  CHECK(error_of(angles, std::vector<double>(lifts.begin(), lifts.end() - 1)).first == "lifts");  // not as long
  CHECK(error_of(std::vector<double>(angles.begin(), angles.begin() + 4), std::vector<double>(lifts.begin(), lifts.begin() + 4)).first == "lifts");  // too few
  CHECK(error_of(angles, lifts, true).first == "file");  // a file and lists: which one?
  CHECK(node_error({{"base_radius", "60 mm"}}) == "file");  // neither
}
