#include "program_law.hpp"
#include "registration.hpp"

#include <mechgraph/domain/cam_curves.hpp>
#include <mechgraph/errors.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>

namespace mechgraph::cams {
namespace {
constexpr double pi = std::numbers::pi;
}

std::string segment_kind_name(CamSegment::Kind k) {
  switch (k) {
    case CamSegment::Kind::rise: return "rise";
    case CamSegment::Kind::dwell: return "dwell";
    case CamSegment::Kind::ret: return "return";
  }
  return "?";
}

ProgramLaw::ProgramLaw(std::vector<CamSegment> segments, double base_radius)
    : segments_(std::move(segments)), base_radius_(base_radius) {
  if (segments_.empty()) throw NodeError("segments", "a cam program needs at least one segment");
  double total = 0.0, h = 0.0;
  for (std::size_t k = 0; k < segments_.size(); ++k) {
    const CamSegment& s = segments_[k];
    std::ostringstream where;
    where << "segment " << k + 1 << " (" << segment_kind_name(s.kind) << ")";
    if (!(s.angle > 0.0) || !std::isfinite(s.angle)) throw NodeError("segments", where.str() + ": angle must be > 0");
    if (s.kind != CamSegment::Kind::dwell && !(s.lift > 0.0 && std::isfinite(s.lift)))
      throw NodeError("segments", where.str() + ": a rise or return needs lift > 0");
    total += s.angle;
    height_.push_back(h);
    if (s.kind == CamSegment::Kind::rise) h += s.lift;
    if (s.kind == CamSegment::Kind::ret) h -= s.lift;
    max_lift_ = std::max(max_lift_, h);
    if (h < -1e-12 * std::max(max_lift_, 1e-3)) {
      std::ostringstream m;
      m << where.str() << " takes the lift to " << h * 1e3 << " mm: a return may take back only what the rises lifted";
      throw NodeError("segments", m.str());
    }
  }
  if (!(total < 2.0 * pi)) {
    std::ostringstream m;
    m << "the segments span " << total * 180.0 / pi << " deg; a lift event must stay below 360 deg (the rest is base circle)";
    throw NodeError("segments", m.str());
  }
  if (std::abs(h) > 1e-12 * std::max(max_lift_, 1e-3)) {
    std::ostringstream m;
    m << "the program ends at lift " << h * 1e3 << " mm, not 0: the returns must take back what the rises lift";
    throw NodeError("segments", m.str());
  }
  if (!(max_lift_ > 0.0)) throw NodeError("segments", "the program never lifts: it needs a rise");
  begin_ = -0.5 * total;
  end_ = 0.5 * total;
  double phi = begin_;
  for (const CamSegment& s : segments_) {
    start_.push_back(phi);
    phi += s.angle;
  }
}

LiftDerivatives ProgramLaw::on_segment(std::size_t k, double x) const {
  const CamSegment& s = segments_[k];
  if (s.kind == CamSegment::Kind::dwell) return {height_[k], 0.0, 0.0, 0.0};
  const RiseValue r = evaluate_rise(s.shape, x);
  const double sign = s.kind == CamSegment::Kind::rise ? 1.0 : -1.0;
  const double L = sign * s.lift, b = 1.0 / s.angle;
  return {height_[k] + L * r.s, L * r.ds * b, L * r.d2s * b * b, L * r.d3s * b * b * b};
}

LiftDerivatives ProgramLaw::evaluate_in_event(double phi) const {
  // The segment holding phi: the last whose start is not after it.
  const auto it = std::upper_bound(start_.begin(), start_.end(), phi);
  const std::size_t k = it == start_.begin() ? 0 : static_cast<std::size_t>(it - start_.begin()) - 1;
  const double x = std::clamp((phi - start_[k]) / segments_[k].angle, 0.0, 1.0);
  LiftDerivatives d = on_segment(k, x);
  d.lift = std::max(d.lift, 0.0);  // rounding at a return's end
  return d;
}

std::vector<double> ProgramLaw::breakpoints() const {
  std::vector<double> b;
  for (std::size_t k = 0; k < segments_.size(); ++k) {
    if (k > 0) b.push_back(start_[k]);
    if (segments_[k].kind != CamSegment::Kind::dwell)
      for (double x : rise_breakpoints(segments_[k].shape)) b.push_back(start_[k] + x * segments_[k].angle);
  }
  std::sort(b.begin(), b.end());
  b.erase(std::unique(b.begin(), b.end()), b.end());
  return b;
}

std::vector<SegmentJoint> ProgramLaw::joints() const {
  std::vector<SegmentJoint> out;
  auto name = [&](std::size_t k) { return segment_kind_name(segments_[k].kind) + " " + std::to_string(k + 1); };
  // A jump counts when it exceeds 1e-9 of the derivative's largest one-sided value over the joints.
  std::vector<std::pair<LiftDerivatives, LiftDerivatives>> sides;
  for (std::size_t j = 0; j <= segments_.size(); ++j) {
    const LiftDerivatives left = j == 0 ? LiftDerivatives{} : on_segment(j - 1, 1.0);
    const LiftDerivatives right = j == segments_.size() ? LiftDerivatives{} : on_segment(j, 0.0);
    sides.emplace_back(left, right);
    SegmentJoint joint;
    joint.angle = j == segments_.size() ? end_ : start_[j];
    joint.between = (j == 0 ? std::string("base circle") : name(j - 1)) + " / " +
                    (j == segments_.size() ? std::string("base circle") : name(j));
    out.push_back(joint);
  }
  double scale[4] = {max_lift_, 0.0, 0.0, 0.0};
  for (const auto& [l, r] : sides) {
    const double a[3] = {l.velocity, l.acceleration, l.jerk}, b[3] = {r.velocity, r.acceleration, r.jerk};
    for (int n = 0; n < 3; ++n) scale[n + 1] = std::max({scale[n + 1], std::abs(a[n]), std::abs(b[n])});
  }
  for (std::size_t j = 0; j < out.size(); ++j) {
    const auto& [l, r] = sides[j];
    const double jump[4] = {r.lift - l.lift, r.velocity - l.velocity, r.acceleration - l.acceleration, r.jerk - l.jerk};
    for (int n = 0; n < 4; ++n) {
      out[j].jump[n] = jump[n];
      if (out[j].first_jump == 4 && std::abs(jump[n]) > 1e-9 * scale[n] && scale[n] > 0.0) out[j].first_jump = n;
    }
  }
  return out;
}

}  // namespace mechgraph::cams

namespace mechgraph::cams {

CamLawDefinition program_law_definition() {
  CamLawDefinition d;
  d.type = "cam.program";
  d.version = 1;
  d.summary = "a cam built from segments (rise, dwell, return), each with its own angle and law; continuity "
              "reported at every joint; lift and event from the segments";
  d.derives_lift_and_action = true;
  d.derived_from = "the segments";
  std::vector<std::string> laws;
  for (RiseShape s : all_rise_shapes) laws.emplace_back(rise_shape_name(s));
  d.params = {ParamSpec::record_list(
                  "segments",
                  {ParamSpec::choice("type", {"rise", "dwell", "return"}, "what the segment does"),
                   ParamSpec::number("angle", dim::angle, "cam angle of the segment", "deg").positive().below(2.0 * pi).because("> 0 and < 360 deg: a segment of one turn"),
                   ParamSpec::number("lift", dim::length, "how far a rise lifts or a return lowers", "mm")
                       .optional()
                       .positive()
                       .at_most(1e3)
                       .because("> 0: a segment that lifts; <= 1 km: as max_lift"),
                   ParamSpec::choice("law", laws, "normalised law of a rise or return").with_default("cycloidal")},
                  "the segments from the start of lift, e.g. [{type: rise, angle: 60 deg, lift: 9 mm, law: poly345}, "
                  "{type: dwell, angle: 10 deg}, {type: return, angle: 80 deg, lift: 9 mm}]; the lift must end at 0")
                  .with_example(std::vector<Record>{
                      {{"type", ParamValue::of_choice("rise")}, {"angle", ParamValue::of_number(55.0 * pi / 180.0)},
                       {"lift", ParamValue::of_number(9e-3)}, {"law", ParamValue::of_choice("poly345")}},
                      {{"type", ParamValue::of_choice("dwell")}, {"angle", ParamValue::of_number(10.0 * pi / 180.0)}},
                      {{"type", ParamValue::of_choice("return")}, {"angle", ParamValue::of_number(65.0 * pi / 180.0)},
                       {"lift", ParamValue::of_number(9e-3)}, {"law", ParamValue::of_choice("cycloidal")}}})};
  d.extra_outputs = {
      PortSpec::table("joints", "a row per joint (the event's ends included) at its cam angle: the jumps of lift, velocity, "
                                "acceleration and jerk (right minus left) and first_jump, the lowest derivative that "
                                "jumps (4: none up to the jerk)")
          .presented(over_cam_angle()),
      PortSpec::scalar("continuity_order", dim::none,
                       "highest derivative continuous at every joint (2: jerk jumps somewhere; 3: continuous to the jerk)"),
  };
  d.make = [](const CamBasics& basics, const ParamSet& params, OutputSet& extra) -> std::shared_ptr<const CamLaw> {
    std::vector<CamSegment> segments;
    for (const Record& r : params.records("segments")) {
      CamSegment s;
      const std::string type = r.at("type").text;
      s.kind = type == "rise" ? CamSegment::Kind::rise : type == "dwell" ? CamSegment::Kind::dwell : CamSegment::Kind::ret;
      s.angle = r.at("angle").number;
      if (auto it = r.find("lift"); it != r.end()) s.lift = it->second.number;
      if (auto it = r.find("law"); it != r.end()) s.shape = *rise_shape_from_name(it->second.text);
      segments.push_back(s);
    }
    auto law = std::make_shared<const ProgramLaw>(std::move(segments), basics.base_radius);
    const double span = law->event_end() - law->event_begin();
    if (basics.has_action_angle && !(std::abs(span - basics.action_angle) <= 1e-9 * span)) {
      std::ostringstream m;
      m << "the segments span " << span * 180.0 / pi << " deg, action_angle asks for " << basics.action_angle * 180.0 / pi << " deg";
      throw NodeError("action_angle", m.str());
    }
    if (basics.has_max_lift && !(std::abs(law->max_lift() - basics.max_lift) <= 1e-9 * law->max_lift())) {
      std::ostringstream m;
      m << "the segments lift " << law->max_lift() * 1e3 << " mm, max_lift asks for " << basics.max_lift * 1e3 << " mm";
      throw NodeError("max_lift", m.str());
    }
    // The joint report.
    const std::vector<SegmentJoint> joints = law->joints();
    Table t;
    t.axis = {"cam_angle", dim::angle, {}, "deg"};
    auto& lift = t.add_channel("lift_jump", dim::length, "mm").values;
    (void)lift;
    t.add_channel("velocity_jump", dim::length / dim::angle, "mm/deg");
    t.add_channel("acceleration_jump", dim::length / dim::angle.pow(2), "mm/deg^2");
    t.add_channel("jerk_jump", dim::length / dim::angle.pow(3), "mm/deg^3");
    t.add_channel("first_jump", dim::none);
    int order = 3;
    const char* names[4] = {"lift", "velocity", "acceleration", "jerk"};
    const double to_deg = pi / 180.0;
    const char* units[4] = {" mm", " mm/deg", " mm/deg^2", " mm/deg^3"};
    for (const SegmentJoint& j : joints) {
      t.axis.values.push_back(j.angle);
      for (int n = 0; n < 4; ++n) t.channels[static_cast<std::size_t>(n)].values.push_back(j.jump[n]);
      t.channels[4].values.push_back(j.first_jump);
      order = std::min(order, j.first_jump - 1);
      if (j.first_jump < 4) {
        std::ostringstream m;
        m << "at " << j.angle * 180.0 / pi << " deg (" << j.between << "): the " << names[j.first_jump] << " jumps by "
          << j.jump[j.first_jump] * 1e3 * std::pow(to_deg, j.first_jump) << units[j.first_jump];
        extra.note(m.str());
      }
    }
    extra.set("joints", Value::table(std::move(t)));
    extra.set_scalar("continuity_order", order);
    return law;
  };
  return d;
}

void add_program_type(NodeTypeList& out) { out.push_back(make_cam_node_type(program_law_definition())); }

}  // namespace mechgraph::cams
