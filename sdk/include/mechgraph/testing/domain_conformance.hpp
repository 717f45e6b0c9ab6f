#pragma once
// Conformance suites of the spring, fit and free-play interfaces (mechgraph/domain/spring.hpp,
// fit.hpp, tolerance.hpp): what any implementation must keep, whatever its model.
#include <mechgraph/domain/fit.hpp>
#include <mechgraph/domain/spring.hpp>
#include <mechgraph/domain/tolerance.hpp>
#include <mechgraph/errors.hpp>
#include <mechgraph/testing/cam_law_conformance.hpp>
#include <mechgraph/testing/report.hpp>

#include <cmath>
#include <string>
#include <vector>

namespace mechgraph::testing {

/// A sized spring: finite positive figures, force rising with deflection, stiffness the derivative
/// of the force (Richardson differences), stress within the allowable over the stroke, coils that fit.
inline Report check_spring(const Spring& s, const std::string& suite = "spring") {
  using detail::num;
  Report r;
  const double stroke = s.stroke();
  r.add(suite, "stroke, mass, surge frequency and allowable stress positive and finite",
        std::isfinite(stroke) && stroke > 0 && std::isfinite(s.mass()) && s.mass() > 0 && std::isfinite(s.surge_frequency()) &&
            s.surge_frequency() > 0 && std::isfinite(s.allowable_stress()) && s.allowable_stress() > 0,
        "stroke " + num(stroke) + " m, mass " + num(s.mass()) + " kg, surge " + num(s.surge_frequency()) + " Hz");
  if (!(std::isfinite(stroke) && stroke > 0)) return r;
  r.add(suite, "effective mass in (0, mass]", s.effective_mass() > 0 && s.effective_mass() <= s.mass() * (1 + 1e-12),
        num(s.effective_mass()) + " kg of " + num(s.mass()) + " kg");
  std::string bad_force, bad_stiffness, bad_stress;
  double previous = -INFINITY;
  for (int i = 0; i <= 20; ++i) {
    const double x = stroke * i / 20.0;
    const double f = s.force(x), k = s.stiffness(x), tau = s.stress(x);
    if (!std::isfinite(f) || !(f > 0) || f < previous) bad_force = "force " + num(f) + " N at " + num(x) + " m";
    previous = f;
    // Differences stay inside [0, stroke] (the interface's domain): one-sided second order at the
    // ends, Richardson-extrapolated central differences inside.
    const double h = 1e-3 * stroke;
    double numeric = 0.0;
    if (i == 0 || i == 20) {
      const double sgn = i == 0 ? 1.0 : -1.0;
      numeric = sgn * (-3.0 * s.force(x) + 4.0 * s.force(x + sgn * h) - s.force(x + 2.0 * sgn * h)) / (2.0 * h);
    } else {
      const double c1 = (s.force(x + h) - s.force(x - h)) / (2 * h), c2 = (s.force(x + h / 2) - s.force(x - h / 2)) / h;
      numeric = (4 * c2 - c1) / 3;
    }
    if (!std::isfinite(k) || std::abs(k - numeric) > 1e-5 * std::abs(numeric) + 1e-9 * std::abs(s.max_force() / stroke))
      bad_stiffness = "at " + num(x) + " m: stiffness " + num(k) + " N/m, differences " + num(numeric) + " N/m";
    if (!std::isfinite(tau) || tau < 0 || tau > s.allowable_stress() * (1 + 1e-9))
      bad_stress = "stress " + num(tau) + " Pa at " + num(x) + " m, allowable " + num(s.allowable_stress()) + " Pa";
  }
  r.add(suite, "force positive and rising over the stroke", bad_force.empty(), bad_force);
  r.add(suite, "stiffness is the derivative of the force", bad_stiffness.empty(), bad_stiffness);
  r.add(suite, "stress within the allowable over the stroke", bad_stress.empty(), bad_stress);
  std::string bad_coil;
  const auto coils = s.coils();
  for (const CoilGeometry& c : coils)
    if (!(c.wire_diameter > 0 && c.mean_diameter > c.wire_diameter && c.active_coils >= 1 && c.total_coils >= c.active_coils &&
          c.solid_length > 0 && c.free_length > c.solid_length && c.rate > 0))
      bad_coil = "wire " + num(c.wire_diameter) + " m, mean diameter " + num(c.mean_diameter) + " m, " + num(c.active_coils) +
                 " active coils, solid " + num(c.solid_length) + " m, free " + num(c.free_length) + " m";
  r.add(suite, "coil geometry consistent", !coils.empty() && bad_coil.empty(), coils.empty() ? "no coils" : bad_coil);
  // The dynamics stop the valve where the first coil goes solid: never inside the working stroke.
  const double solid = s.solid_deflection();
  r.add(suite, "not solid before full stroke", !(solid <= stroke),
        "solid at " + num(solid) + " m of deflection, stroke " + num(stroke) + " m");
  return r;
}

/// A spring model: sizes a spring for a reference valve-spring line and checks that spring
/// reproduces the line; a model that cannot size it must say why with a NodeError.
inline Report check_spring_model(const SpringModel& m, const std::string& suite = "spring_model") {
  using detail::num;
  Report r;
  const std::vector<SpringLine> lines{{300.0, 30e3, 10e-3}, {150.0, 15e3, 8e-3}, {600.0, 60e3, 12e-3}};
  std::vector<std::string> refusals;
  for (const SpringLine& line : lines) {
    std::shared_ptr<const Spring> spring;
    try {
      spring = m.size(line);
    } catch (const NodeError& e) {
      refusals.push_back(e.parameter() + ": " + e.what());
      continue;
    } catch (const std::exception& e) {
      r.add(suite, "refuses what it cannot size with a NodeError", false, std::string("threw another exception: ") + e.what());
      return r;
    }
    const std::string what = "line " + num(line.preload) + " N + " + num(line.rate) + " N/m over " + num(line.stroke) + " m";
    r.add(suite, "sizes a spring for the " + what, spring != nullptr);
    if (!spring) return r;
    const double f0 = spring->force(0.0), f1 = spring->force(line.stroke);
    r.add(suite, "the sized spring gives the line", std::abs(f0 - line.preload) <= 1e-6 * line.max_force() &&
                                                        std::abs(f1 - line.max_force()) <= 1e-6 * line.max_force(),
          "preload " + num(f0) + " N, at full stroke " + num(f1) + " N");
    r.append(check_spring(*spring, suite + " -> spring"));
    return r;
  }
  std::string why;
  for (const auto& s : refusals) why += (why.empty() ? "" : "; ") + s;
  r.skip(suite, "sizing a reference line", "its defaults size none of the reference lines (each refused with a NodeError: " + why + ")");
  return r;
}

/// A fit: limits finite and ordered, the clearance's limits and term consistent.
inline Report check_fit(const Fit& f, const std::string& suite = "fit") {
  using detail::num;
  Report r;
  const bool finite = std::isfinite(f.nominal()) && std::isfinite(f.hole().upper) && std::isfinite(f.hole().lower) &&
                      std::isfinite(f.shaft().upper) && std::isfinite(f.shaft().lower);
  r.add(suite, "nominal size positive, deviations finite", finite && f.nominal() > 0, "nominal " + num(f.nominal()) + " m");
  r.add(suite, "upper deviations not below the lower ones", f.hole().upper >= f.hole().lower && f.shaft().upper >= f.shaft().lower);
  r.add(suite, "clearance limits ordered and the mean between them",
        f.clearance_min() <= f.clearance_mean() && f.clearance_mean() <= f.clearance_max(),
        num(f.clearance_min()) + " .. " + num(f.clearance_max()) + " m");
  const PlayTerm t = f.clearance_term();
  r.add(suite, "clearance term reproduces the clearance limits",
        std::abs(t.lower() - f.clearance_min()) <= 1e-12 + 1e-9 * std::abs(f.clearance_min()) &&
            std::abs(t.upper() - f.clearance_max()) <= 1e-12 + 1e-9 * std::abs(f.clearance_max()),
        "term " + num(t.lower()) + " .. " + num(t.upper()) + " m");
  return r;
}

/// A joint's free play: at least one term, links finite with non-negative half ranges, the play's
/// limits ordered and not negative.
inline Report check_joint_play(const JointPlay& j, const std::string& suite = "joint_play") {
  using detail::num;
  Report r;
  r.add(suite, "names its joint and has play terms", !j.joint().empty() && !j.terms().empty(),
        std::to_string(j.terms().size()) + " terms");
  std::string bad;
  for (const PlayTerm& t : j.terms())
    for (const ToleranceLink& l : t.links)
      if (!std::isfinite(l.mean) || !std::isfinite(l.half_range) || l.half_range < 0 || !std::isfinite(l.sensitivity))
        bad = "link '" + l.label + "' of term '" + t.label + "'";
  r.add(suite, "links finite, half ranges not negative", bad.empty(), bad);
  r.add(suite, "play limits ordered and not negative", 0 <= j.play_min() && j.play_min() <= j.play_max(),
        num(j.play_min()) + " .. " + num(j.play_max()) + " m");
  return r;
}

}  // namespace mechgraph::testing
