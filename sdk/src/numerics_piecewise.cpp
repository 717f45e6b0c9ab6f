#include <mechgraph/numerics/piecewise.hpp>

#include <mechgraph/numerics/chebyshev.hpp>
#include <mechgraph/printf_number.hpp>

#include "piece_points.hpp"

#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <boost/math/tools/minima.hpp>
#include <boost/math/tools/roots.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace mechgraph::numerics {
namespace {

constexpr double eps = std::numeric_limits<double>::epsilon();
constexpr int halvings = 4;  // a piece that does not resolve at 257 points is halved at most this often

void check_knots(std::span<const double> knots, int samples) {
  if (knots.size() < 2) throw std::invalid_argument("piecewise numerics need at least two knots");
  if (samples < 3) throw std::invalid_argument("piecewise numerics need at least 3 samples per piece");
  for (std::size_t i = 0; i < knots.size(); ++i) {
    if (!std::isfinite(knots[i])) throw std::invalid_argument("piecewise numerics need finite knots");
    if (i > 0 && knots[i] < knots[i - 1]) throw std::invalid_argument("piecewise numerics need ascending knots");
  }
}

// The starting number of intervals: the power of two at or above samples - 1, within [16, 256].
int starting_intervals(int samples) {
  // 32 at least: the plateau test needs about 1.25 L + 5 coefficients to see a series of length L
  // end, and the laws' pieces mostly end at a length of 9 to 20 (measured: starting at 16 costs
  // more transforms than the points it saves).
  int n = 32;
  while (n < samples - 1 && n < chebyshev_max_intervals) n *= 2;
  return n;
}


}  // namespace

double one_sided_point(double from, double to) { return detail::one_sided_point(from, to); }

bool has_interior(double a, double b) { return detail::has_interior(a, b); }

SmoothPieces::SmoothPieces(Sampler sample, std::size_t count, std::span<const double> knots, int samples_per_piece)
    : sample_(std::move(sample)), count_(count), scratch_(count), slopes_(count) {
  check_knots(knots, samples_per_piece);
  if (count == 0) throw std::invalid_argument("SmoothPieces needs at least one function");
  const int n0 = starting_intervals(samples_per_piece);
  for (std::size_t p = 0; p + 1 < knots.size(); ++p) {
    const double a = knots[p], b = knots[p + 1];
    if (!(b > a) || !has_interior(a, b)) continue;  // no double of its own: nothing to evaluate
    // Pulled inside: at a knot where f jumps, each piece sees its own side.
    const std::size_t first = pieces_.size();
    resolve(one_sided_point(a, b), one_sided_point(b, a), n0, 0);
    pieces_[first].knot = a;
  }
  if (pieces_.empty()) throw std::invalid_argument("piecewise numerics need an interval of positive length");
}

void SmoothPieces::resolve(double a, double b, int n, int depth) {
  const double mid = 0.5 * (a + b), half = 0.5 * (b - a);
  Piece piece;
  piece.a = a;
  piece.b = b;
  piece.knot = a;
  std::vector<double>& values = piece.values;
  auto sample_point = [&](int j, int intervals) {
    const double x = mid + half * chebyshev_point(j, intervals);
    double* v = &values[static_cast<std::size_t>(j) * count_];
    sample_(std::clamp(x, a, b), v, slopes_.data());
    ++work_.evaluations;
    for (std::size_t f = 0; f < count_; ++f)
      if (!std::isfinite(v[f]))
        throw std::domain_error("a function searched for its extremes or crossings is not finite at x = " + printf_g(x));
  };
  values.assign(static_cast<std::size_t>(n + 1) * count_, 0.0);
  for (int j = 0; j <= n; ++j) sample_point(j, n);
  std::vector<double> column, coefficients;
  // Each function keeps the series of the first density that resolves it (the coarser points are
  // a subset of the finer), so only the unresolved ones are transformed again.
  piece.coefficients.assign(count_, {});
  piece.tail.assign(count_, 0.0);
  std::vector<char> done(count_, 0);
  for (;;) {
    bool resolved = true;
    for (std::size_t f = 0; f < count_; ++f) {
      if (done[f]) continue;
      column.resize(static_cast<std::size_t>(n) + 1);
      for (int j = 0; j <= n; ++j) column[static_cast<std::size_t>(j)] = values[static_cast<std::size_t>(j) * count_ + f];
      chebyshev_coefficients(column, coefficients);
      const std::size_t length = chebyshev_resolved_length(coefficients, eps);
      double tail = 0.0;
      if (length == 0) {
        resolved = false;
      } else {
        for (std::size_t k = length; k < coefficients.size(); ++k) tail += std::abs(coefficients[k]);
        coefficients.resize(length);
        done[f] = 1;
      }
      piece.tail[f] = tail;
      piece.coefficients[f] = coefficients;
    }
    if (resolved || n == chebyshev_max_intervals) {
      if (!resolved && depth < halvings) {
        resolve(a, mid, 32, depth + 1);
        resolve(mid, b, 32, depth + 1);
        return;
      }
      piece.n = n;
      piece.resolved.assign(done.begin(), done.end());
      piece.top.assign(count_, 0);
      piece.bottom.assign(count_, 0);
      for (std::size_t f = 0; f < count_; ++f)
        for (int i = 1; i <= n; ++i) {
          const double v = values[static_cast<std::size_t>(i) * count_ + f];
          if (v > values[static_cast<std::size_t>(piece.top[f]) * count_ + f]) piece.top[f] = i;
          if (v < values[static_cast<std::size_t>(piece.bottom[f]) * count_ + f]) piece.bottom[f] = i;
        }
      work_.unresolved += resolved ? 0 : 1;
      work_.pieces += 1;
      work_.most_points = std::max(work_.most_points, n + 1);
      pieces_.push_back(std::move(piece));
      return;
    }
    // Twice the points: the old ones are the even points of the new set.
    std::vector<double> old = std::move(values);
    values.assign(static_cast<std::size_t>(2 * n + 1) * count_, 0.0);
    for (int j = 0; j <= n; ++j)
      std::copy_n(&old[static_cast<std::size_t>(j) * count_], count_, &values[static_cast<std::size_t>(2 * j) * count_]);
    n *= 2;
    for (int j = 1; j < n; j += 2) sample_point(j, n);
  }
}

double SmoothPieces::value_at(std::size_t j, double x) {
  sample_(x, scratch_.data(), slopes_.data());
  ++work_.evaluations;
  return scratch_[j];
}

Extremum SmoothPieces::extreme(std::size_t j, double sign) {
  if (j >= count_) throw std::out_of_range("SmoothPieces: no such function");
  // The best sample is a lower bound of the maximum; the interpolant's critical points are where
  // anything better can be.
  Extremum best{pieces_.front().a, -std::numeric_limits<double>::infinity()};
  double scale = 0.0;
  auto best_index = [&](const Piece& piece) { return sign > 0.0 ? piece.top[j] : piece.bottom[j]; };
  for (const Piece& piece : pieces_) {
    scale = std::max({scale, std::abs(piece.values[static_cast<std::size_t>(piece.top[j]) * count_ + j]),
                      std::abs(piece.values[static_cast<std::size_t>(piece.bottom[j]) * count_ + j])});
    const int i = best_index(piece);
    const double v = sign * piece.values[static_cast<std::size_t>(i) * count_ + j];
    if (v > best.value) best = {0.5 * (piece.a + piece.b) + 0.5 * (piece.b - piece.a) * chebyshev_point(i, piece.n), v};
  }
  struct Candidate {
    double x, interpolated;
  };
  std::vector<Candidate> candidates;
  double bound = best.value;  // the best value known, raised by the interpolant's candidates
  // A few Newton steps on p' from the best sample of each piece raise the bound to about the true
  // maximum before the branch and bound starts, so that it drops more cells at once. (A bound only:
  // the candidates still come from the branch and bound.)
  for (const Piece& piece : pieces_) {
    if (!piece.resolved[j] || piece.coefficients[j].size() <= 2) continue;
    const int top_i = best_index(piece);
    if (sign * piece.values[static_cast<std::size_t>(top_i) * count_ + j] < bound - 1e-3 * scale) continue;
    const std::vector<double>& c = piece.coefficients[j];
    const std::vector<double> d = chebyshev_derivative(c), d2 = chebyshev_derivative(d);
    const double lo = chebyshev_point(std::min(top_i + 1, piece.n), piece.n), hi = chebyshev_point(std::max(top_i - 1, 0), piece.n);
    double t = chebyshev_point(top_i, piece.n);
    for (int k = 0; k < 4; ++k) {
      const double curvature = chebyshev_value(d2, t);
      if (!(curvature * sign < 0.0)) break;
      t = std::clamp(t - chebyshev_value(d, t) / curvature, lo, hi);
    }
    // The point itself is a candidate: the branch and bound may then drop its cell as no better.
    candidates.push_back({0.5 * (piece.a + piece.b) + 0.5 * (piece.b - piece.a) * t, sign * chebyshev_value(c, t)});
    bound = std::max(bound, candidates.back().interpolated);
  }
  for (const Piece& piece : pieces_) {
    if (!piece.resolved[j]) {
      // No interpolant to trust (a kink or noise the halvings did not isolate): the best sample's
      // bracket is refined on the function itself, as a plain sampling search would.
      int top_i = 0;
      for (int i = 1; i <= piece.n; ++i)
        if (sign * piece.values[static_cast<std::size_t>(i) * count_ + j] > sign * piece.values[static_cast<std::size_t>(top_i) * count_ + j]) top_i = i;
      auto x_of = [&](int i) { return 0.5 * (piece.a + piece.b) + 0.5 * (piece.b - piece.a) * chebyshev_point(std::clamp(i, 0, piece.n), piece.n); };
      std::uintmax_t iterations = 100;
      const auto r = boost::math::tools::brent_find_minima([&](double x) { return -sign * value_at(j, x); }, x_of(top_i + 1),
                                                           x_of(top_i - 1), std::numeric_limits<double>::digits / 2, iterations);
      if (-r.second > best.value) best = {r.first, -r.second};
      continue;
    }
    const std::vector<double>& c = piece.coefficients[j];
    if (c.size() <= 2) continue;  // constant or linear: its ends are samples
    // Branch and bound on p's own series (numerics/chebyshev.hpp): the best sample is the bound
    // to beat; candidates within a margin far below the results' 1e-12 come back.
    std::vector<double> signed_c(c.begin(), c.end());
    for (double& v : signed_c) v *= sign;
    const double margin = std::max(1e-13 * scale, 2.0 * piece.tail[j]);
    for (const SeriesPoint& point : chebyshev_maximum_candidates(signed_c, bound, margin, work_.cells))
      candidates.push_back({0.5 * (piece.a + piece.b) + 0.5 * (piece.b - piece.a) * point.t, point.value});
  }
  // The true function at the candidates the interpolant ranks within a hair of the best (the
  // interpolant is the function to rounding level, so a lower candidate cannot win).
  const double hair = 1e-9 * scale;
  double top = best.value;
  for (const Candidate& c : candidates) top = std::max(top, c.interpolated);
  std::sort(candidates.begin(), candidates.end(),
            [](const Candidate& l, const Candidate& r) { return l.interpolated > r.interpolated; });
  int checked = 0;
  for (const Candidate& c : candidates) {
    if (c.interpolated < top - hair || c.interpolated < best.value - hair || checked == 8) break;
    ++checked;
    const double v = sign * value_at(j, c.x);
    if (v > best.value) best = {c.x, v};
  }
  return {best.x, sign * best.value};
}

Extremum SmoothPieces::maximum(std::size_t j) { return extreme(j, 1.0); }
Extremum SmoothPieces::minimum(std::size_t j) { return extreme(j, -1.0); }

double SmoothPieces::scale(std::size_t j) const {
  double m = 0.0;
  for (const Piece& piece : pieces_)
    m = std::max({m, std::abs(piece.values[static_cast<std::size_t>(piece.top[j]) * count_ + j]),
                  std::abs(piece.values[static_cast<std::size_t>(piece.bottom[j]) * count_ + j])});
  return m;
}

std::vector<std::pair<double, bool>> SmoothPieces::directed_crossings(std::size_t j, double level) {
  if (j >= count_) throw std::out_of_range("SmoothPieces: no such function");
  // Rounding level of f_j - level, the same on every piece: a piece where f_j is the level up to
  // rounding (a dwell, a constant-velocity ramp's h'' = 0) is a zone, not a string of crossings.
  const double floor = 16.0 * eps * (scale(j) + std::abs(level)) + std::numeric_limits<double>::min();
  auto sign_of = [&](double v) { return v > floor ? 1 : v < -floor ? -1 : 0; };
  // Walk left to right: between the simple roots, zones and knots the sign of f_j - level is
  // definite (the root search proves there is no other zero). A crossing is where the definite
  // sign flips: at the simple root between, else at a knot between (a jump), else mid-zone.
  struct Crossing {
    double x;
    bool rising;
    double lo, hi;  // where the signs either side were read: a bracket on the function itself
    bool at_knot;   // a jump at a knot: the knot itself is the answer
  };
  std::vector<Crossing> found;
  int last = 0;
  double last_x = 0.0;
  std::optional<double> pending_root, pending_knot;
  double zone_lo = 0.0, zone_hi = 0.0;
  bool pending_zone = false;
  auto arrive = [&](int sign, double at) {
    if (sign == 0) return;
    if (last != 0 && sign != last) {
      const double x = pending_root ? *pending_root : pending_knot ? *pending_knot : 0.5 * (zone_lo + zone_hi);
      if (pending_root || pending_knot || pending_zone)
        found.push_back({x, sign > 0, last_x, at, !pending_root && pending_knot && !pending_zone});
    }
    last = sign;
    last_x = at;
    pending_root.reset();
    pending_knot.reset();
    pending_zone = false;
  };
  const Piece* previous = nullptr;
  for (const Piece& piece : pieces_) {
    const double mid = 0.5 * (piece.a + piece.b), half = 0.5 * (piece.b - piece.a);
    auto x_of = [&](double t) { return mid + half * t; };
    // A knot (or a halving) between pieces: f_j may jump there, or cross the level right at it
    // with each side's interpolant a rounding error off.
    if (previous && !pending_knot) pending_knot = piece.knot;
    previous = &piece;
    if (!piece.resolved[j]) {
      // No interpolant to trust: sign changes between neighbouring samples, refined on the function.
      auto g = [&](double x) { return value_at(j, x) - level; };
      for (int i = piece.n; i >= 0; --i) {
        const double g1 = piece.values[static_cast<std::size_t>(i) * count_ + j] - level;
        const int s1 = sign_of(g1);
        if (i < piece.n && s1 != 0 && last != 0 && s1 != last && !pending_knot) {
          const double g0 = piece.values[static_cast<std::size_t>(i + 1) * count_ + j] - level;
          if ((g0 < 0.0 && g1 > 0.0) || (g0 > 0.0 && g1 < 0.0)) {
            std::uintmax_t iterations = 200;
            const auto r = boost::math::tools::toms748_solve(g, x_of(chebyshev_point(i + 1, piece.n)),
                                                             x_of(chebyshev_point(i, piece.n)), g0, g1,
                                                             boost::math::tools::eps_tolerance<double>(50), iterations);
            pending_root = 0.5 * (r.first + r.second);
          }
        }
        if (s1 == 0 && !pending_zone) {
          pending_zone = true;
          zone_lo = x_of(chebyshev_point(i, piece.n));
        }
        if (s1 == 0) zone_hi = x_of(chebyshev_point(i, piece.n));
        arrive(s1, x_of(chebyshev_point(i, piece.n)));
      }
      continue;
    }
    std::vector<double> c = piece.coefficients[j];
    c[0] -= level;
    // Below the interpolant's own accuracy on this piece (its cut tail) a sign means nothing either.
    const double piece_floor = std::max(floor, 2.0 * piece.tail[j]);
    auto piece_sign = [&](double v) { return v > piece_floor ? 1 : v < -piece_floor ? -1 : 0; };
    const std::vector<SeriesZero> zeros = chebyshev_zeros(c, piece_floor, work_.cells);
    // The sign on the stretch from t_from to t_to (between two zeros), read at its middle.
    double read_at = 0.0;  // where the last stretch's sign was read
    auto stretch = [&](double t_from, double t_to) {
      if (!(t_to > t_from)) return 0;
      read_at = x_of(0.5 * (t_from + t_to));
      return piece_sign(chebyshev_value(c, 0.5 * (t_from + t_to)));
    };
    double t = -1.0;
    auto ambiguous = [&](double t_from, double t_to) {  // a stretch within the floor: part of a zone
      if (!pending_zone) zone_lo = x_of(t_from);
      pending_zone = true;
      zone_hi = x_of(t_to);
    };
    for (const SeriesZero& z : zeros) {
      const double t_to = z.zone ? z.lo : z.x;
      const int s_before = stretch(t, t_to);
      if (s_before == 0 && t_to > t) ambiguous(t, t_to);
      arrive(s_before, read_at);
      if (z.zone) {
        ambiguous(z.lo, z.hi);
        t = z.hi;
      } else {
        if (!pending_root) pending_root = x_of(z.x);
        t = z.x;
      }
    }
    const int s_end = stretch(t, 1.0);
    if (s_end == 0 && t < 1.0) ambiguous(t, 1.0);
    arrive(s_end, read_at);
  }
  // Each crossing polished on the function itself, so that it does not depend on the interpolant
  // (nor on the starting density): first in a hair-wide bracket about the interpolant's root, else
  // between the places where the signs either side were read. Where the function's sign change
  // is flat (a zone), the interpolant only knows it to the floor; the function knows it exactly.
  std::vector<std::pair<double, bool>> roots;
  const double span = pieces_.back().b - pieces_.front().a;
  auto g = [&](double x) { return value_at(j, x) - level; };
  auto opposite = [](double a, double b) { return (a < 0.0 && b > 0.0) || (a > 0.0 && b < 0.0); };
  for (const Crossing& c : found) {
    if (c.at_knot) {
      roots.push_back({c.x, c.rising});
      continue;
    }
    double lo = std::max(c.lo, c.x - 1e-9 * span), hi = std::min(c.hi, c.x + 1e-9 * span);
    double g_lo = g(lo), g_hi = g(hi);
    if (!opposite(g_lo, g_hi)) {
      lo = c.lo;
      hi = c.hi;
      g_lo = g(lo);
      g_hi = g(hi);
    }
    double x = c.x;
    if (opposite(g_lo, g_hi)) {
      std::uintmax_t iterations = 100;
      const auto r = boost::math::tools::toms748_solve(g, lo, hi, g_lo, g_hi,
                                                       boost::math::tools::eps_tolerance<double>(std::numeric_limits<double>::digits - 2),
                                                       iterations);
      x = 0.5 * (r.first + r.second);
    }
    roots.push_back({x, c.rising});
  }
  return roots;
}

std::vector<double> SmoothPieces::crossings(std::size_t j, double level) {
  std::vector<double> xs;
  for (const auto& r : directed_crossings(j, level)) xs.push_back(r.first);
  return xs;
}

namespace {

Sampler one_function(const Function1D& f) {
  return [&f](double x, double* v, double*) { v[0] = f(x); };
}

}  // namespace

void maximize_piecewise_together(const Sampler& sample, std::size_t count, std::span<const double> knots, int n,
                                 long& evaluations, Extremum* maxima) {
  SmoothPieces pieces(sample, count, knots, n);
  for (std::size_t j = 0; j < count; ++j) maxima[j] = pieces.maximum(j);
  evaluations += pieces.work().evaluations;
}

Extremum maximize_piecewise(const Function1D& f, std::span<const double> knots, int samples, long& evaluations) {
  SmoothPieces pieces(one_function(f), 1, knots, samples);
  const Extremum e = pieces.maximum(0);
  evaluations += pieces.work().evaluations;
  return e;
}

Extremum minimize_piecewise(const Function1D& f, std::span<const double> knots, int samples, long& evaluations) {
  SmoothPieces pieces(one_function(f), 1, knots, samples);
  const Extremum e = pieces.minimum(0);
  evaluations += pieces.work().evaluations;
  return e;
}

std::optional<double> first_sign_change(const Function1D& f, std::span<const double> knots, int n,
                                        long& evaluations) {
  const std::vector<double> roots = all_sign_changes(f, knots, n, evaluations);
  if (roots.empty()) return std::nullopt;
  return roots.front();
}

std::vector<double> all_sign_changes(const Function1D& f, std::span<const double> knots, int n, long& evaluations) {
  SmoothPieces pieces(one_function(f), 1, knots, n);
  std::vector<double> roots = pieces.crossings(0, 0.0);
  evaluations += pieces.work().evaluations;
  return roots;
}

double integrate_piecewise(const Function1D& f, std::span<const double> knots, double tolerance, long& evaluations,
                           double* error_estimate) {
  if (knots.size() < 2) throw std::invalid_argument("integrate_piecewise needs at least two knots");
  double total = 0.0, error = 0.0;
  for (std::size_t p = 0; p + 1 < knots.size(); ++p) {
    const double a = knots[p], b = knots[p + 1];
    if (!(b > a)) continue;
    double piece_error = 0.0;
    long count = 0;
    auto counted = [&](double x) { ++count; return f(x); };
    total += boost::math::quadrature::gauss_kronrod<double, 15>::integrate(counted, a, b, 15, tolerance, &piece_error);
    evaluations += count;
    error += piece_error;
  }
  if (error_estimate) *error_estimate = error;
  return total;
}

}  // namespace mechgraph::numerics
