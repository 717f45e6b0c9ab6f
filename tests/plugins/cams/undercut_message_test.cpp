// An undercut pair (cam law with its follower, at cam.contour) is refused naming the follower and
// the smallest base radius that would work, computed: for a flat tappet the contour's radius of
// curvature is r0 + h + h'', so the limit is r0 - rho_min exactly (a second method); with ramps the
// stated radius is checked by building the cam just above and just below it. The cam node alone
// no longer refuses: whether a contour can be followed depends on the follower.
#include "cam_test_support.hpp"

#include <mechgraph/errors.hpp>

#include <catch2/catch.hpp>

#include <cstdio>
#include <numbers>
#include <regex>

using namespace mechgraph;
using namespace mechgraph::cams::testing;

namespace {
const double deg = std::numbers::pi / 180;

// The cam node's law cut by cam.contour for a flat tappet (throws NodeError when undercut).
void cut(const std::string& type, const std::map<std::string, ParamValue>& p) {
  const OutputSet cam = run_cam(type, p);
  InputSet in;
  in.add("cam", cam.all().at("law"));
  OutputSet out;
  mechgraph::testing::RecordingContext ctx;
  contour_type().evaluate(mechgraph::testing::defaults_of(contour_type().info(), {}), in, out, ctx);
}

// The radius the message names, in m.
double stated_radius(const std::string& type, const std::map<std::string, ParamValue>& p, double* rho_min = nullptr) {
  // The cam alone is made, its flat-tappet curvature negative.
  CHECK(run_cam(type, p).all().at("min_curvature_radius").as_scalar() < 0.0);
  try {
    cut(type, p);
  } catch (const NodeError& e) {
    CHECK(e.parameter() == "follower");
    CHECK_THAT(e.what(), Catch::Matchers::Contains("follower.flat (flat-faced tappet) cannot follow this law"));
    std::smatch m;
    const std::string text = e.what();
    REQUIRE(std::regex_search(text, m, std::regex("base_radius must be at least ([0-9.eE+-]+) mm")));
    if (rho_min) {
      std::smatch r;
      REQUIRE(std::regex_search(text, r, std::regex("radius of curvature is ([0-9.eE+-]+) mm")));
      *rho_min = std::stod(r[1]) * 1e-3;
    }
    return std::stod(m[1]) * 1e-3;
  }
  FAIL("the cam was not refused");
  return 0;
}
}  // namespace

TEST_CASE("undercut: the pair names the smallest base radius that works, flat tappet in closed form", "[cams][undercut]") {
  for (const char* type : {"cam.kurz", "cam.poly4567", "cam.cycloidal"}) {
    INFO(type);
    std::map<std::string, ParamValue> p{{"max_lift", ParamValue::of_number(8e-3)}, {"action_angle", ParamValue::of_number(110 * deg)},
                                        {"base_radius", ParamValue::of_number(10e-3)}};
    if (std::string(type) == "cam.kurz") p["accel_angle"] = ParamValue::of_number(18 * deg);
    double rho_min = 0;
    const double r = stated_radius(type, p, &rho_min);
    CHECK_THAT(r, Catch::Matchers::WithinAbs(10e-3 - rho_min, 2e-6));  // message digits and 1 um bisection
  }
}

TEST_CASE("undercut: the named radius is the limit, ramps included", "[cams][undercut]") {
  // The search rebuilds the law for each trial radius: checked by building it just above and below.
  std::map<std::string, ParamValue> p{{"max_lift", ParamValue::of_number(8e-3)}, {"action_angle", ParamValue::of_number(110 * deg)},
                                      {"accel_angle", ParamValue::of_number(15 * deg)}, {"base_radius", ParamValue::of_number(10e-3)},
                                      {"ramp", ParamValue::of_choice("cosine")}, {"ramp_height", ParamValue::of_number(0.2e-3)},
                                      {"ramp_length", ParamValue::of_number(20 * deg)}};
  const double r = stated_radius("cam.kurz", p);
  p["base_radius"] = ParamValue::of_number(r + 1e-5);
  CHECK_NOTHROW(cut("cam.kurz", p));
  p["base_radius"] = ParamValue::of_number(r - 1e-5);
  CHECK_THROWS_AS(cut("cam.kurz", p), NodeError);
}

TEST_CASE("undercut: the cam node alone says so in a note, with a base radius that works", "[cams][undercut]") {
  // No contour connected: the cam runs, but a note (printed by every host, kept with the results)
  // says its flat-face contour is undercut, by how much, and what base radius removes it; that
  // radius is then accepted by cam.contour (not refused by rounding: a stated 1 % margin).
  std::map<std::string, ParamValue> p{{"max_lift", ParamValue::of_number(8e-3)}, {"action_angle", ParamValue::of_number(110 * deg)},
                                      {"accel_angle", ParamValue::of_number(18 * deg)}, {"base_radius", ParamValue::of_number(3e-3)}};
  const OutputSet out = run_cam("cam.kurz", p);
  const double rho = out.all().at("min_curvature_radius").as_scalar();
  REQUIRE(rho < 0.0);
  std::string note;
  for (const std::string& n : out.notes())
    if (n.find("undercut") != std::string::npos) note = n;
  INFO(note);
  CHECK_THAT(note, Catch::Matchers::Contains("flat-faced follower") && Catch::Matchers::Contains("cam.contour"));
  std::smatch m;
  REQUIRE(std::regex_search(note, m, std::regex("a base_radius of ([0-9.eE+-]+) mm removes it")));
  const double suggested = std::stod(m[1]) * 1e-3;
  CHECK(suggested > 3e-3 - rho);  // the flat-face limit r0 - rho_min, and a margin above it
  p["base_radius"] = ParamValue::of_number(suggested);
  CHECK_NOTHROW(cut("cam.kurz", p));
  const OutputSet again = run_cam("cam.kurz", p);  // kept: notes() refers into it
  for (const std::string& n : again.notes()) CHECK(n.find("undercut") == std::string::npos);
}

TEST_CASE("undercut: the base radius cam.contour suggests is accepted", "[cams][undercut]") {
  std::map<std::string, ParamValue> p{{"max_lift", ParamValue::of_number(8e-3)}, {"action_angle", ParamValue::of_number(110 * deg)},
                                      {"base_radius", ParamValue::of_number(10e-3)}};
  try {
    cut("cam.poly4567", p);
    FAIL("the cam was not refused");
  } catch (const NodeError& e) {
    std::smatch m;
    const std::string text = e.what();
    REQUIRE(std::regex_search(text, m, std::regex("take e.g. ([0-9.eE+-]+) mm")));
    p["base_radius"] = ParamValue::of_number(std::stod(m[1]) * 1e-3);
    CHECK_NOTHROW(cut("cam.poly4567", p));
  }
}

TEST_CASE("undercut: where only a window of base radii works (pivoted flat face), the window is named", "[cams][undercut]") {
  // A finger with a flat pad works on a harmonic cam only between two base radii: below, the
  // contour undercuts; above, the pad cannot reach the larger cam. Both ends are checked by
  // building the cam 1 % inside and outside them.
  auto run_with = [](double r0_mm) {
    char scene[600];
    std::snprintf(scene, sizeof scene,
                  "nodes:\n  cam: { type: cam.harmonic, params: { max_lift: 8 mm, action_angle: 140 deg, base_radius: %.17g mm } }\n"
                  "  finger: { type: follower.pivoted_flat, params: { pivot_x: -60 mm, pivot_y: 50 mm, face_offset: 2 mm } }\n"
                  "  cut: { type: cam.contour, inputs: { cam: cam.law, follower: finger.follower } }\n"
                  "outputs: [cut.max_pressure_angle]\n",
                  r0_mm);
    return mechgraph::testing::run_yaml(scene, mechgraph::testing::project_registry());
  };
  std::string text;
  try {
    run_with(10.0);
    FAIL("the cam was not refused");
  } catch (const std::exception& e) {
    text = e.what();
  }
  std::smatch m;
  REQUIRE(std::regex_search(text, m, std::regex("only base radii from ([0-9.eE+-]+) mm to ([0-9.eE+-]+) mm work")));
  const double low = std::stod(m[1]), high = std::stod(m[2]);
  CHECK_NOTHROW(run_with(low * 1.01));
  CHECK_THROWS(run_with(low * 0.99));
  CHECK_NOTHROW(run_with(high * 0.99));
  CHECK_THROWS(run_with(high * 1.01));
}
