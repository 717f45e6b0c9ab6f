#pragma once
// The smoothing spline of cam.table for measured lift tables: penalised least squares by a quintic
// spline with a knot at every row,
//
//     minimise  sum_{i=1}^{m-2} (y_i - s(x_i))^2  +  lambda hbar^7 integral (s'''')^2 dx,
//
// over the rows x_0 < ... < x_{m-1} of the lift event, with s(x_0) = s(x_{m-1}) = 0 held exactly (the
// base circle) and hbar = (x_{m-1} - x_0) / (m - 1) the mean row step, so lambda is dimensionless
// (lambda = 1: the penalty weighs as much as the misfit over about one row). A penalised regression
// spline (O'Sullivan 1986) in the space of quintic splines with a knot at every row (m + 4
// B-splines, ends clamped): acceleration and jerk are continuous (C4), and the penalty on the fourth
// derivative, the rate of change of the jerk, makes the jerk as smooth as the data allow.
//
// Why the fourth derivative and not the third (the classic quintic smoothing spline): the penalty's
// natural end conditions set its own derivative and the next to zero at the ends. With the third,
// s''' = 0 where the lift meets the base circle, where many cam laws have their largest jerk (a
// quartic or harmonic flank starts with a step of acceleration): on 7.5 (1 - (phi/62 deg)^2)^2 mm
// sampled every 2 deg and rounded to 1 um it pulls the acceleration at the ends down by 11 %; with the
// fourth, s'''' = s^(5) = 0 there and acceleration and jerk are free, 1.7 %. A fifth-derivative
// penalty (null space: quartics) would fit that quartic exactly, but does no better on polydynes and
// needs a lambda some thousand times larger per halving of the row step, beyond what the numerics
// hold on fine tables. lambda -> 0 gives an interpolating spline; lambda -> infinity the penalty's
// null space, the least-squares cubic through the two ends, (x - x_0)(x_{m-1} - x)(a + b x).
//
// The minimiser solves (G + lambda Omega) c = B^T y, G = B^T B, Omega = P^T P with P the fourth
// derivatives of the B-splines at three Gauss-Legendre points per row interval, weighted (exact:
// s'''' is linear there). Rather than these normal equations, whose condition number reaches
// lambda ~ 1e12 on fine tables, the stacked least-squares problem [B; sqrt(lambda) P] c = [y; 0] is
// reduced by Givens rotations to a banded triangular R (half bandwidth 5, as in Dierckx's FITPACK),
// with the square root of that condition number. The effective degrees of freedom, the trace of the
// influence matrix B (R^T R)^-1 B^T = trace((R^T R)^-1 G), come from the band of (R^T R)^-1,
// computed from R by the recursion of Hutchinson and de Hoog (1985): O(m) per lambda like the solve.
//
// lambda is chosen either by the discrepancy principle (the residual RMS equals the measurement
// noise, a root in log lambda by TOMS 748) or by generalised cross-validation (Craven and Wahba
// 1979: minimise V = m' RSS / (m' - dof)^2, m' = m - 2 the rows fitted: a grid in log lambda, then
// Brent's method around the grid's best point). Non-negative lift: every B-spline coefficient is
// kept >= 0 (a B-spline sum is then >= 0, the bases being >= 0), by an active set: negative
// coefficients are held at zero and the system solved again, a held one whose multiplier turns
// negative is freed. See docs/methods/valvetrain.md, "Measured lift tables".
#include "quintic_spline.hpp"

#include <array>
#include <vector>

namespace mechgraph::cams {

/// The work of the smoothing: least-squares solves (each a banded Givens QR), and the steps of the
/// lambda search and of the active set.
struct SmoothingWork {
  long solves = 0;
  long iterations = 0;
};

class QuinticSmoother {
 public:
  /// The range lambda is sought in: from lambda_min, where the fit interpolates the rows (the
  /// roughest shapes the rows carry have penalty weights of order 1), to lambda_max() =
  /// min(1e15, 1e4 (m - 1)^8). The smoothest shape outside the null space weighs about (m / pi)^8,
  /// so up to some 300 rows the upper end is the null space's fit; beyond, 1e15 keeps the degrees of
  /// freedom exact (their recursion loses all digits from about 1e19 on a 1200-row table).
  static constexpr double lambda_min = 1e-8;
  double lambda_max() const;
  static double lambda_max(double rows);

  /// The most steps the active set of fit_nonnegative takes; one more is NodeError("smoothing")
  /// (each step is a solve of O(rows): unbounded, the steps would make the fit quadratic in the rows).
  static constexpr int most_active_set_steps = 64;
  /// The most least-squares solves choosing lambda and fitting take on `rows` rows: gcv, the grid of
  /// quarter decades over [lambda_min, lambda_max] and at most 100 steps of Brent's method;
  /// resolution, the two ends and at most 200 steps of TOMS 748; then the active set, the final fit
  /// with its dof and the noise estimate's. A bound for the work estimate (cam.table's forecast).
  static double most_solves(bool gcv, double rows);

  /// x strictly increasing, at least 4 rows; y the lifts, y at the ends is held at zero whatever
  /// it is. Throws NodeError("file", ...) if fewer rows.
  QuinticSmoother(std::vector<double> x, std::vector<double> y);

  struct Fit {
    std::vector<double> coefficients;  // of the B-splines on knots()
    double lambda = 0.0;
    double rss = 0.0;          // sum of the squared residuals over the inner rows 1 .. m-2
    double dof = 0.0;          // trace of the influence matrix (when asked)
    int held_at_zero = 0;      // coefficients the non-negativity holds at zero
  };

  /// The fit at `lambda` (dimensionless, see above), without a sign constraint; dof if asked.
  Fit fit(double lambda, bool with_dof, SmoothingWork& work) const;
  /// The fit at `lambda` with every coefficient >= 0 (so the spline is >= 0), with its dof.
  Fit fit_nonnegative(double lambda, SmoothingWork& work) const;
  /// The coefficients fitting other values v at the same rows (v at the ends held at zero), with
  /// the same lambda and no sign constraint: the smoother is linear in the data.
  std::vector<double> smooth(const std::vector<double>& v, double lambda, SmoothingWork& work) const;

  /// lambda whose residual RMS over the inner rows is target_rms (discrepancy principle). At_limit
  /// is set when no lambda in [lambda_min, lambda_max()] reaches it (the nearest end is returned).
  double lambda_for_rms(double target_rms, bool& at_limit, SmoothingWork& work) const;
  /// lambda minimising the generalised cross-validation score; at_limit when the minimum lies at
  /// an end of [lambda_min, lambda_max()].
  double lambda_by_gcv(bool& at_limit, SmoothingWork& work) const;
  /// The GCV score m' RSS / (m' - dof)^2 at lambda.
  double gcv(double lambda, SmoothingWork& work) const;

  const std::vector<double>& knots() const { return t_; }
  QuinticPieces pieces(const std::vector<double>& coefficients) const { return quintic_pieces(t_, coefficients); }
  /// The rows fitted (all but the two ends).
  int inner_rows() const { return static_cast<int>(x_.size()) - 2; }

 private:
  using Band = std::vector<std::array<double, 6>>;  // symmetric band: a[j][d] = A(j, j + d)
  struct PenaltyRow {
    int first = 0;  // the B-spline of entries[0]
    std::array<double, 6> entries{};
  };
  /// The fit at lambda to the values y at the rows, the coefficients marked in `held` (by free
  /// index, empty: none) held at zero.
  Fit solve(double lambda, const std::vector<double>& y, const std::vector<char>& held, bool with_dof,
            SmoothingWork& work) const;
  double rss_of(const std::vector<double>& c, const std::vector<double>& y) const;

  std::vector<double> x_, y_, t_;
  std::vector<int> row_span_;                     // knot span of each row
  std::vector<std::array<double, 6>> row_basis_;  // the six B-splines nonzero there, at the row
  std::vector<PenaltyRow> penalty_rows_;          // P, Omega = P^T P (three Gauss points a row interval)
  double hbar_ = 0.0;
  int n_ = 0;     // B-splines: m + 4; the first and last are held at zero, the others free
  Band gram_;     // G = B^T B over the inner rows, on the free B-splines (index j - 1)
  Band penalty_;  // Omega, same indices
  std::vector<double> bty_;  // B^T y
};

}  // namespace mechgraph::cams
