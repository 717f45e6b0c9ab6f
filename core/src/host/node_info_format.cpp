#include <mechgraph/host/node_info_format.hpp>

#include <mechgraph/host/exit_codes.hpp>
#include <mechgraph/host/usage_error.hpp>
#include <mechgraph/shown_number.hpp>

#include <mechgraph/text_escape.hpp>

#include <cmath>
#include <sstream>

namespace mechgraph::host {
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

const char* role_name(Role r) {
  switch (r) {
    case Role::plain: return "plain";
    case Role::derivative_family: return "derivative_family";
    case Role::curve_over_channel: return "curve_over_channel";
    case Role::drawing_to_scale: return "drawing_to_scale";
    case Role::events: return "events";
    case Role::histogram: return "histogram";
  }
  return "plain";
}

std::vector<std::string> flag_names(std::uint32_t flags) {
  std::vector<std::string> out;
  const std::pair<std::uint32_t, const char*> known[] = {{channel_flag::alt_axis, "alt_axis"}, {channel_flag::curvature, "curvature"},
                                                         {channel_flag::positive_only, "positive_only"}, {channel_flag::not_drawn, "not_drawn"},
                                                         {channel_flag::line_from_mark, "line_from_mark"},
                                                         {channel_flag::jumps_at_events, "jumps_at_events"},
                                                         {channel_flag::range_of_rows, "range_of_rows"}};
  for (const auto& [bit, name] : known)
    if (flags & bit) out.emplace_back(name);
  return out;
}

// A channel declaration in one line: "event: \"event after start\", frame shaft, codes 1 a, 2 b".
std::string channel_text(const ChannelDecl& c) {
  std::ostringstream os;
  os << c.name << ":";
  if (!c.label.empty()) os << " \"" << c.label << "\"";
  if (!c.display_unit.empty()) os << " in " << c.display_unit;
  if (!c.angle_frame.empty()) os << " frame " << c.angle_frame;
  if (c.derivative_order >= 0) os << " derivative " << c.derivative_order;
  for (const std::string& f : flag_names(c.flags)) os << " " << f;
  if (!c.from_mark.empty()) os << " from mark \"" << c.from_mark << "\"";
  if (!c.codes.empty()) {
    os << " codes";
    for (std::size_t k = 0; k < c.codes.size(); ++k) os << (k ? ", " : " ") << c.codes[k].value << " " << c.codes[k].name;
  }
  return os.str();
}

void write_presentation_text(std::ostream& os, const PortSpec& p) {
  if (!p.label.empty()) os << "      label: " << p.label << "\n";
  if (!p.angle_frame.empty()) os << "      angle frame: " << p.angle_frame << "\n";
  const Presentation& pr = p.presentation;
  if (pr.empty()) return;
  os << "      presented as " << role_name(pr.role);
  if (!pr.x_channel.empty()) os << " over " << pr.x_channel;
  if (!pr.figure_title.empty()) os << ", \"" << pr.figure_title << "\"";
  os << "\n";
  if (pr.has_axis) os << "        axis " << channel_text(pr.axis) << "\n";
  for (const ChannelDecl& c : pr.channels) os << "        channel " << channel_text(c) << "\n";
  for (const XyPair& xy : pr.pairs) os << "        pair " << xy.x << ", " << xy.y << " on layer " << xy.layer << " (stroke " << xy.stroke << ")\n";
  for (const PointMarks& pm : pr.points) {
    os << "        points from " << pm.port << " row " << pm.row << ":";
    for (std::size_t k = 0; k < pm.x_channels.size(); ++k) os << " " << pm.x_channels[k] << (k < pm.labels.size() ? " (" + pm.labels[k] + ")" : "");
    os << "\n";
  }
}

void write_channel_json(JsonWriter& json, const ChannelDecl& c) {
  json.begin_object().key("name").value(c.name);
  if (!c.label.empty()) json.key("label").value(c.label);
  if (!c.display_unit.empty()) json.key("display_unit").value(c.display_unit);
  if (!c.angle_frame.empty()) json.key("angle_frame").value(c.angle_frame);
  if (c.derivative_order >= 0) json.key("derivative_order").value(static_cast<long>(c.derivative_order));
  json.key("flags").begin_array();
  for (const std::string& f : flag_names(c.flags)) json.value(f);
  json.end_array();
  if (!c.from_mark.empty()) json.key("from_mark").value(c.from_mark);
  if (!c.codes.empty()) {
    json.key("codes").begin_array();
    for (const Code& code : c.codes) json.begin_object().key("value").value(code.value).key("name").value(code.name).key("doc").value(code.doc).end_object();
    json.end_array();
  }
  json.end_object();
}

void write_presentation_json(JsonWriter& json, const PortSpec& p) {
  if (!p.label.empty()) json.key("label").value(p.label);
  if (!p.angle_frame.empty()) json.key("angle_frame").value(p.angle_frame);
  const Presentation& pr = p.presentation;
  if (pr.empty()) return;
  json.key("presentation").begin_object().key("role").value(role_name(pr.role));
  if (pr.has_axis) {
    json.key("axis");
    write_channel_json(json, pr.axis);
  }
  json.key("channels").begin_array();
  for (const ChannelDecl& c : pr.channels) write_channel_json(json, c);
  json.end_array();
  if (!pr.x_channel.empty()) json.key("x_channel").value(pr.x_channel);
  json.key("pairs").begin_array();
  for (const XyPair& xy : pr.pairs)
    json.begin_object().key("x").value(xy.x).key("y").value(xy.y).key("layer").value(xy.layer).key("label").value(xy.label)
        .key("stroke").value(static_cast<long>(xy.stroke)).end_object();
  json.end_array();
  json.key("points").begin_array();
  for (const PointMarks& pm : pr.points) {
    json.begin_object().key("port").value(pm.port).key("row").value(static_cast<long>(pm.row)).key("x_channels").begin_array();
    for (const std::string& x : pm.x_channels) json.value(x);
    json.end_array().key("labels").begin_array();
    for (const std::string& l : pm.labels) json.value(l);
    json.end_array().key("y_from_axis").value(pm.y_from_axis).key("caption").value(pm.caption).end_object();
  }
  json.end_array();
  if (!pr.figure_title.empty()) json.key("figure_title").value(pr.figure_title);
  if (!pr.caption.empty()) json.key("caption").value(pr.caption);
  json.end_object();
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
    write_presentation_text(os, p);
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
    write_presentation_json(json, p);
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
  if (!info.frames.empty()) os << "\nangle frames:\n";
  for (const AngleFrame& f : info.frames) {
    os << "  " << f.id << ": " << f.label << " (degrees shown as deg (" << f.unit_tag << ")); zero: " << f.zero << "\n";
    if (!f.base_frame.empty())
      os << "      = " << f.scale << " x " << f.base_frame << " + " << (f.offset_param.empty() ? "0" : f.offset_param) << "\n";
    if (f.mark_spacing > 0.0) {
      os << "      marks every " << f.mark_spacing * 180.0 / 3.141592653589793 << " deg:";
      for (const std::string& l : f.mark_labels) os << " " << l;
      os << "; quoted " << f.before << "/" << f.after << "\n";
    }
  }
  if (!info.notes.empty()) os << "\nnotes:\n";
  for (const NoteDecl& n : info.notes) os << "  with " << n.when_param << ", made with " << n.output << ": " << n.doc << "\n";
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
  json.key("frames").begin_array();
  for (const AngleFrame& f : info.frames) {
    json.begin_object().key("id").value(f.id).key("label").value(f.label).key("unit_tag").value(f.unit_tag).key("zero").value(f.zero);
    if (!f.base_frame.empty()) json.key("base_frame").value(f.base_frame).key("scale").value(f.scale).key("offset_param").value(f.offset_param);
    if (f.mark_spacing > 0.0) {
      json.key("mark_spacing").value(f.mark_spacing).key("mark_labels").begin_array();
      for (const std::string& l : f.mark_labels) json.value(l);
      json.end_array().key("before").value(f.before).key("after").value(f.after);
    }
    json.end_object();
  }
  json.end_array();
  json.key("notes").begin_array();
  for (const NoteDecl& n : info.notes) json.begin_object().key("output").value(n.output).key("when_param").value(n.when_param).key("doc").value(n.doc).end_object();
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

}  // namespace mechgraph::host
