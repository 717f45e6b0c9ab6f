// Stage 4 of the valve-train study: masses, spring design by both rules, the harmonic screen.
// Each result is checked against a second method: brute-force sampling of the requirement,
// quadrature of the Fourier integrals, hand formulas, a published example.
#include "test_support.hpp"
#include "train_masses.hpp"

#include <mechgraph/domain/valve_motion.hpp>
#include <mechgraph/errors.hpp>
#include <mechgraph/numerics/piecewise.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

using namespace mechgraph;
using namespace mechgraph::testing;
using Catch::Matchers::Contains;
using Catch::Matchers::WithinAbs;
using Catch::Matchers::WithinRel;

namespace {

// The study's Kurz cam and valve train; `design` and `extra` add to the spring_design node and scene.
std::string stage4_scene(const std::string& design = "", const std::string& extra = "") {
  return R"(
params: { rpm: 5600 rpm }
nodes:
  cam:    { type: cam.kurz, params: { max_lift: 8 mm, action_angle: 130 deg, accel_angle: 18 deg, base_radius: 17 mm } }
  v:      { type: valvetrain.valve_motion, inputs: { cam: cam.law }, params: { rpm: $rpm, rocker_ratio: 1.5, lash: 0.25 mm } }
  train:  { type: valvetrain.masses, params: { valve_mass: 55 g, retainer_mass: 18 g, tappet_mass: 60 g, pushrod_mass: 50 g,
                                               rocker_inertia: 4e-5 kg*m^2, arm_valve: 45 mm, arm_pushrod: 30 mm } }
  spring: { type: spring.helical }
  sd:     { type: valvetrain.spring_design, inputs: { valve: v.motion, spring: spring.model, masses: train.masses },
            params: { safety_factor: 1.5 )" + design + R"( } }
  res:    { type: valvetrain.resonance, inputs: { valve: v.motion, design: sd.design }, params: { drive_stiffness: 4000 N/mm } }
)" + extra + R"(
outputs: [ v.motion, v.min_acceleration, train.mass_without_spring, sd.spring, sd.design, sd.max_force, sd.preload,
           sd.stiffness, sd.reduced_mass, sd.force_curve, sd.spring_mass, sd.envelope_margin, sd.min_safety_factor, sd.iterations,
           res.omega0, res.harmonic, res.force_amplitude, res.next_force_amplitude, res.vibration_amplitude,
           res.distortion_percent, res.lift_rms, res.damping_coefficient, res.worst_distortion_percent ]
)";
}

RunResult run(const std::string& yaml) { return run_yaml(yaml, project_registry()); }

double num(const RunResult& r, const std::string& label) { return scalar_output(r, label); }

template <class T>
std::shared_ptr<const T> handle(const RunResult& r, const std::string& label) {
  return std::dynamic_pointer_cast<const T>(output(r, label).as_handle());
}

// max over the open period of f, by brute force on a fine uniform grid (the second method).
template <class F>
double dense_max(const ValveMotion& v, F f, int n = 200001) {
  double best = -1e300;
  for (int i = 0; i <= n; ++i) best = std::max(best, f(v.open_begin() + (v.open_end() - v.open_begin()) * i / n));
  return best;
}

}  // namespace

TEST_CASE("valvetrain.masses: reduced to the valve by hand", "[valvetrain][stage4]") {
  const RunResult r = run(stage4_scene());
  // 55 + 18 g + 4e-5 / 0.045^2 + (50 + 60 g) (30/45)^2 = 73 + 19.75309 + 48.88889 g
  CHECK_THAT(num(r, "train.mass_without_spring"), WithinRel(0.073 + 4e-5 / (0.045 * 0.045) + 0.110 * 4.0 / 9.0, 1e-14));
}

TEST_CASE("valvetrain.masses: the Cam Design Handbook's OHV example", "[valvetrain][stage4]") {
  // Rothbart (ed.), Cam Design Handbook (2004), ch. 11, pushrod valve train: valve 0.0251 lbm, spring
  // 0.0153 lbm, pushrod 0.0114 lbm, lifter 0.0270 lbm, rocker 0.0132 lbm*in^2, arms 1.4875 in (valve)
  // and 0.875 in (pushrod), ratio 1.7. The book's equivalent mass at the lifter: 0.143 lbm; its
  // one-mass frequency with 660 lb/in at the lifter is sqrt(k/m) = 1335 rad/s = 212.5 Hz in
  // consistent units (the book prints 67 Hz, sqrt of lb/in over lbm without the unit factor g).
  const double lbm = 0.45359237, in = 0.0254, lbf_per_in = 4.4482216152605 / 0.0254;
  auto m = std::make_shared<valvetrain::TrainMasses>();
  m->valve = 0.0251 * lbm;
  m->pushrod = 0.0114 * lbm;
  m->tappet = 0.0270 * lbm;
  m->rocker_inertia = 0.0132 * lbm * in * in;
  m->arm_valve = 1.4875 * in;
  m->arm_pushrod = 0.875 * in;
  const double ratio = m->rocker_ratio();
  const double at_valve = m->without_spring() + 0.0153 * lbm / 3;
  const double at_lifter = at_valve * ratio * ratio;
  CHECK_THAT(at_lifter / lbm, WithinRel(0.143, 2e-3));
  const double k_valve = 660 * lbf_per_in / (ratio * ratio);
  CHECK_THAT(std::sqrt(k_valve / at_valve) / (2 * std::numbers::pi), WithinRel(212.5, 3e-3));
}

TEST_CASE("spring_design, free-length rule: tangent to K x inertia force, M_red at its fixed point", "[valvetrain][stage4]") {
  const RunResult r = run(stage4_scene());
  const auto v = handle<ValveMotion>(r, "v.motion");
  const auto spring = handle<Spring>(r, "sd.spring");
  const double K = 1.5, M = num(r, "sd.reduced_mass"), c = num(r, "sd.stiffness");
  const double h_max = 1.5 * 8e-3 - 0.25e-3, f0 = 2 * h_max, w = v->camshaft_speed();
  // Fixed point: M_red = M_ws + m_s / 3.
  CHECK_THAT(M, WithinRel(num(r, "train.mass_without_spring") + num(r, "sd.spring_mass") / 3, 1e-12));
  CHECK(num(r, "sd.iterations") >= 2);
  // The line passes through (-f0, 0) and P_max = c (f0 + h_max).
  CHECK_THAT(num(r, "sd.preload"), WithinRel(c * f0, 1e-14));
  CHECK_THAT(num(r, "sd.max_force"), WithinRel(c * (f0 + h_max), 1e-14));
  CHECK_THAT(spring->max_force(), WithinRel(c * (f0 + h_max), 1e-12));
  // Tangency, by brute force: the steepest ray from (-f0, 0) to the requirement K M |a(h)|.
  const double steepest = dense_max(*v, [&](double phi) {
    const double a = w * w * v->at(phi).acceleration;
    return a < 0 ? K * M * -a / (f0 + v->at(phi).lift) : 0.0;
  });
  CHECK(steepest <= c * (1 + 1e-12));
  CHECK_THAT(steepest, WithinRel(c, 1e-7));
  CHECK_THAT(num(r, "sd.envelope_margin"), WithinAbs(0.0, 1e-9 * num(r, "sd.max_force")));
  CHECK_THAT(num(r, "sd.min_safety_factor"), WithinRel(K, 1e-9));
}

TEST_CASE("spring_design, source rule: P_max = K M_red |a_min|, the margin away from the top", "[valvetrain][stage4]") {
  const RunResult r = run(stage4_scene(", rule: source, preload_ratio: 0.45"));
  const auto v = handle<ValveMotion>(r, "v.motion");
  const double K = 1.5, M = num(r, "sd.reduced_mass"), w = v->camshaft_speed();
  const double p_max = num(r, "sd.max_force"), p0 = num(r, "sd.preload"), c = num(r, "sd.stiffness");
  // a_min from valve_motion's own search (a second search, another node).
  CHECK_THAT(p_max, WithinRel(K * M * std::abs(num(r, "v.min_acceleration")), 1e-12));
  CHECK_THAT(p0, WithinRel(0.45 * p_max, 1e-14));
  CHECK_THAT(c, WithinRel((p_max - p0) / (1.5 * 8e-3 - 0.25e-3), 1e-14));
  // The margin and the least safety factor over the negative phase, by brute force.
  const double worst = -dense_max(*v, [&](double phi) {
    const double a = std::min(0.0, w * w * v->at(phi).acceleration);
    return -(p0 + c * v->at(phi).lift - K * M * -a);
  });
  CHECK(num(r, "sd.envelope_margin") <= worst + 1e-12 * p_max);
  CHECK_THAT(num(r, "sd.envelope_margin"), WithinAbs(worst, 1e-7 * p_max));
  const double least_sf = -dense_max(*v, [&](double phi) {
    const double a = w * w * v->at(phi).acceleration;
    return a < 0 ? -(p0 + c * v->at(phi).lift) / (M * -a) : -1e300;
  });
  CHECK_THAT(num(r, "sd.min_safety_factor"), WithinRel(least_sf, 1e-7));
}

TEST_CASE("spring_design force_curve: the spring line against K times the inertia force over the open period", "[valvetrain][stage4]") {
  // The curve the report plots: the line from the node's own preload and rate, the inertia force
  // from the valve's acceleration in time (read through the motion handle: a second path), the
  // requirement never above the free-length line and touching it near the tangent point.
  for (const char* rule : {"", ", rule: source, preload_ratio: 0.45"}) {
    INFO("rule" << rule);
    const RunResult r = run(stage4_scene(rule));
    const auto v = handle<ValveMotion>(r, "v.motion");
    const Table& t = output(r, "sd.force_curve").as_table();
    const double K = 1.5, M = num(r, "sd.reduced_mass"), p0 = num(r, "sd.preload"), c = num(r, "sd.stiffness");
    REQUIRE(t.axis.values.size() == 361);
    CHECK(t.axis.values.front() == v->open_begin());
    CHECK(t.axis.values.back() == v->open_end());
    const auto& lift = t.find("valve_lift")->values;
    const auto& spring = t.find("spring_force")->values;
    const auto& inertia = t.find("inertia_force")->values;
    const auto& required = t.find("required_force")->values;
    CHECK(t.find("spring_force")->dimension == dim::force);
    double least_gap = 1e300, most_required = 0.0;
    for (std::size_t i = 0; i < lift.size(); ++i) {
      const double phi = t.axis.values[i];
      CHECK_THAT(lift[i], WithinAbs(v->at(phi).lift, 1e-15));
      CHECK_THAT(spring[i], WithinRel(p0 + c * lift[i], 1e-13));
      CHECK_THAT(inertia[i], WithinAbs(M * v->acceleration_in_time(phi), 1e-9 * num(r, "sd.max_force")));
      CHECK_THAT(required[i], WithinAbs(K * std::max(0.0, -inertia[i]), 1e-9 * num(r, "sd.max_force")));
      least_gap = std::min(least_gap, spring[i] - required[i]);
      most_required = std::max(most_required, required[i]);
    }
    // The curve's least gap is the node's envelope margin, up to the grid missing the exact extremum.
    CHECK(least_gap >= num(r, "sd.envelope_margin") - 1e-9 * num(r, "sd.max_force"));
    CHECK(least_gap <= num(r, "sd.envelope_margin") + 2e-3 * num(r, "sd.max_force"));
    CHECK(most_required <= K * M * std::abs(num(r, "v.min_acceleration")) * (1 + 1e-12));
    CHECK_THAT(most_required, WithinRel(K * M * std::abs(num(r, "v.min_acceleration")), 1e-3));
  }
}

TEST_CASE("cam.contour loaded by spring_design's force_curve: the contact force where the valve is open, none on its seat", "[valvetrain][stage4]") {
  // The cam carries i (P0 + c x + M_red a) while the valve is open (x, a at the valve, i = 1.5 the
  // rocker ratio as load_ratio), nothing while it sits on its seat (the lash open).
  std::string yaml = stage4_scene("", R"(
  cut: { type: cam.contour, inputs: { cam: cam.law, forces: sd.force_curve },
         params: { follower: flat, load_ratio: 1.5, contact_length: 12 mm } })");
  yaml.replace(yaml.find("outputs: [ "), 11, "outputs: [ cut.contact, cut.max_contact_stress, ");
  const RunResult r = run(yaml);
  const auto v = handle<ValveMotion>(r, "v.motion");
  const double M = num(r, "sd.reduced_mass"), p0 = num(r, "sd.preload"), c = num(r, "sd.stiffness");
  const Table& t = output(r, "cut.contact").as_table();
  const auto& load = t.find("load")->values;
  int open = 0, closed = 0;
  for (std::size_t i = 0; i < load.size(); ++i) {
    const double phi = t.axis.values[i];
    if (phi <= v->open_begin() || phi >= v->open_end()) {
      ++closed;
      CHECK(load[i] == 0.0);
      continue;
    }
    ++open;
    // The force curve is linear between its 361 points: within the curvature of P0 + c x + M a.
    const double expected = 1.5 * (p0 + c * v->at(phi).lift + M * v->acceleration_in_time(phi));
    CHECK_THAT(load[i], WithinAbs(expected, 2e-3 * num(r, "sd.max_force")));
  }
  CHECK(open > 100);
  CHECK(closed > 10);
  CHECK(num(r, "cut.max_contact_stress") > 0.0);
}

TEST_CASE("resonance: omega0, the harmonic, F_k against quadrature, A_el and distortion", "[valvetrain][stage4]") {
  // The design is valvetrain's private object: read as C++ only where C++ objects cross as they
  // are, on the pre-1.0 entry (elsewhere it crosses as an opaque handle).
  const RunResult r = run_yaml(stage4_scene(), builtin_pre10_registry());
  const auto v = handle<ValveMotion>(r, "v.motion");
  const auto design = handle<valvetrain::SpringDesign>(r, "sd.design");
  const double c_d = 4e6, c_s = design->spring->stiffness(0), M = design->reduced_mass;
  const double omega0 = std::sqrt((c_s + c_d) / M);
  CHECK_THAT(num(r, "res.omega0"), WithinRel(omega0, 1e-14));
  const double k = std::floor(omega0 / v->camshaft_speed());
  CHECK(num(r, "res.harmonic") == k);
  // Second method: the Fourier integrals by adaptive quadrature between the motion's knots,
  // A_k = (c_d / pi) int x cos(k phi) dphi (the lift is zero outside the open period).
  long evaluations = 0;
  auto fourier = [&](double kk) {
    const double a = numerics::integrate_piecewise([&](double p) { return v->at(p).lift * std::cos(kk * p); }, v->knots(),
                                                   1e-13, evaluations);
    const double b = numerics::integrate_piecewise([&](double p) { return v->at(p).lift * std::sin(kk * p); }, v->knots(),
                                                   1e-13, evaluations);
    return c_d / std::numbers::pi * std::hypot(a, b);
  };
  // The 3600-point sum of a lift whose acceleration jumps: agreement to ~1e-5 of the fundamental.
  const double scale = fourier(1);
  CHECK_THAT(num(r, "res.force_amplitude"), WithinAbs(fourier(k), 1e-5 * scale));
  CHECK_THAT(num(r, "res.next_force_amplitude"), WithinAbs(fourier(k + 1), 1e-5 * scale));
  const double rms = std::sqrt(
      numerics::integrate_piecewise([&](double p) { return std::pow(v->at(p).lift, 2); }, v->knots(), 1e-13, evaluations) /
      (2 * std::numbers::pi));
  CHECK_THAT(num(r, "res.lift_rms"), WithinRel(rms, 1e-6));
  // A_el = F_k / (xi omega0), xi = 0.107 M_red omega0; distortion = 100 A_el / x_rms.
  CHECK_THAT(num(r, "res.damping_coefficient"), WithinRel(0.107 * M * omega0, 1e-14));
  CHECK_THAT(num(r, "res.vibration_amplitude"), WithinRel(num(r, "res.force_amplitude") / (0.107 * M * omega0 * omega0), 1e-13));
  CHECK_THAT(num(r, "res.distortion_percent"), WithinRel(100 * num(r, "res.vibration_amplitude") / num(r, "res.lift_rms"), 1e-13));
  CHECK(num(r, "res.worst_distortion_percent") >= num(r, "res.distortion_percent"));
}

TEST_CASE("stage 4 refuses inconsistent or impossible designs, naming the parameter", "[valvetrain][stage4]") {
  auto failure = [](const std::string& yaml) {
    try {
      run(yaml);
    } catch (const EvaluationError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  SECTION("the rocker of the masses and of the valve motion differ") {
    std::string yaml = stage4_scene();
    yaml.replace(yaml.find("arm_valve: 45 mm"), 16, "arm_valve: 50 mm");
    CHECK_THAT(failure(yaml), Contains("parameter 'masses'") && Contains("1.5") && Contains("1.66667") && Contains("disagree"));
  }
  SECTION("rule source needs one preload") {
    CHECK_THAT(failure(stage4_scene(", rule: source")), Contains("exactly one of preload"));
    CHECK_THAT(failure(stage4_scene(", rule: source, preload: 100 N, preload_ratio: 0.3")), Contains("exactly one of preload"));
    CHECK_THAT(failure(stage4_scene(", preload: 100 N")), Contains("belongs to rule source"));
    CHECK_THAT(failure(stage4_scene(", rule: source, preload: 5000 N")), Contains("not below P_max"));
  }
  SECTION("the spring model's own refusal names the model and its parameter") {
    std::string yaml = stage4_scene();
    yaml.replace(yaml.find("{ type: spring.helical }"), 24, "{ type: spring.helical, params: { installed_length: 30 mm } }");
    CHECK_THAT(failure(yaml), Contains("spring.helical, parameter 'installed_length'") && Contains("solid"));
  }
  SECTION("a spring heavier than the load it holds has no fixed point") {
    std::string yaml = stage4_scene();
    yaml.replace(yaml.find("safety_factor: 1.5"), 18, "safety_factor: 3");
    yaml.replace(yaml.find("{ type: spring.helical }"), 24,
                 "{ type: spring.helical, params: { density: 100000 kg/m^3, spring_index: 4 } }");
    CHECK_THAT(failure(yaml), Contains("parameter 'spring'") && Contains("runs away"));
  }
  SECTION("a drive too soft for any harmonic") {
    // A soft spring (P0 = 0.9 P_max, K = 1) on an almost massless drive: omega0 ~ 0.5 w_k.
    std::string yaml = stage4_scene(", rule: source, preload_ratio: 0.9");
    yaml.replace(yaml.find("safety_factor: 1.5"), 18, "safety_factor: 1");
    yaml.replace(yaml.find("drive_stiffness: 4000 N/mm"), 26, "drive_stiffness: 0.001 N/mm");
    CHECK_THAT(failure(yaml), Contains("parameter 'drive_stiffness'") && Contains("below the camshaft speed"));
  }
}
