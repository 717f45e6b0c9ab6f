#pragma once
// The cam contour a follower needs, in the cam's own frame (docs/methods/valvetrain.md, "The cam
// contour"). Seen from the front, the cam turns by the cam angle phi in the stated direction under
// a follower on the fixed axis +y (the nose of a symmetric lobe on +y at phi = 0). In the cam's
// frame the follower's axis then points along u(phi) = (sigma sin phi, cos phi), sigma = +1 when
// the cam turns counterclockwise, -1 clockwise (turning the drawn cam by sigma phi carries u onto
// +y), and t(phi) = du/dphi = (sigma cos phi, -sin phi); t' = -u either way, so the formulas below
// hold for both directions.
//  - Flat-faced follower, face at s = r0 + h from the centre: the contour is the envelope of the
//    faces, P = s u + h' t; the contact lies h' from the axis along the face; rho = r0 + h + h''.
//  - Roller of radius rr, its axis offset by e (positive: the side that lowers the pressure angle
//    on the rise): roller centre (pitch curve) C = (s0 + h) u + e t with s0 = sqrt((r0 + rr)^2 - e^2);
//    C' = (h' - e) u + (s0 + h) t; the contour is P = C - rr N with N the outward normal
//    ((s0 + h) u - (h' - e) t) / |C'|; pressure angle tan(alpha) = (h' - e) / (s0 + h);
//    pitch curvature rho_p = |C'|^3 / ((h' - e)(2h' - e) + (s0 + h)^2 - (s0 + h) h''), contour rho = rho_p - rr.
#include <mechgraph/domain/cam_law.hpp>

#include <vector>

namespace mechgraph::cams {

struct Follower {
  enum class Kind { flat, roller } kind = Kind::flat;
  double base_radius = 0.0;    // r0, m
  double roller_radius = 0.0;  // rr, m (roller)
  double offset = 0.0;         // e, m (roller)
  bool clockwise = false;      // the cam turns clockwise seen from the front (sigma = -1)
  double pitch_base() const;   // s0
};

struct ContactGeometry {
  double x = 0.0, y = 0.0;              // contour point, cam frame, m
  double pitch_x = 0.0, pitch_y = 0.0;  // roller centre (roller only), m
  double pressure_angle = 0.0;          // rad (0 for a flat face)
  double curvature_radius = 0.0;        // of the contour at the contact, m (negative: concave)
  double face_offset = 0.0;             // flat: distance of the contact from the follower axis, m
};

ContactGeometry contact_at(const Follower& f, double phi, const LiftDerivatives& d);

/// The closed contour (and pitch curve) as points at cam angles from -pi up to (not including) pi:
/// every knot of the law, then each interval halved until the chord between neighbours strays from
/// the curve (checked at the interval's midpoint and quarter points) by at most `chord_error`, on
/// the contour and, for a roller, the pitch curve. `evaluations` counts the law's evaluations.
/// Throws NodeError("chord_error") past max_contour_points or where the contour is not finite.
struct ContourPoints {
  std::vector<double> phi;
  std::vector<ContactGeometry> points;
};
/// More points than this is an error naming chord_error (a chord error far below the cam's size).
inline constexpr std::size_t max_contour_points = 1'000'000;
ContourPoints trace_contour(const CamLaw& law, const Follower& f, double chord_error, long& evaluations);

/// Distance from p to the segment a-b (for the chord error).
double distance_to_segment(double px, double py, double ax, double ay, double bx, double by);

}  // namespace mechgraph::cams
