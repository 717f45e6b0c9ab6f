// cam.program: segments against the closed forms of their laws, the joint report (which derivative
// jumps where, by how much), the SDK kit's CamLaw checks on an asymmetric program, and refusals.
#include "cam_test_support.hpp"
#include "program_law.hpp"

#include <mechgraph/testing/cam_law_conformance.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

namespace mechgraph::cams {
namespace {

constexpr double pi = std::numbers::pi;
constexpr double deg = pi / 180.0;

Record segment(const char* type, double angle, double lift = 0.0, const char* law = "cycloidal") {
  Record r{{"type", ParamValue::of_choice(type)}, {"angle", ParamValue::of_number(angle)}, {"law", ParamValue::of_choice(law)}};
  if (lift > 0.0) r["lift"] = ParamValue::of_number(lift);
  return r;
}

OutputSet run_program(std::vector<Record> segments, mechgraph::testing::RecordingContext* ctx_out = nullptr) {
  NodeTypeList types;
  add_program_type(types);
  ParamValue v;
  v.kind = ParamKind::record_list;
  v.records = std::move(segments);
  OutputSet out;
  mechgraph::testing::RecordingContext ctx;
  types.front()->evaluate(mechgraph::testing::defaults_of(types.front()->info(), {{"segments", v}, {"base_radius", ParamValue::of_number(100e-3)}}),
                          InputSet{}, out, ctx);
  if (ctx_out) *ctx_out = ctx;
  return out;
}

TEST_CASE("cam.program: asymmetric rise, dwell and return follow their laws' closed forms") {
  // 3-4-5 rise of 9 mm over 60 deg, dwell 10 deg, cycloidal return over 80 deg: event 150 deg from -75.
  const OutputSet out = run_program({segment("rise", 60 * deg, 9e-3, "poly345"), segment("dwell", 10 * deg),
                                     segment("return", 80 * deg, 9e-3, "cycloidal")});
  const auto law = std::dynamic_pointer_cast<const CamLaw>(out.all().at("law").as_handle());
  REQUIRE(law);
  CHECK_THAT(law->event_begin(), Catch::Matchers::WithinAbs(-75 * deg, 1e-15));
  CHECK_THAT(law->event_end(), Catch::Matchers::WithinAbs(75 * deg, 1e-15));
  CHECK(law->max_lift() == 9e-3);
  // Rise at x = 0.3: s = 10x^3 - 15x^4 + 6x^5, s' = 30x^2 (1 - x)^2.
  const double x = 0.3, phi = -75 * deg + x * 60 * deg;
  const LiftDerivatives r = law->at(phi);
  CHECK_THAT(r.lift, Catch::Matchers::WithinRel(9e-3 * (10 * x * x * x - 15 * std::pow(x, 4) + 6 * std::pow(x, 5)), 1e-13));
  CHECK_THAT(r.velocity, Catch::Matchers::WithinRel(9e-3 * 30 * x * x * (1 - x) * (1 - x) / (60 * deg), 1e-13));
  // Dwell: 9 mm, still. Return at x = 0.25: h = 9 (1 - (x - sin(2 pi x)/(2 pi))).
  CHECK(law->at(-10 * deg).lift == 9e-3);
  CHECK(law->at(-10 * deg).velocity == 0.0);
  const double y = 0.25;
  CHECK_THAT(law->at(-5 * deg + y * 80 * deg).lift,
             Catch::Matchers::WithinRel(9e-3 * (1 - (y - std::sin(2 * pi * y) / (2 * pi))), 1e-13));
  // The kit's checks (continuity to the acceleration: 3-4-5 and cycloidal keep it; jerk jumps).
  mechgraph::testing::CamLawCheckOptions options;
  options.continuity = 2;
  const auto report = mechgraph::testing::check_cam_law(*law, "cam_law", options);
  INFO(report.str());
  CHECK(report.passed());
  // The events are the program's: the lift is 1 mm at opening and closing, and the steep short rise
  // puts the lobe centreline before the event's middle.
  const double open = out.all().at("opening_angle").as_scalar(), close = out.all().at("closing_angle").as_scalar();
  CHECK_THAT(law->at(open).lift, Catch::Matchers::WithinRel(1e-3, 1e-12));
  CHECK_THAT(law->at(close).lift, Catch::Matchers::WithinRel(1e-3, 1e-12));
  CHECK((open > -75 * deg && open < -50 * deg));
  CHECK((close > 40 * deg && close < 75 * deg));
  // The nose (the angle of maximum lift) is the dwell's middle, -10 deg from the law's zero,
  // exactly (it was a point of the plateau, 0.004 deg off, where the flanks, flat as cubics where
  // they meet the dwell, widen it unevenly); the centreline is quoted from it, the event's centre
  // (seat to seat, the law's zero) too.
  const double nose = out.all().at("nose_angle").as_scalar();
  CHECK_THAT(nose, Catch::Matchers::WithinAbs(-10 * deg, 1e-15));
  CHECK_THAT(out.all().at("centreline").as_scalar(), Catch::Matchers::WithinAbs(0.5 * (open + close) - nose, 1e-15));
  CHECK(0.5 * (open + close) < 0.0);
  CHECK_THAT(out.all().at("event_centre").as_scalar(), Catch::Matchers::WithinAbs(-nose, 1e-15));
}

TEST_CASE("cam.program reports which derivative jumps at which joint") {
  mechgraph::testing::RecordingContext ctx;
  // Harmonic rise into a dwell: the acceleration jumps at the start (0 -> pi^2/2 H/beta^2) and at
  // the dwell, where it falls from -pi^2/2 H/beta^2 to 0.
  const OutputSet out = run_program({segment("rise", 50 * deg, 8e-3, "harmonic"), segment("dwell", 20 * deg),
                                     segment("return", 50 * deg, 8e-3, "poly4567")},
                                    &ctx);
  const Table& j = out.all().at("joints").as_table();
  REQUIRE(j.axis.values.size() == 4);
  const auto& first = j.find("first_jump")->values;
  CHECK(first[0] == 2);  // base circle / rise 1: acceleration
  CHECK(first[1] == 2);  // rise 1 / dwell 2
  CHECK(first[2] == 4);  // dwell 2 / return 3: 4-5-6-7 starts smooth to the jerk
  CHECK(first[3] == 4);
  const double beta = 50 * deg;
  CHECK_THAT(j.find("acceleration_jump")->values[0], Catch::Matchers::WithinRel(pi * pi / 2 * 8e-3 / (beta * beta), 1e-12));
  CHECK_THAT(j.find("acceleration_jump")->values[1], Catch::Matchers::WithinRel(pi * pi / 2 * 8e-3 / (beta * beta), 1e-12));
  CHECK(out.all().at("continuity_order").as_scalar() == 1.0);
}

TEST_CASE("cam.program refuses programs that do not close or do not fit in a turn") {
  CHECK_THROWS_WITH(run_program({segment("rise", 60 * deg, 9e-3), segment("return", 60 * deg, 8e-3)}),
                    Catch::Contains("ends at lift 1 mm, not 0"));
  CHECK_THROWS_WITH(run_program({segment("rise", 60 * deg, 9e-3), segment("return", 60 * deg, 10e-3)}),
                    Catch::Contains("takes the lift to -1 mm"));
  CHECK_THROWS_WITH(run_program({segment("rise", 200 * deg, 9e-3), segment("return", 170 * deg, 9e-3)}),
                    Catch::Contains("span 370 deg"));
  CHECK_THROWS_WITH(run_program({segment("rise", 60 * deg), segment("return", 60 * deg, 8e-3)}),
                    Catch::Contains("needs lift > 0"));
}

}  // namespace
}  // namespace mechgraph::cams
