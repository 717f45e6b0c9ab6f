#pragma once
// The follower drawn at rest where it stands at the nose (cam angle 0), in the cam's frame, for the
// contour's drawing to scale: a roller as its circle, a flat face at the width its contact sweeps
// over the turn (min_face_width), and a pivoted follower with its arm and pivot.
//
// The pivot is not part of the Follower interface; it follows from the interface's contract
// (mechgraph/domain/follower.hpp): a pivoted follower turns about its pivot by lift / cam_lever.
//  - Roller: the roller centre C sits cam_lever from the pivot, so the pivot is where the circles
//    of that radius about C at the base circle and C at the nose meet; a third pose (half the
//    nose lift) tells the two intersections apart.
//  - Flat face: with the law's velocity taken as 0, the contact is the foot of the perpendicular
//    from the cam centre onto the face, x = p m (m the face's outward normal); the contact's
//    distance along the face from the pivot is s = e.(x - P) and the face lies f from the pivot,
//    m.(x - P) = -f, so P = x - s e + f m with e = -k J m. Two poses (base circle, nose) give f
//    and k (the arm's sense) by least squares; the pivot is accepted only when its lever
//    sqrt(|P|^2 - (r0 + f)^2) is the follower's cam_lever.
// When the pivot cannot be found so (a follower outside this family's geometry), the follower is
// drawn without arm and pivot.
#include "contour.hpp"

#include <mechgraph/domain/follower.hpp>

#include <vector>

namespace mechgraph::cams {

/// The follower at the nose as one path of `n` points (`x`, `y`, cam frame, m). `face_from` and
/// `face_to` are the least and greatest face positions over the turn (FollowerContact::
/// face_position), the width a flat face is drawn at; unused for a roller.
struct FollowerDrawing {
  std::vector<double> x, y;
};
FollowerDrawing draw_follower_at_nose(const CamLaw& law, const Follower& f, const ContourPoints& contour, bool clockwise,
                                      double face_from, double face_to, std::size_t n);

}  // namespace mechgraph::cams
