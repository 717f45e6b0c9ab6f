#include "node_info_format.hpp"

#include "cli.hpp"

#include <mechgraph/text_escape.hpp>

#include <cmath>
#include <sstream>

namespace mechgraph::cli {
namespace {

const char* kind_name(ParamKind k) {
  switch (k) {
    case ParamKind::number: return "number";
    case ParamKind::integer: return "integer";
    case ParamKind::choice: return "choice";
    case ParamKind::text: return "text";
    case ParamKind::number_list: return "number list";
    case ParamKind::record_list: return "record list";
  }
  return "?";
}

std::string shown(double si, const ParamSpec& p) {
  try {
    return format_value(si, p.dimension, p.display_unit);
  } catch (const std::exception&) {
    return format_value(si, p.dimension, "");
  }
}

std::string default_text(const ParamSpec& p) {
  if (!p.default_value) {
    std::string out = p.required ? "required" : "optional";
    if (p.example_value && (p.kind == ParamKind::number || p.kind == ParamKind::integer))
      out += ", e.g. " + shown(p.example_value->number, p);
    else if (p.example_value && !p.example_value->text.empty()) out += ", e.g. " + p.example_value->text;
    return out;
  }
  const ParamValue& v = *p.default_value;
  switch (v.kind) {
    case ParamKind::number:
    case ParamKind::integer: return "default " + shown(v.number, p);
    case ParamKind::choice:
    case ParamKind::text: return "default " + v.text;
    case ParamKind::number_list: {
      std::string out = "default [";
      for (std::size_t i = 0; i < v.numbers.size(); ++i) out += (i ? ", " : "") + shown(v.numbers[i], p);
      return out + "]";
    }
    case ParamKind::record_list: return "default list";
  }
  return "";
}

std::string range_text(const ParamSpec& p) {
  std::string out;
  if (std::isfinite(p.min)) out += (p.min_exclusive ? "> " : ">= ") + shown(p.min, p);
  if (std::isfinite(p.max)) out += (out.empty() ? "" : ", ") + std::string(p.max_exclusive ? "< " : "<= ") + shown(p.max, p);
  return out;
}

void write_params_text(std::ostream& os, const std::vector<ParamSpec>& params, const std::string& indent) {
  for (const ParamSpec& p : params) {
    os << indent << p.name << "  (" << kind_name(p.kind);
    if (p.kind == ParamKind::number || p.kind == ParamKind::number_list)
      os << ", " << p.dimension.describe() << ", " << (p.display_unit.empty() ? p.dimension.si_unit() : p.display_unit);
    os << "; " << default_text(p);
    if (const std::string r = range_text(p); !r.empty()) os << "; " << r;
    if (p.knob) os << "; accuracy knob";
    os << ")\n" << indent << "    " << p.doc << "\n";
    if (!p.range_reason.empty()) os << indent << "    range: " << p.range_reason << "\n";
    if (!p.choices.empty()) {
      os << indent << "    choices:";
      for (const auto& c : p.choices) os << " " << c;
      os << "\n";
    }
    if (!p.fields.empty()) write_params_text(os, p.fields, indent + "    ");
  }
}

void write_ports_text(std::ostream& os, const std::vector<PortSpec>& ports) {
  for (const PortSpec& p : ports) {
    os << "  " << p.name << "  (";
    if (p.kind == ValueKind::handle) os << "handle: " << p.handle_kind;
    else if (p.kind == ValueKind::table) os << "table of curves";
    else os << to_string(p.kind) << ", " << p.dimension.describe() << ", " << p.dimension.si_unit();
    if (!p.display_unit.empty()) os << ", shown in " << p.display_unit;
    if (p.multiple) os << ", one or more";
    if (p.optional) os << ", optional";
    os << ")\n      " << p.doc << "\n";
  }
}

void write_params_json(JsonWriter& json, const std::vector<ParamSpec>& params) {
  json.begin_array();
  for (const ParamSpec& p : params) {
    json.begin_object();
    json.key("name").value(p.name).key("kind").value(kind_name(p.kind)).key("doc").value(p.doc);
    json.key("dimension").value(p.dimension.describe()).key("unit").value(p.dimension.si_unit());
    if (!p.display_unit.empty()) json.key("display_unit").value(p.display_unit);
    json.key("required").value(p.required).key("knob").value(p.knob);
    if (p.default_value) {
      json.key("default");
      const ParamValue& v = *p.default_value;
      if (v.kind == ParamKind::number || v.kind == ParamKind::integer) json.value(v.number);
      else if (v.kind == ParamKind::number_list) json.numbers(v.numbers);
      else json.value(v.text);
    }
    if (std::isfinite(p.min)) json.key(p.min_exclusive ? "above" : "min").value(p.min);
    if (std::isfinite(p.max)) json.key(p.max_exclusive ? "below" : "max").value(p.max);
    if (!p.range_reason.empty()) json.key("range_reason").value(p.range_reason);
    if (!p.choices.empty()) {
      json.key("choices").begin_array();
      for (const auto& c : p.choices) json.value(c);
      json.end_array();
    }
    if (!p.fields.empty()) {
      json.key("fields");
      write_params_json(json, p.fields);
    }
    json.end_object();
  }
  json.end_array();
}

void write_ports_json(JsonWriter& json, const std::vector<PortSpec>& ports) {
  json.begin_array();
  for (const PortSpec& p : ports) {
    json.begin_object();
    json.key("name").value(p.name).key("kind").value(to_string(p.kind)).key("doc").value(p.doc);
    if (p.kind == ValueKind::handle) json.key("handle").value(p.handle_kind);
    else if (p.kind == ValueKind::table) {}
    else json.key("dimension").value(p.dimension.describe()).key("unit").value(p.dimension.si_unit());
    if (!p.display_unit.empty()) json.key("display_unit").value(p.display_unit);
    json.key("multiple").value(p.multiple).key("optional").value(p.optional);
    json.end_object();
  }
  json.end_array();
}

// The description as written by the plugin, before terminal_text.
void write_node_info_raw(std::ostream& os, const NodeInfo& info) {
  os << info.type << " (version " << info.version << ")\n  " << info.summary << "\n\nparameters:\n";
  write_params_text(os, info.params, "  ");
  os << "\ninputs:\n";
  if (info.inputs.empty()) os << "  (none)\n";
  write_ports_text(os, info.inputs);
  os << "\noutputs:\n";
  write_ports_text(os, info.outputs);
  if (!info.output_dependencies.empty()) {
    os << "\noutput dependencies:\n";
    for (const auto& [out, ins] : info.output_dependencies) {
      os << "  " << out << " <-";
      for (const auto& i : ins) os << " " << i;
      os << "\n";
    }
  }
  os << "\neffects:\n";
  if (info.effects.empty()) os << "  (none)\n";
  for (const EffectSpec& e : info.effects) {
    os << "  " << e.name << ": " << e.doc << "\n";
    auto list = [&](const char* what, const std::vector<std::string>& names) {
      if (names.empty()) return;
      os << "      " << what << ":";
      for (const auto& n : names) os << " " << n;
      os << "\n";
    };
    list("brings outputs", e.outputs);
    list("reads parameters", e.params);
  }
  os << "\nwork counters:";
  for (const auto& w : info.work_counters) os << " " << w;
  os << "\n";
}

}  // namespace

void write_node_info_text(std::ostream& os, const NodeInfo& info) {
  std::ostringstream raw;
  write_node_info_raw(raw, info);
  os << terminal_text(raw.str());
}

void write_node_info_json(JsonWriter& json, const NodeInfo& info) {
  json.begin_object();
  json.key("type").value(info.type).key("version").value(static_cast<long>(info.version)).key("summary").value(info.summary);
  json.key("params");
  write_params_json(json, info.params);
  json.key("inputs");
  write_ports_json(json, info.inputs);
  json.key("outputs");
  write_ports_json(json, info.outputs);
  json.key("effects").begin_array();
  for (const EffectSpec& e : info.effects) {
    json.begin_object().key("name").value(e.name).key("doc").value(e.doc);
    json.key("outputs").begin_array();
    for (const auto& o : e.outputs) json.value(o);
    json.end_array().key("params").begin_array();
    for (const auto& p : e.params) json.value(p);
    json.end_array().end_object();
  }
  json.end_array();
  json.key("work_counters").begin_array();
  for (const auto& w : info.work_counters) json.value(w);
  json.end_array();
  json.key("output_dependencies").begin_object();
  for (const auto& [out, ins] : info.output_dependencies) {
    json.key(out).begin_array();
    for (const auto& i : ins) json.value(i);
    json.end_array();
  }
  json.end_object();
  json.end_object();
}

}  // namespace mechgraph::cli
