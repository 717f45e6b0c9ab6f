// A plugin that provides a node type another plugin (test_arith) already provides: refused.
#include <mechgraph/plugin_abi.hpp>

namespace {
class Clash final : public mechgraph::NodeType {
 public:
  Clash() { info_.type = "test.add"; }
  const mechgraph::NodeInfo& info() const override { return info_; }
  void evaluate(const mechgraph::ParamSet&, const mechgraph::InputSet&, mechgraph::OutputSet&,
                mechgraph::EvalContext&) const override {}

 private:
  mechgraph::NodeInfo info_;
};
mechgraph::NodeTypeList make_types() { return {std::make_shared<Clash>()}; }
}  // namespace

MECHGRAPH_PLUGIN("clash", "0.1.0", &make_types)
