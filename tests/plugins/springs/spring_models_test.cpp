// Spring models: the helical formulas against hand values, the nested spring against two helical
// coils, the limits each model refuses.
#include "spring_test_support.hpp"

#include <mechgraph/errors.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

using namespace mechgraph;
using namespace mechgraph::springs::testing;
using Catch::Matchers::Contains;
using Catch::Matchers::WithinAbs;
using Catch::Matchers::WithinRel;

TEST_CASE("spring.helical: sizing by hand (Wahl factor, wire, coil, coils, mass, surge)", "[springs]") {
  // P0 = 300 N, c = 25 N/mm, stroke 10 mm: P_max = 550 N; C = 7, tau = 600 MPa, G = 81.5 GPa,
  // rho = 7850 kg/m^3, two end coils. By hand: Kw = 27/24 + 0.615/7 = 1.2128571; d = 4.451738 mm;
  // D = 31.16217 mm; i = 5.288873; m_s = 87.18799 g; f1 = 314.3115 Hz.
  const auto model = spring_model("spring.helical");
  const SpringLine line{300.0, 25e3, 10e-3};
  const auto s = model->size(line);
  const CoilGeometry c = s->coils().at(0);
  CHECK_THAT(springs::wahl_factor(7.0), WithinRel(1.2128571428571, 1e-12));
  CHECK_THAT(c.wire_diameter, WithinRel(4.451738257557e-3, 1e-9));
  CHECK_THAT(c.mean_diameter, WithinRel(31.16216780290e-3, 1e-9));
  CHECK_THAT(c.active_coils, WithinRel(5.288872711238, 1e-9));
  CHECK_THAT(c.total_coils, WithinRel(7.288872711238, 1e-9));
  CHECK_THAT(s->mass(), WithinRel(87.18799333385e-3, 1e-9));
  CHECK_THAT(s->surge_frequency(), WithinRel(314.3115158197, 1e-9));
  // Second formula for the surge frequency: f1 = 1/2 sqrt(c / m_active), m_active the active coils' mass.
  const double m_active = 7850.0 * std::numbers::pi * c.wire_diameter * c.wire_diameter / 4 * std::numbers::pi *
                          c.mean_diameter * c.active_coils;
  CHECK_THAT(s->surge_frequency(), WithinRel(0.5 * std::sqrt(25e3 / m_active), 1e-12));
  // The line is reproduced, the stress at full lift is the allowable one, a third of the mass moves.
  CHECK_THAT(s->force(0.0), WithinRel(300.0, 1e-12));
  CHECK_THAT(s->max_force(), WithinRel(550.0, 1e-12));
  CHECK_THAT(s->stiffness(5e-3), WithinRel(25e3, 1e-12));
  CHECK_THAT(s->stress(10e-3), WithinRel(600e6, 1e-12));
  CHECK_THAT(s->effective_mass(), WithinRel(s->mass() / 3, 1e-15));
  // Lengths: solid = total coils x d; the shortest installation keeps 0.5 mm of clearance at full lift.
  CHECK_THAT(c.solid_length, WithinRel(c.total_coils * c.wire_diameter, 1e-12));
  CHECK_THAT(c.free_length, WithinRel(c.solid_length + 0.5e-3 + 10e-3 + 300.0 / 25e3, 1e-12));
}

TEST_CASE("spring.helical refuses what cannot be built, naming the parameter", "[springs]") {
  const auto model = spring_model("spring.helical");
  SECTION("fewer than two active coils") {
    try {
      model->size({300.0, 500e3, 10e-3});  // 500 N/mm: too stiff to wind two coils
      FAIL("no error");
    } catch (const NodeError& e) {
      CHECK(e.parameter() == "spring_index");
      CHECK_THAT(e.what(), Contains("fewer than 2") && Contains("lower spring_index"));
    }
  }
  SECTION("solid before full lift + clearance") {
    const auto short_model = spring_model("spring.helical", {{"installed_length", ParamValue::of_number(40e-3)}});
    try {
      short_model->size({300.0, 25e3, 10e-3});
      FAIL("no error");
    } catch (const NodeError& e) {
      CHECK(e.parameter() == "installed_length");
      CHECK_THAT(e.what(), Contains("solid") && Contains("40 mm"));
    }
    // Long enough: accepted, free length = installed + preload deflection.
    const auto roomy = spring_model("spring.helical", {{"installed_length", ParamValue::of_number(60e-3)}});
    CHECK_THAT(roomy->size({300.0, 25e3, 10e-3})->coils().at(0).free_length, WithinRel(60e-3 + 12e-3, 1e-12));
  }
}

TEST_CASE("spring.dual: two helical coils sharing the line, the inner inside the outer", "[springs]") {
  const auto dual = spring_model("spring.dual");  // outer share 0.6, indices 9 and 6
  const SpringLine line{300.0, 25e3, 10e-3};
  const auto s = dual->size(line);
  const auto coils = s->coils();
  REQUIRE(coils.size() == 2);
  // Each coil is a helical spring of its share of the line: compare with spring.helical sized so.
  const auto outer = spring_model("spring.helical", {{"spring_index", ParamValue::of_number(9.0)}})->size({180.0, 15e3, 10e-3});
  const auto inner = spring_model("spring.helical", {{"spring_index", ParamValue::of_number(6.0)}})->size({120.0, 10e3, 10e-3});
  CHECK_THAT(coils[0].wire_diameter, WithinRel(outer->coils()[0].wire_diameter, 1e-14));
  CHECK_THAT(coils[1].active_coils, WithinRel(inner->coils()[0].active_coils, 1e-14));
  CHECK_THAT(s->mass(), WithinRel(outer->mass() + inner->mass(), 1e-14));
  CHECK_THAT(s->surge_frequency(), WithinRel(std::min(outer->surge_frequency(), inner->surge_frequency()), 1e-14));
  CHECK_THAT(s->force(0.0), WithinRel(300.0, 1e-12));
  CHECK_THAT(s->max_force(), WithinRel(550.0, 1e-12));
  CHECK_THAT(s->stress(10e-3), WithinRel(600e6, 1e-12));
  CHECK((coils[0].mean_diameter - coils[0].wire_diameter) - (coils[1].mean_diameter + coils[1].wire_diameter) >= 2 * 0.3e-3);
  // Both coils seat on one installed length: the longer solid length sets it.
  // (both carry 12 mm of preload deflection, so their free lengths agree).
  const double installed = std::max(coils[0].solid_length, coils[1].solid_length) + 0.5e-3 + 10e-3;
  CHECK_THAT(coils[0].free_length, WithinRel(installed + 12e-3, 1e-12));
  CHECK_THAT(coils[1].free_length, WithinRel(installed + 12e-3, 1e-12));
  // An inner coil too fat for the outer one is refused, naming outer_share.
  const auto tight = spring_model("spring.dual", {{"outer_index", ParamValue::of_number(5.0)},
                                                  {"inner_index", ParamValue::of_number(12.0)}});
  try {
    tight->size(line);
    FAIL("no error");
  } catch (const NodeError& e) {
    CHECK(e.parameter() == "outer_share");
    CHECK_THAT(e.what(), Contains("does not fit"));
  }
}

TEST_CASE("conformance: every spring model, lines from tiny to huge", "[springs][conformance]") {
  // Each model either sizes a spring that honours the Spring contract or refuses with a NodeError:
  // never a NaN, never a spring outside its limits.
  const std::vector<SpringLine> lines{
      {300.0, 25e3, 10e-3},  // a valve spring
      {1.0, 100.0, 1e-3},    // an instrument spring
      {5e4, 2e6, 20e-3},     // a heavy die spring
      {0.0, 10e3, 5e-3},     // no preload
      {300.0, 1e9, 10e-3},   // far too stiff: refused
  };
  for (const auto& type : all_spring_types()) {
    const auto model = spring_model(*type);
    CHECK(model->type_name() == type->info().type);
    for (const SpringLine& line : lines) {
      INFO(type->info().type << ": P0 " << line.preload << " N, c " << line.rate << " N/m, stroke " << line.stroke);
      std::shared_ptr<const Spring> s;
      try {
        s = model->size(line);
      } catch (const NodeError& e) {
        CHECK_FALSE(e.parameter().empty());
        CHECK(type->info().find_param(e.parameter()) != nullptr);  // names one of the model's own parameters
        continue;
      }
      CHECK(s->kind() == Spring::kind_name);
      CHECK_THAT(s->force(0.0), WithinAbs(line.preload, 1e-12 * line.max_force()));
      CHECK_THAT(s->force(line.stroke), WithinRel(line.max_force(), 1e-12));
      CHECK_THAT(s->stiffness(0.5 * line.stroke), WithinRel(line.rate, 1e-12));
      CHECK_THAT(s->stroke(), WithinRel(line.stroke, 1e-15));
      CHECK(s->stress(line.stroke) <= s->allowable_stress() * (1 + 1e-12));
      CHECK(s->stress(0.0) <= s->stress(line.stroke));
      CHECK(std::isfinite(s->mass()));
      CHECK(s->mass() > 0);
      CHECK(s->effective_mass() > 0);
      CHECK(s->effective_mass() < s->mass());
      CHECK(std::isfinite(s->surge_frequency()));
      CHECK(s->surge_frequency() > 0);
      REQUIRE_FALSE(s->coils().empty());
      for (const CoilGeometry& c : s->coils()) {
        CHECK(c.active_coils >= 2.0);
        CHECK(c.total_coils >= c.active_coils);
        CHECK(c.wire_diameter > 0);
        CHECK(c.mean_diameter / c.wire_diameter >= 4.0 - 1e-12);
        CHECK(c.mean_diameter / c.wire_diameter <= 16.0 + 1e-12);
        // At full lift the coil is still 0.5 mm (the default clearance) from solid.
        CHECK(c.free_length - line.preload / line.rate - line.stroke >= c.solid_length + 0.5e-3 - 1e-12);
      }
    }
  }
}

TEST_CASE("solid deflection: where the first coil goes solid, from the installed length the design rule sets",
          "[springs]") {
  // Without installed_length the models install the spring at solid + clearance + stroke, so it
  // goes solid at stroke + clearance (0.5 mm by default) past the closed valve; with a given
  // installed length L at L - (longest solid length).
  const SpringLine line{300.0, 25e3, 10e-3};
  for (const char* type : {"spring.helical", "spring.dual"}) {
    INFO(type);
    const auto shortest = spring_model(type)->size(line);
    CHECK_THAT(shortest->solid_deflection(), WithinRel(10.5e-3, 1e-12));
    const auto roomy = spring_model(type, {{"installed_length", ParamValue::of_number(60e-3)}})->size(line);
    double longest_solid = 0.0;
    for (const CoilGeometry& c : roomy->coils()) longest_solid = std::max(longest_solid, c.solid_length);
    CHECK_THAT(roomy->solid_deflection(), WithinRel(60e-3 - longest_solid, 1e-12));
    CHECK(roomy->solid_deflection() > line.stroke);
  }
}
