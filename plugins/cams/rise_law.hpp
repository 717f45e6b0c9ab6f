#pragma once
// The textbook rise laws as a normalised rise s(x), and the symmetric rise-return cam built on one.
// See docs/methods/valvetrain.md, stage 1 ("Beyond the source: the laws engineers expect").
//
// Normalised rise: x in [0, 1] (fraction of the rise angle) -> s in [0, 1], with s(0) = 0, s(1) = 1,
// s'(0) = s'(1) = 0 and s', s'', s''' exact (derivatives over x). Every one of the six laws is
// antisymmetric about the middle of the rise, s(x) = 1 - s(1 - x).
//
// Peak coefficients (max s', max |s''|), closed forms of the formulas in rise_law.cpp:
//   cycloidal            2                      2 pi                 = 6.2832
//   harmonic             pi/2     = 1.5708      pi^2/2               = 4.9348
//   poly345              15/8     = 1.8750      10/sqrt(3)           = 5.7735
//   poly4567             35/16    = 2.1875      84 sqrt(5)/25        = 7.5132
//   modified_trapezoid   2                      8 pi/(2+pi)          = 4.8881
//   modified_sine        4 pi/(4+pi) = 1.7596   4 pi^2/(4+pi)        = 5.5280
#include <mechgraph/domain/cam_law.hpp>

#include <array>
#include <optional>
#include <string_view>
#include <vector>

namespace mechgraph::cams {

enum class RiseShape { cycloidal, harmonic, poly345, poly4567, modified_trapezoid, modified_sine };

inline constexpr std::array<RiseShape, 6> all_rise_shapes{RiseShape::cycloidal,     RiseShape::harmonic,
                                                         RiseShape::poly345,       RiseShape::poly4567,
                                                         RiseShape::modified_trapezoid, RiseShape::modified_sine};

/// s and its first three derivatives over x.
struct RiseValue {
  double s = 0.0;
  double ds = 0.0;
  double d2s = 0.0;
  double d3s = 0.0;
};

/// The normalised rise at x; x is clamped to [0, 1].
RiseValue evaluate_rise(RiseShape shape, double x);

/// Junctions of the pieces strictly inside (0, 1), ascending: there the formula changes (s''' is
/// continuous at them for the modified trapezoid and modified sine, s'''' is not).
std::vector<double> rise_breakpoints(RiseShape shape);

/// The highest derivative of the symmetric rise-return cam (dwell, rise, return, dwell) that is
/// continuous everywhere: 1 harmonic (acceleration jumps at the start of lift), 3 poly4567 (the
/// fourth derivative jumps), 2 for the others (jerk jumps at the start of lift and at the nose).
int rise_return_continuity(RiseShape shape);

/// "cycloidal", "harmonic", "poly345", "poly4567", "modified_trapezoid", "modified_sine".
std::string_view rise_shape_name(RiseShape shape);
std::optional<RiseShape> rise_shape_from_name(std::string_view name);

/// A cam whose lift rises by a normalised law over half the action angle to max_lift at the nose
/// (phi = 0) and returns symmetrically:
///   rise   (-phi_d/2 < phi <= 0):  x = (phi + phi_d/2)/(phi_d/2),  h = H s(x)
///   return (0 < phi < phi_d/2):    x = (phi_d/2 - phi)/(phi_d/2),  h = H s(x)
/// with h^(k) = H s^(k)(x) (2/phi_d)^k on the rise; on the return the odd derivatives change sign.
class SymmetricRiseReturnLaw final : public CamLaw {
 public:
  /// max_lift [m] > 0, 0 < action_angle [rad] < 2 pi, base_radius [m] > 0, roller_radius [m] >= 0;
  /// throws NodeError naming the parameter otherwise.
  SymmetricRiseReturnLaw(RiseShape shape, double max_lift, double action_angle, double base_radius,
                         double roller_radius = 0.0);

  double event_begin() const override { return -half_action_; }
  double event_end() const override { return half_action_; }
  LiftDerivatives evaluate_in_event(double phi) const override;
  /// The junctions of the rise's and the return's pieces and the nose, where the formula changes
  /// (a superset of the contract's discontinuities: at some only the fourth derivative steps).
  std::vector<double> breakpoints() const override;
  double max_lift() const override { return max_lift_; }
  double base_radius() const override { return base_radius_; }
  double roller_radius() const override { return roller_radius_; }

  RiseShape shape() const { return shape_; }

 private:
  RiseShape shape_;
  double max_lift_;
  double half_action_;
  double base_radius_;
  double roller_radius_;
};

}  // namespace mechgraph::cams
