#include <mechgraph/uncertainty/distribution.hpp>

#include <boost/math/special_functions/erf.hpp>

#include <algorithm>
#include <cmath>

namespace mechgraph {

double standard_normal_cdf(double z) { return 0.5 * std::erfc(-z / std::sqrt(2.0)); }

double standard_normal_quantile(double u) {
  // Phi^-1(u) = -sqrt(2) erfc^-1(2u): accurate in both tails (boost's inverse erfc).
  return -std::sqrt(2.0) * boost::math::erfc_inv(2.0 * u);
}

double Marginal::raw_quantile(double u) const {
  switch (kind) {
    case Kind::normal: return a + b * standard_normal_quantile(u);
    case Kind::uniform: return a + (b - a) * u;
    case Kind::triangular: {
      // F(mode) = (c - a) / (b - a); each side inverts a quadratic.
      const double span = b - a, at_mode = (c - a) / span;
      if (u <= at_mode) return a + std::sqrt(u * span * (c - a));
      return b - std::sqrt((1.0 - u) * span * (b - c));
    }
  }
  return a;
}

double Marginal::raw_cdf(double x) const {
  switch (kind) {
    case Kind::normal: return standard_normal_cdf((x - a) / b);
    case Kind::uniform: return std::clamp((x - a) / (b - a), 0.0, 1.0);
    case Kind::triangular:
      if (x <= a) return 0.0;
      if (x >= b) return 1.0;
      if (x <= c) return (x - a) * (x - a) / ((b - a) * (c - a));
      return 1.0 - (b - x) * (b - x) / ((b - a) * (b - c));
  }
  return 0.0;
}

namespace {
// A normal truncated above its mean (lower > mean) lies in the upper tail, where F rounds to 1
// (beyond about 8 sigma F(lower) is 1 exactly, and F^-1(1) is infinite): there it is read on the
// survival probability S = 1 - F = Phi(-z), which keeps its digits, x = mean - sigma Phi^-1(S).
bool in_upper_tail(const Marginal& m) { return m.kind == Marginal::Kind::normal && m.lower && *m.lower > m.a; }
double survival(const Marginal& m, double x) { return standard_normal_cdf(-(x - m.a) / m.b); }
}  // namespace

double Marginal::quantile(double u) const {
  if (!lower && !upper) return raw_quantile(u);
  // Truncated to [lower, upper]: u maps into [F(lower), F(upper)], then through F^-1 (in the upper
  // tail: S(lower) down to S(upper)); the result is kept inside the limits against rounding.
  double x;
  if (in_upper_tail(*this)) {
    const double s_low = survival(*this, *lower), s_high = upper ? survival(*this, *upper) : 0.0;
    x = a - b * standard_normal_quantile(s_low - u * (s_low - s_high));
  } else {
    const double f_low = lower ? raw_cdf(*lower) : 0.0, f_high = upper ? raw_cdf(*upper) : 1.0;
    x = raw_quantile(f_low + u * (f_high - f_low));
  }
  if (lower) x = std::max(x, *lower);
  if (upper) x = std::min(x, *upper);
  return x;
}

double Marginal::kept_probability() const {
  if (!lower && !upper) return 1.0;
  if (in_upper_tail(*this)) return survival(*this, *lower) - (upper ? survival(*this, *upper) : 0.0);
  return (upper ? raw_cdf(*upper) : 1.0) - (lower ? raw_cdf(*lower) : 0.0);
}

double Marginal::cdf(double x) const {
  if (!lower && !upper) return raw_cdf(x);
  if (lower && x < *lower) return 0.0;
  if (upper && x >= *upper) return 1.0;
  if (in_upper_tail(*this)) {
    const double s_low = survival(*this, *lower), s_high = upper ? survival(*this, *upper) : 0.0;
    return (s_low - survival(*this, x)) / (s_low - s_high);
  }
  const double f_low = lower ? raw_cdf(*lower) : 0.0, f_high = upper ? raw_cdf(*upper) : 1.0;
  return (raw_cdf(x) - f_low) / (f_high - f_low);
}

namespace {
// E[g(X)] = integral over u in (0, 1) of g(Q(u)), by the midpoint rule on 20000 cells: for the
// report's mean and sigma of a truncated distribution (not used by any estimator).
template <class G>
double expectation(const Marginal& m, G g) {
  constexpr int cells = 20000;
  double sum = 0.0;
  for (int k = 0; k < cells; ++k) sum += g(m.quantile((k + 0.5) / cells));
  return sum / cells;
}
}  // namespace

double Marginal::mean() const {
  if (!lower && !upper) {
    switch (kind) {
      case Kind::normal: return a;
      case Kind::uniform: return 0.5 * (a + b);
      case Kind::triangular: return (a + b + c) / 3.0;
    }
  }
  return expectation(*this, [](double x) { return x; });
}

double Marginal::standard_deviation() const {
  if (!lower && !upper) {
    switch (kind) {
      case Kind::normal: return b;
      case Kind::uniform: return (b - a) / std::sqrt(12.0);
      case Kind::triangular: return std::sqrt((a * a + b * b + c * c - a * b - a * c - b * c) / 18.0);
    }
  }
  const double m = mean();
  return std::sqrt(expectation(*this, [m](double x) { return (x - m) * (x - m); }));
}

}  // namespace mechgraph
