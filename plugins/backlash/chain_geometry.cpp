#include "chain_geometry.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace mechgraph::backlash {

Vec3 operator-(const Vec3& a, const Vec3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }

Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

double norm(const Vec3& a) { return std::hypot(a[0], a[1], a[2]); }

double moment_arm(const Vec3& rod_fixed, const Vec3& rod_moving, const Vec3& axis_point, const Vec3& axis_direction) {
  const Vec3 rod = rod_moving - rod_fixed;
  const double rod_length = norm(rod);
  const double axis_length = norm(axis_direction);
  // R = ((P - A) x u) . n, with the normalisations of u and n taken out of the product.
  return dot(cross(rod_moving - axis_point, rod), axis_direction) / (rod_length * axis_length);
}

double determinant(const Matrix2& m) { return m[0] * m[3] - m[1] * m[2]; }

std::array<double, 2> singular_values(const Matrix2& m) {
  const double a = m[0], b = m[1], c = m[2], d = m[3];
  const double largest = 0.5 * (std::hypot(a + d, b - c) + std::hypot(a - d, b + c));
  if (largest == 0.0) return {0.0, 0.0};
  return {largest, std::abs(determinant(m)) / largest};
}

namespace {

// The largest |entry|: the condition number and the inverse are computed on m / scale, whose
// entries lie in [-1, 1], so neither the determinant (1e160^2) nor the singular values overflow
// or underflow for any finite matrix.
double entry_scale(const Matrix2& m) {
  return std::max(std::max(std::abs(m[0]), std::abs(m[1])), std::max(std::abs(m[2]), std::abs(m[3])));
}

Matrix2 scaled(const Matrix2& m, double scale) { return {m[0] / scale, m[1] / scale, m[2] / scale, m[3] / scale}; }

}  // namespace

double condition_number(const Matrix2& m) {
  const double scale = entry_scale(m);
  if (!(scale > 0.0) || !std::isfinite(scale)) return std::numeric_limits<double>::infinity();
  // kappa(m) = kappa(m / scale): the ratio of singular values does not change with a common factor.
  const auto s = singular_values(scaled(m, scale));
  if (s[1] == 0.0) return std::numeric_limits<double>::infinity();
  return s[0] / s[1];
}

Matrix2 inverse(const Matrix2& m) {
  // inv(m) = inv(m / scale) / scale; the caller checks the result is finite (a scale near the
  // smallest double overflows it).
  const double scale = entry_scale(m);
  const Matrix2 n = scaled(m, scale);
  const double det = determinant(n);
  return {n[3] / det / scale, -n[1] / det / scale, -n[2] / det / scale, n[0] / det / scale};
}

}  // namespace mechgraph::backlash
