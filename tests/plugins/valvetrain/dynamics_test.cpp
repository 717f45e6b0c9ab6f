// valvetrain.dynamics and the single-mass model under it: a closed form for the drive, agreement
// of the two integrators, the effects switched on and off, and the hard cases (a very stiff drive,
// a long dwell, a valve that floats every cycle, a chattering landing) ending with finite results
// and bounded work.
#include "chain_model.hpp"
#include "valve_simulation.hpp"
#include "dynamics_scenes.hpp"

#include <mechgraph/domain/valve_motion.hpp>
#include <mechgraph/errors.hpp>

#include <yaml-cpp/yaml.h>

#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

using namespace mechgraph;
using namespace mechgraph::testing;
using namespace mechgraph::testing::dynamics;
using namespace mechgraph::valvetrain;
using Catch::Matchers::Contains;
using Catch::Matchers::WithinAbs;
using Catch::Matchers::WithinRel;

namespace {

constexpr double pi = std::numbers::pi;

// Residual vibration after a cycloidal rise of duration T on an undamped mass of natural period
// Tn, r = T / Tn: A / h = |sin(pi r)| / (pi r |1 - r^2|).
double residual_closed_form(double r) { return std::abs(std::sin(pi * r)) / (pi * r * std::abs(1 - r * r)); }

double simulated_residual(double r, const std::string& integrator) {
  const double h = 0.01, T = 0.02, omega = 2 * pi * r / T;  // Tn = T / r
  ChainParams p;
  p.mass = {0.2};
  p.link_stiffness = {0.2 * omega * omega};
  p.link_damping = {0.0};
  p.seat = false;  // the drive alone
  const ChainModel model(p, [&](double t) {
    if (t >= T) return DriveValue{h, 0.0, 0.0};
    return DriveValue{h * (t / T - std::sin(2 * pi * t / T) / (2 * pi)), h / T * (1 - std::cos(2 * pi * t / T)),
                      2 * pi * h / (T * T) * std::sin(2 * pi * t / T)};
  });
  SimulationOptions o;
  o.integrator = integrator;
  o.rtol = 1e-11;
  o.atol_x = 1e-11 * h;
  o.atol_v = 1e-11 * h / T;
  // After the rise the motion is free: its amplitude about h is read from the state at T.
  const SimulationResult run = simulate(model, 0.0, 2 * T, {T}, {T}, o);
  const auto s = run.state.at(0);
  return std::hypot(s[0] - h, s[1] / omega) / h;
}

}  // namespace

TEST_CASE("dynamics: residual vibration after a cycloidal rise matches the closed form, both integrators", "[valvetrain][dynamics]") {
  for (const char* integrator : {"cvode", "dopri5"})
    for (double r : {0.5, 0.8, 1.5, 2.5, 3.7}) {
      INFO(integrator << ", r = T/Tn = " << r);
      CHECK_THAT(simulated_residual(r, integrator), WithinAbs(residual_closed_form(r), 1e-6 * residual_closed_form(r) + 1e-9));
    }
  // At whole r the residual vanishes (the rise takes whole periods).
  CHECK_THAT(simulated_residual(2.0, "cvode"), WithinAbs(0.0, 1e-7));
}

TEST_CASE("dynamics: the two integrators agree on the elastic valve train", "[valvetrain][dynamics]") {
  const std::string dyn =
      "{ type: valvetrain.dynamics, inputs: { valve: v.motion, design: sd.design }, effects: [ elastic_drive ], "
      "params: { drive_stiffness: 4000 N/mm, tolerance: 1e-10 } }";
  const std::string scene = dynamics_scene(kurz, dyn, "dyn.curves, dyn.max_deviation");
  const RunResult a = run_scene(scene, {parse_override("dyn.integrator=cvode")});
  const RunResult b = run_scene(scene, {parse_override("dyn.integrator=dopri5")});
  const Table& ta = output(a, "dyn.curves").as_table();
  const Table& tb = output(b, "dyn.curves").as_table();
  double worst = 0;
  for (std::size_t i = 0; i < ta.axis.values.size(); ++i)
    worst = std::max(worst, std::abs(ta.find("lift")->values[i] - tb.find("lift")->values[i]));
  CHECK(worst < 1e-8);  // 11.75 mm of lift: 1e-6 relative
  CHECK_THAT(num(a, "dyn.max_deviation"), WithinRel(num(b, "dyn.max_deviation"), 1e-5));
  // Work is reported by both.
  CHECK(node_run(a, "dyn").work.at("steps") > 0);
  CHECK(node_run(a, "dyn").work.at("jacobian_evaluations") > 0);
  CHECK(node_run(b, "dyn").work.at("rhs_evaluations") > node_run(b, "dyn").work.at("steps"));
}

TEST_CASE("dynamics: the two integrators agree on a valve that floats and bounces", "[valvetrain][dynamics]") {
  // Spring designed for 5600 rpm, valve at 7500 rpm: contact lost before the nose, a landing at
  // ~13 m/s and a series of bounces, the last ones hops far shorter than an integration step (a
  // hop that starts and ends inside one explicit step was once missed: the valve fell through).
  const std::string fast = fast_valve(7500);
  const std::string dyn =
      "{ type: valvetrain.dynamics, inputs: { valve: fast.motion, design: sd.design }, "
      "effects: [ elastic_drive, contact_loss, seat_impact ], params: { drive_stiffness: 4000 N/mm, tolerance: 1e-10 } }";
  const std::string scene = dynamics_scene(kurz, dyn, "dyn.curves, dyn.max_deviation, dyn.seating_velocity, dyn.bounces, dyn.floats",
                                           "5600 rpm", "0.25 mm", fast);
  const RunResult a = run_scene(scene, {parse_override("dyn.integrator=cvode")});
  const RunResult b = run_scene(scene, {parse_override("dyn.integrator=dopri5")});
  CHECK(num(a, "dyn.floats") == 1);
  CHECK(num(a, "dyn.bounces") == num(b, "dyn.bounces"));
  CHECK(num(a, "dyn.bounces") >= 3);
  CHECK_THAT(num(a, "dyn.seating_velocity"), WithinRel(num(b, "dyn.seating_velocity"), 1e-6));
  CHECK_THAT(num(a, "dyn.max_deviation"), WithinRel(num(b, "dyn.max_deviation"), 1e-6));
  const Table& ta = output(a, "dyn.curves").as_table();
  const Table& tb = output(b, "dyn.curves").as_table();
  for (std::size_t i = 0; i < ta.axis.values.size(); ++i) {
    REQUIRE(ta.find("lift")->values[i] >= 0.0);  // never through the seat
    REQUIRE_THAT(ta.find("lift")->values[i], WithinAbs(tb.find("lift")->values[i], 1e-7));
  }
}

TEST_CASE("dynamics: effects off are not computed, and their outputs cannot be asked for", "[valvetrain][dynamics]") {
  const std::string rigid = "{ type: valvetrain.dynamics, inputs: { valve: v.motion, design: sd.design } }";
  const RunResult r = run_scene(dynamics_scene(kurz, rigid, "dyn.curves, dyn.min_contact_force, v.min_acceleration, sd.reduced_mass, sd.preload, sd.stiffness"));
  CHECK(node_run(r, "dyn").work.at("steps") == 0);
  // Rigid: the lift is the kinematic lift, the cam force M a + P0 + c_s x.
  const Table& t = output(r, "dyn.curves").as_table();
  for (std::size_t i = 0; i < t.axis.values.size(); ++i)
    REQUIRE(t.find("lift")->values[i] == t.find("kinematic_lift")->values[i]);
  // With K = 1.5 the spring outweighs the inertia force everywhere: the cam always pushes, less than P0 at the nose.
  CHECK(num(r, "dyn.min_contact_force") > 0);
  CHECK(num(r, "dyn.min_contact_force") < num(r, "sd.preload"));
  // Asking for an output of an effect that is off fails when the scene loads, naming the effect.
  try {
    graph_from(dynamics_scene(kurz, rigid, "dyn.max_deviation"), project_registry());
    FAIL("no error");
  } catch (const SceneError& e) {
    CHECK_THAT(e.what(), Contains("scene.yaml:") && Contains("needs effect 'elastic_drive'") && Contains("effects: [elastic_drive]"));
  }
  // A scene-level effect switches it on for every node that has it; a node's own for that node.
  const std::string scene_level = dynamics_scene(kurz, rigid, "dyn.max_deviation") + "effects: [ elastic_drive ]\n";
  CHECK_THROWS_WITH(run_scene(scene_level), Contains("drive_stiffness"));  // now on, and it needs its stiffness
  // An effect the node type does not implement: named with the valid ones.
  try {
    graph_from(dynamics_scene(kurz, "{ type: valvetrain.dynamics, inputs: { valve: v.motion, design: sd.design }, effects: [ elastic_drvie ] }",
                              "dyn.curves"),
               project_registry());
    FAIL("no error");
  } catch (const SceneError& e) {
    CHECK_THAT(e.what(), Contains("elastic_drvie") && Contains("elastic_drive") && Contains("contact_loss"));
  }
  // contact_loss without elastic_drive is refused.
  CHECK_THROWS_WITH(run_scene(dynamics_scene(kurz, "{ type: valvetrain.dynamics, inputs: { valve: v.motion, design: sd.design }, effects: [ contact_loss ] }",
                                             "dyn.floats")),
                    Contains("needs the elastic_drive effect"));
}

TEST_CASE("dynamics hard cases: finite results and bounded work", "[valvetrain][dynamics][stability]") {
  auto dyn = [](const std::string& effects, const std::string& params) {
    return "{ type: valvetrain.dynamics, inputs: { valve: v.motion, design: sd.design }, effects: [ " + effects +
           " ], params: { " + params + " } }";
  };
  auto finite_curves = [](const RunResult& r) {
    for (const auto& c : output(r, "dyn.curves").as_table().channels)
      for (double v : c.values) REQUIRE(std::isfinite(v));
  };
  for (const char* integrator : {"cvode", "dopri5"}) {
    INFO(integrator);
    const std::string chosen = std::string(", integrator: ") + integrator;
    SECTION("a drive 1e10 times its mass: the valve follows its quasi-static lift") {
      // k_d / M_red = 1e10 on a shockless law without lash: the deviation is of order M a / k_d.
      const std::string cam = "{ type: cam.poly4567, params: { max_lift: 8 mm, action_angle: 130 deg, base_radius: 45 mm } }";
      const RunResult r = run_scene(dynamics_scene(cam, dyn("elastic_drive", "drive_stiffness: 1.8e6 N/mm" + chosen),
                                                   "dyn.curves, dyn.max_deviation, sd.reduced_mass", "3000 rpm", "0 mm"));
      finite_curves(r);
      CHECK_THAT(1.8e9 / num(r, "sd.reduced_mass"), WithinRel(1e10, 0.1));
      CHECK(num(r, "dyn.max_deviation") < 1e-6);
      CHECK(node_run(r, "dyn").work.at("steps") < 20000);
    }
    SECTION("a dwell of 300 deg") {
      const std::string cam = "{ type: cam.cycloidal, params: { max_lift: 4 mm, action_angle: 60 deg, base_radius: 120 mm } }";
      const RunResult r = run_scene(dynamics_scene(cam, dyn("elastic_drive", "drive_stiffness: 4000 N/mm" + chosen),
                                                   "dyn.curves, dyn.max_deviation", "3000 rpm"));
      finite_curves(r);
      CHECK(std::isfinite(num(r, "dyn.max_deviation")));
      CHECK(node_run(r, "dyn").work.at("steps") < 20000);
    }
    SECTION("a valve that floats every cycle") {
      // The spring is designed for 5600 rpm; the valve runs at 7500 rpm.
      std::string d = dyn("elastic_drive, contact_loss, seat_impact", "drive_stiffness: 4000 N/mm, revolutions: 4" + chosen);
      d.replace(d.find("v.motion"), 8, "fast.motion");
      const std::string fast = fast_valve(7500);
      const RunResult r = run_scene(dynamics_scene(kurz, d, "dyn.curves, dyn.floats, dyn.seating_velocity, dyn.min_contact_force, dyn.bounces",
                                                   "5600 rpm", "0.25 mm", fast));
      finite_curves(r);
      CHECK(num(r, "dyn.floats") == 1);
      CHECK(num(r, "dyn.min_contact_force") >= 0);  // unilateral: the cam never pulls
      CHECK(std::isfinite(num(r, "dyn.seating_velocity")));
      CHECK(node_run(r, "dyn").work.at("events") < 1000);
    }
    SECTION("a chattering landing ends") {
      // Restitution 0.95 and a seating speed of 1 um/s: a long series of ever smaller bounces,
      // cut by the bounce limit per landing.
      const RunResult r = run_scene(dynamics_scene(kurz, dyn("elastic_drive, contact_loss, seat_impact",
                                                             "drive_stiffness: 4000 N/mm, restitution: 0.95, seating_speed: 1e-6 m/s" + chosen),
                                                   "dyn.curves, dyn.bounces, dyn.bounce_height"));
      finite_curves(r);
      CHECK(num(r, "dyn.bounces") >= 1);
      CHECK(node_run(r, "dyn").work.at("events") < 2000);
    }
  }
}

TEST_CASE("float_speed: the bracket it returns holds below and floats above, checked by the dynamics node", "[valvetrain][dynamics]") {
  const std::string ramped =
      "{ type: cam.kurz, params: { max_lift: 8 mm, action_angle: 130 deg, accel_angle: 18 deg, base_radius: 17 mm, "
      "ramp: cosine, ramp_height: 0.2 mm, ramp_length: 20 deg } }";
  const std::string fs =
      "{ type: valvetrain.float_speed, inputs: { valve: v.motion, design: sd.design }, "
      "params: { rpm_min: 2000 rpm, rpm_max: 9000 rpm, drive_stiffness: 4000 N/mm, speed_tolerance: 0.5 rpm } }";
  const RunResult r = run_scene(dynamics_scene(ramped, fs, "dyn.float_speed, dyn.held_speed, dyn.simulations"));
  const double rpm = 2 * pi / 60;
  const double floats_at = num(r, "dyn.float_speed"), held_at = num(r, "dyn.held_speed");
  CHECK(floats_at > held_at);
  CHECK(floats_at - held_at <= 0.5 * rpm);
  CHECK(num(r, "dyn.simulations") < 40);
  // Second method: the dynamics node itself, with unilateral contact, at both ends of the bracket.
  auto floats = [&](double speed) {
    const std::string fast = fast_valve(speed / rpm);
    const std::string dyn =
        "{ type: valvetrain.dynamics, inputs: { valve: fast.motion, design: sd.design }, effects: [ elastic_drive, contact_loss ], "
        "params: { drive_stiffness: 4000 N/mm, revolutions: 3 } }";
    return num(run_scene(dynamics_scene(ramped, dyn, "dyn.floats", "5600 rpm", "0.25 mm", fast)), "dyn.floats");
  };
  // (at the bracket's ends themselves the decision rests on a contact force of ~0 N: 0.5 % away it is clear)
  CHECK(floats(held_at * 0.995) == 0);
  CHECK(floats(floats_at * 1.005) == 1);
  // A range without float says so, naming rpm_max.
  std::string none = fs;
  none.replace(none.find("rpm_max: 9000 rpm"), 17, "rpm_max: 2500 rpm");
  CHECK_THROWS_WITH(run_scene(dynamics_scene(ramped, none, "dyn.float_speed")),
                    Contains("parameter 'rpm_max'") && Contains("does not float between"));
}

TEST_CASE("polydyne_cam: the synthesised cam delivers the valve law exactly at its design speed, not off it", "[valvetrain][dynamics][polydyne]") {
  // The valve is to follow 1.5 x the polydyne; the cam is synthesised for the undamped single mass
  // (4000 N/mm, 5600 rpm) and the dynamics run it with the drive undamped, lash 0.25 mm taken up by
  // the synthesised ramps. Off the design speed the same cam lets the drive vibrate.
  auto scene = [](const std::string& rpm) {
    return std::string(R"(
nodes:
  poly:  { type: cam.polydyne, params: { max_lift: 8 mm, action_angle: 130 deg, base_radius: 17 mm, exponents: [2, 14, 26, 38, 50] } }
  v_law: { type: valvetrain.valve_motion, inputs: { cam: poly.law }, params: { rpm: 5600 rpm, rocker_ratio: 1.5, lash: 0 mm } }
  train: { type: valvetrain.masses, params: { valve_mass: 55 g, retainer_mass: 18 g, tappet_mass: 60 g, pushrod_mass: 50 g,
                                              rocker_inertia: 4e-5 kg*m^2, arm_valve: 45 mm, arm_pushrod: 30 mm } }
  spring: { type: spring.helical, params: { allowable_stress: 800 MPa } }
  sd:    { type: valvetrain.spring_design, inputs: { valve: v_law.motion, spring: spring.model, masses: train.masses } }
  synth: { type: valvetrain.polydyne_cam, inputs: { law: poly.law, design: sd.design },
           params: { design_rpm: 5600 rpm, drive_stiffness: 4000 N/mm, rocker_ratio: 1.5, lash: 0.25 mm } }
  v_cam: { type: valvetrain.valve_motion, inputs: { cam: synth.law }, params: { rpm: )") + rpm + R"(, rocker_ratio: 1.5, lash: 0.25 mm } }
  dyn:   { type: valvetrain.dynamics, inputs: { valve: v_cam.motion, design: sd.design }, effects: [ elastic_drive ],
           params: { drive_stiffness: 4000 N/mm, damping_ratio: 0, tolerance: 1e-11 } }
outputs: [ dyn.curves, v_law.motion, synth.take_up, sd.preload ]
)";
  };
  auto deviation_from_law = [](const RunResult& r) {
    const Table& t = output(r, "dyn.curves").as_table();
    const auto law = std::dynamic_pointer_cast<const ValveMotion>(output(r, "v_law.motion").as_handle());
    double worst = 0;
    for (std::size_t i = 0; i < t.axis.values.size(); ++i)
      worst = std::max(worst, std::abs(t.find("lift")->values[i] - law->at(t.axis.values[i]).lift));
    return worst;
  };
  const RunResult design = run_scene(scene("5600 rpm"));
  // Ramps take up the lash and preload the drive: (P0 / k_d + lash) / i.
  CHECK_THAT(num(design, "synth.take_up"), WithinRel((num(design, "sd.preload") / 4e6 + 0.25e-3) / 1.5, 1e-14));
  const double exact = deviation_from_law(design);
  CHECK(exact < 1e-9);  // 12 mm of lift followed to better than 1e-7
  const double slow = deviation_from_law(run_scene(scene("4500 rpm")));
  const double fast = deviation_from_law(run_scene(scene("6500 rpm")));
  CHECK(slow > 1e-5);
  CHECK(fast > 1e-5);
}

TEST_CASE("chain natural frequencies: one mass, two masses and a coil chain in closed form", "[valvetrain][dynamics][chain]") {
  ChainParams one;
  one.mass = {0.2};
  one.link_stiffness = {4e6};
  one.spring_rate = 3e4;
  CHECK_THAT(natural_frequencies(one).at(0), WithinRel(std::sqrt(4.03e6 / 0.2), 1e-14));
  // Two masses: cam -k1- m1 -k2- m2 -c_s- ground; omega^2 are the roots of
  // m1 m2 w^4 - (m1 (k2 + c_s) + m2 (k1 + k2)) w^2 + (k1 + k2)(k2 + c_s) - k2^2 = 0.
  ChainParams two;
  two.mass = {0.015, 0.05};
  two.link_stiffness = {5e7, 8e6};
  two.spring_rate = 4e4;
  const double m1 = 0.015, m2 = 0.05, k1 = 5e7, k2 = 8e6, cs = 4e4;
  const double a = m1 * m2, b = -(m1 * (k2 + cs) + m2 * (k1 + k2)), c = (k1 + k2) * (k2 + cs) - k2 * k2;
  const double disc = std::sqrt(b * b - 4 * a * c);
  const auto w = natural_frequencies(two);
  REQUIRE(w.size() == 2);
  CHECK_THAT(w[0], WithinRel(std::sqrt(2 * c / (-b + disc)), 1e-12));  // the small root without cancellation
  CHECK_THAT(w[1], WithinRel(std::sqrt((-b + disc) / (2 * a)), 1e-12));
  // p coil masses between an (almost) immovable valve and the head: a fixed-fixed chain, whose
  // modes are w_r = 2 sqrt(k_e / m_e) sin(r pi / (2 (p + 1))), k_e = (p + 1) c_s.
  for (int p : {1, 4, 16}) {
    INFO(p << " coils");
    ChainParams chain;
    chain.mass = {1e9};
    chain.link_stiffness = {1.0};
    chain.spring_rate = 3e4;
    chain.coils = p;
    chain.coil_mass = 0.03 / p;
    const auto modes = natural_frequencies(chain);
    const double k_e = (p + 1) * 3e4, m_e = 0.03 / p;
    for (int r = 1; r <= p; ++r)
      CHECK_THAT(modes.at(static_cast<std::size_t>(r)), WithinRel(2 * std::sqrt(k_e / m_e) * std::sin(r * pi / (2 * (p + 1))), 1e-9));
  }
  // ... whose first tends to the continuous spring's surge frequency pi sqrt(c_s / m_s) rad/s, as 1 - 1/(2(p+1)).
  for (int p : {50, 200}) {
    ChainParams fine;
    fine.mass = {1e9};
    fine.link_stiffness = {1.0};
    fine.spring_rate = 3e4;
    fine.coils = p;
    fine.coil_mass = 0.03 / p;
    CHECK_THAT(natural_frequencies(fine).at(1), WithinRel(pi * std::sqrt(3e4 / 0.03) * (1 - 0.5 / (p + 1)), 2.0 / (p * p)));
  }
}

TEST_CASE("multi_mass with stiff inner links moves as the single mass, spring_surge shakes the spring force", "[valvetrain][dynamics][chain]") {
  // Cam-tappet at the single mass's drive stiffness, the other three links 1e6 times stiffer:
  // the chain moves as one body of M_red, as the single-mass model does (the same damping of the
  // first mode; the stiff links' own modes are damped out at once).
  const std::string train_masses = "train:  { type: valvetrain.masses";
  auto scene_with = [&](const std::string& effects, const std::string& params) {
    const std::string dyn = "{ type: valvetrain.dynamics, inputs: { valve: v.motion, design: sd.design }, effects: [ elastic_drive" +
                            effects + " ], params: { tolerance: 1e-10, " + params + " } }";
    return dynamics_scene(kurz, dyn, "dyn.curves, dyn.natural_frequencies, dyn.max_spring_force, sd.max_force, sd.surge_frequency");
  };
  const RunResult single = run_scene(scene_with("", "drive_stiffness: 4000 N/mm"));
  const RunResult multi = run_scene(scene_with(", multi_mass", "stiffnesses: [4000 N/mm, 4e9 N/mm, 4e9 N/mm, 4e9 N/mm]"));
  const Table& a = output(single, "dyn.curves").as_table();
  const Table& b = output(multi, "dyn.curves").as_table();
  REQUIRE(b.find("tappet_lift") != nullptr);
  double worst = 0;
  for (std::size_t i = 0; i < a.axis.values.size(); ++i)
    worst = std::max(worst, std::abs(a.find("lift")->values[i] - b.find("lift")->values[i]));
  CHECK(worst < 1e-6);  // of 12 mm
  CHECK_THAT(output(multi, "dyn.natural_frequencies").as_series().values.at(0),
             WithinRel(output(single, "dyn.natural_frequencies").as_series().values.at(0), 1e-5));
  CHECK(output(multi, "dyn.natural_frequencies").as_series().values.size() == 4);
  // Spring surge: the spring's force on the valve swings past its static line at full lift.
  const RunResult surge = run_scene(scene_with(", spring_surge", "drive_stiffness: 4000 N/mm, coils: 12"));
  for (const auto& ch : output(surge, "dyn.curves").as_table().channels)
    for (double v : ch.values) REQUIRE(std::isfinite(v));
  CHECK(num(surge, "dyn.max_spring_force") > num(surge, "sd.max_force"));
  // One of the coupled modes sits near the spring's surge frequency (exactly there with the valve held).
  const auto& f = output(surge, "dyn.natural_frequencies").as_series().values;
  REQUIRE(f.size() == 13);
  bool near_surge = false;
  for (double x : f) near_surge = near_surge || std::abs(x / num(surge, "sd.surge_frequency") - 1) < 0.05;
  CHECK(near_surge);
  // Missing pieces are named.
  CHECK_THROWS_WITH(run_scene(scene_with(", multi_mass", "drive_stiffness: 4000 N/mm")), Contains("stiffnesses"));
}

TEST_CASE("dynamics regressions found in review", "[valvetrain][dynamics]") {
  auto dyn = [](const std::string& effects, const std::string& params) {
    return "{ type: valvetrain.dynamics, inputs: { valve: v.motion, design: sd.design }, effects: [ " + effects +
           " ], params: { drive_stiffness: 4000 N/mm, " + params + " } }";
  };
  SECTION("the last curve point (cam angle pi) is the end of the run, whatever rpm and revolutions") {
    // 3000 rpm with 6, 15 or 18 revolutions put it one rounding past the end: a read past the states.
    for (int revolutions : {6, 15, 18}) {
      INFO(revolutions << " revolutions");
      const RunResult r = run_scene(dynamics_scene(kurz, dyn("elastic_drive", "revolutions: " + std::to_string(revolutions)),
                                                   "dyn.curves", "3000 rpm"));
      CHECK(output(r, "dyn.curves").as_table().find("lift")->values.size() == 1441);
    }
  }
  SECTION("a restitution of 0 seats the valve instead of letting it sink through the seat") {
    const std::string fast = fast_valve(7500);
    std::string d = dyn("elastic_drive, contact_loss, seat_impact", "restitution: 0");
    d.replace(d.find("v.motion"), 8, "fast.motion");
    const RunResult r = run_scene(dynamics_scene(kurz, d, "dyn.curves, dyn.bounces", "5600 rpm", "0.25 mm", fast));
    for (double x : output(r, "dyn.curves").as_table().find("lift")->values) REQUIRE(x >= 0.0);
    CHECK(num(r, "dyn.bounces") == 0);
  }
  SECTION("a unilateral cam pushes only while it touches, whatever the damping") {
    // damping_ratio 2 once pushed the valve across the open lash through the damper.
    const RunResult r = run_scene(dynamics_scene(kurz, dyn("elastic_drive, contact_loss", "damping_ratio: 2"), "dyn.curves", "3000 rpm"));
    const Table& t = output(r, "dyn.curves").as_table();
    for (std::size_t i = 0; i < t.axis.values.size(); ++i) {
      const double force = t.find("contact_force")->values[i];
      REQUIRE(force >= 0.0);
      if (force > 0.0) REQUIRE(t.find("drive_displacement")->values[i] > t.find("lift")->values[i] - 1e-12);
    }
  }
  SECTION("float_speed's bisection ends at the finest speed tolerance") {
    const std::string fs =
        "{ type: valvetrain.float_speed, inputs: { valve: v.motion, design: sd.design }, "
        "params: { rpm_min: 2000 rpm, rpm_max: 9000 rpm, drive_stiffness: 4000 N/mm, speed_tolerance: 1e-6 rpm } }";
    const RunResult r = run_scene(dynamics_scene(kurz, fs, "dyn.float_speed, dyn.simulations"));
    CHECK(num(r, "dyn.simulations") < 80);
  }
}

TEST_CASE("drive damping: the first mode at damping_ratio, for one mass and for four", "[valvetrain][dynamics][chain]") {
  // A sized spring and masses as the study's. The design is valvetrain's private object: read as
  // C++ only where C++ objects cross as they are, on the pre-1.0 entry.
  const RunResult r = run_yaml(dynamics_scene(kurz, "{ type: valvetrain.dynamics, inputs: { valve: v.motion, design: sd.design } }",
                                              "sd.design"),
                               builtin_pre10_registry());
  const auto design = std::dynamic_pointer_cast<const valvetrain::SpringDesign>(output(r, "sd.design").as_handle());
  DriveSettings one;
  one.stiffness = 4e6;
  one.damping_ratio = 0.06;
  const ChainParams single = build_chain(*design, one);
  const double c_s = design->spring->stiffness(0), M = design->reduced_mass;
  CHECK_THAT(single.link_damping.at(0), WithinRel(2 * 0.06 * std::sqrt((4e6 + c_s) * M), 1e-12));
  // Four masses: the modal damping ratio of the first mode, phi' B phi / (2 omega phi' M phi), is 0.06.
  DriveSettings four = one;
  four.multi_mass = true;
  four.stiffnesses = {2e7, 3e7, 1.5e7, 2.5e7};
  const ChainParams chain = build_chain(*design, four);
  const double omega = natural_frequencies(chain).at(0);
  // The first mode by inverse iteration on K - omega^2 M (a second method to Eigen's solver).
  const std::size_t n = 4;
  std::vector<double> K(n * n, 0.0), B(n * n, 0.0);
  auto add = [&](std::vector<double>& A, std::size_t a, long b, double k) {
    A[a * n + a] += k;
    if (b >= 0) {
      A[static_cast<std::size_t>(b) * n + static_cast<std::size_t>(b)] += k;
      A[a * n + static_cast<std::size_t>(b)] -= k;
      A[static_cast<std::size_t>(b) * n + a] -= k;
    }
  };
  add(K, 0, -1, chain.link_stiffness[0]);
  add(B, 0, -1, chain.link_damping[0]);
  for (std::size_t j = 1; j < n; ++j) {
    add(K, j, static_cast<long>(j - 1), chain.link_stiffness[j]);
    add(B, j, static_cast<long>(j - 1), chain.link_damping[j]);
  }
  add(K, n - 1, -1, c_s);
  // (K - w^2 M) phi = 0: solve (K - s M) x = M x_prev repeatedly with s slightly off w^2.
  std::vector<double> phi(n, 1.0);
  const double shift = omega * omega * (1 - 1e-6);
  for (int it = 0; it < 50; ++it) {
    std::vector<double> A(n * n), rhs(n);
    for (std::size_t i = 0; i < n; ++i) {
      for (std::size_t j = 0; j < n; ++j) A[i * n + j] = K[i * n + j] - (i == j ? shift * chain.mass[i] : 0.0);
      rhs[i] = chain.mass[i] * phi[i];
    }
    for (std::size_t c = 0; c < n; ++c)  // Gaussian elimination (the matrix is symmetric and small)
      for (std::size_t i = c + 1; i < n; ++i) {
        const double f = A[i * n + c] / A[c * n + c];
        for (std::size_t j = c; j < n; ++j) A[i * n + j] -= f * A[c * n + j];
        rhs[i] -= f * rhs[c];
      }
    for (std::size_t i = n; i-- > 0;) {
      double s = rhs[i];
      for (std::size_t j = i + 1; j < n; ++j) s -= A[i * n + j] * phi[j];
      phi[i] = s / A[i * n + i];
    }
    double norm = 0;
    for (double v : phi) norm = std::max(norm, std::abs(v));
    for (double& v : phi) v /= norm;
  }
  double pMp = 0, pBp = 0;
  for (std::size_t i = 0; i < n; ++i) {
    pMp += chain.mass[i] * phi[i] * phi[i];
    for (std::size_t j = 0; j < n; ++j) pBp += phi[i] * B[i * n + j] * phi[j];
  }
  CHECK_THAT(pBp / (2 * omega * pMp), WithinRel(0.06, 1e-9));
}
