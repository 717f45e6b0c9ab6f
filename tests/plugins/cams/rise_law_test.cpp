// The normalised rise laws and the symmetric rise-return cam (plugins/cams/rise_law.hpp) against
// independent values: closed-form peak coefficients and published figures, boundary conditions,
// antisymmetry, numerical differentiation, and the cam nodes' outputs.
#include "cam_conformance_cases.hpp"
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

double part(const RiseValue& r, int k) { return k == 0 ? r.s : k == 1 ? r.ds : k == 2 ? r.d2s : r.d3s; }

// Peak of f on [0, 1]: 20001 samples, then golden-section search between the best sample's
// neighbours (the rise laws are smooth around their peaks).
template <class F>
double peak(F f) {
  int best = 0;
  double best_v = f(0.0);
  for (int i = 1; i <= 20000; ++i)
    if (f(i / 20000.0) > best_v) best_v = f(i / 20000.0), best = i;
  double lo = std::max(0.0, (best - 1) / 20000.0), hi = std::min(1.0, (best + 1) / 20000.0);
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  for (int it = 0; it < 100; ++it) {
    const double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo);
    if (f(x1) > f(x2)) hi = x2; else lo = x1;
  }
  return std::max(best_v, f(0.5 * (lo + hi)));
}

struct Coefficients {
  RiseShape shape;
  double cv, ca;                     // closed forms (see rise_law.hpp)
  double cv_published, ca_published;  // as the textbooks round them
};

// Peak velocity and acceleration coefficients, v_max = Cv h/beta, a_max = Ca h/beta^2 for a rise h
// over the cam angle beta.
// Sources: the closed forms are derived in rise_law.cpp from each law's definition. Published
// figures checked: modified sine Cv = 1.76, Ca = 5.53 (MechDesigner reference, "Modified-Sinusoid
// Motion-Law", http://mechdesigner.support/motion-cam-law-modified-sinusoid.htm); cycloidal
// acceleration extremes at x = 0.25, 0.75 (CamDesigner help, "Cycloidal",
// http://delta-eng.com/Help/WebHelp/topics/cycprops.htm). The other published values below are the
// four-digit figures of the cam textbooks (Norton, Rothbart) as quoted in the project brief; the
// brief's 7.5107 for the 4-5-6-7 acceleration is not the peak of s'' = 420 x^2 (1-x)^2 (1-2x):
// at x = (5 - sqrt 5)/10, x(1-x) = 1/5 and 1-2x = 1/sqrt 5, so Ca = 84 sqrt(5)/25 = 7.5132.
const Coefficients coefficients[] = {
    {RiseShape::cycloidal, 2.0, 2.0 * pi, 2.0, 6.2832},
    {RiseShape::harmonic, pi / 2.0, pi * pi / 2.0, 1.5708, 4.9348},
    {RiseShape::poly345, 15.0 / 8.0, 10.0 / std::sqrt(3.0), 1.875, 5.7735},
    {RiseShape::poly4567, 35.0 / 16.0, 84.0 * std::sqrt(5.0) / 25.0, 2.1875, 7.5132},
    {RiseShape::modified_trapezoid, 2.0, 8.0 * pi / (2.0 + pi), 2.0, 4.8881},
    {RiseShape::modified_sine, 4.0 * pi / (4.0 + pi), 4.0 * pi * pi / (4.0 + pi), 1.7596, 5.5280},
};

}  // namespace

TEST_CASE("normalised rises: ends, antisymmetry, names", "[cams][rise]") {
  for (RiseShape shape : all_rise_shapes) {
    INFO(rise_shape_name(shape));
    const RiseValue a = evaluate_rise(shape, 0.0), b = evaluate_rise(shape, 1.0);
    CHECK(a.s == 0.0);
    CHECK(b.s == 1.0);
    CHECK(a.ds == Approx(0.0).epsilon(0.0).margin(1e-15));
    CHECK(b.ds == Approx(0.0).epsilon(0.0).margin(1e-15));
    if (shape == RiseShape::harmonic) {
      CHECK(a.d2s == Approx(pi * pi / 2.0).epsilon(1e-15).margin(1e-15));
      CHECK(b.d2s == Approx(-pi * pi / 2.0).epsilon(1e-15).margin(1e-15));
    } else {
      CHECK(a.d2s == Approx(0.0).epsilon(0.0).margin(1e-14));
      CHECK(b.d2s == Approx(0.0).epsilon(0.0).margin(1e-14));
    }
    // Outside [0, 1] the argument is clamped.
    CHECK(evaluate_rise(shape, -0.5).s == 0.0);
    CHECK(evaluate_rise(shape, 1.5).s == 1.0);
    // s(x) + s(1 - x) = 1, s' even, s'' odd, s''' even about x = 1/2.
    for (int i = 0; i <= 100; ++i) {
      const double x = i / 100.0;
      const RiseValue l = evaluate_rise(shape, x), r = evaluate_rise(shape, 1.0 - x);
      CHECK(l.s + r.s == Approx(1.0).epsilon(1e-15).margin(1e-15));
      CHECK(l.ds == Approx(r.ds).epsilon(1e-13).margin(1e-13));
      CHECK(l.d2s == Approx(-r.d2s).epsilon(1e-13).margin(1e-12));
      CHECK(l.d3s == Approx(r.d3s).epsilon(1e-13).margin(1e-11));
    }
    CHECK(rise_shape_from_name(rise_shape_name(shape)) == shape);
  }
  CHECK(!rise_shape_from_name("cycloid"));
}

TEST_CASE("normalised rises: peak coefficients against closed forms and published figures", "[cams][rise]") {
  for (const Coefficients& c : coefficients) {
    INFO(rise_shape_name(c.shape));
    const double cv = peak([&](double x) { return evaluate_rise(c.shape, x).ds; });
    const double ca = peak([&](double x) { return evaluate_rise(c.shape, x).d2s; });
    const double cd = peak([&](double x) { return -evaluate_rise(c.shape, x).d2s; });
    CHECK(cv == Approx(c.cv).epsilon(1e-12).margin(1e-12));
    CHECK(ca == Approx(c.ca).epsilon(1e-12).margin(1e-12));
    CHECK(cd == Approx(c.ca).epsilon(1e-12).margin(1e-12));  // symmetric deceleration
    CHECK(c.cv == Approx(c.cv_published).epsilon(1e-6).margin(5e-5));
    CHECK(c.ca == Approx(c.ca_published).epsilon(1e-6).margin(5e-5));
  }
  // The points where the closed forms are attained.
  CHECK(evaluate_rise(RiseShape::cycloidal, 0.25).d2s == Approx(2.0 * pi).epsilon(1e-15).margin(1e-14));
  CHECK(evaluate_rise(RiseShape::poly345, (3.0 - std::sqrt(3.0)) / 6.0).d2s ==
        Approx(10.0 / std::sqrt(3.0)).epsilon(1e-14).margin(1e-14));
  CHECK(evaluate_rise(RiseShape::poly4567, (5.0 - std::sqrt(5.0)) / 10.0).d2s ==
        Approx(84.0 * std::sqrt(5.0) / 25.0).epsilon(1e-14).margin(1e-14));
  CHECK(evaluate_rise(RiseShape::modified_trapezoid, 0.25).d2s ==
        Approx(8.0 * pi / (2.0 + pi)).epsilon(1e-15).margin(1e-14));
  CHECK(evaluate_rise(RiseShape::modified_sine, 0.125).d2s ==
        Approx(4.0 * pi * pi / (4.0 + pi)).epsilon(1e-15).margin(1e-14));
  for (const Coefficients& c : coefficients)
    CHECK(evaluate_rise(c.shape, 0.5).ds == Approx(c.cv).epsilon(1e-15).margin(1e-14));
}

TEST_CASE("normalised rises: derivatives against numerical differentiation, continuity at the pieces",
          "[cams][rise]") {
  for (RiseShape shape : all_rise_shapes) {
    INFO(rise_shape_name(shape));
    std::vector<double> knots{0.0};
    for (double b : rise_breakpoints(shape)) knots.push_back(b);
    knots.push_back(1.0);
    for (std::size_t p = 0; p + 1 < knots.size(); ++p) {
      const double a = knots[p], b = knots[p + 1], h = 1e-4 * (b - a);
      for (int i = 0; i <= 20; ++i) {
        const double x = a + (b - a) * (0.05 + 0.9 * i / 20.0);
        auto central = [&](double step, int k) {
          return (part(evaluate_rise(shape, x + step), k) - part(evaluate_rise(shape, x - step), k)) / (2.0 * step);
        };
        const RiseValue r = evaluate_rise(shape, x);
        for (int k = 0; k < 3; ++k) {
          INFO("derivative " << k + 1 << " at x = " << x);
          const double numeric = (4.0 * central(0.5 * h, k) - central(h, k)) / 3.0;
          CHECK(part(r, k + 1) == Approx(numeric).epsilon(1e-8).margin(1e-8));
        }
      }
    }
    // s .. s''' continuous across the junctions of the pieces (C3 rises).
    for (double b : rise_breakpoints(shape)) {
      const RiseValue l = evaluate_rise(shape, b - 1e-12), r = evaluate_rise(shape, b + 1e-12);
      for (int k = 0; k < 4; ++k) {
        INFO("continuity of derivative " << k << " at x = " << b);
        CHECK(part(l, k) == Approx(part(r, k)).epsilon(1e-9).margin(1e-9));
      }
    }
  }
}

TEST_CASE("symmetric rise-return cam: chain rule, mirror, breakpoints, errors", "[cams][rise]") {
  const double H = 9.0 * mm, action = 130.0 * deg, beta = 0.5 * action;
  for (const Coefficients& c : coefficients) {
    INFO(rise_shape_name(c.shape));
    const SymmetricRiseReturnLaw law(c.shape, H, action, 60.0 * mm);
    CHECK(law.event_begin() == -beta);
    CHECK(law.event_end() == beta);
    CHECK(law.max_lift() == H);
    CHECK(law.at(0.0).lift == Approx(H).epsilon(1e-15).margin(0.0));
    // Mid-rise: peak velocity C_v H/beta; mid-return: -C_v H/beta.
    CHECK(law.at(-0.5 * beta).velocity == Approx(c.cv * H / beta).epsilon(1e-14).margin(0.0));
    CHECK(law.at(0.5 * beta).velocity == Approx(-c.cv * H / beta).epsilon(1e-14).margin(0.0));
    CHECK(law.at(-0.5 * beta).lift == Approx(0.5 * H).epsilon(1e-15).margin(1e-18));
    // Lift and derivatives against the normalised rise at a few points, with (1/beta)^k.
    for (double x : {0.1, 0.3, 0.55, 0.9}) {
      const RiseValue r = evaluate_rise(c.shape, x);
      const LiftDerivatives up = law.at(-beta + x * beta), down = law.at(beta - x * beta);
      CHECK(up.lift == Approx(H * r.s).epsilon(1e-13).margin(1e-18));
      CHECK(up.velocity == Approx(H * r.ds / beta).epsilon(1e-13).margin(1e-18));
      CHECK(up.acceleration == Approx(H * r.d2s / (beta * beta)).epsilon(1e-12).margin(1e-16));
      CHECK(up.jerk == Approx(H * r.d3s / (beta * beta * beta)).epsilon(1e-12).margin(1e-15));
      CHECK(down.lift == Approx(up.lift).epsilon(1e-15).margin(0.0));
      CHECK(down.velocity == Approx(-up.velocity).epsilon(1e-15).margin(0.0));
      CHECK(down.acceleration == Approx(up.acceleration).epsilon(1e-15).margin(0.0));
      CHECK(down.jerk == Approx(-up.jerk).epsilon(1e-15).margin(0.0));
    }
    // Breakpoints: the pieces of the rise, the nose, the pieces of the return.
    const auto bps = law.breakpoints();
    CHECK(bps.size() == 2 * rise_breakpoints(c.shape).size() + 1);
    CHECK(std::find(bps.begin(), bps.end(), 0.0) != bps.end());
  }
  CHECK_THROWS_MATCHES(SymmetricRiseReturnLaw(RiseShape::cycloidal, 0.0, action, 0.02),
                       NodeError, Catch::Matchers::Predicate<NodeError>([](const NodeError& e) { return e.parameter() == "max_lift"; }));
  CHECK_THROWS_MATCHES(SymmetricRiseReturnLaw(RiseShape::cycloidal, H, 2.0 * pi, 0.02),
                       NodeError, Catch::Matchers::Predicate<NodeError>([](const NodeError& e) { return e.parameter() == "action_angle"; }));
  // An action angle so small that the jerk H s'''/P^3 would overflow: refused, not Inf.
  CHECK_THROWS_MATCHES(SymmetricRiseReturnLaw(RiseShape::cycloidal, H, 1e-110, 0.02),
                       NodeError, Catch::Matchers::Predicate<NodeError>([](const NodeError& e) { return e.parameter() == "action_angle"; }));
  CHECK_THROWS_MATCHES(SymmetricRiseReturnLaw(RiseShape::cycloidal, H, action, std::nan("")),
                       NodeError, Catch::Matchers::Predicate<NodeError>([](const NodeError& e) { return e.parameter() == "base_radius"; }));
}

TEST_CASE("standard cam nodes: outputs against the closed-form peaks", "[cams][rise][node]") {
  NodeTypeList types;
  add_standard_law_types(types);
  const double H = 9.0 * mm, action = 130.0 * deg, beta = 0.5 * action;
  for (const Coefficients& c : coefficients) {
    const std::string name = "cam." + std::string(rise_shape_name(c.shape));
    INFO(name);
    const NodeType* type = find_type(types, name);
    REQUIRE(type);
    const Evaluation e = evaluate_node(*type, {{"max_lift", "9 mm"}, {"action_angle", "130 deg"}, {"base_radius", "60 mm"}});
    const auto& out = e.outputs.all();
    CHECK(out.at("max_velocity").as_scalar() == Approx(c.cv * H / beta).epsilon(1e-10).margin(0.0));
    CHECK(out.at("max_acceleration").as_scalar() == Approx(c.ca * H / (beta * beta)).epsilon(1e-10).margin(0.0));
    CHECK(out.at("min_acceleration").as_scalar() == Approx(-c.ca * H / (beta * beta)).epsilon(1e-10).margin(0.0));
    // Every one of these laws decelerates from the middle of the rise on.
    CHECK(out.at("accel_angle").as_scalar() == Approx(0.5 * beta).epsilon(1e-10).margin(0.0));
    // Flat tappet: rho = r0 + h + h'' is smallest where r0 + h + h'' is; 60 mm keeps it positive.
    CHECK(out.at("min_curvature_radius").as_scalar() > 0.0);
    CHECK(out.at("min_curvature_radius").as_scalar() <= 60.0 * mm + H);
  }
  // A base circle too small for the cycloidal law's deceleration under a flat face: the law alone
  // is made (a roller or another follower may follow it), its flat-tappet curvature negative at the
  // nose, r0 + H - H (2 pi / beta)^2 / 2 ... checked by its sign; cam.contour refuses the pair.
  const NodeType* cycloidal = find_type(types, "cam.cycloidal");
  REQUIRE(cycloidal);
  const Evaluation small = evaluate_node(*cycloidal, {{"max_lift", "9 mm"}, {"action_angle", "130 deg"}, {"base_radius", "17 mm"}});
  CHECK(small.outputs.all().at("min_curvature_radius").as_scalar() < 0.0);
}
