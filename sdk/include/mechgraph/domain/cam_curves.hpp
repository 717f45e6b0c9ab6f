#pragma once
// What a cam designer reads off any lift curve: the SVAJ curves (lift, velocity, acceleration and
// jerk over cam angle, with the crank angle beside it) as one table, and the events as engine people
// quote them: where the lift passes a checking lift (1 mm, 0.050 in) on the way up and down, the
// duration between and the lobe centreline halfway, in cam and crank degrees (the crank turns twice
// per cam turn). Angles are the law's (radians from its zero, the nose of a symmetric lobe); see
// docs/methods/valvetrain.md, "Cam curves and events". Built-in cam nodes output exactly these.
#include <mechgraph/domain/cam_law.hpp>
#include <mechgraph/node.hpp>

#include <functional>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace mechgraph {

/// Lift, velocity, acceleration and jerk at `points` (>= 2) evenly spaced cam angles over the event
/// widened by a tenth of its width on each side (never past +-pi), so the curves start and end on
/// the base circle. Table: axis cam_angle [rad]; channels crank_angle [rad] (= 2 cam_angle), lift
/// [m], velocity [m/rad], acceleration [m/rad^2], jerk [m/rad^3].
Table svaj_table(const CamLaw& law, int points);
/// The same for any lift with derivatives over cam angle `at(phi)` whose event is [begin, end].
Table svaj_table(const std::function<LiftDerivatives(double)>& at, double begin, double end, int points);

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

/// The nose: the cam angle of the maximum lift (from the law's zero). Where the maximum is a
/// plateau (a dwell at full lift) or is reached more than once, the middle between the first and
/// the last angle at which the lift is within 1e-13 of its maximum, when they lie more than 1e-3 rad
/// apart. A symmetric lobe's is 0; an
/// asymmetric one's is not (a steep opening and a slow closing put it before the event's middle).
double nose_angle(const std::function<double(double)>& lift, std::span<const double> knots, int samples, long& evaluations);

/// One row per checking lift the lift reaches (in the order given; lifts it never reaches are
/// left out; 0 stands for the seat: the ends of the knots, i.e. of the event): axis checking_lift
/// [m]; channels opening, closing (cam angle from the law's zero, as the svaj axis), duration,
/// centreline (cam angle from the nose `nose`) and crank_opening, crank_closing, crank_duration,
/// crank_centreline (crank angle, twice those).
/// With `nose_timing` (the installed lobe: the crank angle of its nose after the overlap TDC),
/// also opening_atdc, closing_atdc, centreline_atdc: crank angle after that TDC,
/// nose_timing + 2 (phi - nose).
Table events_table(const std::function<double(double)>& lift, std::span<const double> knots,
                   const std::vector<double>& checking_lifts, int samples, long& evaluations,
                   std::optional<double> nose_timing = std::nullopt, double nose = 0.0);

/// Events quoted the engine way from the installed lobe's crank angles after the overlap TDC
/// (the nose, at cam angle `nose`, stands at crank angle nose_timing):
/// a lobe whose nose stands after that TDC (nose_timing > 0) is an intake: "opens 12.0 deg BTDC,
/// closes 52.0 deg ABDC"; one before it an exhaust: "opens 52.0 deg BBDC, closes 12.0 deg ATDC".
std::string quote_events(const LiftEvents& e, double nose_timing, double nose = 0.0);

// The events every node with a lift curve gives (built-in cams, valve motion): a `checking_lift`
// parameter (default 1 mm), an optional `nose_timing` parameter, and the ports below.
ParamSpec checking_lift_param(const std::string& whose);
ParamSpec nose_timing_param();
/// The events table and the scalars opening_angle, closing_angle, duration, crank_duration,
/// centreline (from the nose), nose_angle and event_centre (seat to seat, from the nose).
std::vector<PortSpec> lift_event_ports(const std::string& whose);
/// Whether anything reads one of lift_event_ports (they cost a root search each: skipped otherwise).
bool lift_events_wanted(const EvalContext& ctx);
/// Sets lift_event_ports from `lift` (smooth between `knots`, which span the event) at the
/// parameters' checking lift, 0.050 in and the seat; with nose_timing a note quotes them from TDC.
/// When the lift (at most `max_lift`) never reaches the checking lift: throws NodeError("checking_lift")
/// if a scalar event is wanted, else gives the table the rows it can (the seat's) and says so in a note.
void set_lift_events(OutputSet& out, const EvalContext& ctx, const ParamSet& p, const std::function<double(double)>& lift,
                     std::span<const double> knots, double max_lift, const std::string& whose, int samples,
                     long& evaluations);

// Their presentation (presentation.hpp), declared once here for every node with a lift curve:
/// The angle frames such a node declares (NodeInfo::frames): "cam", cam angle from the law's zero
/// (the nose of a symmetric lobe), and "crank", crank angle after the overlap TDC: 2 cam +
/// nose_timing, with the dead centres marked every 180 deg and angles quoted from them ("3.4 ATDC").
/// A node without the nose_timing parameter (`installed` false) gets the crank frame as twice
/// the cam angle only: its figures stay on cam angle.
std::vector<AngleFrame> cam_angle_frames(bool installed = true);
/// The note such a node makes: with nose_timing, its events quoted from TDC and BDC, made while
/// it computes its events table.
NoteDecl timing_note();
/// A table port of svaj_table's channels: one stacked panel of lift and its derivatives over
/// cam angle (crank_angle another scale of the axis), with the events at the checking lift as
/// labelled points when drawn in crank angle.
PortSpec svaj_port(std::string name, std::string doc);
/// A table over cam angle (its axis `axis`, in frame "cam"), drawn plainly or as `role`.
Presentation over_cam_angle(std::string axis = "cam_angle", Role role = Role::plain);

/// 0.050 in in metres: the American checking lift, beside the European 1 mm.
inline constexpr double checking_lift_0050_in = 0.050 * 25.4e-3;

}  // namespace mechgraph
