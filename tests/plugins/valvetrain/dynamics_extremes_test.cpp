// The dynamics' extremes and events found on the integrator's dense output, not on an output grid:
// the free vibration after a cycloidal rise against its closed-form amplitude, a damped drive and
// the dynamics node's scalars (deviations, least contact force, greatest spring force, bounce
// height) against a grid converged to the tolerance, their independence of curve_points, and a
// loss of contact too brief for the step ends to see.
#include "chain_model.hpp"
#include "dynamics_scenes.hpp"
#include "hybrid_simulation.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

using namespace mechgraph;
using namespace mechgraph::testing;
using namespace mechgraph::testing::dynamics;
using namespace mechgraph::valvetrain;
using Catch::Matchers::WithinAbs;
using Catch::Matchers::WithinRel;

namespace {

constexpr double pi = std::numbers::pi;

// One mass on a drive of natural period Tn = T / r, the drive rising cycloidally by h in time T and
// then resting (docs/methods/valvetrain.md, "Residual vibration after a cycloidal rise").
struct CycloidalRise {
  double h = 0.01, T = 0.02, r = 1.0, zeta = 0.0;
  double omega() const { return 2 * pi * r / T; }
  ChainModel model() const {
    ChainParams p;
    p.mass = {0.2};
    p.link_stiffness = {0.2 * omega() * omega()};
    p.link_damping = {2 * zeta * 0.2 * omega()};
    p.seat = false;
    const double h_ = h, T_ = T;
    return ChainModel(p, [h_, T_](double t) {
      if (t >= T_) return DriveValue{h_, 0.0, 0.0};
      return DriveValue{h_ * (t / T_ - std::sin(2 * pi * t / T_) / (2 * pi)), h_ / T_ * (1 - std::cos(2 * pi * t / T_)),
                        2 * pi * h_ / (T_ * T_) * std::sin(2 * pi * t / T_)};
    });
  }
  SimulationOptions options(const std::string& integrator, double rtol) const {
    SimulationOptions o;
    o.integrator = integrator;
    o.rtol = rtol;
    o.atol_x = rtol * h;
    o.atol_v = rtol * h / T;
    return o;
  }
};

// The mass's lift less the drive's: x - y.
Monitor drive_gap(double from, double to) {
  return {from, to, true, true, [](const ChainModel&, const Snapshot& x) {
            return Reading{x.state[0] - x.drive.y, x.state[1] - x.drive.rate};
          }};
}

std::vector<double> grid(double a, double b, int n) {
  std::vector<double> t;
  for (int i = 0; i < n; ++i) t.push_back(a + (b - a) * i / (n - 1));
  return t;
}

}  // namespace

TEST_CASE("dynamics extremes: the free vibration after a cycloidal rise peaks at its closed-form amplitude, between grid points",
          "[valvetrain][dynamics][extremes]") {
  // After the rise, x - h = A cos(omega (t - T) + phase), A / h = |sin(pi r)| / (pi r |1 - r^2|):
  // over [T, 2T] (at least 0.8 of a period) its greatest value is A and its least -A.
  for (const char* integrator : {"cvode", "dopri5"})
    for (double r : {0.8, 1.5, 2.5, 3.7}) {
      INFO(integrator << ", r = " << r);
      const CycloidalRise rise{0.01, 0.02, r};
      const double A = rise.h * std::abs(std::sin(pi * r)) / (pi * r * std::abs(1 - r * r));
      // 41 output points in the window (the peaks, at T/2 + k Tn/2, fall between them).
      const std::vector<double> outputs = grid(rise.T + rise.T / 31, 2 * rise.T, 41);
      const SimulationResult run =
          simulate(rise.model(), 0.0, 2 * rise.T, outputs, {rise.T}, rise.options(integrator, 1e-11), {drive_gap(rise.T, 2 * rise.T)});
      REQUIRE(run.extremes.size() == 1);
      // To the integration's tolerance (as the amplitude read from the state at T in dynamics_test.cpp).
      CHECK_THAT(greatest_of(run.extremes[0]).value, WithinAbs(A, 1e-6 * A + 1e-9 * rise.h));
      CHECK_THAT(least_of(run.extremes[0]).value, WithinAbs(-A, 1e-6 * A + 1e-9 * rise.h));
      // The output grid's own extremes fall short by 2e-4 A and more.
      double top = 0, low = 0;
      for (std::size_t i = 0; i < run.state.size(); ++i) {
        top = std::max(top, run.state[i][0] - rise.h);
        low = std::min(low, run.state[i][0] - rise.h);
      }
      CHECK(A - top > 1e-4 * A);
      CHECK(A + low > 1e-4 * A);
      CHECK(run.work.at("refinements") >= 1);
      CHECK(run.work.at("monitor_evaluations") > 0);
    }
}

TEST_CASE("dynamics extremes: a damped drive's greatest and least gap agree with a converged grid", "[valvetrain][dynamics][extremes]") {
  // Damped, so no closed form is at hand: the reference is the gap on 200001 points at a tighter
  // tolerance (the grid's error ~ (step / 2)^2 x'' / 2 ~ 1e-13 m).
  const CycloidalRise rise{0.01, 0.02, 1.3, 0.05};
  const std::vector<double> fine = grid(0.0, 2 * rise.T, 200001);
  const ChainModel model = rise.model();
  const SimulationResult reference = simulate(model, 0.0, 2 * rise.T, fine, {rise.T}, rise.options("cvode", 1e-12));
  double top = -1, low = 1;
  for (std::size_t i = 0; i < fine.size(); ++i) {
    const double gap = reference.state[i][0] - model.excitation(fine[i]).y;
    top = std::max(top, gap);
    low = std::min(low, gap);
  }
  for (const char* integrator : {"cvode", "dopri5"}) {
    INFO(integrator);
    const SimulationResult run =
        simulate(model, 0.0, 2 * rise.T, {2 * rise.T}, {rise.T}, rise.options(integrator, 1e-10), {drive_gap(0.0, 2 * rise.T)});
    CHECK_THAT(greatest_of(run.extremes[0]).value, WithinRel(top, 1e-7));
    CHECK_THAT(least_of(run.extremes[0]).value, WithinRel(low, 1e-7));
  }
}

namespace {

// The extremes of the dynamics node's curves on their own points: what the node once reported.
struct GridExtremes {
  double max_deviation = 0, residual = 0, min_contact = 1e300, max_spring = -1e300;
};
GridExtremes grid_extremes(const Table& t) {
  GridExtremes g;
  const auto& lift = t.find("lift")->values;
  for (std::size_t i = 0; i < lift.size(); ++i) {
    const double dev = std::abs(lift[i] - t.find("quasi_static_lift")->values[i]);
    g.max_deviation = std::max(g.max_deviation, dev);
    if (t.axis.values[i] >= 0) g.residual = std::max(g.residual, dev);
    if (lift[i] > 0) g.min_contact = std::min(g.min_contact, t.find("contact_force")->values[i]);
    g.max_spring = std::max(g.max_spring, t.find("spring_force")->values[i]);
  }
  return g;
}

}  // namespace

TEST_CASE("dynamics node: its extremes agree with a converged grid and do not depend on curve_points",
          "[valvetrain][dynamics][extremes]") {
  // The `elastic` node of scenes/valvetrain_dynamics.yaml (Kurz cam, lash 0.25 mm, spring for
  // 5600 rpm with K = 1.5, 4000 N/mm, 6 % damping): on its 1441 curve points the greatest deviation
  // is 1.3e-4 relative short of the continuous one.
  auto scene = [](const std::string& integrator, const std::string& points, const std::string& tolerance) {
    return R"(
nodes:
  kurz:   { type: cam.kurz, params: { max_lift: 8 mm, action_angle: 130 deg, accel_angle: 18 deg, base_radius: 17 mm } }
  v:      { type: valvetrain.valve_motion, inputs: { cam: kurz.law }, params: { rpm: 5600 rpm, rocker_ratio: 1.5, lash: 0.25 mm } }
  train:  { type: valvetrain.masses, params: { valve_mass: 55 g, retainer_mass: 18 g, tappet_mass: 60 g, pushrod_mass: 50 g,
                                               rocker_inertia: 4e-5 kg*m^2, arm_valve: 45 mm, arm_pushrod: 30 mm } }
  spring: { type: spring.helical, params: { spring_index: 7, allowable_stress: 800 MPa } }
  sd:     { type: valvetrain.spring_design, inputs: { valve: v.motion, spring: spring.model, masses: train.masses },
            params: { safety_factor: 1.5 } }
  dyn:    { type: valvetrain.dynamics, inputs: { valve: v.motion, design: sd.design }, effects: [ elastic_drive ],
            params: { drive_stiffness: 4000 N/mm, integrator: )" + integrator + ", curve_points: " + points + ", tolerance: " + tolerance + R"( } }
outputs: [ dyn.curves, dyn.max_deviation, dyn.residual_amplitude, dyn.min_contact_force, dyn.max_spring_force ]
)";
  };
  // The reference: 400001 curve points at tolerance 1e-11 (grid error ~1e-11 relative).
  const GridExtremes ref = grid_extremes(output(run_scene(scene("cvode", "400001", "1e-11")), "dyn.curves").as_table());
  for (const char* integrator : {"cvode", "dopri5"}) {
    INFO(integrator);
    const RunResult r = run_scene(scene(integrator, "1441", "1e-10"));
    // To the tolerance: 1e-10 of the 11.75 mm lift, ~1e-9 m with the error's growth, x 4000 N/mm.
    CHECK_THAT(num(r, "dyn.max_deviation"), WithinAbs(ref.max_deviation, 1e-9));
    CHECK_THAT(num(r, "dyn.residual_amplitude"), WithinAbs(ref.residual, 1e-9));
    CHECK_THAT(num(r, "dyn.min_contact_force"), WithinAbs(ref.min_contact, 4e-3));
    CHECK_THAT(num(r, "dyn.max_spring_force"), WithinAbs(ref.max_spring, 1e-4));
    // On its own 1441 points the deviation's peak is ~1e-4 relative short (the issue's measure).
    const GridExtremes coarse = grid_extremes(output(r, "dyn.curves").as_table());
    CHECK(ref.max_deviation - coarse.max_deviation > 5e-5 * ref.max_deviation);
    CHECK(node_run(r, "dyn").work.at("refinements") > 0);
    // The same from 97 curve points: the output grid does not steer the integration or the search.
    const RunResult sparse = run_scene(scene(integrator, "97", "1e-10"));
    for (const char* scalar : {"dyn.max_deviation", "dyn.residual_amplitude", "dyn.min_contact_force", "dyn.max_spring_force"})
      CHECK_THAT(num(sparse, scalar), WithinRel(num(r, scalar), 1e-12));
  }
}

TEST_CASE("dynamics node: the bounce height is the highest hop after the first landing, between grid points",
          "[valvetrain][dynamics][extremes]") {
  // 7500 rpm on a spring for 5600 rpm: the valve floats, lands at ~13 m/s and bounces.
  auto scene = [](const std::string& points, const std::string& tolerance) {
    return dynamics_scene(kurz,
                          "{ type: valvetrain.dynamics, inputs: { valve: fast.motion, design: sd.design }, "
                          "effects: [ elastic_drive, contact_loss, seat_impact ], params: { drive_stiffness: 4000 N/mm, "
                          "curve_points: " + points + ", tolerance: " + tolerance + " } }",
                          "dyn.curves, dyn.bounce_height, dyn.bounces", "5600 rpm", "0.25 mm", fast_valve(7500));
  };
  // Reference: on 400001 points, the highest lift after the first landing (the first local minimum
  // of the lift near the seat after its highest point: the valve floats off the cam first, rebounds
  // from the solid spring (coil bind, a local minimum high above the seat), then hits the seat).
  const RunResult reference = run_scene(scene("400001", "1e-11"));
  const Table& fine = output(reference, "dyn.curves").as_table();
  const auto& lift = fine.find("lift")->values;
  std::size_t j = static_cast<std::size_t>(std::max_element(lift.begin(), lift.end()) - lift.begin());
  const double near_seat = 0.01 * lift[j];
  while (j + 1 < lift.size() && !(lift[j] <= lift[j - 1] && lift[j] < lift[j + 1] && lift[j] < near_seat)) ++j;
  REQUIRE(j + 1 < lift.size());
  const double highest_hop = *std::max_element(lift.begin() + static_cast<long>(j), lift.end());
  REQUIRE(highest_hop > 1e-4);
  const RunResult r = run_scene(scene("1441", "1e-10"));
  CHECK(num(r, "dyn.bounces") >= 3);
  CHECK_THAT(num(r, "dyn.bounce_height"), WithinRel(highest_hop, 1e-6));
}

TEST_CASE("dynamics node: a loss of contact shorter than a step is found whatever the output grid", "[valvetrain][dynamics][extremes]") {
  // Cycloidal cam, 1500 N/mm, 6 % damping: the contact force's least value crosses 0 at about
  // 4326.83 rpm. At 4326.9 rpm it dips 0.07 N below zero for about 1e-5 s, inside one step: the
  // signs at the steps' ends (and once at the output times) do not see it; the dense output does.
  const std::string scene_text = R"(
nodes:
  cam:    { type: cam.cycloidal, params: { max_lift: 8 mm, action_angle: 130 deg, base_radius: 35 mm } }
  v:      { type: valvetrain.valve_motion, inputs: { cam: cam.law }, params: { rpm: 5600 rpm, rocker_ratio: 1.5, lash: 0 mm } }
  train:  { type: valvetrain.masses, params: { valve_mass: 55 g, retainer_mass: 18 g, tappet_mass: 60 g, pushrod_mass: 50 g,
                                               rocker_inertia: 4e-5 kg*m^2, arm_valve: 45 mm, arm_pushrod: 30 mm } }
  spring: { type: spring.helical, params: { allowable_stress: 800 MPa } }
  sd:     { type: valvetrain.spring_design, inputs: { valve: v.motion, spring: spring.model, masses: train.masses } }
  fast:   { type: valvetrain.valve_motion, inputs: { cam: cam.law }, params: { rpm: $n, rocker_ratio: 1.5, lash: 0 mm } }
  uni:    { type: valvetrain.dynamics, inputs: { valve: fast.motion, design: sd.design }, effects: [ elastic_drive, contact_loss ],
            params: { drive_stiffness: 1500 N/mm, damping_ratio: 0.06, revolutions: 3 } }
  bi:     { type: valvetrain.dynamics, inputs: { valve: fast.motion, design: sd.design }, effects: [ elastic_drive ],
            params: { drive_stiffness: 1500 N/mm, damping_ratio: 0.06, revolutions: 3 } }
params:
  n: 4326.9 rpm
outputs: [ uni.floats, uni.min_contact_force, bi.min_contact_force ]
)";
  for (const char* integrator : {"cvode", "dopri5"})
    for (const char* points : {"16", "1441"}) {
      INFO(integrator << ", " << points << " curve points");
      const std::vector<Override> set = {parse_override(std::string("uni.integrator=") + integrator),
                                         parse_override(std::string("bi.integrator=") + integrator),
                                         parse_override(std::string("uni.curve_points=") + points),
                                         parse_override(std::string("bi.curve_points=") + points)};
      const RunResult r = run_scene(scene_text, set);
      CHECK(num(r, "bi.min_contact_force") < -0.05);  // the bilateral drive would pull
      CHECK(num(r, "bi.min_contact_force") > -0.1);
      CHECK(num(r, "uni.floats") == 1);
      CHECK(num(r, "uni.min_contact_force") == 0);
      // 0.4 rpm lower the margin is +0.3 N: no float.
      std::vector<Override> lower = set;
      lower.push_back(parse_override("n=4326.5rpm"));
      CHECK(num(run_scene(scene_text, lower), "uni.floats") == 0);
    }
}

TEST_CASE("chain model: the rates of the forces and event functions are their time derivatives along the motion",
          "[valvetrain][dynamics][extremes]") {
  // Four masses, three coils, damped links and coils, unilateral contact: each rate against the
  // central difference of its quantity at (t +- tau, s +- tau s'), exact to O(tau^2) (the model
  // is affine in the state; the drive y = a sin(w t) curves).
  ChainParams p;
  p.mass = {0.02, 0.03, 0.01, 0.08};
  p.link_stiffness = {5e7, 3e7, 4e7, 2e7};
  p.link_damping = {30.0, 20.0, 25.0, 15.0};
  p.preload = 300.0;
  p.spring_rate = 4e4;
  p.coils = 3;
  p.coil_mass = 0.004;
  p.coil_damping = 2.0;
  p.contact_loss = true;
  const double a = 0.01, w = 300.0;
  const ChainModel model(p, [=](double t) {
    return DriveValue{a * std::sin(w * t), a * w * std::cos(w * t), -a * w * w * std::sin(w * t)};
  });
  const double t = 0.0123, tau = 1e-7;
  for (const Mode mode : {Mode{false, true}, Mode{false, false}, Mode{true, true}}) {
    INFO("seated " << mode.seated << ", contact " << mode.contact);
    // A state with the cam pushing (y > x_0); the valve at rest on its seat when seated.
    ChainState s = {0.5 * a * std::sin(w * t), 1e-3, 2e-3, mode.seated ? 0.0 : 1.5e-3, 4e-4, 2e-4, 1e-4,
                    0.3, -0.2, 0.1, mode.seated ? 0.0 : 0.4, 0.05, -0.02, 0.01};
    Snapshot x, ahead, behind;
    model.snapshot(t, s, mode, x);
    ChainState plus = s, minus = s;
    for (std::size_t i = 0; i < s.size(); ++i) {
      plus[i] += tau * x.rate[i];
      minus[i] -= tau * x.rate[i];
    }
    model.snapshot(t + tau, plus, mode, ahead);
    model.snapshot(t - tau, minus, mode, behind);
    auto difference = [&](auto quantity) { return (quantity(ahead) - quantity(behind)) / (2 * tau); };
    auto check = [&](double rate, double reference) { CHECK_THAT(rate, WithinAbs(reference, 1e-6 * std::abs(reference) + 1e-6)); };
    check(model.cam_force_rate(x), difference([&](const Snapshot& y) { return model.cam_force(y.drive, y.state); }));
    check(model.pushing_force_rate(x), difference([&](const Snapshot& y) { return model.pushing_force(y.drive, y.state); }));
    check(model.force_on_valve_rate(x), difference([&](const Snapshot& y) { return model.force_on_valve(y.drive, y.state); }));
    check(model.spring_force_rate(x), difference([&](const Snapshot& y) { return model.spring_force(y.state); }));
    const std::size_t n = model.root_kinds(mode).size();
    REQUIRE(n >= 1);
    std::vector<double> g(n), dg(n), g_ahead(n), g_behind(n);
    model.roots(x, g.data(), dg.data());
    model.roots(ahead, g_ahead.data(), nullptr);
    model.roots(behind, g_behind.data(), nullptr);
    for (std::size_t i = 0; i < n; ++i) check(dg[i], (g_ahead[i] - g_behind[i]) / (2 * tau));
  }
}
