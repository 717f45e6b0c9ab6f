#pragma once
// Quintic (degree 5) splines for cam.table: the B-spline basis on a clamped knot vector with its
// derivatives, the conversion of a B-spline to polynomial pieces in Taylor form (whose value and
// first three derivatives are exact closed forms), and the not-a-knot interpolant through a table.
// The smoothing spline (smoothing_spline.hpp) uses the same basis. See docs/methods/valvetrain.md,
// "Measured lift tables".
//
// Basis: de Boor, A Practical Guide to Splines (2001), ch. IX (Cox-de Boor recurrence, B-spline
// derivatives by differencing the lower-degree bases).
#include <array>
#include <string>
#include <vector>

namespace mechgraph::cams {

inline constexpr int quintic_degree = 5;

/// A piecewise quintic polynomial: on [breaks[i], breaks[i+1]] it is sum_r taylor[i][r] (x - breaks[i])^r,
/// so taylor[i][r] = s^(r)(breaks[i]) / r!.
struct QuinticPieces {
  std::vector<double> breaks;
  std::vector<std::array<double, 6>> taylor;

  /// s, s', s'', s''' at x (the piece containing x; the first or last piece outside the breaks).
  std::array<double, 4> at(double x) const;
  /// max over the pieces of |s^(k)|, k = 2 or 3, in closed form: per piece the ends and the roots of
  /// s^(k+1) (a quadratic for k = 2, linear for k = 3).
  double max_abs_derivative(int k) const;
  /// sqrt(integral (s^(k))^2 dx / length) over all pieces, k = 2 or 3: exact by four
  /// Gauss-Legendre points a piece (the integrand is a polynomial of degree 6 or 4).
  double rms_derivative(int k) const;
};

/// Index mu of the knot span t[mu] <= x < t[mu+1] holding x, for a clamped knot vector with n
/// B-splines (quintic_degree <= mu <= n - 1; x at the right end gives the last span).
int knot_span(const std::vector<double>& t, int n, double x);

/// Values of the six quintic B-splines nonzero on span mu at x, B_{mu-5} .. B_mu.
std::array<double, 6> quintic_basis(const std::vector<double>& t, int mu, double x);

/// d^r/dx^r of the six quintic B-splines nonzero on span mu at x, r = 0 .. 5 (row r), one-sided from
/// inside span mu at its ends.
std::array<std::array<double, 6>, 6> quintic_basis_derivatives(const std::vector<double>& t, int mu, double x);

/// The B-spline sum_j c_j B_j on knots t (c.size() + 6 knots, clamped) as Taylor pieces, one per
/// span of positive length.
QuinticPieces quintic_pieces(const std::vector<double>& t, const std::vector<double>& c);

/// The quintic spline interpolating (x_i, y_i) with the not-a-knot end conditions of de Boor
/// (interior knots at x_3 .. x_{n-4}; needs n >= 6 strictly increasing x). Built by collocation: the
/// collocation matrix is totally positive, so banded elimination without pivoting is stable.
/// Throws NodeError("file", where + ...) if the system is singular.
QuinticPieces interpolate_quintic(const std::vector<double>& x, const std::vector<double>& y, const std::string& where);

}  // namespace mechgraph::cams
