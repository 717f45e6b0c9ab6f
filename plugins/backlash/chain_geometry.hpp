#pragma once
// Geometry of the steering drive (docs/methods/backlash.md, "Geometry instead of a scalar lever arm").
//
// Moment arm. The rod acts along its line through the fixed attachment F and the moving
// attachment P, unit direction u = (P - F)/|P - F|. The nozzle swivels about the axis through A
// with unit direction n = a/|a|. A unit force along the rod has the moment n . ((P - A) x u)
// about the axis: that is the signed moment arm
//     R = ((P - A) x u) . n,
// and a small rod length change dL turns the nozzle by d_theta = dL / R. |R| is the distance
// between the rod's line and the axis times the sine of the angle between them; R -> 0 (the rod's
// line passing through the axis, or parallel to it) is a singular design.
//
// Two actuators. With the Jacobian J_ij = dL_i/d theta_j (rod i, swivel axis j), small rod length
// changes dL and swivel angles d_theta obey dL = J d_theta, so d_theta = J^-1 dL. The worst case
// of axis j over |dL_i| <= b_i/2 is sum_i |(J^-1)_ji| b_i/2; peak to peak, sum_i |(J^-1)_ji| b_i.
// Near-singular J (condition number sigma_max/sigma_min large) magnifies the play without bound.
#include <array>

namespace mechgraph::backlash {

using Vec3 = std::array<double, 3>;

Vec3 operator-(const Vec3& a, const Vec3& b);
Vec3 cross(const Vec3& a, const Vec3& b);
double dot(const Vec3& a, const Vec3& b);
double norm(const Vec3& a);

/// Signed moment arm R = ((P - A) x u) . n of the rod's line about the axis. Preconditions:
/// |P - F| > 0 and |axis_direction| > 0 (the caller checks and names the parameter).
double moment_arm(const Vec3& rod_fixed, const Vec3& rod_moving, const Vec3& axis_point, const Vec3& axis_direction);

/// A 2x2 matrix, row-major: {a11, a12, a21, a22}.
using Matrix2 = std::array<double, 4>;

double determinant(const Matrix2& m);
/// Singular values sigma_max >= sigma_min >= 0, in closed form:
///   sigma_max = (sqrt((a + d)^2 + (b - c)^2) + sqrt((a - d)^2 + (b + c)^2)) / 2,
///   sigma_min = |det| / sigma_max (no cancellation near singularity).
std::array<double, 2> singular_values(const Matrix2& m);
/// sigma_max / sigma_min; +infinity for a singular (or zero) matrix.
double condition_number(const Matrix2& m);
/// The inverse (1/det) {a22, -a12, -a21, a11}. Precondition: det != 0.
Matrix2 inverse(const Matrix2& m);

}  // namespace mechgraph::backlash
