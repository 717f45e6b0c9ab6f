#include <mechgraph/domain/cam_geometry.hpp>

#include <mechgraph/errors.hpp>

#include <mechgraph/numerics/piecewise.hpp>

#include <cmath>
#include <sstream>
#include <limits>
#include <vector>

namespace mechgraph {
double positive_acceleration_phase(const CamLaw& law, int samples, long& evaluations) {
  const std::vector<double> knots = law.knots();
  auto acceleration = [&](double x) { return law.at(x).acceleration; };
  for (std::size_t p = 0; p + 1 < knots.size(); ++p) {
    const double a = knots[p], b = knots[p + 1];
    for (int i = 0; i < samples; ++i) {
      // Inset from the knot, as the extremum searches are, to see this piece's one-sided value.
      const double x = i == 0 ? a + 1e-13 * (b - a) : a + (b - a) * static_cast<double>(i) / samples;
      ++evaluations;
      if (!(acceleration(x) > 0.0)) continue;
      std::vector<double> rest{x};
      for (std::size_t q = p + 1; q < knots.size(); ++q) rest.push_back(knots[q]);
      const auto end = numerics::first_sign_change(acceleration, rest, samples, evaluations);
      return end ? *end - law.event_begin() : 0.0;
    }
  }
  return 0.0;
}

double contour_curvature_radius(const CamLaw& law, double phi) { return contour_curvature_radius(law, phi, law.at(phi)); }

double contour_curvature_radius(const CamLaw& law, double, const LiftDerivatives& d) {
  const double rr = law.roller_radius();
  if (rr <= 0.0) return law.base_radius() + d.lift + d.acceleration;
  const double R = law.base_radius() + rr + d.lift;
  const double v2 = d.velocity * d.velocity;
  const double rho_pitch = std::pow(R * R + v2, 1.5) / (R * R + 2.0 * v2 - R * d.acceleration);
  return rho_pitch - rr;
}

CamSummary summarize(const CamLaw& law, int samples) {
  CamSummary s;
  const std::vector<double> knots = law.knots();
  const std::span<const double> k(knots);
  // |velocity|, both acceleration extremes and the contour's curvature from one sampling pass.
  numerics::Extremum peaks[4];
  numerics::maximize_piecewise_together(
      [&](double x, double* v, double* slope) {
        const LiftDerivatives d = law.at(x);
        const double sign = d.velocity < 0.0 ? -1.0 : 1.0;
        v[0] = sign * d.velocity;
        slope[0] = sign * d.acceleration;
        v[1] = d.acceleration;
        slope[1] = d.jerk;
        v[2] = -d.acceleration;
        slope[2] = -d.jerk;
        v[3] = -contour_curvature_radius(law, x, d);
        slope[3] = std::numeric_limits<double>::quiet_NaN();  // would need the 4th derivative: Brent
      },
      4, k, samples, s.evaluations, peaks);
  s.max_velocity = peaks[0].value;
  s.max_acceleration = peaks[1].value;
  s.min_acceleration = -peaks[2].value;
  s.accel_angle = positive_acceleration_phase(law, samples, s.evaluations);
  // The contour's curvature is checked around the whole cam: on the base circle it is r0 (flat)
  // or r0 (roller contour) and inside the event it varies.
  s.min_curvature_radius = -peaks[3].value;
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
