// spring.helical: a cylindrical helical compression spring of constant rate
// (docs/methods/valvetrain.md, stage 4b; the formulas are in coil_spring.hpp).
#include "coil_spring.hpp"
#include "node_types.hpp"

namespace mechgraph::springs {
namespace {

class HelicalModel final : public SpringModel {
 public:
  HelicalModel(CoilRules rules, double index) : rules_(rules), index_(index) {}
  std::string_view type_name() const override { return "spring.helical"; }
  std::shared_ptr<const Spring> size(const SpringLine& line) const override {
    std::vector<Coil> coils{size_coil(rules_.material, index_, rules_.end_coils, line, "spring_index")};
    finish_lengths(coils, rules_, line.stroke, type_name());
    return std::make_shared<const CoilSpring>(std::move(coils), rules_.material.allowable_stress);
  }

 private:
  CoilRules rules_;
  double index_;
};

class HelicalSpringType final : public NodeType {
 public:
  HelicalSpringType() {
    info_.type = "spring.helical";
    info_.summary = "cylindrical helical compression spring of constant rate, sized by the stress at full lift";
    info_.params = coil_rule_params();
    info_.params.push_back(ParamSpec::number("spring_index", dim::none, "spring index C = D/d (coil / wire diameter)")
                               .with_default(7.0)
                               .at_least(4.0)
                               .at_most(16.0)
                               .because("4 to 16: the spring index the Wahl correction and coiling hold for"));
    info_.outputs = {PortSpec::handle("model", std::string(SpringModel::kind_name),
                                      "the unsized spring model (material, index, limits); valvetrain.spring_design sizes it")};
  }
  const NodeInfo& info() const override { return info_; }
  void evaluate(const ParamSet& p, const InputSet&, OutputSet& out, EvalContext&) const override {
    out.set("model", Value::handle(std::make_shared<const HelicalModel>(coil_rules(p), p.number("spring_index"))));
  }

 private:
  NodeInfo info_;
};

}  // namespace

std::shared_ptr<const NodeType> make_helical_spring_type() { return std::make_shared<const HelicalSpringType>(); }

}  // namespace mechgraph::springs
