// cam.three_arc: closed-form radii against the tangency relations, the lift against an
// independent geometric construction (support function / roller envelope over the sampled
// contour), exact derivatives against central differences, and the infeasible requests.
#include "cam_test_support.hpp"

#include <catch2/catch.hpp>

#include "registration.hpp"
#include "three_arc.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <string>
#include <vector>

namespace {

using namespace mechgraph;
using namespace mechgraph::cams;

constexpr double pi = std::numbers::pi;
constexpr double deg = pi / 180.0;
constexpr double mm = 1e-3;


// Evaluates the node with the given parameters, the ParamSpec defaults filled in as the
// evaluator would.
OutputSet run(const std::map<std::string, ParamValue>& given) { return mechgraph::cams::testing::run_cam("cam.three_arc", given); }

std::map<std::string, ParamValue> base_params() {
  return {{"max_lift", ParamValue::of_number(9 * mm)},
          {"action_angle", ParamValue::of_number(130 * deg)},
          {"base_radius", ParamValue::of_number(17 * mm)}};
}

// The node's NodeError, or "" if it did not throw one.
std::string error_parameter(std::map<std::string, ParamValue> given, std::string* message = nullptr) {
  try {
    run(std::move(given));
  } catch (const NodeError& e) {
    if (message) *message = e.what();
    return e.parameter();
  }
  return "";
}

// Lift of an in-line follower by brute force over the sampled contour, independent of the
// law's formulas. Follower direction d at angle phi from the nose. Flat face (rr = 0): the
// support function max P.d. Roller: the smallest centre distance s along d for which the roller
// disc clears every contour point, max over |P.n| <= rr of P.d + sqrt(rr^2 - (P.n)^2).
struct Contour {
  std::vector<double> x, y;
};

Contour sample_contour(const ThreeArcGeometry& g, int per_arc) {
  Contour c;
  auto arc = [&](double cx, double cy, double r, double from, double to) {
    for (int i = 0; i <= per_arc; ++i) {
      const double t = from + (to - from) * i / per_arc;
      c.x.push_back(cx + r * std::cos(t));
      c.y.push_back(cy + r * std::sin(t));
    }
  };
  const double pp = g.half_action, al = g.junction_normal;
  arc(0.0, 0.0, g.base_radius, pp, 2.0 * pi - pp);                                     // base circle
  arc(-g.flank_centre * std::cos(pp), -g.flank_centre * std::sin(pp), g.flank_radius, al, pp);    // upper flank
  arc(-g.flank_centre * std::cos(pp), g.flank_centre * std::sin(pp), g.flank_radius, -pp, -al);   // lower flank
  arc(g.nose_centre, 0.0, g.nose_radius, -al, al);                                     // nose
  return c;
}

double brute_force_lift(const Contour& c, const ThreeArcGeometry& g, double rr, double phi) {
  const double dx = std::cos(phi), dy = std::sin(phi);
  double best = -1.0;
  for (std::size_t i = 0; i < c.x.size(); ++i) {
    const double along = c.x[i] * dx + c.y[i] * dy;
    const double across = -c.x[i] * dy + c.y[i] * dx;
    if (std::abs(across) > rr && rr > 0.0) continue;
    const double s = rr > 0.0 ? along + std::sqrt(rr * rr - across * across) : along;
    best = std::max(best, s);
  }
  return best - (g.base_radius + rr);
}

// Checks each derivative against the central difference of the one below, on angles spread over
// the event that keep `step` away from the breakpoints.
void check_derivatives(const CamLaw& law, double step) {
  const double scale_h = law.max_lift();
  const std::vector<double> bps = law.breakpoints();
  int checked = 0;
  for (int i = 1; i < 60; ++i) {
    const double phi = law.event_begin() + (law.event_end() - law.event_begin()) * i / 60.0 + 1e-3;
    if (phi + step >= law.event_end()) continue;
    bool near = false;
    for (double b : bps) near = near || std::abs(phi - b) < 3.0 * step;
    if (near) continue;
    const LiftDerivatives m = law.at(phi - step), c = law.at(phi), p = law.at(phi + step);
    const double v = (p.lift - m.lift) / (2.0 * step);
    const double a = (p.velocity - m.velocity) / (2.0 * step);
    const double j = (p.acceleration - m.acceleration) / (2.0 * step);
    // truncation ~ step^2 f''' / 6, rounding ~ eps f / step: margins scaled on h_max
    CHECK(c.velocity == Approx(v).epsilon(1e-7).margin(1e-9 * scale_h));
    CHECK(c.acceleration == Approx(a).epsilon(1e-7).margin(1e-9 * scale_h));
    CHECK(c.jerk == Approx(j).epsilon(1e-6).margin(1e-8 * scale_h));
    ++checked;
  }
  CHECK(checked > 40);
}

const CamBasics kBasics{9 * mm, 130 * deg, 17 * mm};

}  // namespace

TEST_CASE("three_arc: closed-form radii satisfy the tangency relations", "[cams][three_arc]") {
  struct Case {
    CamBasics b;
    double accel;
  };
  const std::vector<Case> cases{{kBasics, 18 * deg},
                                {kBasics, 5 * deg},
                                {kBasics, 28 * deg},
                                {{6 * mm, 100 * deg, 22 * mm}, 12 * deg},
                                {{12 * mm, 160 * deg, 25 * mm}, 30 * deg},
                                {{8 * mm, 220 * deg, 20 * mm}, 35 * deg}};  // obtuse half action angle
  for (const Case& k : cases) {
    const ThreeArcGeometry g = three_arc_from_accel_angle(k.b, k.accel);
    const double pp = 0.5 * k.b.action_angle;
    const double a = g.nose_centre, e = g.flank_centre, d = g.flank_radius - g.nose_radius;
    INFO("action " << k.b.action_angle / deg << " deg, accel " << k.accel / deg << " deg");
    // The definitions of a and e, then tangency and the junction angle of the method note.
    CHECK(a == Approx(k.b.base_radius + k.b.max_lift - g.nose_radius).epsilon(1e-14).margin(1e-18));
    CHECK(e == Approx(g.flank_radius - k.b.base_radius).epsilon(1e-14).margin(1e-18));
    CHECK(d * d == Approx(a * a + e * e + 2.0 * a * e * std::cos(pp)).epsilon(1e-13).margin(1e-20));
    CHECK(std::sin(k.accel) == Approx(a * std::sin(pp) / d).epsilon(1e-13).margin(1e-16));
    CHECK(g.flank_angle == Approx(k.accel).epsilon(1e-12).margin(1e-15));
    CHECK(g.nose_radius > 0.0);
    CHECK(g.flank_radius > k.b.base_radius);
    // Law of sines in the triangle O, N, F: the flat-tappet velocity is continuous at the switch.
    CHECK(e * std::sin(g.flank_angle) == Approx(a * std::sin(g.junction_normal)).epsilon(1e-13).margin(1e-18));

    // The nose_radius route (linear in e) recovers the same cam.
    const ThreeArcGeometry back = three_arc_from_nose_radius(k.b, g.nose_radius);
    CHECK(back.flank_radius == Approx(g.flank_radius).epsilon(1e-10).margin(1e-15));
    CHECK(back.flank_angle == Approx(k.accel).epsilon(1e-10).margin(1e-14));
  }
  // The figures of the example study (h = 9 mm, 130 deg, r0 = 17 mm, phi_y = 18 deg).
  const ThreeArcGeometry g = three_arc_from_accel_angle(kBasics, 18 * deg);
  CHECK(g.nose_radius == Approx(5.254866457829e-3).epsilon(1e-10).margin(1e-15));
  CHECK(g.flank_radius == Approx(66.09772110540e-3).epsilon(1e-10).margin(1e-15));
}

TEST_CASE("three_arc: flat tappet lift is the support function of the contour", "[cams][three_arc]") {
  const ThreeArcGeometry g = three_arc_from_accel_angle(kBasics, 18 * deg);
  const ThreeArcLaw law(g, 0.0);
  const Contour contour = sample_contour(g, 100000);
  for (int i = 0; i <= 40; ++i) {
    const double phi = -0.999 * g.half_action + 1.998 * g.half_action * i / 40.0;
    INFO("phi = " << phi / deg << " deg");
    CHECK(law.at(phi).lift == Approx(brute_force_lift(contour, g, 0.0, phi)).epsilon(1e-9).margin(1e-11));
  }
  CHECK(law.switch_angle() == Approx(g.junction_normal).epsilon(1e-15).margin(0));
  // Closed forms on each arc and at the special points.
  CHECK(law.at(0.0).lift == Approx(kBasics.max_lift).epsilon(1e-15).margin(1e-18));
  CHECK(law.at(0.0).acceleration == Approx(-g.nose_centre).epsilon(1e-15).margin(0));
  const double start = -g.half_action + 1e-9;
  CHECK(law.at(start).acceleration == Approx(g.flank_centre).epsilon(1e-12).margin(0));  // the jump at lift start
  CHECK(std::abs(law.at(start).lift) < 1e-18);
}

TEST_CASE("three_arc: roller lift follows the offset contour", "[cams][three_arc]") {
  const ThreeArcGeometry g = three_arc_from_accel_angle(kBasics, 18 * deg);
  for (double rr : {4 * mm, 10 * mm, 15 * mm}) {  // 10 and 15 mm exceed the nose radius (5.25 mm)
    const ThreeArcLaw law(g, rr);
    const Contour contour = sample_contour(g, 100000);
    INFO("roller radius " << rr / mm << " mm");
    for (int i = 0; i <= 40; ++i) {
      const double phi = -0.999 * g.half_action + 1.998 * g.half_action * i / 40.0;
      INFO("phi = " << phi / deg << " deg");
      CHECK(law.at(phi).lift == Approx(brute_force_lift(contour, g, rr, phi)).epsilon(1e-8).margin(1e-11));
    }
    // The roller meets the nose arc later in the lift than a flat tappet (closer to the nose).
    CHECK(law.switch_angle() < g.junction_normal);
    CHECK(law.switch_angle() > 0.0);
    // Lift and velocity continuous at the switch (the pitch curve is tangent-continuous).
    for (double sw : {law.switch_angle(), -law.switch_angle()}) {
      const double eps = 1e-11;
      const LiftDerivatives l = law.at(sw - eps), r = law.at(sw + eps);
      CHECK(l.lift == Approx(r.lift).epsilon(1e-10).margin(1e-15));
      CHECK(l.velocity == Approx(r.velocity).epsilon(1e-8).margin(1e-13));
      CHECK((l.acceleration > 0.0) == (sw < 0.0));  // flank (+) before the switch on the rising side
    }
    CHECK(law.at(0.0).lift == Approx(kBasics.max_lift).epsilon(1e-15).margin(1e-18));
    CHECK(law.roller_radius() == rr);
  }
}

TEST_CASE("three_arc: exact derivatives match central differences", "[cams][three_arc]") {
  const ThreeArcGeometry g = three_arc_from_accel_angle(kBasics, 18 * deg);
  SECTION("flat") { check_derivatives(ThreeArcLaw(g, 0.0), 1e-5); }
  SECTION("roller") { check_derivatives(ThreeArcLaw(g, 8 * mm), 1e-5); }
  SECTION("roller on a sharp nose") {
    check_derivatives(ThreeArcLaw(three_arc_from_accel_angle(kBasics, 27 * deg), 12 * mm), 1e-5);
  }
}

TEST_CASE("three_arc: lift is continuous and symmetric", "[cams][three_arc]") {
  const ThreeArcGeometry g = three_arc_from_accel_angle(kBasics, 22 * deg);
  for (double rr : {0.0, 6 * mm}) {
    const ThreeArcLaw law(g, rr);
    for (double b : law.breakpoints()) {
      const LiftDerivatives l = law.at(b * (1 - 1e-12)), r = law.at(b * (1 + 1e-12));
      CHECK(l.lift == Approx(r.lift).epsilon(1e-10).margin(1e-15));
      CHECK(l.velocity == Approx(r.velocity).epsilon(1e-8).margin(1e-14));
      CHECK(l.acceleration * r.acceleration < 0.0);  // the jump from flank (+) to nose (-)
    }
    for (double phi : {0.1, 0.4, 0.7, 1.1}) {
      const LiftDerivatives p = law.at(phi), m = law.at(-phi);
      CHECK(p.lift == m.lift);
      CHECK(p.velocity == -m.velocity);
      CHECK(p.acceleration == m.acceleration);
      CHECK(p.jerk == -m.jerk);
    }
    CHECK(law.at(g.half_action + 1e-3).lift == 0.0);
    CHECK(law.at(-g.half_action + 1e-12).lift == Approx(0.0).margin(1e-20));
  }
}

TEST_CASE("three_arc node: outputs and summary figures", "[cams][three_arc]") {
  auto p = base_params();
  p["accel_angle"] = ParamValue::of_number(18 * deg);
  const OutputSet out = run(p);
  const ThreeArcGeometry g = three_arc_from_accel_angle(kBasics, 18 * deg);
  const auto& all = out.all();
  CHECK(all.at("flank_radius").as_scalar() == Approx(g.flank_radius).epsilon(1e-15).margin(0));
  CHECK(all.at("nose_radius").as_scalar() == Approx(g.nose_radius).epsilon(1e-15).margin(0));
  // Flat tappet: h' peaks at the switch (e sin phi_1), h'' is e on the flank start and -a at the nose,
  // the positive phase is the flank, and the smallest contour radius is the nose arc.
  CHECK(all.at("max_velocity").as_scalar() ==
        Approx(g.flank_centre * std::sin(g.flank_angle)).epsilon(1e-9).margin(1e-15));
  CHECK(all.at("max_acceleration").as_scalar() == Approx(g.flank_centre).epsilon(1e-9).margin(1e-15));
  CHECK(all.at("min_acceleration").as_scalar() == Approx(-g.nose_centre).epsilon(1e-9).margin(1e-15));
  CHECK(all.at("accel_angle").as_scalar() == Approx(18 * deg).epsilon(1e-9).margin(1e-12));
  CHECK(all.at("min_curvature_radius").as_scalar() == Approx(g.nose_radius).epsilon(1e-6).margin(1e-12));

  // From the nose radius, with a roller.
  auto q = base_params();
  q["nose_radius"] = ParamValue::of_number(g.nose_radius);
  q["follower"] = ParamValue::of_choice("roller");
  q["roller_radius"] = ParamValue::of_number(11 * mm);
  const OutputSet roller = run(q);
  CHECK(roller.all().at("flank_radius").as_scalar() == Approx(g.flank_radius).epsilon(1e-10).margin(0));
  const double achieved = roller.all().at("accel_angle").as_scalar();
  CHECK(achieved > 18 * deg);  // the roller stays on the flank longer
  const ThreeArcLaw rl(g, 11 * mm);
  CHECK(achieved == Approx(g.half_action - rl.switch_angle()).epsilon(1e-9).margin(1e-12));
  CHECK(roller.all().at("min_curvature_radius").as_scalar() == Approx(g.nose_radius).epsilon(1e-6).margin(1e-12));
}

TEST_CASE("three_arc: infeasible requests name the parameter and the limit", "[cams][three_arc]") {
  std::string msg;
  auto p = base_params();
  p["accel_angle"] = ParamValue::of_number(40 * deg);
  CHECK(error_parameter(p, &msg) == "accel_angle");
  // r2 = 0 at s* = 1 + (h^2 + 2 h a0 c)/(2 a0 ((1 - c) a0 - h)), a0 = r0 + h: 28.63 deg here.
  CHECK_THAT(msg, Catch::Contains("nose_radius = -10.36 mm") && Catch::Contains("choose accel_angle below 28.63 deg"));
  // ... and the limit it quotes is the limit.
  CHECK(three_arc_from_accel_angle(kBasics, 28.62 * deg).nose_radius > 0.0);
  CHECK_THROWS_AS(three_arc_from_accel_angle(kBasics, 28.64 * deg), NodeError);

  p["accel_angle"] = ParamValue::of_number(65 * deg);
  CHECK(error_parameter(p, &msg) == "accel_angle");
  CHECK_THAT(msg, Catch::Contains("half the action angle (65 deg)"));

  // Exactly one of accel_angle and nose_radius.
  auto both = base_params();
  both["accel_angle"] = ParamValue::of_number(18 * deg);
  both["nose_radius"] = ParamValue::of_number(4 * mm);
  CHECK(error_parameter(both, &msg) == "accel_angle");
  CHECK_THAT(msg, Catch::Contains("accel_angle") && Catch::Contains("nose_radius") && Catch::Contains("both"));
  CHECK(error_parameter(base_params(), &msg) == "accel_angle");
  CHECK_THAT(msg, Catch::Contains("neither"));

  // Nose radius beyond r0 - h cos(phi_p)/(1 - cos(phi_p)) = 10.41 mm: the flank radius would be infinite.
  auto nose = base_params();
  nose["nose_radius"] = ParamValue::of_number(10.5 * mm);
  CHECK(error_parameter(nose, &msg) == "nose_radius");
  CHECK_THAT(msg, Catch::Contains("below 10.41 mm"));
  nose["nose_radius"] = ParamValue::of_number(10.4 * mm);
  CHECK(error_parameter(nose).empty());

  // No nose radius at all: r0 too small for this lift and action angle.
  CHECK_THROWS_WITH(three_arc_from_nose_radius({9 * mm, 60 * deg, 10 * mm}, 1 * mm), Catch::Contains("no nose radius"));

  // Roller settings.
  auto roller = base_params();
  roller["accel_angle"] = ParamValue::of_number(18 * deg);
  roller["follower"] = ParamValue::of_choice("roller");
  CHECK(error_parameter(roller) == "roller_radius");
  auto flat = base_params();
  flat["accel_angle"] = ParamValue::of_number(18 * deg);
  flat["roller_radius"] = ParamValue::of_number(8 * mm);
  CHECK(error_parameter(flat) == "roller_radius");
}
