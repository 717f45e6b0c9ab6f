#pragma once
// Cam geometry for cam-law authors: the characteristic figures of any CamLaw, found numerically on
// the law's exact derivatives (extrema by sampling each smooth piece and refining on the derivative's
// sign change; the end of the positive-acceleration phase by TOMS 748 on h''), the contour's radius
// of curvature, and the undercut check every cam node makes (docs/methods/valvetrain.md, stage 1).
// The built-in cam nodes use exactly these; a plugin's cam node should too, so its outputs mean the
// same. Preconditions: a law that keeps the CamLaw contract (cam_law.hpp); samples >= 2.
#include <mechgraph/domain/cam_law.hpp>

#include <functional>
#include <memory>
#include <optional>

namespace mechgraph {

struct CamSummary {
  double max_velocity = 0.0;          // m/rad, max |h'|
  double max_acceleration = 0.0;      // m/rad^2
  double min_acceleration = 0.0;      // m/rad^2 (most negative)
  double accel_angle = 0.0;           // rad from the start of lift to the first + to - change of h''
  double min_curvature_radius = 0.0;  // m, of the cam contour (flat tappet: r0 + h + h'')
  long evaluations = 0;
  /// false: min_curvature_radius was not asked for (summarize(..., false)) and the contour was
  /// only proven free of undercut (min_curvature_radius then holds r0, a placeholder > 0).
  bool curvature_exact = true;
  /// false: the peaks (max_velocity, max/min_acceleration) or the phase (accel_angle) were not
  /// asked for (summarize with CamSummaryParts) and hold 0.
  bool peaks_known = true;
  bool phase_known = true;
};

/// Which parts of a summary a caller reads (a node asks for what is wanted downstream).
struct CamSummaryParts {
  bool peaks = true;      // max_velocity, max_acceleration, min_acceleration
  bool phase = true;      // accel_angle
  bool curvature = true;  // min_curvature_radius measured (else only proven positive where possible)
};

/// `samples` per smooth piece (the accuracy knob of every cam node).
CamSummary summarize(const CamLaw& law, int samples);
/// The same; with exact_curvature = false, a flat-follower law that declares its monotone runs
/// (CamLaw::monotone_breaks) has its contour proven free of undercut by a bound instead of its
/// smallest radius of curvature measured (cheaper; the undercut refusal is unchanged, and a law
/// whose bound does not settle it is measured).
CamSummary summarize(const CamLaw& law, int samples, bool exact_curvature);
/// Only the parts asked for, where the law declares its monotone runs (a law without them gets
/// every part: one interpolation serves them all). The undercut check's figure is always there.
CamSummary summarize(const CamLaw& law, int samples, const CamSummaryParts& parts);

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

/// The smallest base radius at which `law_for_base_radius(r0)` gives a contour without undercut
/// (min_curvature_radius > 0), bracketed by growing r0 from `base_radius` by 1.5x and bisected to
/// 0.001 mm; nullopt if none up to 1000 x base_radius. A radius for which the factory throws
/// NodeError counts as infeasible (e.g. a three-arc cam without solution).
std::optional<double> smallest_undercut_free_base_radius(
    const std::function<std::shared_ptr<const CamLaw>(double base_radius)>& law_for_base_radius, double base_radius,
    int samples);

/// The cam node's undercut check: if `summary.min_curvature_radius` <= 0, throws
/// NodeError("base_radius", ...) with the smallest radius and the base radius that would remove it
/// (searched with `law_for_base_radius`, which may be empty: then the message says only the radius).
void refuse_undercut(const CamSummary& summary, double base_radius,
                     const std::function<std::shared_ptr<const CamLaw>(double base_radius)>& law_for_base_radius,
                     int samples);

}  // namespace mechgraph
