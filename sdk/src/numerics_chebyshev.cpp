#include <mechgraph/numerics/chebyshev.hpp>

#include <boost/math/tools/roots.hpp>
#include <unsupported/Eigen/FFT>

#include <complex>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <stdexcept>

namespace mechgraph::numerics {
namespace {

constexpr int max_n = chebyshev_max_intervals;

bool power_of_two(int n) { return n > 0 && (n & (n - 1)) == 0; }

// Drops trailing coefficients whose sum stays below `budget` (keeps at least one).
void drop_tail(std::vector<double>& a, double budget) {
  double dropped = 0.0;
  while (a.size() > 1 && dropped + std::abs(a.back()) <= budget) {
    dropped += std::abs(a.back());
    a.pop_back();
  }
}

// The left-half matrix: column k holds the Chebyshev coefficients of T_k((x - 1) / 2), the
// restriction of T_k to [-1, 0] in that half's own variable x. Built once by the recurrence
// T_{k+1}(t) = 2 t T_k(t) - T_{k-1}(t) with 2t = x - 1 and x T_j = (T_{j+1} + T_{|j-1|}) / 2;
// stored column by column, column k holding rows 0..k (it is upper triangular).
constexpr int split_size = chebyshev_max_intervals + 1;

const std::vector<double>& left_split_matrix() {
  static const std::vector<double> matrix = [] {
    std::vector<double> m;
    m.reserve(static_cast<std::size_t>(split_size) * (split_size + 1) / 2);
    std::vector<double> previous{1.0}, current{-0.5, 0.5};
    m.push_back(1.0);
    m.insert(m.end(), current.begin(), current.end());
    for (int k = 1; k + 1 < split_size; ++k) {
      std::vector<double> next(static_cast<std::size_t>(k) + 2, 0.0);
      for (int j = 0; j <= k; ++j) {
        const double v = current[static_cast<std::size_t>(j)];
        next[static_cast<std::size_t>(j) + 1] += 0.5 * v;       // x T_j: half to T_{j+1}
        next[static_cast<std::size_t>(j == 0 ? 1 : j - 1)] += 0.5 * v;  // and half to T_{|j-1|}
        next[static_cast<std::size_t>(j)] -= v;                 // - T_j
      }
      for (int j = 0; j < k; ++j) next[static_cast<std::size_t>(j)] -= previous[static_cast<std::size_t>(j)];
      m.insert(m.end(), next.begin(), next.end());
      previous = std::move(current);
      current = std::move(next);
    }
    return m;
  }();
  return matrix;
}

// The series of p restricted to [-1, 0] (left) or [0, 1] (right), in the half's own variable:
// child_j = sum_{k >= j} L_jk a_k, with R_jk = (-1)^(j+k) L_jk for the right half.
void half_series_into(std::span<const double> a, bool left, double budget, std::vector<double>& child) {
  const auto& m = left_split_matrix();
  const std::size_t n = std::min<std::size_t>(a.size(), split_size);
  child.assign(n, 0.0);
  std::size_t column = 0;  // start of column k in m
  for (std::size_t k = 0; k < n; ++k) {
    const double ak = (!left && (k & 1)) ? -a[k] : a[k];
    for (std::size_t j = 0; j <= k; ++j) child[j] += m[column + j] * ak;
    column += k + 1;
  }
  if (!left)
    for (std::size_t j = 1; j < n; j += 2) child[j] = -child[j];
  drop_tail(child, budget);
}

// Coefficient vectors of finished cells, kept per thread for the next cells (the searches run
// millions of cells in a sweep; an allocation each would cost as much as the arithmetic).
std::vector<std::vector<double>>& spare_vectors() {
  thread_local std::vector<std::vector<double>> spare;
  return spare;
}
std::vector<double> recycled_vector() {
  auto& spare = spare_vectors();
  if (spare.empty()) return {};
  std::vector<double> v = std::move(spare.back());
  spare.pop_back();
  return v;
}
void recycle(std::vector<double>&& v) {
  auto& spare = spare_vectors();
  if (spare.size() < 256) spare.push_back(std::move(v));
}

std::vector<double> half_series(std::span<const double> a, bool left, double budget) {
  std::vector<double> child = recycled_vector();
  half_series_into(a, left, budget, child);
  return child;
}

// p' of a series into `out` (no allocation once `out` has grown).
void derivative_into(std::span<const double> c, std::vector<double>& out) {
  const std::size_t n = c.size();
  if (n <= 1) {
    out.assign(1, 0.0);
    return;
  }
  out.assign(n + 1, 0.0);
  for (std::size_t k = n - 1; k >= 1; --k) out[k - 1] = out[k + 1] + 2.0 * static_cast<double>(k) * c[k];
  out[0] *= 0.5;
  out.resize(n - 1);
}

struct Cell {
  double lo, hi;
  std::vector<double> a;
  int depth;
};

}  // namespace

double chebyshev_point(int j, int n) {
  // sin form, symmetric about 0 and exact at the middle: cos(pi j/n) = sin(pi (n - 2j) / (2n)),
  // from a table of the finest set when n divides it (every n the searches use).
  static const std::array<double, max_n + 1> finest = [] {
    std::array<double, max_n + 1> t{};
    for (int i = 0; i <= max_n; ++i) t[static_cast<std::size_t>(i)] = std::sin(std::numbers::pi * (max_n - 2 * i) / (2.0 * max_n));
    return t;
  }();
  if (n > 0 && n <= max_n && max_n % n == 0 && j >= 0 && j <= n) return finest[static_cast<std::size_t>(j * (max_n / n))];
  return std::sin(std::numbers::pi * (n - 2 * j) / (2.0 * n));
}

void chebyshev_coefficients(std::span<const double> values, std::vector<double>& c) {
  const int n = static_cast<int>(values.size()) - 1;
  if (!power_of_two(n) || n > max_n) throw std::invalid_argument("chebyshev_coefficients: n must be a power of two up to 256");
  c.assign(static_cast<std::size_t>(n) + 1, 0.0);
  if (n >= 64) {
    // By FFT of the even extension [f_0 .. f_n, f_{n-1} .. f_1]: X_k = f_0 + (-1)^k f_n +
    // 2 sum_{j=1}^{n-1} f_j cos(pi j k / n), so c_k = X_k / n (c_0, c_n halved).
    thread_local Eigen::FFT<double> fft;
    thread_local std::vector<double> extended;
    thread_local std::vector<std::complex<double>> spectrum;
    extended.resize(2 * static_cast<std::size_t>(n));
    for (int j = 0; j <= n; ++j) extended[static_cast<std::size_t>(j)] = values[static_cast<std::size_t>(j)];
    for (int j = 1; j < n; ++j) extended[static_cast<std::size_t>(2 * n - j)] = values[static_cast<std::size_t>(j)];
    fft.fwd(spectrum, extended);
    for (int k = 0; k <= n; ++k) c[static_cast<std::size_t>(k)] = spectrum[static_cast<std::size_t>(k)].real() / n;
    c.front() *= 0.5;
    c.back() *= 0.5;
    return;
  }
  {
    // n <= 32 (the rest went by FFT): a stored matrix (vectorises), row k the weights of c_k.
    static const std::array<std::vector<double>, 6> matrices = [] {
      std::array<std::vector<double>, 6> all;
      for (int level = 0; level < 6; ++level) {
        const int m = 1 << level;
        std::vector<double>& w = all[static_cast<std::size_t>(level)];
        w.assign(static_cast<std::size_t>((m + 1) * (m + 1)), 0.0);
        for (int k = 0; k <= m; ++k)
          for (int j = 0; j <= m; ++j) {
            double v = 2.0 / m * std::cos(std::numbers::pi * static_cast<double>(j * k % (2 * m)) / m);
            if (j == 0 || j == m) v *= 0.5;
            if (k == 0 || k == m) v *= 0.5;
            w[static_cast<std::size_t>(k * (m + 1) + j)] = v;
          }
      }
      return all;
    }();
    int level = 0;
    while ((1 << level) < n) ++level;
    const double* w = matrices[static_cast<std::size_t>(level)].data();
    for (int k = 0; k <= n; ++k) {
      double sum = 0.0;
      for (int j = 0; j <= n; ++j) sum += w[k * (n + 1) + j] * values[static_cast<std::size_t>(j)];
      c[static_cast<std::size_t>(k)] = sum;
    }
  }
}

std::size_t chebyshev_resolved_length(std::span<const double> coefficients, double tolerance) {
  // Aurentz & Trefethen's standardChop: the envelope (running maximum from the right, scaled by
  // its first entry) must reach a plateau: from some j on, the envelope at 1.25 j + 5 is still
  // more than r(j) times the envelope at j, where r grows as the envelope falls towards the
  // tolerance. The cut is then where the envelope plus a slight linear tilt is lowest.
  const std::size_t n = coefficients.size();
  if (n < 17) return 0;
  std::vector<double> envelope(n);
  envelope[n - 1] = std::abs(coefficients[n - 1]);
  for (std::size_t j = n - 1; j-- > 0;) envelope[j] = std::max(std::abs(coefficients[j]), envelope[j + 1]);
  if (envelope[0] == 0.0) return 1;
  // Scaled by the largest coefficient (read once: dividing by envelope[0] in the loop would
  // scale only the first entry and leave the rest absolute, so a function of size 1e-15 looked
  // resolved by its first coefficient and one of size 1e9 never resolved).
  const double largest = envelope[0];
  for (double& e : envelope) e /= largest;
  std::size_t plateau = 0, j2 = 0;
  bool found = false;
  const double log_tol = std::log(tolerance), tol_2_3 = std::pow(tolerance, 2.0 / 3.0);
  for (std::size_t j = 2; j <= n; ++j) {  // 1-based j as in the paper
    j2 = static_cast<std::size_t>(std::lround(1.25 * static_cast<double>(j) + 5.0));
    if (j2 > n) return 0;  // no plateau
    const double e1 = envelope[j - 1], e2 = envelope[j2 - 1];
    // Above tol^(2/3), r > 1 >= e2 / e1 (the envelope never rises): no plateau, no logarithm needed.
    if (e1 > tol_2_3) continue;
    const double r = 3.0 * (1.0 - std::log(e1) / log_tol);
    if (e1 == 0.0 || e2 / e1 > r) {
      plateau = j - 1;
      found = true;
      break;
    }
  }
  if (!found) return 0;
  if (envelope[plateau - 1] == 0.0) return plateau;
  // Step 3: the cut minimises log10(envelope) + a line rising by -log10(tol)/3 over the plateau.
  std::size_t j3 = 0;
  const double tol_7_6 = std::pow(tolerance, 7.0 / 6.0);
  for (double e : envelope)
    if (e >= tol_7_6) ++j3;
  std::vector<double> env(envelope.begin(), envelope.begin() + static_cast<long>(std::min(j2, n)));
  if (j3 < j2) {
    j2 = j3 + 1;
    env.resize(j2);
    env[j2 - 1] = tol_7_6;
  }
  // argmin of log10(env_i) + i s, s = -log10(tol) / 3 / (j2 - 1): the same as argmin env_i q^i
  // with q = 10^s, without a logarithm per entry.
  std::size_t best = 0;
  double best_value = std::numeric_limits<double>::infinity();
  const double q = j2 > 1 ? std::pow(10.0, (-1.0 / 3.0) * std::log10(tolerance) / static_cast<double>(j2 - 1)) : 1.0;
  double weight = 1.0;
  for (std::size_t i = 0; i < j2; ++i, weight *= q) {
    const double v = std::max(env[i], std::numeric_limits<double>::min()) * weight;
    if (v < best_value) {
      best_value = v;
      best = i;
    }
  }
  return std::max<std::size_t>(best, 1);  // 1-based d - 1 = 0-based best
}

double chebyshev_value(std::span<const double> c, double x) {
  double b1 = 0.0, b2 = 0.0;
  const double two_x = 2.0 * x;
  for (std::size_t k = c.size(); k-- > 1;) {
    const double b0 = c[k] + two_x * b1 - b2;
    b2 = b1;
    b1 = b0;
  }
  return c.empty() ? 0.0 : c[0] + x * b1 - b2;
}

std::vector<double> chebyshev_derivative(std::span<const double> c) {
  const std::size_t n = c.size();
  if (n <= 1) return {0.0};
  // d_{k-1} = d_{k+1} + 2 k c_k from the top down; d_0 halved.
  std::vector<double> d(n + 1, 0.0);
  for (std::size_t k = n - 1; k >= 1; --k) d[k - 1] = d[k + 1] + 2.0 * static_cast<double>(k) * c[k];
  d[0] *= 0.5;
  d.resize(n - 1);
  return d;
}

std::vector<SeriesZero> chebyshev_zeros(std::span<const double> c, double floor, long& cells,
                                        const std::function<bool(double, double, std::span<const double>)>& skip) {
  std::vector<SeriesZero> zeros;
  if (c.empty()) return zeros;
  const double budget = 0.1 * floor;  // what re-expanded halves may drop (it moves p by no more)
  auto sign = [&](double v) { return v > floor ? 1 : v < -floor ? -1 : 0; };
  std::vector<Cell> stack;
  stack.push_back({-1.0, 1.0, std::vector<double>(c.begin(), c.end()), 0});
  // A bound on the work: a series resolved to rounding level needs a few cells per root; one that
  // is not (noise) could split for long. Past the budget, the cells left count as places where p
  // may be zero (the callers evaluate the function there).
  const long budget_cells = 64 * static_cast<long>(c.size()) + 256;
  long examined = 0;
  while (!stack.empty()) {
    Cell cell = std::move(stack.back());
    stack.pop_back();
    ++cells;
    if (++examined > budget_cells) {
      zeros.push_back({0.5 * (cell.lo + cell.hi), cell.lo, cell.hi, false, false, true});
      continue;
    }
    const std::vector<double>& a = cell.a;
    if (skip && skip(cell.lo, cell.hi, a)) continue;
    double rest = 0.0, curvature = 0.0, right = 0.0, left = 0.0;
    for (std::size_t k = 0; k < a.size(); ++k) {
      if (k >= 1) rest += std::abs(a[k]);
      if (k >= 2) curvature += static_cast<double>(k * k) * std::abs(a[k]);
      right += a[k];
      left += (k & 1) ? -a[k] : a[k];
    }
    const double mid = 0.5 * (cell.lo + cell.hi), half = 0.5 * (cell.hi - cell.lo);
    if (std::abs(a[0]) > rest + floor) continue;  // |p| > floor on the whole cell
    if (std::abs(a[0]) + rest <= floor) {         // |p| <= floor on the whole cell
      zeros.push_back({mid, cell.lo, cell.hi, false, false, true});
      continue;
    }
    // Monotone when p' has no zero on the cell: its series b (in the cell's variable) has
    // |b_0| > sum_{k>=1} |b_k| (the cheaper Markov test |a_1| > sum k^2 |a_k| implies less).
    bool monotone = a.size() > 1 && std::abs(a[1]) > curvature;
    if (!monotone && a.size() > 2) {
      const std::vector<double> b = chebyshev_derivative(a);
      double b_rest = 0.0;
      for (std::size_t k = 1; k < b.size(); ++k) b_rest += std::abs(b[k]);
      monotone = std::abs(b[0]) > b_rest;
    }
    if (monotone) {
      // Monotone on the cell: one root or none. A root within the floor of an end belongs to the
      // cell whose left end it is (the last cell keeps its right end), so it is counted once.
      const int sl = sign(left), sr = sign(right);
      const bool crosses = (sl != 0 && sr != 0 && sl != sr) || (sl == 0 && sr != 0) || (sr == 0 && cell.hi == 1.0 && sl != 0);
      if (sl == 0 && sr == 0) {
        zeros.push_back({mid, cell.lo, cell.hi, false, false, true});
        continue;
      }
      if (!crosses) continue;
      if (sl == 0 || sr == 0) {
        // Zero within the floor at an end: a zone of no width there, so that it joins a zone
        // next to it and its crossing is read off the signs either side like any zone's.
        const double at = sl == 0 ? cell.lo : cell.hi;
        zeros.push_back({at, at, at, false, false, true});
        continue;
      }
      double t;
      if ((left < 0.0 && right > 0.0) || (left > 0.0 && right < 0.0)) {
        std::uintmax_t iterations = 100;
        const auto r = boost::math::tools::toms748_solve([&](double u) { return chebyshev_value(a, u); }, -1.0, 1.0, left,
                                                         right, boost::math::tools::eps_tolerance<double>(52), iterations);
        t = 0.5 * (r.first + r.second);
      } else {
        t = sl == 0 ? -1.0 : 1.0;
      }
      zeros.push_back({std::clamp(mid + half * t, cell.lo, cell.hi), cell.lo, cell.hi, true, right > left});
      continue;
    }
    if (cell.depth >= 60 || half <= 4.0 * std::numeric_limits<double>::epsilon()) {
      zeros.push_back({mid, cell.lo, cell.hi, false, false, true});
      continue;
    }
    // Right half first onto the stack, so cells come off it left to right.
    stack.push_back({mid, cell.hi, half_series(a, false, budget), cell.depth + 1});
    stack.push_back({cell.lo, mid, half_series(a, true, budget), cell.depth + 1});
  }
  // Neighbouring flat cells are one place; whether p changes sign across it is read off p just
  // outside (stepping out until |p| clears the floor).
  std::sort(zeros.begin(), zeros.end(), [](const SeriesZero& l, const SeriesZero& r) { return l.x < r.x; });
  std::vector<SeriesZero> merged;
  for (const SeriesZero& z : zeros) {
    if (!merged.empty() && z.zone && merged.back().zone && z.lo <= merged.back().hi) {
      merged.back().hi = std::max(merged.back().hi, z.hi);
      merged.back().x = 0.5 * (merged.back().lo + merged.back().hi);
      continue;
    }
    merged.push_back(z);
  }
  for (SeriesZero& z : merged) {
    if (!z.zone) continue;
    auto outside = [&](double from, double direction) {
      double step = std::max(z.hi - z.lo, 1e-12);
      for (int i = 0; i < 60; ++i, step *= 2.0) {
        const double x = std::clamp(from + direction * step, -1.0, 1.0);
        const double v = chebyshev_value(c, x);
        if (std::abs(v) > floor || x == -1.0 || x == 1.0) return sign(v);
      }
      return 0;
    };
    const int sl = outside(z.lo, -1.0), sr = outside(z.hi, 1.0);
    z.crosses = sl != 0 && sr != 0 && sl != sr;
    z.rising = sr > 0;
  }
  return merged;
}

std::vector<SeriesPoint> chebyshev_maximum_candidates(std::span<const double> c, double& best, double margin,
                                                      long& cells) {
  std::vector<SeriesPoint> found;
  if (c.empty()) return found;
  const double budget = 0.1 * margin;  // what re-expanded halves may drop (it moves p by no more)
  const long budget_cells = 64 * static_cast<long>(c.size()) + 256;
  long examined = 0;
  auto take = [&](double t, double v) {
    found.push_back({t, v});
    best = std::max(best, v);
  };
  std::vector<Cell> stack;
  stack.push_back({-1.0, 1.0, std::vector<double>(c.begin(), c.end()), 0});
  while (!stack.empty()) {
    Cell cell = std::move(stack.back());
    stack.pop_back();
    ++cells;
    struct Recycle {
      std::vector<double>& v;
      ~Recycle() { recycle(std::move(v)); }
    } recycle_after{cell.a};
    const std::vector<double>& a = cell.a;
    const double mid = 0.5 * (cell.lo + cell.hi), half = 0.5 * (cell.hi - cell.lo);
    double variation = 0.0, right = 0.0, left = 0.0;
    for (std::size_t k = 0; k < a.size(); ++k) {
      if (k >= 1) variation += std::abs(a[k]);
      right += a[k];
      left += (k & 1) ? -a[k] : a[k];
    }
    if (a[0] + variation <= best + margin) { continue; }  // cannot beat the best
    if (variation <= margin || ++examined > budget_cells || cell.depth >= 60) {
      take(mid, a[0]);  // p(mid) = a_0 - a_2 + a_4 - ..., within the variation of a_0 anyway
      continue;
    }
    thread_local std::vector<double> b, b2;
    derivative_into(a, b);  // p' in the cell's variable
    double b_rest = 0.0;
    for (std::size_t k = 1; k < b.size(); ++k) b_rest += std::abs(b[k]);
    if (std::abs(b[0]) > b_rest) {  // p monotone on the cell: its maximum is at an end
      take(b[0] > 0.0 ? cell.hi : cell.lo, b[0] > 0.0 ? right : left);
      continue;
    }
    if (b.size() > 1) {
      derivative_into(b, b2);
      double b2_rest = 0.0;
      for (std::size_t k = 1; k < b2.size(); ++k) b2_rest += std::abs(b2[k]);
      if (std::abs(b2[0]) > b2_rest) {
        // p' monotone: one critical point at most; with p' falling through zero it is a maximum,
        // else the maximum is at an end.
        double b_left = 0.0, b_right = 0.0;
        for (std::size_t k = 0; k < b.size(); ++k) {
          b_right += b[k];
          b_left += (k & 1) ? -b[k] : b[k];
        }
        
        if (b_left > 0.0 && b_right < 0.0) {
          std::uintmax_t iterations = 100;
          const auto r = boost::math::tools::toms748_solve([&](double u) { return chebyshev_value(b, u); }, -1.0, 1.0,
                                                           b_left, b_right, boost::math::tools::eps_tolerance<double>(52),
                                                           iterations);
          const double u = 0.5 * (r.first + r.second);
          take(mid + half * u, chebyshev_value(a, u));
        } else {
          take(cell.lo, left);
          take(cell.hi, right);
        }
        continue;
      }
    }
    
    stack.push_back({mid, cell.hi, half_series(a, false, budget), cell.depth + 1});
    stack.push_back({cell.lo, mid, half_series(a, true, budget), cell.depth + 1});
  }
  return found;
}

}  // namespace mechgraph::numerics
