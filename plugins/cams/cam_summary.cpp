#include "cam_summary.hpp"

#include <mechgraph/numerics/piecewise.hpp>

#include <cmath>
#include <vector>

namespace mechgraph::cams {
namespace {

std::vector<double> knots_of(const CamLaw& law) {
  std::vector<double> knots{law.event_begin()};
  for (double b : law.breakpoints()) knots.push_back(b);
  knots.push_back(law.event_end());
  return knots;
}

}  // namespace

double contour_curvature_radius(const CamLaw& law, double phi) {
  const LiftDerivatives d = law.at(phi);
  const double rr = law.roller_radius();
  if (rr <= 0.0) return law.base_radius() + d.lift + d.acceleration;
  const double R = law.base_radius() + rr + d.lift;
  const double v2 = d.velocity * d.velocity;
  const double rho_pitch = std::pow(R * R + v2, 1.5) / (R * R + 2.0 * v2 - R * d.acceleration);
  return rho_pitch - rr;
}

CamSummary summarize(const CamLaw& law, int samples) {
  CamSummary s;
  const std::vector<double> knots = knots_of(law);
  const std::span<const double> k(knots);
  auto velocity = [&](double x) { return std::abs(law.at(x).velocity); };
  auto acceleration = [&](double x) { return law.at(x).acceleration; };
  s.max_velocity = numerics::maximize_piecewise(velocity, k, samples, s.evaluations).value;
  s.max_acceleration = numerics::maximize_piecewise(acceleration, k, samples, s.evaluations).value;
  s.min_acceleration = numerics::minimize_piecewise(acceleration, k, samples, s.evaluations).value;
  // End of the positive-acceleration phase: first sign change of h'' after the start of lift.
  const auto end_of_positive = numerics::first_sign_change(acceleration, k, samples, s.evaluations);
  s.accel_angle = end_of_positive ? *end_of_positive - law.event_begin() : 0.0;
  // The contour's curvature is checked around the whole cam: on the base circle it is r0 (flat)
  // or r0 (roller contour) and inside the event it varies.
  auto rho = [&](double x) { return contour_curvature_radius(law, x); };
  s.min_curvature_radius = numerics::minimize_piecewise(rho, k, samples, s.evaluations).value;
  s.min_curvature_radius = std::min(s.min_curvature_radius, law.base_radius());
  return s;
}

}  // namespace mechgraph::cams
