#include <mechgraph/domain/cam_geometry.hpp>

#include <mechgraph/errors.hpp>

#include <mechgraph/numerics/piecewise.hpp>

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

CamSummary summarize(const CamLaw& law, int samples) {
  CamSummary s;
  const std::vector<double> knots = law.knots();
  const std::span<const double> k(knots);
  // Velocity, acceleration and the contour's curvature from one interpolation of each smooth piece
  // (certified: numerics/piecewise.hpp); |h'| is the larger of h''s two signed extremes.
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
  // The contour's curvature is checked around the whole cam: on the base circle it is r0 (flat)
  // or r0 (roller contour) and inside the event it varies.
  s.min_curvature_radius = pieces.minimum(2).value;
  s.evaluations += pieces.work().evaluations;
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
