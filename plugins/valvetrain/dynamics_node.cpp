// valvetrain.dynamics: the valve's motion with the drive's elasticity and the contacts as effects
// (docs/methods/valvetrain.md, "dynamic simulation"; the model is in chain_model.hpp). With
// elastic_drive off the node is a pass-through: the rigid drive's (kinematic) lift, nothing
// integrated. Results are taken from the last of `revolutions` cam revolutions, so the start-up
// transient has died out when the drive is damped. The curves are read at their points; the scalar
// extremes (deviations, least contact force, greatest spring force, bounce height) are followed on
// the integrator's dense output between them ("Extremes and events from the dense output"). The
// spring's coil bind (always, with elastic_drive) and a travel stop are stiff contacts on the valve;
// the events table lists every departure from the cam's law and every other jump of the valve's
// speed or the cam's force (the landing on the seat with the cam in contact, the lash taken up; the
// rigid drive's too) with its cam angle, speed and force.
#include "node_types.hpp"
#include "valve_simulation.hpp"

#include <mechgraph/domain/cam_curves.hpp>
#include <mechgraph/domain/valve_motion.hpp>
#include <mechgraph/printf_number.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <string>

namespace mechgraph::valvetrain {
namespace {

constexpr double pi = std::numbers::pi;

// The code of an event in the events table (its port's description lists them), 0: not listed.
// Every event at which the valve's speed or the cam's force jumps has a row: the curves that jump
// (declared jumps_at_events) are drawn in pieces between the rows, so a jump without one would be
// drawn as a steep line. The ordinary seating (cam in contact, no bounce before) follows the law,
// but the seat stops the valve's speed there: it is listed as such (9). Lift-off is not: the
// drive's spring lifts the valve from rest, its speed and the cam's force stay continuous. The
// lash take-up (10) is no event of the simulation: add_lash_take_up, rigid_events_table.
double event_code(const EventRecord& e, bool after_bounce) {
  if (e.kind == "contact_loss") return 1.0;
  if (e.kind == "contact_regain") return 2.0;
  if (e.kind == "bounce") return 3.0;
  if (e.kind == "landing") return !e.cam_contact || after_bounce ? 4.0 : 9.0;
  if (e.kind == "coil_bind") return 5.0;
  if (e.kind == "coil_bind_release") return 6.0;
  if (e.kind == "stop") return 7.0;
  if (e.kind == "stop_release") return 8.0;
  return 0.0;
}

// The names of event_code's values, as the events table declares them.
std::vector<Code> event_codes() {
  return {{1.0, "contact_lost", "the valve leaves the cam"},
          {2.0, "contact_regained", "the follower lands on the cam again"},
          {3.0, "bounce", "a bounce on the seat"},
          {4.0, "seated", "seated off the cam or after bounces"},
          {5.0, "coil_bind", "the spring goes solid"},
          {6.0, "coil_bind_left", "the spring leaves solid"},
          {7.0, "stop_hit", "the travel stop is hit"},
          {8.0, "stop_left", "the travel stop is left"},
          {9.0, "seated_on_cam", "the valve lands on its seat with the cam in contact (the seat stops its speed)"},
          {10.0, "lash_taken_up", "the cam reaches the seated valve's follower: a rigid drive lifts the valve at the "
                                  "drive's speed, a unilateral elastic drive's damper loads the cam at once"}};
}

// An events table without rows, its channels declared (the port's description says what they are).
Table empty_events_table() {
  Table t;
  t.axis = {"cam_angle", dim::angle, {}, "deg"};
  t.add_channel("event", dim::none);
  t.add_channel("speed", dim::velocity, "m/s");
  t.add_channel("cam_force", dim::force, "N");
  t.add_channel("peak_force", dim::force, "N");
  return t;
}

// A row at `angle`, after the rows at or before it (the rows stay in cam-angle order).
void add_event(Table& t, double angle, double code, double speed, double cam_force, double peak_force) {
  const auto at = std::upper_bound(t.axis.values.begin(), t.axis.values.end(), angle) - t.axis.values.begin();
  t.axis.values.insert(t.axis.values.begin() + at, angle);
  const double row[] = {code, speed, cam_force, peak_force};
  for (std::size_t c = 0; c < 4; ++c) t.channels[c].values.insert(t.channels[c].values.begin() + at, row[c]);
}

// The rigid drive's events: the valve follows x = max(0, y) over the open period (the ValveMotion
// contract), so where the drive y = i h - lash passes zero its speed jumps from rest to the
// drive's w y' (the cam takes up the lash) and back to rest (it seats), and the cam's force from 0
// to M w^2 y'' + P0 and back. Both are listed (docs/methods/valvetrain.md, "Events table"), with
// the cam's force just after: at the opening the rigid drive's, at the seat none.
Table rigid_events_table(const ValveMotion& motion, double M, double P0) {
  const double w = motion.camshaft_speed();
  const LiftDerivatives opening = motion.drive(motion.open_begin()), closing = motion.drive(motion.open_end());
  Table t = empty_events_table();
  add_event(t, motion.open_begin(), 10.0, w * std::abs(opening.velocity), M * w * w * opening.acceleration + P0, 0.0);
  add_event(t, motion.open_end(), 9.0, w * std::abs(closing.velocity), 0.0, 0.0);
  return t;
}

// The events of the last revolution (from `last`, s) as a table over cam angle; the peak force of
// a lift limit's engagement from the limit-force monitor's segment that begins with it.
Table events_table(const SimulationResult& run, const std::vector<MonitorSegment>& limit_segments, double last, double w,
                   double period) {
  Table t = empty_events_table();
  bool after_bounce = false;
  for (const EventRecord& e : run.events) {
    const double code = event_code(e, after_bounce);
    after_bounce = e.kind == "bounce";
    if (e.t < last || code == 0.0) continue;
    double peak = 0.0;
    if (code == 5.0 || code == 7.0)
      for (const MonitorSegment& m : limit_segments)
        if (std::abs(m.begin - e.t) <= 1e-12 * period) peak = std::max(peak, m.greatest.value);
    add_event(t, -pi + w * (e.t - last), code, e.speed, e.cam_force, peak);
  }
  return t;
}

// A lone valve held on its seat (ChainModel::rigid_when_seated) on a unilateral drive: the
// simulation does not follow its contact with the cam across the lash (the held valve cannot
// move), but where the drive y = i h - lash passes zero at the opening the cam reaches the
// follower, and the drive's damper loads the cam at once with c_0 y' (ChainModel::
// force_after_event, as at a regain). Its row (10), if the valve is seated then: seated at the
// curve point before the opening, and no seat event between that point and the opening.
void add_lash_take_up(Table& t, const ValveMotion& motion, const ValveSimulation& sim, const std::vector<double>& phi) {
  const SimulationResult& run = sim.run;
  const double open = motion.open_begin(), w = motion.camshaft_speed();
  const auto after = std::upper_bound(phi.begin(), phi.end(), open);
  if (after == phi.begin()) return;
  const auto j = static_cast<std::size_t>(after - phi.begin()) - 1;
  const double t_open = sim.last_start + (open + pi) / w;
  if (!run.mode[j].seated) return;
  for (const EventRecord& e : run.events)
    if (e.t > run.t[j] && e.t <= t_open && (e.kind == "lift_off" || e.kind == "landing" || e.kind == "bounce")) return;
  const LiftDerivatives y = motion.drive(open);
  const DriveValue at{y.lift, w * y.velocity, w * w * y.acceleration};
  add_event(t, open, 10.0, w * std::abs(y.velocity), sim.model.force_after_event(at, ChainState(2 * sim.model.positions(), 0.0)), 0.0);
}

std::string degrees(double radians) { return printf_f(radians * 180.0 / pi, 1); }

// One note per kind of departure in the last revolution, in words: where it began, how often.
void describe_events(const SimulationResult& run, double last, double w, OutputSet& out) {
  struct Seen {
    int count = 0;
    double first = 0.0, speed = 0.0;
  };
  std::map<std::string, Seen> seen;
  for (const EventRecord& e : run.events) {
    if (e.t < last) continue;
    Seen& s = seen[e.kind];
    if (s.count++ == 0) {
      s.first = -pi + w * (e.t - last);
      s.speed = e.speed;
    }
  }
  const auto say = [&](const std::string& kind, const std::string& what) {
    const auto it = seen.find(kind);
    if (it == seen.end()) return;
    out.note(what + ": " + std::to_string(it->second.count) + (it->second.count == 1 ? " time" : " times") +
             " in the last revolution, first at cam angle " + degrees(it->second.first) + " deg (" +
             printf_g(it->second.speed, 3) + " m/s)");
  };
  say("contact_loss", "the follower leaves the cam (valve float)");
  say("bounce", "the valve bounces on its seat");
  say("coil_bind", "the spring goes solid (coil bind)");
  say("stop", "the valve hits the travel stop");
}

class DynamicsType final : public NodeType {
 public:
  DynamicsType() {
    info_.type = "valvetrain.dynamics";
    info_.version = 4;
    info_.summary = "valve motion on an elastic drive (single mass), cam contact, seat, coil bind and travel stop as "
                    "located events; rigid when elastic_drive is off";
    info_.params = {
        ParamSpec::number("drive_stiffness", dim::stiffness,
                          "k_d: the drive's stiffness reduced to the valve (elastic_drive; from 1 N/mm: softer, the "
                          "valve no longer follows the cam at all)",
                          "N/mm")
            .optional()
            .at_least(1e3)
            .at_most(1e13)
            .because("1 N/mm to 1e10 N/mm: softer leaves any cam, stiffer than any steel drive and beyond the integrator's stiffness"),
        ParamSpec::number("damping_ratio", dim::none,
                          "damping of the drive's first mode, share of critical (stiffness-proportional on the drive's "
                          "links) (elastic_drive)")
            .with_default(0.06)
            .non_negative()
            .at_most(2.0)
            .because(">= 0: damping takes energy; <= 2: past critical (1), overdamped"),
        ParamSpec::integer("revolutions", "cam revolutions simulated; results from the last")
            .with_default(2.0)
            .at_least(1)
            .at_most(1000)
            .because("1 to 1000 camshaft turns: the run settles within a few, 1000 bounds the time"),
        ParamSpec::number("tolerance", dim::none,
                          "relative tolerance of the integration (absolute: this times the full lift, and times the "
                          "full lift x camshaft speed for the velocity)")
            .with_default(1e-8)
            .at_least(1e-13)
            .at_most(1e-2)
            .because("1e-13 to 1e-2: tighter than a double's rounding of the state cannot be met, looser says nothing")
            .as_knob(),
        ParamSpec::choice("integrator", {"cvode", "dopri5", "auto"},
                          "cvode: SUNDIALS CVODE, BDF (stiff drives); dopri5: explicit Dormand-Prince 5(4); auto: "
                          "dopri5 where the chain is not stiff at the step cap, cvode where it is (the work counters "
                          "stiffness_ratio and implicit say which ran)")
            .with_default("auto")
            .as_knob(),
        ParamSpec::integer("curve_points", "points of the curves over the last cam revolution (the scalar extremes are found between them)")
            .with_default(1441.0)
            .at_least(16)
            .at_most(1e7)
            .because("16 to 1e7: a curve per turn, bounded in memory")
            .as_knob(),
        ParamSpec::number_list("stiffnesses", dim::stiffness,
                               "multi_mass: stiffnesses reduced to the valve, cam-tappet, tappet-pushrod, pushrod-rocker, "
                               "rocker-valve",
                               "N/mm")
            .optional()
            .positive()
            .at_most(1e13)
            .because("> 0: a spring's stiffness; <= 1e10 N/mm: as drive_stiffness"),
        ParamSpec::integer("coils", "spring_surge: coil masses the spring is cut into")
            .with_default(8.0)
            .at_least(1)
            .at_most(200)
            .because("1 to 200: the spring cut into that many masses, more than any spring's active coils")
            .as_knob(),
        ParamSpec::number("surge_damping_ratio", dim::none, "spring_surge: damping of the first surge mode, share of critical")
            .with_default(0.01)
            .non_negative()
            .at_most(1.0)
            .because(">= 0: damping takes energy; <= 1: critical"),
        ParamSpec::number("restitution", dim::none, "coefficient of restitution of the valve on its seat (seat_impact)")
            .with_default(0.3)
            .non_negative()
            .below(1.0)
            .because(">= 0 and < 1: a landing gives energy back, never all of it"),
        ParamSpec::number("seating_speed", dim::velocity, "a landing whose rebound (restitution x landing speed) would leave the seat slower than this "
                          "seats the valve instead of bouncing (seat_impact)",
                          "m/s")
            .with_default(0.01)
            .positive()
            .at_most(100.0)
            .because("> 0: a speed; <= 100 m/s: far past any valve"),
        ParamSpec::number("coil_bind_stiffness", dim::stiffness,
                          "stiffness of the solid spring (coil bind at the spring's solid length, elastic_drive)", "N/mm")
            .with_default(1e8)
            .at_least(1e4)
            .at_most(1e12)
            .because("10 N/mm to 1e9 N/mm: from soft to solid steel contact"),
        ParamSpec::number("coil_bind_restitution", dim::none,
                          "coefficient of restitution of the valve on the solid spring (rebound speed / impact speed)")
            .with_default(0.5)
            .above(0.0)
            .at_most(1.0)
            .because("> 0 and <= 1: a contact gives energy back, at most all of it"),
        ParamSpec::number("stop_lift", dim::length, "travel_stop: the valve lift at which the stop is met", "mm")
            .optional()
            .positive()
            .at_most(1.0)
            .because("> 0: a lift; <= 1 m: far past any valve"),
        ParamSpec::number("stop_stiffness", dim::stiffness, "travel_stop: stiffness of the stop", "N/mm")
            .with_default(1e8)
            .at_least(1e4)
            .at_most(1e12)
            .because("10 N/mm to 1e9 N/mm: from soft to solid steel contact"),
        ParamSpec::number("stop_restitution", dim::none,
                          "travel_stop: coefficient of restitution of the valve on the stop (rebound speed / impact speed)")
            .with_default(0.3)
            .above(0.0)
            .at_most(1.0)
            .because("> 0 and <= 1: a contact gives energy back, at most all of it"),
    };
    info_.inputs = {
        PortSpec::handle("valve", std::string(ValveMotion::kind_name), "the valve's kinematic motion at the speed simulated"),
        PortSpec::handle("design", std::string(SpringDesign::kind_name), "spring and reduced mass (valvetrain.spring_design)"),
        PortSpec::handle("target", std::string(ValveMotion::kind_name),
                         "optional: the lift the valve should follow (e.g. the law a polydyne cam was made for)")
            .optional_port(),
    };
    info_.outputs = {
        PortSpec::table("curves", "over the last revolution's cam angle: lift x, quasi-static x_qs, kinematic lift, drive "
                                  "displacement y, velocity, contact force, spring force")
            // An impact turns the velocity round and a landing loads the cam at once: both jump at
            // the events' cam angles and are drawn in pieces there.
            .presented(over_cam_angle()
                           .with(ChannelDecl::of("velocity", dim::velocity).flag(channel_flag::jumps_at_events))
                           .with(ChannelDecl::of("contact_force", dim::force).flag(channel_flag::jumps_at_events))),
        PortSpec::scalar("max_deviation", dim::length, "max |x - x_qs| over the last revolution (dense output)", "mm"),
        PortSpec::scalar("residual_amplitude", dim::length, "max |x - x_qs| on the closing side (after the nose)", "mm"),
        PortSpec::scalar("min_contact_force", dim::force,
                         "least cam force while the valve is off its seat (0 if contact is lost). Without contact_loss "
                         "the drive is bilateral: a negative value is a pull no real cam can give, the valve would "
                         "leave the cam there",
                         "N"),
        PortSpec::scalar("seating_velocity", dim::velocity, "speed of the first landing in the last revolution", "m/s"),
        PortSpec::scalar("floats", dim::none, "1 if the valve lost cam contact in the last revolution, else 0"),
        PortSpec::scalar("bounces", dim::none, "bounces on the seat in the last revolution"),
        PortSpec::scalar("bounce_height", dim::length, "highest lift after the first landing of the last revolution", "mm"),
        PortSpec::scalar("target_deviation", dim::length, "max |x - target lift| over the last revolution (with a target)", "mm"),
        PortSpec::scalar("max_spring_force", dim::force,
                         "greatest spring force on the valve over the last revolution (with the solid spring's force at "
                         "coil bind)",
                         "N"),
        PortSpec::scalar("solid_lift", dim::length,
                         "valve lift at which the spring goes solid (coil bind), from the spring's coil geometry", "mm"),
        PortSpec::table("events", "every departure from the cam's law in the last revolution and every jump of the "
                                  "valve's speed or the cam's force, one row each at its cam angle: event 1 contact "
                                  "lost, 2 contact regained (the follower lands on the cam), 3 bounce on the seat, "
                                  "4 seated off the cam or after bounces, 5 coil bind (the spring goes solid), 6 coil "
                                  "bind left, 7 travel stop hit, 8 stop left, 9 landed on the seat with the cam in contact (the law's closing), 10 lash "
                                  "taken up (the cam reaches the seated valve: a rigid drive lifts it at the drive's "
                                  "speed, a unilateral drive's damper loads the cam at once); speed: of approach or "
                                  "separation; cam_force: the cam's force just after; peak_force: the contact's greatest "
                                  "force until it is left (coil bind, stop)")
            .presented(over_cam_angle("cam_angle", Role::events)
                           .with(ChannelDecl::of("event", dim::none).with_codes(event_codes()))),
        PortSpec::series("natural_frequencies", dim::frequency,
                         "of the drive (valve off its seat, cam in contact), lowest first; with spring_surge the coils' too",
                         "Hz"),
    };
    info_.effects = {
        {"elastic_drive", "the drive as a spring-damper between cam and valve (single mass), the spring's coil bind as a "
                          "stiff contact; off: rigid drive",
         {"max_deviation", "residual_amplitude", "natural_frequencies", "solid_lift"},
         {"drive_stiffness", "damping_ratio", "tolerance", "integrator", "revolutions", "coil_bind_stiffness",
          "coil_bind_restitution"}},
        {"travel_stop", "a stop at stop_lift: a stiff contact with its own restitution (needs elastic_drive)", {},
         {"stop_lift", "stop_stiffness", "stop_restitution"}},
        {"contact_loss", "unilateral cam contact: the valve flies free while the drive would pull it (needs elastic_drive)",
         {"floats"}, {}},
        {"seat_impact", "the valve bounces on its seat with a coefficient of restitution (needs elastic_drive)",
         {"bounces", "bounce_height"}, {"restitution", "seating_speed"}},
        {"multi_mass", "tappet, pushrod, rocker and valve as four masses on their own stiffnesses (needs elastic_drive)",
         {}, {"stiffnesses"}},
        {"spring_surge", "the valve spring as a chain of coil masses, its first mode at the surge frequency (needs "
                         "elastic_drive)",
         {}, {"coils", "surge_damping_ratio"}},
    };
    info_.frames = cam_angle_frames(false);
    info_.work_counters = {"steps", "rhs_evaluations", "jacobian_evaluations", "root_evaluations", "rejected_steps",
                           "newton_iterations", "events", "monitor_evaluations", "refinements", "stiffness_ratio",
                           "implicit"};
  }
  const NodeInfo& info() const override { return info_; }

  void evaluate(const ParamSet& p, const InputSet& in, OutputSet& out, EvalContext& ctx) const override {
    const auto motion = in.handle<ValveMotion>("valve");
    const auto design = in.handle<SpringDesign>("design");
    const bool elastic = ctx.effect("elastic_drive");
    for (const char* effect : {"contact_loss", "seat_impact", "multi_mass", "spring_surge", "travel_stop"})
      if (ctx.effect(effect) && !elastic)
        throw NodeError("drive_stiffness", std::string(effect) + " needs the elastic_drive effect as well (a rigid drive "
                                           "has no vibration to show)");
    const double w = motion->camshaft_speed();
    const double period = 2.0 * pi / w;
    const double M = design->reduced_mass;
    const double P0 = design->spring->preload();
    const double c_s = design->spring->stiffness(0.0);
    const long n = p.integer("curve_points");
    const int revolutions = static_cast<int>(p.integer("revolutions"));

    // The curves' cam angles: one revolution from -pi, the nose at 0.
    // (written straight into the curves' axis, which outlives every use below)
    Table curves;
    curves.axis = {"cam_angle", dim::angle, {}, "deg"};
    std::vector<double>& phi = curves.axis.values;
    phi.resize(static_cast<std::size_t>(n));
    for (long j = 0; j < n; ++j) phi[static_cast<std::size_t>(j)] = -pi + 2.0 * pi * static_cast<double>(j) / static_cast<double>(n - 1);

    curves.channels.reserve(8);  // room for tappet_lift (multi_mass): the references below stay valid
    curves.add_channel("lift", dim::length, "mm");
    curves.add_channel("quasi_static_lift", dim::length, "mm");
    curves.add_channel("kinematic_lift", dim::length, "mm");
    curves.add_channel("drive_displacement", dim::length, "mm");
    curves.add_channel("velocity", dim::velocity, "m/s");
    curves.add_channel("contact_force", dim::force, "N");
    curves.add_channel("spring_force", dim::force, "N");
    auto& lift = curves.channels[0].values;  // (references taken once every channel is in place)
    auto& quasi_static = curves.channels[1].values;
    auto& kinematic = curves.channels[2].values;
    auto& drive = curves.channels[3].values;
    auto& velocity = curves.channels[4].values;
    auto& contact = curves.channels[5].values;
    auto& spring = curves.channels[6].values;
    // Each curve written once, at its final size: nothing reallocates while it fills.
    for (std::size_t c = 0; c < 7; ++c) curves.channels[c].values.reserve(phi.size());

    double min_contact = std::numeric_limits<double>::infinity();
    double seating_velocity = 0.0, bounce_height = 0.0, max_dev = 0.0, residual = 0.0, max_spring = 0.0;
    double floats = 0.0, bounces = 0.0;

    if (!elastic) {
      // Rigid drive: the valve follows the cam; the cam must carry inertia and spring.
      for (double a : phi) {
        const LiftDerivatives x = motion->at(a);
        const double force = M * w * w * x.acceleration + P0 + c_s * x.lift;
        lift.push_back(x.lift);
        quasi_static.push_back(x.lift);
        kinematic.push_back(x.lift);
        drive.push_back(motion->drive(a).lift);
        velocity.push_back(w * x.velocity);
        contact.push_back(x.lift > 0.0 ? force : 0.0);
        spring.push_back(P0 + c_s * x.lift);
        if (x.lift > 0.0) min_contact = std::min(min_contact, force);
      }
      seating_velocity = w * std::abs(motion->at(motion->open_end() - 1e-12).velocity);
      out.set("events", Value::table(rigid_events_table(*motion, M, P0)));
      for (const char* counter : {"steps", "rhs_evaluations", "events"}) ctx.report_work(counter, 0.0);
    } else {
      DriveSettings settings;
      settings.multi_mass = ctx.effect("multi_mass");
      if (settings.multi_mass) {
        if (!p.has("stiffnesses")) throw NodeError("stiffnesses", "multi_mass needs stiffnesses (four, valve side)");
        settings.stiffnesses = p.numbers("stiffnesses");
      } else {
        if (!p.has("drive_stiffness")) throw NodeError("drive_stiffness", "elastic_drive needs drive_stiffness");
        settings.stiffness = p.number("drive_stiffness");
      }
      if (ctx.effect("spring_surge")) {
        settings.coils = static_cast<int>(p.integer("coils"));
        settings.surge_damping_ratio = p.number("surge_damping_ratio");
      }
      settings.damping_ratio = p.number("damping_ratio");
      settings.revolutions = revolutions;
      settings.tolerance = p.number("tolerance");
      settings.integrator = p.text("integrator");
      settings.contact_loss = ctx.effect("contact_loss");
      settings.seat_impact = ctx.effect("seat_impact");
      settings.restitution = p.number("restitution");
      settings.seating_speed = p.number("seating_speed");
      // Coil bind: a valve that can leave the cam is watched for it throughout. A bilateral drive
      // holds the valve on the cam, so its run watches only for the greatest lift and is repeated
      // with the coil-bind contact if that reaches the solid length (no cost where it does not).
      settings.coil_bind = settings.contact_loss;
      const double solid_lift = design->spring->solid_deflection();
      settings.coil_bind_stiffness = p.number("coil_bind_stiffness");
      settings.coil_bind_restitution = p.number("coil_bind_restitution");
      settings.stop = ctx.effect("travel_stop");
      if (settings.stop) {
        if (!p.has("stop_lift")) throw NodeError("stop_lift", "travel_stop needs stop_lift (the valve lift of the stop)");
        settings.stop_lift = p.number("stop_lift");
        settings.stop_stiffness = p.number("stop_stiffness");
        settings.stop_restitution = p.number("stop_restitution");
      }
      // The drive's stiffness in series, for the quasi-static lift
      //   x_qs = max(0, (k_d y - P0) / (k_d + c_s)),  x_qs' = k_d y' / (k_d + c_s) where positive.
      double compliance = 0.0;
      for (double k : settings.multi_mass ? settings.stiffnesses : std::vector<double>{settings.stiffness}) compliance += 1.0 / k;
      const double k_d = 1.0 / compliance;
      const double last = (revolutions - 1) * period, nose = last + pi / w;

      // What is followed on the dense output over the last revolution (hybrid_simulation.hpp).
      enum Watched { deviation, closing_deviation, contact_force, spring_force, valve_lift, limit_force, target_gap };
      auto deviation_reading = [=](const ChainModel& model, const Snapshot& x) {
        const std::size_t valve = model.valve(), P = model.positions();
        const double y = x.drive.y, above = k_d * y - P0;
        const double x_qs = above > 0.0 ? above / (k_d + c_s) : 0.0;
        const double x_qs_rate = above > 0.0 ? k_d * x.drive.rate / (k_d + c_s) : 0.0;
        const double d = x.state[valve] - x_qs, d_rate = x.state[P + valve] - x_qs_rate;
        return Reading{std::abs(d), d < 0.0 ? -d_rate : d_rate};
      };
      std::vector<Monitor> watch(7);
      watch[deviation] = {last, period * revolutions, false, true, deviation_reading};
      watch[closing_deviation] = {nose, period * revolutions, false, true, deviation_reading};
      // The cam's force while the valve is off its seat: none without contact.
      watch[contact_force] = {last, period * revolutions, true, false, [](const ChainModel& model, const Snapshot& x) {
                                if (x.mode.seated) return Reading{0.0, 0.0, false};
                                if (!x.mode.contact) return Reading{0.0, 0.0};
                                return Reading{model.pushing_force(x.drive, x.state), model.pushing_force_rate(x)};
                              }};
      watch[spring_force] = {last, period * revolutions, false, true, [](const ChainModel& model, const Snapshot& x) {
                               return Reading{model.spring_force(x.state, x.mode.engaged), model.spring_force_rate(x)};
                             }};
      // The lift limits' force while one is engaged: its peak per engagement for the events table.
      watch[limit_force] = {last, period * revolutions, false, true, [](const ChainModel& model, const Snapshot& x) {
                              if (!x.mode.engaged) return Reading{0.0, 0.0, false};
                              Reading r;
                              for (std::size_t i = 0; i < model.params().limits.size(); ++i)
                                if (x.mode.engaged & (1u << i)) {
                                  r.value += model.limit_force(i, x.state);
                                  r.rate += model.limit_force_rate(i, x);
                                }
                              return r;
                            }};
      // (a massless spring's force gives the greatest lift; coil masses need the lift followed)
      const bool follow_lift = settings.seat_impact || (!settings.coil_bind && settings.coils > 0);
      watch[valve_lift] = {last, period * revolutions, false, follow_lift,
                           [](const ChainModel& model, const Snapshot& x) {
                             return Reading{x.state[model.valve()], x.state[model.positions() + model.valve()]};
                           }};
      std::shared_ptr<const ValveMotion> target;
      if (in.count("target")) {
        target = in.handle<ValveMotion>("target");
        const ValveMotion* law = target.get();
        watch[target_gap] = {last, period * revolutions, false, true, [=](const ChainModel& model, const Snapshot& x) {
                               const LiftDerivatives aim = law->at(-pi + w * (x.t - last));
                               const double d = x.state[model.valve()] - aim.lift;
                               const double rate = x.state[model.positions() + model.valve()] - w * aim.velocity;
                               return Reading{std::abs(d), d < 0.0 ? -rate : rate};
                             }};
      } else {
        watch.pop_back();
      }

      ValveSimulation sim = simulate_valve(*motion, *design, settings, phi, watch);
      const double greatest_lift = settings.coils > 0 ? greatest_of(sim.run.extremes[valve_lift]).value
                                                      : (greatest_of(sim.run.extremes[spring_force]).value - P0) / c_s;
      if (!settings.coil_bind && greatest_lift >= solid_lift) {
        settings.coil_bind = true;
        recycle(std::move(sim.run));
        sim = simulate_valve(*motion, *design, settings, phi, watch);
      }
      const SimulationResult& run = sim.run;
      if (run.state.size() != phi.size())
        throw std::logic_error("the simulation returned " + std::to_string(run.state.size()) + " states for " +
                               std::to_string(phi.size()) + " curve points");
      const ChainModel& model = sim.model;
      const std::size_t v = model.valve(), P = model.positions();
      std::vector<double> frequencies;
      for (double omega : natural_frequencies(model.params())) frequencies.push_back(omega / (2.0 * pi));
      Series modes;
      modes.values = frequencies;
      for (std::size_t i = 0; i < frequencies.size(); ++i) modes.axis.push_back(static_cast<double>(i + 1));
      out.set("natural_frequencies", Value::series(std::move(modes)));
      std::vector<double>* tappet = nullptr;
      if (settings.multi_mass) {
        curves.add_channel("tappet_lift", dim::length, "mm");
        tappet = &curves.channels.back().values;
        tappet->reserve(phi.size());
      }
      for (const auto& [counter, amount] : run.work) ctx.report_work(counter, amount);
      // Which integrator ran, and how stiff the chain is at the step cap (what `auto` decides on).
      ctx.report_work("stiffness_ratio", sim.choice.stiffness_ratio);
      ctx.report_work("implicit", sim.integrator == "cvode" ? 1.0 : 0.0);
      if (settings.integrator == "auto") out.note("integrator auto: " + sim.choice.reason());

      double first_landing = std::numeric_limits<double>::infinity();
      for (const EventRecord& e : run.events) {
        ctx.log(LogLevel::debug, "revolution " + std::to_string(static_cast<int>(e.t / period) + 1) + ", cam angle " +
                                     printf_g((-pi + w * std::fmod(e.t, period)) * 180.0 / pi) + " deg: " + e.kind +
                                     (e.speed > 0.0 ? " at " + printf_g(e.speed) + " m/s" : ""));
        if (e.t < last) continue;
        if (e.kind == "contact_loss") floats = 1.0;
        if (e.kind == "bounce") bounces += 1.0;
        if ((e.kind == "landing" || e.kind == "bounce") && e.t < first_landing) {
          first_landing = e.t;
          seating_velocity = e.speed;
        }
      }
      if (std::isfinite(solid_lift)) out.set_scalar("solid_lift", solid_lift);
      Table events = events_table(run, run.extremes[limit_force], last, w, period);
      if (settings.contact_loss && model.rigid_when_seated()) add_lash_take_up(events, *motion, sim, phi);
      out.set("events", Value::table(std::move(events)));
      describe_events(run, last, w, out);
      ChainState s;
      for (std::size_t j = 0; j < phi.size(); ++j) {
        s.assign(run.state[j].begin(), run.state[j].end());
        const Mode& mode = run.mode[j];
        const double x = s[v];
        // One cam evaluation per point: the drive y = i h - lash, and from it (the ValveMotion
        // contract) the kinematic lift, max(0, y) over the open period and 0 outside it.
        const LiftDerivatives cam = motion->drive(phi[j]);
        const double y = cam.lift;
        const DriveValue at_point{y, w * cam.velocity, w * w * cam.acceleration};
        const bool open = phi[j] >= motion->open_begin() && phi[j] <= motion->open_end();
        const double x_qs = std::max(0.0, (k_d * y - P0) / (k_d + c_s));
        // The cam's force: none without contact, none across an open lash while a lone valve sits.
        const double force = mode.seated && model.rigid_when_seated() ? std::max(0.0, model.pushing_force(at_point, s))
                             : !mode.contact                            ? 0.0
                                                                        : model.pushing_force(at_point, s);
        lift.push_back(x);
        quasi_static.push_back(x_qs);
        kinematic.push_back(open ? std::max(0.0, y) : 0.0);
        drive.push_back(y);
        velocity.push_back(s[P + v]);
        contact.push_back(force);
        spring.push_back(model.spring_force(s, mode.engaged));
        if (tappet) tappet->push_back(s[0]);
      }
      const auto& extremes = run.extremes;
      max_dev = std::max(0.0, greatest_of(extremes[deviation]).value);
      residual = std::max(0.0, greatest_of(extremes[closing_deviation]).value);
      min_contact = least_of(extremes[contact_force]).value;  // +inf: never off the seat
      max_spring = greatest_of(extremes[spring_force]).value;
      // Bounces: the valve's highest lift after the first landing of the last revolution.
      if (std::isfinite(first_landing)) bounce_height = std::max(0.0, greatest_of(extremes[valve_lift], first_landing).value);
      if (target) out.set_scalar("target_deviation", greatest_of(extremes[target_gap]).value);
      recycle(std::move(sim.run));  // its buffers serve this thread's next simulation
      out.set_scalar("max_deviation", max_dev);
      out.set_scalar("residual_amplitude", residual);
      if (settings.contact_loss) out.set_scalar("floats", floats);
      if (settings.seat_impact) {
        out.set_scalar("bounces", bounces);
        out.set_scalar("bounce_height", bounce_height);
      }
    }
    if (!elastic && in.count("target")) {
      const auto target = in.handle<ValveMotion>("target");
      double worst = 0.0;
      for (std::size_t j = 0; j < phi.size(); ++j) worst = std::max(worst, std::abs(lift[j] - target->at(phi[j]).lift));
      out.set_scalar("target_deviation", worst);
    }
    if (!std::isfinite(min_contact)) min_contact = 0.0;  // never off the seat
    if (min_contact < 0.0 && !ctx.effect("contact_loss")) {
      out.note("bilateral drive: the least cam force, " + printf_f(min_contact, 0) +
               " N, is a pull that no real cam can give; there the valve would leave the cam (switch on contact_loss "
               "to simulate it)");
    }
    if (!elastic) max_spring = *std::max_element(spring.begin(), spring.end());
    out.set_scalar("max_spring_force", max_spring);
    out.set_scalar("min_contact_force", min_contact);
    out.set_scalar("seating_velocity", seating_velocity);
    out.set("curves", Value::table(std::move(curves)));
  }

 private:
  NodeInfo info_;
};

}  // namespace

std::shared_ptr<const NodeType> make_dynamics_type() { return std::make_shared<const DynamicsType>(); }

}  // namespace mechgraph::valvetrain
