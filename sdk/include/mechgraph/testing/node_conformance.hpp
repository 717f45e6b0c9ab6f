#pragma once
// The node conformance suite: any node type, evaluated with its own declared defaults (plus the
// values an author adds), against the node contract of mechgraph/node.hpp, then every domain object
// it outputs against its interface's suite (cam_law, spring_model, spring, fit, joint_play, follower).
//
//   mechgraph::testing::NodeCheckOptions options;
//   options.values = {{"max_lift", "9 mm"}};                  // scene text, as in a scene
//   const auto report = mechgraph::testing::check_node_type(MyNode{}, options);
//   CHECK(report.passed());
//
// `mechgraph plugin-test LIB.so` runs it on every type of a plugin, feeding handle inputs from
// other loaded types.
#include <mechgraph/domain/cam_law.hpp>
#include <mechgraph/domain/fit.hpp>
#include <mechgraph/domain/spring.hpp>
#include <mechgraph/domain/tolerance.hpp>
#include <mechgraph/errors.hpp>
#include <mechgraph/node.hpp>
#include <mechgraph/testing/block_conformance.hpp>
#include <mechgraph/testing/cam_law_conformance.hpp>
#include <mechgraph/testing/domain_conformance.hpp>
#include <mechgraph/testing/follower_conformance.hpp>
#include <mechgraph/testing/forecast_conformance.hpp>
#include <mechgraph/testing/node_harness.hpp>
#include <mechgraph/testing/report.hpp>
#include <mechgraph/units.hpp>
#include <mechgraph/worker_threads.hpp>

#include <atomic>
#include <cmath>
#include <exception>
#include <functional>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <thread>
#include <vector>

namespace mechgraph::testing {

/// The name of the check that a type evaluated with its defaults and examples (present, passed or
/// failed, exactly when an evaluation was tried; `plugin-test --strict` looks for it).
inline constexpr const char* evaluation_check = "evaluates with its defaults";

/// The most evaluations at once the thread-safety check runs: more proves nothing on any machine
/// and only multiplies memory.
inline constexpr int max_check_threads = 256;

struct NodeCheckOptions {
  std::map<std::string, std::string> values;  // parameters as scene text; the rest from the defaults
  /// A value for an input port (a cam_law from another type, a scalar); nullopt: none. Optional
  /// ports without a value are left unconnected; a required one without a value skips evaluation.
  std::function<std::optional<Value>(const PortSpec&)> input_for;
  CamLawCheckOptions cam_law;
  int threads = 4;  // evaluations at once for the thread-safety check (0: skip it; at most max_check_threads)
};

namespace detail {


// Two evaluations agree bit for bit (numbers) and in the objects' kinds (handles).
inline bool same_outputs(const OutputSet& a, const OutputSet& b, std::string& where) {
  if (a.all().size() != b.all().size()) return where = "a different set of outputs", false;
  for (const auto& [port, v] : a.all()) {
    const auto it = b.all().find(port);
    if (it == b.all().end() || it->second.kind() != v.kind()) return where = port, false;
    const Value& w = it->second;
    bool same = true;
    switch (v.kind()) {
      case ValueKind::scalar: same = v.as_scalar() == w.as_scalar(); break;
      case ValueKind::series: same = v.as_series().values == w.as_series().values && v.as_series().axis == w.as_series().axis; break;
      case ValueKind::table: {
        same = v.as_table().axis.values == w.as_table().axis.values && v.as_table().channels.size() == w.as_table().channels.size();
        for (std::size_t i = 0; same && i < v.as_table().channels.size(); ++i)
          same = v.as_table().channels[i].values == w.as_table().channels[i].values;
        break;
      }
      default: same = v.as_handle() && w.as_handle() && v.as_handle()->kind() == w.as_handle()->kind(); break;
    }
    if (!same) return where = port, false;
  }
  return true;
}

// What is wrong with the type's presentation declarations (presentation.hpp), or "": every frame
// named (by a port, a channel, another frame) is declared, frame ids are unique and their base
// frames form no cycle, codes are unique per channel (value and name), a note names an output and a
// parameter the type has, a figure's points come from an output it has, a curve over a channel
// names that channel, a drawing names its pairs' channels.
inline std::string presentation_problem(const NodeInfo& info) {
  std::set<std::string> ids;
  for (const AngleFrame& f : info.frames) {
    if (f.id.empty()) return "an angle frame without an id";
    if (!ids.insert(f.id).second) return "angle frame '" + f.id + "' declared twice";
  }
  for (const AngleFrame& f : info.frames) {
    if (!f.base_frame.empty() && !ids.count(f.base_frame)) return "frame '" + f.id + "' maps from frame '" + f.base_frame + "', which is not declared";
    if (!f.offset_param.empty() && !info.find_param(f.offset_param))
      return "frame '" + f.id + "' offsets by parameter '" + f.offset_param + "', which the type does not have";
    if (f.mark_spacing > 0.0 && f.mark_labels.empty()) return "frame '" + f.id + "' has marks without labels";
    // Follow the base frames: no frame may come back to itself.
    std::string at = f.id;
    for (std::size_t steps = 0; !at.empty(); ++steps) {
      if (steps > info.frames.size()) return "frame '" + f.id + "' is derived from itself (a cycle of base frames)";
      const AngleFrame* next = info.find_frame(at);
      at = next ? next->base_frame : std::string();
    }
  }
  auto frame_known = [&](const std::string& id) { return id.empty() || ids.count(id) > 0; };
  auto channel_problem = [&](const ChannelDecl& c, const std::string& where) -> std::string {
    if (c.name.empty()) return where + ": a channel declaration without a name";
    if (!frame_known(c.angle_frame)) return where + " channel '" + c.name + "': frame '" + c.angle_frame + "' is not declared";
    std::set<double> values;
    std::set<std::string> names;
    for (const Code& code : c.codes)
      if (code.name.empty() || !values.insert(code.value).second || !names.insert(code.name).second)
        return where + " channel '" + c.name + "': code " + std::to_string(code.value) + " '" + code.name + "' empty or not unique";
    if ((c.flags & channel_flag::line_from_mark) && c.from_mark.empty()) return where + " channel '" + c.name + "': a line from a mark names no mark";
    if (c.flags & channel_flag::jumps_at_events) {
      bool events = false;
      for (const PortSpec& o : info.outputs) events = events || o.presentation.role == Role::events;
      if (!events) return where + " channel '" + c.name + "': it jumps at events, but the type has no output of role events";
    }
    return {};
  };
  for (const std::vector<PortSpec>* ports : {&info.inputs, &info.outputs})
    for (const PortSpec& port : *ports) {
      const std::string where = "port '" + port.name + "'";
      if (!frame_known(port.angle_frame)) return where + ": frame '" + port.angle_frame + "' is not declared";
      const Presentation& p = port.presentation;
      if (p.has_axis)
        if (std::string bad = channel_problem(p.axis, where); !bad.empty()) return bad;
      std::set<std::string> declared;
      for (const ChannelDecl& c : p.channels) {
        if (std::string bad = channel_problem(c, where); !bad.empty()) return bad;
        if (!declared.insert(c.name).second) return where + ": channel '" + c.name + "' declared twice";
      }
      if (p.role == Role::curve_over_channel && p.x_channel.empty()) return where + ": a curve over a channel names no x_channel";
      for (const XyPair& xy : p.pairs)
        if (xy.x.empty() || xy.y.empty() || xy.layer.empty()) return where + ": an x/y pair without its channels or layer";
      for (const PointMarks& pm : p.points) {
        const PortSpec* from = info.find_output(pm.port);
        if (!from || from->kind != ValueKind::table) return where + ": its points come from '" + pm.port + "', which is no table output of the type";
        if (pm.labels.size() > pm.x_channels.size()) return where + ": more point labels than x channels";
      }
    }
  for (const NoteDecl& n : info.notes) {
    if (!info.find_output(n.output)) return "a note made with output '" + n.output + "', which the type does not have";
    if (!info.find_param(n.when_param)) return "a note made with parameter '" + n.when_param + "', which the type does not have";
  }
  return {};
}

// Declared names the produced value lacks: a curve's x channel or a drawing's pair must be there;
// other declared channels may be absent (made only with some parameters) and are listed.
inline std::string presentation_missing(const PortSpec& port, const Value& v, bool& fatal) {
  fatal = false;
  if (v.kind() != ValueKind::table) return {};
  const Table& t = v.as_table();
  const Presentation& p = port.presentation;
  if (p.role == Role::curve_over_channel && !t.find(p.x_channel)) {
    fatal = true;
    return "output '" + port.name + "' has no channel '" + p.x_channel + "', its declared x_channel";
  }
  if (p.has_axis && p.axis.name != t.axis.name) {
    fatal = true;
    return "output '" + port.name + "' has axis '" + t.axis.name + "', declared '" + p.axis.name + "'";
  }
  std::string absent;
  for (const ChannelDecl& c : p.channels)
    if (!t.find(c.name)) absent += (absent.empty() ? "" : ", ") + port.name + "." + c.name;
  return absent;
}

}  // namespace detail

/// What the type says about itself: names, docs, defaults inside their own ranges, knobs, units.
inline Report check_node_info(const NodeInfo& info) {
  const std::string suite = "node " + info.type;
  Report r;
  r.add(suite, "type named plugin.name, with a summary", info.type.find('.') != std::string::npos && !info.summary.empty(),
        info.summary.empty() ? "no summary" : "");
  std::string bad;
  for (const ParamSpec& p : info.params) {
    const std::string at = "parameter '" + p.name + "'";
    if (p.name.empty() || p.doc.empty()) bad = at + ": no name or no doc";
    else if (p.min > p.max) bad = at + ": min above max";
    else if (p.default_value && (p.kind == ParamKind::number || p.kind == ParamKind::integer)) {
      if (const std::string problem = p.value_problem(p.default_value->number); !problem.empty()) bad = at + ": its default " + problem;
    } else if (p.default_value && p.kind == ParamKind::choice) {
      bool known = false;
      for (const auto& c : p.choices) known = known || c == p.default_value->text;
      if (!known) bad = at + ": its default '" + p.default_value->text + "' is not one of its choices";
    }
    if (p.example_value && (p.kind == ParamKind::number || p.kind == ParamKind::integer)) {
      if (const std::string problem = p.value_problem(p.example_value->number); !problem.empty()) bad = at + ": its example " + problem;
    }
    if (p.knob && !(p.kind == ParamKind::number || p.kind == ParamKind::integer || p.kind == ParamKind::choice))
      bad = at + ": a knob must be a number, an integer or a choice";
    if (!p.display_unit.empty()) {
      try {
        (void)to_unit(1.0, p.dimension, p.display_unit);
      } catch (const std::exception& e) {
        bad = at + ": display unit '" + p.display_unit + "' does not fit its dimension (" + e.what() + ")";
      }
    }
  }
  r.add(suite, "parameters documented, defaults inside their ranges, knobs numeric, units fit", bad.empty(), bad);
  bad.clear();
  std::set<std::string> names;
  for (const PortSpec& o : info.outputs) {
    if (!names.insert(o.name).second) bad = "output '" + o.name + "' twice";
    if (o.kind == ValueKind::handle && o.handle_kind.empty()) bad = "handle output '" + o.name + "' names no kind";
  }
  r.add(suite, "outputs declared once each, handles name their kind", !info.outputs.empty() && bad.empty(),
        info.outputs.empty() ? "no outputs" : bad);
  const std::string presentation = detail::presentation_problem(info);
  r.add(suite, "presentation: frames declared and acyclic, codes unique, notes and points name what the type has",
        presentation.empty(), presentation);
  return r;
}

/// The domain suite for one handle value, by its kind; a kind without a suite is skipped.
inline Report check_domain_object(const DomainObject& object, const std::string& suite, const NodeCheckOptions& options) {
  Report r;
  if (const auto* law = dynamic_cast<const CamLaw*>(&object)) return check_cam_law(*law, suite, options.cam_law);
  if (const auto* model = dynamic_cast<const SpringModel*>(&object)) return check_spring_model(*model, suite);
  if (const auto* spring = dynamic_cast<const Spring*>(&object)) return check_spring(*spring, suite);
  if (const auto* follower = dynamic_cast<const Follower*>(&object)) return check_follower_on_reference(*follower, suite);
  if (const auto* fit = dynamic_cast<const Fit*>(&object)) return check_fit(*fit, suite);
  if (const auto* play = dynamic_cast<const JointPlay*>(&object)) return check_joint_play(*play, suite);
  r.skip(suite, "interface suite", "no conformance suite for kind '" + std::string(object.kind()) + "'");
  return r;
}

inline Report check_node_type(const NodeType& type, const NodeCheckOptions& options = {}) {
  const NodeInfo& info = type.info();
  const std::string suite = "node " + info.type;
  Report r = check_node_info(info);

  ParamSet params;
  try {
    params = params_with_defaults(info, options.values);
  } catch (const std::invalid_argument& e) {
    r.skip(suite, "evaluation with its defaults", e.what());
    return r;
  }
  {
    // Before any evaluation (it needs none): every input connected, as the host sizes a small value.
    InputSizes sizes;
    for (const PortSpec& in : info.inputs) sizes[in.name] = 1.0;
    check_forecast_reads(type, params, sizes, r, suite);
  }
  InputSet inputs;
  for (const PortSpec& in : info.inputs) {
    std::optional<Value> v = options.input_for ? options.input_for(in) : std::nullopt;
    if (v) inputs.add(in.name, *v);
    else if (!in.optional) {
      r.skip(suite, "evaluation with its defaults",
             "needs input '" + in.name + "'" + (in.kind == ValueKind::handle ? " (" + in.handle_kind + ")" : "") + " and none was given");
      return r;
    }
  }

  HarnessRun first;
  try {
    first = run_node(type, params, inputs);
  } catch (const NodeError& e) {
    // An input the harness was given (another type's object) may not suit this type: that is the
    // input's fault, not the type's.
    if (info.find_input(e.parameter()) && !info.find_param(e.parameter())) {
      r.skip(suite, "evaluation with its defaults", "it refused the input '" + e.parameter() + "' it was given: " + e.what());
      return r;
    }
    r.add(suite, evaluation_check, false, "NodeError on '" + e.parameter() + "': " + e.what());
    return r;
  } catch (const std::exception& e) {
    r.add(suite, evaluation_check, false, std::string("threw ") + e.what() + " (a node throws NodeError naming the parameter)");
    return r;
  } catch (...) {
    r.add(suite, evaluation_check, false, "threw something that is not a std::exception");
    return r;
  }
  r.add(suite, evaluation_check, true);

  std::string bad;
  for (const auto& [port, v] : first.outputs.all()) {
    const PortSpec* spec = info.find_output(port);
    if (!spec) bad = "produced undeclared output '" + port + "'";
    else if (spec->kind != v.kind()) bad = "output '" + port + "' is a " + std::string(to_string(v.kind())) + ", declared " + std::string(to_string(spec->kind));
    else if (v.kind() == ValueKind::handle && (!v.as_handle() || v.as_handle()->kind() != spec->handle_kind))
      bad = "output '" + port + "' carries no " + spec->handle_kind;
  }
  // A declared output may be absent for some parameters (a play that needs a given clearance); the
  // host refuses a request for it then. Listed, not failed.
  std::string absent;
  for (const PortSpec& o : info.outputs)
    if (!info.effect_of_output(o.name) && first.outputs.all().find(o.name) == first.outputs.all().end())
      absent += (absent.empty() ? "not produced with these parameters: " : ", ") + o.name;
  r.add(suite, "produces only its declared outputs, of their kinds", bad.empty(), bad.empty() ? absent : bad);
  std::string missing, unmet;
  for (const auto& [port, v] : first.outputs.all()) {
    const PortSpec* spec = info.find_output(port);
    if (!spec) continue;
    bool fatal = false;
    const std::string text = detail::presentation_missing(*spec, v, fatal);
    if (fatal) missing = text;
    else if (!text.empty()) unmet += (unmet.empty() ? "declared, not in these tables: " : ", ") + text;
  }
  r.add(suite, "its tables have the axis and x channel their presentation names", missing.empty(), missing.empty() ? unmet : missing);

  bad.clear();
  for (const auto& [port, v] : first.outputs.all())
    if (!all_finite(v)) bad = "output '" + port + "'";
  r.add(suite, "no NaN or Inf in any output", bad.empty(), bad.empty() ? "" : "not finite: " + bad);

  bad.clear();
  std::string counted;
  for (const auto& [counter, amount] : first.context.work) {
    bool declared = false;
    for (const auto& w : info.work_counters) declared = declared || w == counter;
    if (!declared) bad = "reports undeclared counter '" + counter + "'";
    if (!std::isfinite(amount) || amount < 0) bad = "counter '" + counter + "' is " + detail::num(amount);
    counted += (counted.empty() ? "" : ", ") + counter + " " + detail::num(amount);
  }
  if (!info.work_counters.empty() && first.context.work.empty()) bad = "declares work counters but reported none";
  r.add(suite, "reports its work on declared counters", bad.empty(), bad.empty() ? counted : bad);

  try {
    std::string where;
    const HarnessRun again = run_node(type, params, inputs);
    r.add(suite, "deterministic: the same inputs give the same bits", detail::same_outputs(first.outputs, again.outputs, where),
          where.empty() ? "" : "differs at " + where);
  } catch (const std::exception& e) {
    r.add(suite, "deterministic: the same inputs give the same bits", false, std::string("the second evaluation threw: ") + e.what());
  }
  check_block_evaluation(type, params, inputs, first.outputs, r, suite);
  if (options.threads > 1) {
    // All threads start together (a gate opened once every thread that could start has started)
    // and evaluate several times each, so the evaluations overlap. Threads that cannot start (a
    // process or memory limit) are left out and the check says how many ran.
    constexpr int rounds = 8;
    const auto wanted = static_cast<unsigned>(options.threads);
    std::vector<std::optional<HarnessRun>> runs(wanted);
    std::vector<std::string> errors(runs.size());
    std::atomic<bool> open{false};
    const auto evaluate = [&](unsigned i) {
      while (!open.load(std::memory_order_acquire)) std::this_thread::yield();
      try {
        std::string where;
        for (int k = 0; k < rounds; ++k) {
          runs[i] = run_node(type, params, inputs);
          if (!detail::same_outputs(first.outputs, runs[i]->outputs, where)) break;
        }
      } catch (const std::exception& e) {
        errors[i] = e.what();
      } catch (...) {
        errors[i] = "a non-standard exception";
      }
    };
    unsigned ran = 1;
    {
      WorkerThreads more(wanted - 1, evaluate);
      open.store(true, std::memory_order_release);
      evaluate(0);
      more.join();
      ran += more.started();
    }
    runs.resize(ran);
    std::string where;
    for (std::size_t i = 0; i < runs.size() && where.empty(); ++i) {
      if (!errors[i].empty()) where = "thread " + std::to_string(i) + " threw: " + errors[i];
      else if (!detail::same_outputs(first.outputs, runs[i]->outputs, where)) where = "thread " + std::to_string(i) + " differs at " + where;
    }
    const std::string threads_text = ran == wanted ? std::to_string(wanted) + " threads"
                                                   : std::to_string(ran) + " threads (of " + std::to_string(wanted) +
                                                         " asked; the rest could not start)";
    r.add(suite, "thread-safe: " + threads_text + " x " + std::to_string(rounds) + " evaluations at once agree",
          where.empty(), where);
  }

  for (const auto& [port, v] : first.outputs.all()) {
    if (v.kind() != ValueKind::handle || !v.as_handle()) continue;
    const std::string domain_suite = std::string(v.as_handle()->kind()) + " " + info.type + "." + port;
    try {
      r.append(check_domain_object(*v.as_handle(), domain_suite, options));
      // The cam node convention: peak outputs beside the law agree with the law sampled densely.
      if (const auto* law = dynamic_cast<const CamLaw*>(v.as_handle().get())) r.append(check_cam_peaks(*law, first.outputs, domain_suite));
    } catch (const std::exception& e) {
      r.add(domain_suite, "interface suite", false, std::string("the object threw while checked: ") + e.what());
    }
  }
  return r;
}

}  // namespace mechgraph::testing
