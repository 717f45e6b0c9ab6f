// Ramps (plugins/cams/ramps.hpp) against values computed by hand, on a cycloidal main law:
// max_lift 9 mm, action_angle 130 deg (P = 65 deg each side), ramps 0.3 mm over 20 deg.
// Working in mm and deg, then converted: velocity x (180/pi) per rad, acceleration x (180/pi)^2,
// jerk x (180/pi)^3.
#include "cam_conformance_cases.hpp"
#include "ramps.hpp"
#include "registration.hpp"
#include "rise_law.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

using namespace mechgraph;
using namespace mechgraph::cams;
using namespace mechgraph::cams::testing;

namespace {

constexpr double pi = std::numbers::pi;
constexpr double per_deg = 180.0 / pi;  // d/dphi per deg -> per rad

// A lift in mm, velocity in mm/deg, ... as SI.
LiftDerivatives si_of(double h_mm, double v, double a, double j) {
  return {h_mm * mm, v * mm * per_deg, a * mm * per_deg * per_deg, j * mm * per_deg * per_deg * per_deg};
}

void check_equal(const LiftDerivatives& got, const LiftDerivatives& want) {
  CHECK(got.lift == Approx(want.lift).epsilon(1e-12).margin(1e-15));
  CHECK(got.velocity == Approx(want.velocity).epsilon(1e-12).margin(1e-15));
  CHECK(got.acceleration == Approx(want.acceleration).epsilon(1e-11).margin(1e-14));
  CHECK(got.jerk == Approx(want.jerk).epsilon(1e-10).margin(1e-13));
}

std::map<std::string, std::string> cam(const std::string& ramp) {
  return {{"max_lift", "9 mm"},     {"action_angle", "130 deg"}, {"base_radius", "60 mm"},
          {"ramp", ramp},           {"ramp_height", "0.3 mm"},    {"ramp_length", "20 deg"}};
}

const NodeType& cycloidal_type() {
  static const NodeTypeList types = [] {
    NodeTypeList t;
    add_standard_law_types(t);
    return t;
  }();
  return *find_type(types, "cam.cycloidal");
}

std::string error_parameter(const std::map<std::string, std::string>& values) {
  try {
    evaluate_node(cycloidal_type(), values);
  } catch (const NodeError& e) {
    return e.parameter();
  }
  return "(no error)";
}

// A law that is not symmetric about the nose, to be refused by RampedLaw.
class Lopsided final : public CamLaw {
 public:
  double event_begin() const override { return -0.5; }
  double event_end() const override { return 0.8; }
  LiftDerivatives evaluate_in_event(double) const override { return {1e-3, 0.0, 0.0, 0.0}; }
  std::vector<double> breakpoints() const override { return {}; }
  double max_lift() const override { return 1e-3; }
  double base_radius() const override { return 0.02; }
};

}  // namespace

TEST_CASE("constant-velocity ramp: hand-computed lift and derivatives", "[cams][ramps]") {
  // v_r = 0.3/20 = 0.015 mm/deg; the ramp's share at the nose 0.3 + 0.015 * 65/2 = 0.7875 mm;
  // main cycloidal lift 9 - 0.7875 = 8.2125 mm.
  const RampSpec spec{RampType::constant_velocity, 0.3 * mm, 20.0 * deg};
  CHECK(ramp_end_velocity(spec) == Approx(0.015 * mm * per_deg).epsilon(1e-14).margin(0.0));
  CHECK(ramp_lift_at_nose(spec, 65.0 * deg) == Approx(0.7875 * mm).epsilon(1e-14).margin(0.0));

  const Evaluation e = evaluate_node(cycloidal_type(), cam("constant_velocity"));
  const CamLaw& law = *e.law;
  CHECK(law.event_begin() == Approx(-85.0 * deg).epsilon(1e-15).margin(0.0));
  CHECK(law.event_end() == Approx(85.0 * deg).epsilon(1e-15).margin(0.0));
  CHECK(law.max_lift() == Approx(9.0 * mm).epsilon(1e-14).margin(0.0));

  SECTION("on the ramp: h = 0.3 x mm, v = 0.015 mm/deg, no acceleration") {
    check_equal(law.at(-75.0 * deg), si_of(0.15, 0.015, 0.0, 0.0));
    check_equal(law.at(75.0 * deg), si_of(0.15, -0.015, 0.0, 0.0));
  }
  SECTION("the velocity steps from 0 to 0.015 mm/deg at the start of the ramp (not shockless)") {
    const double d = 1e-9;
    CHECK(law.at(-85.0 * deg - d).velocity == 0.0);
    CHECK(law.at(-85.0 * deg + d).velocity == Approx(0.015 * mm * per_deg).epsilon(1e-12).margin(0.0));
    CHECK(law.at(-85.0 * deg + d).lift == Approx(0.0).epsilon(0.0).margin(1e-12));
  }
  SECTION("junction with the main law: lift 0.3 mm, velocity 0.015 mm/deg on both sides") {
    const double d = 1e-9;
    const LiftDerivatives left = law.at(-65.0 * deg - d);
    CHECK(left.lift == Approx(0.3 * mm).epsilon(1e-8).margin(0.0));
    CHECK(left.velocity == Approx(0.015 * mm * per_deg).epsilon(1e-12).margin(0.0));
    CHECK(left.acceleration == 0.0);
    const LiftDerivatives right = law.at(-65.0 * deg + d);
    CHECK(right.lift == Approx(0.3 * mm).epsilon(1e-8).margin(0.0));
    CHECK(right.velocity == Approx(0.015 * mm * per_deg).epsilon(1e-8).margin(0.0));
    CHECK(right.acceleration == Approx(0.0).epsilon(0.0).margin(1e-8));
  }
  SECTION("half-way up the main rise (w = 1/2)") {
    // Ramp: R = 0.3 + 0.015 * 65 * F(1/2), F(1/2) = 1/2 - 5/32 + 3/32 - 1/64 = 0.421875;
    //       R' = 0.015 (1 - 1/2); R'' = -0.015 * 30 (1/4)(1/4)/65; R''' = 0 (s''(1/2) = 0).
    // Cycloid: M = 8.2125/2; M' = 2 * 8.2125/65; M'' = 0; M''' = 8.2125 * 4 pi^2 cos(pi)/65^3.
    const double Hm = 8.2125;
    check_equal(law.at(-32.5 * deg),
                si_of(0.3 + 0.015 * 65.0 * 0.421875 + Hm / 2.0, 0.0075 + 2.0 * Hm / 65.0, -0.015 * 1.875 / 65.0,
                      -Hm * 4.0 * pi * pi / (65.0 * 65.0 * 65.0)));
  }
  SECTION("at the nose the total lift is max_lift; the cycloid's jerk steps there, +-4 pi^2 Hm/P^3") {
    const LiftDerivatives nose = law.at(0.0);
    CHECK(nose.lift == Approx(9.0 * mm).epsilon(1e-14).margin(0.0));
    CHECK(nose.velocity == Approx(0.0).epsilon(0.0).margin(1e-15));
    CHECK(nose.acceleration == Approx(0.0).epsilon(0.0).margin(1e-12));
    const double jerk = 8.2125 * 4.0 * pi * pi / std::pow(65.0, 3) * mm * std::pow(per_deg, 3);
    CHECK(law.at(-1e-9).jerk == Approx(jerk).epsilon(1e-7).margin(0.0));
    CHECK(law.at(1e-9).jerk == Approx(-jerk).epsilon(1e-7).margin(0.0));
  }
  SECTION("accel_angle: ramp length plus the main rise up to h'' = 0") {
    // Under the main law h'' = Hm 2 pi sin(2 pi w)/P^2 - v_r 30 w^2 (1-w)^2/P (mm, deg); its zero
    // by bisection on [1/4, 1/2], where it changes sign.
    const double Hm = 8.2125, P = 65.0, v = 0.015;
    auto f = [&](double w) { return Hm * 2.0 * pi * std::sin(2.0 * pi * w) / (P * P) - v * 30.0 * w * w * (1 - w) * (1 - w) / P; };
    double lo = 0.25, hi = 0.5;
    REQUIRE(f(lo) > 0.0);
    REQUIRE(f(hi) < 0.0);
    for (int i = 0; i < 200; ++i) (f(0.5 * (lo + hi)) > 0.0 ? lo : hi) = 0.5 * (lo + hi);
    const double expected = (20.0 + 0.5 * (lo + hi) * P) * deg;
    CHECK(e.outputs.all().at("accel_angle").as_scalar() == Approx(expected).epsilon(1e-10).margin(0.0));
  }
}

TEST_CASE("cosine ramp: hand-computed lift and derivatives", "[cams][ramps]") {
  // v_r = (pi/2)(0.3/20) mm/deg; share 0.3 + v_r 65/2; main lift 9 - share. q = pi/40 per deg.
  const double vr = 0.5 * pi * 0.3 / 20.0, q = pi / 40.0;
  const double share = 0.3 + 0.5 * vr * 65.0, Hm = 9.0 - share;
  const RampSpec spec{RampType::cosine, 0.3 * mm, 20.0 * deg};
  CHECK(ramp_lift_at_nose(spec, 65.0 * deg) == Approx(share * mm).epsilon(1e-14).margin(0.0));

  const Evaluation e = evaluate_node(cycloidal_type(), cam("cosine"));
  const CamLaw& law = *e.law;
  const double d = 1e-9;
  SECTION("mid-ramp: R = 0.3 (1 - cos(pi/4))") {
    const double c = std::cos(pi / 4.0);
    check_equal(law.at(-75.0 * deg), si_of(0.3 * (1.0 - c), 0.3 * q * c, 0.3 * q * q * c, -0.3 * q * q * q * c));
  }
  SECTION("start of the ramp: velocity continuous, acceleration steps to 0.3 (pi/40)^2") {
    CHECK(law.at(-85.0 * deg + d).velocity == Approx(0.0).epsilon(0.0).margin(1e-10));
    CHECK(law.at(-85.0 * deg + d).acceleration == Approx(0.3 * q * q * mm * per_deg * per_deg).epsilon(1e-8).margin(0.0));
    CHECK(law.at(-85.0 * deg - d).acceleration == 0.0);
  }
  SECTION("junction: lift, velocity and acceleration continuous, the jerk steps") {
    const LiftDerivatives l = law.at(-65.0 * deg - d), r = law.at(-65.0 * deg + d);
    CHECK(l.lift == Approx(0.3 * mm).epsilon(1e-8).margin(0.0));
    CHECK(r.lift == Approx(0.3 * mm).epsilon(1e-8).margin(0.0));
    CHECK(l.velocity == Approx(vr * mm * per_deg).epsilon(1e-8).margin(0.0));
    CHECK(r.velocity == Approx(vr * mm * per_deg).epsilon(1e-8).margin(0.0));
    CHECK(l.acceleration == Approx(0.0).epsilon(0.0).margin(1e-8));
    CHECK(r.acceleration == Approx(0.0).epsilon(0.0).margin(1e-8));
    // Jerk: ramp side -0.3 q^3; main side the cycloid's 4 pi^2 Hm/65^3 (the fade adds none).
    CHECK(l.jerk == Approx(-0.3 * q * q * q * mm * std::pow(per_deg, 3)).epsilon(1e-7).margin(0.0));
    CHECK(r.jerk == Approx(4.0 * pi * pi * Hm / std::pow(65.0, 3) * mm * std::pow(per_deg, 3)).epsilon(1e-7).margin(0.0));
  }
  SECTION("half-way up the main rise and the nose") {
    check_equal(law.at(-32.5 * deg), si_of(0.3 + vr * 65.0 * 0.421875 + Hm / 2.0, 0.5 * vr + 2.0 * Hm / 65.0,
                                           -vr * 1.875 / 65.0, -Hm * 4.0 * pi * pi / std::pow(65.0, 3)));
    CHECK(law.at(0.0).lift == Approx(9.0 * mm).epsilon(1e-14).margin(0.0));
    CHECK(law.max_lift() == Approx(9.0 * mm).epsilon(1e-14).margin(0.0));
  }
}

TEST_CASE("ramp_part alone and RampedLaw structure", "[cams][ramps]") {
  const RampSpec spec{RampType::constant_velocity, 0.3 * mm, 20.0 * deg};
  const double P = 65.0 * deg;
  CHECK(ramp_part(spec, P, -85.5 * deg).lift == 0.0);
  CHECK(ramp_part(spec, P, 0.0).lift == Approx(0.7875 * mm).epsilon(1e-14).margin(0.0));
  CHECK(ramp_part(spec, P, 0.0).velocity == 0.0);
  CHECK(ramp_part(RampSpec{}, P, 0.0).lift == 0.0);
  auto main = std::make_shared<const SymmetricRiseReturnLaw>(RiseShape::modified_sine, 8.2125 * mm, 2.0 * P, 0.06);
  const RampedLaw law(main, spec);
  const auto bps = law.breakpoints();
  // The main law's 5 (2 + nose + 2), the two junctions; the nose only once.
  CHECK(bps.size() == 7);
  CHECK(std::is_sorted(bps.begin(), bps.end()));
  CHECK(bps.front() == Approx(-P).epsilon(1e-15).margin(0.0));
  CHECK(bps.back() == Approx(P).epsilon(1e-15).margin(0.0));
  CHECK(law.base_radius() == 0.06);
  CHECK(ramp_type_from_name("cosine") == RampType::cosine);
  CHECK(!ramp_type_from_name("linear"));
}

TEST_CASE("ramp parameters: errors name the parameter", "[cams][ramps]") {
  auto with = [](std::map<std::string, std::string> values, const std::string& key, const std::string& value) {
    values[key] = value;
    return values;
  };
  const std::map<std::string, std::string> plain{{"max_lift", "9 mm"}, {"action_angle", "130 deg"}, {"base_radius", "60 mm"}};
  CHECK(error_parameter(plain) == "(no error)");
  CHECK(error_parameter(with(plain, "ramp_height", "0.3 mm")) == "ramp_height");  // set without a ramp
  CHECK(error_parameter(with(plain, "ramp_length", "20 deg")) == "ramp_length");
  CHECK(error_parameter(with(cam("constant_velocity"), "ramp_height", "0 mm")) == "ramp_height");
  CHECK(error_parameter(with(cam("cosine"), "ramp_length", "0 deg")) == "ramp_length");
  CHECK(error_parameter(with(cam("constant_velocity"), "ramp_height", "9 mm")) == "ramp_height");  // takes all lift
  CHECK(error_parameter(with(with(cam("cosine"), "action_angle", "300 deg"), "ramp_length", "40 deg")) == "ramp_length");
  // An unknown ramp name reaching the node (the host checks choices first).
  ParamSet params = make_params(cycloidal_type().info(), cam("cosine"));
  params.set("ramp", ParamValue::of_choice("linear"));
  OutputSet out;
  TestContext ctx;
  try {
    cycloidal_type().evaluate(params, InputSet{}, out, ctx);
    FAIL("expected a NodeError for ramp 'linear'");
  } catch (const NodeError& e) {
    CHECK(e.parameter() == "ramp");
    CHECK_THAT(e.what(), Catch::Matchers::Contains("constant_velocity"));
  }
  // A ramp so short that its jerk H (pi/2L)^3 would overflow: refused, not Inf.
  try {
    auto main = std::make_shared<const SymmetricRiseReturnLaw>(RiseShape::cycloidal, 8.0 * mm, 130.0 * deg, 0.06);
    RampedLaw(main, RampSpec{RampType::cosine, 1e-3 * mm, 1e-110});
    FAIL("expected a NodeError for a vanishing ramp_length");
  } catch (const NodeError& e) {
    CHECK(e.parameter() == "ramp_length");
  }
  // A main law that is not symmetric about the nose.
  try {
    RampedLaw(std::make_shared<const Lopsided>(), RampSpec{RampType::cosine, 0.3 * mm, 20.0 * deg});
    FAIL("expected a NodeError for an asymmetric main law");
  } catch (const NodeError& e) {
    CHECK(e.parameter() == "ramp");
  }
}
