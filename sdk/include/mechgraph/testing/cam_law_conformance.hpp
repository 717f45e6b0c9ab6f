#pragma once
// The CamLaw conformance suite (the contract of mechgraph/domain/cam_law.hpp), for any law: the
// host's own contract check (event bounds, breakpoints, radii, a coarse sampling), no NaN and no
// negative lift under dense sampling, max_lift() against the sampled maximum, continuity at the
// breakpoints and event ends, and each derivative against Richardson-extrapolated central
// differences of the one below, and the monotone runs a law declares (against dense sampling and
// the generic search). `mechgraph plugin-test` runs it on every cam_law a type outputs.
#include <mechgraph/domain/cam_law.hpp>
#include <mechgraph/domain/cam_law_runs.hpp>
#include <mechgraph/numerics/piecewise.hpp>
#include <mechgraph/node.hpp>
#include <mechgraph/testing/report.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

namespace mechgraph::testing {

struct CamLawCheckOptions {
  int samples_per_piece = 2000;  // dense sampling of each smooth piece
  /// Derivatives that must be continuous at the breakpoints and the event ends: 0 = the lift only
  /// (every law), 1 = also the velocity, ... (a constant-velocity ramp steps the velocity at the
  /// event's ends; a cycloidal law is continuous up to the acceleration).
  int continuity = 0;
  double derivative_tolerance = 1e-6;  // relative, and times the derivative's scale as the floor
  double max_lift_tolerance = 1e-6;    // relative, law.max_lift() against the sampled maximum
};

namespace detail {
inline double component(const LiftDerivatives& d, int k) {
  return k == 0 ? d.lift : k == 1 ? d.velocity : k == 2 ? d.acceleration : d.jerk;
}
inline const char* derivative_name(int k) {
  static const char* names[] = {"lift", "velocity", "acceleration", "jerk", "4th derivative"};
  return names[k];
}
inline std::string deg(double rad) {
  std::ostringstream o;
  o.precision(6);
  o << rad * 180.0 / std::numbers::pi << " deg";
  return o.str();
}
inline std::string num(double v) {
  std::ostringstream o;
  o.precision(6);
  o << v;
  return o.str();
}
}  // namespace detail

inline Report check_cam_law(const CamLaw& law, const std::string& suite = "cam_law", CamLawCheckOptions options = {}) {
  options.continuity = std::clamp(options.continuity, 0, 3);
  using detail::component;
  using detail::deg;
  using detail::num;
  constexpr double pi = std::numbers::pi;
  Report r;
  const std::string contract = law.contract_problem();
  r.add(suite, "the host's contract check", contract.empty(), contract);
  // The contract check covers the event's bounds and the breakpoints; the dense checks below need both.
  const double b = law.event_begin(), e = law.event_end();
  const std::vector<double> bps = law.breakpoints();
  const bool bounds = std::isfinite(b) && std::isfinite(e) && b > -pi && e < pi && b < e;
  const bool ascending = std::adjacent_find(bps.begin(), bps.end(), [](double x, double y) { return !(x < y); }) == bps.end();
  if (!bounds || !ascending || (!bps.empty() && !(bps.front() > b && bps.back() < e))) {
    if (contract.empty()) r.add(suite, "event and breakpoints usable", false, "event " + deg(b) + " to " + deg(e));
    return r;
  }
  std::vector<double> knots{b};
  knots.insert(knots.end(), bps.begin(), bps.end());
  knots.push_back(e);

  // Dense sampling of each piece, including the one-sided values at every knot.
  const int n = std::max(options.samples_per_piece, 8);
  double S[4] = {0, 0, 0, 0};
  double sampled_max = -std::numeric_limits<double>::infinity(), at_max = 0.0;
  double most_negative = 0.0, at_negative = 0.0;
  std::string nan_at;
  for (std::size_t p = 0; p + 1 < knots.size(); ++p) {
    const double a0 = knots[p], a1 = knots[p + 1];
    for (int i = -1; i <= n; ++i) {
      const double phi = i < 0 ? numerics::one_sided_point(a0, a1) : i == n ? numerics::one_sided_point(a1, a0) : a0 + (a1 - a0) * (i + 0.5) / n;
      const LiftDerivatives d = law.at(phi);
      for (int k = 0; k < 4; ++k) {
        if (!std::isfinite(component(d, k))) {
          if (nan_at.empty()) nan_at = std::string(detail::derivative_name(k)) + " at " + deg(phi);
        } else {
          S[k] = std::max(S[k], std::abs(component(d, k)));
        }
      }
      if (d.lift > sampled_max) sampled_max = d.lift, at_max = phi;
      if (d.lift < most_negative) most_negative = d.lift, at_negative = phi;
    }
  }
  r.add(suite, "no NaN or Inf in " + std::to_string((knots.size() - 1) * (n + 2)) + " samples", nan_at.empty(),
        nan_at.empty() ? "" : "not finite: " + nan_at);
  if (!nan_at.empty()) return r;
  r.add(suite, "lift never negative", most_negative >= -1e-9 * S[0],
        most_negative < 0.0 ? "least " + num(most_negative) + " m at " + deg(at_negative) : "");

  // The maximum: best sample refined by golden-section search between its neighbours.
  {
    const double step = (e - b) / n;
    double lo = std::max(b, at_max - step), hi = std::min(e, at_max + step);
    const double g = 0.5 * (std::sqrt(5.0) - 1.0);
    for (int it = 0; it < 80; ++it) {
      const double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo);
      if (law.at(x1).lift > law.at(x2).lift) hi = x2;
      else lo = x1;
    }
    sampled_max = std::max(sampled_max, law.at(0.5 * (lo + hi)).lift);
    const double declared = law.max_lift();
    r.add(suite, "max_lift() is the sampled maximum", std::abs(declared - sampled_max) <= options.max_lift_tolerance * sampled_max,
          "declared " + num(declared) + " m, sampled " + num(sampled_max) + " m at " + deg(at_max));
  }

  // Continuity at the knots: the lift always, the derivatives up to options.continuity.
  {
    const double dk = 1e-9 * (e - b);
    int continuous_to = 3;  // the highest order continuous at every knot (measured, reported)
    std::string bad;
    for (double k : knots) {
      const LiftDerivatives left = law.at(k - dk), right = law.at(k + dk);
      for (int o = 0; o < 4; ++o) {
        const bool jump = std::abs(component(right, o) - component(left, o)) > 1e-6 * S[o] + 1e-300;
        if (jump) {
          continuous_to = std::min(continuous_to, o - 1);
          if (o <= options.continuity && bad.empty())
            bad = std::string(detail::derivative_name(o)) + " jumps at " + deg(k) + " from " + num(component(left, o)) +
                  " to " + num(component(right, o));
        }
      }
    }
    // The event's ends are knots: a lift that does not come back to zero there jumps (order 0 is
    // always checked, so continuous_to >= 0 whenever `bad` is empty).
    r.add(suite, "continuous at breakpoints and event ends up to the " + std::string(detail::derivative_name(options.continuity)),
          bad.empty(), bad.empty() ? "continuous up to the " + std::string(detail::derivative_name(continuous_to)) : bad);
  }

  // Exact derivatives against Richardson-extrapolated central differences inside each piece. Three
  // steps (1e-3, 1e-4, 1e-5 of the piece): the closest must agree (large steps for laws whose
  // internal magnitudes leave rounding noise, small ones for laws smooth only to C4).
  for (int o = 0; o < 3; ++o) {
    std::string bad;
    double worst = 0.0;
    for (std::size_t p = 0; p + 1 < knots.size() && bad.empty(); ++p) {
      const double a0 = knots[p], a1 = knots[p + 1];
      for (int i = 0; i <= 24; ++i) {
        const double phi = a0 + (a1 - a0) * (0.05 + 0.9 * i / 24.0);
        const double exact = component(law.at(phi), o + 1);
        auto central = [&](double h) { return (component(law.at(phi + h), o) - component(law.at(phi - h), o)) / (2.0 * h); };
        double best = std::numeric_limits<double>::infinity(), numeric = 0.0;
        for (double fraction : {1e-3, 1e-4, 1e-5}) {
          const double h = fraction * (a1 - a0);
          const double v = (4.0 * central(0.5 * h) - central(h)) / 3.0;
          if (std::abs(v - exact) < best) best = std::abs(v - exact), numeric = v;
        }
        const double allowed = options.derivative_tolerance * std::abs(numeric) + options.derivative_tolerance * S[o + 1];
        worst = std::max(worst, best / std::max(S[o + 1], 1e-300));
        if (best > allowed) {
          bad = "at " + deg(phi) + ": exact " + num(exact) + ", differences " + num(numeric);
          break;
        }
      }
    }
    r.add(suite, std::string(detail::derivative_name(o + 1)) + " is the derivative of the " + detail::derivative_name(o),
          bad.empty(), bad.empty() ? "largest difference " + num(worst) + " of its scale" : bad);
  }

  // Higher derivatives, where the law gives them.
  {
    double d4 = 0.0, d5 = 0.0;
    const double probe = 0.5 * (knots[0] + knots[1]);
    if (law.higher_derivatives(probe, d4, d5)) {
      std::string bad;
      for (std::size_t p = 0; p + 1 < knots.size() && bad.empty(); ++p) {
        const double a0 = knots[p], a1 = knots[p + 1];
        for (int i = 0; i <= 12; ++i) {
          const double phi = a0 + (a1 - a0) * (0.1 + 0.8 * i / 12.0);
          if (!law.higher_derivatives(phi, d4, d5)) continue;
          const double h = 1e-4 * (a1 - a0);
          const double numeric = (law.at(phi + h).jerk - law.at(phi - h).jerk) / (2.0 * h);
          if (!std::isfinite(d4) || !std::isfinite(d5) || std::abs(numeric - d4) > 1e-4 * (std::abs(d4) + S[3] / (e - b))) {
            bad = "at " + deg(phi) + ": d4 " + num(d4) + ", differences of the jerk " + num(numeric);
            break;
          }
        }
      }
      r.add(suite, "4th derivative (higher_derivatives) is the derivative of the jerk", bad.empty(), bad);
    } else {
      r.skip(suite, "4th derivative (higher_derivatives)", "the law does not give it");
    }
  }

  // Monotone runs (CamLaw::monotone_breaks), where the law declares them: each run, sampled
  // densely, must be monotone (to 1e-12 of the derivative's scale: rounding), and the run-based
  // extrema and crossings (cam_law_runs.hpp) must equal the generic certified search's.
  for (int o = 0; o < 3; ++o) {
    const std::string what = std::string("monotone runs of the ") + detail::derivative_name(o);
    std::vector<double> cuts;
    if (!law.monotone_breaks(o, cuts)) {
      r.skip(suite, what, "the law does not declare them");
      continue;
    }
    const auto runs = CamLawRuns::of(law, o);
    if (!runs) {
      r.add(suite, what, false, "the cuts are not ascending and strictly inside the event");
      continue;
    }
    std::vector<double> edges{b};
    edges.insert(edges.end(), cuts.begin(), cuts.end());
    edges.push_back(e);
    const double noise = 1e-12 * S[o] + 1e-300;
    std::string bad;
    for (std::size_t p = 0; p + 1 < edges.size() && bad.empty(); ++p) {
      const double a0 = edges[p], a1 = edges[p + 1];
      if (!numerics::has_interior(a0, a1)) continue;
      const double first = component(law.at(numerics::one_sided_point(a0, a1)), o),
                   last = component(law.at(numerics::one_sided_point(a1, a0)), o);
      const double direction = last >= first ? 1.0 : -1.0;
      double previous = first;
      for (int i = 1; i <= n && bad.empty(); ++i) {
        const double phi = i == n ? numerics::one_sided_point(a1, a0) : a0 + (a1 - a0) * i / n;
        const double v = component(law.at(phi), o);
        if (direction * (v - previous) < -noise)
          bad = "not monotone between " + deg(a0) + " and " + deg(a1) + ": " + num(previous) + " then " + num(v) + " at " + deg(phi);
        previous = v;
      }
    }
    if (bad.empty()) {
      // Against the generic search (numerics::SmoothPieces) over the law's smooth pieces.
      numerics::SmoothPieces pieces([&](double x, double* v, double*) { v[0] = component(law.at(x), o); }, 1, knots, 16);
      long evaluations = 0;
      const double run_max = runs->maximum(evaluations).value, run_min = runs->minimum(evaluations).value;
      const double gen_max = pieces.maximum(0).value, gen_min = pieces.minimum(0).value;
      const double tol = 1e-9 * S[o] + 1e-300;
      if (std::abs(run_max - gen_max) > tol || std::abs(run_min - gen_min) > tol)
        bad = "extrema from the runs " + num(run_min) + " .. " + num(run_max) + ", generic search " + num(gen_min) + " .. " + num(gen_max);
      // Crossings of a level between the extremes (the lift: 0.37 of it, acceleration: zero).
      const double level = o == 2 ? 0.0 : gen_min + 0.37 * (gen_max - gen_min);
      const auto from_runs = runs->directed_crossings(level, evaluations);
      const auto generic = pieces.directed_crossings(0, level);
      if (bad.empty() && from_runs.size() != generic.size())
        bad = std::to_string(from_runs.size()) + " crossings of " + num(level) + " from the runs, " +
              std::to_string(generic.size()) + " by the generic search";
      for (std::size_t i = 0; bad.empty() && i < generic.size(); ++i)
        if (std::abs(from_runs[i].first - generic[i].first) > 1e-9 * (e - b) || from_runs[i].second != generic[i].second)
          bad = "crossing " + std::to_string(i) + " of " + num(level) + " at " + deg(from_runs[i].first) + " from the runs, " +
                deg(generic[i].first) + " by the generic search";
    }
    r.add(suite, what, bad.empty(), bad);
  }

  // Closed-form integrals of h and h^2 (CamLaw::lift_integrals), where the law gives them: against
  // adaptive Gauss-Kronrod over the whole event and over two parts of it, to 1e-11 of the whole.
  {
    double i1 = 0.0, i2 = 0.0;
    if (!law.lift_integrals(b, e, i1, i2)) {
      r.skip(suite, "integrals of the lift and its square", "the law does not give them in closed form");
    } else {
      std::string bad;
      long evaluations = 0;
      const double whole1 = numerics::integrate_piecewise([&](double x) { return law.at(x).lift; }, knots, 1e-13, evaluations);
      const double whole2 =
          numerics::integrate_piecewise([&](double x) { const double h = law.at(x).lift; return h * h; }, knots, 1e-13, evaluations);
      const double parts[3][2] = {{b, e}, {b + 0.13 * (e - b), b + 0.71 * (e - b)}, {b + 0.002 * (e - b), e - 0.3 * (e - b)}};
      for (const auto& part : parts) {
        std::vector<double> k{part[0]};
        for (double x : knots)
          if (x > part[0] && x < part[1]) k.push_back(x);
        k.push_back(part[1]);
        const double q1 = numerics::integrate_piecewise([&](double x) { return law.at(x).lift; }, k, 1e-13, evaluations);
        const double q2 =
            numerics::integrate_piecewise([&](double x) { const double h = law.at(x).lift; return h * h; }, k, 1e-13, evaluations);
        if (!law.lift_integrals(part[0], part[1], i1, i2) || !(std::abs(i1 - q1) <= 1e-11 * std::abs(whole1)) ||
            !(std::abs(i2 - q2) <= 1e-11 * std::abs(whole2))) {
          bad = "over " + deg(part[0]) + " .. " + deg(part[1]) + ": closed form " + num(i1) + ", " + num(i2) + "; quadrature " +
                num(q1) + ", " + num(q2);
          break;
        }
      }
      r.add(suite, "integrals of the lift and its square", bad.empty(), bad);
    }
  }
  return r;
}

/// The peak outputs a cam node sets beside its law (the built-in convention: max_velocity [m/rad],
/// max_acceleration and min_acceleration [m/rad^2]) against the law sampled densely: never below
/// the samples (an extremum found is at least as large as any sample) and within 1e-5 of them.
/// Outputs a node does not set are not checked.
inline Report check_cam_peaks(const CamLaw& law, const OutputSet& outputs, const std::string& suite, int samples_per_piece = 4000) {
  using detail::num;
  Report r;
  const std::vector<double> knots = law.knots();
  double v = 0.0, a_max = -std::numeric_limits<double>::infinity(), a_min = std::numeric_limits<double>::infinity(), scale = 0.0;
  for (std::size_t p = 0; p + 1 < knots.size(); ++p)
    for (int i = -1; i <= samples_per_piece; ++i) {
      const double a0 = knots[p], a1 = knots[p + 1];
      const double phi = i < 0 ? numerics::one_sided_point(a0, a1)
                         : i == samples_per_piece ? numerics::one_sided_point(a1, a0)
                                                  : a0 + (a1 - a0) * (i + 0.5) / samples_per_piece;
      const LiftDerivatives d = law.at(phi);
      v = std::max(v, std::abs(d.velocity));
      a_max = std::max(a_max, d.acceleration);
      a_min = std::min(a_min, d.acceleration);
      scale = std::max(scale, std::abs(d.acceleration));
    }
  auto compare = [&](const char* name, double sampled, double floor_scale, bool is_max) {
    const auto it = outputs.all().find(name);
    if (it == outputs.all().end() || it->second.kind() != ValueKind::scalar) return;
    const double out = it->second.as_scalar();
    const bool beyond = is_max ? out >= sampled - 1e-12 * floor_scale : out <= sampled + 1e-12 * floor_scale;
    const bool close = std::abs(out - sampled) <= 1e-5 * std::abs(sampled) + 1e-9 * floor_scale;
    r.add(suite, std::string("output ") + name + " is the law's extremum", beyond && close,
          "output " + num(out) + ", dense sampling " + num(sampled));
  };
  compare("max_velocity", v, v, true);
  compare("max_acceleration", a_max, scale, true);
  compare("min_acceleration", a_min, scale, false);
  return r;
}

}  // namespace mechgraph::testing
