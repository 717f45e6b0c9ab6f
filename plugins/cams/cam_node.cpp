#include "cam_node.hpp"

#include "cam_summary.hpp"

#include <cmath>
#include <numbers>
#include <sstream>

namespace mechgraph::cams {
namespace {

class CamNodeType final : public NodeType {
 public:
  explicit CamNodeType(CamLawDefinition d) : make_(std::move(d.make)) {
    info_.type = std::move(d.type);
    info_.version = d.version;
    info_.summary = std::move(d.summary);
    info_.params = {
        ParamSpec::number("max_lift", dim::length, "maximum follower lift at the nose", "mm").positive(),
        ParamSpec::number("action_angle", dim::angle, "total cam angle of the lift event", "deg")
            .positive()
            .below(2.0 * std::numbers::pi),
        ParamSpec::number("base_radius", dim::length, "base-circle radius", "mm").positive(),
    };
    for (auto& p : d.params) info_.params.push_back(std::move(p));
    info_.params.push_back(ParamSpec::integer("samples", "samples per smooth piece for the extremum searches")
                               .with_default(400.0)
                               .at_least(8)
                               .as_knob());
    info_.outputs = {
        PortSpec::handle("law", std::string(CamLaw::kind_name), "follower lift over cam angle with 3 derivatives"),
        PortSpec::scalar("max_velocity", dim::length / dim::angle, "max |dh/dphi|", "mm/deg"),
        PortSpec::scalar("max_acceleration", dim::length / dim::angle.pow(2), "max d2h/dphi2"),
        PortSpec::scalar("min_acceleration", dim::length / dim::angle.pow(2), "min (most negative) d2h/dphi2"),
        PortSpec::scalar("accel_angle", dim::angle, "achieved positive-acceleration phase from the start of lift", "deg"),
        PortSpec::scalar("min_curvature_radius", dim::length, "smallest radius of curvature of the cam contour", "mm"),
    };
    for (auto& p : d.extra_outputs) info_.outputs.push_back(std::move(p));
    info_.work_counters = {"evaluations"};
  }

  const NodeInfo& info() const override { return info_; }

  void evaluate(const ParamSet& params, const InputSet&, OutputSet& out, EvalContext& ctx) const override {
    const CamBasics basics{params.number("max_lift"), params.number("action_angle"), params.number("base_radius")};
    std::shared_ptr<const CamLaw> law = make_(basics, params, out);
    const CamSummary s = summarize(*law, static_cast<int>(params.integer("samples")));
    ctx.report_work("evaluations", static_cast<double>(s.evaluations));
    if (!(s.min_curvature_radius > 0.0)) {
      std::ostringstream msg;
      msg << "the cam contour is undercut: its smallest radius of curvature is " << s.min_curvature_radius * 1e3
          << " mm (must be > 0); increase base_radius or soften the law";
      throw NodeError("base_radius", msg.str());
    }
    out.set("law", Value::handle(law));
    out.set_scalar("max_velocity", s.max_velocity);
    out.set_scalar("max_acceleration", s.max_acceleration);
    out.set_scalar("min_acceleration", s.min_acceleration);
    out.set_scalar("accel_angle", s.accel_angle);
    out.set_scalar("min_curvature_radius", s.min_curvature_radius);
  }

 private:
  NodeInfo info_;
  CamLawFactory make_;
};

}  // namespace

std::shared_ptr<const NodeType> make_cam_node_type(CamLawDefinition definition) {
  return std::make_shared<const CamNodeType>(std::move(definition));
}

}  // namespace mechgraph::cams
