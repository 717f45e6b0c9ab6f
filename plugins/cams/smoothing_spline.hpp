#pragma once
// The smoothing spline of cam.table for measured lift tables: penalised least squares by a quintic
// spline with a knot at every row,
//
//     minimise  sum_{i=1}^{m-2} (y_i - s(x_i))^2  +  lambda hbar^5 integral (s''')^2 dx,
//
// over the rows x_0 < ... < x_{m-1} of the lift event, with s(x_0) = s(x_{m-1}) = 0 held exactly (the
// base circle) and hbar = (x_{m-1} - x_0) / (m - 1) the mean row step, so lambda is dimensionless
// (lambda = 1: the penalty weighs as much as the misfit over about one row). The minimiser over all
// functions with a square-integrable third derivative is a quintic spline with knots at the rows
// (Schoenberg 1964, Reinsch 1967); here it is sought in the B-spline basis of that very space
// (m + 4 coefficients, ends clamped), so the solution is exact, not a P-spline approximation: its
// acceleration and jerk are continuous and the jerk is what the data support. lambda -> 0 gives the
// interpolating spline with the natural ends s''' = s'''' = 0; lambda -> infinity the penalty's null
// space, the least-squares parabola a (x - x_0)(x_{m-1} - x).
//
// Normal equations (G + lambda Omega) c = B^T y, G = B^T B, Omega_jk = integral B_j''' B_k''' dx (three
// Gauss-Legendre points per row interval: exact, the integrand is a quartic), both banded with half
// bandwidth 5; solved by a banded LDL^T. The effective degrees of freedom, the trace of the
// influence matrix B (G + lambda Omega)^-1 B^T = trace((G + lambda Omega)^-1 G), come from the band
// of the inverse, computed from the factor by the recursion of Hutchinson and de Hoog (1985):
// O(m) per lambda like the solve.
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

/// The work of the smoothing: banded factorisations, and the steps of the lambda search and the
/// active set.
struct SmoothingWork {
  long solves = 0;
  long iterations = 0;
};

class QuinticSmoother {
 public:
  /// The searchable range of lambda: below it the fit is the interpolant to 1e-8 of the lift,
  /// above it the normal equations lose the digits of the penalty's null space.
  static constexpr double lambda_min = 1e-8;
  static constexpr double lambda_max = 1e12;

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
  /// is set when no lambda in [lambda_min, lambda_max] reaches it (the nearest end is returned).
  double lambda_for_rms(double target_rms, bool& at_limit, SmoothingWork& work) const;
  /// lambda minimising the generalised cross-validation score; at_limit when the minimum lies at
  /// an end of [lambda_min, lambda_max].
  double lambda_by_gcv(bool& at_limit, SmoothingWork& work) const;
  /// The GCV score m' RSS / (m' - dof)^2 at lambda.
  double gcv(double lambda, SmoothingWork& work) const;

  const std::vector<double>& knots() const { return t_; }
  QuinticPieces pieces(const std::vector<double>& coefficients) const { return quintic_pieces(t_, coefficients); }
  /// The rows fitted (all but the two ends).
  int inner_rows() const { return static_cast<int>(x_.size()) - 2; }

 private:
  using Band = std::vector<std::array<double, 6>>;  // symmetric band: a[j][d] = A(j, j + d)
  Fit solve(double lambda, const std::vector<double>& rhs, const std::vector<char>& held, bool with_dof,
            SmoothingWork& work) const;
  double rss_of(const std::vector<double>& c, const std::vector<double>& y) const;

  std::vector<double> x_, y_, t_;
  std::vector<int> row_span_;                     // knot span of each row
  std::vector<std::array<double, 6>> row_basis_;  // the six B-splines nonzero there, at the row
  double hbar_ = 0.0;
  int n_ = 0;     // B-splines: m + 4; the first and last are held at zero, the others free
  Band gram_;     // B^T B over the inner rows, on the free B-splines (index j - 1)
  Band penalty_;  // hbar^5 integral B_j''' B_k''' dx, same indices
  std::vector<double> bty_;  // B^T y
};

}  // namespace mechgraph::cams
