#include "shockless.hpp"

#include <mechgraph/printf_number.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace mechgraph::cams {
namespace {

constexpr double pi = std::numbers::pi;
constexpr double two_over_pi = 2.0 / std::numbers::pi;

// 1 - cos x = 2 sin^2(x/2), without cancellation near 0.
double one_minus_cos(double x) {
  const double s = std::sin(0.5 * x);
  return 2.0 * s * s;
}

// x - sin x, by its series below 1 (where the subtraction would lose digits), directly above
// (sin x given when the caller has it).
double x_minus_sin(double x, double sin_x) {
  if (std::abs(x) >= 1.0) return x - sin_x;
  const double x2 = x * x;
  double term = x * x2 / 6.0;  // x^3/3!
  double sum = term;
  for (int k = 2; k < 12; ++k) {  // next term: -x^(2k+1)/(2k+1)!
    term *= -x2 / ((2.0 * k) * (2.0 * k + 1.0));
    sum += term;
    if (std::abs(term) < 1e-18 * std::abs(sum)) break;
  }
  return sum;
}

}  // namespace

const ShapeEnds& AccelShape::make_ends() const {
  std::call_once(ends_once_, [this] {
    ends_ = {value(0.0), value(1.0), slope(1.0), integral(1.0), integral2(1.0)};
    ends_.has_moments = moments(1.0, ends_.i3, ends_.j1, ends_.j2);
    ends_ready_.store(true, std::memory_order_release);
  });
  return ends_;
}

// Quarter sine, theta = pi tau / 2: a = sin theta, I1 = (2/pi)(1 - cos theta),
// I2 = (2/pi)^2 (theta - sin theta).
double QuarterSineRise::value(double tau) const { return std::sin(0.5 * pi * tau); }
double QuarterSineRise::slope(double tau) const { return 0.5 * pi * std::cos(0.5 * pi * tau); }
double QuarterSineRise::integral(double tau) const { return two_over_pi * one_minus_cos(0.5 * pi * tau); }
double QuarterSineRise::integral2(double tau) const {
  const double theta = 0.5 * pi * tau;
  return two_over_pi * two_over_pi * x_minus_sin(theta, std::abs(theta) >= 1.0 ? std::sin(theta) : 0.0);
}
// One sine and cosine for all four: on theta in [0, pi/2], 1 - cos = sin^2 / (1 + cos) has no
// cancellation (1 + cos >= 1).
ShapeValues QuarterSineRise::all(double tau) const {
  const double theta = 0.5 * pi * tau;
  double s, c;
  ::sincos(theta, &s, &c);
  return {s, 0.5 * pi * c, two_over_pi * s * s / (1.0 + c), two_over_pi * two_over_pi * x_minus_sin(theta, s)};
}

// Quarter cosine: a = cos theta, I1 = (2/pi) sin theta, I2 = (2/pi)^2 (1 - cos theta).
double QuarterCosineFall::value(double tau) const { return std::cos(0.5 * pi * tau); }
double QuarterCosineFall::slope(double tau) const { return -0.5 * pi * std::sin(0.5 * pi * tau); }
double QuarterCosineFall::integral(double tau) const { return two_over_pi * std::sin(0.5 * pi * tau); }
double QuarterCosineFall::integral2(double tau) const {
  return two_over_pi * two_over_pi * one_minus_cos(0.5 * pi * tau);
}
ShapeValues QuarterCosineFall::all(double tau) const {
  double s, c;
  ::sincos(0.5 * pi * tau, &s, &c);
  return {c, -0.5 * pi * s, two_over_pi * s, two_over_pi * two_over_pi * s * s / (1.0 + c)};
}

// Parabola a = tau (2 - tau): I1 = tau^2 (1 - tau/3), I2 = tau^3 (4 - tau) / 12.
double ParabolaToVertex::value(double tau) const { return tau * (2.0 - tau); }
double ParabolaToVertex::slope(double tau) const { return 2.0 * (1.0 - tau); }
double ParabolaToVertex::integral(double tau) const { return tau * tau * (1.0 - tau / 3.0); }
double ParabolaToVertex::integral2(double tau) const { return tau * tau * tau * (4.0 - tau) / 12.0; }
ShapeValues ParabolaToVertex::all(double tau) const {
  return {ParabolaToVertex::value(tau), ParabolaToVertex::slope(tau), ParabolaToVertex::integral(tau),
          ParabolaToVertex::integral2(tau)};
}

// Moments for the closed-form integrals of h and h^2 (ShocklessLaw::lift_integrals):
// I3 = int_0^tau I2, J1 = int_0^tau t I2(t) dt, J2 = int_0^tau I2(t)^2 dt. With k = pi/2, theta = k tau:
//   quarter sine   (I2 = (theta - sin theta)/k^2):  I3 = (theta^2/2 - (1 - cos theta))/k^3,
//                  J1 = (theta^3/3 - sin theta + theta cos theta)/k^4,
//                  J2 = (theta^3/3 - 2 (sin theta - theta cos theta) + theta/2 - sin(2 theta)/4)/k^5;
//   quarter cosine (I2 = (1 - cos theta)/k^2):       I3 = (theta - sin theta)/k^3,
//                  J1 = (theta^2/2 - (cos theta + theta sin theta - 1))/k^4,
//                  J2 = (3 theta/2 - 2 sin theta + sin(2 theta)/4)/k^5;
//   parabola       (I2 = tau^3/3 - tau^4/12):         I3 = tau^4/12 - tau^5/60, J1 = tau^5/15 - tau^6/72,
//                  J2 = tau^7/63 - tau^8/144 + tau^9/1296.
// The trigonometric forms cancel for small theta, but only within terms of the size of the lift
// (every term of h is O(h_max)), so their absolute error stays at rounding of the whole integral.
bool QuarterSineRise::moments(double tau, double& i3, double& j1, double& j2) const {
  const double k = 0.5 * pi, t = k * tau;
  double s, c;
  ::sincos(t, &s, &c);
  const double k3 = k * k * k;
  i3 = (0.5 * t * t - one_minus_cos(t)) / k3;
  j1 = (t * t * t / 3.0 - s + t * c) / (k3 * k);
  j2 = (t * t * t / 3.0 - 2.0 * (s - t * c) + 0.5 * t - 0.25 * std::sin(2.0 * t)) / (k3 * k * k);
  return true;
}
bool QuarterCosineFall::moments(double tau, double& i3, double& j1, double& j2) const {
  const double k = 0.5 * pi, t = k * tau;
  double s, c;
  ::sincos(t, &s, &c);
  const double k3 = k * k * k;
  i3 = x_minus_sin(t, s) / k3;
  j1 = (0.5 * t * t - (c + t * s - 1.0)) / (k3 * k);
  j2 = (1.5 * t - 2.0 * s + 0.25 * std::sin(2.0 * t)) / (k3 * k * k);
  return true;
}
bool ParabolaToVertex::moments(double tau, double& i3, double& j1, double& j2) const {
  const double t2 = tau * tau, t4 = t2 * t2;
  i3 = t4 * (1.0 / 12.0 - tau / 60.0);
  j1 = t4 * tau * (1.0 / 15.0 - tau / 72.0);
  j2 = t4 * t2 * tau * (1.0 / 63.0 - tau / 144.0 + t2 / 1296.0);
  return true;
}

bool ShocklessLaw::lift_integrals(double a, double b, double& integral, double& integral_of_square) const {
  // Per piece, from its start over y = L tau (h = h_k + v_k y + A L^2 I2(tau)):
  //   F1 = L [h_k tau + v_k L tau^2/2 + A L^2 I3],
  //   F2 = L [h_k^2 tau + h_k v_k L tau^2 + v_k^2 L^2 tau^3/3 + 2 h_k A L^2 I3 + 2 v_k A L^3 J1 + A^2 L^4 J2];
  // G(x) sums them from the start of lift to x; P(phi) = G(phi_p + phi) before the nose and
  // 2 G(phi_p) - G(phi_p - phi) after it (the law is symmetric); the answer is P(b) - P(a).
  // A piece wholly inside [0, x] (tau = 1: every piece before x's) takes its shape's kept moments.
  auto piece_integrals = [](const Piece& p, double tau, double& f1, double& f2) {
    double i3, j1, j2;
    if (tau == 1.0) {
      const ShapeEnds& e = p.shape->ends();
      if (!e.has_moments) return false;
      i3 = e.i3, j1 = e.j1, j2 = e.j2;
    } else if (!p.shape->moments(tau, i3, j1, j2)) {
      return false;
    }
    const double L = p.length, A = p.amplitude, h = p.lift0, v = p.velocity0;
    f1 = L * (h * tau + 0.5 * v * L * tau * tau + A * L * L * i3);
    f2 = L * (h * h * tau + h * v * L * tau * tau + v * v * L * L * tau * tau * tau / 3.0 + 2.0 * h * A * L * L * i3 +
              2.0 * v * A * L * L * L * j1 + A * A * L * L * L * L * j2);
    return true;
  };
  auto G = [&](double x, double& g1, double& g2) {
    g1 = g2 = 0.0;
    for (const Piece& p : pieces_) {
      const double tau = std::clamp((x - p.start) / p.length, 0.0, 1.0);
      if (tau <= 0.0) break;
      double f1, f2;
      if (!piece_integrals(p, tau, f1, f2)) return false;
      g1 += f1;
      g2 += f2;
    }
    return true;
  };
  double half1, half2;
  if (!G(half_action_, half1, half2)) return false;
  auto P = [&](double phi, double& p1, double& p2) {
    phi = std::clamp(phi, -half_action_, half_action_);
    if (phi <= 0.0) return G(half_action_ + phi, p1, p2);
    double g1, g2;
    const bool ok = G(half_action_ - phi, g1, g2);
    p1 = 2.0 * half1 - g1;
    p2 = 2.0 * half2 - g2;
    return ok;
  };
  double a1, a2, b1, b2;
  if (!P(a, a1, a2) || !P(b, b1, b2)) return false;
  integral = b1 - a1;
  integral_of_square = b2 - a2;
  return true;
}

ShocklessLaw::ShocklessLaw(double max_lift, double action_angle, double base_radius,
                           std::span<const ShapeSegment> positive, std::span<const ShapeSegment> negative)
    : max_lift_(max_lift), half_action_(0.5 * action_angle), base_radius_(base_radius) {
  if (positive.empty() || negative.empty()) throw std::invalid_argument("shockless law: each phase needs a shape");
  constexpr double tol = 1e-12;
  double total = 0.0;
  for (const auto* phase : {&positive, &negative}) {
    for (const ShapeSegment& s : *phase) {
      if (!s.shape || !(s.length > 0.0)) throw std::invalid_argument("shockless law: empty segment");
      total += s.length;
    }
  }
  if (std::abs(total - half_action_) > 1e-12 * half_action_) {
    throw std::invalid_argument("shockless law: segment lengths must add up to half the action angle");
  }
  // Continuity of the acceleration: zero at the start, at the phase change (different
  // amplitudes) and at the nose-side end is free; inside a phase the shapes must meet.
  // The shapes' values at their ends are the same for every law: each shape keeps them (ends()).
  auto meets = [&](double a, double b) { return std::abs(a - b) <= tol; };
  if (!meets(positive.front().shape->ends().value0, 0.0)) {
    throw std::invalid_argument("shockless law: the acceleration must start at zero");
  }
  for (const auto* phase : {&positive, &negative}) {
    for (std::size_t i = 0; i + 1 < phase->size(); ++i) {
      if (!meets((*phase)[i].shape->ends().value1, (*phase)[i + 1].shape->ends().value0)) {
        throw std::invalid_argument("shockless law: shapes of one phase must join continuously");
      }
    }
  }
  if (!meets(positive.back().shape->ends().value1, 0.0) || !meets(negative.front().shape->ends().value0, 0.0)) {
    throw std::invalid_argument("shockless law: the acceleration must cross zero between the phases");
  }

  // Lift and velocity at the nose per unit amplitude of each phase (index 0: A+, 1: A-):
  // over a segment of phase p, v += L I1(1) [p], h += v L + L^2 I2(1) [p].
  double h[2] = {0.0, 0.0}, v[2] = {0.0, 0.0};
  auto propagate = [&](const ShapeSegment& s, int phase) {
    const double L = s.length;
    for (int k = 0; k < 2; ++k) h[k] += v[k] * L;
    h[phase] += L * L * s.shape->ends().integral2;
    v[phase] += L * s.shape->ends().integral1;
  };
  for (const ShapeSegment& s : positive) propagate(s, 0);
  for (const ShapeSegment& s : negative) propagate(s, 1);
  // [v+ v-; h+ h-] [A+; A-] = [0; h_max]
  const double det = v[0] * h[1] - v[1] * h[0];
  amplitude_pos_ = -v[1] * max_lift_ / det;
  amplitude_neg_ = v[0] * max_lift_ / det;
  if (!(amplitude_pos_ > 0.0) || !(amplitude_neg_ < 0.0) || !std::isfinite(amplitude_pos_) ||
      !std::isfinite(amplitude_neg_)) {
    throw std::invalid_argument("shockless law: the shapes give no rising law (amplitudes " +
                                printf_g(amplitude_pos_) + ", " + printf_g(amplitude_neg_) + ")");
  }

  // The pieces with their starting lift and velocity for the actual amplitudes.
  double x = 0.0, lift = 0.0, vel = 0.0;
  pieces_.reserve(positive.size() + negative.size());
  auto add = [&](const ShapeSegment& s, double A) {
    const double L = s.length;
    const ShapeEnds& e = s.shape->ends();
    pieces_.push_back({s.shape, x, L, A, lift, vel});
    lift += vel * L + A * L * L * e.integral2;
    vel += A * L * e.integral1;
    x += L;
  };
  for (const ShapeSegment& s : positive) add(s, amplitude_pos_);
  for (const ShapeSegment& s : negative) add(s, amplitude_neg_);
  pieces_.back().length = half_action_ - pieces_.back().start;  // the last piece ends at the nose exactly

  breakpoints_.reserve(2 * pieces_.size() - 1);
  for (std::size_t i = 1; i < pieces_.size(); ++i) {  // the junctions, x_1 ... x_{n-1} from the start of lift
    const double xj = pieces_[i].start;
    breakpoints_.push_back(-(half_action_ - xj));
    breakpoints_.push_back(half_action_ - xj);
  }
  const Piece& last = pieces_.back();
  // h''' is odd about the nose: it jumps there unless the last shape ends with zero slope.
  if (std::abs(last.shape->ends().slope1) > 1e-12) breakpoints_.push_back(0.0);
  std::sort(breakpoints_.begin(), breakpoints_.end());
}

std::vector<double> ShocklessLaw::junctions_from_start() const {
  std::vector<double> out;
  for (std::size_t i = 1; i < pieces_.size(); ++i) out.push_back(pieces_[i].start);
  return out;
}

LiftDerivatives ShocklessLaw::evaluate_in_event(double phi) const {
  // x from the start of lift; dx/dphi = +1 before the nose (phi < 0), -1 after it.
  const double x = half_action_ - std::abs(phi);
  const double sign = phi < 0.0 ? 1.0 : -1.0;
  std::size_t k = 0;
  while (k + 1 < pieces_.size() && x >= pieces_[k + 1].start) ++k;
  const Piece& p = pieces_[k];
  const double y = x - p.start;
  const double tau = std::clamp(y / p.length, 0.0, 1.0);
  const double A = p.amplitude, L = p.length;
  const ShapeValues v = p.shape->all(tau);
  const double H = p.lift0 + p.velocity0 * y + A * L * L * v.integral2;
  const double H1 = p.velocity0 + A * L * v.integral;
  const double H2 = A * v.value;
  const double H3 = A * v.slope / L;
  return {H, sign * H1, H2, sign * H3};
}

}  // namespace mechgraph::cams

namespace mechgraph::cams {

bool ShocklessLaw::monotone_breaks(int order, std::vector<double>& breaks) const {
  if (order < 0 || order > 2) return false;
  for (const Piece& p : pieces_)
    if (!p.shape->monotone()) return false;
  if (order == 0) {
    // The velocity is 0 at the start, rises through the positive phase and falls back to 0 at the
    // nose through the negative one (mirrored on the return): h' changes sign at the nose only.
    breaks = {0.0};
    return true;
  }
  breaks = breakpoints_;
  if (!std::binary_search(breaks.begin(), breaks.end(), 0.0)) breaks.insert(std::upper_bound(breaks.begin(), breaks.end(), 0.0), 0.0);
  return true;
}

}  // namespace mechgraph::cams
