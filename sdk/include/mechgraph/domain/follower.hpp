#pragma once
// Follower: what rides on a cam. Any cam law combines with any follower; the pair (law, follower)
// decides the contour, the contact point, the pressure angle, the radius of curvature at the
// contact and whether the follower can follow the law at all (undercut). The mathematics of each
// follower is in docs/methods/followers.md.
//
// Contract
//  - The cam law's lift h(phi) (mechgraph/domain/cam_law.hpp) is the follower's motion on the cam
//    side: a translating follower moves by h along its axis; a pivoted follower turns by h / lever
//    about its pivot (the arc its cam-side contact travels, the lever being the pivot's distance to
//    the base-circle contact: cam_lever()).
//  - Frames: the cam's own frame is the one of mechgraph/domain/cam_law.hpp and the cam.contour
//    node: seen from the front, the follower sits on +y over the cam centre; the cam turns by the
//    cam angle phi counterclockwise (clockwise = false) or clockwise under it.
//  - contact(phi, d, r0, clockwise) gives, for the law's lift and derivatives d at phi and the base
//    radius r0, the contact point on the contour in the cam's frame, the roller centre (pitch
//    curve), the pressure angle, the contour's radius of curvature at the contact (positive convex),
//    where the contact lies on a flat face, and the follower's turn (pivoted). Throws NodeError
//    naming the follower's parameter when the follower cannot sit on that base circle.
//  - roller_radius() is 0 for a flat face; cam_lever(r0) is 0 for a translating follower.
//  - Every value finite; implementations immutable and thread-safe.
//
// Who checks what: the follower checks its own geometry (contact() throws); the node where cam and
// follower meet (cam.contour) refuses an undercut pair, naming the follower (follow_margin below);
// the conformance kit (mechgraph/testing/follower_conformance.hpp) checks the contact against the
// contour's own geometry (tangency, curvature from neighbouring points, the base circle).
#include <mechgraph/domain/cam_law.hpp>
#include <mechgraph/value.hpp>

#include <string>
#include <string_view>

namespace mechgraph {

struct FollowerContact {
  double x = 0.0, y = 0.0;              // contact point on the cam contour, cam frame, m
  double pitch_x = 0.0, pitch_y = 0.0;  // roller centre (pitch curve); a flat face: the contact point
  double pressure_angle = 0.0;          // rad, between the contact normal and the follower's motion
  double curvature_radius = 0.0;        // of the contour at the contact, m (negative: concave)
  double face_position = 0.0;           // flat face: contact along the face, m (translating: h' from the axis)
  double follower_angle = 0.0;          // pivoted: turn of the arm from its base-circle position, rad
};

class MECHGRAPH_INTERFACE Follower : public DomainObject {
 public:
  ~Follower() override;  // out of line (key function, sdk/src/interfaces.cpp)
  static constexpr std::string_view kind_name = "follower";
  std::string_view kind() const override { return kind_name; }

  /// The node type that made it ("follower.pivoted_roller"), for messages.
  virtual std::string_view type_name() const = 0;
  /// A short description with its dimensions ("roller 8 mm, offset 2 mm"), for messages.
  virtual std::string describe() const = 0;
  virtual double roller_radius() const = 0;  // m, 0 for a flat face
  virtual bool pivoted() const = 0;
  /// Pivoted: the pivot's distance to the contact on the base circle (the roller centre for a
  /// roller), so the arm turns by h / cam_lever; 0 for a translating follower.
  virtual double cam_lever(double base_radius) const = 0;
  virtual FollowerContact contact(double phi, const LiftDerivatives& d, double base_radius, bool clockwise) const = 0;

  /// Whether the follower can follow the contour at this contact: < 0 it can, >= 0 undercut.
  /// A flat face needs a convex contour (rho > 0); a roller of radius rr a pitch curve whose convex
  /// radius rho + rr exceeds rr (a concave pitch curve is always followed): 1/(rho + rr) - 1/rr.
  double follow_margin(const FollowerContact& c) const {
    const double rr = roller_radius();
    if (rr <= 0.0) return -c.curvature_radius;
    return 1.0 / (c.curvature_radius + rr) - 1.0 / rr;
  }
  /// The family's word for the follower in messages: "the pivoted roller follower (follower.pivoted_roller, ...)".
  std::string named() const { return std::string(type_name()) + " (" + describe() + ")"; }
};

}  // namespace mechgraph
