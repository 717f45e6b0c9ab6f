// Cam laws that break the CamLaw contract in one chosen way each, as a careless plugin would: the
// host must refuse every one naming the node type, and `mechgraph plugin-test` must fail them.
//   test.skewed_cam { rise, return, defect }: a parabolic-style lift rising over `rise` before the
//   nose and falling over `return` after it (250/50 deg puts the event's start at -250 deg);
//   defect: none | unsorted_breakpoints | breakpoint_outside | negative_lift | nan | wrong_velocity.
#include <mechgraph/domain/cam_law.hpp>
#include <mechgraph/plugin_abi.hpp>

#include <cmath>
#include <limits>
#include <numbers>

namespace {

using namespace mechgraph;

class SkewedLaw final : public CamLaw {
 public:
  SkewedLaw(double rise, double fall, std::string defect) : rise_(rise), fall_(fall), defect_(std::move(defect)) {}
  double event_begin() const override { return -rise_; }
  double event_end() const override { return fall_; }
  std::vector<double> breakpoints() const override {
    if (defect_ == "unsorted_breakpoints") return {0.5 * fall_, -0.5 * rise_};
    if (defect_ == "breakpoint_outside") return {-2.0 * rise_};
    return {0.0};
  }
  double max_lift() const override { return 1e-2; }
  double base_radius() const override { return 3e-2; }
  LiftDerivatives evaluate_in_event(double phi) const override {
    // h = H (1 - (phi/w)^2)^2 on each side (w = rise or fall): zero with zero slope at the ends.
    const double w = phi < 0 ? rise_ : fall_;
    const double x = phi / w, s = 1.0 - x * x;
    LiftDerivatives d{1e-2 * s * s, 1e-2 * 2.0 * s * (-2.0 * x) / w, 1e-2 * (12.0 * x * x - 4.0) / (w * w), 1e-2 * 24.0 * x / (w * w * w)};
    if (defect_ == "negative_lift") d.lift -= 2e-3;
    if (defect_ == "nan" && phi > 0.3 * fall_) d.acceleration = std::numeric_limits<double>::quiet_NaN();
    if (defect_ == "wrong_velocity") d.velocity *= 1.5;
    return d;
  }

 private:
  double rise_, fall_;
  std::string defect_;
};

class SkewedCam final : public NodeType {
 public:
  SkewedCam() {
    constexpr double deg = std::numbers::pi / 180.0;
    info_.type = "test.skewed_cam";
    info_.summary = "a cam law that breaks its contract in a chosen way";
    info_.params = {
        ParamSpec::number("rise", dim::angle, "cam angle before the nose", "deg").positive().with_default(60 * deg),
        ParamSpec::number("return", dim::angle, "cam angle after the nose", "deg").positive().with_default(60 * deg),
        ParamSpec::choice("defect", {"none", "unsorted_breakpoints", "breakpoint_outside", "negative_lift", "nan", "wrong_velocity"},
                          "how the law breaks the contract")
            .with_default("none"),
    };
    info_.outputs = {PortSpec::handle("law", std::string(CamLaw::kind_name), "the law"),
                     PortSpec::scalar("max_lift", dim::length, "declared lift", "mm")};
  }
  const NodeInfo& info() const override { return info_; }
  void evaluate(const ParamSet& p, const InputSet&, OutputSet& out, EvalContext&) const override {
    auto law = std::make_shared<const SkewedLaw>(p.number("rise"), p.number("return"), p.text("defect"));
    out.set("law", Value::handle(law));
    out.set_scalar("max_lift", law->max_lift());
  }

 private:
  NodeInfo info_;
};

NodeTypeList make_types() { return {std::make_shared<const SkewedCam>()}; }

}  // namespace

MECHGRAPH_PLUGIN("test_bad_laws", "0.1.0", &make_types)
