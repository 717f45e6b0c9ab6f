#include "rise_law.hpp"

#include <mechgraph/errors.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <string>

namespace mechgraph::cams {
namespace {

constexpr double pi = std::numbers::pi;

// t - sin(t) without the cancellation of the direct difference for small t (Taylor series below
// 0.1: the first neglected term, t^13/13!, is below 1e-22 of t^3/6 there).
double t_minus_sin(double t) {
  if (std::abs(t) >= 0.1) return t - std::sin(t);
  const double t2 = t * t;
  return t * t2 * (1.0 / 6.0 - t2 * (1.0 / 120.0 - t2 * (1.0 / 5040.0 - t2 * (1.0 / 362880.0 - t2 / 39916800.0))));
}

// A sine-shaped acceleration start shared by the modified trapezoid and modified sine: on
// 0 <= x <= 1/8, s'' = A sin(w x) with w = 4 pi (a quarter wave reaching A at x = 1/8), so
// s''' = A w cos(w x), s' = (A/w)(1 - cos w x) = (2A/w) sin^2(w x/2), s = (A/w^2)(w x - sin w x).
RiseValue quarter_sine_start(double A, double x) {
  constexpr double w = 4.0 * pi;
  const double half = std::sin(0.5 * w * x);
  return {A / (w * w) * t_minus_sin(w * x), 2.0 * A / w * half * half, A * std::sin(w * x), A * w * std::cos(w * x)};
}

// Each law on the first half of the rise, 0 <= x <= 1/2; the second half follows from the
// antisymmetry s(x) = 1 - s(1 - x).
RiseValue first_half(RiseShape shape, double x) {
  switch (shape) {
    case RiseShape::cycloidal: {
      // s = x - sin(2 pi x)/(2 pi), s' = 1 - cos(2 pi x) = 2 sin^2(pi x), s'' = 2 pi sin(2 pi x),
      // s''' = 4 pi^2 cos(2 pi x).
      const double t = 2.0 * pi * x;
      const double h = std::sin(pi * x);
      return {t_minus_sin(t) / (2.0 * pi), 2.0 * h * h, 2.0 * pi * std::sin(t), 4.0 * pi * pi * std::cos(t)};
    }
    case RiseShape::harmonic: {
      // s = (1 - cos pi x)/2 = sin^2(pi x/2), s' = (pi/2) sin(pi x), s'' = (pi^2/2) cos(pi x),
      // s''' = -(pi^3/2) sin(pi x).
      const double h = std::sin(0.5 * pi * x);
      const double sn = std::sin(pi * x), cs = std::cos(pi * x);
      return {h * h, 0.5 * pi * sn, 0.5 * pi * pi * cs, -0.5 * pi * pi * pi * sn};
    }
    case RiseShape::poly345: {
      // s = 10x^3 - 15x^4 + 6x^5 = x^3 (10 - 15x + 6x^2), s' = 30 x^2 (1-x)^2,
      // s'' = 60 x (1-x)(1-2x), s''' = 60 (1 - 6x + 6x^2).
      const double y = 1.0 - x;
      return {x * x * x * (10.0 + x * (-15.0 + 6.0 * x)), 30.0 * x * x * y * y, 60.0 * x * y * (1.0 - 2.0 * x),
              60.0 * (1.0 + x * (-6.0 + 6.0 * x))};
    }
    case RiseShape::poly4567: {
      // s = 35x^4 - 84x^5 + 70x^6 - 20x^7, s' = 140 x^3 (1-x)^3, s'' = 420 x^2 (1-x)^2 (1-2x),
      // s''' = 840 x (1-x)(1 - 5x + 5x^2).
      const double y = 1.0 - x;
      const double x2 = x * x;
      return {x2 * x2 * (35.0 + x * (-84.0 + x * (70.0 - 20.0 * x))), 140.0 * x2 * x * y * y * y,
              420.0 * x2 * y * y * (1.0 - 2.0 * x), 840.0 * x * y * (1.0 + x * (-5.0 + 5.0 * x))};
    }
    case RiseShape::modified_trapezoid: {
      // Acceleration: quarter sine up to A on [0, 1/8], constant A on [1/8, 3/8], a half cosine
      // A cos(4 pi (x - 3/8)) through zero at 1/2 (and on to -A at 5/8). s(1/2) = 1/2 gives
      // A (2 + pi)/(16 pi) = 1/2, A = 8 pi/(2 + pi); peak velocity s'(1/2) = A (2 + pi)/(4 pi) = 2.
      constexpr double A = 8.0 * pi / (2.0 + pi);
      constexpr double w = 4.0 * pi;
      if (x <= 0.125) return quarter_sine_start(A, x);
      const double v1 = A / w;                      // s'(1/8)
      const double s1 = A / (w * w) * (0.5 * pi - 1.0);  // s(1/8)
      if (x <= 0.375) {
        const double u = x - 0.125;
        return {s1 + u * (v1 + 0.5 * A * u), v1 + A * u, A, 0.0};
      }
      const double v2 = v1 + 0.25 * A;                    // s'(3/8)
      const double s2 = s1 + 0.25 * v1 + A / 32.0;        // s(3/8)
      const double u = x - 0.375;
      const double half = std::sin(0.5 * w * u);
      return {s2 + v2 * u + 2.0 * A / (w * w) * half * half, v2 + A / w * std::sin(w * u), A * std::cos(w * u),
              -A * w * std::sin(w * u)};
    }
    case RiseShape::modified_sine: {
      // Acceleration: quarter sine up to A on [0, 1/8], then A cos(4 pi/3 (x - 1/8)) through zero
      // at 1/2 (and on to -A at 7/8). s(1/2) = 1/2 gives A (4 + pi)/(8 pi^2) = 1/2,
      // A = 4 pi^2/(4 + pi); peak velocity s'(1/2) = A/pi = 4 pi/(4 + pi).
      constexpr double A = 4.0 * pi * pi / (4.0 + pi);
      constexpr double w1 = 4.0 * pi;
      constexpr double w2 = 4.0 * pi / 3.0;
      if (x <= 0.125) return quarter_sine_start(A, x);
      const double v1 = A / w1;
      const double s1 = A / (w1 * w1) * (0.5 * pi - 1.0);
      const double u = x - 0.125;
      const double half = std::sin(0.5 * w2 * u);
      return {s1 + v1 * u + 2.0 * A / (w2 * w2) * half * half, v1 + A / w2 * std::sin(w2 * u),
              A * std::cos(w2 * u), -A * w2 * std::sin(w2 * u)};
    }
  }
  return {};
}

void require(bool ok, const char* parameter, const std::string& message) {
  if (!ok) throw NodeError(parameter, message);
}

}  // namespace

RiseValue evaluate_rise(RiseShape shape, double x) {
  x = std::clamp(x, 0.0, 1.0);
  if (x <= 0.5) return first_half(shape, x);
  // s(x) = 1 - s(1 - x): s' and s''' even about 1/2, s'' odd.
  const RiseValue m = first_half(shape, 1.0 - x);
  return {1.0 - m.s, m.ds, -m.d2s, m.d3s};
}

std::vector<double> rise_breakpoints(RiseShape shape) {
  switch (shape) {
    case RiseShape::modified_trapezoid: return {0.125, 0.375, 0.625, 0.875};
    case RiseShape::modified_sine: return {0.125, 0.875};
    default: return {};
  }
}

int rise_return_continuity(RiseShape shape) {
  switch (shape) {
    case RiseShape::harmonic: return 1;
    case RiseShape::poly4567: return 3;
    default: return 2;
  }
}

std::string_view rise_shape_name(RiseShape shape) {
  switch (shape) {
    case RiseShape::cycloidal: return "cycloidal";
    case RiseShape::harmonic: return "harmonic";
    case RiseShape::poly345: return "poly345";
    case RiseShape::poly4567: return "poly4567";
    case RiseShape::modified_trapezoid: return "modified_trapezoid";
    case RiseShape::modified_sine: return "modified_sine";
  }
  return "?";
}

std::optional<RiseShape> rise_shape_from_name(std::string_view name) {
  for (RiseShape s : all_rise_shapes)
    if (rise_shape_name(s) == name) return s;
  return std::nullopt;
}

SymmetricRiseReturnLaw::SymmetricRiseReturnLaw(RiseShape shape, double max_lift, double action_angle,
                                               double base_radius, double roller_radius)
    : shape_(shape),
      max_lift_(max_lift),
      half_action_(0.5 * action_angle),
      base_radius_(base_radius),
      roller_radius_(roller_radius) {
  std::ostringstream m;
  m << "max_lift must be positive and finite (got " << max_lift * 1e3 << " mm)";
  require(std::isfinite(max_lift) && max_lift > 0.0, "max_lift", m.str());
  m.str("");
  m << "action_angle must lie in (0, 360) deg (got " << action_angle * 180.0 / pi << " deg)";
  require(std::isfinite(action_angle) && action_angle > 0.0 && action_angle < 2.0 * pi, "action_angle", m.str());
  m.str("");
  m << "base_radius must be positive and finite (got " << base_radius * 1e3 << " mm)";
  require(std::isfinite(base_radius) && base_radius > 0.0, "base_radius", m.str());
  m.str("");
  m << "roller_radius must be non-negative and finite (got " << roller_radius * 1e3 << " mm)";
  require(std::isfinite(roller_radius) && roller_radius >= 0.0, "roller_radius", m.str());
  // |s'''| < 70 for all six laws: the jerk H s'''/P^3 must be a finite number.
  const double k = 1.0 / half_action_;
  m.str("");
  m << "action_angle " << action_angle * 180.0 / pi << " deg is too small for double precision at max_lift "
    << max_lift * 1e3 << " mm (the jerk overflows)";
  require(std::isfinite(70.0 * max_lift * k * k * k), "action_angle", m.str());
}

LiftDerivatives SymmetricRiseReturnLaw::evaluate_in_event(double phi) const {
  // Chain rule for x = (phi + P)/P on the rise (P = phi_d/2): d/dphi = (1/P) d/dx. The return is
  // the mirror image h(phi) = h(-phi), so its odd derivatives change sign.
  const double k = 1.0 / half_action_;
  const bool rising = phi <= 0.0;
  const double x = rising ? (phi + half_action_) * k : (half_action_ - phi) * k;
  const RiseValue r = evaluate_rise(shape_, x);
  const double sign = rising ? 1.0 : -1.0;
  const double H = max_lift_;
  return {H * r.s, sign * H * r.ds * k, H * r.d2s * k * k, sign * H * r.d3s * k * k * k};
}

std::vector<double> SymmetricRiseReturnLaw::breakpoints() const {
  // Rise pieces, the nose (the formula mirrors there), then the return pieces.
  std::vector<double> out;
  for (double x : rise_breakpoints(shape_)) out.push_back(-half_action_ + x * half_action_);
  out.push_back(0.0);
  for (double x : rise_breakpoints(shape_)) out.push_back(half_action_ - x * half_action_);
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

}  // namespace mechgraph::cams
