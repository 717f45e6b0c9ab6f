#include "follower_drawing.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <utility>

namespace mechgraph::cams {
namespace {

constexpr double pi = std::numbers::pi;

struct Point {
  double x = 0.0, y = 0.0;
};
Point operator+(Point a, Point b) { return {a.x + b.x, a.y + b.y}; }
Point operator-(Point a, Point b) { return {a.x - b.x, a.y - b.y}; }
Point operator*(double s, Point a) { return {s * a.x, s * a.y}; }
double dot(Point a, Point b) { return a.x * b.x + a.y * b.y; }
double norm(Point a) { return std::hypot(a.x, a.y); }
Point quarter_turn(Point a) { return {-a.y, a.x}; }  // J a

// `n` points along the path through `corners` (a polyline): every corner, and the points left
// over spread along the segments by their length, so that the drawing keeps its exact ends (a
// face's width, the pivot). Fewer points than corners: evenly spaced by length instead.
void along_path(const std::vector<Point>& corners, std::size_t n, FollowerDrawing& out) {
  std::vector<double> length;
  double total = 0.0;
  for (std::size_t k = 1; k < corners.size(); ++k) total += length.emplace_back(norm(corners[k] - corners[k - 1]));
  auto put = [&](Point p) {
    out.x.push_back(p.x);
    out.y.push_back(p.y);
  };
  if (corners.size() < 2 || n < corners.size() || !(total > 0.0)) {
    for (std::size_t i = 0; i < n; ++i) put(corners[std::min(corners.size() - 1, i * corners.size() / std::max<std::size_t>(n, 1))]);
    return;
  }
  const std::size_t spare = n - corners.size();
  std::vector<std::size_t> inside(length.size());
  std::size_t given = 0;
  for (std::size_t k = 0; k < length.size(); ++k) given += inside[k] = static_cast<std::size_t>(static_cast<double>(spare) * length[k] / total);
  for (std::size_t k = 0; given < spare; k = (k + 1) % length.size(), ++given) ++inside[k];
  for (std::size_t k = 0; k < length.size(); ++k) {
    put(corners[k]);
    for (std::size_t j = 1; j <= inside[k]; ++j)
      put(corners[k] + (static_cast<double>(j) / static_cast<double>(inside[k] + 1)) * (corners[k + 1] - corners[k]));
  }
  put(corners.back());
}

// A circle about `c` of radius `r` as corners, from and back to the point at angle `start`.
void add_circle(std::vector<Point>& corners, Point c, double r, double start, int segments = 72) {
  for (int i = 0; i <= segments; ++i) {
    const double a = start + 2.0 * pi * i / segments;
    corners.push_back({c.x + r * std::cos(a), c.y + r * std::sin(a)});
  }
}

LiftDerivatives at_rest(double lift) {
  LiftDerivatives d;
  d.lift = lift;
  return d;
}

// The pivot of a pivoted roller (follower_drawing.hpp): where the circles of radius cam_lever about
// the roller centre at the base circle and at the nose meet, the one a pose at half the lift agrees with.
std::optional<Point> roller_pivot(const Follower& f, double r0, double nose_lift, bool clockwise) {
  const double lever = f.cam_lever(r0);
  auto centre = [&](double lift) {
    const FollowerContact c = f.contact(0.0, at_rest(lift), r0, clockwise);
    return Point{c.pitch_x, c.pitch_y};
  };
  const Point c0 = centre(0.0), cn = centre(nose_lift), cm = centre(0.5 * nose_lift);
  const double d = norm(cn - c0);
  if (!(d > 1e-9 * lever) || !(d < 2.0 * lever)) return std::nullopt;
  const Point mid = 0.5 * (c0 + cn), across = (1.0 / d) * quarter_turn(cn - c0);
  const double h = std::sqrt(lever * lever - 0.25 * d * d);
  const Point a = mid + h * across, b = mid - h * across;
  const Point p = std::abs(norm(cm - a) - lever) <= std::abs(norm(cm - b) - lever) ? a : b;
  if (!(std::abs(norm(cm - p) - lever) <= 1e-6 * lever)) return std::nullopt;
  return p;
}

// The pivot and face offset of a pivoted flat face (follower_drawing.hpp), and the arm's sense k.
struct FlatArm {
  Point pivot;
  double face_offset = 0.0, k = 1.0;
};
std::optional<FlatArm> flat_pivot(const Follower& f, double r0, double nose_lift, bool clockwise) {
  const FollowerContact g0 = f.contact(0.0, at_rest(0.0), r0, clockwise), gn = f.contact(0.0, at_rest(nose_lift), r0, clockwise);
  const Point x0{g0.x, g0.y}, xn{gn.x, gn.y};
  if (!(norm(x0) > 0.0) || !(norm(xn) > 0.0)) return std::nullopt;
  const Point m0 = (1.0 / norm(x0)) * x0, mn = (1.0 / norm(xn)) * xn, dm = m0 - mn;
  if (!(dot(dm, dm) > 1e-18)) return std::nullopt;
  std::optional<FlatArm> best;
  double best_residual = std::numeric_limits<double>::infinity();
  for (const double k : {1.0, -1.0}) {
    const Point e0 = -k * quarter_turn(m0), en = -k * quarter_turn(mn);
    // f (m0 - mn) = xn - x0 - sn en + s0 e0
    const Point rhs = xn - x0 - gn.face_position * en + g0.face_position * e0;
    const double offset = dot(rhs, dm) / dot(dm, dm);
    const double residual = norm(rhs - offset * dm);
    if (residual < best_residual) {
      best_residual = residual;
      best = FlatArm{x0 - g0.face_position * e0 + offset * m0, offset, k};
    }
  }
  const double lever = f.cam_lever(r0);
  const double reach = dot(best->pivot, best->pivot) - (r0 + best->face_offset) * (r0 + best->face_offset);
  if (!(reach > 0.0) || !(std::abs(std::sqrt(reach) - lever) <= 1e-6 * lever)) return std::nullopt;
  return best;
}

}  // namespace

FollowerDrawing draw_follower_at_nose(const CamLaw& law, const Follower& f, const ContourPoints& c, bool clockwise,
                                      double face_from, double face_to, std::size_t n) {
  FollowerDrawing out;
  const double r0 = law.base_radius(), nose_lift = law.at(0.0).lift;
  const double rr = f.roller_radius();
  std::vector<Point> corners;
  if (rr > 0.0) {
    if (f.pivoted()) {
      // The roller at the nose, its arm to the pivot and the pivot (a small circle).
      const FollowerContact g = f.contact(0.0, law.at(0.0), r0, clockwise);
      const Point centre{g.pitch_x, g.pitch_y};
      const std::optional<Point> pivot = roller_pivot(f, r0, nose_lift, clockwise);
      const double toward = pivot ? std::atan2(pivot->y - centre.y, pivot->x - centre.x) : 0.0;
      add_circle(corners, centre, rr, toward);
      if (pivot) {
        corners.push_back(*pivot);
        add_circle(corners, *pivot, 0.25 * rr, toward + pi);
      }
    } else {
      // A translating roller about the furthest point of the pitch curve.
      std::size_t far = 0;
      for (std::size_t i = 0; i < c.points.size(); ++i)
        if (std::hypot(c.points[i].pitch_x, c.points[i].pitch_y) > std::hypot(c.points[far].pitch_x, c.points[far].pitch_y)) far = i;
      add_circle(corners, {c.points[far].pitch_x, c.points[far].pitch_y}, rr, 0.0, 360);
    }
    along_path(corners, n, out);
    return out;
  }
  if (f.pivoted()) {
    if (const std::optional<FlatArm> arm = flat_pivot(f, r0, nose_lift, clockwise)) {
      // The face at the nose: the line f from the pivot, from the least to the greatest contact
      // position along it; the arm from the pivot to the face's near end; the pivot.
      const FollowerContact g = f.contact(0.0, at_rest(nose_lift), r0, clockwise);
      const Point x{g.x, g.y};
      const Point m = (1.0 / norm(x)) * x, e = -arm->k * quarter_turn(m);
      const Point foot = arm->pivot - arm->face_offset * m;
      const Point near_end = foot + face_from * e, far_end = foot + face_to * e;
      const double pin = 0.04 * std::max(norm(far_end - arm->pivot), norm(near_end - arm->pivot));
      const double toward = std::atan2(near_end.y - arm->pivot.y, near_end.x - arm->pivot.x);
      add_circle(corners, arm->pivot, pin, toward);
      corners.push_back(arm->pivot);
      corners.push_back(near_end);
      corners.push_back(far_end);
      along_path(corners, n, out);
      return out;
    }
  }
  // A flat face square to the follower's motion at the nose: the face from the least to the
  // greatest contact position (h' both ways: min_face_width), its stem along the axis. The face
  // position's sign in the drawing is read from a contact away from the axis.
  const FollowerContact g = f.contact(0.0, law.at(0.0), r0, clockwise);
  const double sigma = clockwise ? -1.0 : 1.0;
  double side = 1.0, widest = 0.0;
  const double from = law.event_begin(), to = law.event_end();
  for (int i = 1; i < 32; ++i) {
    const double phi = from + (to - from) * i / 32.0;
    const FollowerContact h = f.contact(phi, law.at(phi), r0, clockwise);
    const double x_fixed = std::cos(sigma * phi) * h.x - std::sin(sigma * phi) * h.y;
    if (std::abs(h.face_position) > widest) widest = std::abs(h.face_position), side = x_fixed * h.face_position >= 0.0 ? 1.0 : -1.0;
  }
  const double y = g.y, stem = 0.8 * r0;
  corners = {{side * face_from, y}, {side * face_to, y}, {0.0, y}, {0.0, y + stem}};
  along_path(corners, n, out);
  return out;
}

}  // namespace mechgraph::cams
