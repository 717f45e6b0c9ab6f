#pragma once
// numerics::one_sided_point and numerics::has_interior (mechgraph/numerics/piecewise.hpp) as inline
// functions of the SDK library's own sources: the exported ones call these, and the searches of
// cam_law_runs.cpp, which read a few of them per law evaluation, call them without a call.
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

namespace mechgraph::numerics::detail {

/// std::nextafter(a, b) for a finite or infinite and b not NaN, without the library call: the next
/// double from a toward b (one unit in the last place; from zero the smallest subnormal; b itself
/// when a == b).
inline double next_toward(double a, double b) {
  if (a == b) return b;
  if (a == 0.0) return b > 0.0 ? std::numeric_limits<double>::denorm_min() : -std::numeric_limits<double>::denorm_min();
  const std::uint64_t bits = std::bit_cast<std::uint64_t>(a);
  return std::bit_cast<double>((b > a) == (a > 0.0) ? bits + 1 : bits - 1);  // away from zero: a larger magnitude
}

/// Whether a double lies strictly between a and b (a < b; false otherwise).
inline bool has_interior(double a, double b) { return a < b && next_toward(a, b) < b; }

/// 1e-13 of the width inside from `from` toward `to`, at least 4 ulps of the larger end, at most
/// the middle; the next double when that rounds back to `from` (a piece of two ulps: its middle).
inline double one_sided_point(double from, double to) {
  constexpr double eps = std::numeric_limits<double>::epsilon();
  const double width = std::abs(to - from), toward = to > from ? 1.0 : -1.0;
  const double inset = std::max(1e-13 * width, 4.0 * eps * std::max(std::abs(from), std::abs(to)));
  const double mid = from + 0.5 * (to - from);
  double x = from + toward * inset;
  if (toward * (x - mid) > 0.0) x = mid;
  if (x == from) x = next_toward(from, to);
  return x;
}

}  // namespace mechgraph::numerics::detail
