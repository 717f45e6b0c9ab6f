// backlash.chain against hand computations of the source's method (docs/methods/backlash.md,
// steps 3-4), the geometry of the moment arm, and the closed form of a truncated normal.
#include "test_support.hpp"

#include "backlash/chain_geometry.hpp"
#include "backlash/node_types.hpp"

#include <mechgraph/domain/tolerance.hpp>
#include <mechgraph/errors.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

using namespace mechgraph;
using namespace mechgraph::testing;
using Catch::Matchers::Contains;

namespace {

constexpr double um = 1e-6;
constexpr double mm = 1e-3;
constexpr double arcmin = std::numbers::pi / 10800.0;

// A fit's clearance as the source builds it: hole (+1) minus shaft (-1), each link holding its
// mean deviation (dB + dH)/2 and half tolerance (dB - dH)/2.
PlayTerm fit(const std::string& name, double hole_upper, double hole_lower, double shaft_upper, double shaft_lower) {
  return {name,
          {{name + " hole", 0.5 * (hole_upper + hole_lower), 0.5 * (hole_upper - hole_lower), +1.0, Distribution::normal},
           {name + " shaft", 0.5 * (shaft_upper + shaft_lower), 0.5 * (shaft_upper - shaft_lower), -1.0, Distribution::normal}}};
}

PlayTerm single(const std::string& name, double mean, double half_range) {
  return {name, {{name, mean, half_range, 1.0, Distribution::normal}}};
}

std::shared_ptr<const JointPlay> joint(const std::string& name, std::vector<PlayTerm> terms) {
  return std::make_shared<const JointPlay>(name, std::move(terms));
}

// The hand-computed chain:
//  h1: pin in bracket bore 20 H11/h11 (hole 0/+130 um, shaft 0/-130 um): S = 65 + 65 = 130 um,
//      dS = 65 + 65 = 130 um; plus a bearing's internal clearance 40 +- 10 um: S = 40, dS = 10.
//  h5: 16 H11/d11 (hole 0/+110 um, shaft -50/-160 um): S = 55 - (-105) = 160 um, dS = 55 + 55 = 110 um.
//  k = [1, 0.8], actuator 25 +- 25 um, R = 500 mm.
//  L  = 25 + 1 (130 + 40) + 0.8 * 160 = 323 um,   dL = 25 + 1 (130 + 10) + 0.8 * 110 = 253 um.
//  delta = 323e-6 / 0.5 = 646e-6 rad = 2.22078 arcmin, d_delta = 506e-6 rad = 1.73950 arcmin,
//  maximum (323 + 253) / 0.5 = 1152e-6 rad = 3.96028 arcmin.
std::vector<std::shared_ptr<const JointPlay>> hand_chain() {
  return {joint("h1", {fit("20 H11/h11", 130 * um, 0, 0, -130 * um), single("bearing", 40 * um, 10 * um)}),
          joint("h5", {fit("16 H11/d11", 110 * um, 0, -50 * um, -160 * um)})};
}

struct Run {
  OutputSet out;
  std::map<std::string, double> work;
};

Run run_chain(const std::vector<std::shared_ptr<const JointPlay>>& joints, std::map<std::string, ParamValue> params,
              std::vector<std::string> effects = {}) {
  auto type = backlash::make_backlash_chain_type();
  InputSet in;
  for (const auto& j : joints) in.add("joints", Value::handle(j));
  Run r;
  RecordingContext ctx(std::move(effects));
  type->evaluate(defaults_of(type->info(), params), in, r.out, ctx);
  r.work = ctx.work;
  return r;
}

std::map<std::string, ParamValue> hand_params() {
  return {{"transfer_ratios", ParamValue::of_list({1.0, 0.8})},
          {"actuator_backlash", ParamValue::of_number(25 * um)},
          {"actuator_backlash_limit", ParamValue::of_number(25 * um)},
          {"lever_arm", ParamValue::of_number(500 * mm)}};
}

double scalar(const OutputSet& o, const std::string& port) { return o.all().at(port).as_scalar(); }

auto names(const std::string& parameter) {
  return Catch::Matchers::Predicate<NodeError>([parameter](const NodeError& e) { return e.parameter() == parameter; },
                                               "NodeError naming " + parameter);
}

ParamValue point(double x, double y, double z) { return ParamValue::of_list({x * mm, y * mm, z * mm}); }

}  // namespace

TEST_CASE("backlash.chain: the source's worst case on a hand-computed chain", "[backlash]") {
  const Run r = run_chain(hand_chain(), hand_params());
  CHECK(scalar(r.out, "rod_backlash_mean") == Approx(323 * um).epsilon(1e-13).margin(0));
  CHECK(scalar(r.out, "rod_backlash_limit") == Approx(253 * um).epsilon(1e-13).margin(0));
  CHECK(scalar(r.out, "rod_backlash_max") == Approx(576 * um).epsilon(1e-13).margin(0));
  CHECK(scalar(r.out, "angular_backlash_mean") / arcmin == Approx(2.22078).epsilon(0).margin(5e-6));
  CHECK(scalar(r.out, "angular_backlash_limit") / arcmin == Approx(1.73950).epsilon(0).margin(5e-6));
  CHECK(scalar(r.out, "angular_backlash_max") / arcmin == Approx(3.96028).epsilon(0).margin(5e-6));
  CHECK(scalar(r.out, "lever_arm") == 0.5);
  // Pareto of the worst-case maximum: h1 (170 + 140)/576, h5 0.8 (160 + 110)/576, actuator 50/576.
  const auto& share = r.out.all().at("joint_contribution_worst_case").as_series();
  REQUIRE(share.values.size() == 2);
  CHECK(share.axis == std::vector<double>{0.0, 1.0});
  CHECK(share.values[0] == Approx(310.0 / 576).epsilon(1e-13).margin(0));
  CHECK(share.values[1] == Approx(216.0 / 576).epsilon(1e-13).margin(0));
  CHECK(scalar(r.out, "actuator_contribution_worst_case") == Approx(50.0 / 576).epsilon(1e-13).margin(0));
  // None of the effect outputs without their effects.
  for (const char* port : {"rod_backlash_mc_mean", "mc_mean_error", "rod_elastic_deflection", "rod_total_under_load"})
    CHECK(r.out.all().count(port) == 0);
}

TEST_CASE("backlash.chain: RSS from each term's links", "[backlash]") {
  const Run r = run_chain(hand_chain(), hand_params());
  // sigma_L^2 = (25/3)^2 + 1 [2 (65/3)^2 + (10/3)^2] + 0.8^2 [2 (55/3)^2] = 1449.667 um^2, sigma_L = 38.07449 um.
  CHECK(scalar(r.out, "rod_backlash_rss_sigma") / um == Approx(38.07449).epsilon(0).margin(5e-6));
  CHECK(scalar(r.out, "rod_backlash_rss_max") / um == Approx(437.22347).epsilon(0).margin(5e-6));
  CHECK(scalar(r.out, "angular_backlash_rss_max") == Approx(scalar(r.out, "rod_backlash_rss_max") / 0.5).epsilon(1e-15).margin(0));
  const auto& share = r.out.all().at("joint_contribution_rss").as_series().values;
  CHECK(share[0] == Approx(950.0 / 1449.6666666666667).epsilon(1e-12).margin(0));
  CHECK(share[1] == Approx(0.64 * 2 * (55.0 / 3) * (55.0 / 3) / 1449.6666666666667).epsilon(1e-12).margin(0));
}

TEST_CASE("backlash.chain: Monte Carlo of the hand chain agrees with the linear mean", "[backlash]") {
  // Every clearance here is positive at the mean by > 4 sigma, so truncation is negligible and
  // the Monte Carlo mean is L; the actuator (25 +- 25 um, clipped at 0) shifts it by
  // sigma phi(3) - mu Phi(-3) = 0.0032 um, well inside the error.
  const Run r = run_chain(hand_chain(), hand_params(), {"monte_carlo"});
  const double error = scalar(r.out, "mc_mean_error");
  CHECK(error == Approx(scalar(r.out, "rod_backlash_mc_sigma") / std::sqrt(1e5)).epsilon(1e-14).margin(0));
  CHECK(scalar(r.out, "rod_backlash_mc_mean") == Approx(323 * um).epsilon(0).margin(4 * error));
  CHECK(scalar(r.out, "rod_backlash_mc_sigma") == Approx(38.07449 * um).epsilon(0.02).margin(0));
  CHECK(scalar(r.out, "angular_backlash_mc_q999") == Approx(scalar(r.out, "rod_backlash_mc_q999") / 0.5).epsilon(1e-15).margin(0));
  // The statistical maximum lies well below the worst case.
  CHECK(scalar(r.out, "rod_backlash_mc_q999") < scalar(r.out, "rod_backlash_max"));
  CHECK(r.work.at("samples") == 100000.0);
}

TEST_CASE("backlash.chain: Monte Carlo of one truncated normal clearance against E[max(0, X)]", "[backlash]") {
  // E[max(0, X)] = mu Phi(mu/s) + s phi(mu/s) for X ~ N(mu, s).
  auto Phi = [](double x) { return 0.5 * std::erfc(-x / std::numbers::sqrt2); };
  auto phi = [](double x) { return std::exp(-0.5 * x * x) / std::sqrt(2 * std::numbers::pi); };
  for (const double mu : {10 * um, 0.0, -5 * um}) {
    const double s = 10 * um;  // half range 30 um = 3 s
    const Run r = run_chain({joint("pin", {single("clearance", mu, 3 * s)})},
                            {{"transfer_ratios", ParamValue::of_list({1.0})},
                             {"actuator_backlash", ParamValue::of_number(0.0)},
                             {"actuator_backlash_limit", ParamValue::of_number(0.0)},
                             {"lever_arm", ParamValue::of_number(1.0)}},
                            {"monte_carlo"});
    const double expected = mu * Phi(mu / s) + s * phi(mu / s);
    const double error = scalar(r.out, "mc_mean_error");
    INFO("mu = " << mu / um << " um, expected " << expected / um << " um, error " << error / um << " um");
    CHECK(scalar(r.out, "rod_backlash_mc_mean") == Approx(expected).epsilon(0).margin(4 * error));
    // The linear mean (clipped at zero) misses the truncation by many standard errors.
    CHECK(std::abs(scalar(r.out, "rod_backlash_mean") - expected) > 20 * error);
    // Above P(X < 0) the quantiles of max(0, X) are those of X: q(Phi(3)) = mu + 3 s, within the
    // standard error of a sample quantile, sqrt(p (1 - p) / N) / phi(3) * s.
    const double p = 1 - Phi(3.0);
    const double q_error = std::sqrt(p * (1 - p) / 1e5) / phi(3.0) * s;
    CHECK(scalar(r.out, "rod_backlash_mc_q999") == Approx(mu + 3 * s).epsilon(0).margin(4 * q_error));
  }
}

TEST_CASE("backlash.chain: an interference fit contributes no play, a transition fit only its upper part", "[backlash]") {
  const Run base = run_chain(hand_chain(), hand_params());
  // 20 H7/s6 (hole 0/+21 um, shaft +35/+48 um): clearance -48 .. -14 um, interference throughout.
  auto chain = hand_chain();
  chain.push_back(joint("press", {fit("20 H7/s6", 21 * um, 0, 48 * um, 35 * um)}));
  auto params = hand_params();
  params["transfer_ratios"] = ParamValue::of_list({1.0, 0.8, 1.0});
  const Run r = run_chain(chain, params, {"monte_carlo"});
  for (const char* port : {"rod_backlash_mean", "rod_backlash_limit", "rod_backlash_rss_sigma", "angular_backlash_max"})
    CHECK(scalar(r.out, port) == scalar(base.out, port));
  CHECK(r.out.all().at("joint_contribution_worst_case").as_series().values[2] == 0.0);
  CHECK(scalar(r.out, "rod_backlash_mc_mean") == Approx(323 * um).epsilon(0).margin(4 * scalar(r.out, "mc_mean_error")));

  // Transition: clearance mean -10 um, limits -40 .. +20 um: S = 0, dS = 20 um (the worst case max).
  const Run t = run_chain({joint("k6", {single("transition", -10 * um, 30 * um)})},
                          {{"transfer_ratios", ParamValue::of_list({1.0})},
                           {"actuator_backlash", ParamValue::of_number(0.0)},
                           {"actuator_backlash_limit", ParamValue::of_number(0.0)},
                           {"lever_arm", ParamValue::of_number(0.2)}});
  CHECK(scalar(t.out, "rod_backlash_mean") == 0.0);
  CHECK(scalar(t.out, "rod_backlash_limit") == Approx(20 * um).epsilon(1e-13).margin(0));
  CHECK(scalar(t.out, "angular_backlash_max") == Approx(100 * um).epsilon(1e-13).margin(0));
}

TEST_CASE("backlash.chain: the moment arm from the geometry against a hand computation", "[backlash]") {
  // Axis: the z direction (0, 0, 2) through A = (100, 100, 7000) mm. Rod from F = (500, -600, 0) to
  // P = (600, 0, 300) mm: P - F = (100, 600, 300), |P - F| = sqrt(460000) mm. The moment about z of
  // a unit force u through P is (x - x_A) u_y - (y - y_A) u_x = (500 * 600 + 100 * 100)/sqrt(460000)
  // = 310000/678.233 = 457.07006 mm.
  auto params = hand_params();
  params.erase("lever_arm");
  params["rod_attach_fixed"] = point(500, -600, 0);
  params["rod_attach_moving"] = point(600, 0, 300);
  params["axis_point"] = point(100, 100, 7000);
  params["axis_direction"] = ParamValue::of_list({0, 0, 2});
  const Run r = run_chain(hand_chain(), params);
  CHECK(scalar(r.out, "lever_arm") / mm == Approx(457.07006).epsilon(0).margin(5e-6));
  CHECK(scalar(r.out, "angular_backlash_max") == Approx(576 * um / 0.45707006408).epsilon(1e-10).margin(0));

  // The opposite axis direction turns the sign of R, not the play.
  params["axis_direction"] = ParamValue::of_list({0, 0, -1});
  const Run flipped = run_chain(hand_chain(), params);
  CHECK(scalar(flipped.out, "lever_arm") == Approx(-scalar(r.out, "lever_arm")).epsilon(1e-14).margin(0));
  CHECK(scalar(flipped.out, "angular_backlash_max") == Approx(scalar(r.out, "angular_backlash_max")).epsilon(1e-14).margin(0));
}

TEST_CASE("moment arm: invariant under a rigid motion of the whole drive", "[backlash]") {
  using backlash::Vec3;
  // Rotation by 90 deg about x, then by 90 deg about z: (x, y, z) -> (y, z, x)... composed as the
  // cyclic permutation (x, y, z) -> (z, x, y), a proper rotation; then a translation.
  auto move = [](const Vec3& v, bool translate) {
    const Vec3 r{v[2], v[0], v[1]};
    return translate ? Vec3{r[0] + 3.0, r[1] - 1.0, r[2] + 0.5} : r;
  };
  const Vec3 F{0.5, -0.6, 0.0}, P{0.6, 0.0, 0.3}, A{0.1, 0.1, 7.0}, n{0.0, 0.0, 2.0};
  const double R = backlash::moment_arm(F, P, A, n);
  CHECK(R == Approx(0.31 / std::sqrt(0.46)).epsilon(1e-14).margin(0));
  CHECK(backlash::moment_arm(move(F, true), move(P, true), move(A, true), move(n, false)) == Approx(R).epsilon(1e-13).margin(0));
  // A point of the axis anywhere along it gives the same R.
  CHECK(backlash::moment_arm(F, P, Vec3{0.1, 0.1, -3.0}, n) == Approx(R).epsilon(1e-14).margin(0));
}

TEST_CASE("backlash.chain: a rod line passing 0.5 mm from the axis is a singular design", "[backlash]") {
  auto params = hand_params();
  params.erase("lever_arm");
  params["rod_attach_fixed"] = point(0.5, -600, 200);
  params["rod_attach_moving"] = point(0.5, 100, 200);
  params["axis_point"] = point(0, 0, 0);
  params["axis_direction"] = ParamValue::of_list({0, 0, 1});
  CHECK_THROWS_MATCHES(run_chain(hand_chain(), params), NodeError, names("rod_attach_moving"));
  CHECK_THROWS_WITH(run_chain(hand_chain(), params), Contains("0.5 mm") && Contains("min_lever_arm = 1 mm"));
  // A smaller limit accepts it (a deliberate choice of the designer), R = 0.5 mm.
  params["min_lever_arm"] = ParamValue::of_number(0.1 * mm);
  CHECK(scalar(run_chain(hand_chain(), params).out, "lever_arm") == Approx(0.5 * mm).epsilon(1e-12).margin(0));
  // A rod parallel to the axis has no moment at all.
  params["rod_attach_moving"] = point(0.5, -600, 900);
  CHECK_THROWS_MATCHES(run_chain(hand_chain(), params), NodeError, names("rod_attach_moving"));

  auto given = hand_params();
  given["lever_arm"] = ParamValue::of_number(0.5 * mm);
  CHECK_THROWS_MATCHES(run_chain(hand_chain(), given), NodeError, names("lever_arm"));
  given["lever_arm"] = ParamValue::of_number(0.0);
  CHECK_THROWS_MATCHES(run_chain(hand_chain(), given), NodeError, names("lever_arm"));
}

TEST_CASE("backlash.chain: parameter errors name the parameter", "[backlash]") {
  auto params = hand_params();
  params["transfer_ratios"] = ParamValue::of_list({1.0});
  CHECK_THROWS_MATCHES(run_chain(hand_chain(), params), NodeError, names("transfer_ratios"));
  CHECK_THROWS_WITH(run_chain(hand_chain(), params), Contains("1 values for 2 joints"));
  params["transfer_ratios"] = ParamValue::of_list({1.0, 0.0});
  CHECK_THROWS_MATCHES(run_chain(hand_chain(), params), NodeError, names("transfer_ratios"));

  auto both = hand_params();
  both["axis_point"] = point(0, 0, 0);
  CHECK_THROWS_MATCHES(run_chain(hand_chain(), both), NodeError, names("lever_arm"));
  auto partial = hand_params();
  partial.erase("lever_arm");
  CHECK_THROWS_MATCHES(run_chain(hand_chain(), partial), NodeError, names("lever_arm"));
  partial["rod_attach_fixed"] = point(0, 0, 0);
  partial["rod_attach_moving"] = point(0, 100, 0);
  partial["axis_point"] = point(300, 0, 0);
  CHECK_THROWS_MATCHES(run_chain(hand_chain(), partial), NodeError, names("axis_direction"));
  partial["axis_direction"] = ParamValue::of_list({0, 1});
  CHECK_THROWS_MATCHES(run_chain(hand_chain(), partial), NodeError, names("axis_direction"));
  partial["axis_direction"] = ParamValue::of_list({0, 0, 0});
  CHECK_THROWS_MATCHES(run_chain(hand_chain(), partial), NodeError, names("axis_direction"));
  partial["axis_direction"] = ParamValue::of_list({0, 0, 1});
  partial["rod_attach_moving"] = point(0, 0, 0);
  CHECK_THROWS_MATCHES(run_chain(hand_chain(), partial), NodeError, names("rod_attach_moving"));
}

TEST_CASE("backlash.chain: compliance reports the elastic deflection apart from the free play", "[backlash]") {
  auto params = hand_params();
  params["load"] = ParamValue::of_number(500.0);     // N
  params["stiffness"] = ParamValue::of_number(2e7);  // N/m: 500 / 2e7 = 25 um
  const Run r = run_chain(hand_chain(), params, {"compliance"});
  CHECK(scalar(r.out, "rod_elastic_deflection") == Approx(25 * um).epsilon(1e-14).margin(0));
  CHECK(scalar(r.out, "rod_total_under_load") == Approx(601 * um).epsilon(1e-13).margin(0));
  CHECK(scalar(r.out, "angular_total_under_load") == Approx(1202 * um).epsilon(1e-13).margin(0));
  CHECK(scalar(r.out, "rod_backlash_max") == Approx(576 * um).epsilon(1e-13).margin(0));  // free play unchanged

  params.erase("stiffness");
  CHECK_THROWS_MATCHES(run_chain(hand_chain(), params, {"compliance"}), NodeError, names("stiffness"));
  CHECK_NOTHROW(run_chain(hand_chain(), params));  // without the effect stiffness is not needed
}

TEST_CASE("backlash.chain: Monte Carlo is reproducible from its seed", "[backlash]") {
  auto params = hand_params();
  params["samples"] = ParamValue::of_integer(2000);
  const Run a = run_chain(hand_chain(), params, {"monte_carlo"}), b = run_chain(hand_chain(), params, {"monte_carlo"});
  params["seed"] = ParamValue::of_integer(2);
  const Run c = run_chain(hand_chain(), params, {"monte_carlo"});
  for (const char* port : {"rod_backlash_mc_mean", "rod_backlash_mc_q999", "mc_mean_error"}) {
    CHECK(scalar(a.out, port) == scalar(b.out, port));
    CHECK(scalar(a.out, port) != scalar(c.out, port));
  }
}

TEST_CASE("backlash.chain in a scene: fits -> pins -> chain -> two axes, through the loader", "[backlash]") {
  const PluginRegistry& registry = project_registry();
  for (const char* type : {"backlash.chain", "backlash.two_axis", "fit.explicit", "joint.pin"}) {
    INFO("node type " << type << " among the built plugins");
    REQUIRE(registry.find(type));
  }
  // The hand chain without the bearing term: L = 25 + 130 + 0.8 * 160 = 283 um,
  // L + dL = 50 + 260 + 0.8 * 270 = 526 um; the two rods through J = [500 50; 0 450] mm/rad:
  // J^-1 = [2 -0.2222; 0 2.2222] /m, pitch = (2 + 0.2222) 526e-6, yaw = 2.2222 * 526e-6 rad.
  const char* scene = R"(nodes:
  f1: { type: fit.explicit, params: { size: 20 mm, hole_upper: 130 um, hole_lower: 0 um, shaft_upper: 0 um, shaft_lower: -130 um } }
  f5: { type: fit.explicit, params: { size: 16 mm, hole_upper: 110 um, hole_lower: 0 um, shaft_upper: -50 um, shaft_lower: -160 um } }
  h1: { type: joint.pin, inputs: { fits: [f1.fit] } }
  h5: { type: joint.pin, inputs: { fits: [f5.fit] } }
  chain: { type: backlash.chain, inputs: { joints: [h1.play, h5.play] },
           params: { transfer_ratios: [1, 0.8], actuator_backlash: 25 um, actuator_backlash_limit: 25 um,
                     lever_arm: 500 mm } }
  both: { type: backlash.two_axis, inputs: { rod_backlash_1: chain.rod_backlash_max, rod_backlash_2: chain.rod_backlash_max },
          params: { jacobian: [500 mm/rad, 50 mm/rad, 0 mm/rad, 450 mm/rad] } }
outputs: [ chain.rod_backlash_mean, chain.rod_backlash_max, chain.angular_backlash_max, both.angular_backlash_pitch,
           both.angular_backlash_yaw ]
)";
  MemoCache cache;
  const RunResult r = evaluate(graph_from(scene, registry), cache);
  CHECK(output(r, "chain.rod_backlash_mean").as_scalar() == Approx(283 * um).epsilon(1e-12).margin(0));
  CHECK(output(r, "chain.rod_backlash_max").as_scalar() == Approx(526 * um).epsilon(1e-12).margin(0));
  CHECK(output(r, "chain.angular_backlash_max").as_scalar() == Approx(1052 * um).epsilon(1e-12).margin(0));
  CHECK(output(r, "both.angular_backlash_pitch").as_scalar() == Approx((2 + 0.1 / 0.45) * 526 * um).epsilon(1e-12).margin(0));
  CHECK(output(r, "both.angular_backlash_yaw").as_scalar() == Approx(526 * um / 0.45).epsilon(1e-12).margin(0));
}

TEST_CASE("backlash.chain and stack.linear describe the contract's names", "[backlash]") {
  const auto chain_type = backlash::make_backlash_chain_type();
  const NodeInfo& chain = chain_type->info();
  for (const char* name : {"transfer_ratios", "actuator_backlash", "actuator_backlash_limit", "lever_arm", "rod_attach_fixed",
                           "rod_attach_moving", "axis_point", "axis_direction", "min_lever_arm", "load", "stiffness",
                           "samples", "seed"})
    CHECK(chain.find_param(name) != nullptr);
  for (const char* name : {"rod_backlash_mean", "rod_backlash_limit", "angular_backlash_mean", "angular_backlash_limit",
                           "angular_backlash_max", "lever_arm", "joint_contribution_worst_case", "rod_backlash_rss_sigma",
                           "rod_backlash_rss_max", "rod_backlash_mc_mean", "rod_backlash_mc_q999", "angular_backlash_mc_q999",
                           "mc_mean_error", "rod_elastic_deflection", "rod_total_under_load"})
    CHECK(chain.find_output(name) != nullptr);
  CHECK(chain.implements_effect("monte_carlo"));
  CHECK(chain.implements_effect("compliance"));
  CHECK(chain.find_input("joints")->multiple);
  CHECK(chain.find_param("samples")->knob);
  const auto stack_type = backlash::make_stack_linear_type();
  const NodeInfo& stack = stack_type->info();
  for (const char* name : {"mean", "worst_case_min", "worst_case_max", "rss_sigma", "rss_min", "rss_max", "contribution_worst_case",
                           "contribution_rss", "mc_mean", "mc_sigma", "mc_min", "mc_max", "mc_q001", "mc_q999", "mc_mean_error",
                           "mc_sigma_error"})
    CHECK(stack.find_output(name) != nullptr);
  CHECK(stack.implements_effect("monte_carlo"));
}
