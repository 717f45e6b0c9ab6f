// A node type from outside the built-in set, with names of its own and its own declared
// presentation (presentation.hpp): a pump plunger driven by a shaft, its position and two
// derivatives over shaft angle as one derivative family, a second frame (rotor angle = 3 x shaft
// angle + phase, marked every 120 deg as P1, P2, P3), a table of port events with named codes whose
// angles are drawn as points on the family, a scalar angle in the shaft frame, and a note made
// with the port events when `phase` is given, and a plain table (no role) with a figure title of
// its own: the gap at the plunger's two seals over shaft angle. The host's reports know none of these names
// (tests/cli/foreign_presentation_test.cpp). Built twice: with the pre-1.0 entry (C++ classes
// cross) and, with STROKE_SDK1, through the SDK 1.x C boundary, where every declaration crosses as
// the C structs of c/present.h; the host must present both alike.
#ifdef STROKE_SDK1
#include <mechgraph/plugin_sdk1.hpp>
#else
#include <mechgraph/plugin_abi.hpp>
#endif

#include <cmath>
#include <numbers>

namespace {

using namespace mechgraph;
constexpr double pi = std::numbers::pi;

class Stroke final : public NodeType {
 public:
  Stroke() {
    info_.type = "pump.stroke";
    info_.summary = "plunger position of a shaft-driven pump over shaft angle";
    info_.work_counters = {"points"};
    info_.params = {ParamSpec::number("stroke", dim::length, "plunger stroke", "mm").with_default(0.02).positive(),
                    ParamSpec::number("phase", dim::angle, "rotor angle at shaft angle 0", "deg").optional(),
                    ParamSpec::integer("points", "rows of the motion table").with_default(181.0).at_least(16).at_most(1e5)};
    AngleFrame shaft;
    shaft.id = "shaft";
    shaft.label = "shaft angle from the top";
    shaft.unit_tag = "shaft";
    shaft.zero = "the plunger at the top";
    AngleFrame rotor;
    rotor.id = "rotor";
    rotor.label = "rotor angle after port one";
    rotor.unit_tag = "rotor";
    rotor.zero = "port one open";
    rotor.base_frame = "shaft";
    rotor.scale = 3.0;
    rotor.offset_param = "phase";
    rotor.mark_spacing = 2.0 * pi / 3.0;
    rotor.mark_labels = {"P1", "P2", "P3"};
    rotor.before = "-";
    rotor.after = "+";
    info_.frames = {shaft, rotor};
    info_.notes = {{"port_events", "phase", "where the ports open, quoted from the nearest port mark"}};

    Presentation motion;
    motion.role = Role::derivative_family;
    motion.figure_title = "Plunger position, speed and acceleration";
    motion.with_axis(ChannelDecl::of("shaft_angle", dim::angle).in_frame("shaft"));
    motion.with(ChannelDecl::of("rotor_angle", dim::angle).in_frame("rotor").flag(channel_flag::alt_axis));
    motion.with(ChannelDecl::of("position").derivative(0).labelled("plunger position"));
    motion.with(ChannelDecl::of("speed").derivative(1).in_frame("shaft"));
    motion.with(ChannelDecl::of("accel").derivative(2).in_frame("shaft").labelled("acceleration"));
    PointMarks ports;
    ports.port = "port_events";
    ports.x_channels = {"opens_rotor", "closes_rotor"};
    ports.labels = {"opens", "closes"};
    ports.caption = "ports at {axis} travel";
    motion.points.push_back(ports);

    Presentation events;
    events.role = Role::events;
    events.with_axis(ChannelDecl::of("travel", dim::length));
    events.with(ChannelDecl::of("kind").with_codes({{1.0, "suction_port", "the suction port opens"}, {2.0, "delivery_port", "the delivery port opens"}}));
    events.with(ChannelDecl::of("opens_shaft", dim::angle).in_frame("shaft").labelled("opening"));
    events.with(ChannelDecl::of("opens_rotor", dim::angle).in_frame("rotor").labelled("opening on the rotor"));
    events.with(ChannelDecl::of("closes_rotor", dim::angle).in_frame("rotor").labelled("closing on the rotor"));

    Presentation gaps;  // plain: a plot per dimension, titled as declared
    gaps.figure_title = "Seal gaps over a turn";
    gaps.with_axis(ChannelDecl::of("shaft_angle", dim::angle).in_frame("shaft"));

    info_.outputs = {PortSpec::table("motion", "position, speed and acceleration over shaft angle").presented(motion),
                     PortSpec::table("gaps", "the gap at the upper and the lower seal over shaft angle").presented(gaps),
                     PortSpec::table("port_events", "where the ports open and close, a row per port").presented(events),
                     PortSpec::scalar("peak_angle", dim::angle, "shaft angle of the greatest speed", "deg").in_frame("shaft")};
  }
  const NodeInfo& info() const override { return info_; }

  void evaluate(const ParamSet& p, const InputSet&, OutputSet& out, EvalContext& ctx) const override {
    const double h = p.number("stroke");
    const auto n = static_cast<std::size_t>(p.integer("points"));
    Table t;
    t.axis = {"shaft_angle", dim::angle, {}, "deg"};
    t.add_channel("rotor_angle", dim::angle, "deg");
    t.add_channel("position", dim::length, "mm");
    t.add_channel("speed", dim::length / dim::angle, "mm/deg");
    t.add_channel("accel", dim::length / dim::angle.pow(2), "mm/deg^2");
    for (std::size_t i = 0; i < n; ++i) {
      const double a = -pi + 2.0 * pi * static_cast<double>(i) / static_cast<double>(n - 1);
      t.axis.values.push_back(a);
      t.channels[0].values.push_back(3.0 * a);
      t.channels[1].values.push_back(0.5 * h * (1.0 + std::cos(a)));
      t.channels[2].values.push_back(-0.5 * h * std::sin(a));
      t.channels[3].values.push_back(-0.5 * h * std::cos(a));
    }
    ctx.report_work("points", static_cast<double>(n));
    out.set("motion", Value::table(std::move(t)));
    if (ctx.wanted("gaps")) {
      Table g;
      g.axis = {"shaft_angle", dim::angle, {}, "deg"};
      g.add_channel("upper_gap", dim::length, "mm");
      g.add_channel("lower_gap", dim::length, "mm");
      for (std::size_t i = 0; i < n; ++i) {
        const double a = -pi + 2.0 * pi * static_cast<double>(i) / static_cast<double>(n - 1);
        g.axis.values.push_back(a);
        g.channels[0].values.push_back(1e-5 * (1.0 + 0.5 * std::sin(a)));
        g.channels[1].values.push_back(1e-5 * (1.0 - 0.5 * std::sin(a)));
      }
      out.set("gaps", Value::table(std::move(g)));
    }
    out.set_scalar("peak_angle", -pi / 2.0);
    if (ctx.wanted("port_events")) {
      const double phase = p.has("phase") ? p.number("phase") : 0.0;
      Table e;
      e.axis = {"travel", dim::length, {0.25 * h, 0.75 * h}, "mm"};
      e.add_channel("kind", dim::none).values = {1.0, 2.0};
      e.add_channel("opens_shaft", dim::angle, "deg").values = {-pi / 3.0, pi / 6.0};
      e.add_channel("opens_rotor", dim::angle, "deg").values = {phase - pi, phase + pi / 2.0};
      e.add_channel("closes_rotor", dim::angle, "deg").values = {phase + 0.1, phase + 2.0};
      out.set("port_events", Value::table(std::move(e)));
      if (p.has("phase")) out.note("ports: suction opens at rotor angle " + std::to_string(std::lround((phase - pi) * 180.0 / pi)) + " deg");
    }
  }

 private:
  NodeInfo info_;
};

NodeTypeList make_types() { return {std::make_shared<Stroke>()}; }

}  // namespace

#ifdef STROKE_SDK1
MECHGRAPH_PLUGIN_1("test_stroke", "0.1.0", &make_types)
#else
MECHGRAPH_PLUGIN("test_stroke", "0.1.0", &make_types)
#endif
