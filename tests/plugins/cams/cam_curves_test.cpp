// SVAJ curves and events at a checking lift (mechgraph/domain/cam_curves.hpp), against closed forms
// of the harmonic rise-return law and against finite differences of the tabulated lift.
#include "cam_test_support.hpp"
#include "rise_law.hpp"

#include <mechgraph/domain/cam_curves.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

namespace mechgraph::cams {
namespace {

constexpr double pi = std::numbers::pi;
constexpr double deg = pi / 180.0;

// Harmonic rise over B = phi_d/2: h = H (1 - cos(pi x))/2, x = (phi + B)/B, so h = hc at
// phi = B (acos(1 - 2 hc/H)/pi - 1) on the rise, mirrored on the return.
double harmonic_opening(double H, double phi_d, double hc) {
  const double B = 0.5 * phi_d;
  return B * (std::acos(1.0 - 2.0 * hc / H) / pi - 1.0);
}

TEST_CASE("events at a checking lift match the harmonic law's closed form, in cam and crank degrees") {
  const double H = 9e-3, phi_d = 140 * deg;
  const SymmetricRiseReturnLaw law(RiseShape::harmonic, H, phi_d, 20e-3);
  for (double hc : {1e-3, checking_lift_0050_in, 5e-3, 8.9e-3}) {
    long evaluations = 0;
    const auto e = events_at_lift(law, hc, 16, evaluations);
    REQUIRE(e);
    const double expected = harmonic_opening(H, phi_d, hc);
    CHECK_THAT(e->opening, Catch::Matchers::WithinAbs(expected, 1e-12));
    CHECK_THAT(e->closing, Catch::Matchers::WithinAbs(-expected, 1e-12));
    CHECK_THAT(e->duration, Catch::Matchers::WithinAbs(-2.0 * expected, 1e-12));
    CHECK_THAT(e->centreline, Catch::Matchers::WithinAbs(0.0, 1e-12));
    CHECK(evaluations > 0);
  }
  long evaluations = 0;
  CHECK_FALSE(events_at_lift(law, 9.1e-3, 16, evaluations));

  std::vector<double> knots{law.event_begin(), 0.0, law.event_end()};
  const Table t = events_table([&](double phi) { return law.at(phi).lift; }, knots, {1e-3, 20e-3, 0.0}, 16, evaluations);
  REQUIRE(t.axis.values.size() == 2);  // 20 mm is never reached: no row
  CHECK(t.axis.values[0] == 1e-3);
  const double open1 = harmonic_opening(H, phi_d, 1e-3);
  CHECK_THAT(t.find("crank_opening")->values[0], Catch::Matchers::WithinAbs(2.0 * open1, 1e-12));
  CHECK_THAT(t.find("crank_duration")->values[0], Catch::Matchers::WithinAbs(-4.0 * open1, 1e-12));
  // Seat to seat: the whole event.
  CHECK_THAT(t.find("duration")->values[1], Catch::Matchers::WithinAbs(phi_d, 1e-15));
}

// A checking lift at the rounding level of the lift (below 16 ulps of its top) lies in the zone
// the interpolants cannot sign at the seat: the crossings were lost and a valid checking lift
// (> 0) refused. h = H sin^2(pi x / 2) on the rise, so the opening is -B + B (2/pi) asin(sqrt(hc/H)).
TEST_CASE("events at a checking lift down to the least double: found on the lift, as the closed form") {
  const double H = 9e-3, phi_d = 140 * deg, B = 0.5 * phi_d;
  const SymmetricRiseReturnLaw law(RiseShape::harmonic, H, phi_d, 20e-3);
  std::vector<double> knots{law.event_begin(), 0.0, law.event_end()};
  for (double hc : {1e-16, 1e-20, 1e-30, 1e-300, 4.9406564584124654e-324}) {
    INFO("checking lift " << hc << " m");
    long evaluations = 0;
    const Table t = events_table([&](double phi) { return law.at(phi).lift; }, knots, {hc, 0.0}, 16, evaluations);
    REQUIRE(t.axis.values.size() == 2);
    const double opening = -B + B * (2.0 / pi) * std::asin(std::sqrt(hc / H));
    CHECK_THAT(t.find("opening")->values[0], Catch::Matchers::WithinAbs(opening, 1e-14));
    CHECK_THAT(t.find("closing")->values[0], Catch::Matchers::WithinAbs(-opening, 1e-14));
  }
  const OutputSet out = testing::run_cam("cam.harmonic", {{"max_lift", ParamValue::of_number(H)},
                                                          {"action_angle", ParamValue::of_number(phi_d)},
                                                          {"base_radius", ParamValue::of_number(40e-3)},
                                                          {"checking_lift", ParamValue::of_number(4.9406564584124654e-324)}});
  CHECK_THAT(out.all().at("duration").as_scalar(), Catch::Matchers::WithinAbs(phi_d, 1e-14));
}

TEST_CASE("the svaj table spans the event with a margin, and its velocity is the derivative of its lift") {
  const double phi_d = 130 * deg;
  const SymmetricRiseReturnLaw law(RiseShape::cycloidal, 8e-3, phi_d, 17e-3);
  const Table t = svaj_table(law, 2001);
  REQUIRE(t.axis.values.size() == 2001);
  CHECK_THAT(t.axis.values.front(), Catch::Matchers::WithinAbs(-0.6 * phi_d, 1e-15));
  CHECK_THAT(t.axis.values.back(), Catch::Matchers::WithinAbs(0.6 * phi_d, 1e-15));
  const auto& lift = t.find("lift")->values;
  const auto& velocity = t.find("velocity")->values;
  const auto& acceleration = t.find("acceleration")->values;
  CHECK(lift.front() == 0.0);
  CHECK(lift.back() == 0.0);
  CHECK_THAT(lift[1000], Catch::Matchers::WithinRel(8e-3, 1e-14));
  CHECK_THAT(t.find("crank_angle")->values[10], Catch::Matchers::WithinRel(2.0 * t.axis.values[10], 1e-15));
  CHECK(t.find("jerk")->dimension == dim::length / dim::angle.pow(3));
  // Second method: central differences of the tabulated columns.
  const double h = t.axis.values[1] - t.axis.values[0];
  for (std::size_t i = 1; i + 1 < lift.size(); i += 37) {
    // Not across the event's ends and the nose, where the jerk jumps and the differences err by O(h).
    const double phi = t.axis.values[i];
    if (std::abs(phi) < 2.0 * h || std::abs(std::abs(phi) - 0.5 * phi_d) < 2.0 * h) continue;
    const double dv = (lift[i + 1] - lift[i - 1]) / (2.0 * h);
    CHECK_THAT(velocity[i], Catch::Matchers::WithinAbs(dv, 2e-4 * 8e-3));
    const double da = (velocity[i + 1] - velocity[i - 1]) / (2.0 * h);
    CHECK_THAT(acceleration[i], Catch::Matchers::WithinAbs(da, 2e-3 * 8e-3));
  }
}

TEST_CASE("cam nodes output svaj and events, a checking lift above the lift names checking_lift") {
  const OutputSet out = testing::run_cam("cam.harmonic", {{"max_lift", ParamValue::of_number(9e-3)},
                                                          {"action_angle", ParamValue::of_number(140 * deg)},
                                                          {"base_radius", ParamValue::of_number(40e-3)}});
  const double open1 = harmonic_opening(9e-3, 140 * deg, 1e-3);
  CHECK_THAT(out.all().at("duration").as_scalar(), Catch::Matchers::WithinAbs(-2.0 * open1, 1e-12));
  CHECK_THAT(out.all().at("crank_duration").as_scalar(), Catch::Matchers::WithinAbs(-4.0 * open1, 1e-12));
  CHECK_THAT(out.all().at("opening_angle").as_scalar(), Catch::Matchers::WithinAbs(open1, 1e-12));
  CHECK(out.all().at("svaj").as_table().axis.values.size() == 361);
  CHECK(out.all().at("events").as_table().axis.values.size() == 3);
  CHECK_THROWS_WITH(testing::run_cam("cam.harmonic", {{"max_lift", ParamValue::of_number(9e-3)},
                                                      {"action_angle", ParamValue::of_number(140 * deg)},
                                                      {"base_radius", ParamValue::of_number(40e-3)},
                                                      {"checking_lift", ParamValue::of_number(10e-3)}}),
                    Catch::Contains("checking_lift 10 mm is not below the cam's lift 9 mm"));
}

}  // namespace
}  // namespace mechgraph::cams
