#pragma once
// An eccentric circle under any follower of the followers plugin, in closed form and in long
// double: the independent reference of tests/stability/follower_stability_test.cpp.
//
// The cam is a circle of radius Rc whose centre sits eps from the cam centre, turned so that the
// follower is lowest at cam angle +-pi. Whatever the follower, it touches that circle, so the
// contour it makes from its lift law must be the circle again: every contact point Rc from the
// circle's centre, the radius of curvature Rc, the roller centre Rc + rr from it, and the pressure
// angle the one between the circle's normal at the contact and the way the follower's point there
// moves. The follower's motion comes from plane geometry alone (docs/methods/followers.md gives the
// follower's own formulas; none is used here):
//  - translating flat face: it rests on the circle's top, s = c_y + Rc;
//  - translating roller on the line x = sigma e: its centre Rc + rr from the circle's centre,
//    y = c_y + sqrt((Rc + rr)^2 - (sigma e - c_x)^2);
//  - pivoted flat face at f from the pivot P: the face's outward normal m = k J e(psi) and the
//    tangency m.(P - c) = f + Rc give psi = angle(P - c) - pi + k asin((f + Rc) / |P - c|);
//  - pivoted roller on an arm L: its centre P + L e(psi) is Rc + rr from c, the triangle
//    (P, c, centre) gives psi = angle(P - c) - pi + k acos(-cos), the cosine by the law of cosines.
// The lift law the follower reads is that motion over cam angle, measured from the base circle
// the follower sees at its lowest (radius r0, rounded to a double: the law's base radius), times
// the lever for a pivoted follower; its first two derivatives are exact (forward-mode jets), so
// the follower under test and the reference differ only by the follower's own rounding.
//
// Asin and acos near +-1 are taken as atan2 of factored differences (Kahan), so the reference
// keeps its digits where the follower is near its limits (a lever or an arm's reach near zero).
#include <cmath>
#include <numbers>

namespace mechgraph::testing::eccentric {

using Real = long double;
constexpr Real pi_l = std::numbers::pi_v<long double>;

/// A value and its first two derivatives over the cam angle.
struct Jet {
  Real v = 0, d = 0, dd = 0;
};
inline Jet constant(Real c) { return {c, 0, 0}; }
inline Jet operator+(Jet a, Jet b) { return {a.v + b.v, a.d + b.d, a.dd + b.dd}; }
inline Jet operator-(Jet a, Jet b) { return {a.v - b.v, a.d - b.d, a.dd - b.dd}; }
inline Jet operator-(Jet a) { return {-a.v, -a.d, -a.dd}; }
inline Jet operator*(Real s, Jet a) { return {s * a.v, s * a.d, s * a.dd}; }
inline Jet operator*(Jet a, Jet b) { return {a.v * b.v, a.d * b.v + a.v * b.d, a.dd * b.v + 2 * a.d * b.d + a.v * b.dd}; }
inline Jet inverse(Jet b) { return {1 / b.v, -b.d / (b.v * b.v), -b.dd / (b.v * b.v) + 2 * b.d * b.d / (b.v * b.v * b.v)}; }
inline Jet operator/(Jet a, Jet b) { return a * inverse(b); }
inline Jet sin(Jet a) {
  const Real s = std::sin(a.v), c = std::cos(a.v);
  return {s, c * a.d, c * a.dd - s * a.d * a.d};
}
inline Jet cos(Jet a) {
  const Real s = std::sin(a.v), c = std::cos(a.v);
  return {c, -s * a.d, -s * a.dd - c * a.d * a.d};
}
inline Jet sqrt(Jet a) {
  const Real r = std::sqrt(a.v);
  return {r, a.d / (2 * r), a.dd / (2 * r) - a.d * a.d / (4 * r * a.v)};
}
// atan2(y, x): d = (x y' - y x') / r2, its derivative (x y'' - y x'') / r2 - (x y' - y x') r2' / r2^2.
inline Jet atan2(Jet y, Jet x) {
  const Real r2 = x.v * x.v + y.v * y.v, n = x.v * y.d - y.v * x.d;
  return {std::atan2(y.v, x.v), n / r2, (x.v * y.dd - y.v * x.dd) / r2 - n * 2 * (x.v * x.d + y.v * y.d) / (r2 * r2)};
}
inline Jet hypot(Jet x, Jet y) { return sqrt(x * x + y * y); }
/// The value shifted by whole turns into (-pi, pi]; the derivatives unchanged.
inline Jet wrap(Jet a) { return {std::remainder(a.v, 2 * pi_l), a.d, a.dd}; }

/// The followers of the plugin.
enum class Kind { flat, roller, pivoted_flat, pivoted_roller };

/// A follower and the eccentric circle it rides on (metres; the pivot in the drawn fixed frame).
struct Design {
  Kind kind = Kind::flat;
  double roller_radius = 0, offset = 0, pivot_x = 0, pivot_y = 0, face_offset = 0, arm = 0;
  double circle_radius = 20e-3, eccentricity = 4e-3;
  bool clockwise = false;
};

/// The reference at one cam angle, fixed and cam frame as in mechgraph/domain/follower.hpp.
struct Contact {
  Real x = 0, y = 0, pitch_x = 0, pitch_y = 0;  // cam frame
  Real pressure_angle = 0, curvature_radius = 0, face_position = 0, follower_angle = 0;
  Jet lift;  // the law's lift and its derivatives
};

/// The eccentric circle and its follower, prepared: the turn that puts the follower's lowest point
/// at +-pi, the base radius (a double) and the lever.
class Reference {
 public:
  explicit Reference(const Design& d);
  double base_radius() const { return base_radius_; }
  Real lever() const { return lever_; }
  /// False when the follower cannot ride on this circle (an arm that cannot reach it all round,
  /// an offset past it, a pivot inside it): such a design is no reference.
  bool valid() const { return valid_; }
  Contact at(Real phi) const;
  Jet lift(Real phi) const;
  /// The circle's centre in the cam's frame (fixed in the cam).
  Real centre_in_cam_x() const { return -eps_ * std::sin(sigma_ * turn_); }
  Real centre_in_cam_y() const { return eps_ * std::cos(sigma_ * turn_); }

 private:
  // The follower's motion coordinate (translation s, or k psi) over cam angle, for the circle
  // centre turned by `turn` more, and the circle's centre in the fixed frame.
  // The follower's motion coordinate over cam angle: its translation s, or its arm's angle psi
  // (raw, as atan2 gives it), on a circle of radius `radius` centred at c; `ok` false where the
  // follower cannot touch that circle.
  Jet raw_motion(Jet cx, Jet cy, Real radius, bool& ok) const;
  // The motion coordinate measured the way the law reads it (k psi, continuous over the turn).
  Jet motion(Jet phi, bool& ok) const;
  Jet centre_x(Jet phi) const { return -eps_ * sin(sigma_ * (phi + constant(turn_))); }
  Jet centre_y(Jet phi) const { return eps_ * cos(sigma_ * (phi + constant(turn_))); }
  bool pivoted() const { return d_.kind == Kind::pivoted_flat || d_.kind == Kind::pivoted_roller; }
  Design d_;
  Real sigma_, k_, Rc_, eps_, turn_ = 0, psi_ref_ = 0, base_motion_ = 0, lever_ = 1;
  double base_radius_ = 0;
  bool valid_ = true;
};

// asin(w / dist) as atan2(w, sqrt((dist - w)(dist + w))): no digits lost near +-1.
inline Jet asin_ratio(Jet w, Jet dist) { return atan2(w, sqrt((dist - w) * (dist + w))); }

inline Jet Reference::raw_motion(Jet cx, Jet cy, Real radius, bool& ok) const {
  const Real rr = d_.roller_radius;
  switch (d_.kind) {
    case Kind::flat:
      return cy + constant(radius);
    case Kind::roller: {
      // The centre on x = sigma e, radius + rr from c.
      const Jet dx = constant(sigma_ * Real(d_.offset)) - cx, reach = constant(radius + rr);
      const Jet under = (reach - dx) * (reach + dx);
      ok = ok && under.v > 0;
      return under.v > 0 ? cy + sqrt(under) : cy;
    }
    case Kind::pivoted_flat: {
      const Jet dx = constant(d_.pivot_x) - cx, dy = constant(d_.pivot_y) - cy, dist = hypot(dx, dy);
      const Jet w = constant(Real(d_.face_offset) + radius);
      ok = ok && dist.v > std::abs(w.v);
      if (!(dist.v > std::abs(w.v))) return constant(0);
      return atan2(dy, dx) - constant(pi_l) + k_ * asin_ratio(w, dist);
    }
    case Kind::pivoted_roller: {
      // Law of cosines in the triangle pivot, circle centre, roller centre; acos(-c) as
      // atan2(sqrt((1 - c)(1 + c)), -c) with 1 +- c factored (Kahan).
      const Jet dx = constant(d_.pivot_x) - cx, dy = constant(d_.pivot_y) - cy, dist = hypot(dx, dy);
      const Jet L = constant(d_.arm), R = constant(radius + rr), two_ld = 2 * L * dist;
      const Jet one_plus = (R - dist + L) * (R + dist - L) / two_ld;   // 1 + c
      const Jet one_minus = (dist + L - R) * (dist + L + R) / two_ld;  // 1 - c
      ok = ok && one_plus.v > 0 && one_minus.v > 0;
      if (!(one_plus.v > 0 && one_minus.v > 0)) return constant(0);
      const Jet c = (R * R - dist * dist - L * L) / two_ld;
      return atan2(dy, dx) - constant(pi_l) + k_ * atan2(sqrt(one_minus * one_plus), -c);
    }
  }
  return constant(0);
}

inline Jet Reference::motion(Jet phi, bool& ok) const {
  const Jet q = raw_motion(centre_x(phi), centre_y(phi), Rc_, ok);
  return pivoted() ? k_ * wrap(q - constant(psi_ref_)) : q;
}

inline Reference::Reference(const Design& d)
    : d_(d), sigma_(d.clockwise ? -1 : 1), k_(d.pivot_x <= 0 ? 1 : -1), Rc_(d.circle_radius), eps_(d.eccentricity) {
  bool ok = true;
  if (pivoted()) psi_ref_ = raw_motion(centre_x(constant(0)), centre_y(constant(0)), Rc_, ok).v;
  // The lowest point of the motion: the best of 720 samples, then Newton on its slope.
  Real best = 0, lowest = 0;
  for (int i = 0; i < 720; ++i) {
    const Real phi = -pi_l + 2 * pi_l * i / 720;
    const Real q = motion({phi, 1, 0}, ok).v;
    if (i == 0 || q < lowest) lowest = q, best = phi;
  }
  if (!ok) {
    valid_ = false;
    return;
  }
  for (int i = 0; i < 60; ++i) {
    const Jet q = motion({best, 1, 0}, ok);
    if (!(q.dd > 0)) break;
    const Real step = q.d / q.dd;
    best -= step;
    if (std::abs(step) < 1e-19L) break;
  }
  turn_ = best - pi_l;  // the lowest point at +-pi
  // The base circle the follower sees at its lowest: a circle about the cam centre its face or
  // roller touches there.
  const Jet low_x = centre_x(constant(pi_l)), low_y = centre_y(constant(pi_l));
  const Jet low = raw_motion(low_x, low_y, Rc_, ok);
  Real r0 = 0;
  const Real px = d_.pivot_x, py = d_.pivot_y, rr = d_.roller_radius;
  switch (d_.kind) {
    case Kind::flat: r0 = low.v; break;
    case Kind::roller: r0 = std::hypot(sigma_ * Real(d_.offset), low.v) - rr; ok = ok && low.v > 0; break;
    case Kind::pivoted_flat: r0 = k_ * (-std::sin(low.v) * px + std::cos(low.v) * py) - d_.face_offset; break;
    case Kind::pivoted_roller: r0 = std::hypot(px + d_.arm * std::cos(low.v), py + d_.arm * std::sin(low.v)) - rr; break;
  }
  base_radius_ = static_cast<double>(r0);
  if (!ok || !(base_radius_ > 0)) {
    valid_ = false;
    return;
  }
  const Real r0d = base_radius_;
  const Jet base = raw_motion(constant(0), constant(0), r0d, ok);
  base_motion_ = pivoted() ? k_ * std::remainder(base.v - psi_ref_, 2 * pi_l) : base.v;
  if (d_.kind == Kind::pivoted_flat) {
    const Real dist = std::hypot(px, py), w = r0d + d_.face_offset;
    lever_ = std::sqrt((dist - w) * (dist + w));
  } else if (d_.kind == Kind::pivoted_roller) {
    lever_ = d_.arm;
  }
  valid_ = ok;
}

inline Jet Reference::lift(Real phi) const {
  bool ok = true;
  return lever_ * (motion({phi, 1, 0}, ok) - constant(base_motion_));
}

inline Contact Reference::at(Real phi) const {
  Contact out;
  out.lift = lift(phi);
  const Real cx = centre_x(constant(phi)).v, cy = centre_y(constant(phi)).v;
  bool ok = true;
  const Real q = raw_motion(constant(cx), constant(cy), Rc_, ok).v;
  const Real px = d_.pivot_x, py = d_.pivot_y, rr = d_.roller_radius;
  Real x = 0, y = 0, pitch_x = 0, pitch_y = 0, nx = 0, ny = 0, vx = 0, vy = 1;  // contact, normal, motion
  switch (d_.kind) {
    case Kind::flat:
      nx = 0, ny = 1;
      out.face_position = sigma_ * cx;  // along the face's direction t = (sigma, 0)
      break;
    case Kind::roller: {
      pitch_x = sigma_ * Real(d_.offset), pitch_y = q;
      const Real dist = std::hypot(pitch_x - cx, pitch_y - cy);
      nx = (pitch_x - cx) / dist, ny = (pitch_y - cy) / dist;
      break;
    }
    case Kind::pivoted_flat:
      nx = -k_ * std::sin(q), ny = k_ * std::cos(q);  // m = k J e(psi)
      break;
    case Kind::pivoted_roller: {
      pitch_x = px + d_.arm * std::cos(q), pitch_y = py + d_.arm * std::sin(q);
      const Real dist = std::hypot(pitch_x - cx, pitch_y - cy);
      nx = (pitch_x - cx) / dist, ny = (pitch_y - cy) / dist;
      vx = -k_ * std::sin(q), vy = k_ * std::cos(q);  // k J e
      break;
    }
  }
  x = cx + Rc_ * nx, y = cy + Rc_ * ny;  // the circle's point with that outward normal
  if (d_.kind == Kind::pivoted_flat) {
    vx = -k_ * (y - py), vy = k_ * (x - px);                      // k J (x - P)
    out.face_position = std::cos(q) * (x - px) + std::sin(q) * (y - py);  // e.(x - P)
  }
  if (rr == 0) pitch_x = x, pitch_y = y;
  out.pressure_angle = sigma_ * std::atan2(vx * ny - vy * nx, vx * nx + vy * ny);
  out.curvature_radius = Rc_;
  if (pivoted()) out.follower_angle = out.lift.v / lever_;
  // Into the cam's frame: R(-sigma phi).
  const Real c = std::cos(sigma_ * phi), s = std::sin(sigma_ * phi);
  out.x = x * c + y * s, out.y = -x * s + y * c;
  out.pitch_x = pitch_x * c + pitch_y * s, out.pitch_y = -pitch_x * s + pitch_y * c;
  return out;
}

}  // namespace mechgraph::testing::eccentric
