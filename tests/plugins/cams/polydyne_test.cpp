// cam.polydyne: closed-form coefficients against independent solves of the end conditions
// (exact rational elimination, and long double elimination within its conditioning), the end
// conditions themselves, precision near the seat against a 100-digit reference, exact
// derivatives against central differences, exponent validation and extreme exponent sets.
#include "cam_test_support.hpp"

#include <catch2/catch.hpp>

#include "polydyne.hpp"
#include "registration.hpp"

#include <boost/multiprecision/cpp_bin_float.hpp>
#include <boost/multiprecision/cpp_int.hpp>

#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <string>
#include <vector>

namespace {

using namespace mechgraph;
using namespace mechgraph::cams;
using boost::multiprecision::cpp_bin_float_100;
using boost::multiprecision::cpp_int;
using boost::multiprecision::cpp_rational;

constexpr double pi = std::numbers::pi;
constexpr double deg = pi / 180.0;
constexpr double mm = 1e-3;


OutputSet run_polydyne(const std::map<std::string, ParamValue>& given) { return mechgraph::cams::testing::run_cam("cam.polydyne", given); }

// Base radius large enough that a flat tappet does not undercut even [2, 4, 6, 8, 10]
// (r0 + h + h'' > 0 with h''(0) = -10 h / phi_p^2).
std::map<std::string, ParamValue> base_params() {
  return {{"max_lift", ParamValue::of_number(9 * mm)},
          {"action_angle", ParamValue::of_number(160 * deg)},
          {"base_radius", ParamValue::of_number(50 * mm)}};
}

std::string exponent_error(std::vector<double> exponents) {
  auto p = base_params();
  p["exponents"] = ParamValue::of_list(std::move(exponents));
  try {
    run_polydyne(p);
  } catch (const NodeError& e) {
    return e.parameter() + ": " + e.what();
  }
  return "";
}

// Falling factorial n (n-1) ... (n-m+1): d^m/du^m u^n at u = 1.
template <class T>
T falling(int n, int m) {
  T r = 1;
  for (int k = 0; k < m; ++k) r *= T(n - k);
  return r;
}

// The end conditions as a linear system: sum_i C_i P_m(n_i) = -[m == 0], m = 0..4.
template <class T>
std::vector<std::vector<T>> end_condition_matrix(const std::vector<int>& n) {
  std::vector<std::vector<T>> M(5, std::vector<T>(6));
  for (int m = 0; m < 5; ++m) {
    for (int i = 0; i < 5; ++i) M[m][i] = falling<T>(n[i], m);
    M[m][5] = m == 0 ? T(-1) : T(0);
  }
  return M;
}

// Gaussian elimination with partial pivoting on an augmented 5x6 matrix.
template <class T>
std::vector<T> solve(std::vector<std::vector<T>> M) {
  using std::abs;
  const int N = 5;
  for (int c = 0; c < N; ++c) {
    int p = c;
    for (int r = c + 1; r < N; ++r)
      if (abs(M[r][c]) > abs(M[p][c])) p = r;
    std::swap(M[c], M[p]);
    for (int r = c + 1; r < N; ++r) {
      const T f = M[r][c] / M[c][c];
      for (int k = c; k <= N; ++k) M[r][k] -= f * M[c][k];
    }
  }
  std::vector<T> x(N);
  for (int r = N - 1; r >= 0; --r) {
    T s = M[r][N];
    for (int k = r + 1; k < N; ++k) s -= M[r][k] * x[k];
    x[r] = s / M[r][r];
  }
  return x;
}

// 1-norm condition number of the 5x5 system matrix, its inverse column by column.
long double condition_number(const std::vector<int>& n) {
  auto M = end_condition_matrix<long double>(n);
  long double norm = 0, inv_norm = 0;
  for (int c = 0; c < 5; ++c) {
    long double col = 0;
    for (int r = 0; r < 5; ++r) col += std::abs(M[r][c]);
    norm = std::max(norm, col);
  }
  for (int c = 0; c < 5; ++c) {
    auto A = M;
    for (int r = 0; r < 5; ++r) A[r][5] = r == c ? 1.0L : 0.0L;
    long double col = 0;
    for (long double v : solve(A)) col += std::abs(v);
    inv_norm = std::max(inv_norm, col);
  }
  return norm * inv_norm;
}

std::vector<cpp_rational> closed_form_rational(const std::vector<int>& n) {
  std::vector<cpp_rational> c;
  for (const auto& [num, den] : polydyne_coefficients_exact(n)) c.emplace_back(cpp_int(num), cpp_int(den));
  return c;
}

// 100-digit reference of d^m/du^m x(u)/h from the exact coefficients, summed as monomials.
cpp_bin_float_100 reference(const std::vector<int>& n, const std::vector<cpp_rational>& c, int m,
                           const cpp_bin_float_100& u) {
  cpp_bin_float_100 sum = m == 0 ? 1 : 0;
  for (std::size_t i = 0; i < n.size(); ++i) {
    const cpp_bin_float_100 ci = cpp_bin_float_100(numerator(c[i])) / cpp_bin_float_100(denominator(c[i]));
    sum += ci * falling<cpp_bin_float_100>(n[i], m) * pow(u, n[i] - m);
  }
  return sum;
}

const std::vector<std::vector<int>> kExponentSets{
    {2, 6, 10, 14, 18}, {2, 10, 20, 30, 40}, {2, 4, 6, 8, 10}, {2, 10, 18, 26, 34}, {2, 14, 26, 38, 50}};

}  // namespace

TEST_CASE("polydyne: closed-form coefficients", "[cams][polydyne]") {
  // 2-6-10-14-18 (the family of Dudley's and Stoddart's valve cams; Rothbart, Cam Design
  // Handbook, fig. 4.9): C = -315/128, 105/32, -189/64, 45/32, -35/128.
  const auto c = polydyne_coefficients_exact({2, 6, 10, 14, 18});
  const std::vector<std::pair<std::int64_t, std::int64_t>> expected{
      {-315, 128}, {105, 32}, {-189, 64}, {45, 32}, {-35, 128}};
  CHECK(c == expected);
  // [2, 4, 6, 8, 10] is x = (1 - u^2)^5: binomial coefficients.
  const std::vector<std::pair<std::int64_t, std::int64_t>> binomial{{-5, 1}, {10, 1}, {-10, 1}, {5, 1}, {-1, 1}};
  CHECK(polydyne_coefficients_exact({2, 4, 6, 8, 10}) == binomial);

  for (const auto& n : kExponentSets) {
    INFO("exponents " << n[0] << "-" << n[1] << "-" << n[2] << "-" << n[3] << "-" << n[4]);
    const std::vector<cpp_rational> closed = closed_form_rational(n);
    // Independent 1: exact rational elimination of the end-condition system: identical.
    const std::vector<cpp_rational> exact = solve(end_condition_matrix<cpp_rational>(n));
    for (int i = 0; i < 5; ++i) CHECK(closed[i] == exact[i]);
    // The end conditions hold exactly: x(1) = x'(1) = ... = x''''(1) = 0, and x(0) = 1 by form.
    for (int m = 0; m < 5; ++m) {
      cpp_rational s = m == 0 ? 1 : 0;
      for (int i = 0; i < 5; ++i) s += closed[i] * falling<cpp_rational>(n[i], m);
      CHECK(s == 0);
    }
    // Independent 2: long double elimination, within what its conditioning allows.
    const std::vector<long double> ld = solve(end_condition_matrix<long double>(n));
    const long double cond = condition_number(n);
    const long double tol = 100.0L * cond * std::numeric_limits<long double>::epsilon();
    INFO("condition number " << static_cast<double>(cond));
    const PolydyneLaw law(9 * mm, 130 * deg, 17 * mm, n);
    long double cmax = 0;
    for (long double v : ld) cmax = std::max(cmax, std::abs(v));
    for (int i = 0; i < 5; ++i) {
      CHECK(static_cast<double>(std::abs(ld[i] - static_cast<long double>(law.coefficients()[i]))) <=
            static_cast<double>(tol * cmax) + 1e-16 * std::abs(law.coefficients()[i]));
    }
  }
  // The conditioning the method note warns about.
  CHECK(condition_number({2, 14, 26, 38, 50}) > 1e6);
}

TEST_CASE("polydyne: the factored derivatives q_m are the exact rationals' to the last bit", "[cams][polydyne]") {
  // The series is computed over integers scaled by a common denominator; the reference here is
  // the plain rational computation: x = 1 + sum C_i u^n_i, its m-th derivative divided by
  // (1 - u)^(5-m) coefficient by coefficient (prefix sums), each reduced fraction converted to
  // long double as numerator / denominator.
  for (const std::vector<int>& n : std::vector<std::vector<int>>{{2, 6, 10, 14, 18}, {2, 14, 26, 38, 50},
                                                                 {2, 4, 6, 8, 10}, {2, 40, 400, 600, 1000}}) {
    INFO("exponents " << n[0] << "-" << n[1] << "-" << n[2] << "-" << n[3] << "-" << n[4]);
    const auto c = polydyne_coefficients_exact(n);
    std::vector<cpp_rational> x(static_cast<std::size_t>(n.back()) + 1, cpp_rational(0));
    x[0] = 1;
    for (int i = 0; i < 5; ++i) x[static_cast<std::size_t>(n[i])] = cpp_rational(cpp_int(c[i].first), cpp_int(c[i].second));
    const auto series = polydyne_series(n);
    std::vector<cpp_rational> derivative = x;
    for (int m = 0; m < 6; ++m) {
      if (m > 0) {
        std::vector<cpp_rational> d(derivative.size() - 1);
        for (std::size_t k = 1; k < derivative.size(); ++k) d[k - 1] = derivative[k] * static_cast<long long>(k);
        derivative = std::move(d);
      }
      std::vector<cpp_rational> q = derivative;
      for (int k = 0; k < 5 - m; ++k) {
        std::vector<cpp_rational> divided(q.size() - 1);
        cpp_rational sum = 0;
        for (std::size_t j = 0; j + 1 < q.size(); ++j) divided[j] = sum += q[j];
        REQUIRE(sum + q.back() == 0);
        q = std::move(divided);
      }
      const std::vector<long double>& got = series->q[static_cast<std::size_t>(m)];
      REQUIRE(got.size() == q.size());
      std::size_t differing = 0;
      for (std::size_t k = 0; k < q.size(); ++k) {
        const long double want = static_cast<long double>(numerator(q[k])) / static_cast<long double>(denominator(q[k]));
        // Equal finite values with equal signs: the same bits on any IEEE format.
        if (!(want == got[k] && std::signbit(want) == std::signbit(got[k]))) ++differing;
      }
      CHECK(differing == 0);
    }
  }
}

TEST_CASE("polydyne: lift keeps its digits near the seat", "[cams][polydyne]") {
  const double phi_p = 65 * deg, h = 9 * mm;
  for (const auto& n : kExponentSets) {
    INFO("exponents " << n[0] << "-" << n[1] << "-" << n[2] << "-" << n[3] << "-" << n[4]);
    const PolydyneLaw law(h, 2 * phi_p, 17 * mm, n);
    const std::vector<cpp_rational> c = closed_form_rational(n);
    // x^(5)(1): x^(m)(1 - w) ~ x^(5)(1) (-w)^(5-m) / (5-m)! sets the local scale of each derivative.
    cpp_rational d5 = 0;
    for (int i = 0; i < 5; ++i) d5 += c[i] * falling<cpp_rational>(n[i], 5);
    const double x5 = std::abs(static_cast<double>(cpp_bin_float_100(numerator(d5)) / cpp_bin_float_100(denominator(d5))));
    for (double w : {0.9, 0.5, 0.2, 1e-2, 1e-4, 1e-6, 1e-8}) {
      const double phi = phi_p * (1.0 - w);  // the double the law sees; the reference uses it exactly
      const cpp_bin_float_100 u = cpp_bin_float_100(phi) / cpp_bin_float_100(phi_p);
      const LiftDerivatives d = law.evaluate_in_event(phi);
      const double got[4] = {d.lift / h, d.velocity * phi_p / h, d.acceleration * phi_p * phi_p / h,
                             d.jerk * phi_p * phi_p * phi_p / h};
      for (int m = 0; m < 4; ++m) {
        const double ref = static_cast<double>(reference(n, c, m, u));
        double factorial = 1;
        for (int k = 2; k <= 5 - m; ++k) factorial *= k;
        const double local = x5 / factorial * std::pow(w, 5 - m);
        INFO("w = " << w << ", derivative " << m << ", reference " << ref);
        CHECK(got[m] == Approx(ref).epsilon(1e-14).margin(1e-15 * local));
      }
    }
  }
  // At u = 1 - 1e-4 the lift is ~2.5e-18 h: the naive monomial sum in double has no digit left,
  // the factored form has all of them.
  const std::vector<int> n{2, 6, 10, 14, 18};
  const PolydyneLaw law(h, 2 * phi_p, 17 * mm, n);
  const double phi = phi_p * (1.0 - 1e-4);
  const double u = phi / phi_p;
  double naive = 1.0;
  for (int i = 0; i < 5; ++i) naive += law.coefficients()[i] * std::pow(u, n[i]);
  const double ref =
      static_cast<double>(reference(n, closed_form_rational(n), 0, cpp_bin_float_100(phi) / cpp_bin_float_100(phi_p)));
  CHECK(ref == Approx(252e-20).epsilon(1e-3).margin(0));  // q_0(1) = 252: x ~ 252 w^5
  CHECK(std::abs(naive - ref) / ref > 1e-2);
  CHECK(law.evaluate_in_event(phi).lift / h == Approx(ref).epsilon(1e-15).margin(1e-40));
}

TEST_CASE("polydyne: law values, symmetry and derivatives", "[cams][polydyne]") {
  const PolydyneLaw law(9 * mm, 130 * deg, 17 * mm, {2, 6, 10, 14, 18});
  CHECK(law.at(0.0).lift == Approx(9 * mm).epsilon(1e-15).margin(0));
  CHECK(law.at(0.0).velocity == 0.0);
  CHECK(law.at(0.0).acceleration == Approx(2.0 * (-315.0 / 128.0) * 9 * mm / std::pow(65 * deg, 2)).epsilon(1e-15).margin(0));
  CHECK(law.breakpoints().empty());
  for (double phi : {0.05, 0.3, 0.7, 1.1}) {
    const LiftDerivatives p = law.at(phi), m = law.at(-phi);
    CHECK(p.lift == m.lift);
    CHECK(p.velocity == -m.velocity);
    CHECK(p.acceleration == m.acceleration);
    CHECK(p.jerk == -m.jerk);
  }
  // Central differences of each derivative against the next one.
  const double step = 1e-5, sh = 9 * mm;
  for (int i = 1; i < 60; ++i) {
    const double phi = -65 * deg + 130 * deg * i / 60.0 + 7e-4;
    const LiftDerivatives m = law.at(phi - step), c = law.at(phi), p = law.at(phi + step);
    CHECK(c.velocity == Approx((p.lift - m.lift) / (2 * step)).epsilon(1e-7).margin(1e-9 * sh));
    CHECK(c.acceleration == Approx((p.velocity - m.velocity) / (2 * step)).epsilon(1e-7).margin(1e-9 * sh));
    CHECK(c.jerk == Approx((p.acceleration - m.acceleration) / (2 * step)).epsilon(1e-6).margin(1e-8 * sh));
  }
  // Smooth onto the base circle: all four quantities vanish at the ends.
  for (int m = 0; m < 4; ++m) CHECK(law.normalized_derivative(m, 0.0L) == 0.0L);
  const LiftDerivatives end = law.at(65 * deg * (1 - 1e-9));
  CHECK(std::abs(end.lift) < 1e-40);
  CHECK(std::abs(end.jerk) < 1e-12);
}

TEST_CASE("polydyne node: default and extreme exponents", "[cams][polydyne]") {
  for (const auto& n : kExponentSets) {
    auto p = base_params();
    p["exponents"] = ParamValue::of_list(std::vector<double>(n.begin(), n.end()));
    const OutputSet out = run_polydyne(p);
    const auto law = std::dynamic_pointer_cast<const PolydyneLaw>(out.all().at("law").as_handle());
    REQUIRE(law);
    const double accel = out.all().at("accel_angle").as_scalar();
    INFO("exponents " << n[0] << "-" << n[1] << "-" << n[2] << "-" << n[3] << "-" << n[4]);
    CHECK(accel > 0.0);
    CHECK(accel < 80 * deg);
    CHECK(law->at(-80 * deg + accel).acceleration == Approx(0.0).margin(1e-9 * 9 * mm));
    CHECK(out.all().at("max_acceleration").as_scalar() > 0.0);
    CHECK(out.all().at("min_acceleration").as_scalar() < 0.0);
    // Lift falls monotonically from the nose.
    double last = law->at(0.0).lift;
    for (int i = 1; i <= 200; ++i) {
      const double now = law->at(80 * deg * i / 200.0).lift;
      CHECK(now <= last);
      last = now;
    }
  }
  // Higher exponents: shorter positive phase.
  auto p = base_params();
  const double default_accel = run_polydyne(p).all().at("accel_angle").as_scalar();
  p["exponents"] = ParamValue::of_list({2, 14, 26, 38, 50});
  CHECK(run_polydyne(p).all().at("accel_angle").as_scalar() < default_accel);
  // Large exponents stay exact and finite.
  const PolydyneLaw big(9 * mm, 130 * deg, 17 * mm, {2, 4, 6, 8, 1000});
  CHECK(std::isfinite(big.at(-64 * deg).jerk));
  CHECK(big.at(0.0).lift == Approx(9 * mm).epsilon(1e-15).margin(0));
}

TEST_CASE("polydyne: exponent validation", "[cams][polydyne]") {
  CHECK(exponent_error({2, 6, 10, 14, 18}).empty());
  CHECK_THAT(exponent_error({2, 6, 10, 14}), Catch::StartsWith("exponents: ") && Catch::Contains("exactly five"));
  CHECK_THAT(exponent_error({2, 6, 10, 14, 18, 22}), Catch::Contains("exactly five"));
  CHECK_THAT(exponent_error({4, 6, 10, 14, 18}), Catch::StartsWith("exponents: ") && Catch::Contains("first exponent must be 2"));
  CHECK_THAT(exponent_error({2, 6, 6, 14, 18}), Catch::Contains("increase strictly"));
  CHECK_THAT(exponent_error({2, 10, 6, 14, 18}), Catch::Contains("increase strictly"));
  CHECK_THAT(exponent_error({2, 5, 10, 14, 18}), Catch::Contains("even") && Catch::Contains("5 is odd"));
  CHECK_THAT(exponent_error({2, 6.5, 10, 14, 18}), Catch::Contains("integer"));
  CHECK_THAT(exponent_error({2, 6, 10, 14, 2000}), Catch::Contains("[2, 1000]"));
  CHECK_THAT(exponent_error({2, 6, 10, 14, -18}), Catch::StartsWith("exponents: "));
}

TEST_CASE("polydyne: the 4th and 5th derivatives against central differences of the lower ones", "[cams][polydyne]") {
  // Second method: 4-point central differences of the jerk (for d4) and of d4 (for d5), with the
  // step chosen for ~1e-8 relative accuracy; and the end conditions: d4 = 0 at the seat.
  const PolydyneLaw law(8e-3, 130 * std::numbers::pi / 180, 17e-3, {2, 6, 10, 14, 18});
  const double phi_p = 65 * std::numbers::pi / 180;
  for (double f : {-0.9, -0.5, -0.1, 0.05, 0.3, 0.7, 0.95}) {
    const double phi = f * phi_p, h = 1e-3;
    INFO("phi = " << f << " phi_p");
    double d4 = 0, d5 = 0;
    REQUIRE(law.higher_derivatives(phi, d4, d5));
    auto jerk = [&](double x) { return law.evaluate_in_event(x).jerk; };
    auto fourth = [&](double x) {
      double a = 0, b = 0;
      law.higher_derivatives(x, a, b);
      return a;
    };
    const double d4_fd = (-jerk(phi + 2 * h) + 8 * jerk(phi + h) - 8 * jerk(phi - h) + jerk(phi - 2 * h)) / (12 * h);
    const double d5_fd = (-fourth(phi + 2 * h) + 8 * fourth(phi + h) - 8 * fourth(phi - h) + fourth(phi - 2 * h)) / (12 * h);
    const double scale4 = 8e-3 / std::pow(phi_p, 4), scale5 = scale4 / phi_p;
    CHECK_THAT(d4, Catch::Matchers::WithinAbs(d4_fd, 1e-7 * scale4 * 1e3));
    CHECK_THAT(d5, Catch::Matchers::WithinAbs(d5_fd, 1e-7 * scale5 * 1e4));
  }
  // d4 has a simple zero at the seat (d4 ~ 1 - u): a thousand times closer, a thousand times smaller.
  double near4 = 0, near5 = 0, nearer4 = 0, nearer5 = 0;
  law.higher_derivatives(phi_p * (1 - 1e-6), near4, near5);
  law.higher_derivatives(phi_p * (1 - 1e-9), nearer4, nearer5);
  CHECK_THAT(nearer4 / near4, Catch::Matchers::WithinRel(1e-3, 1e-4));
  CHECK_THAT(nearer5, Catch::Matchers::WithinRel(near5, 1e-4));  // d5 does not vanish there
}

TEST_CASE("polydyne accel_angle: a real exponent q for the positive-acceleration phase", "[cams][polydyne]") {
  using Catch::Matchers::WithinAbs;
  using Catch::Matchers::WithinRel;
  const double deg = std::numbers::pi / 180;
  const std::map<std::string, ParamValue> basics{{"max_lift", ParamValue::of_number(8e-3)},
                                                 {"action_angle", ParamValue::of_number(130 * deg)},
                                                 {"base_radius", ParamValue::of_number(17e-3)}};
  auto with = [&](std::map<std::string, ParamValue> extra) {
    auto all = basics;
    all.insert(extra.begin(), extra.end());
    return all;
  };
  // Second method: the exact integer family 2-14-26-38-50 has some phase phi_y; asking the real
  // solver for that phase with step 12 must give back q = 14 and the same law.
  const OutputSet exact = cams::testing::run_cam("cam.polydyne", with({{"exponents", ParamValue::of_list({2, 14, 26, 38, 50})}}));
  const double phi_y = exact.all().at("accel_angle").as_scalar();
  const OutputSet real = cams::testing::run_cam("cam.polydyne", with({{"accel_angle", ParamValue::of_number(phi_y)},
                                                                {"exponent_step", ParamValue::of_number(12)}}));
  CHECK_THAT(real.all().at("exponent_q").as_scalar(), WithinRel(14.0, 1e-9));
  const auto a = std::dynamic_pointer_cast<const CamLaw>(exact.all().at("law").as_handle());
  const auto b = std::dynamic_pointer_cast<const CamLaw>(real.all().at("law").as_handle());
  for (double f : {-0.99, -0.6, -0.2, 0.0, 0.3, 0.8, 0.97}) {
    const double phi = f * 65 * deg;
    INFO("phi = " << f << " phi_p");
    CHECK_THAT(b->at(phi).lift, WithinAbs(a->at(phi).lift, 1e-13 * 8e-3));
    CHECK_THAT(b->at(phi).acceleration, WithinAbs(a->at(phi).acceleration, 1e-9 * 8e-3));
  }
  // Right at the seat (where the powers cancel and the law is summed as its series about u = 1) the
  // real law keeps its relative accuracy against the exact one; across the switch it is continuous.
  for (double w : {1e-2, 1e-3, 1e-5, 1e-7}) {
    const double phi = 65 * deg * (1 - w);
    INFO("w = " << w);
    CHECK_THAT(b->at(phi).lift, WithinRel(a->at(phi).lift, 1e-9));
    CHECK_THAT(b->at(phi).velocity, WithinRel(a->at(phi).velocity, 1e-9));
    CHECK_THAT(b->at(phi).acceleration, WithinRel(a->at(phi).acceleration, 1e-8));
    CHECK_THAT(b->at(phi).jerk, WithinRel(a->at(phi).jerk, 1e-7));
  }
  const RealPolydyneLaw direct(8e-3, 130 * deg, 17e-3, {2.0L, 14.0L, 26.0L, 38.0L, 50.0L});
  const long double zone = 2.0L / 50.0L;
  for (int m = 0; m <= 5; ++m) {
    INFO("derivative " << m);
    const long double below = direct.normalized_derivative(m, 1.0L - zone * (1 + 1e-12L));
    const long double above = direct.normalized_derivative(m, 1.0L - zone * (1 - 1e-12L));
    CHECK_THAT(static_cast<double>(below), WithinRel(static_cast<double>(above), 1e-9));
  }
  // No NaN at the nose, where u^2 differentiated three times vanishes.
  double d4 = 0, d5 = 0;
  CHECK(direct.higher_derivatives(0.0, d4, d5));
  CHECK(std::isfinite(d4));
  CHECK(std::isfinite(d5));
  CHECK(std::isfinite(direct.evaluate_in_event(0.0).jerk));
  // The phase asked for is the phase achieved (the node's own search of the law, a second method).
  for (double target : {14.0, 18.0, 25.0}) {
    INFO(target << " deg");
    const OutputSet out = cams::testing::run_cam("cam.polydyne", with({{"accel_angle", ParamValue::of_number(target * deg)}}));
    CHECK_THAT(out.all().at("accel_angle").as_scalar(), WithinRel(target * deg, 1e-9));
    // No negative lift, even right at the seat where the real-exponent terms cancel.
    const auto law = std::dynamic_pointer_cast<const CamLaw>(out.all().at("law").as_handle());
    for (double w : {1e-2, 1e-4, 1e-6, 1e-9}) CHECK(law->at(65 * deg * (1 - w)).lift >= 0.0);
  }
  // Out of reach: the achievable interval is named.
  try {
    cams::testing::run_cam("cam.polydyne", with({{"accel_angle", ParamValue::of_number(60 * deg)}}));
    FAIL("no error");
  } catch (const NodeError& e) {
    CHECK(e.parameter() == "accel_angle");
    CHECK_THAT(e.what(), Catch::Matchers::Contains("must lie in [") && Catch::Matchers::Contains("exponent_step"));
  }
}
