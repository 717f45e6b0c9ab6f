#include <mechgraph/domain/cam_curves.hpp>

#include <mechgraph/errors.hpp>
#include <mechgraph/numerics/piecewise.hpp>
#include <mechgraph/printf_number.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <numbers>

namespace mechgraph {

Table svaj_table(const CamLaw& law, int points) {
  return svaj_table([&](double phi) { return law.at(phi); }, law.event_begin(), law.event_end(), points);
}

Table svaj_table(const std::function<LiftDerivatives(double)>& at, double begin, double end, int points) {
  const double width = end - begin;
  const double from = std::max(-std::numbers::pi, begin - 0.1 * width);
  const double to = std::min(std::numbers::pi, end + 0.1 * width);
  const auto n = static_cast<std::size_t>(std::max(points, 2));
  Table t;
  t.axis = {"cam_angle", dim::angle, std::vector<double>(n), "deg"};
  t.add_channel("crank_angle", dim::angle, "deg");
  t.add_channel("lift", dim::length, "mm");
  t.add_channel("velocity", dim::length / dim::angle, "mm/deg");
  t.add_channel("acceleration", dim::length / dim::angle.pow(2), "mm/deg^2");
  t.add_channel("jerk", dim::length / dim::angle.pow(3), "mm/deg^3");
  std::vector<double>* column[5];
  for (std::size_t k = 0; k < 5; ++k) column[k] = &t.channels[k].values;
  for (auto* c : column) c->resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    // The last point exactly at `to`: no rounding past +-pi.
    const double phi = i + 1 == n ? to : from + (to - from) * static_cast<double>(i) / static_cast<double>(n - 1);
    const LiftDerivatives d = at(phi);
    t.axis.values[i] = phi;
    (*column[0])[i] = 2.0 * phi;
    (*column[1])[i] = d.lift;
    (*column[2])[i] = d.velocity;
    (*column[3])[i] = d.acceleration;
    (*column[4])[i] = d.jerk;
  }
  return t;
}

namespace {

// The events from the crossings of one checking lift: the first and the last.
std::optional<LiftEvents> events_from(const std::vector<double>& crossings) {
  if (crossings.empty()) return std::nullopt;
  LiftEvents e;
  e.opening = crossings.front();
  e.closing = crossings.size() > 1 ? crossings.back() : crossings.front();
  e.duration = e.closing - e.opening;
  e.centreline = 0.5 * (e.opening + e.closing);
  return e;
}

// Where the lift passes `h` between `from` (lift below or at h: a seat) and `to` (lift above it),
// on the lift itself: scanned from `from` at distances halving down to 2^-60 of the span (the
// first point above h nearest the seat), then bisected to neighbouring doubles. Used for a
// crossing the interpolants cannot sign: a checking lift at the lift's rounding level (16 ulps of
// its largest value), where near the seat lift - h is a zone of rounding. The lift is 0 at the
// event's ends (the CamLaw contract), so the first crossing rises and the last falls.
double crossing_from_seat(const std::function<double(double)>& lift, double from, double to, double h) {
  double below = from, above = to;
  for (int k = 60; k >= 1; --k) {
    const double x = from + (to - from) * std::ldexp(1.0, -k);
    if (lift(x) > h) {
      above = x;
      break;
    }
    below = x;
  }
  while (true) {
    const double mid = 0.5 * (below + above);
    if (mid == below || mid == above) break;
    (lift(mid) > h ? above : below) = mid;
  }
  return 0.5 * (below + above);
}

}  // namespace

std::optional<LiftEvents> events_at_lift(const std::function<double(double)>& lift, std::span<const double> knots,
                                         double checking_lift, int samples, long& evaluations) {
  return events_from(numerics::all_sign_changes([&](double phi) { return lift(phi) - checking_lift; }, knots, samples,
                                                evaluations));
}

std::optional<LiftEvents> events_at_lift(const CamLaw& law, double checking_lift, int samples, long& evaluations) {
  return events_at_lift([&](double phi) { return law.at(phi).lift; }, law.knots(), checking_lift, samples, evaluations);
}

double nose_angle(const std::function<double(double)>& lift, std::span<const double> knots, int samples, long& evaluations) {
  numerics::SmoothPieces pieces([&](double phi, double* v, double*) { v[0] = lift(phi); }, 1, knots, samples);
  const numerics::Extremum top = pieces.maximum(0);
  double nose = top.x;
  if (top.value > 0.0) {
    // A dwell at full lift: the pieces (between knots) on which the lift holds the top, read at
    // both one-sided ends and the middle (a dwell returns its height; 4 ulps allow the top a
    // rounding above it at a flank's end). The nose is then exactly halfway between the first such
    // piece's start and the last one's end: the dwell's middle, not some point of the plateau.
    const double tolerance = 4.0 * std::numeric_limits<double>::epsilon() * top.value;
    std::optional<double> dwell_begin, dwell_end;
    for (std::size_t p = 0; p + 1 < knots.size(); ++p) {
      const double a = knots[p], b = knots[p + 1];
      if (!(b > a) || !numerics::has_interior(a, b)) continue;
      bool holds = true;
      for (const double x : {numerics::one_sided_point(a, b), 0.5 * (a + b), numerics::one_sided_point(b, a)}) {
        ++evaluations;
        if (!(std::abs(lift(x) - top.value) <= tolerance)) {
          holds = false;
          break;
        }
      }
      if (!holds) continue;
      if (!dwell_begin) dwell_begin = a;
      dwell_end = b;
    }
    if (dwell_begin) {
      evaluations += pieces.work().evaluations;
      return 0.5 * (*dwell_begin + *dwell_end);
    }
    // A plateau without knots or a second equal maximum: the middle of where the lift is
    // within 1e-13 of the top (above the interpolation's rounding), when that spans more than 1e-3 rad (a
    // smooth top, even one as flat as a cubic's, is far narrower, and its maximum is the search's
    // own). Flanks that leave a dwell as flat as a cubic widen it by some 1e-5 rad, unevenly.
    const std::vector<double> near = pieces.crossings(0, top.value * (1.0 - 1e-13));
    if (near.size() >= 2 && near.back() - near.front() > 1e-3) nose = 0.5 * (near.front() + near.back());
  }
  evaluations += pieces.work().evaluations;
  return nose;
}

Table events_table(const std::function<double(double)>& lift, std::span<const double> knots,
                   const std::vector<double>& checking_lifts, int samples, long& evaluations,
                   std::optional<double> nose_timing, double nose) {
  Table t;
  t.axis = {"checking_lift", dim::length, {}, "mm"};
  const char* names[8] = {"opening",       "closing",       "duration",       "centreline",
                          "crank_opening", "crank_closing", "crank_duration", "crank_centreline"};
  for (const char* n : names) t.add_channel(n, dim::angle, "deg");
  if (nose_timing)
    for (const char* n : {"opening_atdc", "closing_atdc", "centreline_atdc"}) t.add_channel(n, dim::angle, "deg");
  // One interpolation of the lift answers every checking lift.
  std::optional<numerics::SmoothPieces> pieces;
  for (double h : checking_lifts) {
    std::optional<LiftEvents> e;
    if (h == 0.0) {
      e = LiftEvents{knots.front(), knots.back(), knots.back() - knots.front(), 0.5 * (knots.front() + knots.back())};
    } else {
      if (!pieces) pieces.emplace([&](double phi, double* v, double*) { v[0] = lift(phi); }, 1, knots, samples);
      std::vector<std::pair<double, bool>> xs = pieces->directed_crossings(0, h);
      if (lift(nose) > h) {
        // A checking lift at the rounding level of the lift: the interpolants see a zone at the
        // seat and miss the crossing nearest it; it is found on the lift itself.
        if (xs.empty() || !xs.front().second) xs.insert(xs.begin(), {crossing_from_seat(lift, knots.front(), nose, h), true});
        if (xs.back().second) xs.push_back({crossing_from_seat(lift, knots.back(), nose, h), false});
      }
      std::vector<double> crossings;
      for (const auto& x : xs) crossings.push_back(x.first);
      e = events_from(crossings);
    }
    if (!e) continue;
    t.axis.values.push_back(h);
    const double cam[4] = {e->opening, e->closing, e->duration, e->centreline - nose};
    for (std::size_t k = 0; k < 4; ++k) {
      t.channels[k].values.push_back(cam[k]);
      t.channels[k + 4].values.push_back(2.0 * cam[k]);
    }
    if (nose_timing) {
      // Crank angle after the overlap TDC: the nose's, plus twice the cam angle from the nose.
      t.channels[8].values.push_back(*nose_timing + 2.0 * (e->opening - nose));
      t.channels[9].values.push_back(*nose_timing + 2.0 * (e->closing - nose));
      t.channels[10].values.push_back(*nose_timing + 2.0 * (e->centreline - nose));
    }
  }
  if (pieces) evaluations += pieces->work().evaluations;
  return t;
}

namespace {

std::string degrees(double rad) { return printf_f(std::abs(rad) * 180.0 / std::numbers::pi, 1) + " deg"; }

// An angle after the overlap TDC as "x deg BTDC/ATDC" about `dead_centre` (0 for TDC, +-pi for BDC).
std::string about(double after_tdc, double dead_centre, const char* centre) {
  const double from = after_tdc - dead_centre;
  return degrees(from) + (from < 0.0 ? " B" : " A") + centre;
}

}  // namespace

std::string quote_events(const LiftEvents& e, double nose_timing, double nose) {
  const double pi = std::numbers::pi;
  const double opening = nose_timing + 2.0 * (e.opening - nose), closing = nose_timing + 2.0 * (e.closing - nose);
  // An intake opens about the overlap TDC and closes about the BDC after it; an exhaust opens about
  // the BDC before that TDC and closes about the TDC.
  if (nose_timing >= 0.0) return "intake: opens " + about(opening, 0.0, "TDC") + ", closes " + about(closing, pi, "BDC");
  return "exhaust: opens " + about(opening, -pi, "BDC") + ", closes " + about(closing, 0.0, "TDC");
}

ParamSpec checking_lift_param(const std::string& whose) {
  return ParamSpec::number("checking_lift", dim::length,
                           "lift of the " + whose + " at which the events (opening, closing, duration, centreline) are "
                           "measured; the events table adds 0.050 in and the seat (zero lift)",
                           "mm")
      .with_default(1e-3)
      .positive()
      .because("> 0: the seat (zero lift) is the events table's own row");
}

ParamSpec nose_timing_param() {
  return ParamSpec::number("nose_timing", dim::angle,
                           "installed lobe: crank angle of the nose (the maximum lift, also on an asymmetric lobe) "
                           "after the overlap TDC (intake positive, about 100 to 115 deg; exhaust negative); the events "
                           "table then adds opening_atdc, closing_atdc, centreline_atdc and a note quotes the events "
                           "from TDC and BDC",
                           "deg")
      .optional()
      .at_least(-2.0 * std::numbers::pi)
      .at_most(2.0 * std::numbers::pi)
      .because("-360 to 360 deg: one turn of the crank either way of the overlap TDC");
}

std::vector<AngleFrame> cam_angle_frames(bool installed) {
  AngleFrame cam;
  cam.id = "cam";
  cam.label = "cam angle from the nose";
  cam.unit_tag = "cam";
  cam.zero = "the law's zero: the nose of a symmetric lobe";
  AngleFrame crank;
  crank.id = "crank";
  crank.label = "crank angle after the overlap TDC";
  crank.unit_tag = "crank";
  crank.zero = installed ? "the overlap TDC when nose_timing is given (crank = 2 cam + nose_timing), else twice the cam's zero"
                        : "twice the cam's zero";
  crank.base_frame = "cam";
  crank.scale = 2.0;
  if (installed) crank.offset_param = "nose_timing";
  crank.mark_spacing = std::numbers::pi;
  crank.mark_labels = {"TDC", "BDC"};
  crank.before = "B";
  crank.after = "A";
  std::vector<AngleFrame> frames;  // moved in: a braced list would copy both
  frames.reserve(2);
  frames.push_back(std::move(cam));
  frames.push_back(std::move(crank));
  return frames;
}

NoteDecl timing_note() {
  return {"events", "nose_timing", "the events quoted from TDC and BDC (\"intake: opens 3.4 deg ATDC, ...\")"};
}

PortSpec svaj_port(std::string name, std::string doc) {
  Presentation p;
  p.role = Role::derivative_family;
  p.figure_title = "Lift, velocity, acceleration and jerk";
  p.with_axis(ChannelDecl::of("cam_angle", dim::angle).in_frame("cam"));
  p.with(ChannelDecl::of("crank_angle", dim::angle).in_frame("crank").flag(channel_flag::alt_axis));
  const char* names[] = {"lift", "velocity", "acceleration", "jerk"};
  for (int k = 0; k < 4; ++k) p.with(ChannelDecl::of(names[k]).in_frame("cam").derivative(k));
  PointMarks events;
  events.port = "events";
  events.x_channels = {"opening_atdc", "closing_atdc"};
  events.labels = {"opens", "closes"};
  events.caption = "events at {axis} lift";
  p.points.push_back(std::move(events));
  PortSpec port = PortSpec::table(std::move(name), std::move(doc));
  port.presented(std::move(p));
  return port;
}

Presentation over_cam_angle(std::string axis, Role role) {
  Presentation p;
  p.role = role;
  p.with_axis(ChannelDecl::of(std::move(axis), dim::angle).in_frame("cam"));
  return p;
}

std::vector<PortSpec> lift_event_ports(const std::string& whose) {
  Presentation events;
  events.role = Role::events;
  events.with_axis(ChannelDecl::of("checking_lift", dim::length));
  for (const char* n : {"opening", "closing", "duration", "centreline"}) events.with(ChannelDecl::of(n, dim::angle).in_frame("cam"));
  for (const char* n : {"crank_opening", "crank_closing", "crank_duration", "crank_centreline"})
    events.with(ChannelDecl::of(n, dim::angle).in_frame("crank"));
  for (const char* n : {"opening", "closing", "centreline"})
    events.with(ChannelDecl::of(std::string(n) + "_atdc", dim::angle).labelled(std::string(n) + " after TDC").in_frame("crank"));
  // Each port moved into the list: a braced list, or a push_back of what the fluent setters return
  // (a reference), would copy it with its presentation.
  std::vector<PortSpec> ports;
  ports.reserve(9);
  const auto add = [&ports](PortSpec& port) { ports.push_back(std::move(port)); };
  add(PortSpec::table("events", "opening, closing, duration and centreline of the " + whose +
                                    " in cam and crank angle at checking_lift, 0.050 in and the seat, a row per "
                                    "checking lift reached (with nose_timing also from the overlap TDC)")
          .presented(std::move(events)));
  add(PortSpec::scalar("opening_angle", dim::angle, "cam angle where the " + whose + " lift rises through checking_lift", "deg").in_frame("cam"));
  add(PortSpec::scalar("closing_angle", dim::angle, "cam angle where the " + whose + " lift falls through checking_lift", "deg").in_frame("cam"));
  add(PortSpec::scalar("duration", dim::angle, "cam angle between opening and closing at checking_lift", "deg").in_frame("cam"));
  add(PortSpec::scalar("crank_duration", dim::angle, "duration at checking_lift in crank degrees (2 x cam)", "deg").in_frame("crank"));
  add(PortSpec::scalar("centreline", dim::angle,
                       "halfway between opening and closing at checking_lift, cam angle from the nose (0 on a symmetric "
                       "lobe)",
                       "deg")
          .in_frame("cam"));
  add(PortSpec::scalar("nose_angle", dim::angle,
                       "cam angle of the maximum " + whose + " lift (the nose), from the law's zero (the svaj axis); "
                       "on a dwell at full lift, the dwell's middle, exactly halfway between its ends",
                       "deg")
          .in_frame("cam"));
  add(PortSpec::scalar("event_centre", dim::angle,
                       "halfway between the ends of the lift event (seat to seat), cam angle from the nose", "deg")
          .in_frame("cam"));
  return ports;
}

bool lift_events_wanted(const EvalContext& ctx) {
  for (const char* port : {"events", "opening_angle", "closing_angle", "duration", "crank_duration", "centreline",
                           "nose_angle", "event_centre"})
    if (ctx.wanted(port)) return true;
  return false;
}

void set_lift_events(OutputSet& out, const EvalContext& ctx, const ParamSet& p, const std::function<double(double)>& lift,
                     std::span<const double> knots, double max_lift, const std::string& whose, int samples,
                     long& evaluations) {
  const double checking_lift = p.number("checking_lift");
  std::optional<double> nose_timing;
  if (p.has("nose_timing")) nose_timing = p.number("nose_timing");
  // The last row (0) is seat to seat: the event's ends. The first, when reached, is the checking
  // lift's: the scalars are read from it (one root search each, not two).
  const std::vector<double> lifts{checking_lift, checking_lift_0050_in, 0.0};
  const double nose = nose_angle(lift, knots, samples, evaluations);
  out.set_scalar("nose_angle", nose);
  out.set_scalar("event_centre", 0.5 * (knots.front() + knots.back()) - nose);
  Table table = events_table(lift, knots, lifts, samples, evaluations, nose_timing, nose);
  std::optional<LiftEvents> e;
  if (!table.axis.values.empty() && table.axis.values.front() == checking_lift)
    e = LiftEvents{table.channels[0].values[0], table.channels[1].values[0], table.channels[2].values[0],
                   table.channels[3].values[0]};  // centreline from the nose (opening, closing from the law's zero)
  if (ctx.wanted("events")) out.set("events", Value::table(std::move(table)));
  if (!e) {
    const std::string m = "checking_lift " + printf_g(checking_lift * 1e3) + " mm is not below the " + whose + "'s lift " +
                          printf_g(max_lift * 1e3) + " mm: the events need a checking lift the " + whose + " reaches";
    for (const char* port : {"opening_angle", "closing_angle", "duration", "crank_duration", "centreline"})
      if (ctx.wanted(port)) throw NodeError("checking_lift", m);
    out.note(m + " (the events table has only the rows of the lifts reached)");
    return;
  }
  out.set_scalar("opening_angle", e->opening);
  out.set_scalar("closing_angle", e->closing);
  out.set_scalar("duration", e->duration);
  out.set_scalar("crank_duration", 2.0 * e->duration);
  out.set_scalar("centreline", e->centreline);  // the table's, already from the nose
  if (nose_timing) {
    out.note(quote_events(*e, *nose_timing, nose) + " at " + printf_g(checking_lift * 1e3) + " mm " + whose + " lift");
  }
}

}  // namespace mechgraph
