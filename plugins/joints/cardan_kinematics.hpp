#pragma once
// Kinematics of a single cardan (Hooke) joint with bend angle b between its shafts
// (methods/backlash.md, "Joint types"), input yoke angle t1 measured from the plane of the bend.
//
//   tan t2 = tan t1 / cos b,  i.e. t2 = atan2(sin t1, cos t1 cos b) on the principal branch.
//
// Evaluated in forms that stay accurate for b -> 0 and for cos b -> 0:
//   angular error  e = t2 - t1 = atan2(sin t1 cos t1 (1 - cos b), sin^2 t1 + cos^2 t1 cos b)
//       (from tan(t2 - t1) with (sin t2, cos t2) ~ (sin t1, cos t1 cos b); the second argument is
//       positive for cos b > 0, so |e| < pi/2 and e is continuous in t1), with 1 - cos b written
//       2 sin^2(b/2);
//   output angle   t2 = t1 + e (unwrapped: continuous in t1, within pi/2 of it, equal to the
//       closed form modulo 2 pi);
//   speed ratio    w2/w1 = dt2/dt1 = cos b / (1 - sin^2 b cos^2 t1)
//                        = cos b / (sin^2 t1 + cos^2 t1 cos^2 b)   (a sum of squares: no cancellation)
//       ranging from cos b (t1 = 90 deg) to 1/cos b (t1 = 0).
// The joint locks as b -> 90 deg: 1/cos b grows without bound. Every bend angle below 90 deg is
// accepted (the double below pi/2 has 1/cos b = 6.2e15, finite); for b >= 90 deg (the double
// nearest pi/2 included, as "90 deg" reads) the constructor throws NodeError("bend_angle").
namespace mechgraph::joints {

class CardanKinematics final {
 public:
  /// Throws NodeError("bend_angle") for b < 0, b >= pi/2 (the double) or NaN.
  explicit CardanKinematics(double bend_angle);

  double bend_angle() const { return b_; }
  /// e = t2 - t1 (rad).
  double angular_error(double t1) const;
  /// t2 = t1 + e (rad), continuous in t1.
  double output_angle(double t1) const { return t1 + angular_error(t1); }
  /// w2/w1 at input angle t1.
  double speed_ratio(double t1) const;
  double speed_ratio_min() const { return cos_b_; }
  double speed_ratio_max() const { return 1.0 / cos_b_; }

 private:
  double b_;
  double cos_b_;
  double one_minus_cos_b_;  // 2 sin^2(b/2)
};

}  // namespace mechgraph::joints
