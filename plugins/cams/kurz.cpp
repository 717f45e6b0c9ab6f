#include "kurz.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <numbers>
#include <sstream>
#include <string>

namespace mechgraph::cams {
namespace {

constexpr double pi = std::numbers::pi;

std::string deg(double rad) {
  std::ostringstream s;
  s << std::setprecision(4) << rad * 180.0 / pi << " deg";
  return s.str();
}

}  // namespace

double kurz_jerk_continuous_split(double phi_y, double phi_p) {
  const double r = (phi_p - phi_y) / phi_y;
  return 1.0 - pi * pi * r * r / 12.0;
}

double kurz_minimax_split(double phi_y, double phi_p) {
  const double phi_3 = phi_p - phi_y;
  // kappa = 6 phi_y^2 / (pi phi_3^2); the root of pi/(2 x1) = pi/(2 (phi_y - x1)) - k, written
  // without the cancellation of kappa - pi + sqrt(pi^2 + kappa^2).
  const double kappa = 6.0 * phi_y * phi_y / (pi * phi_3 * phi_3);
  return 0.5 * (1.0 + kappa / (pi + std::hypot(pi, kappa)));
}

double kurz_default_split(double phi_y, double phi_p) {
  const double jerk_continuous = kurz_jerk_continuous_split(phi_y, phi_p);
  return jerk_continuous > 0.0 ? jerk_continuous : kurz_minimax_split(phi_y, phi_p);
}

std::shared_ptr<const ShocklessLaw> make_kurz_law(const CamBasics& basics, double phi_y,
                                                  std::optional<double> rise_split) {
  const double phi_p = 0.5 * basics.action_angle;
  // Both phases need a resolvable share of the half event: a phase of 1e-3 of it or less makes the
  // law impulsive (not shockless any more) and its amplitudes overflow.
  constexpr double min_share = 1e-3;
  if (!(phi_y >= min_share * phi_p) || !(phi_y <= (1.0 - min_share) * phi_p)) {
    std::ostringstream msg;
    msg << "accel_angle = " << deg(phi_y) << " must lie between " << deg(min_share * phi_p) << " and "
        << deg((1.0 - min_share) * phi_p) << " (0.1 % and 99.9 % of half the action angle, " << deg(phi_p)
        << "): both the positive and the negative phase need room";
    throw NodeError("accel_angle", msg.str());
  }
  const double sigma = rise_split ? *rise_split : kurz_default_split(phi_y, phi_p);
  if (!(sigma > 0.0) || !(sigma < 1.0)) {
    std::ostringstream msg;
    msg << "rise_split = " << sigma
        << " must lie strictly between 0 and 1 (0 loses the quarter sine, so the acceleration would jump at "
           "the start of lift; 1 loses the quarter cosine, so it would jump at the end of the positive phase)";
    throw NodeError("rise_split", msg.str());
  }
  const double phi_1 = sigma * phi_y;
  const double phi_2 = phi_y - phi_1;
  // Each quarter wave must be wide enough to be told apart from its ends: the host's searches see
  // a piece's one-sided value at 1e-13 of its width from a knot, and a knot at |phi| <= phi_p is
  // resolved only to half an ulp, up to 1.1e-16 phi_p; so a wave narrower than 1.1e-3 phi_p merges
  // into its neighbour (rise_split 0.999 with accel_angle 18 deg reported accel_angle 0). 4e-3 phi_p
  // (0.26 deg for a 130 deg event) leaves a factor of 3.6; the feasible split is then
  // [min_wave / accel_angle, 1 - min_wave / accel_angle].
  const double min_wave = 4e-3 * phi_p;
  if (phi_y < 2.0 * min_wave) {
    std::ostringstream msg;
    msg << "accel_angle = " << deg(phi_y) << " is below " << deg(2.0 * min_wave)
        << ": its quarter sine and quarter cosine need at least " << deg(min_wave)
        << " each (0.4 % of half the action angle, " << deg(phi_p) << ")";
    throw NodeError("accel_angle", msg.str());
  }
  if (!(phi_1 >= min_wave) || !(phi_2 >= min_wave)) {
    std::ostringstream msg;
    msg << std::setprecision(6) << "rise_split = " << sigma << " leaves the quarter " << (phi_1 < phi_2 ? "sine " : "cosine ")
        << deg(std::min(phi_1, phi_2)) << " of accel_angle = " << deg(phi_y) << "; each quarter wave needs at least "
        << deg(min_wave) << " (0.4 % of half the action angle), so rise_split must lie within " << min_wave / phi_y
        << " .. " << 1.0 - min_wave / phi_y;
    if (!rise_split)
      msg << "; this is the default split for accel_angle = " << deg(phi_y) << " and half the action angle "
          << deg(phi_p) << ": move accel_angle away from half the action angle, or give rise_split";
    throw NodeError(rise_split ? "rise_split" : "accel_angle", msg.str());
  }
  const double phi_3 = phi_p - phi_y;
  std::vector<ShapeSegment> positive{{std::make_shared<const QuarterSineRise>(), phi_1},
                                     {std::make_shared<const QuarterCosineFall>(), phi_2}};
  std::vector<ShapeSegment> negative{{std::make_shared<const ParabolaToVertex>(), phi_3}};
  return std::make_shared<const ShocklessLaw>(basics.max_lift, basics.action_angle, basics.base_radius,
                                              std::move(positive), std::move(negative));
}

CamLawDefinition kurz_definition() {
  CamLawDefinition d;
  d.type = "cam.kurz";
  d.version = 1;
  d.summary =
      "Kurz shockless cam: acceleration a quarter sine up and a quarter cosine down over the positive phase, "
      "then a parabola with its vertex at the nose; amplitudes from zero velocity and max_lift at the nose";
  d.params = {
      ParamSpec::number("accel_angle", dim::angle,
                        "positive-acceleration phase phi_y from the start of lift; must be below half the action "
                        "angle",
                        "deg")
          .positive()
          .with_example(30.0 * std::numbers::pi / 180.0),
      ParamSpec::number(
          "rise_split", dim::none,
          "share of the positive phase taken by the quarter sine (the rest is the quarter cosine). Default: the "
          "split that makes the jerk continuous at the positive/negative junction, 1 - pi^2 (phi_3/phi_y)^2 / 12 "
          "(phi_3 = half action angle - accel_angle), which exists only while phi_3 < 1.103 phi_y. Otherwise (the "
          "usual case for valve cams) no split can make the jerk continuous there, and the default is the split "
          "that minimises the larger of the two jerk jumps left, at the start of lift and at the junction: "
          "(1 + k / (pi + sqrt(pi^2 + k^2))) / 2 with k = 6 phi_y^2 / (pi phi_3^2), between 0.5 and 0.62. The "
          "default therefore changes branch where phi_3 = 1.103 phi_y. The split used is the rise_split output. Each "
          "quarter wave must span at least 0.4 % of half the action angle, w (so the split lies within w / "
          "accel_angle .. 1 - w / accel_angle), the default included")
          .optional()
          .above(0.0)
          .below(1.0),
  };
  d.extra_outputs = {
      PortSpec::scalar("rise_split", dim::none, "share of the positive phase taken by the quarter sine, as used"),
  };
  d.make = [](const CamBasics& basics, const ParamSet& params, OutputSet& extra) -> std::shared_ptr<const CamLaw> {
    const double phi_y = params.number("accel_angle");
    std::optional<double> split;
    if (params.has("rise_split")) split = params.number("rise_split");
    auto law = make_kurz_law(basics, phi_y, split);
    extra.set_scalar("rise_split", split ? *split : kurz_default_split(phi_y, 0.5 * basics.action_angle));
    return law;
  };
  return d;
}

}  // namespace mechgraph::cams
