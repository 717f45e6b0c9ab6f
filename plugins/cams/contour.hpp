#pragma once
// The cam contour a follower needs, in the cam's own frame (docs/methods/followers.md): seen from
// the front, the cam turns by the cam angle phi in the stated direction under a follower on +y
// (the nose of a symmetric lobe on +y at phi = 0). The follower (mechgraph/domain/follower.hpp, the
// followers plugin) gives the contact point, pitch curve, pressure angle and curvature; this file
// traces the closed contour to a chord error.
#include <mechgraph/domain/cam_law.hpp>
#include <mechgraph/domain/follower.hpp>

#include <vector>

namespace mechgraph::cams {

/// The closed contour (and pitch curve) as points at cam angles from -pi up to (not including) pi:
/// every knot of the law, then each interval halved until the chord between neighbours strays from
/// the curve (checked at the interval's midpoint and quarter points) by at most `chord_error`, on
/// the contour and, for a roller, the pitch curve. `evaluations` counts the law's evaluations.
/// Throws NodeError("chord_error") past max_contour_points or where the contour is not finite.
struct ContourPoints {
  std::vector<double> phi;
  std::vector<FollowerContact> points;
};
/// More points than this is an error naming chord_error (a chord error far below the cam's size).
inline constexpr std::size_t max_contour_points = 1'000'000;
ContourPoints trace_contour(const CamLaw& law, const Follower& f, bool clockwise, double chord_error, long& evaluations);

/// Distance from p to the segment a-b (for the chord error).
double distance_to_segment(double px, double py, double ax, double ay, double bx, double by);

}  // namespace mechgraph::cams
