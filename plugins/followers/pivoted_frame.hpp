#pragma once
// What the pivoted followers share (docs/methods/followers.md, "Pivoted followers"): plane vectors,
// the turn from the fixed frame into the cam's, and the arm's turn over the law's lift.
//  - Fixed frame: cam centre at the origin, the follower above it (+y). The pivot P; the arm's
//    direction e(psi) = (cos psi, sin psi), J e = (-sin psi, cos psi) (J: a quarter turn ccw).
//  - The arm reaches from the pivot across the follower axis; lifting turns it away from the cam:
//    counterclockwise (k = +1) for a pivot left of the axis (pivot_x <= 0), clockwise (k = -1) else.
//    psi = psi0 + k h / L, L the cam-side lever.
//  - The cam turned by phi (sigma = +1 ccw, -1 cw) carries a point v of the cam's frame onto
//    R(sigma phi) v of the fixed frame, so a fixed point w sits at R(-sigma phi) w in the cam's frame.
#include <mechgraph/domain/cam_law.hpp>

#include <cmath>

namespace mechgraph::followers {

struct Vec2 {
  double x = 0.0, y = 0.0;
};
inline Vec2 operator+(Vec2 a, Vec2 b) { return {a.x + b.x, a.y + b.y}; }
inline Vec2 operator-(Vec2 a, Vec2 b) { return {a.x - b.x, a.y - b.y}; }
inline Vec2 operator*(double s, Vec2 a) { return {s * a.x, s * a.y}; }
inline double dot(Vec2 a, Vec2 b) { return a.x * b.x + a.y * b.y; }
inline double cross(Vec2 a, Vec2 b) { return a.x * b.y - a.y * b.x; }
inline Vec2 quarter_turn(Vec2 a) { return {-a.y, a.x}; }  // J a
inline double norm(Vec2 a) { return std::hypot(a.x, a.y); }

/// R(-sigma phi) w: a point of the fixed frame in the cam's frame.
Vec2 into_cam_frame(Vec2 w, double phi, double sigma);

/// The arm's angle and its first two derivatives over cam angle.
struct ArmTurn {
  double psi = 0.0, dpsi = 0.0, d2psi = 0.0;
};
inline ArmTurn arm_turn(double psi0, double k, double lever, const LiftDerivatives& d) {
  return {psi0 + k * d.lift / lever, k * d.velocity / lever, k * d.acceleration / lever};
}

/// Signed angle from the follower's direction of motion `motion` to the contact normal `normal`
/// (both fixed frame), with the sign of a translating roller's pressure angle (positive on the
/// rise of a cam turning ccw).
inline double pressure_angle(Vec2 motion, Vec2 normal, double sigma) {
  return sigma * std::atan2(cross(motion, normal), dot(motion, normal));
}

}  // namespace mechgraph::followers
