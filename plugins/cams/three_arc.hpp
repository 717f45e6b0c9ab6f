#pragma once
// Three-arc convex cam: base circle r0, two flank arcs r1, nose arc r2, all tangent
// (docs/methods/valvetrain.md, stage 1). Cam frame: cam centre O at the origin, nose on +x.
//
//   nose-arc centre N = (a, 0),                   a = r0 + h_max - r2
//   flank-arc centre F = -e (cos phi_p, sin phi_p), e = r1 - r0   (flank of the phi > 0 side)
//   internal tangency of flank and nose:  |N - F| = r1 - r2
//       (r1 - r2)^2 = a^2 + e^2 + 2 a e cos(phi_p)
//   the common normal N - F points at alpha = atan2(e sin phi_p, a + e cos phi_p) from the nose,
//   and the flank spans phi_1 = phi_p - alpha from the start of lift, where (law of sines in O,N,F)
//       sin(phi_1) = a sin(phi_p) / (r1 - r2).
//
// Followers (both translating, in line with O):
//  - flat-faced tappet: the lift is the support function of the contour,
//       flank  h = e (1 - cos x)            x = phi_p - |phi|  (from the start of lift)
//       nose   h = a cos t - (r0 - r2)      t = |phi|          (from the nose)
//    switching where the follower direction crosses the common normal, |phi| = alpha.
//  - roller of radius rr: the roller centre follows the pitch curve, the contour offset by rr
//    (arcs of the same centres with radii r0 + rr, r1 + rr, r2 + rr). For an arc of centre at
//    distance c from O and radius rho, with theta the angle between the follower line and the
//    direction of the centre, the roller centre is at s = c cos(theta) + sqrt(rho^2 - c^2 sin^2 theta).
//    It switches from flank to nose where the follower line passes through the pitch-curve
//    junction N + (r2 + rr) n_alpha, at |phi| = beta < alpha.
#include "cam_node.hpp"

#include <mechgraph/domain/cam_law.hpp>

#include <vector>

namespace mechgraph::cams {

/// The contour of a three-arc cam, in SI (m, rad).
struct ThreeArcGeometry {
  double max_lift = 0.0;       // h_max
  double half_action = 0.0;    // phi_p
  double base_radius = 0.0;    // r0
  double flank_radius = 0.0;   // r1
  double nose_radius = 0.0;    // r2
  double nose_centre = 0.0;    // a = r0 + h_max - r2
  double flank_centre = 0.0;   // e = r1 - r0
  double flank_angle = 0.0;    // phi_1, flank span from the start of lift
  double junction_normal = 0.0;  // alpha = phi_p - phi_1, direction of the common normal from the nose
};

/// Radii from the flank angle phi_1 (= the positive-acceleration phase of a flat tappet), the
/// closed form of the method note: s = sin(phi_p)/sin(phi_1), A = 2(s-1)(1-cos phi_p),
/// B = -2h(s-1+cos phi_p), C = -h^2, a = (-B + sqrt(B^2-4AC))/(2A), r2 = r0 + h - a,
/// r1 = r0 + a(s-1) + h. Throws NodeError naming accel_angle when the request is infeasible.
ThreeArcGeometry three_arc_from_accel_angle(const CamBasics& basics, double accel_angle);

/// Radii from the nose radius r2: a = r0 + h - r2 is known and the tangency relation is linear
/// in e: e = (a^2 - (r0 - r2)^2) / (2 (r0 - r2 - a cos phi_p)). Throws NodeError naming
/// nose_radius when the request is infeasible.
ThreeArcGeometry three_arc_from_nose_radius(const CamBasics& basics, double nose_radius);

/// The lift of a flat or roller tappet on a three-arc cam, exactly, with three derivatives.
class ThreeArcLaw final : public CamLaw {
 public:
  /// roller_radius = 0: flat-faced tappet.
  ThreeArcLaw(const ThreeArcGeometry& geometry, double roller_radius);

  double event_begin() const override { return -g_.half_action; }
  double event_end() const override { return g_.half_action; }
  LiftDerivatives evaluate_in_event(double phi) const override;
  std::vector<double> breakpoints() const override { return {-switch_angle_, switch_angle_}; }
  double max_lift() const override { return g_.max_lift; }
  double base_radius() const override { return g_.base_radius; }
  double roller_radius() const override { return roller_radius_; }
  /// Flat tappet: the flank/nose switches and the nose (plus 90 deg into a long flank for the
  /// velocity). A roller: false (the generic search).
  bool monotone_breaks(int order, std::vector<double>& breaks) const override;
  /// Flat tappet: the integrals of h and h^2 in closed form (arcs: x - sin x and its square's).
  bool lift_integrals(double a, double b, double& integral, double& integral_of_square) const override;

  const ThreeArcGeometry& geometry() const { return g_; }
  /// |phi| (from the nose) where the follower passes from flank to nose: alpha for the flat
  /// tappet, beta for the roller.
  double switch_angle() const { return switch_angle_; }

 private:
  ThreeArcGeometry g_;
  double roller_radius_ = 0.0;
  double switch_angle_ = 0.0;
};

/// cam.three_arc: parameters accel_angle | nose_radius, follower, roller_radius; extra outputs
/// flank_radius and nose_radius.
CamLawDefinition three_arc_definition();

}  // namespace mechgraph::cams
