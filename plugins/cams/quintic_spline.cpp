#include "quintic_spline.hpp"

#include <mechgraph/errors.hpp>

#include <algorithm>
#include <cmath>

namespace mechgraph::cams {
namespace {

constexpr int p = quintic_degree;

// max |q(u)| over u in [0, h] for q(u) = c0 + c1 u + c2 u^2 + c3 u^3 (c3 may be 0): the ends and the
// roots of q' = c1 + 2 c2 u + 3 c3 u^2 inside.
double max_abs_cubic(double c0, double c1, double c2, double c3, double h) {
  auto q = [&](double u) { return c0 + u * (c1 + u * (c2 + u * c3)); };
  double best = std::max(std::abs(q(0.0)), std::abs(q(h)));
  auto consider = [&](double u) {
    if (u > 0.0 && u < h) best = std::max(best, std::abs(q(u)));
  };
  const double a = 3.0 * c3, b = 2.0 * c2, c = c1;
  if (a == 0.0) {
    if (b != 0.0) consider(-c / b);
    return best;
  }
  const double disc = b * b - 4.0 * a * c;
  if (disc < 0.0) return best;
  // The root of larger magnitude without cancellation, the other from the product of the roots.
  const double qq = -0.5 * (b + std::copysign(std::sqrt(disc), b));
  if (qq != 0.0) {
    consider(qq / a);
    consider(c / qq);
  } else {
    consider(0.0);
  }
  return best;
}

}  // namespace

std::array<double, 4> QuinticPieces::at(double x) const {
  const auto it = std::upper_bound(breaks.begin(), breaks.end() - 1, x);
  const std::size_t i = it == breaks.begin() ? 0 : std::min<std::size_t>(it - breaks.begin() - 1, taylor.size() - 1);
  const double u = x - breaks[i];
  const auto& a = taylor[i];
  // s = sum a_r u^r and its first three derivatives, by Horner.
  return {a[0] + u * (a[1] + u * (a[2] + u * (a[3] + u * (a[4] + u * a[5])))),
          a[1] + u * (2.0 * a[2] + u * (3.0 * a[3] + u * (4.0 * a[4] + u * 5.0 * a[5]))),
          2.0 * a[2] + u * (6.0 * a[3] + u * (12.0 * a[4] + u * 20.0 * a[5])),
          6.0 * a[3] + u * (24.0 * a[4] + u * 60.0 * a[5])};
}

double QuinticPieces::max_abs_derivative(int k) const {
  double best = 0.0;
  for (std::size_t i = 0; i < taylor.size(); ++i) {
    const auto& a = taylor[i];
    const double h = breaks[i + 1] - breaks[i];
    // s'' = 2 a2 + 6 a3 u + 12 a4 u^2 + 20 a5 u^3; s''' = 6 a3 + 24 a4 u + 60 a5 u^2.
    const double m = k == 2 ? max_abs_cubic(2.0 * a[2], 6.0 * a[3], 12.0 * a[4], 20.0 * a[5], h)
                            : max_abs_cubic(6.0 * a[3], 24.0 * a[4], 60.0 * a[5], 0.0, h);
    best = std::max(best, m);
  }
  return best;
}

double QuinticPieces::rms_derivative(int k) const {
  // Four-point Gauss-Legendre nodes and weights on [-1, 1].
  const double a = std::sqrt(3.0 / 7.0 - 2.0 / 7.0 * std::sqrt(1.2)), b = std::sqrt(3.0 / 7.0 + 2.0 / 7.0 * std::sqrt(1.2));
  const double wa = (18.0 + std::sqrt(30.0)) / 36.0, wb = (18.0 - std::sqrt(30.0)) / 36.0;
  const double nodes[4] = {-b, -a, a, b}, weights[4] = {wb, wa, wa, wb};
  double sum = 0.0;
  for (std::size_t i = 0; i < taylor.size(); ++i) {
    const double mid = 0.5 * (breaks[i] + breaks[i + 1]), half = 0.5 * (breaks[i + 1] - breaks[i]);
    for (int g = 0; g < 4; ++g) {
      const double v = at(mid + half * nodes[g])[k];
      sum += weights[g] * half * v * v;
    }
  }
  return std::sqrt(sum / (breaks.back() - breaks.front()));
}

int knot_span(const std::vector<double>& t, int n, double x) {
  const auto it = std::upper_bound(t.begin() + p + 1, t.begin() + n, x);
  return static_cast<int>(it - t.begin()) - 1;
}

std::array<double, 6> quintic_basis(const std::vector<double>& t, int mu, double x) {
  // Cox-de Boor: the degree-j values from the degree-(j-1) ones, B_{mu-j} .. B_mu.
  std::array<double, 6> N{};
  std::array<double, 6> left{}, right{};
  N[0] = 1.0;
  for (int j = 1; j <= p; ++j) {
    left[j] = x - t[mu + 1 - j];
    right[j] = t[mu + j] - x;
    double saved = 0.0;
    for (int r = 0; r < j; ++r) {
      const double temp = N[r] / (right[r + 1] + left[j - r]);
      N[r] = saved + right[r + 1] * temp;
      saved = left[j - r] * temp;
    }
    N[j] = saved;
  }
  return N;
}

std::array<std::array<double, 6>, 6> quintic_basis_derivatives(const std::vector<double>& t, int mu, double x) {
  // ndu holds the bases of every degree j (upper triangle, ndu[r][j] = B_{mu-j+r, j}) and the knot
  // differences (lower triangle, ndu[j][r] = t[mu+r+1] - t[mu+1-j+r], never zero on a span of
  // positive length). A derivative of a degree-p B-spline is p times a difference of two degree
  // p-1 ones divided by their knot spans (de Boor, ch. X); applied k times, with coefficients a.
  double ndu[p + 1][p + 1] = {};
  double left[p + 1] = {}, right[p + 1] = {};
  ndu[0][0] = 1.0;
  for (int j = 1; j <= p; ++j) {
    left[j] = x - t[mu + 1 - j];
    right[j] = t[mu + j] - x;
    double saved = 0.0;
    for (int r = 0; r < j; ++r) {
      ndu[j][r] = right[r + 1] + left[j - r];
      const double temp = ndu[r][j - 1] / ndu[j][r];
      ndu[r][j] = saved + right[r + 1] * temp;
      saved = left[j - r] * temp;
    }
    ndu[j][j] = saved;
  }
  std::array<std::array<double, 6>, 6> ders{};
  for (int j = 0; j <= p; ++j) ders[0][j] = ndu[j][p];
  for (int r = 0; r <= p; ++r) {
    double a[2][p + 1] = {};
    int s1 = 0, s2 = 1;
    a[0][0] = 1.0;
    for (int k = 1; k <= p; ++k) {
      double d = 0.0;
      const int rk = r - k, pk = p - k;
      if (r >= k) {
        a[s2][0] = a[s1][0] / ndu[pk + 1][rk];
        d = a[s2][0] * ndu[rk][pk];
      }
      const int j1 = rk >= -1 ? 1 : -rk;
      const int j2 = (r - 1 <= pk) ? k - 1 : p - r;
      for (int j = j1; j <= j2; ++j) {
        a[s2][j] = (a[s1][j] - a[s1][j - 1]) / ndu[pk + 1][rk + j];
        d += a[s2][j] * ndu[rk + j][pk];
      }
      if (r <= pk) {
        a[s2][k] = -a[s1][k - 1] / ndu[pk + 1][r];
        d += a[s2][k] * ndu[r][pk];
      }
      ders[k][r] = d;
      std::swap(s1, s2);
    }
  }
  // The factors p (p-1) ... (p-k+1).
  double factor = p;
  for (int k = 1; k <= p; ++k) {
    for (int j = 0; j <= p; ++j) ders[k][j] *= factor;
    factor *= (p - k);
  }
  return ders;
}

QuinticPieces quintic_pieces(const std::vector<double>& t, const std::vector<double>& c) {
  const int n = static_cast<int>(c.size());
  constexpr double factorial[p + 1] = {1.0, 1.0, 2.0, 6.0, 24.0, 120.0};
  QuinticPieces out;
  for (int mu = p; mu <= n - 1; ++mu) {
    if (!(t[mu + 1] > t[mu])) continue;
    const auto D = quintic_basis_derivatives(t, mu, t[mu]);
    std::array<double, 6> coef{};
    for (int r = 0; r <= p; ++r) {
      double v = 0.0;
      for (int k = 0; k <= p; ++k) v += c[mu - p + k] * D[r][k];
      coef[r] = v / factorial[r];
    }
    out.breaks.push_back(t[mu]);
    out.taylor.push_back(coef);
  }
  out.breaks.push_back(t[n]);
  return out;
}

QuinticPieces interpolate_quintic(const std::vector<double>& x, const std::vector<double>& y, const std::string& where) {
  const int n = static_cast<int>(x.size());
  // Knots: x_0 six times, the rows x_3 .. x_{n-4}, x_{n-1} six times (n + 6 knots, n B-splines).
  std::vector<double> t;
  t.reserve(n + p + 1);
  for (int k = 0; k <= p; ++k) t.push_back(x.front());
  for (int i = 3; i <= n - 4; ++i) t.push_back(x[i]);
  for (int k = 0; k <= p; ++k) t.push_back(x.back());

  // Collocation B c = y, band storage A(i, j) = band[i][j - i + 5], |j - i| <= 5.
  constexpr int w = p;
  std::vector<std::array<double, 2 * w + 1>> band(n);
  std::vector<double> c(y);
  for (int i = 0; i < n; ++i) {
    band[i].fill(0.0);
    const int mu = knot_span(t, n, x[i]);
    const auto N = quintic_basis(t, mu, x[i]);
    for (int r = 0; r <= p; ++r) {
      const int j = mu - p + r;
      if (std::abs(j - i) > w) {
        if (N[r] != 0.0) throw NodeError("file", where + "internal: collocation outside the band");
        continue;
      }
      band[i][j - i + w] = N[r];
    }
  }
  // Gaussian elimination without pivoting (the collocation matrix is totally positive).
  for (int k = 0; k < n; ++k) {
    const double pivot = band[k][w];
    if (!(std::abs(pivot) > 0.0)) throw NodeError("file", where + "the spline through the table is singular");
    for (int i = k + 1; i <= std::min(n - 1, k + w); ++i) {
      const double f = band[i][k - i + w] / pivot;
      if (f == 0.0) continue;
      for (int j = k; j <= std::min(n - 1, k + w); ++j) band[i][j - i + w] -= f * band[k][j - k + w];
      c[i] -= f * c[k];
    }
  }
  for (int k = n - 1; k >= 0; --k) {
    double sum = c[k];
    for (int j = k + 1; j <= std::min(n - 1, k + w); ++j) sum -= band[k][j - k + w] * c[j];
    c[k] = sum / band[k][w];
  }
  return quintic_pieces(t, c);
}

}  // namespace mechgraph::cams
