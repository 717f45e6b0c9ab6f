// A small, well-formed plugin for the framework's own tests: arithmetic on lengths, a series,
// a domain object, a node that emits NaN (a bug the evaluator must catch), one that fails
// properly, and one with an effect. Built twice: with the pre-1.0 entry (test_arith) and, with
// ARITH_SDK1, through the SDK 1.x C boundary (test_arith_sdk1), so that the bench measures one node
// type through both entries (bench/evaluation_bench.cpp, BM_NodeCallEntries).
#ifdef ARITH_SDK1
#include <mechgraph/plugin_sdk1.hpp>
#else
#include <mechgraph/plugin_abi.hpp>
#endif

#include <cmath>
#include <cstdlib>
#include <new>
#include <chrono>
#include <limits>
#include <thread>

namespace {

using namespace mechgraph;

class Box final : public DomainObject {
 public:
  explicit Box(double v) : value(v) {}
  std::string_view kind() const override { return "test_box"; }
  double value;
};

class Arith final : public NodeType {
 public:
  enum class Op { constant, add, box, unbox, nan, fail, series, effectful, table, slow, chaos };
  Arith(Op op, std::string type) : op_(op) {
    info_.type = std::move(type);
    info_.summary = "test node";
    info_.work_counters = {"calls"};
    switch (op) {
      case Op::constant:
        info_.params = {ParamSpec::number("value", dim::length, "the value", "mm"),
                        ParamSpec::choice("mode", {"plain", "fancy"}, "unused choice").with_default("plain")};
        info_.outputs = {PortSpec::scalar("out", dim::length, "the value")};
        break;
      case Op::add:
        info_.params = {ParamSpec::number("gain", dim::none, "multiplies the sum").with_default(1.0).positive()};
        info_.inputs = {PortSpec::scalar("a", dim::length, "first"), PortSpec::scalar("b", dim::length, "second").many()};
        info_.outputs = {PortSpec::scalar("sum", dim::length, "gain * (a + sum of b)"),
                         PortSpec::scalar("twice", dim::length, "2 a")};
        info_.output_dependencies = {{"twice", {"a"}}};
        break;
      case Op::box:
        info_.inputs = {PortSpec::scalar("x", dim::length, "value to box")};
        info_.outputs = {PortSpec::handle("box", "test_box", "boxed value")};
        break;
      case Op::unbox:
        info_.inputs = {PortSpec::handle("box", "test_box", "boxed value")};
        info_.outputs = {PortSpec::scalar("x", dim::length, "unboxed")};
        break;
      case Op::nan:
        info_.outputs = {PortSpec::scalar("out", dim::length, "always NaN (a deliberately broken node)")};
        break;
      case Op::fail:
        info_.params = {ParamSpec::number("limit", dim::length, "anything", "mm").with_default(0.001)};
        info_.outputs = {PortSpec::scalar("out", dim::length, "never produced")};
        break;
      case Op::series:
        info_.params = {ParamSpec::integer("points", "how many").with_default(5.0).at_least(2).as_knob()};
        info_.outputs = {PortSpec::series("curve", dim::length, "x^2 over [0,1]")};
        break;
      case Op::effectful:
        info_.effects = {{"test_effect", "doubles the output"}};
        info_.params = {ParamSpec::number("value", dim::length, "the value", "mm")};
        info_.outputs = {PortSpec::scalar("out", dim::length, "value, doubled with test_effect")};
        break;
      case Op::table:
        info_.params = {ParamSpec::integer("points", "how many").with_default(4.0).at_least(2),
                        ParamSpec::choice("defect", {"none", "nan", "short", "twice"}, "a deliberate defect").with_default("none"),
                        ParamSpec::number("extra_gain", dim::none, "scales extra (test_extra)").with_default(1.0)};
        info_.outputs = {PortSpec::table("curves", "x^2 [m] and 2x [m/s] over x [s]"),
                         PortSpec::scalar("extra", dim::length, "only with test_extra")};
        info_.effects = {{"test_extra", "brings the output extra", {"extra"}, {"extra_gain"}}};
        break;
      case Op::chaos:
        info_.params = {ParamSpec::choice("mode", {"ok", "throw", "nan", "sleep", "allocate", "throw_other", "stray_counter", "ask_stray"},
                                          "how this node misbehaves").with_default("ok")};
        info_.inputs = {PortSpec::scalar("in", dim::length, "summed").many().optional_port()};
        info_.outputs = {PortSpec::scalar("out", dim::length, "the sum of the inputs, or mischief")};
        break;
      case Op::slow:
        info_.params = {ParamSpec::number("value", dim::length, "the value", "mm"),
                        ParamSpec::number("delay", dim::time, "how long it takes", "ms").with_default(0.01)};
        info_.outputs = {PortSpec::scalar("out", dim::length, "the value, after the delay")};
        break;
    }
  }
  const NodeInfo& info() const override { return info_; }
  void evaluate(const ParamSet& p, const InputSet& in, OutputSet& out, EvalContext& ctx) const override {
    ctx.report_work("calls", 1);
    switch (op_) {
      case Op::constant: out.set_scalar("out", p.number("value")); break;
      case Op::add: {
        double s = in.scalar("a");
        for (std::size_t i = 0; i < in.count("b"); ++i) s += in.scalar("b", i);
        out.set_scalar("sum", p.number("gain") * s);
        out.set_scalar("twice", 2 * in.scalar("a"));
        break;
      }
      case Op::box: out.set("box", Value::handle(std::make_shared<const Box>(in.scalar("x")))); break;
      case Op::unbox: out.set_scalar("x", in.handle<Box>("box")->value); break;
      case Op::nan: out.set_scalar("out", std::numeric_limits<double>::quiet_NaN()); break;
      case Op::fail: throw NodeError("limit", "limit exceeded: 1 mm > 0.5 mm");
      case Op::series: {
        Series s;
        const long n = p.integer("points");
        for (long i = 0; i < n; ++i) {
          const double x = static_cast<double>(i) / (n - 1);
          s.axis.push_back(x);
          s.values.push_back(x * x);
        }
        out.set("curve", Value::series(std::move(s)));
        break;
      }
      case Op::effectful:
        out.set_scalar("out", p.number("value") * (ctx.effect("test_effect") ? 2.0 : 1.0));
        ctx.log(LogLevel::debug, "effectful evaluated");
        break;
      case Op::table: {
        Table t;
        t.axis = {"time", dim::time, {}, "ms"};
        const long n = p.integer("points");
        for (long i = 0; i < n; ++i) t.axis.values.push_back(static_cast<double>(i) / (n - 1));
        t.add_channel("square", dim::length);
        t.add_channel("speed", dim::velocity);
        for (double x : t.axis.values) {
          t.channels[0].values.push_back(x * x);
          t.channels[1].values.push_back(2 * x);
        }
        const std::string& defect = p.text("defect");
        if (defect == "nan") t.channels[1].values.back() = std::numeric_limits<double>::quiet_NaN();
        if (defect == "short") t.channels[0].values.pop_back();
        if (defect == "twice") t.channels[1].name = "square";
        out.set("curves", Value::table(std::move(t)));
        if (ctx.effect("test_extra")) out.set_scalar("extra", p.number("extra_gain"));
        break;
      }
      case Op::chaos: {
        double sum = 0.0;
        for (std::size_t i = 0; i < in.count("in"); ++i) sum += in.scalar("in", i);
        const std::string& mode = p.text("mode");
        if (mode == "throw") throw NodeError("mode", "chaos: thrown on purpose");
        if (mode == "nan") sum = std::numeric_limits<double>::quiet_NaN();
        if (mode == "sleep") std::this_thread::sleep_for(std::chrono::milliseconds(30));
        if (mode == "allocate") {  // far beyond any machine: the allocation fails, as std::vector's would
          // volatile: clang may drop a malloc whose block is only freed, and with it the failure
          void* volatile block = std::malloc(std::size_t{1} << 62);
          if (!block) throw std::bad_alloc();
          std::free(block);
        }
        if (mode == "throw_other") throw 42;  // not even a std::exception
        if (mode == "stray_counter") ctx.report_work("stray", 1);  // a counter it does not declare
        if (mode == "ask_stray") sum = ctx.wanted("stray") ? 1.0 : -1.0;  // an output it does not declare
        out.set_scalar("out", sum);
        break;
      }
      case Op::slow:
        std::this_thread::sleep_for(std::chrono::duration<double>(p.number("delay")));
        out.set_scalar("out", p.number("value"));
        break;
    }
  }

 private:
  Op op_;
  NodeInfo info_;
};

NodeTypeList make_types() {
  using Op = Arith::Op;
  return {std::make_shared<Arith>(Op::constant, "test.constant"), std::make_shared<Arith>(Op::add, "test.add"),
          std::make_shared<Arith>(Op::box, "test.box"),           std::make_shared<Arith>(Op::unbox, "test.unbox"),
          std::make_shared<Arith>(Op::nan, "test.nan"),           std::make_shared<Arith>(Op::fail, "test.fail"),
          std::make_shared<Arith>(Op::series, "test.series"),     std::make_shared<Arith>(Op::effectful, "test.effectful"),
          std::make_shared<Arith>(Op::table, "test.table"),           std::make_shared<Arith>(Op::slow, "test.slow"),
          std::make_shared<Arith>(Op::chaos, "test.chaos")};
}

}  // namespace

#ifdef ARITH_SDK1
MECHGRAPH_PLUGIN_1("test_arith", "1.2.3", &make_types)
#else
MECHGRAPH_PLUGIN("test_arith", "1.2.3", &make_types)
#endif
