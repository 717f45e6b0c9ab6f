#pragma once
// One uncertain parameter's distribution, in SI: normal, uniform or triangular, optionally
// truncated to [lower, upper]. A sample is made by the inverse of the distribution function
// (quantile) of a point u in (0, 1), so any design of points in the unit cube (Monte Carlo,
// Latin hypercube, Sobol') becomes a sample of the parameter (docs/methods/uncertainty.md).
#include <mechgraph/dimension.hpp>

#include <optional>
#include <string>

namespace mechgraph {

struct Marginal {
  enum class Kind { normal, uniform, triangular } kind = Kind::normal;
  // normal: a = mean, b = sigma; uniform: a = lower, b = upper; triangular: a = lower, b = upper, c = mode.
  double a = 0.0, b = 1.0, c = 0.0;
  std::optional<double> lower, upper;  // truncation (SI), either may be absent
  Dimension dimension;

  /// The value whose probability of not being exceeded is `u` (0 < u < 1), truncation included.
  double quantile(double u) const;
  /// P(X <= x), truncation included.
  double cdf(double x) const;
  /// The probability the truncation keeps of the distribution without it (1 when not truncated),
  /// from the tail it lies in, so that a truncation far out keeps its digits (7 sigma: 1.3e-12).
  double kept_probability() const;
  /// Mean and standard deviation of the distribution as sampled (truncation included: by
  /// quadrature of the quantile for a truncated one).
  double mean() const;
  double standard_deviation() const;

 private:
  double raw_quantile(double u) const;  // without truncation
  double raw_cdf(double x) const;
};

/// The standard normal distribution function and its inverse (used by the Gaussian copula too).
double standard_normal_cdf(double z);
double standard_normal_quantile(double u);

}  // namespace mechgraph
