// C++ node types exported through the SDK 1.x C boundary (MECHGRAPH_PLUGIN_1): built by the
// project's compiler and, as test_sdk1_other, by the other one (clang++ for a gcc-built host, g++
// for a clang-built one), and loaded into the host either way.
//   cxx1.scale  out = gain * in (a scalar parameter and input), a note, a work counter
//   cxx1.curve  a table x, y = a x^2 and a series, refusing a < 0 with a NodeError
#include <mechgraph/plugin_sdk1.hpp>

namespace {

using namespace mechgraph;

class Scale final : public NodeType {
 public:
  Scale() {
    info_.type = "cxx1.scale";
    info_.summary = "multiplies its input";
    info_.params = {ParamSpec::number("gain", dim::none, "the factor").with_default(2.0)};
    info_.inputs = {PortSpec::scalar("in", dim::length, "what is scaled")};
    info_.outputs = {PortSpec::scalar("out", dim::length, "gain * in", "mm")};
    info_.work_counters = {"products"};
  }
  const NodeInfo& info() const override { return info_; }
  void evaluate(const ParamSet& params, const InputSet& inputs, OutputSet& outputs, EvalContext& context) const override {
    outputs.set_scalar("out", params.number("gain") * inputs.scalar("in"));
    outputs.note("scaled in C++ behind the C boundary");
    context.report_work("products", 1.0);
  }

 private:
  NodeInfo info_;
};

class Curve final : public NodeType {
 public:
  Curve() {
    info_.type = "cxx1.curve";
    info_.summary = "a parabola as a table and a series";
    info_.params = {ParamSpec::number("a", dim::length, "y at x = 1", "mm").with_default(0.001),
                    ParamSpec::integer("points", "rows").with_default(4.0).at_least(2).as_knob()};
    info_.outputs = {PortSpec::table("table", "y = a x^2 over x"), PortSpec::series("series", dim::length, "the same y")};
  }
  const NodeInfo& info() const override { return info_; }
  void evaluate(const ParamSet& params, const InputSet&, OutputSet& outputs, EvalContext& context) const override {
    const double a = params.number("a");
    if (a < 0.0) throw NodeError("a", "a negative a would dig below the axis");
    const long n = params.integer("points");
    Table t;
    t.axis = {"x", dim::none, {}, ""};
    Table::Column& y = t.add_channel("y", dim::length, "mm");
    Series s;
    for (long i = 0; i < n; ++i) {
      const double x = static_cast<double>(i) / static_cast<double>(n - 1);
      t.axis.values.push_back(x);
      y.values.push_back(a * x * x);
      s.axis.push_back(x);
      s.values.push_back(a * x * x);
    }
    if (context.wanted("table")) outputs.set("table", Value::table(std::move(t)));
    outputs.set("series", Value::series(std::move(s)));
  }
  // Its own count (it reaches the host through mechgraph.node.forecast/1): 500 items a row.
  std::optional<WorkForecast> forecast(const ParamSet& params, const InputSizes&) const override {
    const double n = static_cast<double>(params.integer("points"));
    return WorkForecast{500.0 * n, 64.0 * n, n, "points = " + std::to_string(params.integer("points"))};
  }

 private:
  NodeInfo info_;
};

NodeTypeList make_node_types() { return {std::make_shared<const Scale>(), std::make_shared<const Curve>()}; }

}  // namespace

#ifndef SDK1_PLUGIN_ID
#define SDK1_PLUGIN_ID "cxx1"
#endif
MECHGRAPH_PLUGIN_1(SDK1_PLUGIN_ID, "1.0.0", &make_node_types)
