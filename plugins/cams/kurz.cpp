#include "kurz.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <numbers>
#include <sstream>
#include <stdexcept>
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
  // The limits are the mathematics' and a double's only: the phases must exist (0 < phi_y < phi_p,
  // 0 < sigma < 1), each wave must hold an angle of its own (a double strictly inside it), and the
  // amplitudes and jerks (A+ pi / (2 phi_1), A+ pi / (2 phi_2), 2 A- / phi_3) must stay finite.
  // The searches read any piece from two ulps up (numerics::one_sided_point), so a wave of 0.22
  // deg (rise_split 0.01 of 22 deg) or far narrower is computed as it is.
  if (!(phi_y > 0.0) || !(phi_y < phi_p)) {
    std::ostringstream msg;
    msg << "accel_angle = " << deg(phi_y) << " must lie strictly between 0 and half the action angle (" << deg(phi_p)
        << "): the positive phase and the negative phase after it both need room";
    throw NodeError("accel_angle", msg.str());
  }
  const double sigma = rise_split ? *rise_split : kurz_default_split(phi_y, phi_p);
  if (rise_split && (!(sigma > 0.0) || !(sigma < 1.0))) {
    std::ostringstream msg;
    msg << "rise_split = " << sigma
        << " must lie strictly between 0 and 1 (0 loses the quarter sine, so the acceleration would jump at "
           "the start of lift; 1 loses the quarter cosine, so it would jump at the end of the positive phase)";
    throw NodeError("rise_split", msg.str());
  }
  const double phi_3 = phi_p - phi_y;
  // The default jerk-continuous split gives the quarter cosine phi_2 = pi^2 phi_3^2 / (12 phi_y)
  // directly: through sigma it would round to nothing as accel_angle nears half the action angle.
  const bool jerk_continuous = !rise_split && kurz_jerk_continuous_split(phi_y, phi_p) > 0.0;
  const double phi_2 = jerk_continuous ? pi * pi * phi_3 * phi_3 / (12.0 * phi_y) : phi_y - sigma * phi_y;
  const double phi_1 = jerk_continuous ? phi_y - phi_2 : sigma * phi_y;
  const char* split_parameter = rise_split ? "rise_split" : "accel_angle";
  // The shapes hold no state: one of each serves every law (a sweep makes a law per case). They
  // are never destroyed (not even at exit, where a law on another thread may still be in use),
  // so the laws hold them uncounted (an aliasing shared_ptr with no owner, whose copies touch no
  // counter): a law made or dropped on one thread then writes nothing another thread's laws
  // write. Counted, every law's making and dropping incremented and decremented the same three
  // counters from every thread.
  static const AccelShape* const quarter_sine = new QuarterSineRise();
  static const AccelShape* const quarter_cosine = new QuarterCosineFall();
  static const AccelShape* const parabola = new ParabolaToVertex();
  const auto uncounted = [](const AccelShape* shape) { return std::shared_ptr<const AccelShape>(std::shared_ptr<const AccelShape>(), shape); };
  const ShapeSegment positive[] = {{uncounted(quarter_sine), phi_1}, {uncounted(quarter_cosine), phi_2}};
  const ShapeSegment negative[] = {{uncounted(parabola), phi_3}};
  std::shared_ptr<const ShocklessLaw> law;
  try {
    law = std::make_shared<const ShocklessLaw>(basics.max_lift, basics.action_angle, basics.base_radius,
                                               std::span<const ShapeSegment>(positive), std::span<const ShapeSegment>(negative));
  } catch (const std::invalid_argument& e) {
    throw NodeError(phi_1 < phi_3 || phi_2 < phi_3 ? split_parameter : "accel_angle",
                    std::string("accel_angle = ") + deg(phi_y) + " and rise_split = " + std::to_string(sigma) +
                        " give no law: " + e.what());
  }
  // The waves as the law cuts them (knots: start, sine | cosine, cosine | parabola, ...): each
  // needs a double strictly inside, else it has no angle of its own.
  const std::vector<double>& breaks = law->breakpoint_list();
  const std::size_t knots = breaks.size() + 2;  // the event's start, the breakpoints, its end (CamLaw::knots)
  const auto knot = [&](std::size_t i) {
    return i == 0 ? law->event_begin() : i <= breaks.size() ? breaks[i - 1] : law->event_end();
  };
  const char* wave[3] = {"quarter sine", "quarter cosine", "parabola"};
  const double width[3] = {phi_1, phi_2, phi_3};
  for (std::size_t i = 0; i < 3; ++i) {
    if (i + 1 < knots && std::nextafter(knot(i), knot(i + 1)) < knot(i + 1)) continue;
    std::ostringstream msg;
    msg << std::setprecision(6) << "accel_angle = " << deg(phi_y) << " with rise_split = " << sigma << " leaves the "
        << wave[i] << " " << width[i] * 180.0 / pi << " deg wide, below one ulp of the cam angle ("
        << std::abs(std::nextafter(phi_p, 4.0) - phi_p) * 180.0 / pi
        << " deg at the start of lift): no double angle lies inside it";
    throw NodeError(i == 2 ? "accel_angle" : split_parameter, msg.str());
  }
  const double jerk[3] = {law->positive_amplitude() * 0.5 * pi / phi_1, law->positive_amplitude() * 0.5 * pi / phi_2,
                          2.0 * law->negative_amplitude() / phi_3};
  for (std::size_t i = 0; i < 3; ++i) {
    if (std::isfinite(jerk[i]) && std::isfinite(law->positive_amplitude()) && std::isfinite(law->negative_amplitude()))
      continue;
    std::ostringstream msg;
    msg << std::setprecision(6) << "accel_angle = " << deg(phi_y) << " with rise_split = " << sigma << ": the "
        << wave[i] << " (" << width[i] * 180.0 / pi
        << " deg) is so narrow that its jerk leaves the range of a double (larger than 1.8e308 m/rad^3)";
    throw NodeError(i == 2 ? "accel_angle" : split_parameter, msg.str());
  }
  return law;
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
                        "positive-acceleration phase phi_y from the start of lift; strictly between 0 and half the "
                        "action angle (both phases need room); beyond that only what a double demands: each wave "
                        "wider than one ulp of the cam angle, its jerk finite",
                        "deg")
          .at_least(4.0 * min_start_of_lift_ulp)
          .because(">= 4 x 2^-63 rad: each of its two waves must hold a double angle of its own, two ulps of the start of lift at the smallest action angle (0.05 deg from the nose)")
          .with_example(30.0 * std::numbers::pi / 180.0),
      ParamSpec::number(
          "rise_split", dim::none,
          "share of the positive phase taken by the quarter sine (the rest is the quarter cosine). Default: the "
          "split that makes the jerk continuous at the positive/negative junction, 1 - pi^2 (phi_3/phi_y)^2 / 12 "
          "(phi_3 = half action angle - accel_angle), which exists only while phi_3 < 1.103 phi_y. Otherwise (the "
          "usual case for valve cams) no split can make the jerk continuous there, and the default is the split "
          "that minimises the larger of the two jerk jumps left, at the start of lift and at the junction: "
          "(1 + k / (pi + sqrt(pi^2 + k^2))) / 2 with k = 6 phi_y^2 / (pi phi_3^2), between 0.5 and 0.62. The "
          "default therefore changes branch where phi_3 = 1.103 phi_y. The split used is the rise_split output. "
          "Range: strictly between 0 and 1 (at 0 or 1 a wave vanishes and the acceleration jumps); beyond that only "
          "what a double demands: each wave must hold a double angle of its own (wider than one ulp of the cam "
          "angle) and its jerk must stay finite, or the node is refused naming the wave")
          .optional()
          .at_least(0x1p-52)
          .below(1.0)
          .because(">= 2^-52: the quarter sine (rise_split x accel_angle) must hold a double angle at the start of lift, two ulps of that angle, which exceeds accel_angle; < 1: at 1 the quarter cosine vanishes"),
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
