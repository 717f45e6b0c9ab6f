#include <mechgraph/domain/cam_law_runs.hpp>

#include "piece_points.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

namespace mechgraph {
namespace {

// Where a run's one-sided values are read: numerics::one_sided_point, as the generic search reads
// its knots (1e-13 of the width inside, at least 4 ulps, at most the middle).
using numerics::detail::has_interior;
using numerics::detail::one_sided_point;

int sign_of(double v) { return v > 0.0 ? 1 : v < 0.0 ? -1 : 0; }

// CamLaw::at at an angle between the first and last edges of the runs, which are the event's
// bounds inside (-pi, pi): no angle to reduce, and the bounds read without calling the law.
LiftDerivatives at_edge_bounded(const CamLaw& law, const std::vector<double>& edges, double x) {
  if (x <= edges.front() || x >= edges.back()) return {};
  return law.evaluate_in_event(x);
}

}  // namespace

std::optional<CamLawRuns> CamLawRuns::of(const CamLaw& law, int order) {
  CamLawRuns runs;
  if (!runs.assign(law, order)) return std::nullopt;
  return runs;
}

bool CamLawRuns::assign(const CamLaw& law, int order) {
  law_ = &law;
  order_ = order;
  edges_.clear();  // the cuts are read into the edges' own storage, then framed by the event's ends
  if (order < 0 || order > 2 || !law.monotone_breaks(order, edges_)) {
    edges_.clear();
    return false;
  }
  const double begin = law.event_begin(), end = law.event_end();
  double previous = begin;
  for (double b : edges_) {  // a cut outside the event or out of order would void the certificate: refuse it
    if (!(b > previous) || !(b < end)) {
      edges_.clear();
      return false;
    }
    previous = b;
  }
  edges_.insert(edges_.begin(), begin);
  edges_.push_back(end);
  return true;
}

namespace {

double slope_of(int order, const LiftDerivatives& d) { return order == 0 ? d.velocity : order == 1 ? d.acceleration : d.jerk; }
double curvature_of(int order, const LiftDerivatives& d) { return order == 0 ? d.acceleration : d.jerk; }

// The crossing of `level` by h^(order) in a run [a, b] where g = h^(order) - level has the signs of
// ga and gb (opposite), from the start x strictly inside. Halley's steps, x -= t / (1 - t g'' / (2 g'))
// with t = g / g' (g' = h^(order+1) and g'' = h^(order+2), which the same evaluation of the law gives;
// Newton's step t where g'' is not given, for the acceleration's runs, or where the correction is
// large), kept inside the bracket: where a step would leave it or does not halve the one before,
// the bracket is bisected instead (Press et al., Numerical Recipes, rtsafe). So it converges whatever
// g' does, and cubically near a simple root. It stops when a step is below 2 ulps of the root or the
// bracket has no double inside. (Boost's newton_raphson_iterate moves its bracket by the steps'
// signs, not g's, and raises an error where it judges there is no root; here the run guarantees the
// bracket, and it is kept by g.)
double refine_root(const CamLaw& law, const std::vector<double>& edges, int order, double level, double a, double b,
                   double ga, double x, long& evaluations) {
  auto value_of = [order](const LiftDerivatives& d) {
    return order == 0 ? d.lift : order == 1 ? d.velocity : d.acceleration;
  };
  double lo = ga < 0.0 ? a : b, hi = ga < 0.0 ? b : a;  // g(lo) < 0 < g(hi)
  double step_before = std::abs(b - a), step = step_before;
  LiftDerivatives d = at_edge_bounded(law, edges, x);
  ++evaluations;
  double g = value_of(d) - level, slope = slope_of(order, d);
  if (g < 0.0) lo = x;
  else if (g > 0.0) hi = x;
  for (int iteration = 0; iteration < 200 && g != 0.0; ++iteration) {
    // One division for both steps (a loop of dependent divisions is what a root costs).
    const double inverse_slope = 1.0 / slope;
    double proposal = g * inverse_slope;  // Newton's
    if (order < 2) {
      const double correction = 0.5 * proposal * curvature_of(order, d) * inverse_slope;
      if (std::abs(correction) < 0.5) proposal /= 1.0 - correction;  // Halley's
    }
    const double candidate = x - proposal;
    const bool leaves = !(candidate >= std::min(lo, hi) && candidate <= std::max(lo, hi));
    const bool slow = std::abs(2.0 * proposal) > std::abs(step_before);
    if (leaves || slow || !std::isfinite(proposal)) {
      step_before = step;
      step = 0.5 * (hi - lo);
      const double mid = lo + step;
      if (mid == lo || mid == hi) break;  // no double inside the bracket
      x = mid;
    } else {
      step_before = step;
      step = proposal;
      if (candidate == x) break;
      x = candidate;
    }
    if (std::abs(step) <= 2.0 * std::numeric_limits<double>::epsilon() * std::abs(x)) break;
    d = at_edge_bounded(law, edges, x);
    ++evaluations;
    g = value_of(d) - level;
    slope = slope_of(order, d);
    if (g < 0.0) lo = x;
    else hi = x;
  }
  return x;
}

// Where the chord of g over [a, b] crosses zero, or the middle if that is not strictly inside.
double chord_start(double a, double b, double ga, double gb) {
  const double x = a - ga * (b - a) / (gb - ga);
  return x > std::min(a, b) && x < std::max(a, b) ? x : 0.5 * (a + b);
}

// Where the Taylor polynomial of g at `from` (value g0, derivatives g1, g2, g3 along the angle; the
// terms the law gives) reaches zero on the way to `to`, a distance t in (0, |to - from|): Newton's
// steps on the polynomial kept in a bracket (no evaluation of the law). NaN when the polynomial does
// not change sign over the way, or the result is not strictly inside.
double taylor_start(double from, double to, double g0, double g1, double g2, double g3) {
  const double sigma = to > from ? 1.0 : -1.0, width = std::abs(to - from);
  // p(t) = g0 + s1 t + s2 t^2 + s3 t^3 with the signs of the way folded in.
  const double s1 = sigma * g1, s2 = 0.5 * g2, s3 = sigma * g3 / 6.0;
  auto p = [&](double t) { return g0 + t * (s1 + t * (s2 + t * s3)); };
  const double p_end = p(width);
  if (!std::isfinite(p_end) || !std::isfinite(g0) || g0 == 0.0 || (p_end > 0.0) == (g0 > 0.0) || p_end == 0.0)
    return std::numeric_limits<double>::quiet_NaN();
  double lo = 0.0, hi = width;  // p(lo) has g0's sign, p(hi) the other
  // The first guess: where the fastest single term alone closes the gap |g0| (those of the sign
  // that closes it): each term with the others left out reaches the level no sooner than they all
  // do when all close it, the usual case at a foot or a nose. Else the chord of the polynomial.
  const double toward = g0 < 0.0 ? 1.0 : -1.0, gap = std::abs(g0);
  double t = width;
  if (toward * s1 > 0.0) t = std::min(t, gap / (toward * s1));
  if (toward * s2 > 0.0) t = std::min(t, std::sqrt(gap / (toward * s2)));
  if (toward * s3 > 0.0) t = std::min(t, std::cbrt(gap / (toward * s3)));
  if (!(t > 0.0 && t < width)) t = width * g0 / (g0 - p_end);
  for (int i = 0; i < 8; ++i) {
    const double v = p(t);
    if (v == 0.0) break;
    if ((v > 0.0) == (g0 > 0.0)) lo = t;
    else hi = t;
    const double dv = s1 + t * (2.0 * s2 + 3.0 * t * s3);
    double next = t - v / dv;
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    // A start only: the polynomial is near the law, not the law; Halley's steps on it finish.
    if (std::abs(next - t) <= 1e-3 * t) {
      t = next;
      break;
    }
    t = next;
  }
  const double x = from + sigma * t;
  return x > std::min(from, to) && x < std::max(from, to) ? x : std::numeric_limits<double>::quiet_NaN();
}

}  // namespace

double CamLawRuns::root_in_run(double level, double a, double b, double ga, double gb, long& evaluations) const {
  // Started where the chord crosses zero (inside the bracket, away from its ends).
  return refine_root(*law_, edges_, order_, level, a, b, ga, chord_start(a, b, ga, gb), evaluations);
}

double CamLawRuns::root_in_run(double level, double a, double b, const LiftDerivatives& da, const LiftDerivatives& db,
                               long& evaluations) const {
  // The end nearer the level (the smaller |g|) carries the better polynomial: for a lash just above
  // the foot of a lift, g there is -lash and its slope nearly 0, so the crossing is where the
  // curvature (or the jerk) lifts it, which the polynomial finds closely; Halley's steps finish.
  const double ga = value_of(da) - level, gb = value_of(db) - level;
  const bool from_a = std::abs(ga) <= std::abs(gb);
  auto start_from = [&](bool at_a) {
    const LiftDerivatives& e = at_a ? da : db;
    return taylor_start(at_a ? a : b, at_a ? b : a, at_a ? ga : gb, slope_of(order_, e),
                        order_ < 2 ? curvature_of(order_, e) : 0.0, order_ == 0 ? e.jerk : 0.0);  // h^(order+3): the lift's only
  };
  // Where the nearer end's polynomial stays on its side (a lift that leaves its foot with its first
  // three derivatives zero, as a polydyne's), the farther end's; else the chord.
  double x = start_from(from_a);
  if (!(x == x)) x = start_from(!from_a);
  if (!(x == x)) x = chord_start(a, b, ga, gb);
  return refine_root(*law_, edges_, order_, level, a, b, ga, x, evaluations);
}

double CamLawRuns::value(double x) const { return value_of(at_edge_bounded(*law_, edges_, x)); }

numerics::Extremum CamLawRuns::extreme(double a, double b, double sign, long& evaluations) const {
  const Peaks p = peaks({this}, a, b, evaluations).front();
  return sign > 0.0 ? p.max : p.min;
}

std::vector<CamLawRuns::Peaks> CamLawRuns::peaks(std::initializer_list<const CamLawRuns*> runs, double a, double b,
                                                 long& evaluations) {
  std::vector<Peaks> out(runs.size());
  peaks(runs, a, b, evaluations, out.data());
  return out;
}

void CamLawRuns::peaks(std::initializer_list<const CamLawRuns*> runs, double a, double b, long& evaluations, Peaks* out) {
  // One run set's least and greatest value over [a, b]: at each run's ends inside it (its
  // one-sided points), in ascending order, each read through `at` (h, h', h'' at an angle).
  const auto scan = [a, b](const CamLawRuns& r, auto&& at) {
    const double lo_end = std::max(a, r.edges_.front()), hi_end = std::min(b, r.edges_.back());
    Peaks p{{lo_end, std::numeric_limits<double>::infinity()}, {lo_end, -std::numeric_limits<double>::infinity()}};
    const auto first = std::upper_bound(r.edges_.begin(), r.edges_.end(), lo_end) - r.edges_.begin() - 1;
    const auto order = static_cast<std::size_t>(r.order_);
    for (auto k = std::max<std::ptrdiff_t>(first, 0); k + 1 < static_cast<std::ptrdiff_t>(r.edges_.size()); ++k) {
      const double lo = r.edges_[static_cast<std::size_t>(k)], hi = r.edges_[static_cast<std::size_t>(k) + 1];
      if (lo >= hi_end) break;
      if (!has_interior(lo, hi)) continue;  // no angle of its own: its ends belong to its neighbours
      const double inner_lo = one_sided_point(lo, hi), inner_hi = one_sided_point(hi, lo);
      for (double x : {std::max(lo_end, lo), std::min(hi_end, hi)}) {
        const double f = at(r, std::clamp(x, inner_lo, inner_hi))[order];
        if (f < p.min.value) p.min = {x, f};
        if (f > p.max.value) p.max = {x, f};
      }
    }
    return p;
  };
  if (runs.size() == 1) {
    // One set (the acceleration alone, where a valve motion's velocity is not read): its points
    // ascend, so a point can only repeat the one read just before it (both ends of a run of a
    // few ulps), and no table of points is kept. The same points and evaluations as below.
    double last_x = std::numeric_limits<double>::quiet_NaN();  // equal to no angle
    double last[3] = {};
    *out = scan(**runs.begin(), [&](const CamLawRuns& r, double x) -> const double* {
      if (x == last_x) return last;
      ++evaluations;
      const LiftDerivatives d = at_edge_bounded(*r.law_, r.edges_, x);
      last_x = x;
      last[0] = d.lift, last[1] = d.velocity, last[2] = d.acceleration;
      return last;
    });
    return;
  }
  // The points each run set reads (as extreme() does), evaluated once each across the sets. They
  // are kept sorted by angle; each set reads its points in ascending order, so a point read before
  // is found by a cursor that only moves forward (the sets share most of their cuts): the first
  // few on the stack (a law has a handful of runs), any more in a vector.
  struct Read {
    double x;
    double v[3];  // lift, velocity, acceleration: h^(order) for order 0..2 (no initialiser: filled when read)
  };
  constexpr std::size_t kept_on_stack = 32;
  Read on_stack[kept_on_stack];
  std::vector<Read> on_heap;
  Read* read = on_stack;
  std::size_t count = 0;
  std::size_t cursor = 0;  // the first read at or after the set's last point
  auto at = [&](const CamLawRuns& runs, double x) -> const Read& {
    while (cursor < count && read[cursor].x < x) ++cursor;
    if (cursor < count && read[cursor].x == x) return read[cursor];
    ++evaluations;
    const LiftDerivatives d = at_edge_bounded(*runs.law_, runs.edges_, x);
    const Read r{x, {d.lift, d.velocity, d.acceleration}};
    const std::size_t where = cursor;
    if (count == kept_on_stack && read == on_stack) {  // more than the stack holds: to the heap
      on_heap.assign(on_stack, on_stack + count);
      read = nullptr;
    }
    if (read == on_stack) {
      std::move_backward(read + where, read + count, read + count + 1);
      read[where] = r;
    } else {
      on_heap.insert(on_heap.begin() + static_cast<std::ptrdiff_t>(where), r);
      read = on_heap.data();
    }
    ++count;
    return read[where];
  };
  for (const CamLawRuns* r : runs) {
    cursor = 0;
    *out++ = scan(*r, [&](const CamLawRuns& set, double x) -> const double* { return at(set, x).v; });
  }
}

std::vector<std::pair<double, bool>> CamLawRuns::directed_crossings(double level, long& evaluations) const {
  std::vector<std::pair<double, bool>> found;
  directed_crossings(level, evaluations, found);
  return found;
}

void CamLawRuns::directed_crossings(double level, long& evaluations, std::vector<std::pair<double, bool>>& found) const {
  found.clear();
  // A left-to-right walk over the runs' one-sided ends; exact zeros are skipped (a touch is no
  // crossing), and the first of them marks where a crossing through them lies.
  int last_sign = 0;
  std::ptrdiff_t last_run = -1;
  bool last_was_left = false;
  double last_x = 0.0;
  LiftDerivatives last_d;  // the law at last_x: the Taylor start of a root in the run
  double zero_at = 0.0;  // the first exact zero since the last signed point
  bool zero_since_last = false;
  for (std::size_t k = 0; k + 1 < edges_.size(); ++k) {
    const double lo = edges_[k], hi = edges_[k + 1];
    if (!has_interior(lo, hi)) continue;  // no angle of its own
    for (const bool left : {true, false}) {
      const double x = left ? one_sided_point(lo, hi) : one_sided_point(hi, lo);
      ++evaluations;
      const LiftDerivatives d = at_edge_bounded(*law_, edges_, x);
      const int s = sign_of(value_of(d) - level);
      if (s == 0) {
        if (!zero_since_last) zero_at = x, zero_since_last = true;
        continue;
      }
      if (last_sign != 0 && s != last_sign) {
        const bool rising = s > 0;
        if (zero_since_last) {
          found.push_back({zero_at, rising});  // the function is at the level exactly there
        } else if (last_run == static_cast<std::ptrdiff_t>(k) && last_was_left && !left) {
          // Inside one run: one sign change, bracketed; on the law itself.
          found.push_back({root_in_run(level, last_x, x, last_d, d, evaluations), rising});
        } else {
          found.push_back({lo, rising});  // a jump across the level at the cut that begins this run
        }
      }
      last_sign = s;
      last_run = static_cast<std::ptrdiff_t>(k);
      last_was_left = left;
      last_x = x;
      last_d = d;
      zero_since_last = false;
    }
  }
}

}  // namespace mechgraph
