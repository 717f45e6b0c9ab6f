// C++ domain objects through the SDK 1.x C boundary (mechgraph/detail/object_bridge.hpp), built
// twice from this file, as plugins `objsa` and `objsb` (OBJECTS_PLUGIN_ID), so that one's objects
// are foreign to the other:
//   <id>.law          a CamLaw made here: h = lift cos^2(pi phi / (2 w)) on (-w, w); refuses a lift
//                     above 50 mm; also in blocks of cases (BlockEvaluation, c/node_block.h)
//   <id>.relay        passes a cam law on; `native` 1 when it arrived as this plugin's own C++ law,
//                     `view` 1 when it arrived as a view over another library's C tables (not when
//                     that library's C++ layer has this one's key, c/object_cxx.h); also in blocks
//                     (the law block passed on, the scalars per case)
//   <id>.motion       a ValveMotion over a cam law (valve lift = ratio * cam lift)
//   <id>.read_motion  reads a valve motion and its cam at 0.3 rad; `native`, `cam_native` as above
//   <id>.play         a JointPlay (plain data): one term of two links
//   <id>.follower     a Follower made here: the SDK's reference translating roller (roller_radius, offset)
//   <id>.read_follower reads a follower's contact at 0.3 rad over a given lift; `native` as above
//   <id>.throws       throws what `what` says (0: an int, 1: std::bad_alloc, 2: std::runtime_error)
// objects_live() (exported, for the test) counts this plugin's laws and motions alive. Built a third
// time as `objsc` with MECHGRAPH_SDK_CXX_SHORTCUT 0: a library that keeps to the C tables.
#include <mechgraph/block.hpp>
#include <mechgraph/domain/cam_law_block.hpp>
#include <mechgraph/domain/tolerance.hpp>
#include <mechgraph/domain/translating_followers.hpp>
#include <mechgraph/domain/valve_motion.hpp>
#include <mechgraph/plugin_sdk1.hpp>

#include <atomic>
#include <cmath>
#include <new>
#include <numbers>
#include <stdexcept>

namespace {

using namespace mechgraph;

std::atomic<long> live{0};

struct Counted {
  Counted() { ++live; }
  Counted(const Counted&) { ++live; }
  ~Counted() { --live; }
};

class CosineLaw final : public CamLaw {
 public:
  CosineLaw(double lift, double half_width) : lift_(lift), w_(half_width) {}
  double event_begin() const override { return -w_; }
  double event_end() const override { return w_; }
  std::vector<double> breakpoints() const override { return {}; }
  double max_lift() const override { return lift_; }
  double base_radius() const override { return 0.02; }
  // h = H cos^2(k phi) = H (1 + cos 2k phi) / 2, k = pi / (2 w)
  LiftDerivatives evaluate_in_event(double phi) const override {
    const double k = std::numbers::pi / (2.0 * w_), a = 2.0 * k * phi, h = 0.5 * lift_;
    return {h * (1.0 + std::cos(a)), -h * 2.0 * k * std::sin(a), -h * 4.0 * k * k * std::cos(a), h * 8.0 * k * k * k * std::sin(a)};
  }
  bool lift_integrals(double a, double b, double& integral, double& of_square) const override {
    // integral of H (1 + cos 2k phi) / 2; of its square H^2 (3/8 + cos(2k phi)/2 + cos(4k phi)/8)
    const double k = std::numbers::pi / (2.0 * w_), h = lift_;
    const auto f = [&](double x) { return 0.5 * h * (x + std::sin(2.0 * k * x) / (2.0 * k)); };
    const auto g = [&](double x) {
      return h * h * (0.375 * x + std::sin(2.0 * k * x) / (4.0 * k) + std::sin(4.0 * k * x) / (32.0 * k));
    };
    integral = f(b) - f(a);
    of_square = g(b) - g(a);
    return true;
  }

 private:
  Counted counted_;
  double lift_, w_;
};

class RatioMotion final : public ValveMotion {
 public:
  RatioMotion(std::shared_ptr<const CamLaw> cam, double ratio) : cam_(std::move(cam)), ratio_(ratio), knots_(cam_->knots()) {}
  LiftDerivatives at(double phi) const override {
    const LiftDerivatives h = cam_->at(phi);
    return {ratio_ * h.lift, ratio_ * h.velocity, ratio_ * h.acceleration, ratio_ * h.jerk};
  }
  double camshaft_speed() const override { return 300.0; }
  double open_begin() const override { return cam_->event_begin(); }
  double open_end() const override { return cam_->event_end(); }
  const std::vector<double>& knots() const override { return knots_; }
  double rocker_ratio() const override { return ratio_; }
  double lash() const override { return 0.0; }
  const CamLaw& cam() const override { return *cam_; }

 private:
  Counted counted_;
  std::shared_ptr<const CamLaw> cam_;
  double ratio_;
  std::vector<double> knots_;
};

std::string type_name(const char* name) { return std::string(OBJECTS_PLUGIN_ID) + "." + name; }

class Node : public NodeType {
 public:
  const NodeInfo& info() const override { return info_; }

 protected:
  NodeInfo info_;
};

class LawNode final : public Node, public BlockEvaluation {
 public:
  LawNode() {
    info_.type = type_name("law");
    info_.summary = "a cosine-squared cam law";
    info_.params = {ParamSpec::number("lift", dim::length, "largest lift").with_default(0.008).positive(),
                    ParamSpec::number("half_width", dim::angle, "half the event").with_default(1.0).positive().below(3.0)};
    info_.outputs = {PortSpec::handle("law", std::string(CamLaw::kind_name), "the law")};
  }
  void evaluate(const ParamSet& p, const InputSet&, OutputSet& out, EvalContext&) const override {
    out.set("law", Value::handle(make(p.number("lift"), p.number("half_width"))));
  }
  bool block_supported(const BlockRequest&) const override { return true; }
  void evaluate_block(const BlockParams& p, const BlockInputs&, BlockOutputs& out, BlockCases& cases, EvalContext&) const override {
    const BlockColumn lift = p.number("lift"), half_width = p.number("half_width");
    std::vector<std::shared_ptr<const CamLaw>> laws(cases.size());
    for_each_live_case(cases, [&](std::size_t i) { laws[i] = make(lift[i], half_width[i]); });
    out.set_handle("law", std::make_shared<const CamLawBlock>(std::move(laws)));
  }

 private:
  static std::shared_ptr<const CamLaw> make(double lift, double half_width) {
    if (lift > 0.05) throw NodeError("lift", "a cosine-squared law of more than 50 mm lift is not made here");
    return std::make_shared<const CosineLaw>(lift, half_width);
  }
};

class Relay final : public Node, public BlockEvaluation {
 public:
  Relay() {
    info_.type = type_name("relay");
    info_.summary = "passes a cam law on";
    info_.inputs = {PortSpec::handle("law", std::string(CamLaw::kind_name), "a law")};
    info_.outputs = {PortSpec::handle("law", std::string(CamLaw::kind_name), "the same law"),
                     PortSpec::scalar("native", dim::none, "1: this plugin's own C++ law"),
                     PortSpec::scalar("view", dim::none, "1: a view over another library's C tables"),
                     PortSpec::scalar("lift_at_half", dim::length, "lift at half the event's end"),
                     PortSpec::scalar("integral", dim::length * dim::angle, "integral of the lift over the event, -1 if unsaid")};
  }
  void evaluate(const ParamSet&, const InputSet& in, OutputSet& out, EvalContext&) const override {
    const auto law = in.handle<CamLaw>("law");
    out.set("law", in.value("law"));
    out.set_scalar("native", dynamic_cast<const CosineLaw*>(law.get()) ? 1.0 : 0.0);
    out.set_scalar("view", is_view(*law) ? 1.0 : 0.0);
    out.set_scalar("lift_at_half", law->at(0.5 * law->event_end()).lift);
    out.set_scalar("integral", integral_of(*law));
  }
  bool block_supported(const BlockRequest&) const override { return true; }
  void evaluate_block(const BlockParams&, const BlockInputs& in, BlockOutputs& out, BlockCases& cases, EvalContext&) const override {
    const auto& laws = in.handle<CamLawBlock>("law");
    double* native = out.scalar("native");
    double* view = out.scalar("view");
    double* lift_at_half = out.scalar("lift_at_half");
    double* integral = out.scalar("integral");
    for_each_live_case(cases, [&](std::size_t i) {
      const CamLaw& law = laws.law(i);
      if (native) native[i] = dynamic_cast<const CosineLaw*>(&law) ? 1.0 : 0.0;
      if (view) view[i] = is_view(law) ? 1.0 : 0.0;
      if (lift_at_half) lift_at_half[i] = law.at(0.5 * law.event_end()).lift;
      if (integral) integral[i] = integral_of(law);
    });
    out.set_handle("law", in.shared_handle<CamLawBlock>("law"));
  }

 private:
  static bool is_view(const CamLaw& law) { return dynamic_cast<const detail::ForeignObject*>(&law) != nullptr; }
  static double integral_of(const CamLaw& law) {
    double integral = -1.0, of_square = 0.0;
    if (!law.lift_integrals(law.event_begin(), law.event_end(), integral, of_square)) integral = -1.0;
    return integral;
  }
};

class MotionNode final : public Node {
 public:
  MotionNode() {
    info_.type = type_name("motion");
    info_.summary = "a valve motion over a cam law";
    info_.params = {ParamSpec::number("ratio", dim::none, "rocker ratio").with_default(1.5).positive()};
    info_.inputs = {PortSpec::handle("law", std::string(CamLaw::kind_name), "a law")};
    info_.outputs = {PortSpec::handle("motion", std::string(ValveMotion::kind_name), "the motion")};
  }
  void evaluate(const ParamSet& p, const InputSet& in, OutputSet& out, EvalContext&) const override {
    out.set("motion", Value::handle(std::make_shared<const RatioMotion>(in.handle<CamLaw>("law"), p.number("ratio"))));
  }
};

class ReadMotion final : public Node {
 public:
  ReadMotion() {
    info_.type = type_name("read_motion");
    info_.summary = "reads a valve motion";
    info_.inputs = {PortSpec::handle("motion", std::string(ValveMotion::kind_name), "a motion")};
    info_.outputs = {PortSpec::scalar("lift", dim::length, "valve lift at 0.3 rad"),
                     PortSpec::scalar("cam_lift", dim::length, "cam lift at 0.3 rad"),
                     PortSpec::scalar("ratio", dim::none, "rocker ratio"),
                     PortSpec::scalar("knots", dim::none, "number of knots"),
                     PortSpec::scalar("native", dim::none, "1: this plugin's own motion"),
                     PortSpec::scalar("cam_native", dim::none, "1: its cam is this plugin's own law")};
  }
  void evaluate(const ParamSet&, const InputSet& in, OutputSet& out, EvalContext&) const override {
    const auto motion = in.handle<ValveMotion>("motion");
    out.set_scalar("lift", motion->at(0.3).lift);
    out.set_scalar("cam_lift", motion->cam().at(0.3).lift);
    out.set_scalar("ratio", motion->rocker_ratio());
    out.set_scalar("knots", static_cast<double>(motion->knots().size()));
    out.set_scalar("native", dynamic_cast<const RatioMotion*>(motion.get()) ? 1.0 : 0.0);
    out.set_scalar("cam_native", dynamic_cast<const CosineLaw*>(&motion->cam()) ? 1.0 : 0.0);
  }
};

class PlayNode final : public Node {
 public:
  PlayNode() {
    info_.type = type_name("play");
    info_.summary = "a joint's play";
    info_.outputs = {PortSpec::handle("play", std::string(JointPlay::kind_name), "the play"),
                     PortSpec::scalar("play_max", dim::length, "greatest play")};
  }
  void evaluate(const ParamSet&, const InputSet&, OutputSet& out, EvalContext&) const override {
    auto play = std::make_shared<const JointPlay>(
        "test joint", std::vector<PlayTerm>{{"pin", {{"bore", 40e-6, 10e-6, 1.0, Distribution::uniform},
                                                     {"pin", 10e-6, 5e-6, 2.0, Distribution::triangular}}}});
    out.set("play", Value::handle(play));
    out.set_scalar("play_max", play->play_max());
  }
};

class FollowerNode final : public Node {
 public:
  FollowerNode() {
    info_.type = type_name("follower");
    info_.summary = "a translating roller follower (the SDK's reference one)";
    info_.params = {ParamSpec::number("roller_radius", dim::length, "roller radius").with_default(0.008).positive(),
                    ParamSpec::number("offset", dim::length, "offset of the roller's line").with_default(0.0)};
    info_.outputs = {PortSpec::handle("follower", std::string(Follower::kind_name), "the follower")};
  }
  void evaluate(const ParamSet& p, const InputSet&, OutputSet& out, EvalContext&) const override {
    out.set("follower", Value::handle(std::make_shared<const reference::TranslatingRoller>(p.number("roller_radius"), p.number("offset"))));
  }
};

class ReadFollower final : public Node {
 public:
  ReadFollower() {
    info_.type = type_name("read_follower");
    info_.summary = "reads a follower's contact at 0.3 rad over the lift h = 2 mm, h' = 5 mm/rad, h'' = -10 mm/rad^2";
    info_.params = {ParamSpec::number("base_radius", dim::length, "base radius").with_default(0.02).positive()};
    info_.inputs = {PortSpec::handle("follower", std::string(Follower::kind_name), "a follower")};
    info_.outputs = {PortSpec::scalar("x", dim::length, "contact x"), PortSpec::scalar("y", dim::length, "contact y"),
                     PortSpec::scalar("pressure_angle", dim::angle, "pressure angle"),
                     PortSpec::scalar("curvature_radius", dim::length, "contour radius of curvature"),
                     PortSpec::scalar("follower_angle", dim::angle, "arm's turn"),
                     PortSpec::scalar("cam_lever", dim::length, "lever at the base radius"),
                     PortSpec::scalar("roller_radius", dim::length, "roller radius"),
                     PortSpec::scalar("pivoted", dim::none, "1: pivoted"),
                     PortSpec::scalar("type_name_length", dim::none, "characters of its type name"),
                     PortSpec::scalar("native", dim::none, "1: this plugin's own follower")};
  }
  void evaluate(const ParamSet& p, const InputSet& in, OutputSet& out, EvalContext&) const override {
    const auto f = in.handle<Follower>("follower");
    const FollowerContact c = f->contact(0.3, {0.002, 0.005, -0.010, 0.0}, p.number("base_radius"), false);
    out.set_scalar("x", c.x);
    out.set_scalar("y", c.y);
    out.set_scalar("pressure_angle", c.pressure_angle);
    out.set_scalar("curvature_radius", c.curvature_radius);
    out.set_scalar("follower_angle", c.follower_angle);
    out.set_scalar("cam_lever", f->cam_lever(p.number("base_radius")));
    out.set_scalar("roller_radius", f->roller_radius());
    out.set_scalar("pivoted", f->pivoted() ? 1.0 : 0.0);
    out.set_scalar("type_name_length", static_cast<double>(f->type_name().size()));
    out.set_scalar("native", dynamic_cast<const reference::TranslatingRoller*>(f.get()) ? 1.0 : 0.0);
  }
};

class Throws final : public Node {
 public:
  Throws() {
    info_.type = type_name("throws");
    info_.summary = "throws what it is told";
    info_.params = {ParamSpec::integer("what", "0: an int, 1: std::bad_alloc, 2: std::runtime_error").with_default(0)};
    info_.outputs = {PortSpec::scalar("out", dim::none, "never set")};
  }
  void evaluate(const ParamSet& p, const InputSet&, OutputSet&, EvalContext&) const override {
    switch (p.integer("what")) {
      case 0: throw 7;
      case 1: throw std::bad_alloc();
      default: throw std::runtime_error("a runtime_error from the plugin");
    }
  }
};

NodeTypeList make_node_types() {
  return {std::make_shared<const LawNode>(), std::make_shared<const Relay>(), std::make_shared<const MotionNode>(),
          std::make_shared<const ReadMotion>(), std::make_shared<const PlayNode>(), std::make_shared<const Throws>(),
          std::make_shared<const FollowerNode>(), std::make_shared<const ReadFollower>()};
}

}  // namespace

extern "C" __attribute__((visibility("default"))) long objects_live() { return live.load(); }

MECHGRAPH_PLUGIN_1(OBJECTS_PLUGIN_ID, "1.0.0", &make_node_types)
