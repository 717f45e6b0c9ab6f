// A node type that reads every kind of parameter and input the way node code does, and says what
// it saw: echo.params outputs one labelled series element per thing read (the label says what and
// how, the value is the number read, or a text's length). Built twice: with the pre-1.0 entry
// (test_echo) and, with ECHO_SDK1, through the SDK 1.x C boundary and the SDK's bridge
// (test_echo_sdk1), so that tests/core/sdk1_bridge_views_test.cpp can check that the bridge hands a
// node exactly what the host hands it on the pre-1.0 path.
//   echo.constant  out = value (a scalar to feed echo.params' inputs)
//   echo.curve     a series y = 2 x over x in {0, 0.5, 1}
//   echo.params    every parameter kind, has/absent optionals, a multiple input, a series input
#ifdef ECHO_SDK1
#include <mechgraph/plugin_sdk1.hpp>
#else
#include <mechgraph/plugin_abi.hpp>
#endif

#include <string>

namespace {

using namespace mechgraph;

class Constant final : public NodeType {
 public:
  Constant() {
    info_.type = "echo.constant";
    info_.summary = "a scalar";
    info_.params = {ParamSpec::number("value", dim::length, "the value", "mm")};
    info_.outputs = {PortSpec::scalar("out", dim::length, "the value")};
  }
  const NodeInfo& info() const override { return info_; }
  void evaluate(const ParamSet& p, const InputSet&, OutputSet& out, EvalContext&) const override {
    out.set_scalar("out", p.number("value"));
  }

 private:
  NodeInfo info_;
};

class Curve final : public NodeType {
 public:
  Curve() {
    info_.type = "echo.curve";
    info_.summary = "a short series";
    info_.outputs = {PortSpec::series("curve", dim::length, "2 x over x")};
  }
  const NodeInfo& info() const override { return info_; }
  void evaluate(const ParamSet&, const InputSet&, OutputSet& out, EvalContext&) const override {
    out.set("curve", Value::series(Series{{0.0, 0.5, 1.0}, {0.0, 1.0, 2.0}, dim::none, {"start", "middle", "end"}}));
  }

 private:
  NodeInfo info_;
};

std::string kind_name(ParamKind k) {
  static const char* names[] = {"number", "integer", "choice", "text", "number_list", "record_list"};
  return names[static_cast<int>(k)];
}

class Params final : public NodeType {
 public:
  Params() {
    info_.type = "echo.params";
    info_.summary = "says what it reads of its parameters and inputs";
    info_.params = {
        ParamSpec::number("length", dim::length, "a number", "mm").with_default(0.01),
        ParamSpec::integer("count", "an integer").with_default(3.0),
        ParamSpec::choice("mode", {"fast", "exact"}, "a choice").with_default("fast"),
        ParamSpec::text("label", "a text").with_default("plain"),
        ParamSpec::number_list("steps", dim::length, "a number list", "mm").with_default(std::vector<double>{0.001, 0.002}),
        ParamSpec::record_list("links",
                               {ParamSpec::number("size", dim::length, "a record's number", "mm"),
                                ParamSpec::integer("n", "a record's integer").with_default(1.0),
                                ParamSpec::choice("fit", {"pin", "slot"}, "a record's choice").with_default("pin"),
                                ParamSpec::text("name", "a record's optional text").optional()},
                               "a record list")
            .optional(),
        ParamSpec::number("extra", dim::length, "an optional number", "mm").optional(),
        ParamSpec::text("remark", "an optional text").optional(),
        ParamSpec::number_list("weights", dim::none, "an optional number list").optional(),
    };
    info_.inputs = {PortSpec::scalar("in", dim::length, "any number of scalars").many().optional_port(),
                    PortSpec::series("curve", dim::length, "a series").optional_port()};
    info_.outputs = {PortSpec::series("seen", dim::none, "what it read, one labelled element each")};
  }
  const NodeInfo& info() const override { return info_; }

  void evaluate(const ParamSet& p, const InputSet& in, OutputSet& out, EvalContext&) const override {
    Series seen;
    const auto say = [&](std::string what, double value) {
      seen.axis.push_back(static_cast<double>(seen.axis.size()));
      seen.values.push_back(value);
      seen.labels.push_back(std::move(what));
    };
    const auto say_value = [&](const std::string& what, const ParamValue& v) {
      say(what + " kind " + kind_name(v.kind) + " text '" + v.text + "'", v.number);
      for (std::size_t i = 0; i < v.numbers.size(); ++i) say(what + "[" + std::to_string(i) + "]", v.numbers[i]);
      for (std::size_t r = 0; r < v.records.size(); ++r)
        for (const auto& [field, value] : v.records[r]) say(what + " record " + std::to_string(r) + " field " + field + ":", value.number);
    };
    // Each declared parameter through the accessor node code uses for its kind.
    for (const ParamSpec& spec : info_.params) {
      const std::string& name = spec.name;
      say("has " + name, p.has(name) ? 1.0 : 0.0);
      if (!p.has(name)) {
        try {
          (void)p.get(name);
          say("get " + name + " did not throw", 1.0);
        } catch (const NodeError& e) {
          say("get " + name + " threw for '" + e.parameter() + "': " + e.what(), 0.0);
        }
        continue;
      }
      switch (spec.kind) {
        case ParamKind::number: say("number " + name, p.number(name)); break;
        case ParamKind::integer: say("integer " + name, static_cast<double>(p.integer(name))); break;
        case ParamKind::choice:
        case ParamKind::text: say("text " + name + " '" + p.text(name) + "'", static_cast<double>(p.text(name).size())); break;
        case ParamKind::number_list:
          say("numbers " + name + " size", static_cast<double>(p.numbers(name).size()));
          for (double x : p.numbers(name)) say("numbers " + name, x);
          break;
        case ParamKind::record_list: {
          const std::vector<Record>& records = p.records(name);
          say("records " + name + " size", static_cast<double>(records.size()));
          for (std::size_t r = 0; r < records.size(); ++r) {
            for (const ParamSpec& field : spec.fields) {
              const auto it = records[r].find(field.name);
              say("record " + std::to_string(r) + " has " + field.name, it != records[r].end() ? 1.0 : 0.0);
            }
            for (const auto& [field, value] : records[r]) say_value("record " + std::to_string(r) + " " + field, value);
          }
          break;
        }
      }
      say_value("get " + name, p.get(name));
    }
    // The whole set, as a host or a helper iterating it sees it.
    say("all size", static_cast<double>(p.all().size()));
    for (const auto& [name, value] : p.all()) say_value("all " + name, value);
    // An undeclared name.
    try {
      say("undeclared number did not throw", p.number("undeclared"));
    } catch (const NodeError& e) {
      say("undeclared threw for '" + e.parameter() + "': " + e.what(), 0.0);
    }
    // Inputs: a multiple port, a series port, an unconnected or undeclared one.
    for (const char* port : {"in", "curve", "undeclared"}) {
      const std::size_t n = in.count(port);
      say(std::string("count ") + port, static_cast<double>(n));
      for (std::size_t i = 0; i < n; ++i) {
        const Value& v = in.value(port, i);
        if (v.kind() == ValueKind::scalar) say(std::string("scalar ") + port, in.scalar(port, i));
        if (v.kind() == ValueKind::series) {
          const Series& s = v.as_series();
          for (std::size_t k = 0; k < s.values.size(); ++k)
            say(std::string("series ") + port + " at " + std::to_string(s.axis[k]) + " '" + (k < s.labels.size() ? s.labels[k] : "") + "'",
                s.values[k]);
        }
      }
      try {
        (void)in.value(port, n);
        say(std::string("value past the end of ") + port + " did not throw", 1.0);
      } catch (const NodeError& e) {
        say(std::string("value past the end of ") + port + " threw for '" + e.parameter() + "': " + e.what(), 0.0);
      }
    }
    out.set("seen", Value::series(std::move(seen)));
  }

 private:
  NodeInfo info_;
};

NodeTypeList make_types() {
  return {std::make_shared<const Constant>(), std::make_shared<const Curve>(), std::make_shared<const Params>()};
}

}  // namespace

#ifdef ECHO_SDK1
MECHGRAPH_PLUGIN_1("echo", "1.0.0", &make_types)
#else
MECHGRAPH_PLUGIN("echo", "1.0.0", &make_types)
#endif
