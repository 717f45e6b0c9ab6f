// Test functions of uncertainty studies with closed-form answers (tests/core/uncertainty_test.cpp):
//  - test.ishigami: y = sin x1 + a sin^2 x2 + b x3^4 sin x1 (Ishigami and Homma 1990), x_i plain
//    numbers; the node fails (an evaluation error) when y > fail_above, for event probabilities.
//  - test.linear: y = c1 x1 + c2 x2 + c3 x3 on lengths, so units cross the scene boundary (and an
//    integer parameter, terms, it does not use).
#include <mechgraph/plugin_abi.hpp>

#include <cmath>

namespace {

using namespace mechgraph;

class Ishigami final : public NodeType {
 public:
  Ishigami() {
    info_.type = "test.ishigami";
    info_.summary = "the Ishigami function";
    for (const char* x : {"x1", "x2", "x3"}) info_.params.push_back(ParamSpec::number(x, dim::none, "input").with_default(0.0));
    info_.params.push_back(ParamSpec::number("a", dim::none, "a").with_default(7.0));
    info_.params.push_back(ParamSpec::number("b", dim::none, "b").with_default(0.1));
    info_.params.push_back(ParamSpec::number("fail_above", dim::none, "y above this is an evaluation error").with_default(1e300));
    info_.outputs = {PortSpec::scalar("y", dim::none, "sin x1 + a sin^2 x2 + b x3^4 sin x1")};
  }
  const NodeInfo& info() const override { return info_; }
  void evaluate(const ParamSet& p, const InputSet&, OutputSet& out, EvalContext&) const override {
    const double x1 = p.number("x1"), x2 = p.number("x2"), x3 = p.number("x3");
    const double y = std::sin(x1) + p.number("a") * std::sin(x2) * std::sin(x2) + p.number("b") * std::pow(x3, 4) * std::sin(x1);
    if (y > p.number("fail_above")) throw NodeError("fail_above", "y above fail_above (a deliberate failure)");
    out.set_scalar("y", y);
  }

 private:
  NodeInfo info_;
};

class Linear final : public NodeType {
 public:
  Linear() {
    info_.type = "test.linear";
    info_.summary = "c1 x1 + c2 x2 + c3 x3";
    for (const char* x : {"x1", "x2", "x3"}) info_.params.push_back(ParamSpec::number(x, dim::length, "input", "mm").with_default(0.0));
    for (const char* c : {"c1", "c2", "c3"}) info_.params.push_back(ParamSpec::number(c, dim::none, "coefficient").with_default(1.0));
    // A whole number y does not use: a study must refuse a distribution on it before it runs.
    info_.params.push_back(ParamSpec::integer("terms", "a whole number (unused)").with_default(3.0));
    info_.outputs = {PortSpec::scalar("y", dim::length, "c1 x1 + c2 x2 + c3 x3", "mm")};
  }
  const NodeInfo& info() const override { return info_; }
  void evaluate(const ParamSet& p, const InputSet&, OutputSet& out, EvalContext&) const override {
    out.set_scalar("y", p.number("c1") * p.number("x1") + p.number("c2") * p.number("x2") + p.number("c3") * p.number("x3"));
  }

 private:
  NodeInfo info_;
};

NodeTypeList make_types() { return {std::make_shared<Ishigami>(), std::make_shared<Linear>()}; }

}  // namespace

MECHGRAPH_PLUGIN("test_uq", "1.0.0", &make_types)
