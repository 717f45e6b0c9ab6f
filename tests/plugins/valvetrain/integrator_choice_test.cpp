// integrator: auto (valve_simulation.hpp, choose_integrator): the chain's fastest rate against
// closed forms and the exact natural frequencies, and the choice it makes on scenes: explicit
// dopri5 for the single mass and for a spring cut into many coil masses, implicit cvode for very
// stiff damped links, each agreeing with a second method.
#include "dynamics_scenes.hpp"
#include "valve_simulation.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

using namespace mechgraph;
using namespace mechgraph::valvetrain;
using namespace mechgraph::testing;
using namespace mechgraph::testing::dynamics;
using Catch::Matchers::Contains;
using Catch::Matchers::WithinAbs;
using Catch::Matchers::WithinRel;

namespace {

ChainParams single_mass(double m, double k, double c_s, double b) {
  ChainParams p;
  p.mass = {m};
  p.link_stiffness = {k};
  p.link_damping = {b};
  p.spring_rate = c_s;
  return p;
}

std::string dyn_node(const std::string& effects, const std::string& params) {
  return "{ type: valvetrain.dynamics, inputs: { valve: v.motion, design: sd.design }, effects: [ elastic_drive" + effects +
         " ], params: { " + params + " } }";
}

double worst_lift_gap(const RunResult& a, const RunResult& b) {
  const Table& ta = output(a, "dyn.curves").as_table();
  const Table& tb = output(b, "dyn.curves").as_table();
  double worst = 0.0;
  for (std::size_t i = 0; i < ta.axis.values.size(); ++i)
    worst = std::max(worst, std::abs(ta.find("lift")->values[i] - tb.find("lift")->values[i]));
  return worst;
}

bool noted(const RunResult& r, const std::string& text) {
  for (const std::string& n : node_run(r, "dyn").notes)
    if (n.find(text) != std::string::npos) return true;
  return false;
}

}  // namespace

TEST_CASE("integrator choice: the single mass's fastest rate in closed form, under- and overdamped", "[valvetrain][dynamics][integrator]") {
  const double m = 0.13, k = 4e6, c_s = 3e4, h = 2.98e-5;
  const double omega = std::sqrt((k + c_s) / m);
  SECTION("underdamped: |lambda| = omega") {
    const IntegratorChoice c = choose_integrator(single_mass(m, k, c_s, 2 * 0.06 * std::sqrt((k + c_s) * m)), h);
    CHECK_THAT(c.fastest_rate, WithinRel(omega, 1e-12) || WithinAbs(omega, 1e-9));
    CHECK_THAT(c.stiffness_ratio, WithinRel(omega * h, 1e-12) || WithinAbs(omega * h, 1e-15));
    CHECK_FALSE(c.stiff);
    CHECK_THAT(c.reason(), Contains("not stiff"));
  }
  SECTION("overdamped 10x critical: the fast root (d + sqrt(d^2 - 4 w^2)) / 2 is within 1 % of d = b / m") {
    const double d = 20.0 * omega;  // b / m, ten times critical (2 omega)
    const IntegratorChoice c = choose_integrator(single_mass(m, k, c_s, d * m), h);
    const double fast = (d + std::sqrt(d * d - 4 * omega * omega)) / 2;
    CHECK(c.fastest_rate >= fast);
    CHECK_THAT(c.fastest_rate, WithinRel(fast, 0.01) || WithinAbs(fast, 1e-9));
  }
  SECTION("a very stiff link, lightly damped: beyond the stability interval, yet an oscillation BDF must resolve too") {
    const IntegratorChoice c = choose_integrator(single_mass(m, 1e12, c_s, 2 * 0.06 * std::sqrt(1e12 * m)), h);
    CHECK(c.stiffness_ratio > 10 * IntegratorChoice::explicit_limit);
    CHECK_FALSE(c.overdamped);
    CHECK_FALSE(c.stiff);
  }
  SECTION("a very stiff link, overdamped: stiff") {
    const IntegratorChoice c = choose_integrator(single_mass(m, 1e12, c_s, 4 * std::sqrt(1e12 * m)), h);
    CHECK(c.overdamped);
    CHECK(c.stiff);
    CHECK_THAT(c.reason(), Contains("stiff, implicit BDF (cvode)"));
  }
}

TEST_CASE("integrator choice: a coil chain's bound against its exact fastest mode", "[valvetrain][dynamics][integrator]") {
  // Gershgorin's bound on the chain never falls below the exact fastest mode (natural_frequencies,
  // an eigen-solver) and stays within a factor 2 of it.
  for (int coils : {1, 8, 40, 150}) {
    INFO(coils << " coils");
    ChainParams p = single_mass(0.1, 4e6, 4e4, 0.0);
    p.coils = coils;
    p.coil_mass = 0.02 / coils;
    const double exact = natural_frequencies(p).back();
    const IntegratorChoice c = choose_integrator(p, 1e-5);
    CHECK(c.fastest_rate >= exact * (1 - 1e-12));
    CHECK(c.fastest_rate <= 2 * exact);
  }
}

TEST_CASE("integrator auto: explicit for the single mass, the same lift as cvode within the tolerance", "[valvetrain][dynamics][integrator]") {
  const std::string scene = dynamics_scene(kurz, dyn_node("", "drive_stiffness: 4000 N/mm, tolerance: 1e-10"), "dyn.curves, dyn.max_deviation");
  const RunResult chosen = run_scene(scene);  // auto is the default
  const RunResult bdf = run_scene(scene, {parse_override("dyn.integrator=cvode")});
  const RunResult rk = run_scene(scene, {parse_override("dyn.integrator=dopri5")});
  const auto& work = node_run(chosen, "dyn").work;
  CHECK(work.at("implicit") == 0);
  CHECK(work.at("stiffness_ratio") > 0);
  CHECK(work.at("stiffness_ratio") < IntegratorChoice::explicit_limit);
  CHECK(noted(chosen, "not stiff, explicit Dormand-Prince"));
  CHECK(worst_lift_gap(chosen, rk) == 0.0);  // dopri5 ran
  CHECK(worst_lift_gap(chosen, bdf) < 1e-8);  // of 11.75 mm
  CHECK_THAT(num(chosen, "dyn.max_deviation"), WithinRel(num(bdf, "dyn.max_deviation"), 1e-5));
  CHECK(node_run(bdf, "dyn").work.at("implicit") == 1);
  CHECK_FALSE(noted(bdf, "integrator auto"));  // a choice the scene made needs no reason
}

TEST_CASE("integrator auto: implicit for very stiff damped links, explicit for many coil masses, each agrees with the other integrator",
          "[valvetrain][dynamics][integrator]") {
  SECTION("multi_mass with inner links of 4e9 N/mm: their modes overdamped far beyond the step cap") {
    const std::string scene = dynamics_scene(
        kurz, dyn_node(", multi_mass", "stiffnesses: [4000 N/mm, 4e9 N/mm, 4e9 N/mm, 4e9 N/mm], tolerance: 1e-8"), "dyn.curves");
    const RunResult chosen = run_scene(scene);
    CHECK(node_run(chosen, "dyn").work.at("implicit") == 1);
    CHECK(node_run(chosen, "dyn").work.at("stiffness_ratio") > 1e5);
    CHECK(noted(chosen, "stiff, implicit BDF (cvode)"));
    // dopri5 would need millions of steps here (its stability, not its accuracy): the single
    // mass of the same drive (the inner links rigid) is the second method.
    const RunResult single = run_scene(dynamics_scene(kurz, dyn_node("", "drive_stiffness: 4000 N/mm, tolerance: 1e-8"), "dyn.curves"));
    CHECK(worst_lift_gap(chosen, single) < 1e-6);  // of 11.75 mm (the inner links' own compliance)
  }
  SECTION("a spring of 150 coil masses: stiff at the cap (ratio ~12), but BDF's dense algebra on 302 states costs more") {
    const std::string scene = dynamics_scene(kurz, dyn_node(", spring_surge", "drive_stiffness: 4000 N/mm, coils: 150, tolerance: 1e-8"),
                                             "dyn.curves, dyn.max_spring_force");
    const RunResult chosen = run_scene(scene);
    INFO("stiffness ratio " << node_run(chosen, "dyn").work.at("stiffness_ratio"));
    CHECK(node_run(chosen, "dyn").work.at("stiffness_ratio") > IntegratorChoice::explicit_limit);
    CHECK(node_run(chosen, "dyn").work.at("implicit") == 0);
    const RunResult bdf = run_scene(scene, {parse_override("dyn.integrator=cvode")});
    CHECK(worst_lift_gap(chosen, bdf) < 1e-8);
    CHECK_THAT(num(chosen, "dyn.max_spring_force"), WithinRel(num(bdf, "dyn.max_spring_force"), 1e-6));
  }
}
