// The cam conformance suite: every cam node type of the plugin (source profiles and standard laws)
// is evaluated over the design scenarios of cam_conformance_cases.hpp and its law checked against
// the CamLaw contract (sdk/include/mechgraph/domain/cam_law.hpp), with the scenario's own knowledge
// (where the event must be, symmetry, the summary outputs) on top of the SDK's conformance kit
// (mechgraph/testing/cam_law_conformance.hpp, which it also runs):
//  - zero lift and derivatives outside the event; the event where the scenario puts it;
//  - breakpoints sorted and strictly inside the event;
//  - max_lift at the nose (max over the event), law.max_lift() consistent;
//  - symmetry h(-phi) = h(phi), odd derivatives antisymmetric;
//  - continuity of the lift everywhere and of the derivatives the case promises, checked at every
//    breakpoint and at the event ends;
//  - each derivative against a central difference (Richardson-extrapolated) of the next lower
//    one, away from breakpoints;
//  - max_velocity, max/min_acceleration, accel_angle outputs against dense sampling;
//  - hard scenarios (tiny/huge lift and action angle): success, or a NodeError where the case
//    allows it; infeasible scenarios: a NodeError for every law; never NaN or Inf.
#include "cam_conformance_cases.hpp"
#include "registration.hpp"

#include <mechgraph/testing/cam_law_conformance.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <system_error>

using namespace mechgraph;
using namespace mechgraph::cams;
using namespace mechgraph::cams::testing;

namespace {

NodeTypeList all_cam_types() {
  NodeTypeList types;
  add_source_profile_types(types);
  add_standard_law_types(types);
  return types;
}

double component(const LiftDerivatives& d, int k) {
  switch (k) {
    case 0: return d.lift;
    case 1: return d.velocity;
    case 2: return d.acceleration;
    default: return d.jerk;
  }
}

bool finite(const LiftDerivatives& d) {
  return std::isfinite(d.lift) && std::isfinite(d.velocity) && std::isfinite(d.acceleration) && std::isfinite(d.jerk);
}

int promised_continuity(const ConformanceCase& c, const Scenario& s) {
  switch (s.ramp.type) {
    case RampType::constant_velocity: return 0;
    case RampType::cosine: return std::min(c.continuity, 1);
    default: return c.continuity;
  }
}

const char* names[] = {"lift", "velocity", "acceleration", "jerk"};

void check_law(const CamLaw& law, const OutputSet& outputs, const ConformanceCase& c, const Scenario& s) {
  constexpr double pi = std::numbers::pi;
  const double b = law.event_begin(), e = law.event_end();
  const double half = 0.5 * s.action_angle + (s.ramp.type == RampType::none ? 0.0 : s.ramp.length);

  // The event.
  REQUIRE(b < e);
  CHECK(b >= -pi);
  CHECK(e <= pi);
  CHECK(b == Approx(-half).epsilon(1e-12).margin(1e-12));
  CHECK(e == Approx(half).epsilon(1e-12).margin(1e-12));

  // Breakpoints: sorted, strictly inside.
  const std::vector<double> bps = law.breakpoints();
  for (std::size_t i = 0; i < bps.size(); ++i) {
    INFO("breakpoint " << i << " at " << bps[i] / deg << " deg");
    CHECK(bps[i] > b);
    CHECK(bps[i] < e);
    if (i > 0) CHECK(bps[i] > bps[i - 1]);
  }
  std::vector<double> knots{b};
  for (double x : bps)
    if (x > knots.back() && x < e) knots.push_back(x);
  knots.push_back(e);

  // Zero outside the event, periodic over 2 pi, zero at the event ends themselves.
  for (double phi : {b, e, b - 1e-9, e + 1e-9, 0.5 * (b - pi), 0.5 * (e + pi), -pi, pi, 3.0 * pi + 0.5 * (e - pi)}) {
    if (phi > b && phi < e) continue;
    INFO("outside the event at " << phi / deg << " deg");
    const LiftDerivatives d = law.at(phi);
    CHECK(d.lift == 0.0);
    CHECK(d.velocity == 0.0);
    CHECK(d.acceleration == 0.0);
    CHECK(d.jerk == 0.0);
  }
  CHECK(law.at(0.1 * b + 2.0 * pi).lift == Approx(law.at(0.1 * b).lift).epsilon(1e-9).margin(1e-15));

  // Dense sampling of every piece.
  double S[4] = {0, 0, 0, 0};
  double max_h = -1.0, max_v = 0.0, max_a = -std::numeric_limits<double>::infinity();
  double min_a = std::numeric_limits<double>::infinity();
  std::vector<std::pair<double, double>> accel_samples;
  bool all_finite = true;
  const int per_piece = 2000;
  for (std::size_t p = 0; p + 1 < knots.size(); ++p) {
    const double a0 = knots[p], a1 = knots[p + 1];
    // Midpoints of per_piece cells, and the one-sided values at both knots (an extremum of a
    // derivative that steps, or of the velocity at a corner, sits on a knot).
    for (int i = -1; i <= per_piece; ++i) {
      const double phi = i < 0            ? a0 + 1e-12 * (a1 - a0)
                         : i == per_piece ? a1 - 1e-12 * (a1 - a0)
                                          : a0 + (a1 - a0) * (i + 0.5) / per_piece;
      const LiftDerivatives d = law.at(phi);
      all_finite = all_finite && finite(d);
      for (int k = 0; k < 4; ++k) S[k] = std::max(S[k], std::abs(component(d, k)));
      max_h = std::max(max_h, d.lift);
      max_v = std::max(max_v, std::abs(d.velocity));
      max_a = std::max(max_a, d.acceleration);
      min_a = std::min(min_a, d.acceleration);
      accel_samples.emplace_back(phi, d.acceleration);
    }
  }
  REQUIRE(all_finite);
  for (int k = 0; k < 4; ++k) {
    INFO(names[k] << " scale");
    REQUIRE(S[k] > 0.0);
    REQUIRE(std::isfinite(S[k]));
  }

  // Maximum lift at the nose: the best sample refined by golden-section search between its
  // neighbours, and the nose itself.
  {
    double best_x = 0.0, best = law.at(0.0).lift;
    for (std::size_t p = 0; p + 1 < knots.size(); ++p)
      for (int i = 0; i < per_piece; ++i) {
        const double phi = knots[p] + (knots[p + 1] - knots[p]) * (i + 0.5) / per_piece;
        if (law.at(phi).lift > best) best = law.at(phi).lift, best_x = phi;
      }
    const double step = (e - b) / per_piece;
    double lo = std::max(b, best_x - step), hi = std::min(e, best_x + step);
    const double g = 0.5 * (std::sqrt(5.0) - 1.0);
    for (int it = 0; it < 80; ++it) {
      const double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo);
      if (law.at(x1).lift > law.at(x2).lift) hi = x2; else lo = x1;
    }
    max_h = std::max(best, law.at(0.5 * (lo + hi)).lift);
  }
  CHECK(max_h == Approx(s.max_lift).epsilon(c.lift_tolerance).margin(0.0));
  CHECK(law.max_lift() == Approx(max_h).epsilon(std::max(c.lift_tolerance, 1e-9)).margin(0.0));
  if (c.peak_at_nose) CHECK(law.at(0.0).lift == Approx(max_h).epsilon(std::max(c.lift_tolerance, 1e-9)).margin(0.0));

  // Symmetry about the nose.
  if (c.symmetric) {
    for (int i = 1; i < 400; ++i) {
      const double phi = e * i / 400.0;
      const LiftDerivatives r = law.at(phi), l = law.at(-phi);
      INFO("symmetry at +-" << phi / deg << " deg");
      CHECK(l.lift == Approx(r.lift).epsilon(1e-9).margin(1e-9 * S[0]));
      CHECK(l.velocity == Approx(-r.velocity).epsilon(1e-9).margin(1e-9 * S[1]));
      CHECK(l.acceleration == Approx(r.acceleration).epsilon(1e-9).margin(1e-9 * S[2]));
      CHECK(l.jerk == Approx(-r.jerk).epsilon(1e-9).margin(1e-9 * S[3]));
    }
  }

  // Continuity at every knot (breakpoints and event ends).
  const int order = promised_continuity(c, s);
  const double dk = 1e-9 * (e - b);
  for (double k : knots) {
    const LiftDerivatives l = law.at(k - dk), r = law.at(k + dk);
    for (int o = 0; o <= order; ++o) {
      INFO(names[o] << " continuity at " << k / deg << " deg (promised up to " << names[order] << ")");
      CHECK(component(r, o) == Approx(component(l, o)).epsilon(0.0).margin(1e-6 * S[o]));
    }
  }

  // Exact derivatives against Richardson-extrapolated central differences, inside the pieces.
  // Three steps (1e-3, 1e-4, 1e-5 of the piece): the large one for laws whose internal magnitudes
  // (e.g. a 1 m base radius) leave rounding noise far above the lift's own scale, the small ones
  // for laws smooth only to C4 (an interpolated table); the closest of the three must agree.
  for (std::size_t p = 0; p + 1 < knots.size(); ++p) {
    const double a0 = knots[p], a1 = knots[p + 1];
    for (int i = 0; i <= 24; ++i) {
      const double phi = a0 + (a1 - a0) * (0.05 + 0.9 * i / 24.0);
      const LiftDerivatives d = law.at(phi);
      auto central = [&](double step, int o) {
        return (component(law.at(phi + step), o) - component(law.at(phi - step), o)) / (2.0 * step);
      };
      for (int o = 0; o < 3; ++o) {
        const double exact = component(d, o + 1);
        double numeric = 0.0, best = std::numeric_limits<double>::infinity();
        for (double fraction : {1e-3, 1e-4, 1e-5}) {
          const double h = fraction * (a1 - a0);
          const double value = (4.0 * central(0.5 * h, o) - central(h, o)) / 3.0;
          if (std::abs(value - exact) < best) best = std::abs(value - exact), numeric = value;
        }
        INFO("d/dphi " << names[o] << " vs " << names[o + 1] << " at " << phi / deg << " deg");
        CHECK(exact == Approx(numeric).epsilon(1e-6).margin(1e-6 * S[o + 1]));
      }
    }
  }

  // The summary outputs against the dense sampling (which can only under-estimate an extremum).
  const auto& out = outputs.all();
  for (const auto& [name, value] : out) {
    if (value.kind() != ValueKind::scalar) continue;
    INFO("output " << name);
    CHECK(std::isfinite(value.as_scalar()));
  }
  const double out_v = out.at("max_velocity").as_scalar();
  const double out_amax = out.at("max_acceleration").as_scalar();
  const double out_amin = out.at("min_acceleration").as_scalar();
  CHECK(out_v >= max_v * (1.0 - 1e-12));
  CHECK(out_v == Approx(max_v).epsilon(1e-5).margin(1e-9 * S[1]));
  CHECK(out_amax >= max_a - 1e-12 * S[2]);
  CHECK(out_amax == Approx(max_a).epsilon(1e-5).margin(1e-6 * S[2]));
  CHECK(out_amin <= min_a + 1e-12 * S[2]);
  CHECK(out_amin == Approx(min_a).epsilon(1e-5).margin(1e-6 * S[2]));
  CHECK(out.at("min_curvature_radius").as_scalar() > 0.0);

  // accel_angle: from the start of lift to the end of the first positive-acceleration phase
  // (the first + to - change of sign of h'' after h'' has been positive).
  bool positive = false;
  double change = std::numeric_limits<double>::quiet_NaN(), spacing = 0.0;
  for (std::size_t i = 0; i < accel_samples.size(); ++i) {
    const double a = accel_samples[i].second;
    if (a > 0.0) positive = true;
    if (positive && a < 0.0) {
      change = accel_samples[i].first;
      spacing = accel_samples[i].first - accel_samples[i - 1].first;
      break;
    }
  }
  if (std::isfinite(change)) {
    INFO("h'' first changes sign near " << change / deg << " deg");
    CHECK(out.at("accel_angle").as_scalar() == Approx(change - b).epsilon(0.0).margin(1.01 * spacing));
  }
}

void run(const NodeType& type, const ConformanceCase& c, const Scenario& s) {
  std::map<std::string, std::string> values = common_params(s);
  for (const auto& [name, text] : c.params(s)) values[name] = text;
  struct RemoveScenarioFiles {
    const std::map<std::string, std::string>& values;
    ~RemoveScenarioFiles() {
      for (const auto& [name, text] : values)
        if (is_scenario_file(text)) {
          std::error_code ignored;
          std::filesystem::remove(text, ignored);
        }
    }
  } remove_files{values};
  InputSet inputs;
  if (c.inputs) c.inputs(s, inputs);
  const NodeInfo& info = type.info();

  if (s.must_fail) {
    try {
      evaluate_node(type, values, inputs);
      FAIL("expected a NodeError for this infeasible design, the node succeeded");
    } catch (const NodeError& error) {
      INFO("NodeError(" << error.parameter() << "): " << error.what());
      CHECK(std::string(error.what()).size() > 10);
      CHECK((info.find_param(error.parameter()) != nullptr || info.find_input(error.parameter()) != nullptr));
      if (!s.expected_parameter.empty()) CHECK(error.parameter() == s.expected_parameter);
    }
    return;
  }

  Evaluation result;
  try {
    result = evaluate_node(type, values, inputs);
  } catch (const NodeError& error) {
    INFO("NodeError(" << error.parameter() << "): " << error.what());
    CHECK((info.find_param(error.parameter()) != nullptr || info.find_input(error.parameter()) != nullptr));
    if (c.may_fail.count(s.name)) {
      WARN(info.type << " refuses scenario " << s.name << " (allowed): " << error.what());
      return;
    }
    FAIL(info.type << " refused scenario " << s.name << " with NodeError(" << error.parameter()
                   << "): " << error.what());
  }
  CHECK(result.context.work["evaluations"] > 0.0);
  check_law(*result.law, result.outputs, c, s);
  // The SDK's kit (what `mechgraph plugin-test` and plugin authors run) agrees on every scenario.
  mechgraph::testing::CamLawCheckOptions kit;
  kit.continuity = promised_continuity(c, s);
  kit.samples_per_piece = 400;
  const mechgraph::testing::Report report = mechgraph::testing::check_cam_law(*result.law, "cam_law", kit);
  INFO(report.str());
  CHECK(report.passed());
}

}  // namespace

TEST_CASE("every cam node type has a conformance case", "[cams][conformance]") {
  const NodeTypeList types = all_cam_types();
  REQUIRE(!types.empty());
  std::set<std::string> seen;
  for (const auto& t : types) {
    const std::string& name = t->info().type;
    INFO("node type " << name);
    CHECK(seen.insert(name).second);  // no duplicates
    if (!find_case(name)) FAIL_CHECK("no conformance case for " << name << ": add one to cam_conformance_cases.hpp");
  }
  for (const auto& c : conformance_cases())
    if (!find_type(types, c.type)) WARN("conformance case " << c.type << " has no registered node type (yet)");
}

TEST_CASE("cam node types conform to the CamLaw contract", "[cams][conformance]") {
  const NodeTypeList types = all_cam_types();
  for (const auto& t : types) {
    const ConformanceCase* c = find_case(t->info().type);
    if (!c) continue;  // reported by the test case above
    for (const Scenario& s : conformance_scenarios()) {
      DYNAMIC_SECTION(t->info().type << " / " << s.name) { run(*t, *c, s); }
    }
  }
}
