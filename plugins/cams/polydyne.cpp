#include "polydyne.hpp"

#include <boost/multiprecision/cpp_int.hpp>

#include <cmath>
#include <memory>
#include <numeric>
#include <sstream>
#include <string>

namespace mechgraph::cams {
namespace {

using boost::multiprecision::cpp_int;
using boost::multiprecision::cpp_rational;

constexpr int kMaxExponent = 1000;  // keeps every product of four exponents (< 1e12) exact in int64

std::string list_text(const std::vector<double>& v) {
  std::ostringstream s;
  s << "[";
  for (std::size_t i = 0; i < v.size(); ++i) s << (i ? ", " : "") << v[i];
  s << "]";
  return s.str();
}

// Divides the polynomial p (monomial coefficients, ascending) by (1 - u): with p = (1 - u) s,
// p_j = s_j - s_{j-1}, so s_j = p_0 + ... + p_j; the remainder p(1) must vanish.
std::vector<cpp_rational> divide_by_one_minus_u(const std::vector<cpp_rational>& p) {
  std::vector<cpp_rational> s(p.size() - 1);
  cpp_rational sum = 0;
  for (std::size_t j = 0; j + 1 < p.size(); ++j) {
    sum += p[j];
    s[j] = sum;
  }
  sum += p.back();
  if (sum != 0) throw std::logic_error("polydyne: the polynomial does not vanish at u = 1");
  return s;
}

}  // namespace

std::vector<int> validate_polydyne_exponents(const std::vector<double>& e) {
  const std::string given = "exponents = " + list_text(e);
  if (e.size() != 5) {
    throw NodeError("exponents", given + ": give exactly five exponents 2, p, q, r, s (the five end conditions "
                                         "x = x' = x'' = x''' = x'''' = 0 fix five coefficients)");
  }
  std::vector<int> n;
  for (double v : e) {
    if (!(std::abs(v - std::round(v)) == 0.0) || !std::isfinite(v)) {
      throw NodeError("exponents", given + ": every exponent must be an integer");
    }
    if (std::round(v) > kMaxExponent || std::round(v) < 0.0) {
      throw NodeError("exponents", given + ": exponents must lie in [2, " + std::to_string(kMaxExponent) + "]");
    }
    n.push_back(static_cast<int>(std::round(v)));
  }
  if (n.front() != 2) throw NodeError("exponents", given + ": the first exponent must be 2");
  for (std::size_t i = 0; i < n.size(); ++i) {
    if (n[i] % 2 != 0) {
      throw NodeError("exponents", given + ": every exponent must be even (the lift is symmetric about the nose); " +
                                       std::to_string(n[i]) + " is odd");
    }
    if (i > 0 && n[i] <= n[i - 1]) throw NodeError("exponents", given + ": exponents must increase strictly");
  }
  return n;
}

std::vector<std::pair<std::int64_t, std::int64_t>> polydyne_coefficients_exact(const std::vector<int>& n) {
  // C_i = - prod_{j != i} n_j / prod_{j != i} (n_i - n_j): the 5th divided-difference weights.
  std::vector<std::pair<std::int64_t, std::int64_t>> c;
  for (std::size_t i = 0; i < n.size(); ++i) {
    std::int64_t num = -1, den = 1;
    for (std::size_t j = 0; j < n.size(); ++j) {
      if (j == i) continue;
      num *= n[j];
      den *= n[i] - n[j];
    }
    if (den < 0) {
      num = -num;
      den = -den;
    }
    const std::int64_t g = std::gcd(num, den);
    c.emplace_back(num / g, den / g);
  }
  return c;
}

PolydyneLaw::PolydyneLaw(double max_lift, double action_angle, double base_radius, std::vector<int> exponents)
    : max_lift_(max_lift), half_action_(0.5 * action_angle), base_radius_(base_radius), exponents_(std::move(exponents)) {
  const auto exact = polydyne_coefficients_exact(exponents_);
  const int degree = exponents_.back();
  std::vector<cpp_rational> p(static_cast<std::size_t>(degree) + 1, cpp_rational(0));
  p[0] = 1;
  for (std::size_t i = 0; i < exponents_.size(); ++i) {
    const auto [num, den] = exact[i];
    p[static_cast<std::size_t>(exponents_[i])] = cpp_rational(cpp_int(num), cpp_int(den));
    // num and den are exact in double (< 2^53), so one division rounds correctly.
    coefficients_.push_back(static_cast<double>(num) / static_cast<double>(den));
  }
  std::vector<cpp_rational> derivative = p;
  for (int m = 0; m < 6; ++m) {
    if (m > 0) {  // d/du of sum c_k u^k
      std::vector<cpp_rational> d(derivative.size() - 1);
      for (std::size_t k = 1; k < derivative.size(); ++k) d[k - 1] = derivative[k] * static_cast<long long>(k);
      derivative = std::move(d);
    }
    std::vector<cpp_rational> q = derivative;
    for (int k = 0; k < 5 - m; ++k) q = divide_by_one_minus_u(q);
    // Sign structure that makes lift and velocity cancellation-free (and the lift monotonic).
    for (std::size_t k = 0; k < q.size(); ++k) {
      const bool ok = m == 0 ? q[k] > 0 : m == 1 ? (k == 0 ? q[k] == 0 : q[k] < 0) : true;
      if (!ok) {
        throw NodeError("exponents", "these exponents give a lift that does not fall monotonically from the nose");
      }
    }
    q_[static_cast<std::size_t>(m)].reserve(q.size());
    for (const cpp_rational& r : q) {
      const long double value = static_cast<long double>(numerator(r)) / static_cast<long double>(denominator(r));
      q_[static_cast<std::size_t>(m)].push_back(value);
    }
  }
}

long double PolydyneLaw::normalized_derivative(int m, long double w) const {
  const std::vector<long double>& q = q_[static_cast<std::size_t>(m)];
  const long double u = 1.0L - w;
  long double sum = 0.0L;
  for (std::size_t k = q.size(); k-- > 0;) sum = sum * u + q[k];
  long double factor = 1.0L;
  for (int k = 0; k < 5 - m; ++k) factor *= w;
  return factor * sum;
}

bool PolydyneLaw::higher_derivatives(double phi, double& d4, double& d5) const {
  const long double phi_p = half_action_;
  const long double w = (phi_p - std::abs(static_cast<long double>(phi))) / phi_p;
  const long double h = max_lift_;
  const long double scale4 = h / (phi_p * phi_p * phi_p * phi_p);
  d4 = static_cast<double>(scale4 * normalized_derivative(4, w));  // even in phi
  d5 = (phi < 0.0 ? -1.0 : 1.0) * static_cast<double>(scale4 / phi_p * normalized_derivative(5, w));
  return true;
}

LiftDerivatives PolydyneLaw::evaluate_in_event(double phi) const {
  const long double psi = std::abs(phi);
  const long double phi_p = half_action_;
  const long double w = (phi_p - psi) / phi_p;  // 1 - u, the subtraction exact near the seat
  const double sign = phi < 0.0 ? -1.0 : 1.0;  // x is even in u: odd derivatives change sign
  const long double h = max_lift_;
  const long double x0 = normalized_derivative(0, w);
  const long double x1 = normalized_derivative(1, w);
  const long double x2 = normalized_derivative(2, w);
  const long double x3 = normalized_derivative(3, w);
  // d/dphi = (1/phi_p) d/du
  return {static_cast<double>(h * x0), sign * static_cast<double>(h * x1 / phi_p),
          static_cast<double>(h * x2 / (phi_p * phi_p)), sign * static_cast<double>(h * x3 / (phi_p * phi_p * phi_p))};
}

CamLawDefinition polydyne_definition() {
  CamLawDefinition d;
  d.type = "cam.polydyne";
  d.version = 1;
  d.summary =
      "Polydyne valve polynomial x = h [1 + C2 u^2 + Cp u^p + Cq u^q + Cr u^r + Cs u^s], u from the nose, "
      "derivatives up to the 4th zero at the seat; exact rational coefficients (the kinematic polynomial: "
      "synthesising the cam against the drive elasticity is a separate step)";
  d.params = {
      ParamSpec::number_list("exponents", dim::none,
                             "the exponents 2, p, q, r, s: five even integers, the first 2, strictly increasing, "
                             "at most 1000; they set the positive-acceleration phase (higher exponents: shorter, "
                             "sharper opening)")
          .with_default(std::vector<double>{2.0, 6.0, 10.0, 14.0, 18.0}),
  };
  d.make = [](const CamBasics& basics, const ParamSet& params, OutputSet&) -> std::shared_ptr<const CamLaw> {
    std::vector<int> exponents = validate_polydyne_exponents(params.numbers("exponents"));
    return std::make_shared<const PolydyneLaw>(basics.max_lift, basics.action_angle, basics.base_radius,
                                               std::move(exponents));
  };
  return d;
}

}  // namespace mechgraph::cams
