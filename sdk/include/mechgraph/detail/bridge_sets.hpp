#pragma once
// The ParamSet, InputSet and OutputSet a C++ node type behind MECHGRAPH_PLUGIN_1 evaluates with
// (docs/design/sdk-1.0.md, 3.2; mechgraph/detail/export_node.hpp): made once per node type and
// thread, and refreshed in place from each evaluation's C arguments, so that an evaluation
// allocates nothing for them once the sets have their shape, and the node's lookups cost what
// they cost on the pre-1.0 entry (the same std::map the host fills for a pre-1.0 node).
//
// Why refreshed sets and not views over mg_eval_args: the three classes are SDK 1.0's, with their
// layout and inline accessors compiled into plugins built against the sdk-1.0 tag, which call
// libmechgraph_sdk's ParamSet::get and InputSet::value with that layout (scripts/test-sdk-compat.sh
// holds it), and their accessors return references to std::string, std::vector and Record, which a
// view over mg_param_value would have to make anyway. Refreshed in place, a number is one store, a
// text or list one copy into the capacity it already has; a parameter that comes or goes, a list
// that grows, or an output the node does not declare makes the set again, once.
//
// Inside evaluate, the OutputSet lists every declared output from the start: one not set in this
// evaluation holds an empty placeholder (a handle of no kind) that never reaches the host.
#include <mechgraph/c/node.h>
#include <mechgraph/c/value.h>
#include <mechgraph/detail/object_bridge.hpp>
#include <mechgraph/node.hpp>

#include <algorithm>
#include <cstdint>
#include <deque>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace mechgraph::detail {

inline Dimension cxx_dim(const mg_dim& d) { return {d.length, d.mass, d.time, d.angle, d.temperature}; }

/// `out` made equal to the C parameter value `v` of `spec`, reusing what `out` already holds.
inline void assign_param(ParamValue& out, const mg_param_value& v, const ParamSpec& spec) {
  out.kind = spec.kind;
  out.number = v.number;
  if (spec.kind == ParamKind::number || spec.kind == ParamKind::integer) {
    // A number's view carries no text, list or records (CallViews, ParamViews): what `out` held of
    // them is emptied only when it holds any, so a sweep's numbers are one store each.
    if (!v.text.data && !v.numbers && !v.records) {
      if (!out.text.empty()) out.text.clear();
      if (!out.numbers.empty()) out.numbers.clear();
      if (!out.records.empty()) out.records.clear();
      return;
    }
  }
  if (v.text.data)
    out.text.assign(v.text.data, v.text.size);
  else
    out.text.clear();
  if (v.numbers)
    out.numbers.assign(v.numbers, v.numbers + v.number_count);
  else
    out.numbers.clear();
  out.records.resize(v.records ? v.record_count : 0);
  for (std::size_t r = 0; r < out.records.size(); ++r) {
    Record& record = out.records[r];
    const mg_record& c = v.records[r];
    for (std::size_t f = 0; f < spec.fields.size(); ++f) {
      const std::string& name = spec.fields[f].name;
      auto it = record.find(name);
      if (f < c.field_count && c.fields[f].present) {
        if (it == record.end()) it = record.emplace(name, ParamValue{}).first;
        assign_param(it->second, c.fields[f], spec.fields[f]);
      } else if (it != record.end()) {
        record.erase(it);
      }
    }
  }
}

/// `params` made to hold the C parameters `c` (declared order, as info.params), reusing it.
/// `slots` (one per declared parameter, nullptr when absent) points into `params`; a parameter
/// that came or went since the last call makes the set again.
inline void load_params(ParamSet& params, std::vector<ParamValue*>& slots, const std::vector<ParamSpec>& specs,
                        const mg_param_value* c) {
  const auto make = [&] {
    params = ParamSet();
    slots.assign(specs.size(), nullptr);
    for (std::size_t i = 0; i < specs.size(); ++i)
      if (c[i].present) slots[i] = &params.slot(specs[i].name);
  };
  if (slots.size() != specs.size()) make();
  // One pass: a presence that differs makes the set again (then every presence agrees) and starts
  // over; a number is a store or two (assign_param).
  for (std::size_t i = 0; i < specs.size(); ++i) {
    ParamValue* out = slots[i];
    if ((c[i].present != 0) != (out != nullptr)) {
      make();
      i = static_cast<std::size_t>(-1);
      continue;
    }
    if (out) assign_param(*out, c[i], specs[i]);
  }
}

inline Table::Column cxx_column(const mg_column& c, std::size_t rows) {
  return {c.name ? c.name : "", cxx_dim(c.dim), std::vector<double>(c.values, c.values + rows), c.display_unit ? c.display_unit : ""};
}

/// An input value as the node reads it: a scalar as it is, a series or table copied (the host's
/// arrays are borrowed for the call only), an object imported (its own C++ object when this plugin
/// made it, else a view over its C tables).
inline Value cxx_input(const mg_value& v, const std::string& interface) {
  switch (v.kind) {
    case MG_VALUE_OBJECT: return Value::handle(import_object(v.u.object, interface, 1));
    case MG_VALUE_SCALAR: return Value::scalar(v.u.scalar);
    case MG_VALUE_SERIES: {
      const mg_series& s = *v.u.series;
      Series out{{s.axis, s.axis + s.size}, {s.values, s.values + s.size}, cxx_dim(s.axis_dim), {}};
      if (s.labels)
        for (std::size_t i = 0; i < s.size; ++i) out.labels.emplace_back(s.labels[i] ? s.labels[i] : "");
      return Value::series(std::move(out));
    }
    case MG_VALUE_TABLE: {
      const mg_table& t = *v.u.table;
      Table out;
      out.axis = cxx_column(t.axis, t.rows);
      for (std::size_t i = 0; i < t.channel_count; ++i) out.channels.push_back(cxx_column(t.channels[i], t.rows));
      out.closed_curve = (t.flags & MG_TABLE_CLOSED_CURVE) != 0;
      out.histogram = (t.flags & MG_TABLE_HISTOGRAM) != 0;
      out.turns_clockwise = (t.flags & MG_TABLE_TURNS_CW) != 0;
      for (std::size_t i = 0; i < t.mark_count; ++i) out.axis_marks.push_back({t.marks[i].label ? t.marks[i].label : "", t.marks[i].value});
      return Value::table(std::move(out));
    }
    default: throw std::invalid_argument("an input value of a kind this bridge does not import");
  }
}

/// What an output holds while the node has not set it: a handle to this object, owned by nobody
/// (no reference count is touched when it is copied).
class UnsetOutput final : public DomainObject {
 public:
  std::string_view kind() const override { return {}; }
};
MECHGRAPH_DETAIL_HIDDEN inline const Value& unset_output() {
  static const UnsetOutput object;
  static const Value placeholder = Value::handle(std::shared_ptr<const DomainObject>(std::shared_ptr<const DomainObject>(), &object));
  return placeholder;
}
inline bool is_unset(const Value& v) { return v.kind() == ValueKind::handle && v.as_handle().get() == unset_output().as_handle().get(); }

/// The sets of one node type's evaluations on one thread (see the top of this file).
class BridgeSets {
 public:
  explicit BridgeSets(const NodeInfo& info) : info_(info) { make_outputs(); }
  BridgeSets(const BridgeSets&) = delete;
  BridgeSets& operator=(const BridgeSets&) = delete;

  ParamSet params;
  InputSet inputs;
  OutputSet outputs;
  InputSizes sizes;   // a forecast's (load_forecast)
  bool busy = false;  // an evaluation is using them (a nested one on this thread makes its own)

  /// Parameters and input sizes of one forecast (node_forecast.h): `input_sizes` holds one
  /// figure per declared input, 0 for one not connected (left out of `sizes`, as the host's
  /// InputSizes leaves it out). Refreshed in place as the parameters are; an input that came or
  /// went makes `sizes` again.
  void load_forecast(const mg_param_value* c_params, const double* input_sizes) {
    load_params(params, param_slots_, info_.params, c_params);
    bool same = size_slots_.size() == info_.inputs.size();
    for (std::size_t i = 0; same && i < info_.inputs.size(); ++i) same = (input_sizes[i] > 0) == (size_slots_[i] != nullptr);
    if (!same) {
      sizes = InputSizes();
      size_slots_.assign(info_.inputs.size(), nullptr);
      for (std::size_t i = 0; i < info_.inputs.size(); ++i)
        if (input_sizes[i] > 0) size_slots_[i] = &sizes[info_.inputs[i].name];
    }
    for (std::size_t i = 0; i < info_.inputs.size(); ++i)
      if (size_slots_[i]) *size_slots_[i] = input_sizes[i];
  }

  /// Parameters and inputs of one evaluation; `interfaces` names each input port's interface.
  void load(const mg_eval_args& args, const std::deque<std::string>& interfaces) {
    if (output_slots_.size() != info_.outputs.size()) make_outputs();
    load_params(params, param_slots_, info_.params, args.params);
    if (input_slots_.size() != info_.inputs.size()) {
      inputs = InputSet();
      input_slots_.clear();
      for (const PortSpec& p : info_.inputs) input_slots_.push_back(&inputs.slot(p.name));
    }
    for (std::size_t i = 0; i < info_.inputs.size(); ++i)
      for (std::size_t k = 0; k < args.inputs[i].count; ++k) input_slots_[i]->push_back(cxx_input(args.inputs[i].values[k], interfaces[i]));
  }

  /// Hands `put(index, value)` each output the node set (the value may be moved from), by declared
  /// index, in the order of their names (as the host's set lists them); throws std::logic_error
  /// naming an output the node does not declare.
  template <class Put>
  mg_status put_outputs(Put&& put) {
    if (outputs.all().size() != output_slots_.size())
      for (const auto& [name, value] : outputs.all())
        if (!info_.find_output(name)) throw std::logic_error("set output '" + name + "', which it does not declare");
    for (const auto& [slot, index] : output_slots_)
      if (!is_unset(*slot))
        if (const mg_status s = put(index, *slot); s != MG_OK) return s;
    return MG_OK;
  }

  /// After an evaluation, however it ended: inputs and outputs let go (objects released), notes
  /// emptied, and an output the node does not declare removed with the set made again.
  void release() noexcept {
    for (std::vector<Value>* values : input_slots_) values->clear();
    for (const auto& [slot, index] : output_slots_)
      if (!is_unset(*slot)) *slot = unset_output();
    outputs.clear_notes();
    if (outputs.all().size() != output_slots_.size()) {
      try {
        make_outputs();
      } catch (...) {  // out of memory: the next evaluation makes them again
        output_slots_.clear();
      }
    }
  }

 private:
  void make_outputs() {
    outputs = OutputSet();
    output_slots_.clear();
    for (std::size_t i = 0; i < info_.outputs.size(); ++i) {
      Value& slot = outputs.slot(info_.outputs[i].name);
      slot = unset_output();
      output_slots_.emplace_back(&slot, static_cast<std::uint32_t>(i));
    }
    std::sort(output_slots_.begin(), output_slots_.end(),
              [&](const auto& a, const auto& b) { return info_.outputs[a.second].name < info_.outputs[b.second].name; });
  }

  const NodeInfo& info_;
  std::vector<ParamValue*> param_slots_;
  std::vector<double*> size_slots_;  // into `sizes`, one per declared input, nullptr when absent
  std::vector<std::vector<Value>*> input_slots_;
  std::vector<std::pair<Value*, std::uint32_t>> output_slots_;  // by output name
};

}  // namespace mechgraph::detail
