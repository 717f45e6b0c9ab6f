#include "smoothing_spline.hpp"

#include <mechgraph/errors.hpp>

#include <boost/math/tools/minima.hpp>
#include <boost/math/tools/roots.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <sstream>

namespace mechgraph::cams {
namespace {

constexpr int p = quintic_degree;
constexpr int w = p;  // half bandwidth of the normal equations

// A symmetric positive definite band matrix A (a[j][d] = A(j, j + d), d = 0 .. w) as A = L D L^T,
// L unit lower triangular with the same band (l[i][d] = L(i, i - d), d = 1 .. w).
struct BandLdl {
  std::vector<std::array<double, w + 1>> l;
  std::vector<double> d;
};

// Returns false if a pivot is not positive (A not positive definite in double precision).
bool factor(const std::vector<std::array<double, w + 1>>& a, BandLdl& f) {
  const int n = static_cast<int>(a.size());
  f.l.assign(n, {});
  f.d.assign(n, 0.0);
  auto L = [&](int i, int k) -> double& { return f.l[i][i - k]; };
  for (int i = 0; i < n; ++i) {
    const int lo = std::max(0, i - w);
    for (int k = lo; k < i; ++k) {
      double s = a[k][i - k];
      for (int q = lo; q < k; ++q) s -= L(i, q) * f.d[q] * L(k, q);
      L(i, k) = s / f.d[k];
    }
    double s = a[i][0];
    for (int q = lo; q < i; ++q) s -= L(i, q) * L(i, q) * f.d[q];
    if (!(s > 1e-15 * std::abs(a[i][0])) || !std::isfinite(s)) return false;
    f.d[i] = s;
  }
  return true;
}

void solve_in_place(const BandLdl& f, std::vector<double>& b) {
  const int n = static_cast<int>(b.size());
  for (int i = 0; i < n; ++i)
    for (int k = std::max(0, i - w); k < i; ++k) b[i] -= f.l[i][i - k] * b[k];
  for (int i = 0; i < n; ++i) b[i] /= f.d[i];
  for (int i = n - 1; i >= 0; --i)
    for (int k = i + 1; k <= std::min(n - 1, i + w); ++k) b[i] -= f.l[k][k - i] * b[k];
}

// The band of Z = A^-1 from A = L D L^T (Hutchinson and de Hoog 1985): L^T Z = D^-1 L^-1, whose
// upper triangle is diag(1/D), gives for j >= i
//     Z(i, j) = delta_ij / D_i - sum_{k = i+1}^{i+w} L(k, i) Z(k, j),
// run from the last row up; every Z(k, j) it needs lies in the band already computed.
std::vector<std::array<double, w + 1>> inverse_band(const BandLdl& f) {
  const int n = static_cast<int>(f.d.size());
  std::vector<std::array<double, w + 1>> z(n);
  auto Z = [&](int i, int j) -> double& { return i <= j ? z[i][j - i] : z[j][i - j]; };
  for (int i = n - 1; i >= 0; --i) {
    const int hi = std::min(n - 1, i + w);
    for (int j = hi; j >= i; --j) {
      double s = j == i ? 1.0 / f.d[i] : 0.0;
      for (int k = i + 1; k <= hi; ++k) s -= f.l[k][k - i] * Z(k, j);
      Z(i, j) = s;
    }
  }
  return z;
}

}  // namespace

QuinticSmoother::QuinticSmoother(std::vector<double> x, std::vector<double> y) : x_(std::move(x)), y_(std::move(y)) {
  const int m = static_cast<int>(x_.size());
  if (m < 4 || y_.size() != x_.size()) throw NodeError("file", "the smoothing spline needs at least 4 rows");
  for (int k = 0; k <= p; ++k) t_.push_back(x_.front());
  for (int i = 1; i <= m - 2; ++i) t_.push_back(x_[i]);
  for (int k = 0; k <= p; ++k) t_.push_back(x_.back());
  n_ = m + 4;
  hbar_ = (x_.back() - x_.front()) / (m - 1);
  const int nf = n_ - 2;
  gram_.assign(nf, {});
  penalty_.assign(nf, {});
  bty_.assign(nf, 0.0);
  auto free_index = [&](int j) { return j >= 1 && j <= n_ - 2; };

  // G = B^T B and B^T y over the inner rows.
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
  // hbar^5 integral B_j''' B_k''' dx: the integrand is a quartic on each row interval, so three
  // Gauss-Legendre points (exact to degree 5) give it exactly.
  const double g = std::sqrt(0.6);
  const double nodes[3] = {-g, 0.0, g}, weights[3] = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};
  const double h5 = std::pow(hbar_, 5);
  for (int q = 0; q + 1 < m; ++q) {
    const int mu = p + q;
    const double mid = 0.5 * (x_[q] + x_[q + 1]), half = 0.5 * (x_[q + 1] - x_[q]);
    for (int gp = 0; gp < 3; ++gp) {
      const auto D = quintic_basis_derivatives(t_, mu, mid + half * nodes[gp]);
      const double wt = weights[gp] * half * h5;
      for (int r = 0; r <= p; ++r) {
        const int j = mu - p + r;
        if (!free_index(j)) continue;
        for (int s = r; s <= p; ++s)
          if (free_index(mu - p + s)) penalty_[j - 1][s - r] += wt * D[3][r] * D[3][s];
      }
    }
  }
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

QuinticSmoother::Fit QuinticSmoother::solve(double lambda, const std::vector<double>& rhs, const std::vector<char>& held,
                                            bool with_dof, SmoothingWork& work) const {
  const int nf = n_ - 2;
  // A = G + lambda Omega; a coefficient held at zero gets the row and column of the identity.
  std::vector<std::array<double, w + 1>> a(nf);
  std::vector<double> b(rhs);
  auto is_held = [&](int f) { return !held.empty() && held[f]; };
  for (int f = 0; f < nf; ++f)
    for (int d = 0; d <= w; ++d) {
      if (f + d >= nf) break;
      a[f][d] = (is_held(f) || is_held(f + d)) ? (d == 0 ? 1.0 : 0.0) : gram_[f][d] + lambda * penalty_[f][d];
    }
  for (int f = 0; f < nf; ++f)
    if (is_held(f)) b[f] = 0.0;
  BandLdl ldl;
  ++work.solves;
  if (!factor(a, ldl)) {
    std::ostringstream m;
    m << "the smoothing spline's normal equations are not positive definite in double precision at lambda = " << lambda
      << " (rows too uneven?)";
    throw NodeError("smoothing", m.str());
  }
  solve_in_place(ldl, b);
  Fit fit;
  fit.lambda = lambda;
  fit.coefficients.assign(n_, 0.0);
  for (int f = 0; f < nf; ++f) fit.coefficients[f + 1] = b[f];
  fit.rss = rss_of(fit.coefficients, y_);
  for (int f = 0; f < nf; ++f) fit.held_at_zero += is_held(f) ? 1 : 0;
  if (with_dof) {
    // trace(A^-1 G) over the free, not held coefficients (G masked like A).
    const auto z = inverse_band(ldl);
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
  return solve(lambda, bty_, {}, with_dof, work);
}

std::vector<double> QuinticSmoother::smooth(const std::vector<double>& v, double lambda, SmoothingWork& work) const {
  std::vector<double> rhs(n_ - 2, 0.0);
  for (int i = 1; i + 1 < static_cast<int>(x_.size()); ++i)
    for (int r = 0; r <= p; ++r) {
      const int j = row_span_[i] - p + r;
      if (j >= 1 && j <= n_ - 2) rhs[j - 1] += row_basis_[i][r] * v[i];
    }
  return solve(lambda, rhs, {}, false, work).coefficients;
}

QuinticSmoother::Fit QuinticSmoother::fit_nonnegative(double lambda, SmoothingWork& work) const {
  const int nf = n_ - 2;
  std::vector<char> held(nf, 0);
  double scale = 0.0;
  for (double v : bty_) scale = std::max(scale, std::abs(v));
  const double tolerance = 1e-12 * scale;
  // Active set: hold the negative coefficients at zero; free the held one with the most negative
  // multiplier (A c - b)_j, the slope of the objective along it; after 2 nf + 20 steps only hold
  // (each step then holds one more, so it ends).
  const int release_steps = 2 * nf + 20;
  Fit f;
  for (int step = 0;; ++step) {
    ++work.iterations;
    f = solve(lambda, bty_, held, false, work);
    bool added = false;
    for (int j = 0; j < nf; ++j)
      if (!held[j] && f.coefficients[j + 1] < 0.0) held[j] = 1, added = true;
    if (added) continue;
    if (step >= release_steps) break;
    int worst = -1;
    double worst_multiplier = -tolerance;
    for (int j = 0; j < nf; ++j) {
      if (!held[j]) continue;
      double ac = 0.0;  // (A c)_j with the full, unmasked A
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
  return solve(lambda, bty_, held, true, work);
}

double QuinticSmoother::gcv(double lambda, SmoothingWork& work) const {
  const Fit f = fit(lambda, true, work);
  const double m = inner_rows();
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
  const double lo = std::log10(lambda_min), hi = std::log10(lambda_max);
  const double g_lo = g(lo), g_hi = g(hi);
  at_limit = false;
  if (!(g_lo < 0.0)) return at_limit = true, lambda_min;
  if (!(g_hi > 0.0)) return at_limit = true, lambda_max;
  std::uintmax_t max_iterations = 200;
  const auto root = boost::math::tools::toms748_solve(g, lo, hi, g_lo, g_hi, boost::math::tools::eps_tolerance<double>(40),
                                                      max_iterations);
  return std::pow(10.0, 0.5 * (root.first + root.second));
}

double QuinticSmoother::lambda_by_gcv(bool& at_limit, SmoothingWork& work) const {
  // A grid of quarter decades over the range, then Brent's method between the neighbours of the
  // grid's best point (the score may have more than one dip; the grid finds the deepest).
  const double lo = std::log10(lambda_min), hi = std::log10(lambda_max);
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
