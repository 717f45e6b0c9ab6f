#include "smoothing_spline.hpp"

#include <mechgraph/errors.hpp>

#include <boost/math/tools/minima.hpp>
#include <boost/math/tools/roots.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>

namespace mechgraph::cams {
namespace {

constexpr int p = quintic_degree;
constexpr int w = p;  // half bandwidth of the normal equations; every row has w + 1 consecutive entries

// The upper triangular band factor R of a least-squares problem (R[j][d] = R(j, j + d)), built a row
// at a time by Givens rotations (as in Dierckx's FITPACK): each row of the stacked system
// [B; sqrt(lambda) P] c = [y; 0] is rotated into R, its right-hand side into z. Working on the rows
// rather than on the normal equations G + lambda Omega = R^T R keeps the condition number at the
// square root of theirs: with lambda up to 1e12 the normal equations would lose 12 digits.
class BandQr {
 public:
  explicit BandQr(int n) : r_(n), z_(n, 0.0), set_(n, 0) {}

  // Adds the row with entries a[0..w] at columns first .. first + w (entries at columns outside
  // 0 .. n-1 must be zero) and right-hand side beta. The row is held in a window h[t] = entry at
  // column j + t that moves right as its leading entry is rotated out: each rotation with row j of R
  // (columns j .. j + w) fills the window up to column j + w.
  void add(int first, const std::array<double, w + 1>& a, double beta) {
    const int n = static_cast<int>(r_.size());
    std::array<double, w + 1> h = a;
    for (int j = first; j < n; ++j) {
      if (std::all_of(h.begin(), h.end(), [](double v) { return v == 0.0; })) return;
      if (j >= 0 && h[0] != 0.0) {
        if (!set_[j]) {  // an empty row of R takes the row as it is
          set_[j] = 1;
          r_[j] = h;
          z_[j] = beta;
          return;
        }
        const double pivot = r_[j][0], rho = std::hypot(pivot, h[0]);
        const double c = pivot / rho, s = h[0] / rho;
        for (int t = 0; t <= w; ++t) {
          const double rv = r_[j][t], hv = h[t];
          r_[j][t] = c * rv + s * hv;
          h[t] = -s * rv + c * hv;
        }
        const double zv = z_[j];
        z_[j] = c * zv + s * beta;
        beta = -s * zv + c * beta;
      }
      for (int t = 0; t < w; ++t) h[t] = h[t + 1];
      h[w] = 0.0;
    }
  }

  // Back substitution R c = z; false if R is singular (an unset row or a zero on the diagonal).
  bool solve(std::vector<double>& c) const {
    const int n = static_cast<int>(r_.size());
    c.assign(n, 0.0);
    double largest = 0.0;
    for (int j = 0; j < n; ++j) largest = std::max(largest, std::abs(r_[j][0]));
    for (int j = n - 1; j >= 0; --j) {
      if (!set_[j] || !(std::abs(r_[j][0]) > 1e-14 * largest)) return false;
      double s = z_[j];
      for (int d = 1; d <= w && j + d < n; ++d) s -= r_[j][d] * c[j + d];
      c[j] = s / r_[j][0];
    }
    return true;
  }

  // The band of (R^T R)^-1 (z[i][d] = Z(i, i + d)), by the recursion of Hutchinson and de Hoog
  // (1985): with R^T R = L D L^T, L(k, i) = R(i, k) / R(i, i), D_i = R(i, i)^2, the identity
  // L^T Z = D^-1 L^-1, whose upper triangle is diag(1/D), gives for j >= i
  //     Z(i, j) = delta_ij / D_i - sum_{k = i+1}^{i+w} L(k, i) Z(k, j),
  // run from the last row up; every Z(k, j) it needs lies in the band already computed.
  std::vector<std::array<double, w + 1>> inverse_band() const {
    const int n = static_cast<int>(r_.size());
    std::vector<std::array<double, w + 1>> z(n);
    auto Z = [&](int i, int j) -> double& { return i <= j ? z[i][j - i] : z[j][i - j]; };
    for (int i = n - 1; i >= 0; --i) {
      const int hi = std::min(n - 1, i + w);
      const double rii = r_[i][0];
      for (int j = hi; j >= i; --j) {
        double s = j == i ? 1.0 / (rii * rii) : 0.0;
        for (int k = i + 1; k <= hi; ++k) s -= (r_[i][k - i] / rii) * Z(k, j);
        Z(i, j) = s;
      }
    }
    return z;
  }

 private:
  std::vector<std::array<double, w + 1>> r_;
  std::vector<double> z_;
  std::vector<char> set_;
};

}  // namespace

QuinticSmoother::QuinticSmoother(std::vector<double> x, std::vector<double> y) : x_(std::move(x)), y_(std::move(y)) {
  const int m = static_cast<int>(x_.size());
  if (m < 4 || y_.size() != x_.size()) throw NodeError("file", "the smoothing spline needs at least 4 rows");
  for (int k = 0; k <= p; ++k) t_.push_back(x_.front());
  for (int i = 1; i <= m - 2; ++i) t_.push_back(x_[i]);
  for (int k = 0; k <= p; ++k) t_.push_back(x_.back());
  n_ = static_cast<int>(t_.size()) - p - 1;
  hbar_ = (x_.back() - x_.front()) / (m - 1);
  const int nf = n_ - 2;
  gram_.assign(nf, {});
  penalty_.assign(nf, {});
  bty_.assign(nf, 0.0);
  auto free_index = [&](int j) { return j >= 1 && j <= n_ - 2; };

  // The rows of B: the six B-splines nonzero at each row; G = B^T B and B^T y over the inner rows.
  row_span_.assign(m, 0);
  row_basis_.assign(m, {});
  for (int i = 0; i < m; ++i) {
    row_span_[i] = knot_span(t_, n_, x_[i]);
    row_basis_[i] = quintic_basis(t_, row_span_[i], x_[i]);
  }
  for (int i = 1; i <= m - 2; ++i) {
    const auto& N = row_basis_[i];
    const int first = row_span_[i] - p;
    for (int r = 0; r <= p; ++r) {
      const int j = first + r;
      if (!free_index(j)) continue;
      bty_[j - 1] += N[r] * y_[i];
      for (int s = r; s <= p; ++s)
        if (free_index(first + s)) gram_[j - 1][s - r] += N[r] * N[s];
    }
  }
  // The penalty hbar^7 integral (s'''')^2 dx = |P c|^2: on each row interval s'''' is linear, its
  // square a quadratic, so three Gauss-Legendre points (exact to degree 5) give it exactly; P has a
  // row sqrt(weight hbar^7) B''''(x_g) per point. Omega = P^T P is kept for the active set's
  // multipliers.
  const double gauss = std::sqrt(0.6);
  const double nodes[3] = {-gauss, 0.0, gauss}, weights[3] = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};
  const double h7 = std::pow(hbar_, 7);
  for (int mu = p; mu < n_; ++mu) {
    if (!(t_[mu + 1] > t_[mu])) continue;
    const double mid = 0.5 * (t_[mu] + t_[mu + 1]), half = 0.5 * (t_[mu + 1] - t_[mu]);
    for (int g = 0; g < 3; ++g) {
      const auto D = quintic_basis_derivatives(t_, mu, mid + half * nodes[g]);
      const double scale = std::sqrt(weights[g] * half * h7);
      std::array<double, 6> row{};
      for (int r = 0; r <= p; ++r) row[r] = scale * D[4][r];
      penalty_rows_.push_back({mu - p, row});
      for (int r = 0; r <= p; ++r) {
        const int j = mu - p + r;
        if (!free_index(j)) continue;
        for (int s = r; s <= p; ++s)
          if (free_index(mu - p + s)) penalty_[j - 1][s - r] += row[r] * row[s];
      }
    }
  }
}

double QuinticSmoother::lambda_max() const { return lambda_max(static_cast<double>(x_.size())); }

double QuinticSmoother::lambda_max(double rows) { return std::min(1e15, 1e4 * std::pow(std::max(rows - 1.0, 1.0), 8)); }

double QuinticSmoother::most_solves(bool gcv, double rows) {
  constexpr double brent_steps = 100, toms748_steps = 200, after = 3;  // the limits given to Boost below
  const double grid = std::round((std::log10(lambda_max(rows)) - std::log10(lambda_min)) / 0.25) + 1.0;
  return (gcv ? grid + brent_steps : 2.0 + toms748_steps) + most_active_set_steps + after;
}

double QuinticSmoother::rss_of(const std::vector<double>& c, const std::vector<double>& y) const {
  double rss = 0.0;
  for (int i = 1; i + 1 < static_cast<int>(x_.size()); ++i) {
    double s = 0.0;
    for (int r = 0; r <= p; ++r) s += row_basis_[i][r] * c[row_span_[i] - p + r];
    rss += (y[i] - s) * (y[i] - s);
  }
  return rss;
}

QuinticSmoother::Fit QuinticSmoother::solve(double lambda, const std::vector<double>& y, const std::vector<char>& held,
                                            bool with_dof, SmoothingWork& work) const {
  const int nf = n_ - 2;
  auto is_held = [&](int f) { return !held.empty() && held[f]; };
  // Columns: the free B-splines 1 .. n-2 as 0 .. nf-1; a held one gets the row of the identity.
  BandQr qr(nf);
  auto add = [&](int first_bspline, const std::array<double, 6>& entries, double rhs) {
    std::array<double, 6> a = entries;
    for (int r = 0; r <= p; ++r)
      if (const int f = first_bspline + r - 1; f < 0 || f >= nf || is_held(f)) a[r] = 0.0;
    qr.add(first_bspline - 1, a, rhs);
  };
  // The rows in the order of their first column, so that each row meets only rows of R that hold
  // columns it has itself (no fill-in beyond its six columns: O(m) in all).
  const double root_lambda = std::sqrt(lambda);
  const int m = static_cast<int>(x_.size());
  std::size_t next_penalty = 0;
  int next_row = 1;
  for (int first = 0; first < n_; ++first) {
    for (; next_penalty < penalty_rows_.size() && penalty_rows_[next_penalty].first == first; ++next_penalty) {
      std::array<double, 6> a = penalty_rows_[next_penalty].entries;
      for (double& v : a) v *= root_lambda;
      add(first, a, 0.0);
    }
    for (; next_row + 1 < m && row_span_[next_row] - p == first; ++next_row) add(first, row_basis_[next_row], y[next_row]);
    if (first >= 1 && first - 1 < nf && is_held(first - 1)) qr.add(first - 1, {1.0, 0.0, 0.0, 0.0, 0.0, 0.0}, 0.0);
  }
  ++work.solves;
  std::vector<double> c;
  if (!qr.solve(c)) {
    std::ostringstream m;
    m << "the smoothing spline's least-squares system is singular at lambda = " << lambda << " (rows too uneven?)";
    throw NodeError("smoothing", m.str());
  }
  Fit fit;
  fit.lambda = lambda;
  fit.coefficients.assign(n_, 0.0);
  for (int f = 0; f < nf; ++f) fit.coefficients[f + 1] = c[f];
  fit.rss = rss_of(fit.coefficients, y);
  for (int f = 0; f < nf; ++f) fit.held_at_zero += is_held(f) ? 1 : 0;
  if (with_dof) {
    // trace((G + lambda Omega)^-1 G) over the free, not held coefficients (G masked like the system).
    const auto z = qr.inverse_band();
    double trace = 0.0;
    for (int f = 0; f < nf; ++f) {
      if (is_held(f)) continue;
      trace += z[f][0] * gram_[f][0];
      for (int d = 1; d <= w && f + d < nf; ++d)
        if (!is_held(f + d)) trace += 2.0 * z[f][d] * gram_[f][d];
    }
    fit.dof = trace;
  }
  return fit;
}

QuinticSmoother::Fit QuinticSmoother::fit(double lambda, bool with_dof, SmoothingWork& work) const {
  return solve(lambda, y_, {}, with_dof, work);
}

std::vector<double> QuinticSmoother::smooth(const std::vector<double>& v, double lambda, SmoothingWork& work) const {
  return solve(lambda, v, {}, false, work).coefficients;
}

QuinticSmoother::Fit QuinticSmoother::fit_nonnegative(double lambda, SmoothingWork& work) const {
  const int nf = n_ - 2;
  std::vector<char> held(nf, 0);
  double scale = 0.0;
  for (double v : bty_) scale = std::max(scale, std::abs(v));
  const double tolerance = 1e-12 * scale;
  // Active set: hold the negative coefficients at zero; free the held one with the most negative
  // multiplier (A c - b)_j, A = G + lambda Omega, b = B^T y: the slope of the objective along it.
  // After 2 nf + 20 steps only hold (each step then holds one more, so it ends).
  const int release_steps = 2 * nf + 20;
  Fit f;
  for (int step = 0;; ++step) {
    if (step == most_active_set_steps) {
      std::ostringstream m;
      m << "the non-negative fit did not settle in " << most_active_set_steps << " active-set steps (" << f.held_at_zero
        << " of " << nf << " B-spline coefficients held at zero); the rows fall below zero in many places: check the "
        << "table's zero rows, or smooth less";
      throw NodeError("smoothing", m.str());
    }
    ++work.iterations;
    f = solve(lambda, y_, held, false, work);
    bool added = false;
    for (int j = 0; j < nf; ++j)
      if (!held[j] && f.coefficients[j + 1] < 0.0) held[j] = 1, added = true;
    if (added) continue;
    if (step >= release_steps) break;
    int worst = -1;
    double worst_multiplier = -tolerance;
    for (int j = 0; j < nf; ++j) {
      if (!held[j]) continue;
      double ac = 0.0;  // (A c)_j
      for (int k = std::max(0, j - w); k <= std::min(nf - 1, j + w); ++k) {
        const int lo = std::min(j, k), d = std::abs(j - k);
        ac += (gram_[lo][d] + lambda * penalty_[lo][d]) * f.coefficients[k + 1];
      }
      const double multiplier = ac - bty_[j];
      if (multiplier < worst_multiplier) worst_multiplier = multiplier, worst = j;
    }
    if (worst < 0) break;
    held[worst] = 0;
  }
  if (f.held_at_zero == 0) return fit(lambda, true, work);
  return solve(lambda, y_, held, true, work);
}

double QuinticSmoother::gcv(double lambda, SmoothingWork& work) const {
  const Fit f = fit(lambda, true, work);
  const double m = inner_rows();
  // dof lies in [2, m'] (the null space's two cubics .. interpolation); outside it, rounding has
  // eaten the trace: no score.
  if (!(f.dof > 1.5 && f.dof < m + 0.5)) return std::numeric_limits<double>::infinity();
  const double free = std::max(m - f.dof, 1e-300);
  return m * f.rss / (free * free);
}

double QuinticSmoother::lambda_for_rms(double target_rms, bool& at_limit, SmoothingWork& work) const {
  const double target_rss = inner_rows() * target_rms * target_rms;
  // g(l) = log(RSS(10^l) / target): RSS grows with lambda, so g has one root.
  auto g = [&](double l) {
    ++work.iterations;
    return std::log(std::max(fit(std::pow(10.0, l), false, work).rss, 1e-300) / target_rss);
  };
  const double lo = std::log10(lambda_min), hi = std::log10(lambda_max());
  const double g_lo = g(lo), g_hi = g(hi);
  at_limit = false;
  if (!(g_lo < 0.0)) return at_limit = true, lambda_min;
  if (!(g_hi > 0.0)) return at_limit = true, lambda_max();
  std::uintmax_t max_iterations = 200;
  const auto root = boost::math::tools::toms748_solve(g, lo, hi, g_lo, g_hi, boost::math::tools::eps_tolerance<double>(40),
                                                      max_iterations);
  return std::pow(10.0, 0.5 * (root.first + root.second));
}

double QuinticSmoother::lambda_by_gcv(bool& at_limit, SmoothingWork& work) const {
  // A grid of quarter decades over the range, then Brent's method between the neighbours of the
  // grid's best point (the score may have more than one dip; the grid finds the deepest).
  const double lo = std::log10(lambda_min), hi = std::log10(lambda_max());
  auto score = [&](double l) {
    ++work.iterations;
    return gcv(std::pow(10.0, l), work);
  };
  const int steps = static_cast<int>(std::lround((hi - lo) / 0.25));
  std::vector<double> values(steps + 1);
  int best = 0;
  for (int k = 0; k <= steps; ++k) {
    values[k] = score(lo + (hi - lo) * k / steps);
    if (values[k] < values[best]) best = k;
  }
  at_limit = best == 0 || best == steps;
  if (at_limit) return std::pow(10.0, lo + (hi - lo) * best / steps);
  std::uintmax_t max_iterations = 100;
  const auto minimum = boost::math::tools::brent_find_minima(score, lo + (hi - lo) * (best - 1) / steps,
                                                             lo + (hi - lo) * (best + 1) / steps, 30, max_iterations);
  return std::pow(10.0, minimum.first);
}

}  // namespace mechgraph::cams
