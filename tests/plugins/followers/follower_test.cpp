// Followers against independent geometry (docs/methods/followers.md):
//  - a circular-arc (eccentric circle) cam under every follower, its motion in closed form, the
//    contour the circle again: tests/stability/follower_stability_test.cpp (with the conformance
//    kit on the ordinary designs, and every parameter walked to its limits);
//  - a cycloidal cam under each pivoted follower: the contour against the brute-force envelope of
//    the follower's positions (every face or roller at 3600 cam angles: none cuts the contour, each
//    touches it to the chord error);
//  - the conformance kit on every follower; the translating ones against the old closed forms.
#include "contour.hpp"
#include "rise_law.hpp"

#include "test_support.hpp"

#include <followers/follower_types.hpp>
#include <mechgraph/errors.hpp>
#include <mechgraph/testing/cam_law_conformance.hpp>
#include <mechgraph/testing/follower_conformance.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>
#include <regex>

namespace mechgraph::followers {
namespace {

constexpr double pi = std::numbers::pi;
constexpr double deg = pi / 180.0;
using Catch::Matchers::WithinAbs;
using Catch::Matchers::WithinRel;

struct Vec {
  double x, y;
};
// A point of the cam's frame seen in the fixed frame after the cam turned by sigma phi.
Vec to_fixed(Vec v, double phi, double sigma) {
  const double c = std::cos(sigma * phi), s = std::sin(sigma * phi);
  return {v.x * c - v.y * s, v.x * s + v.y * c};
}
Vec to_cam(Vec v, double phi, double sigma) { return to_fixed(v, -phi, sigma); }

// The cam for the envelope tests: cycloidal, 7 mm over 140 deg on a 40 mm base circle. A translating
// flat face needs r0 > 2 pi H / beta^2 - h(3/4 of the rise) = 29.5 - 6.4 = 23 mm; a pivoted one
// more (its face turns as well): with the pivot at (-50, 45) mm and the face 2 mm from it, its
// smallest radius of curvature is 3.8 mm at r0 = 40 mm and negative at 30 mm. Every follower here
// follows it.
std::shared_ptr<const CamLaw> cycloidal() {
  return std::make_shared<const cams::SymmetricRiseReturnLaw>(cams::RiseShape::cycloidal, 7e-3, 140 * deg, 40e-3, 0.0);
}

TEST_CASE("pivoted flat face: the contour is the envelope of the face's positions (brute force)", "[followers][pivoted]") {
  const auto law = cycloidal();
  const double px = -50e-3, py = 45e-3, f = 2e-3, tol = 1e-6;
  for (const bool clockwise : {false, true}) {
    const double sigma = clockwise ? -1.0 : 1.0;
    const auto follower = make_pivoted_flat(px, py, f);
    long evaluations = 0;
    const cams::ContourPoints contour = cams::trace_contour(*law, *follower, clockwise, tol, evaluations);
    // The face at cam angle phi, in the cam's frame: outward normal m and distance p from the centre.
    const double r = law->base_radius();
    const double psi0 = std::atan2(py, px) - pi + std::asin((r + f) / std::hypot(px, py));
    const double lever = std::sqrt(px * px + py * py - (r + f) * (r + f));
    double worst_cut = -1.0, worst_gap = 0.0;
    for (int j = 0; j < 3600; ++j) {
      const double phi = -pi + 2 * pi * j / 3600.0;
      const double psi = psi0 + law->at(phi).lift / lever;
      const Vec mf{-std::sin(psi), std::cos(psi)};  // k = +1: the pivot is left of the axis
      const Vec m = to_cam(mf, phi, sigma);
      const double distance = mf.x * px + mf.y * py - f;
      double support = -1.0;
      for (const auto& c : contour.points) {
        const double reach = m.x * c.x + m.y * c.y;
        support = std::max(support, reach);
      }
      worst_cut = std::max(worst_cut, support - distance);  // > 0: the face cuts into the contour
      worst_gap = std::max(worst_gap, distance - support);  // > tol: the face misses it
    }
    INFO((clockwise ? "cw" : "ccw") << ": cut " << worst_cut << " m, gap " << worst_gap << " m");
    CHECK(worst_cut <= 1e-12);
    CHECK(worst_gap <= tol + 1e-12);
  }
}

TEST_CASE("pivoted roller: the contour is the envelope of the roller's positions (brute force)", "[followers][pivoted]") {
  const auto law = cycloidal();
  const double px = -38e-3, py = 24e-3, arm = 37e-3, rr = 8e-3, tol = 1e-6;
  for (const bool clockwise : {false, true}) {
    const double sigma = clockwise ? -1.0 : 1.0;
    const auto follower = make_pivoted_roller(px, py, arm, rr);
    long evaluations = 0;
    const cams::ContourPoints contour = cams::trace_contour(*law, *follower, clockwise, tol, evaluations);
    const double r = law->base_radius();
    const double d = std::hypot(px, py);
    const double psi0 = std::atan2(py, px) - pi + std::acos(-((r + rr) * (r + rr) - d * d - arm * arm) / (2 * arm * d));
    double worst_cut = 0.0, worst_gap = 0.0;
    for (int j = 0; j < 3600; ++j) {
      const double phi = -pi + 2 * pi * j / 3600.0;
      const double psi = psi0 + law->at(phi).lift / arm;
      const Vec centre = to_cam({px + arm * std::cos(psi), py + arm * std::sin(psi)}, phi, sigma);
      // Nearest distance from the roller centre to the contour polyline.
      double nearest = 1.0;
      const auto& pts = contour.points;
      for (std::size_t i = 0; i < pts.size(); ++i) {
        const auto& a = pts[i];
        const auto& b = pts[(i + 1) % pts.size()];
        nearest = std::min(nearest, cams::distance_to_segment(centre.x, centre.y, a.x, a.y, b.x, b.y));
      }
      // The polyline's chords lie inside the convex contour by at most tol.
      worst_cut = std::max(worst_cut, rr - nearest - tol);
      worst_gap = std::max(worst_gap, nearest - rr);
    }
    INFO((clockwise ? "cw" : "ccw") << ": cut " << worst_cut << " m, gap " << worst_gap << " m");
    CHECK(worst_cut <= 1e-12);
    CHECK(worst_gap <= tol + 1e-12);
  }
}

TEST_CASE("every follower passes the conformance kit on a cycloidal cam", "[followers][conformance]") {
  const auto law = cycloidal();
  const std::shared_ptr<const Follower> all[] = {make_flat(), make_roller(9e-3, 0.0), make_roller(9e-3, 3e-3),
                                                 make_pivoted_flat(-50e-3, 45e-3, 2e-3),
                                                 make_pivoted_roller(-38e-3, 24e-3, 37e-3, 8e-3),
                                                 make_pivoted_roller(38e-3, 24e-3, 37e-3, 8e-3)};
  for (const auto& f : all)
    for (const bool clockwise : {false, true}) {
      const auto report = mechgraph::testing::check_follower(*f, *law, clockwise);
      INFO(f->named() << (clockwise ? " cw" : " ccw") << "\n" << report.str());
      CHECK(report.passed());
    }
}

TEST_CASE("translating followers keep their closed forms, names and refusals say which follower", "[followers]") {
  const auto law = cycloidal();
  const double phi = -25 * deg;
  const LiftDerivatives d = law->at(phi);
  // Flat: rho = r0 + h + h'', the contact h' from the axis.
  const FollowerContact flat = make_flat()->contact(phi, d, 20e-3, false);
  CHECK_THAT(flat.curvature_radius, WithinRel(20e-3 + d.lift + d.acceleration, 1e-14));
  CHECK_THAT(flat.face_position, WithinRel(d.velocity, 1e-14));
  // Offset roller: tan(alpha) = (h' - e) / (s0 + h), s0 = sqrt((r0 + rr)^2 - e^2).
  const FollowerContact roller = make_roller(9e-3, 3e-3)->contact(phi, d, 20e-3, false);
  CHECK_THAT(roller.pressure_angle, WithinAbs(std::atan((d.velocity - 3e-3) / (std::sqrt(29e-3 * 29e-3 - 9e-6) + d.lift)), 1e-15));
  CHECK(make_roller(9e-3, 3e-3)->type_name() == "follower.offset_roller");
  CHECK_THAT(make_pivoted_roller(-38e-3, 24e-3, 37e-3, 8e-3)->named(),
             Catch::Contains("follower.pivoted_roller (pivoted roller 8 mm, pivot (-38 mm, 24 mm), arm 37 mm)"));
  // A pivoted roller whose arm cannot reach the base circle; a flat face whose pivot is inside it.
  CHECK_THROWS_WITH(make_pivoted_roller(-38e-3, 24e-3, 5e-3, 8e-3)->contact(0.0, d, 20e-3, false),
                    Catch::Contains("arm must lie between") && Catch::Contains("follower.pivoted_roller"));
  CHECK_THROWS_WITH(make_pivoted_flat(-10e-3, 5e-3, 0.0)->contact(0.0, d, 20e-3, false),
                    Catch::Contains("the pivot must lie farther"));
}

OutputSet run_valve_lift(std::shared_ptr<const CamLaw> law, std::shared_ptr<const Follower> follower,
                         const std::map<std::string, ParamValue>& given) {
  const auto type = make_valve_lift_type();
  InputSet in;
  in.add("cam", Value::handle(std::move(law)));
  in.add("follower", Value::handle(std::move(follower)));
  OutputSet out;
  mechgraph::testing::RecordingContext ctx;
  type->evaluate(mechgraph::testing::defaults_of(type->info(), given), in, out, ctx);
  return out;
}

TEST_CASE("follower.valve_lift: the valve lift of a finger in closed form, its derivatives through the cam-law kit",
          "[followers][pivoted]") {
  const auto law = cycloidal();
  const double arm = 37e-3, Lv = 50e-3, a = 5 * deg;
  const OutputSet out = run_valve_lift(law, make_pivoted_roller(-38e-3, 24e-3, arm, 8e-3),
                                       {{"valve_arm", ParamValue::of_number(Lv)}, {"valve_arm_angle", ParamValue::of_number(a)}});
  const auto valve = std::dynamic_pointer_cast<const CamLaw>(out.all().at("law").as_handle());
  REQUIRE(valve);
  // v = Lv (sin(h / L - a) + sin a): the pad centre's travel along the valve axis.
  for (double phi = -80 * deg; phi <= 80 * deg; phi += 4 * deg) {
    const double h = law->at(phi).lift;
    CHECK_THAT(valve->at(phi).lift, WithinRel(Lv * (std::sin(h / arm - a) + std::sin(a)), 1e-12) || WithinAbs(0.0, 1e-18));
  }
  CHECK_THAT(valve->max_lift(), WithinRel(Lv * (std::sin(7e-3 / arm - a) + std::sin(a)), 1e-14));
  CHECK_THAT(out.all().at("ratio_closed").as_scalar(), WithinRel(Lv / arm * std::cos(a), 1e-14));
  CHECK_THAT(out.all().at("ratio_at_nose").as_scalar(), WithinRel(Lv / arm * std::cos(7e-3 / arm - a), 1e-14));
  // Velocity, acceleration and jerk by the chain rule, against Richardson differences (the kit).
  mechgraph::testing::CamLawCheckOptions options;
  options.continuity = 2;
  const auto report = mechgraph::testing::check_cam_law(*valve, "valve side", options);
  INFO(report.str());
  CHECK(report.passed());
  // A translating follower acts on the valve directly: the law passes through.
  const OutputSet bucket = run_valve_lift(law, make_flat(), {});
  CHECK(bucket.all().at("law").as_handle() == law);
  CHECK_THROWS_WITH(run_valve_lift(law, make_flat(), {{"valve_arm", ParamValue::of_number(Lv)}}),
                    Catch::Contains("acts on the valve directly"));
  CHECK_THROWS_WITH(run_valve_lift(law, make_pivoted_roller(-38e-3, 24e-3, 150e-3, 8e-3), {{"valve_arm", ParamValue::of_number(Lv)}}),
                    Catch::Contains("cannot reach the base circle"));
  // An arm that would pass 90 deg from square: the valve would fall back.
  CHECK_THROWS_WITH(run_valve_lift(law, make_pivoted_roller(-38e-3, 24e-3, arm, 8e-3),
                                   {{"valve_arm", ParamValue::of_number(Lv)}, {"valve_arm_angle", ParamValue::of_number(-85 * deg)}}),
                    Catch::Contains("valve_arm_angle") || Catch::Contains("fall back"));
}

}  // namespace
}  // namespace mechgraph::followers

namespace mechgraph::followers {
namespace {

TEST_CASE("a law a flat face undercuts is made, and reaches cam.contour with a roller, the flat face is refused by name",
          "[followers][undercut]") {
  // Cycloidal 9 mm over 130 deg on 17 mm: a flat face's contour radius r0 + h + h'' goes to
  // -18.78 mm (the cam node says so), so a flat face needs r0 >= 17 + 18.78 = 35.78 mm with this
  // lift; a 6 mm roller follows it as it is.
  const std::string scene =
      "nodes:\n"
      "  cam: { type: cam.cycloidal, params: { max_lift: 9 mm, action_angle: 130 deg, base_radius: 17 mm } }\n"
      "  roller: { type: follower.roller, params: { roller_radius: 6 mm } }\n"
      "  flat: { type: follower.flat }\n"
      "  cut_roller: { type: cam.contour, inputs: { cam: cam.law, follower: roller.follower } }\n"
      "  cut_flat: { type: cam.contour, inputs: { cam: cam.law, follower: flat.follower } }\n";
  using mechgraph::testing::project_registry;
  const auto ok = mechgraph::testing::run_yaml(scene + "outputs: [cam.min_curvature_radius, cut_roller.max_pressure_angle]\n",
                                               project_registry());
  const double rho = mechgraph::testing::scalar_output(ok, "cam.min_curvature_radius");
  CHECK(rho < -18e-3);
  CHECK(mechgraph::testing::scalar_output(ok, "cut_roller.max_pressure_angle") > 0.0);
  try {
    mechgraph::testing::run_yaml(scene + "outputs: [cut_flat.max_pressure_angle]\n", project_registry());
    FAIL("the flat face was not refused");
  } catch (const EvaluationError& e) {
    const std::string text = e.what();
    CHECK_THAT(text, Catch::Contains("follower.flat (flat-faced tappet) cannot follow this law") && Catch::Contains("node 'cut_flat'"));
    std::smatch m;
    REQUIRE(std::regex_search(text, m, std::regex("base_radius must be at least ([0-9.eE+-]+) mm")));
    CHECK_THAT(std::stod(m[1]) * 1e-3, WithinAbs(17e-3 - rho, 2e-6));  // message digits and the 1 um bisection
  }
}

}  // namespace
}  // namespace mechgraph::followers
