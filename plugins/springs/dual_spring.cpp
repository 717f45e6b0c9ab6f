// spring.dual: two helical springs nested one inside the other, deflecting together
// (docs/methods/valvetrain.md, stage 4b). The outer coil carries the share s of the line (preload
// and rate), the inner the rest; each is sized as a helical coil (coil_spring.hpp) for its share.
// The inner coil must fit inside the outer with a radial clearance s_r:
//   (D_o - d_o) - (D_i + d_i) >= 2 s_r.
// Two coils halve each wire's load, so the springs are shorter and lighter per unit of force, and
// the surge frequency that counts is the lower of the two.
#include "coil_spring.hpp"
#include "node_types.hpp"

#include <mechgraph/errors.hpp>

#include <sstream>

namespace mechgraph::springs {
namespace {

class DualModel final : public SpringModel {
 public:
  DualModel(CoilRules rules, double outer_index, double inner_index, double outer_share, double radial_clearance)
      : rules_(rules), outer_index_(outer_index), inner_index_(inner_index), share_(outer_share),
        radial_clearance_(radial_clearance) {}
  std::string_view type_name() const override { return "spring.dual"; }
  std::shared_ptr<const Spring> size(const SpringLine& line) const override {
    const SpringLine outer_line{share_ * line.preload, share_ * line.rate, line.stroke};
    const SpringLine inner_line{(1.0 - share_) * line.preload, (1.0 - share_) * line.rate, line.stroke};
    std::vector<Coil> coils{size_coil(rules_.material, outer_index_, rules_.end_coils, outer_line, "outer_index"),
                            size_coil(rules_.material, inner_index_, rules_.end_coils, inner_line, "inner_index")};
    const CoilGeometry& o = coils[0].geometry;
    const CoilGeometry& i = coils[1].geometry;
    const double gap = (o.mean_diameter - o.wire_diameter) - (i.mean_diameter + i.wire_diameter);
    if (gap < 2.0 * radial_clearance_) {
      std::ostringstream msg;
      msg << "the inner coil (outer diameter " << (i.mean_diameter + i.wire_diameter) * 1e3
          << " mm) does not fit inside the outer coil (inner diameter " << (o.mean_diameter - o.wire_diameter) * 1e3
          << " mm) with " << radial_clearance_ * 1e3 << " mm radial clearance: raise outer_share (now " << share_
          << ") or outer_index, or lower inner_index";
      throw NodeError("outer_share", msg.str());
    }
    finish_lengths(coils, rules_, line.stroke, type_name());
    return std::make_shared<const CoilSpring>(std::move(coils), rules_.material.allowable_stress);
  }

 private:
  CoilRules rules_;
  double outer_index_, inner_index_, share_, radial_clearance_;
};

class DualSpringType final : public NodeType {
 public:
  DualSpringType() {
    info_.type = "spring.dual";
    info_.summary = "two nested helical springs sharing the load (outer and inner coil, same deflection)";
    info_.params = coil_rule_params();
    info_.params.push_back(
        ParamSpec::number("outer_index", dim::none, "spring index D/d of the outer coil").with_default(9.0).at_least(4.0).at_most(16.0).because("4 to 16: the spring index the Wahl correction and coiling hold for"));
    info_.params.push_back(
        ParamSpec::number("inner_index", dim::none, "spring index D/d of the inner coil").with_default(6.0).at_least(4.0).at_most(16.0).because("4 to 16: the spring index the Wahl correction and coiling hold for"));
    info_.params.push_back(ParamSpec::number("outer_share", dim::none, "share of preload and rate the outer coil carries")
                               .with_default(0.6)
                               .above(0.0)
                               .below(1.0)
                               .because("> 0 and < 1: each spring carries part of the load"));
    info_.params.push_back(ParamSpec::number("radial_clearance", dim::length, "least radial gap between the two coils", "mm")
                               .with_default(0.3e-3)
                               .non_negative()
                               .at_most(0.1)
                               .because(">= 0: a gap; <= 0.1 m: far past any nested pair"));
    info_.outputs = {PortSpec::handle("model", std::string(SpringModel::kind_name),
                                      "the unsized nested-spring model; valvetrain.spring_design sizes it")};
  }
  const NodeInfo& info() const override { return info_; }
  void evaluate(const ParamSet& p, const InputSet&, OutputSet& out, EvalContext&) const override {
    out.set("model", Value::handle(std::make_shared<const DualModel>(coil_rules(p), p.number("outer_index"),
                                                                      p.number("inner_index"), p.number("outer_share"),
                                                                      p.number("radial_clearance"))));
  }

 private:
  NodeInfo info_;
};

}  // namespace

std::shared_ptr<const NodeType> make_dual_spring_type() { return std::make_shared<const DualSpringType>(); }

}  // namespace mechgraph::springs
