#pragma once
// Polydyne valve polynomial (Dudley 1948, Stoddart 1953; docs/methods/valvetrain.md, stage 1):
//     x(u) = h [1 + C2 u^2 + Cp u^p + Cq u^q + Cr u^r + Cs u^s],   u = phi / phi_p in [-1, 1],
// u = 0 at the nose, even exponents 2 < p < q < r < s (symmetric law), and
// x(1) = x'(1) = x''(1) = x'''(1) = x''''(1) = 0 (the valve leaves and meets the seat smoothly).
//
// Coefficients in closed form. With n_0 = 0 (the constant term, coefficient 1) and n_1..n_5 the
// exponents, the five end conditions say sum_i C_i Q(n_i) = 0 for every polynomial Q of degree
// <= 4 in n (the falling factorials n(n-1)..(n-m+1) span them), so C_i are the weights of the 5th
// divided difference over n_0..n_5, scaled to C_0 = 1:
//     C_i = - prod_{j != i} n_j / prod_{j != i} (n_i - n_j)          (j over 1..5)
// e.g. 2-6-10-14-18: C = -315/128, 105/32, -189/64, 45/32, -35/128. Exact rationals, no linear
// solve of the (cond ~1e7) monomial system.
//
// Evaluation keeps its digits near the seat. Near u = 1 the sum of the large alternating terms
// cancels (at u = 1 - 1e-4 the lift is ~1e-18 h). Every derivative has a zero of order 5 - m at
// u = 1, so x^(m)(u) = (1 - u)^(5-m) q_m(u); q_m is found exactly (cpp_rational: division by
// (1 - u) is a prefix sum of the coefficients) once, and evaluated by Horner in u in long double.
// q_0 has only positive and q_1 only negative coefficients (checked at construction), so lift and
// velocity are free of cancellation on the whole of [0, 1]; q_2 and q_3 change sign once inside,
// where h'' and h''' must. 1 - u is formed as (phi_p - |phi|) / phi_p, exactly to one rounding.
#include "cam_node.hpp"

#include <mechgraph/domain/cam_law.hpp>

#include <array>
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

namespace mechgraph::cams {

/// Checks the `exponents` parameter: exactly five even integers, the first 2, strictly
/// increasing, none above 1000. Throws NodeError naming "exponents".
std::vector<int> validate_polydyne_exponents(const std::vector<double>& exponents);

struct PolydyneSeries;
/// The series of one exponent set (as validate_polydyne_exponents returns it), made once and
/// shared by every law of it through a small, bounded, thread-safe table.
std::shared_ptr<const PolydyneSeries> polydyne_series(const std::vector<int>& exponents);

/// C2, Cp, Cq, Cr, Cs as exact fractions (numerator, denominator > 0, reduced).
std::vector<std::pair<std::int64_t, std::int64_t>> polydyne_coefficients_exact(const std::vector<int>& exponents);

/// The polynomials q_m (x^(m)(u)/h = (1 - u)^(5-m) q_m(u), m = 0..5) of one exponent set.
/// A polynomial of few nonzero terms (the primitives of a polydyne and of its square: a handful
/// of powers up to 2 n_max + 1), by Horner's rule over the gaps between its powers, each power of
/// u a gap needs made once per evaluation: about 40 long double operations where the dense rule
/// takes 2 n_max + 2.
class SparsePolynomial {
 public:
  SparsePolynomial() = default;
  explicit SparsePolynomial(const std::vector<long double>& dense);  // monomial coefficients
  long double operator()(long double u) const;

 private:
  struct Term {
    long double coefficient;
    std::size_t gap;  // index into gaps_ of the gap down to the next lower power (or to 0)
  };
  std::size_t gap_index(int gap);

  std::vector<Term> terms_;  // nonzero, highest power first
  std::vector<int> gaps_;    // the distinct gaps
};

struct PolydyneSeries {
  std::vector<int> exponents;                        // 2, p, q, r, s: what the rest is of
  std::array<std::vector<long double>, 6> q;        // monomial coefficients, exact to long double
  std::vector<std::array<double, 4>> interleaved;   // q_0..q_3 in double, power by power
  std::vector<double> coefficients;                 // C2, Cp, Cq, Cr, Cs
  /// For m = 1..3: every u in (0, 1) where q_m changes sign (so the m-th derivative does),
  /// ascending: the monotone runs of the (m-1)-th (CamLaw::monotone_breaks), found once per
  /// exponent set.
  std::array<std::vector<double>, 4> sign_changes;
  /// int_0^U x du and int_0^U x^2 du as polynomials in U (monomial coefficients).
  std::vector<long double> lift_primitive, square_primitive;
  SparsePolynomial lift_primitive_sparse, square_primitive_sparse;  // the same, by their nonzero terms
};

class PolydyneLaw final : public CamLaw {
 public:
  /// `exponents` as returned by validate_polydyne_exponents.
  PolydyneLaw(double max_lift, double action_angle, double base_radius, std::vector<int> exponents);
  /// With the series of its exponents found already (polydyne_series; a block finds it once).
  PolydyneLaw(double max_lift, double action_angle, double base_radius, std::shared_ptr<const PolydyneSeries> series);

  double event_begin() const override { return -half_action_; }
  double event_end() const override { return half_action_; }
  LiftDerivatives evaluate_in_event(double phi) const override;
  bool higher_derivatives(double phi, double& d4, double& d5) const override;
  std::vector<double> breakpoints() const override { return {}; }
  double max_lift() const override { return max_lift_; }
  double base_radius() const override { return base_radius_; }
  /// The nose and the sign changes of q_(order+1), mirrored (x is even in u).
  bool monotone_breaks(int order, std::vector<double>& breaks) const override;
  /// The integrals of h and h^2 from the exact polynomial primitives.
  bool lift_integrals(double a, double b, double& integral, double& integral_of_square) const override;

  const std::vector<int>& exponents() const { return series_->exponents; }
  /// C2, Cp, Cq, Cr, Cs, each the correctly rounded double of the exact fraction.
  const std::vector<double>& coefficients() const { return series_->coefficients; }
  /// d^m/du^m of x(u)/h at u = 1 - w (0 <= w <= 1), m = 0..5, in long double.
  long double normalized_derivative(int m, long double w) const;

 private:
  double max_lift_ = 0.0;
  double half_action_ = 0.0;
  double base_radius_ = 0.0;
  std::shared_ptr<const PolydyneSeries> series_;  // shared by every law of these exponents
};

/// The polydyne polynomial with real exponents 2 < n_2 < ... < n_5 (the family [2, q, q+s, q+2s,
/// q+3s] that `accel_angle` solves for). Coefficients from the same divided-difference weights in
/// long double; evaluated as the sum of powers of u = |phi| / phi_p in long double, so near the
/// seat the terms cancel, so there (w = 1 - u below 2 / n_max) the law is summed as its series in
/// w instead: x/h = sum_{k>=5} a_k (-w)^k, a_k = sum_i C_i binom(n_i, k) (a_0..a_4 vanish by the end
/// conditions), which keeps the relative accuracy of lift and derivatives up to the seat.
class RealPolydyneLaw final : public CamLaw {
 public:
  RealPolydyneLaw(double max_lift, double action_angle, double base_radius, std::vector<long double> exponents);
  double event_begin() const override { return -half_action_; }
  double event_end() const override { return half_action_; }
  LiftDerivatives evaluate_in_event(double phi) const override;
  bool higher_derivatives(double phi, double& d4, double& d5) const override;
  std::vector<double> breakpoints() const override { return {}; }
  double max_lift() const override { return max_lift_; }
  double base_radius() const override { return base_radius_; }
  /// d^m/du^m of x(u)/h, m = 0..5, at u in [0, 1].
  long double normalized_derivative(int m, long double u) const;
  /// d^m/du^m of x(u)/h for m = 0..m_max (<= 5) into d[0..m_max], with one power per term.
  void normalized_derivatives(long double u, int m_max, long double* d) const;

 private:
  double max_lift_ = 0.0;
  double half_action_ = 0.0;
  double base_radius_ = 0.0;
  std::vector<long double> exponents_;     // 0 (the constant), 2, q, q+s, q+2s, q+3s
  std::vector<long double> coefficients_;  // 1, C2, Cq, ...
  std::vector<long double> seat_series_;   // a_k of x/h = sum_k a_k (-w)^k, w = 1 - u (a_0..a_4 = 0)
  long double seat_zone_ = 0.0L;           // w below which the series is used
};

/// The positive-acceleration phase (from the start of lift) of the polydyne with exponents
/// [2, q, q+s, q+2s, q+3s] over `action_angle`: phi_p (1 - u*), x''(u*) = 0.
double polydyne_accel_angle(double q, double step, double action_angle);
/// The largest q found for accel_angle with step s: the last exponent q + 3 s stays at most 1000.
/// The narrowest phase, polydyne_accel_angle(polydyne_q_max(1), 1, min_action_angle), is
/// accel_angle's least value.
inline double polydyne_q_max(double step) { return 1000.0 - 3.0 * step; }

/// cam.polydyne: exponents (default 2, 6, 10, 14, 18), or accel_angle with exponent_step; extra
/// output exponent_q (the second exponent).
CamLawDefinition polydyne_definition();

}  // namespace mechgraph::cams
