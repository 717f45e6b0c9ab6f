// A plugin that breaks the host's expectations on purpose, as a careless or hostile one would; the
// host must survive each case and name the plugin, node and port. Built three times:
//   HOSTILE_FACTORY_THROWS_INT   its node type factory throws 7 (not a std::exception)
//   HOSTILE_FACTORY_THROWS_STD   its node type factory throws std::runtime_error
//   (neither)                    node types whose values have the wrong shape:
//     hostile.series { defect: short_axis | long_axis | labels | none }  a series of 4 values
//     hostile.nan_work                a good scalar, but a NaN work counter
//     hostile.throw_int               evaluate() throws 7 while making its domain object
//     hostile.bad_contract            a domain object whose contract_problem() throws 7
//     hostile.evil_curve              a closed curve whose channel names hold DXF group lines
//     hostile.evil_text               terminal control sequences (ESC, OSC, CSI as C1, bidi
//                                     overrides) in its summary, docs, choices, series labels,
//                                     notes, log messages and errors; its `label` (scene text)
//                                     goes into all of them; label "fail" makes it throw
#include <mechgraph/plugin_abi.hpp>

#include <mechgraph/errors.hpp>

#include <limits>
#include <stdexcept>

namespace {

using namespace mechgraph;

// ESC ] 0 ; ... BEL sets a terminal's title; ESC [ 2 J clears the screen; U+009B is CSI as a C1
// control (in UTF-8 and as the raw byte 0x9B); U+202E reverses the text that follows.
const std::string evil = "\x1b]0;PWNED\x07 \x1b[2J \xc2\x9b" "31m \x9b" "1m \xe2\x80\xae \x7f \r\x08 end";

class Thing final : public DomainObject {
 public:
  Thing() { throw 7; }  // a constructor that fails the wrong way
  std::string_view kind() const override { return "hostile_thing"; }
};

class Liar final : public DomainObject {
 public:
  std::string_view kind() const override { return "hostile_liar"; }
  std::string contract_problem() const override { throw 7; }
};

class Hostile final : public NodeType {
 public:
  enum class Kind { series, nan_work, throw_int, bad_contract, evil_curve, evil_text };
  Hostile(Kind kind, std::string type) : kind_(kind) {
    info_.type = std::move(type);
    info_.summary = "a deliberately broken node (host tests)";
    info_.work_counters = {"calls"};
    switch (kind) {
      case Kind::series:
        info_.params = {ParamSpec::choice("defect", {"none", "short_axis", "long_axis", "labels"}, "what is wrong")
                            .with_default("none")};
        info_.outputs = {PortSpec::series("curve", dim::length, "four values")};
        break;
      case Kind::nan_work: info_.outputs = {PortSpec::scalar("out", dim::length, "1 mm")}; break;
      case Kind::throw_int: info_.outputs = {PortSpec::handle("thing", "hostile_thing", "never made")}; break;
      case Kind::bad_contract: info_.outputs = {PortSpec::handle("liar", "hostile_liar", "cannot say if it is sound")}; break;
      case Kind::evil_curve: {
        // Its pair declared (the host draws declared pairs only), on a layer named like the channels.
        const std::string forge = "e\n  0\nLINE\n  8\nEVIL";
        Presentation drawing;
        drawing.role = Role::drawing_to_scale;
        drawing.pairs = {{forge + "_x", forge + "_y", forge, forge, 0}};
        info_.outputs = {PortSpec::table("curve", "a square, channels named to forge DXF entities").presented(drawing)};
        break;
      }
      case Kind::evil_text:
        info_.summary = "a node whose words hold " + evil;
        info_.params = {ParamSpec::text("label", "free text " + evil).with_default("x"),
                        ParamSpec::choice("mode", {"plain", "also " + evil}, "a choice " + evil).with_default("plain")};
        info_.outputs = {PortSpec::series("curve", dim::length, "labelled values " + evil)};
        break;
    }
  }
  const NodeInfo& info() const override { return info_; }
  void evaluate(const ParamSet& p, const InputSet&, OutputSet& out, EvalContext& ctx) const override {
    switch (kind_) {
      case Kind::series: {
        Series s;
        s.values = {1e-3, 2e-3, 3e-3, 4e-3};
        s.axis = {0.0, 1.0, 2.0, 3.0};
        const std::string& defect = p.text("defect");
        if (defect == "short_axis") s.axis.resize(2);
        if (defect == "long_axis") s.axis.resize(4000, 5.0);
        if (defect == "labels") s.labels = {"a", "b"};
        out.set("curve", Value::series(std::move(s)));
        break;
      }
      case Kind::nan_work:
        ctx.report_work("calls", std::numeric_limits<double>::quiet_NaN());
        out.set_scalar("out", 1e-3);
        break;
      case Kind::throw_int: out.set("thing", Value::handle(std::make_shared<const Thing>())); break;
      case Kind::bad_contract: out.set("liar", Value::handle(std::make_shared<const Liar>())); break;
      case Kind::evil_curve: {
        Table t;
        t.axis = {"i", dim::none, {0.0, 1.0, 2.0, 3.0}, ""};
        t.closed_curve = true;
        const std::string evil = "e\n  0\nLINE\n  8\nEVIL";
        t.add_channel(evil + "_x", dim::length).values = {0.0, 1e-3, 1e-3, 0.0};
        t.add_channel(evil + "_y", dim::length).values = {0.0, 0.0, 1e-3, 1e-3};
        out.set("curve", Value::table(std::move(t)));
        break;
      }
      case Kind::evil_text: {
        const std::string& label = p.text("label");
        if (label == "fail") throw NodeError("label", "refused " + evil);
        ctx.log(LogLevel::warn, "a warning " + evil + " about " + label);
        Series s;
        s.values = {1e-3, 2e-3};
        s.axis = {0.0, 1.0};
        s.labels = {label, evil};
        out.set("curve", Value::series(std::move(s)));
        out.note("made from " + label + " and " + evil);
        break;
      }
    }
  }

 private:
  Kind kind_;
  NodeInfo info_;
};

NodeTypeList make_types() {
#if defined(HOSTILE_FACTORY_THROWS_INT)
  throw 7;
#elif defined(HOSTILE_FACTORY_THROWS_STD)
  throw std::runtime_error("the factory gave up");
#else
  using Kind = Hostile::Kind;
  return {std::make_shared<Hostile>(Kind::series, "hostile.series"), std::make_shared<Hostile>(Kind::nan_work, "hostile.nan_work"),
          std::make_shared<Hostile>(Kind::throw_int, "hostile.throw_int"),
          std::make_shared<Hostile>(Kind::bad_contract, "hostile.bad_contract"),
          std::make_shared<Hostile>(Kind::evil_curve, "hostile.evil_curve"),
          std::make_shared<Hostile>(Kind::evil_text, "hostile.evil_text")};
#endif
}

}  // namespace

#if defined(HOSTILE_FACTORY_THROWS_INT)
MECHGRAPH_PLUGIN("hostile_throw_int", "0.0.1", &make_types)
#elif defined(HOSTILE_FACTORY_THROWS_STD)
MECHGRAPH_PLUGIN("hostile_throw_std", "0.0.1", &make_types)
#else
MECHGRAPH_PLUGIN("hostile_values", "0.0.1", &make_types)
#endif
