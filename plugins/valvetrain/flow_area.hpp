#pragma once
// Flow area of a poppet valve with a conical seat (docs/methods/valvetrain.md, stage 3).
//
// Conical (the source): f = pi L (d0 cos a + L sin a cos^2 a), for valve lift L, seat angle a
// (from the valve axis' normal, 45 deg usual), inner seat diameter d0. It holds only while the
// flow is bounded by the seat cone, L <= w / (sin a cos a) with seat width w.
//
// Three-stage (Heywood, Internal Combustion Engine Fundamentals, sec. 6.3), with mean seat
// diameter Dm = d0 + w, port diameter Dp, stem diameter Ds:
//  1. L <= w/(sin a cos a):                f = pi L cos a (d0 + L sin a cos a)   (same as conical)
//  2. up to L2 = sqrt(((Dp^2 - Ds^2)/(4 Dm))^2 - w^2) + w tan a:
//                                          f = pi Dm sqrt((L - w tan a)^2 + w^2)
//  3. beyond:                              f = pi/4 (Dp^2 - Ds^2)                (the port)
#include <vector>

namespace mechgraph::valvetrain {

struct SeatGeometry {
  double inner_diameter = 0.0;  // d0
  double seat_angle = 0.0;      // a
  bool three_stage = false;
  double seat_width = 0.0;      // w
  double port_diameter = 0.0;   // Dp
  double stem_diameter = 0.0;   // Ds
};

class FlowArea {
 public:
  /// Throws NodeError for inconsistent three-stage geometry (port area below the seat's).
  explicit FlowArea(const SeatGeometry& seat);
  double operator()(double lift) const;
  /// Lifts where the formula changes stage (empty for the conical formula).
  const std::vector<double>& stage_lifts() const { return stage_lifts_; }
  /// The conical formula as f = k1 L + k2 L^2 (k1 = pi d0 cos a, k2 = pi sin a cos^2 a); false
  /// for the three-stage formula.
  bool quadratic(double& k1, double& k2) const;

 private:
  SeatGeometry seat_;
  double lift_1_ = 0.0, lift_2_ = 0.0, mean_diameter_ = 0.0, port_area_ = 0.0;
  std::vector<double> stage_lifts_;
};

}  // namespace mechgraph::valvetrain
