// joint.cardan: kinematics against the closed form, numerical differentiation and a 50-digit
// reference; the singular bend angle; play through the joint with cardan_kinematics on and off.
#include "test_support.hpp"

#include "joints/cardan_kinematics.hpp"
#include "joints/node_types.hpp"

#include <mechgraph/domain/fit.hpp>
#include <mechgraph/errors.hpp>

#include <boost/multiprecision/cpp_bin_float.hpp>
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

using namespace mechgraph;
using namespace mechgraph::testing;
using mechgraph::joints::CardanKinematics;
using Catch::Matchers::Contains;
using Catch::Matchers::WithinAbs;
using Catch::Matchers::WithinRel;

namespace {

constexpr double pi = std::numbers::pi;
constexpr double deg = pi / 180.0;
using big = boost::multiprecision::cpp_bin_float_50;

// The closed form of the source, on the principal branch: t2 = atan2(sin t1, cos t1 cos b).
double closed_form(double t1, double b) { return std::atan2(std::sin(t1), std::cos(t1) * std::cos(b)); }

// 50-digit references of the same double inputs, in the textbook forms (not the rearranged ones):
// t2 - t1 from the principal atan2 (for |t1| < pi/2), w2/w1 = cos b / (1 - sin^2 b cos^2 t1).
double reference_error(double t1, double b) {
  const big T = t1, B = b;
  return static_cast<double>(atan2(sin(T), cos(T) * cos(B)) - T);
}
double reference_ratio(double t1, double b) {
  const big T = t1, B = b, sb = sin(B), ct = cos(T);
  return static_cast<double>(cos(B) / (1 - sb * sb * ct * ct));
}

OutputSet run_cardan(double t1, double b, std::vector<std::string> effects = {},
                     const std::vector<std::shared_ptr<const Fit>>& fits = {}, double end_float = 0.0) {
  auto type = joints::make_cardan_joint_type();
  InputSet in;
  for (const auto& f : fits) in.add("fits", Value::handle(f));
  OutputSet out;
  RecordingContext ctx(std::move(effects));
  type->evaluate(defaults_of(type->info(), {{"input_angle", ParamValue::of_number(t1)},
                                            {"bend_angle", ParamValue::of_number(b)},
                                            {"end_float", ParamValue::of_number(end_float)}}),
                 in, out, ctx);
  return out;
}

double scalar(const OutputSet& o, const std::string& port) { return o.all().at(port).as_scalar(); }

bool names_bend_angle(const NodeError& e) { return e.parameter() == "bend_angle"; }

}  // namespace

TEST_CASE("cardan: output angle equals the closed form modulo 2 pi and stays within pi/2 of the input", "[joints][cardan]") {
  for (double b_deg : {0.0, 1.0, 5.0, 20.0, 45.0, 60.0, 80.0, 89.0}) {
    const CardanKinematics joint(b_deg * deg);
    for (double t1_deg = -720.0; t1_deg <= 720.0; t1_deg += 7.3) {
      const double t1 = t1_deg * deg;
      const double t2 = joint.output_angle(t1);
      INFO("b = " << b_deg << " deg, t1 = " << t1_deg << " deg");
      CHECK_THAT(std::remainder(t2 - closed_form(t1, b_deg * deg), 2 * pi), WithinAbs(0.0, 1e-13));
      CHECK(std::abs(t2 - t1) < pi / 2);
      CHECK_THAT(joint.angular_error(t1), WithinAbs(t2 - t1, 1e-14));
    }
  }
  // One value worked by hand: tan t2 = tan 30 deg / cos 20 deg = 0.6144033 -> t2 = 31.566704 deg.
  const CardanKinematics uj(20 * deg);
  CHECK_THAT(uj.output_angle(30 * deg), WithinRel(std::atan(std::tan(30 * deg) / std::cos(20 * deg)), 1e-15));
  CHECK_THAT(uj.output_angle(30 * deg) / deg, WithinRel(31.566704, 1e-7));
}

TEST_CASE("cardan: speed ratio equals the central difference of the output angle", "[joints][cardan]") {
  const double h = 1e-5;
  for (double b_deg : {3.0, 20.0, 45.0, 70.0}) {
    const CardanKinematics joint(b_deg * deg);
    for (double t1_deg = -180.0; t1_deg <= 360.0; t1_deg += 11.0) {
      const double t1 = t1_deg * deg;
      const double numeric = (joint.output_angle(t1 + h) - joint.output_angle(t1 - h)) / (2 * h);
      INFO("b = " << b_deg << " deg, t1 = " << t1_deg << " deg");
      CHECK_THAT(joint.speed_ratio(t1), WithinRel(numeric, 2e-8));
    }
  }
}

TEST_CASE("cardan: speed ratio extremes cos b at t1 = 90 deg and 1/cos b at t1 = 0, bounded between", "[joints][cardan]") {
  for (double b_deg : {10.0, 30.0, 60.0, 85.0}) {
    const double b = b_deg * deg;
    const CardanKinematics joint(b);
    CHECK_THAT(joint.speed_ratio(90 * deg), WithinRel(std::cos(b), 1e-14));
    CHECK_THAT(joint.speed_ratio(270 * deg), WithinRel(std::cos(b), 1e-14));
    CHECK_THAT(joint.speed_ratio(0.0), WithinRel(1 / std::cos(b), 1e-15));
    CHECK_THAT(joint.speed_ratio(pi), WithinRel(1 / std::cos(b), 1e-14));
    CHECK(joint.speed_ratio_min() == std::cos(b));
    CHECK_THAT(joint.speed_ratio_max(), WithinRel(1 / std::cos(b), 1e-15));
    for (double t1_deg = 0.0; t1_deg < 360.0; t1_deg += 0.7) {
      const double r = joint.speed_ratio(t1_deg * deg);
      CHECK(r >= std::cos(b) * (1 - 1e-15));
      CHECK(r <= (1 + 1e-15) / std::cos(b));
    }
  }
}

TEST_CASE("cardan: identities at t1 = 0, 90, 180 deg and b = 0", "[joints][cardan]") {
  const CardanKinematics joint(35 * deg);
  CHECK(joint.output_angle(0.0) == 0.0);
  CHECK_THAT(joint.output_angle(pi / 2), WithinAbs(pi / 2, 1e-15));
  CHECK_THAT(joint.output_angle(pi), WithinAbs(pi, 1e-15));
  CHECK_THAT(joint.output_angle(-pi / 2), WithinAbs(-pi / 2, 1e-15));
  const CardanKinematics straight(0.0);
  for (double t1 : {-4.0, -1.0, 0.3, 1.2, 2.9, 7.5}) {
    CHECK(straight.output_angle(t1) == t1);
    CHECK(straight.angular_error(t1) == 0.0);
    CHECK(straight.speed_ratio(t1) == 1.0);
  }
}

TEST_CASE("cardan: output angle is continuous across 90 deg and across the atan2 branch cut", "[joints][cardan]") {
  const double b = 40 * deg;
  const CardanKinematics joint(b);
  const double eps = 1e-9;
  // Across 90 deg the slope is cos b: t2(90 + eps) - t2(90 - eps) = 2 eps cos b.
  CHECK_THAT(joint.output_angle(pi / 2 + eps) - joint.output_angle(pi / 2 - eps), WithinRel(2 * eps * std::cos(b), 1e-6));
  // Across 180 deg (where atan2 jumps by 2 pi) the slope is 1/cos b.
  CHECK_THAT(joint.output_angle(pi + eps) - joint.output_angle(pi - eps), WithinRel(2 * eps / std::cos(b), 1e-6));
  // Over three turns: increasing, and no step larger than the largest slope allows.
  const double step = 0.01 * deg;
  double previous = joint.output_angle(-2 * pi);
  for (double t1 = -2 * pi + step; t1 <= 4 * pi; t1 += step) {
    const double t2 = joint.output_angle(t1);
    REQUIRE(t2 > previous);
    REQUIRE(t2 - previous <= step / std::cos(b) * (1 + 1e-6));
    previous = t2;
  }
  CHECK_THAT(joint.output_angle(4 * pi), WithinAbs(4 * pi, 1e-13));
}

TEST_CASE("cardan: near-singular bend angles 89.9 and 89.999 deg against a 50-digit reference", "[joints][cardan]") {
  for (double b_deg : {89.9, 89.999, 89.9999}) {
    const double b = b_deg * deg;
    const CardanKinematics joint(b);
    const long double cos_b = std::cos(static_cast<long double>(b));
    INFO("b = " << b_deg << " deg");
    CHECK_THAT(joint.speed_ratio_max(), WithinRel(static_cast<double>(1.0L / cos_b), 1e-14));
    CHECK_THAT(joint.speed_ratio_min(), WithinRel(static_cast<double>(cos_b), 1e-14));
    // The interesting region is |t1| ~ cos b, where the ratio swings from 1/cos b to ~1.
    for (double k : {0.0, 0.1, 0.5, 1.0, 2.0, 10.0, 1e3, 1e5}) {
      const double t1 = k * static_cast<double>(cos_b);
      if (t1 > 1.5) continue;  // the principal-branch references hold for |t1| < pi/2
      INFO("t1 = " << k << " cos b");
      CHECK_THAT(joint.speed_ratio(t1), WithinRel(reference_ratio(t1, b), 1e-13));
      CHECK_THAT(joint.angular_error(t1), WithinAbs(reference_error(t1, b), 4e-15));
      // long double closed form of the output angle (principal branch is right for |t1| < pi/2)
      const long double t2 = std::atan2(std::sin(static_cast<long double>(t1)), std::cos(static_cast<long double>(t1)) * cos_b);
      CHECK_THAT(joint.output_angle(t1), WithinAbs(static_cast<double>(t2), 2e-16 + 1e-15 * std::abs(static_cast<double>(t2))));
      CHECK(std::isfinite(joint.speed_ratio(t1)));
    }
    CHECK_THAT(joint.speed_ratio(pi / 2), WithinRel(static_cast<double>(cos_b), 1e-12));
  }
}

TEST_CASE("cardan: bend angle 90 deg and beyond is a NodeError naming bend_angle, every bend below computes", "[joints][cardan]") {
  CHECK_THROWS_MATCHES(CardanKinematics(90 * deg), NodeError, Catch::Matchers::Predicate<NodeError>(names_bend_angle));
  CHECK_THROWS_MATCHES(CardanKinematics(95 * deg), NodeError, Catch::Matchers::Predicate<NodeError>(names_bend_angle));
  CHECK_THROWS_MATCHES(CardanKinematics(-1 * deg), NodeError, Catch::Matchers::Predicate<NodeError>(names_bend_angle));
  CHECK_THROWS_MATCHES(CardanKinematics(std::nan("")), NodeError, Catch::Matchers::Predicate<NodeError>(names_bend_angle));
  // The mathematics' limit only (it was 1/cos b <= 1e6, 89.99994 deg, before): the double below
  // pi/2 computes, with 1/cos b = 1 / cos(pi/2 - 2.2e-16) finite and right.
  const double last = std::nextafter(0.5 * pi, 0.0);
  CHECK_NOTHROW(CardanKinematics(89.99995 * deg));
  const CardanKinematics edge(last);
  CHECK(std::isfinite(edge.speed_ratio_max()));
  CHECK_THAT(edge.speed_ratio_max(), WithinRel(1.0 / std::cos(last), 1e-15));
  CHECK_THAT(edge.speed_ratio(0.0), WithinRel(1.0 / std::cos(last), 1e-12));
  CHECK_THAT(edge.speed_ratio(pi / 2), WithinRel(std::cos(last), 1e-12));
  CHECK(std::isfinite(edge.angular_error(0.3)));

  // Through the node type: the message names the limit.
  CHECK_THROWS_MATCHES(run_cardan(0.0, 90 * deg), NodeError, Catch::Matchers::Predicate<NodeError>(names_bend_angle));
  CHECK_THROWS_WITH(run_cardan(0.0, 90 * deg), Contains("below 90 deg"));
  CHECK_NOTHROW(run_cardan(0.3, last));
}

TEST_CASE("joint.cardan: kinematic outputs at 30 deg input, 20 deg bend", "[joints][cardan]") {
  const double t1 = 30 * deg, b = 20 * deg;
  const OutputSet out = run_cardan(t1, b);
  // tan t2 = tan t1 / cos b; w2/w1 = cos b / (1 - sin^2 b cos^2 t1) = 0.9396926 / 0.9122667 = 1.0300635
  const double t2 = std::atan(std::tan(t1) / std::cos(b));
  CHECK_THAT(scalar(out, "output_angle"), WithinRel(t2, 1e-15));
  CHECK_THAT(scalar(out, "angular_error"), WithinRel(t2 - t1, 1e-13));
  CHECK_THAT(scalar(out, "speed_ratio"), WithinRel(1.0300635, 1e-7));
  CHECK_THAT(scalar(out, "speed_ratio"), WithinRel(reference_ratio(t1, b), 1e-15));
  CHECK_THAT(scalar(out, "speed_ratio_min"), WithinRel(std::cos(b), 1e-15));
  CHECK_THAT(scalar(out, "speed_ratio_max"), WithinRel(1 / std::cos(b), 1e-15));
  CHECK(scalar(out, "play_min") == 0.0);  // no fits, no end float
  CHECK(scalar(out, "play_max") == 0.0);
  const auto play = std::dynamic_pointer_cast<const JointPlay>(out.all().at("play").as_handle());
  REQUIRE(play);
  CHECK(play->kind() == "joint_play");
  CHECK(play->terms().empty());
}

TEST_CASE("joint.cardan: trunnion clearances and end float, scaled by the speed ratio only with cardan_kinematics",
          "[joints][cardan]") {
  // Needle trunnion fit 16 H7/g6: H7 +18/0 um, g6 -6/-17 um -> clearance 6..35 um, mean 20.5 um.
  auto trunnion = std::make_shared<const Fit>("16 H7/g6", 0.016, LimitPair{18e-6, 0.0}, LimitPair{-6e-6, -17e-6},
                                              Distribution::normal, Distribution::normal);
  const double b = 25 * deg, end_float = 50e-6;
  const auto fits = std::vector<std::shared_ptr<const Fit>>{trunnion, trunnion};
  const OutputSet off = run_cardan(0.0, b, {}, fits, end_float);
  CHECK_THAT(scalar(off, "play_min"), WithinRel(2 * 6e-6 + 50e-6, 1e-12));
  CHECK_THAT(scalar(off, "play_max"), WithinRel(2 * 35e-6 + 50e-6, 1e-12));
  CHECK_THAT(scalar(off, "play_mean"), WithinRel(2 * 20.5e-6 + 50e-6, 1e-12));
  CHECK(scalar(off, "play_scale") == 1.0);
  const auto play = std::dynamic_pointer_cast<const JointPlay>(off.all().at("play").as_handle());
  REQUIRE(play->terms().size() == 3);
  CHECK(play->terms()[0].label == "16 H7/g6");
  CHECK(play->terms()[2].label == "trunnion end float 50 um");

  // On, at t1 = 0 (ratio 1/cos b) and at t1 = 90 deg (ratio cos b).
  for (double t1 : {0.0, pi / 2}) {
    const OutputSet on = run_cardan(t1, b, {"cardan_kinematics"}, fits, end_float);
    const double ratio = reference_ratio(t1, b);
    CHECK_THAT(scalar(on, "play_scale"), WithinRel(ratio, 1e-14));
    CHECK_THAT(scalar(on, "play_min"), WithinRel(ratio * (2 * 6e-6 + 50e-6), 1e-12));
    CHECK_THAT(scalar(on, "play_max"), WithinRel(ratio * (2 * 35e-6 + 50e-6), 1e-12));
    CHECK_THAT(scalar(on, "play_mean"), WithinRel(ratio * (2 * 20.5e-6 + 50e-6), 1e-12));
  }
  // The kinematic outputs do not depend on the effect.
  const OutputSet on = run_cardan(0.3, b, {"cardan_kinematics"});
  const OutputSet plain = run_cardan(0.3, b);
  CHECK(scalar(on, "output_angle") == scalar(plain, "output_angle"));
  CHECK(scalar(on, "speed_ratio") == scalar(plain, "speed_ratio"));
  CHECK(joints::make_cardan_joint_type()->info().implements_effect("cardan_kinematics"));
}
