#pragma once
// The node contract. A NodeType *describes* itself (NodeInfo: parameters, ports, accuracy knobs,
// effects, output dependencies, work counters) separately from *evaluating*. evaluate() is a
// pure function of parameters and inputs: it is const, keeps no state, and may be called from
// many threads at once. Nodes never return NaN or Inf: the evaluator checks, and a node that
// meets an infeasible or singular input throws NodeError naming the parameter and the limit.
#include <mechgraph/dimension.hpp>
#include <mechgraph/errors.hpp>
#include <mechgraph/params.hpp>
#include <mechgraph/presentation.hpp>
#include <mechgraph/value.hpp>

#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace mechgraph {

/// One parameter: its kind, dimension (SI), default, admissible range and documentation.
/// A parameter marked `knob` is an accuracy setting (step, tolerance, samples, method):
/// `mechgraph bench` varies knobs and nothing else. Its convention: an integer knob is more
/// accurate when larger, a real knob when smaller, and a choice knob lists its most accurate
/// choice first.
struct ParamSpec {
  std::string name;
  ParamKind kind = ParamKind::number;
  Dimension dimension{};
  std::string doc;
  std::optional<ParamValue> default_value;  // absent and not required: the node sees has()==false
  /// A typical value for a parameter without a default (a design size a scene must state): the
  /// conformance kit and `mechgraph plugin-test` evaluate the type with its defaults and these.
  std::optional<ParamValue> example_value;
  bool required = true;
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
  bool min_exclusive = false;
  bool max_exclusive = false;
  /// Why the range is what it is: a short sentence for every finite bound ("> 0: a length;
  /// <= 1 km: the square of a lift stays inside a double"), shown by `mechgraph describe` and in
  /// the out-of-range message. A plain string (SDK 1.0: mg_param_decl::range_reason).
  std::string range_reason;
  std::vector<std::string> choices;  // for choice
  std::vector<ParamSpec> fields;     // for record_list: the fields of each record
  bool knob = false;
  std::string display_unit;          // unit used when describing and reporting, e.g. "mm"
  bool is_path = false;              // text naming a file: resolved against the scene's folder

  // Fluent construction, so node descriptions read like a data sheet.
  static ParamSpec number(std::string name, Dimension d, std::string doc, std::string unit = {});
  static ParamSpec integer(std::string name, std::string doc);
  static ParamSpec choice(std::string name, std::vector<std::string> choices, std::string doc);
  static ParamSpec text(std::string name, std::string doc);
  static ParamSpec number_list(std::string name, Dimension d, std::string doc, std::string unit = {});
  static ParamSpec record_list(std::string name, std::vector<ParamSpec> fields, std::string doc);

  ParamSpec& with_default(double v);
  ParamSpec& with_default(std::string v);
  ParamSpec& with_default(std::vector<double> v);
  ParamSpec& with_example(double v);
  ParamSpec& with_example(std::string v);
  ParamSpec& with_example(std::vector<Record> v);  // a record list's example
  ParamSpec& optional();            // may be absent, no default
  ParamSpec& positive();            // > 0
  ParamSpec& non_negative();        // >= 0
  ParamSpec& at_least(double v);
  ParamSpec& above(double v);
  ParamSpec& at_most(double v);
  ParamSpec& below(double v);
  ParamSpec& because(std::string reason);  // sets range_reason
  ParamSpec& as_knob();
  ParamSpec& as_path();             // a text parameter that names a file

  /// The one range check (scene loading, sweeps, the knob bench and the conformance kit use it):
  /// whether `si` lies in [min, max] with the exclusive ends excluded (NaN never does).
  bool admits(double si) const;
  /// Why `si` cannot be this parameter's value (out of range, with the range in the display unit;
  /// not a whole number for an integer), in words that follow "parameter = 'value' "; empty when it
  /// can. The dimension is the caller's check.
  std::string value_problem(double si) const;
};

/// A typed port. Inputs marked `multiple` accept a list of connections (`fits: [a.fit, b.fit]`).
struct PortSpec {
  std::string name;
  ValueKind kind = ValueKind::scalar;
  Dimension dimension{};
  std::string handle_kind;  // for handles: the DomainObject::kind() it carries
  std::string doc;
  bool multiple = false;
  bool optional = false;
  std::string display_unit;
  /// How hosts present it (docs/design/sdk-1.0.md, 1.6): a label ("" : the name with '_' read as
  /// ' '), the angle frame an angle (or a rate per angle) counts (an id of NodeInfo::frames), and
  /// for tables and series the figure it calls for.
  std::string label;
  std::string angle_frame;
  Presentation presentation;

  static PortSpec scalar(std::string name, Dimension d, std::string doc, std::string unit = {});
  static PortSpec series(std::string name, Dimension d, std::string doc, std::string unit = {});
  static PortSpec handle(std::string name, std::string handle_kind, std::string doc);
  /// A table port: its channels carry their own dimensions (the port's dimension is none).
  static PortSpec table(std::string name, std::string doc);
  PortSpec& many();
  PortSpec& optional_port();
  PortSpec& labelled(std::string text) { label = std::move(text); return *this; }
  PortSpec& in_frame(std::string frame) { angle_frame = std::move(frame); return *this; }
  PortSpec& presented(Presentation p) { presentation = std::move(p); return *this; }
};

/// An optional piece of physics a node implements, switched on by the scene's `effects:` or the
/// node's own `effects:`. The outputs it lists exist only while it is on: asking for one of them
/// with the effect off is a load-time error naming the effect. The parameters it lists are read
/// only while it is on (a value written for one with the effect off is reported as unused).
struct EffectSpec {
  std::string name;
  std::string doc;
  std::vector<std::string> outputs{};
  std::vector<std::string> params{};
};

/// Everything a node type says about itself.
struct NodeInfo {
  std::string type;       // "cam.kurz"
  int version = 1;        // bump when results change: part of the memo hash
  std::string summary;
  std::vector<ParamSpec> params;
  std::vector<PortSpec> inputs;
  std::vector<PortSpec> outputs;
  std::vector<EffectSpec> effects;
  std::vector<std::string> work_counters;  // what report_work() may count: "samples", "evaluations"
  /// Which inputs each output depends on; an output not listed depends on all inputs.
  std::map<std::string, std::vector<std::string>> output_dependencies;
  /// The angle references its ports and channels name (presentation.hpp).
  std::vector<AngleFrame> frames;
  /// The notes it makes when a parameter is given, and the output it makes them with.
  std::vector<NoteDecl> notes;

  const ParamSpec* find_param(std::string_view name) const;
  const PortSpec* find_input(std::string_view name) const;
  const PortSpec* find_output(std::string_view name) const;
  bool implements_effect(std::string_view name) const;
  /// The frame `id`, or nullptr (also for "").
  const AngleFrame* find_frame(std::string_view id) const {
    for (const AngleFrame& f : frames)
      if (!id.empty() && f.id == id) return &f;
    return nullptr;
  }
  /// The effect that brings output `port`, or nullptr if the output is always there.
  const EffectSpec* effect_of_output(std::string_view port) const;
  /// The effect that brings parameter `name`, or nullptr.
  const EffectSpec* effect_of_param(std::string_view name) const;
};

/// The inputs of one evaluation: each port's connected values (several for `multiple` ports).
class InputSet {
 public:
  void add(const std::string& port, Value v) { values_[port].push_back(std::move(v)); }
  /// The values of `port`, made (empty) when absent; a port without values counts as not
  /// connected. For a host or the SDK's bridge that reuses one set for many evaluations.
  std::vector<Value>& slot(std::string_view port) {
    auto it = values_.find(port);
    return it != values_.end() ? it->second : values_.emplace(std::string(port), std::vector<Value>{}).first->second;
  }
  /// Every port's values, by port name (ports with no values may be listed, empty).
  const std::map<std::string, std::vector<Value>, std::less<>>& all() const { return values_; }
  std::size_t count(std::string_view port) const;
  const Value& value(std::string_view port, std::size_t i = 0) const;
  double scalar(std::string_view port, std::size_t i = 0) const { return value(port, i).as_scalar(); }

  /// The domain object behind a handle port, cast to its interface; throws NodeError if it is not one.
  template <class T>
  std::shared_ptr<const T> handle(std::string_view port, std::size_t i = 0) const {
    auto object = std::dynamic_pointer_cast<const T>(value(port, i).as_handle());
    if (!object) throw NodeError(std::string(port), "input '" + std::string(port) + "' does not carry the expected domain object");
    return object;
  }

 private:
  std::map<std::string, std::vector<Value>, std::less<>> values_;
};

/// The outputs one evaluation produces.
class OutputSet {
 public:
  void set(std::string port, Value v) { values_[std::move(port)] = std::move(v); }
  void set_scalar(std::string port, double v) { set(std::move(port), Value::scalar(v)); }
  const std::map<std::string, Value, std::less<>>& all() const { return values_; }
  /// A line that says how the results were made (e.g. "Monte Carlo: 1000000 samples, seed 1"):
  /// printed with the results and kept with them in the memo cache.
  void note(std::string text) { notes_.push_back(std::move(text)); }
  const std::vector<std::string>& notes() const { return notes_; }
  /// For a host or the SDK's bridge that reuses one set for many evaluations: the value stored
  /// for `port`, made (as an empty Value) when absent, and a way to empty the notes.
  Value& slot(std::string_view port) {
    auto it = values_.find(port);
    return it != values_.end() ? it->second : values_.emplace(std::string(port), Value{}).first->second;
  }
  void clear_notes() { notes_.clear(); }

 private:
  std::map<std::string, Value, std::less<>> values_;
  std::vector<std::string> notes_;
};

enum class LogLevel { debug, info, warn };

/// What the host gives a node while it evaluates: the effects switched on, a logger, and the
/// work counters. Nodes log through this, never through a global logger.
class MECHGRAPH_INTERFACE EvalContext {
 public:
  virtual ~EvalContext();  // out of line: the key function, so the RTTI lives in libmechgraph once
  virtual bool effect(std::string_view name) const = 0;
  virtual void log(LogLevel level, std::string_view message) = 0;
  /// Adds `amount` to the named work counter (samples, steps, iterations, evaluations).
  virtual void report_work(std::string_view counter, double amount) = 0;
  /// Whether anything downstream (another node's input, a requested output, a report cell) reads
  /// this output. A node may skip an output nobody reads when it costs real work (a curve of a
  /// few hundred points, a table); cheap outputs are simply always set.
  virtual bool wanted(std::string_view output) const = 0;
};

/// What one evaluation will cost, said from the parameters before anything runs, so the host can
/// refuse a scene beyond the user's budget (docs/writing-plugins.md, "Counts of work"). A work item
/// is about the cost of evaluating a cam law at one angle (0.1 to 1 us; the calibration test,
/// tests/core/work_estimate_calibration_test.cpp, holds every built-in type to it within a stated
/// factor). An upper bound is better than a guess: a scene refused is told why, a scene admitted
/// that runs for an hour is not.
struct WorkForecast {
  double items = 0.0;        // work items of one evaluation
  double memory = 0.0;       // bytes held at the peak of one evaluation (outputs included)
  /// How large what it outputs is for the nodes downstream: for a domain object the smooth pieces
  /// a search over it resolves (a law's pieces), for a curve its points. 1 for a small value.
  double output_size = 1.0;
  /// The parameter that makes it this large, and how, for a refusal: "file (about 80000 rows,
  /// smoothing gcv)", "curve_points = 300000". The host puts the node's name and a dot before it.
  std::string driver;
};

/// The size of the values an evaluation will receive, as the host knows it before anything runs:
/// per input port the largest `WorkForecast::output_size` of the nodes connected to it (1 when the
/// producer does not say). A port with nothing connected is absent.
using InputSizes = std::map<std::string, double, std::less<>>;

/// A node type. Implementations are `final`, stateless and const.
class MECHGRAPH_INTERFACE NodeType {
 public:
  virtual ~NodeType();  // out of line (key function)
  virtual const NodeInfo& info() const = 0;
  virtual void evaluate(const ParamSet& params, const InputSet& inputs, OutputSet& outputs,
                        EvalContext& context) const = 0;
  /// The cost of one evaluation with `params` (ranges checked, defaults filled) on inputs of
  /// `sizes`. Cheap: no evaluation, at most a look at a file's size; never throws (a parameter it
  /// cannot judge is evaluate()'s to refuse). The default, std::nullopt, lets the host count by the
  /// naming conventions of "Counts of work" (points, samples, bins, revolutions, list lengths).
  virtual std::optional<WorkForecast> forecast(const ParamSet& params, const InputSizes& sizes) const;
};

/// SDK 1.3: a NodeType whose forecast() reads only some of its parameters says which by also
/// implementing this (c/node_forecast_reads.h, mechgraph.node.forecast_reads/1). A sweep that
/// varies none of them then asks the forecast once for all its cases instead of case by case. The
/// contract, checked by the conformance kit: forecast() gives the same figures whatever the value of
/// a parameter not named (it may read the input sizes). A name too many costs only speed.
class MECHGRAPH_INTERFACE ForecastReads {
 public:
  virtual ~ForecastReads();  // out of line (key function)
  /// The names of the parameters forecast() reads: declared parameters of info(), fixed for the
  /// type; std::nullopt when it cannot say (it may read any: asked case by case). Asked once per
  /// type, from any thread, like info().
  virtual std::optional<std::vector<std::string>> forecast_reads() const = 0;
};

using NodeTypeList = std::vector<std::shared_ptr<const NodeType>>;

}  // namespace mechgraph
