#include <mechgraph/node.hpp>

#include <mechgraph/units.hpp>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace mechgraph {

namespace {

std::string format_number(double v) {
  std::ostringstream os;
  os.precision(6);
  os << v;
  return os.str();
}

// A limit in the parameter's display unit if it has one ("0.1 deg"), else in SI.
std::string quantity_text(double si, const ParamSpec& spec) {
  if (!spec.display_unit.empty()) {
    try {
      return format_number(to_unit(si, spec.dimension, spec.display_unit)) + " " + spec.display_unit;
    } catch (const UnitError&) {
    }
  }
  const std::string unit = spec.dimension.si_unit();
  return format_number(si) + (unit == "1" ? "" : " " + unit);
}

}  // namespace

bool ParamSpec::admits(double si) const {
  const bool low = min_exclusive ? !(si > min) : !(si >= min);
  const bool high = max_exclusive ? !(si < max) : !(si <= max);
  return !low && !high;
}

std::string ParamSpec::value_problem(double si) const {
  if (!admits(si)) {
    std::string range;
    if (std::isfinite(min)) range += (min_exclusive ? "> " : ">= ") + quantity_text(min, *this);
    if (std::isfinite(max))
      range += (range.empty() ? "" : " and ") + std::string(max_exclusive ? "< " : "<= ") + quantity_text(max, *this);
    return "is out of range: it must be " + range + (range_reason.empty() ? "" : " (" + range_reason + ")");
  }
  if (kind == ParamKind::integer && si != std::floor(si)) return "must be a whole number";
  if (kind == ParamKind::integer && std::abs(si) > 9007199254740992.0)  // 2^53: exact in a double
    return "is too large for a whole number (at most 2^53)";
  return {};
}

const ParamValue& ParamSet::get(std::string_view name) const {
  auto it = values_.find(name);
  if (it == values_.end()) throw NodeError(std::string(name), "parameter '" + std::string(name) + "' is not set");
  return it->second;
}

ParamSpec ParamSpec::number(std::string name, Dimension d, std::string doc, std::string unit) {
  ParamSpec s;
  s.name = std::move(name);
  s.kind = ParamKind::number;
  s.dimension = d;
  s.doc = std::move(doc);
  s.display_unit = std::move(unit);
  return s;
}
ParamSpec ParamSpec::integer(std::string name, std::string doc) {
  ParamSpec s = number(std::move(name), dim::none, std::move(doc));
  s.kind = ParamKind::integer;
  return s;
}
ParamSpec ParamSpec::choice(std::string name, std::vector<std::string> choices, std::string doc) {
  ParamSpec s;
  s.name = std::move(name);
  s.kind = ParamKind::choice;
  s.choices = std::move(choices);
  s.doc = std::move(doc);
  return s;
}
ParamSpec ParamSpec::text(std::string name, std::string doc) {
  ParamSpec s;
  s.name = std::move(name);
  s.kind = ParamKind::text;
  s.doc = std::move(doc);
  return s;
}
ParamSpec ParamSpec::number_list(std::string name, Dimension d, std::string doc, std::string unit) {
  ParamSpec s = number(std::move(name), d, std::move(doc), std::move(unit));
  s.kind = ParamKind::number_list;
  return s;
}
ParamSpec ParamSpec::record_list(std::string name, std::vector<ParamSpec> fields, std::string doc) {
  ParamSpec s;
  s.name = std::move(name);
  s.kind = ParamKind::record_list;
  s.fields = std::move(fields);
  s.doc = std::move(doc);
  return s;
}

ParamSpec& ParamSpec::with_default(double v) {
  default_value = kind == ParamKind::integer ? ParamValue::of_integer(static_cast<long>(v)) : ParamValue::of_number(v);
  required = false;
  return *this;
}
ParamSpec& ParamSpec::with_default(std::string v) {
  default_value = kind == ParamKind::choice ? ParamValue::of_choice(std::move(v)) : ParamValue::of_text(std::move(v));
  required = false;
  return *this;
}
ParamSpec& ParamSpec::with_default(std::vector<double> v) {
  default_value = ParamValue::of_list(std::move(v));
  required = false;
  return *this;
}
ParamSpec& ParamSpec::optional() {
  required = false;
  return *this;
}
ParamSpec& ParamSpec::positive() { return above(0.0); }
ParamSpec& ParamSpec::non_negative() { return at_least(0.0); }
ParamSpec& ParamSpec::at_least(double v) {
  min = v;
  min_exclusive = false;
  return *this;
}
ParamSpec& ParamSpec::above(double v) {
  min = v;
  min_exclusive = true;
  return *this;
}
ParamSpec& ParamSpec::at_most(double v) {
  max = v;
  max_exclusive = false;
  return *this;
}
ParamSpec& ParamSpec::below(double v) {
  max = v;
  max_exclusive = true;
  return *this;
}
ParamSpec& ParamSpec::because(std::string reason) {
  range_reason = std::move(reason);
  return *this;
}
ParamSpec& ParamSpec::with_example(double v) {
  example_value = kind == ParamKind::integer ? ParamValue::of_integer(static_cast<long>(v)) : ParamValue::of_number(v);
  return *this;
}
ParamSpec& ParamSpec::with_example(std::string v) {
  example_value = kind == ParamKind::choice ? ParamValue::of_choice(std::move(v)) : ParamValue::of_text(std::move(v));
  return *this;
}
ParamSpec& ParamSpec::with_example(std::vector<Record> v) {
  ParamValue value;
  value.kind = ParamKind::record_list;
  value.records = std::move(v);
  example_value = std::move(value);
  return *this;
}
ParamSpec& ParamSpec::as_knob() {
  knob = true;
  return *this;
}
ParamSpec& ParamSpec::as_path() {
  is_path = true;
  return *this;
}

PortSpec PortSpec::scalar(std::string name, Dimension d, std::string doc, std::string unit) {
  PortSpec p;
  p.name = std::move(name);
  p.kind = ValueKind::scalar;
  p.dimension = d;
  p.doc = std::move(doc);
  p.display_unit = std::move(unit);
  return p;
}
PortSpec PortSpec::series(std::string name, Dimension d, std::string doc, std::string unit) {
  PortSpec p = scalar(std::move(name), d, std::move(doc), std::move(unit));
  p.kind = ValueKind::series;
  return p;
}
PortSpec PortSpec::table(std::string name, std::string doc) {
  PortSpec p = scalar(std::move(name), dim::none, std::move(doc));
  p.kind = ValueKind::table;
  return p;
}
PortSpec PortSpec::handle(std::string name, std::string handle_kind, std::string doc) {
  PortSpec p;
  p.name = std::move(name);
  p.kind = ValueKind::handle;
  p.handle_kind = std::move(handle_kind);
  p.doc = std::move(doc);
  return p;
}
PortSpec& PortSpec::many() {
  multiple = true;
  return *this;
}
PortSpec& PortSpec::optional_port() {
  optional = true;
  return *this;
}

namespace {
template <class T>
const T* find_named(const std::vector<T>& items, std::string_view name) {
  auto it = std::find_if(items.begin(), items.end(), [&](const T& t) { return t.name == name; });
  return it == items.end() ? nullptr : &*it;
}
}  // namespace

const ParamSpec* NodeInfo::find_param(std::string_view name) const { return find_named(params, name); }
const PortSpec* NodeInfo::find_input(std::string_view name) const { return find_named(inputs, name); }
const PortSpec* NodeInfo::find_output(std::string_view name) const { return find_named(outputs, name); }
bool NodeInfo::implements_effect(std::string_view name) const { return find_named(effects, name) != nullptr; }

const EffectSpec* NodeInfo::effect_of_output(std::string_view port) const {
  for (const EffectSpec& e : effects)
    if (std::find(e.outputs.begin(), e.outputs.end(), port) != e.outputs.end()) return &e;
  return nullptr;
}

const EffectSpec* NodeInfo::effect_of_param(std::string_view name) const {
  for (const EffectSpec& e : effects)
    if (std::find(e.params.begin(), e.params.end(), name) != e.params.end()) return &e;
  return nullptr;
}

std::size_t InputSet::count(std::string_view port) const {
  auto it = values_.find(port);
  return it == values_.end() ? 0 : it->second.size();
}

const Value& InputSet::value(std::string_view port, std::size_t i) const {
  auto it = values_.find(port);
  if (it == values_.end() || i >= it->second.size())
    throw NodeError(std::string(port), "input '" + std::string(port) + "' is not connected");
  return it->second[i];
}

}  // namespace mechgraph
