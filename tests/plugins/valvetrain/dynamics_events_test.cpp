// valvetrain.dynamics: the events table (every departure from the cam's law, every jump of the
// curves declared to jump), coil bind at the spring's solid length, the travel stop, and the
// bilateral drive's note. The lift limits' closed forms (impact, restitution, free flight) are in
// lift_limit_test.cpp; here the node's outputs are checked against each other and against bounds
// that follow from the model.
#include "dynamics_scenes.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

using namespace mechgraph;
using namespace mechgraph::testing;
using namespace mechgraph::testing::dynamics;
using Catch::Matchers::WithinAbs;
using Catch::Matchers::WithinRel;

namespace {

constexpr double pi = std::numbers::pi;

const std::vector<double>& channel(const Table& t, const std::string& name) {
  const Table::Column* c = t.find(name);
  if (!c) throw std::runtime_error("no channel " + name);
  return c->values;
}

long count_code(const Table& events, double code) {
  const auto& e = channel(events, "event");
  return std::count(e.begin(), e.end(), code);
}

bool has_note(const RunResult& r, const std::string& node, const std::string& part) {
  for (const std::string& n : node_run(r, node).notes)
    if (n.find(part) != std::string::npos) return true;
  return false;
}

std::string dyn_node(const std::string& valve, const std::string& effects, const std::string& params = "") {
  return "{ type: valvetrain.dynamics, inputs: { valve: " + valve + ".motion, design: sd.design }, effects: [ " + effects +
         " ], params: { drive_stiffness: 4000 N/mm, revolutions: 3" + params + " } }";
}

}  // namespace

TEST_CASE("dynamics events: the valve that floats at 7500 rpm, every loss and regain of the cam at its angle",
          "[valvetrain][dynamics][events]") {
  // Spring designed for 5600 rpm, run at 7500 rpm: the valve leaves the cam and lands on the seat.
  const RunResult r = run_scene(dynamics_scene(kurz, dyn_node("fast", "elastic_drive, contact_loss, seat_impact"),
                                               "dyn.events, dyn.curves, dyn.floats, dyn.bounces", "5600 rpm", "0.25 mm",
                                               fast_valve(7500)));
  const Table& events = output(r, "dyn.events").as_table();
  const Table& curves = output(r, "dyn.curves").as_table();
  REQUIRE(num(r, "dyn.floats") == 1.0);
  const long losses = count_code(events, 1.0), regains = count_code(events, 2.0);
  CHECK(losses >= 1);
  CHECK(regains <= losses);
  CHECK(count_code(events, 3.0) == static_cast<long>(num(r, "dyn.bounces")));
  const auto& angle = events.axis.values;
  const auto& code = channel(events, "event");
  const auto& speed = channel(events, "speed");
  const auto& cam_force = channel(events, "cam_force");
  REQUIRE(std::is_sorted(angle.begin(), angle.end()));
  for (std::size_t i = 0; i < angle.size(); ++i) {
    INFO("row " << i << ": event " << code[i] << " at " << angle[i] * 180 / pi << " deg");
    CHECK(angle[i] >= -pi);
    CHECK(angle[i] <= pi);
    CHECK(std::isfinite(speed[i]));
    CHECK(speed[i] >= 0.0);
    if (code[i] == 1.0) CHECK(cam_force[i] == 0.0);  // the cam no longer touches
    if (code[i] == 3.0) CHECK(speed[i] > 0.0);
  }
  // The first loss against the curves: the cam pushes at the grid point before it, and the curve's
  // contact force is 0 at the grid point after it when contact stays lost past it.
  const auto& phi = curves.axis.values;
  const auto& force = channel(curves, "contact_force");
  std::size_t first = 0;
  while (code[first] != 1.0) ++first;
  const std::size_t after = static_cast<std::size_t>(std::upper_bound(phi.begin(), phi.end(), angle[first]) - phi.begin());
  REQUIRE(after > 0);
  REQUIRE(after < phi.size());
  CHECK(force[after - 1] > 0.0);
  if (first + 1 < angle.size() && angle[first + 1] > phi[after]) CHECK(force[after] == 0.0);
  CHECK(has_note(r, "dyn", "the follower leaves the cam"));
}

TEST_CASE("dynamics events: a valve train that follows its cam lists only its lash take-up and seating",
          "[valvetrain][dynamics][events]") {
  // The ramped cam's float speed is about 3800 rpm (scenes/valvetrain_dynamics.yaml): at 3000 rpm
  // its valve stays on the cam. No departure from the law, but two jumps: the cam takes up the
  // lash (10: the unilateral drive's damper loads it at once) and the valve lands on its seat with
  // the cam in contact (9: the seat stops its speed; without seat_impact no bounce, the chain may
  // carry it on and it lands again).
  const std::string ramped =
      "{ type: cam.kurz, params: { max_lift: 8 mm, action_angle: 130 deg, accel_angle: 18 deg, base_radius: 17 mm, "
      "ramp: cosine, ramp_height: 0.2 mm, ramp_length: 20 deg } }";
  const RunResult r = run_scene(dynamics_scene(ramped, dyn_node("v", "elastic_drive, contact_loss"),
                                               "dyn.events, dyn.floats, dyn.solid_lift, dyn.max_deviation", "3000 rpm"));
  CHECK(num(r, "dyn.floats") == 0.0);
  const Table& events = output(r, "dyn.events").as_table();
  CHECK(events.channels.size() == 4);
  const auto& code = channel(events, "event");
  REQUIRE(code.size() >= 2);
  CHECK(code.front() == 10.0);
  CHECK(events.axis.values.front() < 0.0);  // on the opening flank
  CHECK(count_code(events, 9.0) == static_cast<long>(code.size()) - 1);
  CHECK(events.axis.values[1] > 0.0);  // the seatings on the closing flank
  for (double speed : channel(events, "speed")) CHECK(speed > 0.0);
  CHECK(num(r, "dyn.solid_lift") > 8e-3 * 1.5 - 0.25e-3);  // the spring design keeps it above full lift
  CHECK_FALSE(has_note(r, "dyn", "bilateral"));
}

TEST_CASE("dynamics: the bilateral drive's pull is named in a note", "[valvetrain][dynamics][events]") {
  const RunResult r = run_scene(dynamics_scene(kurz, dyn_node("v", "elastic_drive"), "dyn.min_contact_force, dyn.events"));
  REQUIRE(num(r, "dyn.min_contact_force") < 0.0);
  CHECK(has_note(r, "dyn", "bilateral drive"));
  CHECK(has_note(r, "dyn", "no real cam"));
  // Bilateral: nothing leaves the cam; the rows are its landings on the seat with the cam in contact.
  const Table& events = output(r, "dyn.events").as_table();
  REQUIRE(!events.axis.values.empty());
  CHECK(count_code(events, 9.0) == static_cast<long>(events.axis.values.size()));
}

TEST_CASE("dynamics: coil bind stops a spring sized for 4000 rpm run at 7500 rpm at its solid length",
          "[valvetrain][dynamics][events]") {
  // Without coil bind this valve flew about 32 mm off its law; the solid spring stops it.
  const RunResult r = run_scene(dynamics_scene(kurz, dyn_node("fast", "elastic_drive, contact_loss, seat_impact"),
                                               "dyn.events, dyn.curves, dyn.solid_lift, dyn.max_deviation, dyn.max_spring_force, "
                                               "sd.preload, sd.stiffness",
                                               "4000 rpm", "0.25 mm", fast_valve(7500)));
  const Table& events = output(r, "dyn.events").as_table();
  const Table& curves = output(r, "dyn.curves").as_table();
  const double solid = num(r, "dyn.solid_lift"), k_bind = 1e8;  // the default coil_bind_stiffness
  REQUIRE(count_code(events, 5.0) >= 1);
  CHECK(count_code(events, 6.0) == count_code(events, 5.0));  // each engagement is left again
  const auto& code = channel(events, "event");
  const auto& peak = channel(events, "peak_force");
  double greatest_peak = 0.0;
  for (std::size_t i = 0; i < code.size(); ++i) {
    if (code[i] == 5.0) CHECK(peak[i] > 0.0);
    if (code[i] != 5.0 && code[i] != 7.0) CHECK(peak[i] == 0.0);
    greatest_peak = std::max(greatest_peak, peak[i]);
  }
  // At the highest lift the valve stands still, so the contact's force there is k (x - a_s) alone,
  // at most its peak: x_max <= a_s + peak / k (micrometres above the solid length).
  const auto& lift = channel(curves, "lift");
  const double highest = *std::max_element(lift.begin(), lift.end());
  CHECK(highest > solid - 1e-3);
  CHECK(highest <= solid + greatest_peak / k_bind * (1.0 + 1e-9) + 1e-12);
  CHECK(num(r, "dyn.max_deviation") < solid);
  // The solid spring's force is part of the spring force: at the peak the valve is beyond a_s.
  CHECK(num(r, "dyn.max_spring_force") >= (num(r, "sd.preload") + num(r, "sd.stiffness") * solid + greatest_peak) * (1.0 - 1e-9));
  CHECK(has_note(r, "dyn", "coil bind"));
}

TEST_CASE("dynamics: a travel stop below full lift is hit on every opening and holds the valve at it",
          "[valvetrain][dynamics][events]") {
  // Full valve lift 1.5 x 8 mm - 0.25 mm = 11.75 mm; the stop at 10 mm.
  const double stop = 10e-3, k_stop = 5e7;
  const RunResult r = run_scene(dynamics_scene(
      kurz, dyn_node("v", "elastic_drive, contact_loss, travel_stop", ", stop_lift: 10 mm, stop_stiffness: 50000 N/mm"),
      "dyn.events, dyn.curves"));
  const Table& events = output(r, "dyn.events").as_table();
  REQUIRE(count_code(events, 7.0) >= 1);
  CHECK(count_code(events, 8.0) == count_code(events, 7.0));
  const auto& peak = channel(events, "peak_force");
  const double greatest_peak = *std::max_element(peak.begin(), peak.end());
  // The drive pushes the valve into the stop: the stop carries about k_d (y - stop) at the nose.
  CHECK(greatest_peak > 1000.0);
  const auto& lift = channel(output(r, "dyn.curves").as_table(), "lift");
  const double highest = *std::max_element(lift.begin(), lift.end());
  CHECK(highest > stop);
  CHECK(highest <= stop + greatest_peak / k_stop * (1.0 + 1e-9));
  CHECK(has_note(r, "dyn", "travel stop"));
}

TEST_CASE("dynamics: travel_stop without stop_lift names the parameter", "[valvetrain][dynamics][events]") {
  CHECK_THROWS_WITH(run_scene(dynamics_scene(kurz, dyn_node("v", "elastic_drive, travel_stop"), "dyn.events")),
                    Catch::Contains("stop_lift"));
}

TEST_CASE("dynamics: a bilateral drive that vibrates the valve into coil bind is run again with the solid spring",
          "[valvetrain][dynamics][events]") {
  // A soft drive (1000 N/mm), spring for 4000 rpm, 7500 rpm, the cam allowed to pull: the valve's
  // vibration overshoots the 0.5 mm coil clearance. The first run finds the greatest lift beyond
  // the solid length; the run reported has the coil-bind contact and stays at it.
  const std::string dyn = "{ type: valvetrain.dynamics, inputs: { valve: fast.motion, design: sd.design }, effects: [ "
                          "elastic_drive ], params: { drive_stiffness: 1000 N/mm } }";
  const RunResult r = run_scene(dynamics_scene(kurz, dyn, "dyn.events, dyn.curves, dyn.solid_lift", "4000 rpm", "0.25 mm",
                                               fast_valve(7500)));
  const Table& events = output(r, "dyn.events").as_table();
  REQUIRE(count_code(events, 5.0) >= 1);
  CHECK(count_code(events, 1.0) == 0);  // bilateral: the cam is never left
  const auto& peak = channel(events, "peak_force");
  const double greatest_peak = *std::max_element(peak.begin(), peak.end());
  const auto& lift = channel(output(r, "dyn.curves").as_table(), "lift");
  const double highest = *std::max_element(lift.begin(), lift.end());
  CHECK(highest <= num(r, "dyn.solid_lift") + greatest_peak / 1e8 * (1.0 + 1e-9));
  CHECK(has_note(r, "dyn", "coil bind"));
  CHECK(has_note(r, "dyn", "bilateral drive"));
}

TEST_CASE("dynamics hard cases: coil bind from the softest to the stiffest contact, restitution 1 and nearly 0",
          "[valvetrain][dynamics][events][stability]") {
  for (const std::string params : {", coil_bind_stiffness: 1e9 N/mm", ", coil_bind_stiffness: 10 N/mm",
                                   ", coil_bind_restitution: 1", ", coil_bind_restitution: 1e-12"}) {
    INFO(params);
    const RunResult r = run_scene(dynamics_scene(kurz, dyn_node("fast", "elastic_drive, contact_loss, seat_impact", params),
                                                 "dyn.events, dyn.curves, dyn.max_deviation, dyn.max_spring_force",
                                                 "5600 rpm", "0.25 mm", fast_valve(7500)));
    CHECK(count_code(output(r, "dyn.events").as_table(), 5.0) >= 1);
    CHECK(std::isfinite(num(r, "dyn.max_deviation")));
    CHECK(std::isfinite(num(r, "dyn.max_spring_force")));
    for (const auto& c : output(r, "dyn.curves").as_table().channels)
      for (double x : c.values) REQUIRE(std::isfinite(x));
  }
}

TEST_CASE("dynamics events: the cam force just after a regain is the drive's damper times the approach speed",
          "[valvetrain][dynamics][events]") {
  // Closed form: at a regain the gap y - x_0 is the located root, so just after it the cam force is
  // k_0 (y - x_0) + c_0 (y' - x_0') = c_0 v, v the speed of approach, the same c_0 for every regain
  // of one drive. On the wrong side of the root by a rounding the table read 0 (3 of 14 regains of
  // the example scene at 7500 and 5600 rpm).
  std::vector<double> ratio;  // cam_force / speed of every regain, both speeds
  for (double rpm : {5600.0, 7500.0}) {
    const RunResult r = run_scene(dynamics_scene(kurz, dyn_node("fast", "elastic_drive, contact_loss, seat_impact"),
                                                 "dyn.events", "5600 rpm", "0.25 mm", fast_valve(rpm)),
                                  {});
    const Table& events = output(r, "dyn.events").as_table();
    const auto& code = channel(events, "event");
    const auto& speed = channel(events, "speed");
    const auto& cam_force = channel(events, "cam_force");
    for (std::size_t i = 0; i < code.size(); ++i)
      if (code[i] == 2.0) {
        INFO(rpm << " rpm, regain at " << events.axis.values[i] * 180 / pi << " deg, speed " << speed[i] << " m/s");
        CHECK(cam_force[i] > 0.0);
        ratio.push_back(cam_force[i] / speed[i]);
      }
  }
  REQUIRE(ratio.size() >= 3);
  for (double c : ratio) CHECK_THAT(c, WithinRel(ratio.front(), 1e-6));
}

namespace {

// The curves' channels the node declares to jump at its events (jumps_at_events): the report draws
// them in pieces between the events table's rows, so every jump must have a row.
std::vector<std::string> channels_that_jump() {
  const RegisteredType* type = project_registry().find("valvetrain.dynamics");
  REQUIRE(type);
  std::vector<std::string> names;
  for (const ChannelDecl& c : type->type->info().find_output("curves")->presentation.channels)
    if (c.flags & channel_flag::jumps_at_events) names.push_back(c.name);
  return names;
}

// The steps of a curve between neighbouring points that stand out of both neighbouring steps (a
// jump between two points, not a steep but smooth stretch) with no events row between the two
// points: phi_{i-1} < event <= phi_i, the interval the report breaks the curve at. On a fine grid a
// smooth curve's neighbouring steps are nearly alike; a jump is many times either.
std::vector<double> jumps_without_row(const std::vector<double>& phi, const std::vector<double>& y, const std::vector<double>& events) {
  double scale = 0.0;
  for (double v : y) scale = std::max(scale, std::abs(v));
  const auto row_between = [&](std::size_t i) {
    const auto next = std::upper_bound(events.begin(), events.end(), phi[i - 1]);
    return next != events.end() && *next <= phi[i];
  };
  std::vector<double> at;
  for (std::size_t i = 2; i + 1 < phi.size(); ++i) {
    const double step = std::abs(y[i] - y[i - 1]);
    const double beside = std::max(std::abs(y[i - 1] - y[i - 2]), std::abs(y[i + 1] - y[i]));
    if (step > 1e-3 * scale && step > 8.0 * beside && !row_between(i)) at.push_back(phi[i] * 180.0 / pi);
  }
  return at;
}

}  // namespace

TEST_CASE("dynamics events: every jump of a curve declared to jump has a row, the rigid drive's too",
          "[valvetrain][dynamics][events][jumps]") {
  // The rigid drive lifts the valve at the drive's speed where it takes up the lash and sets it
  // down at that speed; the bilateral drive's valve seats with the cam in contact. Before these had
  // rows (the rigid drive had no events table) the report drew their jumps as steep lines.
  const std::vector<std::string> jumping = channels_that_jump();
  REQUIRE(jumping.size() >= 2);  // velocity and the cam's force
  const std::string ramped =
      "{ type: cam.kurz, params: { max_lift: 8 mm, action_angle: 130 deg, accel_angle: 18 deg, base_radius: 17 mm, "
      "ramp: cosine, ramp_height: 0.2 mm, ramp_length: 20 deg } }";
  struct Case {
    const char* name;
    std::string cam, effects, rpm;
  };
  for (const Case& c : {Case{"rigid", kurz, "", "5600 rpm"}, Case{"rigid, ramped", ramped, "", "5600 rpm"},
                        Case{"bilateral", kurz, "elastic_drive", "5600 rpm"},
                        Case{"bilateral, ramped", ramped, "elastic_drive", "5600 rpm"},
                        Case{"contacts, on the cam", ramped, "elastic_drive, contact_loss", "3000 rpm"},
                        Case{"contacts and seat", kurz, "elastic_drive, contact_loss, seat_impact", "5600 rpm"},
                        Case{"multi mass", kurz, "elastic_drive, multi_mass", "5600 rpm"},
                        Case{"multi mass, contacts and seat", kurz, "elastic_drive, multi_mass, contact_loss, seat_impact", "5600 rpm"},
                        Case{"coil masses, contacts", kurz, "elastic_drive, spring_surge, contact_loss", "5600 rpm"},
                        Case{"travel stop", kurz, "elastic_drive, contact_loss, travel_stop", "5600 rpm"}}) {
    INFO(c.name);
    const std::string params = c.effects.empty() ? "curve_points: 14401"
                               : std::string(c.effects.find("multi_mass") != std::string::npos
                                                 ? "stiffnesses: [ 20000 N/mm, 20000 N/mm, 20000 N/mm, 20000 N/mm ], "
                                                 : "drive_stiffness: 4000 N/mm, ") +
                                     (c.effects.find("travel_stop") != std::string::npos ? "stop_lift: 10 mm, " : "") +
                                     "revolutions: 3, curve_points: 14401";
    const std::string dyn = "{ type: valvetrain.dynamics, inputs: { valve: v.motion, design: sd.design }, effects: [ " + c.effects +
                            " ], params: { " + params + " } }";
    const RunResult r = run_scene(dynamics_scene(c.cam, dyn, "dyn.events, dyn.curves, dyn.seating_velocity", c.rpm));
    const Table& events = output(r, "dyn.events").as_table();
    const Table& curves = output(r, "dyn.curves").as_table();
    REQUIRE(std::is_sorted(events.axis.values.begin(), events.axis.values.end()));
    // Every run opens and seats its valve: the seating is a row (9 with the cam in contact).
    CHECK(count_code(events, 9.0) + count_code(events, 4.0) >= 1);
    if (c.effects.empty()) {
      // Rigid: lifted by the cam (10), then seated (9), the speeds the drive's.
      REQUIRE(events.axis.values.size() == 2);
      CHECK(channel(events, "event") == std::vector<double>{10.0, 9.0});
      for (double speed : channel(events, "speed")) CHECK(speed > 0.0);
      CHECK_THAT(channel(events, "speed")[1], WithinRel(num(r, "dyn.seating_velocity"), 1e-6));
    }
    for (const std::string& name : jumping) {
      INFO(name);
      CHECK(jumps_without_row(curves.axis.values, channel(curves, name), events.axis.values) == std::vector<double>{});
    }
  }
}
