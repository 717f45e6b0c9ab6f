#include "polydyne.hpp"

#include <mechgraph/numerics/piecewise.hpp>

#include <boost/math/tools/roots.hpp>
#include <boost/multiprecision/cpp_int.hpp>

#include <cmath>
#include <cstring>
#include <map>
#include <mutex>
#include <memory>
#include <numbers>
#include <numeric>
#include <sstream>
#include <string>

namespace mechgraph::cams {
namespace {

using boost::multiprecision::cpp_int;

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
std::vector<cpp_int> divide_by_one_minus_u(const std::vector<cpp_int>& p) {
  std::vector<cpp_int> s(p.size() - 1);
  cpp_int sum = 0;
  for (std::size_t j = 0; j + 1 < p.size(); ++j) {
    sum += p[j];
    s[j] = sum;
  }
  sum += p.back();
  if (sum != 0) throw std::logic_error("polydyne: the polynomial does not vanish at u = 1");
  return s;
}

// value / scale in long double, as the fraction in lowest terms converts (numerator and
// denominator each rounded, then divided): the same bits as an exact rational would give.
long double reduced_ratio(const cpp_int& value, const cpp_int& scale) {
  if (value == 0) return 0.0L;
  const cpp_int g = gcd(value, scale);
  return static_cast<long double>(cpp_int(value / g)) / static_cast<long double>(cpp_int(scale / g));
}

}  // namespace

std::vector<int> validate_polydyne_exponents(const std::vector<double>& e) {
  // The message prefix only when a refusal is thrown (a sweep validates every design).
  const auto given = [&e] { return "exponents = " + list_text(e); };
  if (e.size() != 5) {
    throw NodeError("exponents", given() + ": give exactly five exponents 2, p, q, r, s (the five end conditions "
                                         "x = x' = x'' = x''' = x'''' = 0 fix five coefficients)");
  }
  std::vector<int> n;
  n.reserve(e.size());
  for (double v : e) {
    if (!(std::abs(v - std::round(v)) == 0.0) || !std::isfinite(v)) {
      throw NodeError("exponents", given() + ": every exponent must be an integer");
    }
    if (std::round(v) > kMaxExponent || std::round(v) < 0.0) {
      throw NodeError("exponents", given() + ": exponents must lie in [2, " + std::to_string(kMaxExponent) + "]");
    }
    n.push_back(static_cast<int>(std::round(v)));
  }
  if (n.front() != 2) throw NodeError("exponents", given() + ": the first exponent must be 2");
  for (std::size_t i = 0; i < n.size(); ++i) {
    if (n[i] % 2 != 0) {
      throw NodeError("exponents", given() + ": every exponent must be even (the lift is symmetric about the nose); " +
                                       std::to_string(n[i]) + " is odd");
    }
    if (i > 0 && n[i] <= n[i - 1]) throw NodeError("exponents", given() + ": exponents must increase strictly");
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

namespace {

// The factored derivatives q_0..q_5 of one exponent set, found in exact rationals. They depend on
// the exponents alone, so a sweep over lift, action angle or base radius finds them once: they are
// kept per exponent set (a small, bounded, thread-safe table; 0.2 ms saved per design).
std::shared_ptr<const PolydyneSeries> make_series(const std::vector<int>& exponents) {
  auto series = std::make_shared<PolydyneSeries>();
  series->exponents = exponents;
  const auto exact = polydyne_coefficients_exact(exponents);
  const int degree = exponents.back();
  // Exact arithmetic over integers: the polynomial times the least common multiple L of its
  // coefficients' denominators. Derivatives and divisions by (1 - u) keep integers (prefix sums),
  // and every sign is the rational's (L > 0); one gcd per coefficient at the end, instead of one
  // per rational operation.
  cpp_int scale = 1;
  for (const auto& [num, den] : exact) scale = lcm(scale, cpp_int(den));
  std::vector<cpp_int> p(static_cast<std::size_t>(degree) + 1, cpp_int(0));
  p[0] = scale;
  for (std::size_t i = 0; i < exponents.size(); ++i) {
    const auto [num, den] = exact[i];
    p[static_cast<std::size_t>(exponents[i])] = cpp_int(num) * (scale / den);
    // num and den are exact in double (< 2^53), so one division rounds correctly.
    series->coefficients.push_back(static_cast<double>(num) / static_cast<double>(den));
  }
  std::vector<cpp_int> derivative = p;
  for (int m = 0; m < 6; ++m) {
    if (m > 0) {  // d/du of sum c_k u^k
      std::vector<cpp_int> d(derivative.size() - 1);
      for (std::size_t k = 1; k < derivative.size(); ++k) d[k - 1] = derivative[k] * static_cast<long long>(k);
      derivative = std::move(d);
    }
    std::vector<cpp_int> q = derivative;
    for (int k = 0; k < 5 - m; ++k) q = divide_by_one_minus_u(q);
    // Sign structure that makes lift and velocity cancellation-free (and the lift monotonic).
    for (std::size_t k = 0; k < q.size(); ++k) {
      const bool ok = m == 0 ? q[k] > 0 : m == 1 ? (k == 0 ? q[k] == 0 : q[k] < 0) : true;
      if (!ok) {
        throw NodeError("exponents", "these exponents give a lift that does not fall monotonically from the nose");
      }
    }
    auto& target = series->q[static_cast<std::size_t>(m)];
    target.reserve(q.size());
    for (const cpp_int& v : q) target.push_back(reduced_ratio(v, scale));
  }
  // Where the first three derivatives of x change sign on (0, 1): the sign changes of q_1, q_2,
  // q_3 (the factor (1 - u)^(5-m) keeps its sign there), by the certified search
  // (numerics/piecewise.hpp) on each polynomial in long double, once per exponent set.
  for (std::size_t m = 1; m <= 3; ++m) {
    const std::vector<long double>& q = series->q[m];
    auto q_at = [&q](double u) {
      long double sum = 0.0L;
      for (std::size_t k = q.size(); k-- > 0;) sum = sum * u + q[k];
      return static_cast<double>(sum);
    };
    const double ends[2] = {0.0, 1.0};
    long search_evaluations = 0;
    series->sign_changes[m] = numerics::all_sign_changes(q_at, ends, 16, search_evaluations);
    // A sign change at u = 0 is the nose, a cut anyway.
    std::erase_if(series->sign_changes[m], [](double u) { return !(u > 0.0 && u < 1.0); });
  }
  // The primitives of x and x^2 from the nose (u = 0) as dense polynomials in u (valvetrain.md,
  // stage 3 in closed form): int_0^U x = sum_i C_i U^(n_i+1) / (n_i+1), int_0^U x^2 =
  // sum_ij C_i C_j U^(n_i+n_j+1) / (n_i+n_j+1), with C_0 = 1, n_0 = 0; from the exact fractions.
  {
    std::vector<long double> c{1.0L};
    std::vector<int> n{0};
    for (std::size_t i = 0; i < exponents.size(); ++i) {
      c.push_back(static_cast<long double>(exact[i].first) / static_cast<long double>(exact[i].second));
      n.push_back(exponents[i]);
    }
    series->lift_primitive.assign(static_cast<std::size_t>(degree) + 2, 0.0L);
    series->square_primitive.assign(2 * static_cast<std::size_t>(degree) + 2, 0.0L);
    for (std::size_t i = 0; i < c.size(); ++i) {
      series->lift_primitive[static_cast<std::size_t>(n[i]) + 1] += c[i] / (n[i] + 1);
      for (std::size_t j = 0; j < c.size(); ++j)
        series->square_primitive[static_cast<std::size_t>(n[i] + n[j]) + 1] += c[i] * c[j] / (n[i] + n[j] + 1);
    }
  }
  series->lift_primitive_sparse = SparsePolynomial(series->lift_primitive);
  series->square_primitive_sparse = SparsePolynomial(series->square_primitive);
  // q_0..q_3 all have degree n_max - 5: one table, four coefficients per power.
  series->interleaved.resize(series->q[0].size());
  for (std::size_t m = 0; m < 4; ++m)
    for (std::size_t k = 0; k < series->q[m].size(); ++k) series->interleaved[k][m] = static_cast<double>(series->q[m][k]);
  return series;
}

std::shared_ptr<const PolydyneSeries> series_for(const std::vector<int>& exponents) {
  static std::mutex mutex;
  static std::map<std::vector<int>, std::shared_ptr<const PolydyneSeries>> known;
  {
    std::lock_guard lock(mutex);
    if (auto it = known.find(exponents); it != known.end()) return it->second;
  }
  auto series = make_series(exponents);  // outside the lock: a refusal throws, and others need not wait
  std::lock_guard lock(mutex);
  if (known.size() >= 256) known.clear();  // a bound; sweeps use a handful of exponent sets
  known.emplace(exponents, series);
  return series;
}

}  // namespace

std::shared_ptr<const PolydyneSeries> polydyne_series(const std::vector<int>& exponents) { return series_for(exponents); }

PolydyneLaw::PolydyneLaw(double max_lift, double action_angle, double base_radius, std::vector<int> exponents)
    : PolydyneLaw(max_lift, action_angle, base_radius, series_for(exponents)) {}

PolydyneLaw::PolydyneLaw(double max_lift, double action_angle, double base_radius, std::shared_ptr<const PolydyneSeries> series)
    : max_lift_(max_lift), half_action_(0.5 * action_angle), base_radius_(base_radius), series_(std::move(series)) {}

SparsePolynomial::SparsePolynomial(const std::vector<long double>& dense) {
  int previous = -1;
  for (std::size_t k = dense.size(); k-- > 0;) {
    if (dense[k] == 0.0L) continue;
    if (previous >= 0) terms_.back().gap = gap_index(previous - static_cast<int>(k));
    terms_.push_back({dense[k], 0});
    previous = static_cast<int>(k);
  }
  if (previous >= 0) terms_.back().gap = gap_index(previous);
}

std::size_t SparsePolynomial::gap_index(int gap) {
  for (std::size_t i = 0; i < gaps_.size(); ++i)
    if (gaps_[i] == gap) return i;
  gaps_.push_back(gap);
  return gaps_.size() - 1;
}

long double SparsePolynomial::operator()(long double u) const {
  // p(u) = (((c_1 u^g_1 + c_2) u^g_2 + c_3) ... ) u^g_last, with c_1 the highest power's.
  constexpr std::size_t few = 8;
  long double on_stack[few];
  std::vector<long double> more;
  long double* power = gaps_.size() <= few ? on_stack : (more.resize(gaps_.size()), more.data());
  for (std::size_t i = 0; i < gaps_.size(); ++i) {
    long double p = 1.0L, base = u;  // u^gap by squaring
    for (int e = gaps_[i]; e > 0; e >>= 1, base *= base)
      if (e & 1) p *= base;
    power[i] = p;
  }
  long double sum = 0.0L;
  for (const Term& t : terms_) sum = (sum + t.coefficient) * power[t.gap];
  return sum;
}

bool PolydyneLaw::lift_integrals(double a, double b, double& integral, double& integral_of_square) const {
  // h = H x(|phi| / phi_p): the primitives S(phi) = sign(phi) phi_p F(|phi| / phi_p) with the
  // polynomial primitives F of x and x^2 (from the nose, so no cancellation near the seat), by
  // their nonzero terms.
  const long double phi_p = half_action_, H = max_lift_;
  auto S = [&](double phi, const SparsePolynomial& p) {
    const long double u = std::min<long double>(std::abs(static_cast<long double>(phi)) / phi_p, 1.0L);
    return (phi < 0.0 ? -1.0L : 1.0L) * phi_p * p(u);
  };
  integral = static_cast<double>(H * (S(b, series_->lift_primitive_sparse) - S(a, series_->lift_primitive_sparse)));
  integral_of_square =
      static_cast<double>(H * H * (S(b, series_->square_primitive_sparse) - S(a, series_->square_primitive_sparse)));
  return true;
}

bool PolydyneLaw::monotone_breaks(int order, std::vector<double>& breaks) const {
  if (order < 0 || order > 2) return false;
  // h^(order) is monotone between the sign changes of h^(order+1) = (h / phi_p^m) x^(m)(|phi| / phi_p)
  // (mirrored, with the sign of phi for odd m): those of q_m at u = |phi| / phi_p, and the nose.
  const std::vector<double>& u = series_->sign_changes[static_cast<std::size_t>(order + 1)];
  breaks.clear();
  for (auto it = u.rbegin(); it != u.rend(); ++it) breaks.push_back(-*it * half_action_);
  breaks.push_back(0.0);
  for (double v : u) breaks.push_back(v * half_action_);
  return true;
}

long double PolydyneLaw::normalized_derivative(int m, long double w) const {
  const std::vector<long double>& q = series_->q[static_cast<std::size_t>(m)];
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

namespace {

// q_0..q_3 at u by split Horner, the four as the lanes of one vector (GCC vector extensions: two
// SSE2 operations per step on any x86-64, one AVX operation where the processor has it; NEON on
// ARM): q(u) = E(u^2) + u O(u^2) with E and O the even and odd coefficients, two independent
// chains of n/2 steps instead of one of n (a degree-45 chain is latency, not arithmetic). For q_0
// (positive coefficients) and q_1 (negative) both halves keep one sign, so the lift and velocity
// stay free of cancellation. On x86-64 a second version for processors with AVX2 and FMA is
// chosen at load time; it rounds each step once (fused multiply-add) instead of twice.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
__attribute__((target_clones("arch=x86-64-v3", "default")))
#endif
void horner4(const std::array<double, 4>* c, std::size_t n, double u, double* s) {
  typedef double lanes __attribute__((vector_size(32)));
  const double v = u * u;
  const lanes uu = {u, u, u, u}, vv = {v, v, v, v};
  lanes even = {0.0, 0.0, 0.0, 0.0}, odd = {0.0, 0.0, 0.0, 0.0};
  std::size_t top = n;
  if (n % 2 == 1) {  // the highest power is even: the even chain starts with it
    std::memcpy(&even, c[n - 1].data(), sizeof even);
    top = n - 1;
  }
  for (std::size_t k = top; k >= 2; k -= 2) {
    lanes ce, co;
    std::memcpy(&ce, c[k - 2].data(), sizeof ce);
    std::memcpy(&co, c[k - 1].data(), sizeof co);
    even = even * vv + ce;
    odd = odd * vv + co;
  }
  const lanes acc = even + uu * odd;
  std::memcpy(s, &acc, sizeof acc);
}

}  // namespace

LiftDerivatives PolydyneLaw::evaluate_in_event(double phi) const {
  // x^(m) = h (1 - u)^(5-m) q_m(u) / phi_p^m, the four q_m by Horner in one pass in double: q_0
  // has only positive and q_1 only negative coefficients, so lift and velocity carry a relative
  // error of a few times n_max * eps on the whole event, seat included (checked against a
  // 100-digit reference in tests/plugins/cams/polydyne_test.cpp).
  const double phi_p = half_action_;
  const double w = (phi_p - std::abs(phi)) / phi_p;  // 1 - u; phi_p - |phi| is exact near the seat
  const double u = 1.0 - w;
  const double sign = phi < 0.0 ? -1.0 : 1.0;  // x is even in u: odd derivatives change sign
  double s[4];
  horner4(series_->interleaved.data(), series_->interleaved.size(), u, s);
  const double w2 = w * w, w3 = w2 * w, h = max_lift_;
  return {h * (w3 * w2) * s[0], sign * h * (w2 * w2) * s[1] / phi_p, h * w3 * s[2] / (phi_p * phi_p),
          sign * h * w2 * s[3] / (phi_p * phi_p * phi_p)};
}

RealPolydyneLaw::RealPolydyneLaw(double max_lift, double action_angle, double base_radius, std::vector<long double> exponents)
    : max_lift_(max_lift), half_action_(0.5 * action_angle), base_radius_(base_radius) {
  exponents_.push_back(0.0L);
  for (long double n : exponents) exponents_.push_back(n);
  // C_i = w_i / w_0, w_i = 1 / prod_{j != i} (n_i - n_j): the 5th divided-difference weights.
  auto weight = [&](std::size_t i) {
    long double w = 1.0L;
    for (std::size_t j = 0; j < exponents_.size(); ++j)
      if (j != i) w *= exponents_[i] - exponents_[j];
    return 1.0L / w;
  };
  const long double w0 = weight(0);
  for (std::size_t i = 0; i < exponents_.size(); ++i) coefficients_.push_back(weight(i) / w0);
  // The series about the seat: u^n = (1 - w)^n = sum_k binom(n, k) (-w)^k. With n w <= 2 its terms
  // fall as 2^k / k!: 48 terms reach far below rounding.
  constexpr int terms = 48;
  seat_series_.assign(terms + 1, 0.0L);
  for (std::size_t i = 1; i < exponents_.size(); ++i) {
    long double binomial = 1.0L;  // binom(n, k)
    for (int k = 1; k <= terms; ++k) {
      binomial *= (exponents_[i] - (k - 1)) / k;
      if (k >= 5) seat_series_[static_cast<std::size_t>(k)] += coefficients_[i] * binomial;
    }
  }
  seat_zone_ = std::min(0.1L, 2.0L / exponents_.back());
}

void RealPolydyneLaw::normalized_derivatives(long double u, int m_max, long double* d) const {
  const long double w = 1.0L - u;
  for (int m = 0; m <= m_max; ++m) d[m] = 0.0L;
  if (w < seat_zone_) {
    // d^m/du^m = (-1)^m d^m/dw^m of sum_{k>=5} a_k (-1)^k w^k, each by Horner in w.
    const int top = static_cast<int>(seat_series_.size()) - 1;
    for (int m = 0; m <= m_max; ++m) {
      const int low = std::max(5, m);
      long double sum = 0.0L;
      for (int k = top; k >= low; --k) {
        long double falling = 1.0L;
        for (int j = 0; j < m; ++j) falling *= static_cast<long double>(k - j);
        sum = sum * w + (k % 2 == 0 ? 1.0L : -1.0L) * seat_series_[static_cast<std::size_t>(k)] * falling;
      }
      for (int k = m; k < low; ++k) sum *= w;  // w^(low - m)
      d[m] = m % 2 == 0 ? sum : -sum;
    }
    return;
  }
  d[0] = 1.0L;
  for (std::size_t i = 1; i < exponents_.size(); ++i) {
    const long double n = exponents_[i];
    // One power per term: u^(n - m) = u^(n - m_max) u^(m_max - m); the exponent 2 (n < m_max) by hand.
    const bool integer_two = n < static_cast<long double>(m_max);
    const long double base = integer_two ? 0.0L : std::pow(u, n - m_max);
    long double up = 1.0L;  // u^(m_max - m), built from m = m_max down
    for (int m = m_max; m >= 0; --m) {
      long double falling = 1.0L;
      for (int k = 0; k < m; ++k) falling *= n - k;
      if (falling != 0.0L) {
        const long double power = integer_two ? (n - m == 0.0L ? 1.0L : std::pow(u, n - m)) : base * up;
        d[m] += coefficients_[i] * falling * power;
      }
      up *= u;
    }
  }
}

long double RealPolydyneLaw::normalized_derivative(int m, long double u) const {
  long double d[6];
  normalized_derivatives(u, m, d);
  return d[m];
}

LiftDerivatives RealPolydyneLaw::evaluate_in_event(double phi) const {
  const long double phi_p = half_action_;
  const long double u = std::min(1.0L, std::abs(static_cast<long double>(phi)) / phi_p);
  const double sign = phi < 0.0 ? -1.0 : 1.0;  // x is even in phi: odd derivatives change sign
  const long double h = max_lift_;
  long double d[4];
  normalized_derivatives(u, 3, d);
  return {std::max(0.0, static_cast<double>(h * d[0])), sign * static_cast<double>(h * d[1] / phi_p),
          static_cast<double>(h * d[2] / (phi_p * phi_p)), sign * static_cast<double>(h * d[3] / (phi_p * phi_p * phi_p))};
}

bool RealPolydyneLaw::higher_derivatives(double phi, double& d4, double& d5) const {
  const long double phi_p = half_action_;
  const long double u = std::min(1.0L, std::abs(static_cast<long double>(phi)) / phi_p);
  const long double scale4 = max_lift_ / (phi_p * phi_p * phi_p * phi_p);
  long double d[6];
  normalized_derivatives(u, 5, d);
  d4 = static_cast<double>(scale4 * d[4]);
  d5 = (phi < 0.0 ? -1.0 : 1.0) * static_cast<double>(scale4 / phi_p * d[5]);
  return true;
}

double polydyne_accel_angle(double q, double step, double action_angle) {
  const RealPolydyneLaw law(1.0, action_angle, 1.0, {2.0L, q, q + step, q + 2 * step, q + 3 * step});
  // x'' < 0 at the nose, > 0 near the seat (as (1 - u)^3): one sign change in between.
  auto acc = [&](double u) { return static_cast<double>(law.normalized_derivative(2, u)); };
  boost::uintmax_t iterations = 200;
  const auto r = boost::math::tools::toms748_solve(acc, 0.0, 1.0 - 1e-3, boost::math::tools::eps_tolerance<double>(52), iterations);
  return 0.5 * action_angle * (1.0 - 0.5 * (r.first + r.second));
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
      ParamSpec::number("accel_angle", dim::angle,
                        "positive-acceleration phase from the start of lift: solves for a real q in the exponents "
                        "[2, q, q+s, q+2s, q+3s] (s = exponent_step); exponents is then not used",
                        "deg")
          .optional()
          .at_least(polydyne_accel_angle(polydyne_q_max(1.0), 1.0, min_action_angle))
          .because(">= the narrowest phase the exponents reach (q + 3 s up to 1000, s = 1) at the smallest action angle, 0.1 deg"),
      ParamSpec::number("exponent_step", dim::none, "s, the spacing of the exponents found for accel_angle")
          .with_default(8.0)
          .at_least(1.0)
          .at_most(100.0)
          .because("1 to 100: exponents at least 1 apart, and q + 3 s within the family's 1000"),
      ParamSpec::number_list("exponents", dim::none,
                             "the exponents 2, p, q, r, s: five even integers, the first 2, strictly increasing, "
                             "at most 1000; they set the positive-acceleration phase (higher exponents: shorter, "
                             "sharper opening)")
          .with_default(std::vector<double>{2.0, 6.0, 10.0, 14.0, 18.0}),
  };
  d.extra_outputs = {PortSpec::scalar("exponent_q", dim::none, "the second exponent (q; found for accel_angle)")};
  d.make = [](const CamBasics& basics, const ParamSet& params, OutputSet& extra) -> std::shared_ptr<const CamLaw> {
    if (params.has("accel_angle")) {
      // phi_y falls as q grows; q from 5 (derivatives to the 5th stay finite at the nose, as cam
      // synthesis needs) to 1000 - 3s.
      const double s = params.number("exponent_step"), target = params.number("accel_angle");
      const double q_low = 5.0, q_high = polydyne_q_max(s);
      auto phase = [&](double q) { return polydyne_accel_angle(q, s, basics.action_angle); };
      const double widest = phase(q_low), narrowest = phase(q_high);
      if (!(target <= widest && target >= narrowest)) {
        std::ostringstream msg;
        msg.precision(6);
        msg << "accel_angle " << target * 180.0 / std::numbers::pi << " deg is out of reach of the exponents [2, q, q+"
            << s << ", ...] for this action angle: it must lie in [" << narrowest * 180.0 / std::numbers::pi << ", "
            << widest * 180.0 / std::numbers::pi << "] deg (change exponent_step to move the interval)";
        throw NodeError("accel_angle", msg.str());
      }
      boost::uintmax_t iterations = 200;
      const auto r = boost::math::tools::toms748_solve([&](double q) { return phase(q) - target; }, q_low, q_high,
                                                       boost::math::tools::eps_tolerance<double>(50), iterations);
      const double q = 0.5 * (r.first + r.second);
      extra.set_scalar("exponent_q", q);
      return std::make_shared<const RealPolydyneLaw>(basics.max_lift, basics.action_angle, basics.base_radius,
                                                     std::vector<long double>{2.0L, q, q + s, q + 2 * s, q + 3 * s});
    }
    std::vector<int> exponents = validate_polydyne_exponents(params.numbers("exponents"));
    extra.set_scalar("exponent_q", exponents[1]);
    return std::make_shared<const PolydyneLaw>(basics.max_lift, basics.action_angle, basics.base_radius,
                                               std::move(exponents));
  };
  // A block: the exponents (a list, never varied in a block) checked and their series found once;
  // each case is then its lift, action angle and base radius. With accel_angle q is found per case.
  d.prepare_block = [](const BlockParams& p) -> CamLawCaseFactory {
    if (p.fixed().has("accel_angle")) return {};
    const std::vector<int> exponents = validate_polydyne_exponents(p.fixed().numbers("exponents"));
    const double q = exponents[1];
    return [series = polydyne_series(exponents), q](const CamBasics& basics, const ParamSet&, std::size_t,
                                                     OutputSet& extra) -> std::shared_ptr<const CamLaw> {
      extra.set_scalar("exponent_q", q);
      return std::make_shared<const PolydyneLaw>(basics.max_lift, basics.action_angle, basics.base_radius, series);
    };
  };
  return d;
}

}  // namespace mechgraph::cams
