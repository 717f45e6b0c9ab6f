#include <mechgraph/domain/cam_geometry.hpp>

#include <mechgraph/domain/cam_law_runs.hpp>
#include <mechgraph/errors.hpp>

#include <mechgraph/numerics/piecewise.hpp>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <limits>
#include <vector>

namespace mechgraph {
namespace {

// The end of the positive-acceleration phase: the first place where h'' falls through zero (it was
// positive just before, so a ramp's h'' = 0 or a table's tiny negative start does not end it).
double phase_end(numerics::SmoothPieces& pieces, std::size_t acceleration, double begin) {
  for (const auto& [x, rising] : pieces.directed_crossings(acceleration, 0.0))
    if (!rising) return x - begin;
  return 0.0;
}

}  // namespace

double positive_acceleration_phase(const CamLaw& law, int samples, long& evaluations) {
  if (const auto runs = CamLawRuns::of(law, 2)) {
    for (const auto& [x, rising] : runs->directed_crossings(0.0, evaluations))
      if (!rising) return x - law.event_begin();
    return 0.0;
  }
  const std::vector<double> knots = law.knots();
  numerics::SmoothPieces pieces([&](double x, double* v, double*) { v[0] = law.at(x).acceleration; }, 1, knots, samples);
  const double phase = phase_end(pieces, 0, law.event_begin());
  evaluations += pieces.work().evaluations;
  return phase;
}

double contour_curvature_radius(const CamLaw& law, double phi) { return contour_curvature_radius(law, phi, law.at(phi)); }

double contour_curvature_radius(const CamLaw& law, double, const LiftDerivatives& d) {
  const double rr = law.roller_radius();
  if (rr <= 0.0) return law.base_radius() + d.lift + d.acceleration;
  const double R = law.base_radius() + rr + d.lift;
  const double v2 = d.velocity * d.velocity;
  const double r2 = R * R + v2;
  const double rho_pitch = r2 * std::sqrt(r2) / (R * R + 2.0 * v2 - R * d.acceleration);  // (R^2 + h'^2)^(3/2) / (...)
  return rho_pitch - rr;
}

// A certificate that the flat-follower contour has no undercut, without its minimum: on an interval
// where h and h'' are both monotone (the law's runs of order 0 and 2), rho = r0 + h + h'' is at
// least r0 + min(h at the ends) + min(h'' at the ends); intervals whose bound is not positive are
// halved (the bound tightens with the width). True once every interval is proven, false when the
// law has no runs, a roller follows it, or 400 evaluations do not settle it (the caller then
// computes the minimum itself).
bool flat_contour_certainly_convex(const CamLaw& law, long& evaluations) {
  if (law.roller_radius() > 0.0) return false;
  std::vector<double> cuts0, cuts2;
  if (!law.monotone_breaks(0, cuts0) || !law.monotone_breaks(2, cuts2)) return false;
  std::vector<double> cuts{law.event_begin(), law.event_end()};
  cuts.insert(cuts.end(), cuts0.begin(), cuts0.end());
  cuts.insert(cuts.end(), cuts2.begin(), cuts2.end());
  std::sort(cuts.begin(), cuts.end());
  cuts.erase(std::unique(cuts.begin(), cuts.end()), cuts.end());
  const double r0 = law.base_radius();
  // The lift may dip to -1e-9 max_lift by the contract: counted against the bound.
  const double slack = 1e-9 * law.max_lift();
  struct End {
    double x, h, a;
  };
  long budget = 400;
  auto read = [&](double x) {
    const LiftDerivatives d = law.at(x);
    --budget;
    ++evaluations;
    return End{x, d.lift, d.acceleration};
  };
  for (std::size_t k = 0; k + 1 < cuts.size(); ++k) {
    const double lo = cuts[k], hi = cuts[k + 1];
    if (!numerics::has_interior(lo, hi)) continue;  // no angle of its own
    std::vector<std::pair<End, End>> pending{{read(numerics::one_sided_point(lo, hi)), read(numerics::one_sided_point(hi, lo))}};
    while (!pending.empty()) {
      const auto [l, r] = pending.back();
      pending.pop_back();
      if (r0 + std::min(l.h, r.h) + std::min(l.a, r.a) - slack > 0.0) continue;
      if (budget <= 0) return false;
      const End m = read(0.5 * (l.x + r.x));
      if (!(r0 + m.h + m.a > 0.0)) return false;  // a point with rho <= 0: not convex, let the caller measure it
      pending.push_back({l, m});
      pending.push_back({m, r});
    }
  }
  return true;
}

CamSummary summarize(const CamLaw& law, int samples) { return summarize(law, samples, true); }

CamSummary summarize(const CamLaw& law, int samples, bool exact_curvature) {
  return summarize(law, samples, CamSummaryParts{true, true, exact_curvature});
}

CamSummary summarize(const CamLaw& law, int samples, const CamSummaryParts& parts) {
  const bool exact_curvature = parts.curvature;
  CamSummary s;
  const std::vector<double> knots = law.knots();
  const std::span<const double> k(knots);
  const auto velocity_runs = CamLawRuns::of(law, 1);
  const auto acceleration_runs = CamLawRuns::of(law, 2);
  if (velocity_runs && acceleration_runs) {
    // The law's monotone runs (closed form, mechgraph/domain/cam_law_runs.hpp): the peaks at run
    // ends, the end of the positive phase by TOMS 748 in its run; only the contour's curvature
    // needs the interpolation below.
    // Only the parts asked for (a sweep that reads none of them still gets its undercut check).
    if (parts.peaks) {
      const auto peaks = CamLawRuns::peaks({&*velocity_runs, &*acceleration_runs}, law.event_begin(), law.event_end(),
                                           s.evaluations);
      s.max_velocity = std::max(peaks[0].max.value, -peaks[0].min.value);
      s.max_acceleration = peaks[1].max.value;
      s.min_acceleration = peaks[1].min.value;
    } else {
      s.peaks_known = false;
    }
    s.accel_angle = 0.0;
    if (parts.phase) {
      for (const auto& [x, rising] : acceleration_runs->directed_crossings(0.0, s.evaluations))
        if (!rising) {
          s.accel_angle = x - law.event_begin();
          break;
        }
    } else {
      s.phase_known = false;
    }
    if (!exact_curvature && flat_contour_certainly_convex(law, s.evaluations)) {
      s.curvature_exact = false;
      s.min_curvature_radius = law.base_radius();  // proven positive; the minimum itself was not asked for
    } else {
      numerics::SmoothPieces curvature(
          [&](double x, double* v, double*) { v[0] = contour_curvature_radius(law, x, law.at(x)); }, 1, k, samples);
      s.min_curvature_radius = curvature.minimum(0).value;
      s.evaluations += curvature.work().evaluations;
    }
  } else {
    // Velocity, acceleration and the contour's curvature from one interpolation of each smooth
    // piece (certified: numerics/piecewise.hpp); |h'| is the larger of h''s two signed extremes.
    numerics::SmoothPieces pieces(
        [&](double x, double* v, double*) {
          const LiftDerivatives d = law.at(x);
          v[0] = d.velocity;
          v[1] = d.acceleration;
          v[2] = contour_curvature_radius(law, x, d);
        },
        3, k, samples);
    s.max_velocity = std::max(pieces.maximum(0).value, -pieces.minimum(0).value);
    s.max_acceleration = pieces.maximum(1).value;
    s.min_acceleration = pieces.minimum(1).value;
    s.accel_angle = phase_end(pieces, 1, law.event_begin());
    s.min_curvature_radius = pieces.minimum(2).value;
    s.evaluations += pieces.work().evaluations;
  }
  // The contour's curvature is checked around the whole cam: on the base circle it is r0 (flat)
  // or r0 (roller contour) and inside the event it varies.
  s.min_curvature_radius = std::min(s.min_curvature_radius, law.base_radius());
  return s;
}

std::optional<double> smallest_undercut_free_base_radius(
    const std::function<std::shared_ptr<const CamLaw>(double base_radius)>& law_for_base_radius, double base_radius,
    int samples) {
  // The smallest radius of curvature grows with the base radius, so the limit is bracketed and bisected.
  auto feasible = [&](double r0) {
    try {
      const auto law = law_for_base_radius(r0);
      return law && summarize(*law, samples).min_curvature_radius > 0.0;
    } catch (const NodeError&) {
      return false;
    }
  };
  if (!(base_radius > 0.0) || !std::isfinite(base_radius)) return std::nullopt;
  double low = base_radius, high = base_radius;
  while (!feasible(high)) {
    low = high;
    high *= 1.5;
    if (high > 1000.0 * base_radius) return std::nullopt;
  }
  while (high - low > 1e-6) {
    const double mid = 0.5 * (low + high);
    if (mid == low || mid == high) break;  // neighbouring doubles: as close as it gets
    (feasible(mid) ? high : low) = mid;
  }
  return high;
}

void refuse_undercut(const CamSummary& summary, double base_radius,
                     const std::function<std::shared_ptr<const CamLaw>(double base_radius)>& law_for_base_radius,
                     int samples) {
  if (summary.min_curvature_radius > 0.0) return;
  std::ostringstream msg;
  msg << "the cam contour is undercut: its smallest radius of curvature is " << summary.min_curvature_radius * 1e3
      << " mm (must be > 0); ";
  if (!law_for_base_radius) {
    msg << "raise base_radius or soften the law";
  } else if (const auto r_min = smallest_undercut_free_base_radius(law_for_base_radius, base_radius, samples)) {
    msg << "base_radius must be at least " << *r_min * 1e3 << " mm for this law and follower, or soften the law";
  } else {
    msg << "no base_radius up to " << base_radius * 1e6 << " mm removes it: soften the law";
  }
  throw NodeError("base_radius", msg.str());
}

}  // namespace mechgraph
