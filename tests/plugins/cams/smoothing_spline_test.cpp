// The smoothing spline of cam.table (plugins/cams/smoothing_spline.hpp) and the quintic pieces it
// shares with the interpolant (quintic_spline.hpp): the limits lambda -> 0 (interpolation) and
// lambda -> infinity (the penalty's null space, against a least-squares cubic solved apart), the
// null space reproduced at every lambda, the degrees of freedom against the influence matrix built
// column by column, the discrepancy and GCV choices of lambda, the non-negative fit, few rows.
#include "quintic_spline.hpp"
#include "smoothing_spline.hpp"

#include <mechgraph/errors.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <functional>
#include <numbers>
#include <vector>

using namespace mechgraph;
using namespace mechgraph::cams;
using Catch::Matchers::WithinAbs;
using Catch::Matchers::WithinRel;

namespace {

constexpr double pi = std::numbers::pi;
constexpr double H = 8e-3;          // lift scale, m
constexpr double P = 65 * pi / 180;  // half event, rad

struct Rows {
  std::vector<double> x, y;
};

// m rows over [-P, P], unevenly spaced inside, y = f(x) with both ends zero.
Rows rows_of(int m, const std::function<double(double)>& f) {
  Rows r;
  for (int i = 0; i < m; ++i) {
    const double even = -P + 2 * P * i / (m - 1);
    const double x = (i == 0 || i == m - 1) ? even : even + 0.2 * (2 * P / (m - 1)) * std::sin(3.7 * i);
    r.x.push_back(x);
    r.y.push_back((i == 0 || i == m - 1) ? 0.0 : f(x));
  }
  return r;
}

// A smooth lift with a fixed, noise-like ripple of 0.5 um (deterministic).
double rippled(double x, int i) { return H * 0.5 * (1 + std::cos(pi * x / P)) + 0.5e-6 * std::sin(37.0 * i); }

Rows rippled_rows(int m) {
  Rows r = rows_of(m, [](double) { return 0.0; });
  for (int i = 1; i + 1 < m; ++i) r.y[i] = rippled(r.x[i], i);
  return r;
}

// The spline's value at every row.
std::vector<double> values_at_rows(const QuinticPieces& s, const std::vector<double>& x) {
  std::vector<double> v;
  for (double xi : x) v.push_back(s.at(xi)[0]);
  return v;
}

}  // namespace

TEST_CASE("smoothing spline: lambda -> 0 interpolates the rows", "[cams][table][smoothing]") {
  const Rows r = rippled_rows(15);
  const QuinticSmoother smoother(r.x, r.y);
  SmoothingWork work;
  const auto fit = smoother.fit(QuinticSmoother::lambda_min, true, work);
  const auto v = values_at_rows(smoother.pieces(fit.coefficients), r.x);
  for (std::size_t i = 0; i < r.x.size(); ++i) CHECK_THAT(v[i], WithinAbs(r.y[i], 1e-7 * H));
  // Every inner row is a degree of freedom.
  CHECK_THAT(fit.dof, WithinAbs(smoother.inner_rows(), 1e-4));
  CHECK(work.solves == 1);
}

TEST_CASE("smoothing spline: lambda -> infinity is the least-squares cubic through the ends", "[cams][table][smoothing]") {
  // The penalty's null space, held at zero at both ends: s = q(x) (a + b x), q = (x - x0)(xn - x).
  // Its least-squares fit to the inner rows by the 2 x 2 normal equations, solved apart.
  const Rows r = rippled_rows(15);
  const double x0 = r.x.front(), xn = r.x.back();
  double s11 = 0, s12 = 0, s22 = 0, t1 = 0, t2 = 0;
  for (std::size_t i = 1; i + 1 < r.x.size(); ++i) {
    const double q = (r.x[i] - x0) * (xn - r.x[i]), u = q * r.x[i];
    s11 += q * q, s12 += q * u, s22 += u * u, t1 += q * r.y[i], t2 += u * r.y[i];
  }
  const double det = s11 * s22 - s12 * s12;
  const double a = (t1 * s22 - t2 * s12) / det, b = (s11 * t2 - s12 * t1) / det;
  const QuinticSmoother smoother(r.x, r.y);
  SmoothingWork work;
  const auto fit = smoother.fit(smoother.lambda_max(), true, work);
  const QuinticPieces s = smoother.pieces(fit.coefficients);
  for (int k = 0; k <= 200; ++k) {
    const double x = x0 + (xn - x0) * k / 200.0;
    const double q = (x - x0) * (xn - x), cubic = q * (a + b * x);
    CHECK_THAT(s.at(x)[0], WithinAbs(cubic, 1e-7 * H));
  }
  CHECK_THAT(fit.dof, WithinAbs(2.0, 1e-5));
}

TEST_CASE("smoothing spline: a cubic through the ends is reproduced at every lambda", "[cams][table][smoothing]") {
  // In the penalty's null space: nothing to smooth, whatever lambda.
  auto cubic = [](double x) { return H * (P * P - x * x) / (P * P) * (0.7 + 0.3 * x / P); };
  const Rows r = rows_of(21, cubic);
  const QuinticSmoother smoother(r.x, r.y);
  SmoothingWork work;
  for (double lambda : {1e-6, 1.0, 1e4, 1e9}) {
    INFO("lambda = " << lambda);
    const QuinticPieces s = smoother.pieces(smoother.fit(lambda, false, work).coefficients);
    for (int k = 1; k < 100; ++k) {
      const double x = -P + 2 * P * k / 100.0;
      const auto d = s.at(x);
      // h = H (P^2 - x^2)(0.7 + 0.3 x/P) / P^2 and its derivatives.
      const double h1 = H / (P * P) * (-2 * x * (0.7 + 0.3 * x / P) + (P * P - x * x) * 0.3 / P);
      const double h2 = H / (P * P) * (-2 * (0.7 + 0.3 * x / P) - 1.2 * x / P);
      const double h3 = H / (P * P) * (-1.8 / P);
      CHECK_THAT(d[0], WithinAbs(cubic(x), 1e-12 * H));
      CHECK_THAT(d[1], WithinAbs(h1, 1e-9 * H / P));
      CHECK_THAT(d[2], WithinAbs(h2, 1e-8 * H / (P * P)));
      CHECK_THAT(d[3], WithinAbs(h3, 1e-7 * H / (P * P * P)));
    }
  }
}

TEST_CASE("smoothing spline: degrees of freedom equal the trace of the influence matrix", "[cams][table][smoothing]") {
  // Second method: the influence matrix column by column, smoothing the unit vector of each inner
  // row; its diagonal summed is the trace the band recursion gives.
  const Rows r = rippled_rows(20);
  const QuinticSmoother smoother(r.x, r.y);
  SmoothingWork work;
  for (double lambda : {1e-3, 1.0, 1e3, 1e7}) {
    INFO("lambda = " << lambda);
    double trace = 0.0;
    for (std::size_t i = 1; i + 1 < r.x.size(); ++i) {
      std::vector<double> e(r.x.size(), 0.0);
      e[i] = 1.0;
      trace += smoother.pieces(smoother.smooth(e, lambda, work)).at(r.x[i])[0];
    }
    const double dof = smoother.fit(lambda, true, work).dof;
    CHECK_THAT(dof, WithinRel(trace, 1e-9) || WithinAbs(trace, 1e-9));
    CHECK(dof > 2.0);
    CHECK(dof < smoother.inner_rows());
  }
}

TEST_CASE("smoothing spline: the discrepancy principle and GCV", "[cams][table][smoothing]") {
  const Rows r = rippled_rows(40);
  const QuinticSmoother smoother(r.x, r.y);
  const int m = smoother.inner_rows();
  SmoothingWork work;
  // The residual RMS grows with lambda.
  double previous = -1.0;
  for (double l = -8; l <= 15; l += 1.0) {
    const double rss = smoother.fit(std::pow(10.0, l), false, work).rss;
    CHECK(rss >= previous * (1 - 1e-9));
    previous = rss;
  }
  // The root: the residual RMS at the lambda found is the target.
  bool at_limit = true;
  const double target = 0.2e-6;
  const double lambda = smoother.lambda_for_rms(target, at_limit, work);
  CHECK_FALSE(at_limit);
  CHECK_THAT(std::sqrt(smoother.fit(lambda, false, work).rss / m), WithinRel(target, 1e-6));
  // Targets out of reach: the ends of the range, flagged.
  CHECK(smoother.lambda_for_rms(1e-30, at_limit, work) == QuinticSmoother::lambda_min);
  CHECK(at_limit);
  CHECK(smoother.lambda_for_rms(1.0, at_limit, work) == smoother.lambda_max());
  CHECK(at_limit);
  // GCV: a minimum of the score (not above its neighbours 1 % either side).
  const long solves_before = work.solves;
  const double best = smoother.lambda_by_gcv(at_limit, work);
  CHECK_FALSE(at_limit);
  CHECK(work.solves > solves_before);
  const double score = smoother.gcv(best, work);
  CHECK(score <= smoother.gcv(best * 1.01, work) * (1 + 1e-9));
  CHECK(score <= smoother.gcv(best / 1.01, work) * (1 + 1e-9));
}

TEST_CASE("smoothing spline: the non-negative fit keeps the lift >= 0", "[cams][table][smoothing]") {
  // A narrow lobe on long zero flanks: the unconstrained fit swings below zero beside it.
  const Rows r = rows_of(41, [](double x) { return H * std::exp(-std::pow(x / (0.12 * P), 2)); });
  const QuinticSmoother smoother(r.x, r.y);
  SmoothingWork work;
  const double lambda = 10.0;
  auto dense_min = [&](const QuinticPieces& s) {
    double lowest = 0.0;
    for (int k = 0; k <= 4000; ++k) lowest = std::min(lowest, s.at(-P + 2 * P * k / 4000.0)[0]);
    return lowest;
  };
  const auto free = smoother.fit(lambda, false, work);
  REQUIRE(dense_min(smoother.pieces(free.coefficients)) < -1e-3 * H);
  const auto kept = smoother.fit_nonnegative(lambda, work);
  CHECK(kept.held_at_zero > 0);
  for (double c : kept.coefficients) CHECK(c >= 0.0);
  CHECK(dense_min(smoother.pieces(kept.coefficients)) >= -1e-15 * H);  // >= 0 but for rounding
  // The constraint costs some fit, not much: the residual stays of the same order.
  CHECK(kept.rss >= free.rss);
  CHECK(kept.rss < 4.0 * free.rss + 1e-18);
  CHECK(kept.dof > 2.0);
  CHECK(kept.dof < smoother.inner_rows());
  // Data that rise from the ends with a slope need no constraint: nothing held.
  Rows smooth = rippled_rows(30);
  for (std::size_t i = 1; i + 1 < smooth.x.size(); ++i) smooth.y[i] = H * (1 - std::pow(smooth.x[i] / P, 2)) + 0.5e-6 * std::sin(37.0 * i);
  const QuinticSmoother other(smooth.x, smooth.y);
  CHECK(other.fit_nonnegative(1.0, work).held_at_zero == 0);
}

TEST_CASE("smoothing spline: few rows", "[cams][table][smoothing]") {
  const Rows r = rippled_rows(4);
  const QuinticSmoother smoother(r.x, r.y);
  SmoothingWork work;
  for (double lambda : {QuinticSmoother::lambda_min, 1.0, smoother.lambda_max()}) {
    const auto fit = smoother.fit(lambda, true, work);
    for (double c : fit.coefficients) CHECK(std::isfinite(c));
    CHECK(fit.dof >= 2.0 - 1e-6);
    CHECK(fit.dof <= 2.0 + 1e-6);  // two inner rows, two null-space cubics: nothing to smooth
  }
  bool at_limit = false;
  CHECK(std::isfinite(smoother.lambda_by_gcv(at_limit, work)));
  const Rows three = rippled_rows(3);
  CHECK_THROWS_AS(QuinticSmoother(three.x, three.y), NodeError);
}

TEST_CASE("quintic pieces: peak and RMS of h'' and h''' against dense sampling", "[cams][table]") {
  const Rows r = rows_of(31, [](double x) { return H * 0.5 * (1 + std::cos(pi * x / P)) * (1 + 0.2 * x / P); });
  const QuinticPieces s = interpolate_quintic(r.x, r.y, "test: ");
  for (int k : {2, 3}) {
    INFO("derivative " << k);
    double peak = 0.0, sum = 0.0;
    const int n = 200000;
    for (int i = 0; i <= n; ++i) {
      const double v = s.at(-P + 2 * P * i / n)[k];
      peak = std::max(peak, std::abs(v));
      sum += (i == 0 || i == n ? 0.5 : 1.0) * v * v;
    }
    const double rms = std::sqrt(sum / n);
    const double scale = H / std::pow(P, k);
    CHECK(s.max_abs_derivative(k) >= peak * (1 - 1e-12));
    CHECK_THAT(s.max_abs_derivative(k), WithinRel(peak, 1e-6) || WithinAbs(peak, 1e-9 * scale));
    CHECK_THAT(s.rms_derivative(k), WithinRel(rms, 1e-4));
  }
}
