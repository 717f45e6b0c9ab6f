#pragma once
// Evaluating a node type outside the host, the way the host would: parameters given as scene text
// ("9 mm", "cycloidal"), parsed with their unit and checked against the type's ParamSpec (the same
// range check as the host, ParamSpec::value_problem), defaults filled in; a context that records
// work and logs and reads every output. Used by the conformance suites and by plugin authors' tests.
#include <mechgraph/node.hpp>
#include <mechgraph/printf_number.hpp>
#include <mechgraph/units.hpp>

#include <map>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

namespace mechgraph::testing {

/// A host stand-in for one evaluation: the effects given are on, every output is wanted, work and
/// logs are kept.
class HarnessContext final : public EvalContext {
 public:
  explicit HarnessContext(const std::vector<std::string>& effects = {}) : effects_(effects.begin(), effects.end()) {}
  bool effect(std::string_view name) const override { return effects_.find(name) != effects_.end(); }
  void log(LogLevel, std::string_view message) override { logs.emplace_back(message); }
  void report_work(std::string_view counter, double amount) override { work[std::string(counter)] += amount; }
  bool wanted(std::string_view) const override { return true; }
  std::map<std::string, double> work;
  std::vector<std::string> logs;

 private:
  std::set<std::string, std::less<>> effects_;
};

/// An SI value as scene text that parses back to the same double ("0.0090000000000000002 m").
inline std::string si_text(double value, const char* si_unit) {
  return printf_g(value, 17) + " " + si_unit;
}

/// The type's parameters: `values` (scene text, numbers with their unit) parsed and checked, then
/// the declared defaults, then (with `fill_examples`) the declared examples (ParamSpec::example_value). Throws std::invalid_argument naming the type and parameter for an unknown
/// name, a wrong dimension, a value out of range, an unknown choice, or a required parameter that has
/// neither a value nor a default.
inline ParamSet params_with_defaults(const NodeInfo& info, const std::map<std::string, std::string>& values = {},
                                     bool fill_examples = true) {
  ParamSet out;
  for (const auto& [name, text] : values) {
    const ParamSpec* spec = info.find_param(name);
    if (!spec) throw std::invalid_argument(info.type + " has no parameter '" + name + "'");
    const std::string where = info.type + "." + name + " = '" + text + "'";
    switch (spec->kind) {
      case ParamKind::number:
      case ParamKind::integer: {
        Quantity q;
        try {
          q = parse_quantity(text);
        } catch (const std::exception& e) {
          throw std::invalid_argument(where + ": " + e.what());
        }
        if (!(q.dimension == spec->dimension))
          throw std::invalid_argument(where + ": expected a value in " + spec->dimension.si_unit());
        if (const std::string problem = spec->value_problem(q.value); !problem.empty())
          throw std::invalid_argument(where + " " + problem);
        out.set(name, spec->kind == ParamKind::integer ? ParamValue::of_integer(static_cast<long>(q.value))
                                                       : ParamValue::of_number(q.value));
        break;
      }
      case ParamKind::choice: {
        bool known = false;
        for (const auto& c : spec->choices) known = known || c == text;
        if (!known) throw std::invalid_argument(where + " is not one of its choices");
        out.set(name, ParamValue::of_choice(text));
        break;
      }
      case ParamKind::text: out.set(name, ParamValue::of_text(text)); break;
      default: throw std::invalid_argument(where + ": list parameters cannot be given as text here");
    }
  }
  for (const ParamSpec& spec : info.params) {
    if (out.has(spec.name)) continue;
    if (spec.default_value) out.set(spec.name, *spec.default_value);
    else if (fill_examples && spec.example_value) out.set(spec.name, *spec.example_value);
    else if (spec.required)
      throw std::invalid_argument(info.type + ": required parameter '" + spec.name +
                                  "' has neither a default nor an example (ParamSpec::with_example); give it a value");
  }
  return out;
}

/// What one evaluation produced.
struct HarnessRun {
  OutputSet outputs;
  HarnessContext context;
};

/// Evaluates `type` once with `params` and `inputs`; exceptions (NodeError) pass through.
inline HarnessRun run_node(const NodeType& type, const ParamSet& params, const InputSet& inputs = {},
                        const std::vector<std::string>& effects = {}) {
  HarnessRun run{{}, HarnessContext(effects)};
  type.evaluate(params, inputs, run.outputs, run.context);
  return run;
}

}  // namespace mechgraph::testing
