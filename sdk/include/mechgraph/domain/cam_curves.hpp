#pragma once
// What a cam designer reads off any lift curve: the SVAJ curves (lift, velocity, acceleration and
// jerk over cam angle, with the crank angle beside it) as one table, and the events as engine people
// quote them: where the lift passes a checking lift (1 mm, 0.050 in) on the way up and down, the
// duration between and the lobe centreline halfway, in cam and crank degrees (the crank turns twice
// per cam turn). Angles are the law's (radians from its zero, the nose of a symmetric lobe); see
// docs/methods/valvetrain.md, "Cam curves and events". Built-in cam nodes output exactly these.
#include <mechgraph/domain/cam_law.hpp>

#include <functional>
#include <optional>
#include <span>
#include <vector>

namespace mechgraph {

/// Lift, velocity, acceleration and jerk at `points` (>= 2) evenly spaced cam angles over the event
/// widened by a tenth of its width on each side (never past +-pi), so the curves start and end on
/// the base circle. Table: axis cam_angle [rad]; channels crank_angle [rad] (= 2 cam_angle), lift
/// [m], velocity [m/rad], acceleration [m/rad^2], jerk [m/rad^3].
Table svaj_table(const CamLaw& law, int points);

/// Events at one checking lift, cam angles in radians.
struct LiftEvents {
  double opening = 0.0;     // first angle where the lift rises through the checking lift
  double closing = 0.0;     // last angle where it falls through it
  double duration = 0.0;    // closing - opening
  double centreline = 0.0;  // (opening + closing) / 2
};

/// The events of `lift` (a function of cam angle, smooth between `knots`, which span the event) at
/// `checking_lift`: sign changes of lift - checking_lift found by sampling each piece with `samples`
/// points and refined by TOMS 748. nullopt when the lift never reaches the checking lift.
std::optional<LiftEvents> events_at_lift(const std::function<double(double)>& lift, std::span<const double> knots,
                                         double checking_lift, int samples, long& evaluations);
/// The same for a cam law (its event and breakpoints as knots).
std::optional<LiftEvents> events_at_lift(const CamLaw& law, double checking_lift, int samples, long& evaluations);

/// One row per checking lift the lift reaches (in the order given; lifts it never reaches are
/// left out; 0 stands for the seat: the ends of the knots, i.e. of the event): axis checking_lift [m]; channels opening, closing, duration, centreline (cam angle,
/// rad) and crank_opening, crank_closing, crank_duration, crank_centreline (crank angle, rad).
Table events_table(const std::function<double(double)>& lift, std::span<const double> knots,
                   const std::vector<double>& checking_lifts, int samples, long& evaluations);

/// 0.050 in in metres: the American checking lift, beside the European 1 mm.
inline constexpr double checking_lift_0050_in = 0.050 * 25.4e-3;

}  // namespace mechgraph
