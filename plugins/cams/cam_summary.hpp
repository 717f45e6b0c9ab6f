#pragma once
// Characteristic figures of any cam law, found numerically on the law's exact derivatives:
// extrema by sampling each smooth piece and refining with Brent's method; the end of the
// positive-acceleration phase by TOMS 748 on h'' (see positive_acceleration_phase).
#include <mechgraph/domain/cam_law.hpp>

namespace mechgraph::cams {

struct CamSummary {
  double max_velocity = 0.0;          // m/rad, max |h'|
  double max_acceleration = 0.0;      // m/rad^2
  double min_acceleration = 0.0;      // m/rad^2 (most negative)
  double accel_angle = 0.0;           // rad from the start of lift to the first + to - change of h''
  double min_curvature_radius = 0.0;  // m, of the cam contour (flat tappet: r0 + h + h'')
  long evaluations = 0;
};

/// `samples` per smooth piece (the accuracy knob of every cam node).
CamSummary summarize(const CamLaw& law, int samples);

/// The positive-acceleration phase measured from the start of lift: up to the first + to -
/// change of sign of h'' after the first angle where h'' > 0 (so a constant-velocity ramp, where
/// h'' is exactly 0, or a table starting with a tiny negative h'' does not end it early).
double positive_acceleration_phase(const CamLaw& law, int samples, long& evaluations);

/// Radius of curvature of the cam contour at angle phi: flat-faced follower rho = r0 + h + h'';
/// in-line roller of radius rr: pitch radius R = r0 + rr + h,
/// rho_pitch = (R^2 + h'^2)^(3/2) / (R^2 + 2 h'^2 - R h''), contour rho = rho_pitch - rr.
double contour_curvature_radius(const CamLaw& law, double phi);
/// The same from the law's values at phi, already evaluated.
double contour_curvature_radius(const CamLaw& law, double phi, const LiftDerivatives& values);

}  // namespace mechgraph::cams
