// backlash.two_axis: two rods' play through the 2x2 Jacobian (docs/methods/backlash.md,
// "Two actuators (pitch and yaw) share the nozzle").
#include "test_support.hpp"

#include "backlash/chain_geometry.hpp"
#include "backlash/node_types.hpp"

#include <mechgraph/errors.hpp>

#include <catch2/catch.hpp>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>

using namespace mechgraph;
using namespace mechgraph::testing;

namespace {

constexpr double um = 1e-6;

OutputSet run_two_axis(std::vector<double> jacobian, double b1, double b2, std::map<std::string, ParamValue> extra = {}) {
  auto type = backlash::make_two_axis_type();
  extra["jacobian"] = ParamValue::of_list(std::move(jacobian));
  InputSet in;
  in.add("rod_backlash_1", Value::scalar(b1));
  in.add("rod_backlash_2", Value::scalar(b2));
  OutputSet out;
  RecordingContext ctx;
  type->evaluate(defaults_of(type->info(), extra), in, out, ctx);
  return out;
}

double scalar(const OutputSet& o, const std::string& port) { return o.all().at(port).as_scalar(); }

}  // namespace

TEST_CASE("two axes driven apart: each angle is its rod's play over its lever arm", "[backlash]") {
  const OutputSet o = run_two_axis({0.5, 0.0, 0.0, 0.4}, 576 * um, 400 * um);
  CHECK(scalar(o, "angular_backlash_pitch") == Approx(576 * um / 0.5).epsilon(1e-15).margin(0));
  CHECK(scalar(o, "angular_backlash_yaw") == Approx(400 * um / 0.4).epsilon(1e-15).margin(0));
  CHECK(scalar(o, "condition_number") == Approx(1.25).epsilon(1e-15).margin(0));
}

TEST_CASE("coupled axes: the worst case is the extent of the reachable parallelogram", "[backlash]") {
  const std::vector<double> j{0.5, 0.1, 0.05, 0.4};
  const double b1 = 576 * um, b2 = 400 * um;
  const OutputSet o = run_two_axis(j, b1, b2);
  // By hand: det = 0.2 - 0.005 = 0.195, J^-1 = [0.4 -0.1; -0.05 0.5] / 0.195.
  CHECK(scalar(o, "angular_backlash_pitch") == Approx((0.4 * b1 + 0.1 * b2) / 0.195).epsilon(1e-14).margin(0));
  CHECK(scalar(o, "angular_backlash_yaw") == Approx((0.05 * b1 + 0.5 * b2) / 0.195).epsilon(1e-14).margin(0));
  // Independently: solve J d_theta = dL at the four corners dL = (+-b1/2, +-b2/2); peak to peak = max - min.
  Eigen::Matrix2d J;
  J << j[0], j[1], j[2], j[3];
  double lo[2] = {1e9, 1e9}, hi[2] = {-1e9, -1e9};
  for (double s1 : {-0.5, 0.5})
    for (double s2 : {-0.5, 0.5}) {
      const Eigen::Vector2d theta = J.fullPivLu().solve(Eigen::Vector2d(s1 * b1, s2 * b2));
      for (int a = 0; a < 2; ++a) {
        lo[a] = std::min(lo[a], theta[a]);
        hi[a] = std::max(hi[a], theta[a]);
      }
    }
  CHECK(scalar(o, "angular_backlash_pitch") == Approx(hi[0] - lo[0]).epsilon(1e-13).margin(0));
  CHECK(scalar(o, "angular_backlash_yaw") == Approx(hi[1] - lo[1]).epsilon(1e-13).margin(0));
  // The condition number against Eigen's SVD.
  const Eigen::JacobiSVD<Eigen::Matrix2d> svd(J);
  CHECK(scalar(o, "condition_number") ==
        Approx(svd.singularValues()[0] / svd.singularValues()[1]).epsilon(1e-13).margin(0));
}

TEST_CASE("closed-form singular values of a 2x2 against Eigen, down to near-singular matrices", "[backlash]") {
  for (const backlash::Matrix2& m : {backlash::Matrix2{0.5, 0.1, 0.05, 0.4}, backlash::Matrix2{-0.3, 0.7, 0.2, 0.1},
                                     backlash::Matrix2{0.5, 0.5, 0.5, 0.5 + 1e-9}, backlash::Matrix2{0.0, 2.0, -3.0, 0.0}}) {
    Eigen::Matrix2d e;
    e << m[0], m[1], m[2], m[3];
    const Eigen::JacobiSVD<Eigen::Matrix2d> svd(e);
    const auto s = backlash::singular_values(m);
    CHECK(s[0] == Approx(svd.singularValues()[0]).epsilon(1e-14).margin(0));
    CHECK(s[1] == Approx(svd.singularValues()[1]).epsilon(1e-6).margin(0));  // Eigen's small one carries its own rounding
  }
  CHECK(std::isinf(backlash::condition_number({1.0, 2.0, 2.0, 4.0})));
  CHECK(std::isinf(backlash::condition_number({0.0, 0.0, 0.0, 0.0})));
}

TEST_CASE("a near-singular Jacobian is an error naming the parameter", "[backlash]") {
  auto names_jacobian = Catch::Matchers::Predicate<NodeError>([](const NodeError& e) { return e.parameter() == "jacobian"; });
  // Both rods act about (nearly) the same axis.
  CHECK_THROWS_MATCHES(run_two_axis({0.5, 0.5, 0.5, 0.5001}, 1e-4, 1e-4), NodeError, names_jacobian);
  CHECK_THROWS_WITH(run_two_axis({0.5, 0.5, 0.5, 0.5001}, 1e-4, 1e-4), Catch::Matchers::Contains("max_condition = 1000"));
  CHECK_THROWS_MATCHES(run_two_axis({0.5, 1.0, 0.25, 0.5}, 1e-4, 1e-4), NodeError, names_jacobian);
  CHECK_THROWS_MATCHES(run_two_axis({0.5, 0.0, 0.4}, 1e-4, 1e-4), NodeError, names_jacobian);
  // A looser limit accepts the first design; its play is then large about one axis.
  const OutputSet o = run_two_axis({0.5, 0.5, 0.5, 0.5001}, 1e-4, 1e-4, {{"max_condition", ParamValue::of_number(1e5)}});
  CHECK(scalar(o, "angular_backlash_pitch") > 1.0);
}
