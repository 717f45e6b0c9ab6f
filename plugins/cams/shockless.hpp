#pragma once
// Shockless cams built from their acceleration diagram (docs/methods/valvetrain.md, stage 1,
// "Kurz cam"): the positive-acceleration phase is a chain of shapes scaled by one amplitude A+,
// the negative phase (to the nose) a chain scaled by A-; the shapes start and end where their
// neighbours do, so the acceleration is continuous, and the first starts at zero (no shock at the
// start of lift). With x from the start of lift, h(0) = h'(0) = 0 and the two amplitudes follow
// from the two linear conditions at the nose x = phi_p:
//     h'(phi_p) = A+ V+ + A- V- = 0,   h(phi_p) = A+ H+ + A- H- = h_max,
// where (H, V) are the lift and velocity at the nose that each phase gives at unit amplitude.
// The law is symmetric about the nose: h(phi) = H(phi_p - |phi|).
//
// A shape lives on the unit interval tau in [0, 1]; on a segment of length L starting at x_k with
// amplitude A:  h'' = A a(tau),  h''' = A a'(tau) / L,  h' = v_k + A L I1(tau),
// h = h_k + v_k (x - x_k) + A L^2 I2(tau), with I1, I2 the first and second integrals from 0.
// Every shape gives these in closed form, so the lift and its derivatives are exact.
#include <mechgraph/domain/cam_law.hpp>

#include <atomic>
#include <memory>
#include <mutex>
#include <span>
#include <vector>

namespace mechgraph::cams {

struct ShapeValues {
  double value, slope, integral, integral2;
};

/// What a law reads of a shape at the ends of its unit interval.
struct ShapeEnds {
  double value0 = 0.0;     // a(0)
  double value1 = 0.0;     // a(1)
  double slope1 = 0.0;     // a'(1)
  double integral1 = 0.0;  // I1(1)
  double integral2 = 0.0;  // I2(1)
  bool has_moments = false;  // moments(1) gave these:
  double i3 = 0.0, j1 = 0.0, j2 = 0.0;
};

/// One piece of an acceleration diagram on tau in [0, 1], with exact derivative and integrals.
class AccelShape {
 public:
  virtual ~AccelShape() = default;
  virtual double value(double tau) const = 0;      // a(tau)
  virtual double slope(double tau) const = 0;      // da/dtau
  virtual double integral(double tau) const = 0;   // I1(tau) = int_0^tau a
  virtual double integral2(double tau) const = 0;  // I2(tau) = int_0^tau I1
  /// All four at once (the trigonometric shapes share one sine and cosine).
  virtual ShapeValues all(double tau) const { return {value(tau), slope(tau), integral(tau), integral2(tau)}; }
  /// Whether a(tau) is monotone on [0, 1] (a law of such shapes declares its monotone runs).
  virtual bool monotone() const { return false; }
  /// I3 = int_0^tau I2, J1 = int_0^tau t I2(t) dt, J2 = int_0^tau I2(t)^2 dt in closed form (a law
  /// of such shapes gives the integrals of h and h^2); false if the shape has none.
  virtual bool moments(double /*tau*/, double& /*i3*/, double& /*j1*/, double& /*j2*/) const { return false; }
  /// a(0), a(1), a'(1), I1(1), I2(1) and the moments at 1 by the functions above, computed once
  /// per shape and kept (a sweep builds a law per case from the same few shapes); thread-safe.
  const ShapeEnds& ends() const { return ends_ready_.load(std::memory_order_acquire) ? ends_ : make_ends(); }

 private:
  const ShapeEnds& make_ends() const;
  mutable std::once_flag ends_once_;
  mutable std::atomic<bool> ends_ready_{false};  // set once ends_ is made: then read without a call
  mutable ShapeEnds ends_;
};

/// a = sin(pi tau / 2): a quarter sine rising from 0 to 1 (zero acceleration, finite jerk at 0).
class QuarterSineRise final : public AccelShape {
 public:
  ShapeValues all(double tau) const override;
  double value(double tau) const override;
  double slope(double tau) const override;
  double integral(double tau) const override;
  double integral2(double tau) const override;
  bool monotone() const override { return true; }
  bool moments(double tau, double& i3, double& j1, double& j2) const override;
};

/// a = cos(pi tau / 2): a quarter cosine falling from 1 to 0 (zero jerk at its start).
class QuarterCosineFall final : public AccelShape {
 public:
  ShapeValues all(double tau) const override;
  double value(double tau) const override;
  double slope(double tau) const override;
  double integral(double tau) const override;
  double integral2(double tau) const override;
  bool monotone() const override { return true; }
  bool moments(double tau, double& i3, double& j1, double& j2) const override;
};

/// a = 1 - (1 - tau)^2: a parabola from 0 to its vertex 1 at tau = 1 (zero slope there, so a
/// law that ends with it at the nose has a continuous jerk across the nose).
class ParabolaToVertex final : public AccelShape {
 public:
  ShapeValues all(double tau) const override;  // the four below, without four virtual calls
  double value(double tau) const override;
  double slope(double tau) const override;
  double integral(double tau) const override;
  double integral2(double tau) const override;
  bool monotone() const override { return true; }
  bool moments(double tau, double& i3, double& j1, double& j2) const override;
};

struct ShapeSegment {
  std::shared_ptr<const AccelShape> shape;
  double length = 0.0;  // rad of cam angle
};

/// The generic law. Shapes are given as non-negative bumps; A+ comes out > 0 and A- < 0.
class ShocklessLaw final : public CamLaw {
 public:
  /// The segment lengths of both phases must add up to half the action angle. Throws
  /// std::invalid_argument if the shapes do not join continuously (a programming error).
  ShocklessLaw(double max_lift, double action_angle, double base_radius, std::span<const ShapeSegment> positive,
               std::span<const ShapeSegment> negative);
  ShocklessLaw(double max_lift, double action_angle, double base_radius, const std::vector<ShapeSegment>& positive,
               const std::vector<ShapeSegment>& negative)
      : ShocklessLaw(max_lift, action_angle, base_radius, std::span<const ShapeSegment>(positive),
                     std::span<const ShapeSegment>(negative)) {}

  double event_begin() const override { return -half_action_; }
  double event_end() const override { return half_action_; }
  LiftDerivatives evaluate_in_event(double phi) const override;
  /// Every segment junction on both sides (the formula changes there; at some of them only
  /// derivatives above the third jump, which quadrature still likes to know), and the nose if
  /// the jerk does not vanish there.
  std::vector<double> breakpoints() const override { return breakpoints_; }
  double max_lift() const override { return max_lift_; }
  double base_radius() const override { return base_radius_; }
  /// With monotone shapes: the junctions and the nose for the velocity and the acceleration, the
  /// nose alone for the lift (the shapes are non-negative bumps, A+ > 0 > A-: h'' keeps one sign
  /// per phase, so h' rises then falls back to 0 at the nose and the lift is monotone on each side
  /// of it).
  bool monotone_breaks(int order, std::vector<double>& breaks) const override;
  /// With shapes that give their moments: the integrals of h and h^2 in closed form.
  bool lift_integrals(double a, double b, double& integral, double& integral_of_square) const override;

  double positive_amplitude() const { return amplitude_pos_; }  // A+, m/rad^2
  double negative_amplitude() const { return amplitude_neg_; }  // A-, m/rad^2 (< 0)
  /// Junctions measured from the start of lift, x_1 ... x_{n-1}.
  std::vector<double> junctions_from_start() const;
  /// breakpoints() without the copy.
  const std::vector<double>& breakpoint_list() const { return breakpoints_; }

 private:
  struct Piece {
    std::shared_ptr<const AccelShape> shape;
    double start = 0.0;   // x_k from the start of lift
    double length = 0.0;
    double amplitude = 0.0;
    double lift0 = 0.0;      // h at x_k
    double velocity0 = 0.0;  // h' at x_k
  };
  double max_lift_ = 0.0;
  double half_action_ = 0.0;
  double base_radius_ = 0.0;
  double amplitude_pos_ = 0.0;
  double amplitude_neg_ = 0.0;
  std::vector<Piece> pieces_;
  std::vector<double> breakpoints_;
};

}  // namespace mechgraph::cams
