// cam.contour: the contour against properties a second method gives independently (the support
// function of a flat-faced follower's cam, the roller's clearance from the contour, curvature from
// three neighbouring points, the pressure angle from the contour's own tangent), the chord-error
// knob, Hertz stress against the cam node's own radius of curvature, and the refusals.
#include "cam_test_support.hpp"
#include "contour.hpp"
#include "rise_law.hpp"

#include <followers/follower_types.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace mechgraph::cams {
namespace {

constexpr double pi = std::numbers::pi;
constexpr double deg = pi / 180.0;


OutputSet run_contour(std::shared_ptr<const CamLaw> law, const std::map<std::string, ParamValue>& given,
                      const Table* forces = nullptr) {
  InputSet in;
  in.add("cam", Value::handle(std::move(law)));
  if (forces) in.add("forces", Value::table(*forces));
  OutputSet out;
  mechgraph::testing::RecordingContext ctx;
  testing::contour_type().evaluate(mechgraph::testing::defaults_of(testing::contour_type().info(), given), in, out, ctx);
  CHECK(ctx.work.at("evaluations") > 0);
  return out;
}

std::shared_ptr<const CamLaw> cycloidal(double roller = 0.0, double base_radius = 40e-3) {
  return std::make_shared<const SymmetricRiseReturnLaw>(RiseShape::cycloidal, 8e-3, 130 * deg, base_radius, roller);
}

double scalar(const OutputSet& out, const char* name) { return out.all().at(name).as_scalar(); }

TEST_CASE("flat-face contour: base circle at r0, and its support function is r0 + h (the envelope property)") {
  const auto law = cycloidal();
  const double tol = 1e-6;
  const OutputSet out = run_contour(law, {{"chord_error", ParamValue::of_number(tol)}});
  const Table& c = out.all().at("contour").as_table();
  CHECK(c.closed_curve);
  const auto& x = c.find("x")->values;
  const auto& y = c.find("y")->values;
  REQUIRE(x.size() == c.axis.values.size());
  CHECK(scalar(out, "points") == static_cast<double>(x.size()));
  for (std::size_t i = 0; i < x.size(); ++i)
    if (std::abs(c.axis.values[i]) > 65.0 * deg) CHECK_THAT(std::hypot(x[i], y[i]), Catch::Matchers::WithinAbs(40e-3, 1e-12));
  // The face at angle phi touches the cam: max over the contour of P.u(phi) = r0 + h(phi), to the
  // chord error (the polyline lies inside the convex contour by at most tol).
  for (double phi = -pi; phi < pi; phi += 0.7 * deg) {
    const double ux = std::sin(phi), uy = std::cos(phi);  // ccw: u(phi) = (sin phi, cos phi)
    double support = -1.0;
    for (std::size_t i = 0; i < x.size(); ++i) support = std::max(support, x[i] * ux + y[i] * uy);
    const double expected = 40e-3 + law->at(phi).lift;
    CHECK(support <= expected + 1e-12);
    CHECK(support >= expected - tol - 1e-12);
  }
}

TEST_CASE("the chord error holds between every pair of points, and the point count follows tol^-1/2") {
  const auto law = cycloidal(10e-3);
  const auto roller = followers::make_roller(10e-3, 3e-3);
  const auto contact_at = [&](double phi, const LiftDerivatives& d) { return roller->contact(phi, d, 40e-3, false); };
  std::size_t previous = 0;
  for (double tol : {1e-4, 1e-5, 1e-6}) {
    long evaluations = 0;
    const ContourPoints c = trace_contour(*law, *roller, false, tol, evaluations);
    double worst = 0.0;
    for (std::size_t i = 0; i < c.phi.size(); ++i) {
      const std::size_t j = (i + 1) % c.phi.size();
      const double b = j == 0 ? c.phi[0] + 2.0 * pi : c.phi[j];
      for (int k = 1; k < 16; ++k) {
        const double phi = c.phi[i] + (b - c.phi[i]) * k / 16.0;
        const FollowerContact g = contact_at(phi, law->at(phi));
        worst = std::max(worst, distance_to_segment(g.x, g.y, c.points[i].x, c.points[i].y, c.points[j].x, c.points[j].y));
        worst = std::max(worst, distance_to_segment(g.pitch_x, g.pitch_y, c.points[i].pitch_x, c.points[i].pitch_y,
                                                    c.points[j].pitch_x, c.points[j].pitch_y));
      }
    }
    CHECK(worst <= tol * (1.0 + 1e-9));
    if (previous) {
      // Sagitta ~ L^2 / (8 rho): ten times finer needs about sqrt(10) = 3.2 times the points.
      const double ratio = static_cast<double>(c.phi.size()) / static_cast<double>(previous);
      CHECK(ratio > 2.0);
      CHECK(ratio < 4.5);
    }
    previous = c.phi.size();
  }
}

TEST_CASE("roller contour: the roller centred on the pitch curve touches the contour and never cuts it") {
  const auto law = cycloidal();
  const double rr = 8e-3, tol = 1e-6;
  const OutputSet out = run_contour(law, {{"follower", ParamValue::of_choice("roller")},
                                          {"roller_radius", ParamValue::of_number(rr)},
                                          {"offset", ParamValue::of_number(4e-3)},
                                          {"chord_error", ParamValue::of_number(tol)}});
  const Table& c = out.all().at("contour").as_table();
  const auto& x = c.find("x")->values;
  const auto& y = c.find("y")->values;
  const auto& px = c.find("pitch_x")->values;
  const auto& py = c.find("pitch_y")->values;
  for (std::size_t i = 0; i < px.size(); i += 7) {
    double nearest = 1.0;
    for (std::size_t j = 0; j < x.size(); ++j) {
      const std::size_t k = (j + 1) % x.size();
      nearest = std::min(nearest, distance_to_segment(px[i], py[i], x[j], y[j], x[k], y[k]));
    }
    CHECK_THAT(nearest, Catch::Matchers::WithinAbs(rr, tol + 1e-12));
    // The pitch circle radius on the base circle: sqrt((r0 + rr)^2 - e^2) along the axis, e across.
    if (std::abs(c.axis.values[i]) > 65.0 * deg)
      CHECK_THAT(std::hypot(px[i], py[i]), Catch::Matchers::WithinAbs(40e-3 + rr, 1e-12));
  }
}

TEST_CASE("pressure angle and radius of curvature agree with the contour's own geometry (offset roller)") {
  const auto law = cycloidal();
  const auto roller = followers::make_roller(9e-3, -2.5e-3);
  const auto contact_at = [&](double phi, const LiftDerivatives& d) { return roller->contact(phi, d, 40e-3, false); };
  const double h = 1e-5;
  for (double phi = -60 * deg; phi <= 60 * deg; phi += 7 * deg) {
    const FollowerContact g = contact_at(phi, law->at(phi));
    const FollowerContact a = contact_at(phi - h, law->at(phi - h)), b = contact_at(phi + h, law->at(phi + h));
    // The contact normal is perpendicular to the pitch curve's tangent; the pressure angle is the
    // angle between that normal and the follower axis u.
    const double tx = b.pitch_x - a.pitch_x, ty = b.pitch_y - a.pitch_y;
    // The cam turns ccw, so the pitch curve is run through clockwise as phi grows: the tangent
    // turned counterclockwise points outward; u = (sin phi, cos phi).
    const double nx = -ty, ny = tx;
    const double cos_alpha = (nx * std::sin(phi) + ny * std::cos(phi)) / std::hypot(nx, ny);
    CHECK_THAT(std::abs(g.pressure_angle), Catch::Matchers::WithinAbs(std::acos(std::min(1.0, cos_alpha)), 1e-6));
    // Circumradius of three contour points.
    const double ab = std::hypot(b.x - a.x, b.y - a.y), ag = std::hypot(g.x - a.x, g.y - a.y), gb = std::hypot(b.x - g.x, b.y - g.y);
    const double area2 = std::abs((g.x - a.x) * (b.y - a.y) - (g.y - a.y) * (b.x - a.x));
    const double R = ab * ag * gb / (2.0 * area2);
    CHECK_THAT(std::abs(g.curvature_radius), Catch::Matchers::WithinRel(R, 1e-4));
  }
  // Norton's formula by hand at one angle: tan(alpha) = (h' - e)/(s0 + h).
  const LiftDerivatives d = law->at(-30 * deg);
  const double s0 = std::sqrt(49e-3 * 49e-3 - 2.5e-3 * 2.5e-3);
  CHECK_THAT(contact_at(-30 * deg, d).pressure_angle,
             Catch::Matchers::WithinAbs(std::atan((d.velocity + 2.5e-3) / (s0 + d.lift)), 1e-15));
}

TEST_CASE("flat face: width from the velocity's extremes, Hertz stress at the cam node's smallest radius") {
  const OutputSet cam = testing::run_cam("cam.cycloidal", {{"max_lift", ParamValue::of_number(8e-3)},
                                                           {"action_angle", ParamValue::of_number(130 * deg)},
                                                           {"base_radius", ParamValue::of_number(40e-3)}});
  const auto law = std::dynamic_pointer_cast<const CamLaw>(cam.all().at("law").as_handle());
  const double F = 1200.0, L = 12e-3;
  const OutputSet out = run_contour(law, {{"load", ParamValue::of_number(F)}, {"contact_length", ParamValue::of_number(L)}});
  const double vmax = cam.all().at("max_velocity").as_scalar();
  CHECK_THAT(scalar(out, "min_face_width"), Catch::Matchers::WithinRel(2.0 * vmax, 1e-10));
  CHECK_THAT(scalar(out, "min_face_diameter"), Catch::Matchers::WithinRel(2.0 * vmax, 1e-10));
  CHECK(scalar(out, "max_pressure_angle") == 0.0);
  // p0 = sqrt(F E* / (pi L R)), E* = E / (2 (1 - nu^2)) for two equal steels (Johnson 4.3).
  const double e_star = 206e9 / (2.0 * (1.0 - 0.09));
  const double rho = cam.all().at("min_curvature_radius").as_scalar();
  CHECK_THAT(scalar(out, "max_contact_stress"), Catch::Matchers::WithinRel(std::sqrt(F * e_star / (pi * L * rho)), 1e-8));
  // A worked number: F = 1200 N, L = 12 mm, R = 5 mm, E* = 113.19 GPa -> p0 = 848.8 MPa.
  CHECK_THAT(std::sqrt(1200.0 * e_star / (pi * 12e-3 * 5e-3)), Catch::Matchers::WithinRel(848.8e6, 1e-4));

  // The same load as a table over cam angle (times load_ratio) gives the same stress.
  Table forces;
  forces.axis = {"cam_angle", dim::angle, {-pi, 0.0, pi}, "deg"};
  forces.add_channel("contact_force", dim::force, "N").values = {F / 1.5, F / 1.5, F / 1.5};
  const OutputSet via_table = run_contour(law, {{"load_ratio", ParamValue::of_number(1.5)}, {"contact_length", ParamValue::of_number(L)}}, &forces);
  CHECK_THAT(scalar(via_table, "max_contact_stress"), Catch::Matchers::WithinRel(scalar(out, "max_contact_stress"), 1e-12));
  const Table& contact = via_table.all().at("contact").as_table();
  CHECK(contact.find("load")->values[100] == Approx(F).epsilon(1e-12).margin(1e-9));
}

TEST_CASE("a forces table over part of the turn loads the cam only there, its ends included") {
  // A constant F over [-40, 30] deg (a valve open there): the contact table carries F inside, 0
  // outside; the largest stress lies inside; a sparse table over 250 deg is part of a turn too.
  const auto law = cycloidal();
  const double F = 900.0, L = 10e-3, a = -40 * deg, b = 30 * deg;
  Table forces;
  forces.axis = {"cam_angle", dim::angle, {a, 0.0, b}, "deg"};
  forces.add_channel("contact_force", dim::force, "N").values = {F, F, F};
  const OutputSet out = run_contour(law, {{"contact_length", ParamValue::of_number(L)}, {"curve_points", ParamValue::of_integer(2001)}}, &forces);
  const Table& contact = out.all().at("contact").as_table();
  int inside = 0, outside = 0;
  for (std::size_t i = 0; i < contact.axis.values.size(); ++i) {
    const double phi = contact.axis.values[i], load = contact.find("load")->values[i];
    if (phi >= a && phi <= b) {
      ++inside;
      CHECK(load == F);
    } else {
      ++outside;
      CHECK(load == 0.0);
    }
  }
  CHECK(inside > 500);
  CHECK(outside > 500);
  const double at = scalar(out, "max_stress_angle");
  CHECK(at >= a - 1e-12);
  CHECK(at <= b + 1e-12);
  // A table ending exactly on contact rows is loaded there, at both ends (an angle inside the
  // table is not wrapped, which could round it past the end).
  for (std::size_t first : {std::size_t{300}, std::size_t{777}}) {
    const std::size_t last = first + 613;
    Table ends;
    ends.axis = {"cam_angle", dim::angle, {contact.axis.values[first], contact.axis.values[last]}, "deg"};
    ends.add_channel("contact_force", dim::force, "N").values = {F, F};
    const OutputSet on_rows =
        run_contour(law, {{"contact_length", ParamValue::of_number(L)}, {"curve_points", ParamValue::of_integer(2001)}}, &ends);
    const auto& load = on_rows.all().at("contact").as_table().find("load")->values;
    CHECK(load[first] == F);
    CHECK(load[last] == F);
    CHECK(load[first - 1] == 0.0);
    CHECK(load[last + 1] == 0.0);
  }
}

TEST_CASE("cw mirrors the contour, refusals name the parameter") {
  const auto law = cycloidal();
  const OutputSet ccw = run_contour(law, {});
  const OutputSet cw = run_contour(law, {{"rotation", ParamValue::of_choice("cw")}});
  const Table& a = ccw.all().at("contour").as_table();
  const Table& b = cw.all().at("contour").as_table();
  REQUIRE(a.axis.values.size() == b.axis.values.size());
  for (std::size_t i = 0; i < a.axis.values.size(); i += 11) CHECK(b.find("x")->values[i] == -a.find("x")->values[i]);

  auto fails = [&](const std::shared_ptr<const CamLaw>& l, const std::map<std::string, ParamValue>& p) {
    try {
      run_contour(l, p);
    } catch (const NodeError& e) {
      return e.parameter() + ": " + e.what();
    }
    return std::string("no error");
  };
  // A roller larger than the nose's pitch radius cannot follow it: on r0 = 5 mm the pitch radius
  // at the nose is R^2 / (R - h'') = 33^2 / (33 + 39) = 15 mm (R = r0 + rr + H, all in mm).
  CHECK_THAT(fails(cycloidal(0.0, 5e-3), {{"follower", ParamValue::of_choice("roller")}, {"roller_radius", ParamValue::of_number(20e-3)}}),
             Catch::Contains("roller_radius: ") && Catch::Contains("undercut"));
  CHECK_THAT(fails(law, {{"follower", ParamValue::of_choice("roller")}}), Catch::Contains("roller_radius: follower roller needs roller_radius"));
  CHECK_THAT(fails(cycloidal(10e-3), {{"follower", ParamValue::of_choice("flat")}}), Catch::Contains("follower: the law's lift is that of a roller"));
  CHECK_THAT(fails(cycloidal(10e-3), {{"roller_radius", ParamValue::of_number(12e-3)}}), Catch::Contains("differs from the 10 mm"));
  CHECK_THAT(fails(law, {{"load", ParamValue::of_number(100.0)}}), Catch::Contains("contact_length: "));
  // A chord error a hundred-millionth of the cam's size would need millions of points.
  CHECK_THAT(fails(std::make_shared<const SymmetricRiseReturnLaw>(RiseShape::cycloidal, 8e-3, 130 * deg, 100.0),
                   {{"chord_error", ParamValue::of_number(1e-9)}}),
             Catch::Contains("chord_error: the contour needs more than 1000000 points"));
  CHECK_THAT(fails(law, {{"follower", ParamValue::of_choice("roller")}, {"roller_radius", ParamValue::of_number(5e-3)},
                         {"offset", ParamValue::of_number(50e-3)}}),
             Catch::Contains("offset: "));
}

}  // namespace
}  // namespace mechgraph::cams

namespace {
std::vector<std::string> notes_of(const mechgraph::RunResult& r, const std::string& node) {
  for (const auto& n : r.runs)
    if (n.node == node) return n.notes;
  return {};
}
bool any_note(const std::vector<std::string>& notes, const std::string& part) {
  for (const std::string& n : notes)
    if (n.find(part) != std::string::npos) return true;
  return false;
}
}  // namespace

TEST_CASE("contour: undercut margin and the least convex and concave radii as scalars", "[cams][contour][undercut]") {
  using mechgraph::testing::project_registry;
  using mechgraph::testing::run_yaml;
  using mechgraph::testing::scalar_output;
  // Flat face: the margin is the contour's least radius r0 + h + h'' (the cam node's figure, a
  // second method); a harmonic cam with a small roller has concave flanks: their curvature against
  // the contact table (every table row within the peaks found).
  const mechgraph::RunResult r = run_yaml(
      "nodes:\n  cam: { type: cam.harmonic, params: { max_lift: 8 mm, action_angle: 100 deg, base_radius: 20 mm } }\n"
      "  big: { type: cam.harmonic, params: { max_lift: 8 mm, action_angle: 100 deg, base_radius: 50 mm } }\n"
      "  flat: { type: cam.contour, inputs: { cam: big.law } }\n"
      "  roll: { type: cam.contour, inputs: { cam: cam.law }, params: { follower: roller, roller_radius: 4 mm, curve_points: 2001 } }\n"
      "outputs: [big.min_curvature_radius, flat.undercut_margin, flat.min_convex_radius, flat.max_concave_curvature,\n"
      "          roll.undercut_margin, roll.min_convex_radius, roll.max_concave_curvature, roll.contact]\n",
      project_registry());
  CHECK_THAT(scalar_output(r, "flat.undercut_margin"), Catch::Matchers::WithinRel(scalar_output(r, "big.min_curvature_radius"), 1e-9));
  CHECK_THAT(scalar_output(r, "flat.min_convex_radius"), Catch::Matchers::WithinRel(scalar_output(r, "big.min_curvature_radius"), 1e-9));
  CHECK(scalar_output(r, "flat.max_concave_curvature") == 0.0);
  const mechgraph::Table& t = mechgraph::testing::output(r, "roll.contact").as_table();
  const auto& rho = t.find("curvature_radius")->values;
  double least_convex = 1e300, most_concave = 0.0;
  for (double v : rho)
    if (v > 0.0) least_convex = std::min(least_convex, v);
    else most_concave = std::max(most_concave, -1.0 / v);
  REQUIRE(most_concave > 0.0);  // the flanks are concave
  CHECK(scalar_output(r, "roll.min_convex_radius") <= least_convex * (1 + 1e-12));
  CHECK_THAT(scalar_output(r, "roll.min_convex_radius"), Catch::Matchers::WithinRel(least_convex, 1e-3));
  CHECK(scalar_output(r, "roll.max_concave_curvature") >= most_concave * (1 - 1e-12));
  CHECK_THAT(scalar_output(r, "roll.max_concave_curvature"), Catch::Matchers::WithinRel(most_concave, 1e-3));
  CHECK(scalar_output(r, "roll.undercut_margin") > 0.0);
}

TEST_CASE("contour: pressure angle and contact stress limits, and the constant load, in notes", "[cams][contour]") {
  using mechgraph::testing::project_registry;
  using mechgraph::testing::run_yaml;
  using mechgraph::testing::scalar_output;
  const std::string cam = "nodes:\n  cam: { type: cam.harmonic, params: { max_lift: 8 mm, action_angle: 100 deg, base_radius: 12 mm } }\n";
  // A translating roller on a small cam: above the 30 deg default.
  const mechgraph::RunResult r = run_yaml(
      cam + "  roll: { type: cam.contour, inputs: { cam: cam.law }, params: { follower: roller, roller_radius: 8 mm, load: 800 N, contact_length: 10 mm } }\n"
            "outputs: [roll.max_pressure_angle, roll.max_contact_stress]\n",
      project_registry());
  REQUIRE(scalar_output(r, "roll.max_pressure_angle") > 30.0 * std::numbers::pi / 180.0);
  const auto notes = notes_of(r, "roll");
  CHECK(any_note(notes, "pressure angle:"));
  CHECK(any_note(notes, "exceeds the default limit"));
  CHECK(any_note(notes, "constant load of 800 N assumed"));
  // The engineer's own limits: above the angle, no note; below the stress, a note.
  const double stress = scalar_output(r, "roll.max_contact_stress");
  char limits[200];
  std::snprintf(limits, sizeof limits, "pressure_angle_limit: 89 deg, contact_stress_limit: %.17g MPa", 0.5 * stress * 1e-6);
  const mechgraph::RunResult own = run_yaml(
      cam + "  roll: { type: cam.contour, inputs: { cam: cam.law }, params: { follower: roller, roller_radius: 8 mm, load: 800 N, "
            "contact_length: 10 mm, " + limits + " } }\noutputs: [roll.max_pressure_angle]\n",
      project_registry());
  CHECK_FALSE(any_note(notes_of(own, "roll"), "pressure angle:"));
  CHECK(any_note(notes_of(own, "roll"), "exceeds contact_stress_limit"));
}

TEST_CASE("contour: the default contact stress limit is the cited value for each follower type", "[cams][contour]") {
  // docs/methods/valvetrain.md, "Where the defaults come from": under a roller (rolling) 1648 MPa,
  // induction-hardened steel on steel at 1e8 cycles (Shigley, 9th ed., p. 329); under a flat face
  // (sliding) 1200 MPa, an assumption. The peak stress goes as sqrt(load): the load is set to put it
  // 0.1 % below and 0.1 % above the value, and the note must come only above, naming the value.
  using mechgraph::testing::project_registry;
  using mechgraph::testing::run_yaml;
  using mechgraph::testing::scalar_output;
  struct Case {
    const char* name;
    std::string followers;  // follower nodes, if any
    std::string contour;    // the contour node's inputs and params (before the load)
    double limit;
    const char* words;
  };
  const std::string cam = "  cam: { type: cam.harmonic, params: { max_lift: 8 mm, action_angle: 140 deg, base_radius: 30 mm } }\n";
  const Case cases[] = {
      {"translating flat", "", "inputs: { cam: cam.law }, params: { follower: flat", 1200e6, "the default for a flat face (sliding), 1200 MPa"},
      {"translating roller", "", "inputs: { cam: cam.law }, params: { follower: roller, roller_radius: 8 mm", 1648e6,
       "the default for a roller (rolling), 1648 MPa"},
      {"pivoted flat", "  finger: { type: follower.pivoted_flat, params: { pivot_x: -60 mm, pivot_y: 50 mm, face_offset: 2 mm } }\n",
       "inputs: { cam: cam.law, follower: finger.follower }, params: {", 1200e6, "the default for a flat face (sliding), 1200 MPa"},
      {"pivoted roller",
       "  rocker: { type: follower.pivoted_roller, params: { pivot_x: -45 mm, pivot_y: 40 mm, arm_length: 40 mm, roller_radius: 8 mm } }\n",
       "inputs: { cam: cam.law, follower: rocker.follower }, params: {", 1648e6, "the default for a roller (rolling), 1648 MPa"},
  };
  for (const Case& c : cases) {
    INFO(c.name);
    auto run = [&](double load_n) {
      char load[120];
      std::snprintf(load, sizeof load, " load: %.17g N, contact_length: 10 mm } }\n", load_n);
      const std::string separator = c.contour.back() == '{' ? "" : ",";
      return run_yaml("nodes:\n" + cam + c.followers + "  cut: { type: cam.contour, " + c.contour + separator + load +
                          "outputs: [cut.max_contact_stress]\n",
                      project_registry());
    };
    const double probe_load = 1000.0;
    const double probe_stress = scalar_output(run(probe_load), "cut.max_contact_stress");
    REQUIRE(probe_stress > 0.0);
    const double load_at_limit = probe_load * (c.limit / probe_stress) * (c.limit / probe_stress);
    const mechgraph::RunResult below = run(load_at_limit * 0.999 * 0.999);
    const mechgraph::RunResult above = run(load_at_limit * 1.001 * 1.001);
    CHECK_THAT(scalar_output(below, "cut.max_contact_stress"), Catch::Matchers::WithinRel(0.999 * c.limit, 1e-6));
    CHECK_FALSE(any_note(notes_of(below, "cut"), " MPa at cam angle "));  // the stress note, not the pressure angle's
    CHECK(any_note(notes_of(above, "cut"), c.words));
  }
}
