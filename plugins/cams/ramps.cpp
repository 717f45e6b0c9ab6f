#include "ramps.hpp"

#include <mechgraph/errors.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>

namespace mechgraph::cams {
namespace {

constexpr double pi = std::numbers::pi;

// The ramp part on the opening side, u = phi + P + L in [0, L + P] from the start of the ramp.
LiftDerivatives opening_side(const RampSpec& r, double P, double u) {
  const double L = r.length, H = r.height;
  if (u <= L) {
    const double x = u / L;
    if (r.type == RampType::constant_velocity) return {H * x, H / L, 0.0, 0.0};
    // Cosine: R = H (1 - cos(q u)), q = pi/(2L); 1 - cos = 2 sin^2(q u/2) keeps digits near 0.
    const double q = 0.5 * pi / L;
    const double half = std::sin(0.5 * q * u);
    const double sn = std::sin(q * u), cs = std::cos(q * u);
    return {2.0 * H * half * half, H * q * sn, H * q * q * cs, -H * q * q * q * sn};
  }
  // Fade of the ramp velocity under the main law, w in [0, 1]:
  //   R' = v (1 - s(w)), s = 10w^3 - 15w^4 + 6w^5, s' = 30 w^2 (1-w)^2, s'' = 60 w (1-w)(1-2w),
  //   R = H + v P F(w), F = integral of (1 - s) = w - 5w^4/2 + 3w^5 - w^6,
  //   R'' = -v s'(w)/P, R''' = -v s''(w)/P^2.
  const double v = ramp_end_velocity(r);
  const double w = std::min((u - L) / P, 1.0);
  const double y = 1.0 - w;
  const double w2 = w * w;
  const double s = w2 * w * (10.0 + w * (-15.0 + 6.0 * w));
  const double F = w - w2 * w2 * (2.5 + w * (-3.0 + w));
  return {H + v * P * F, v * (1.0 - s), -v * 30.0 * w2 * y * y / P, -v * 60.0 * w * y * (1.0 - 2.0 * w) / (P * P)};
}

std::string degrees(double rad) {
  std::ostringstream m;
  m << rad * 180.0 / pi << " deg";
  return m.str();
}

std::string millimetres(double m) {
  std::ostringstream out;
  out << m * 1e3 << " mm";
  return out.str();
}

}  // namespace

std::string_view ramp_type_name(RampType type) {
  switch (type) {
    case RampType::none: return "none";
    case RampType::constant_velocity: return "constant_velocity";
    case RampType::cosine: return "cosine";
  }
  return "?";
}

std::optional<RampType> ramp_type_from_name(std::string_view name) {
  for (RampType t : {RampType::none, RampType::constant_velocity, RampType::cosine})
    if (ramp_type_name(t) == name) return t;
  return std::nullopt;
}

std::vector<std::string> ramp_type_names() { return {"none", "constant_velocity", "cosine"}; }

double ramp_end_velocity(const RampSpec& r) {
  if (r.type == RampType::none || !(r.length > 0.0)) return 0.0;
  // Constant velocity: H_r/L. Cosine: d/dphi H_r (1 - cos(pi x/2)) at x = 1 is (pi/2) H_r/L.
  return r.type == RampType::constant_velocity ? r.height / r.length : 0.5 * pi * r.height / r.length;
}

double ramp_lift_at_nose(const RampSpec& r, double half_action_angle) {
  if (r.type == RampType::none) return 0.0;
  return r.height + 0.5 * ramp_end_velocity(r) * half_action_angle;
}

LiftDerivatives ramp_part(const RampSpec& r, double P, double phi) {
  if (r.type == RampType::none) return {};
  const double reach = P + r.length;
  if (!(phi > -reach && phi < reach)) return {};
  if (phi <= 0.0) return opening_side(r, P, phi + reach);
  // Closing side: mirror image, odd derivatives change sign.
  const LiftDerivatives m = opening_side(r, P, reach - phi);
  return {m.lift, -m.velocity, m.acceleration, -m.jerk};
}

RampedLaw::RampedLaw(std::shared_ptr<const CamLaw> main, RampSpec ramp)
    : main_(std::move(main)), ramp_(ramp), half_main_(0.0) {
  if (!main_) throw NodeError("ramp", "a ramp needs a main law");
  if (ramp_.type == RampType::none) throw NodeError("ramp", "RampedLaw built with ramp 'none'");
  if (!(std::isfinite(ramp_.height) && ramp_.height > 0.0))
    throw NodeError("ramp_height", "a ramp needs ramp_height > 0 (got " + millimetres(ramp_.height) + ")");
  if (!(std::isfinite(ramp_.length) && ramp_.length > 0.0))
    throw NodeError("ramp_length", "a ramp needs ramp_length > 0 (got " + degrees(ramp_.length) + ")");
  const double b = main_->event_begin(), e = main_->event_end();
  if (!(std::abs(b + e) <= 1e-9 * (e - b))) {
    std::ostringstream m;
    m << "ramps need a main law symmetric about the nose; this law's event is " << degrees(b) << " .. "
      << degrees(e);
    throw NodeError("ramp", m.str());
  }
  half_main_ = 0.5 * (e - b);
  // The largest derivatives of R: on a cosine ramp H q^k (q = pi/(2L)), under the fade v,
  // 1.875 v/P and 5.78 v/P^2; all must be finite numbers.
  const double q = 0.5 * pi / ramp_.length, v = ramp_end_velocity(ramp_);
  if (!std::isfinite(ramp_.height * q * q * q) || !std::isfinite(6.0 * v / (half_main_ * half_main_)))
    throw NodeError("ramp_length", "ramp_length " + degrees(ramp_.length) + " is too short for double precision");
  if (!(half_main_ + ramp_.length < pi)) {
    std::ostringstream m;
    m << "action_angle + 2 ramp_length = " << degrees(2.0 * (half_main_ + ramp_.length))
      << " must stay below 360 deg";
    throw NodeError("ramp_length", m.str());
  }
}

LiftDerivatives RampedLaw::evaluate_in_event(double phi) const {
  const LiftDerivatives r = ramp_part(ramp_, half_main_, phi);
  const LiftDerivatives m = main_->at(phi);
  return {r.lift + m.lift, r.velocity + m.velocity, r.acceleration + m.acceleration, r.jerk + m.jerk};
}

std::vector<double> RampedLaw::breakpoints() const {
  std::vector<double> out = main_->breakpoints();
  out.push_back(-half_main_);
  out.push_back(0.0);
  out.push_back(half_main_);
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

double RampedLaw::max_lift() const { return main_->max_lift() + ramp_lift_at_nose(ramp_, half_main_); }

}  // namespace mechgraph::cams
