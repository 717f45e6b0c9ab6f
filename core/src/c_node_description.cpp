#include "c_node_description.hpp"

#include <mechgraph/detail/object_bridge.hpp>

#include <mechgraph/errors.hpp>

#include <cstddef>

namespace mechgraph::detail {
namespace {

// A field of a growable struct, or `fallback` when the writer's struct ends before it.
#define MG_FIELD_OR(ptr, type, field, fallback) (MG_HAS_FIELD(ptr, type, field) ? (ptr)->field : (fallback))

std::string text(const char* s) { return s ? s : ""; }

// What a refusal names ("lib.so: node type 'acme.gauge' parameter 'span' default"), put together only
// when there is a refusal: a declaration is read for every type at every start, and it is sound.
// Each part is up to four pieces of text after its parent's; the pieces must outlive the part.
struct Subject {
  Subject(const Subject* up, std::string_view p1, std::string_view p2 = {}, std::string_view p3 = {}, std::string_view p4 = {})
      : parent(up), a(p1), b(p2), c(p3), d(p4) {}
  const Subject* parent;
  std::string_view a, b, c, d;
  std::string str() const {
    std::string s = parent ? parent->str() : std::string();
    s.append(a).append(b).append(c).append(d);
    return s;
  }
};
std::string operator+(const Subject& what, std::string_view more) { return what.str().append(more); }

Dimension c_dim(const mg_dim& d, const Subject& what);

// The part of each struct an SDK 1.x writer must fill (node.h, "Required prefixes"): shorter is
// refused; the fields after it may be absent and are then taken as their defaults.
template <class T>
void require_prefix(const T* p, std::size_t required, const Subject& what) {
  if (p->struct_size < required)
    throw PluginError(what + " is " + std::to_string(p->struct_size) + " bytes (struct_size), shorter than the " +
                      std::to_string(required) + " bytes every SDK 1.x writer fills; a defect of the plugin");
}

// Element i of a plugin's array of growable structs: all elements have the size of the first.
template <class T>
const T* element(const T* array, std::size_t i, std::size_t required, const Subject& what) {
  if (!array) throw PluginError(what + ": the array is missing (a null pointer with a non-zero count)");
  require_prefix(array, required, what);
  const T* e = MG_ELEMENT(T, array, i);
  if (e->struct_size != array->struct_size)
    throw PluginError(what + " element " + std::to_string(i) + " has struct_size " + std::to_string(e->struct_size) +
                      ", the first " + std::to_string(array->struct_size) + " (one array, one size)");
  return e;
}

std::vector<std::string> names(const char* const* list, std::size_t count, const Subject& what) {
  std::vector<std::string> out;
  if (count > 0 && !list) throw PluginError(what + ": the list is missing (a null pointer with a non-zero count)");
  for (std::size_t i = 0; i < count; ++i) {
    if (!list[i]) throw PluginError(what + ": entry " + std::to_string(i) + " is a null pointer");
    out.emplace_back(list[i]);
  }
  return out;
}

ParamKind param_kind(std::int32_t kind, const Subject& what) {
  switch (kind) {
    case MG_PARAM_NUMBER: return ParamKind::number;
    case MG_PARAM_INTEGER: return ParamKind::integer;
    case MG_PARAM_CHOICE: return ParamKind::choice;
    case MG_PARAM_TEXT: return ParamKind::text;
    case MG_PARAM_NUMBER_LIST: return ParamKind::number_list;
    case MG_PARAM_RECORD_LIST: return ParamKind::record_list;
    default: throw PluginError(what + " has kind " + std::to_string(kind) + ", not one of MG_PARAM_*");
  }
}

ParamValue param_value(const mg_param_value& v, const ParamSpec& spec, const Subject& what) {
  ParamValue out;
  out.kind = spec.kind;
  switch (spec.kind) {
    case ParamKind::number:
    case ParamKind::integer: out.number = v.number; break;
    case ParamKind::choice:
    case ParamKind::text:
      if (v.text.size > 0 && !v.text.data) throw PluginError(what + ": its text is a null pointer");
      out.text.assign(v.text.data ? v.text.data : "", v.text.size);
      break;
    case ParamKind::number_list:
      if (v.number_count > 0 && !v.numbers) throw PluginError(what + ": its numbers are a null pointer");
      out.numbers.assign(v.numbers, v.numbers + v.number_count);
      break;
    case ParamKind::record_list:
      if (v.record_count > 0 && !v.records) throw PluginError(what + ": its records are a null pointer");
      for (std::size_t r = 0; r < v.record_count; ++r) {
        const mg_record& rec = v.records[r];
        if (rec.field_count != spec.fields.size() || (rec.field_count > 0 && !rec.fields))
          throw PluginError(what + ": record " + std::to_string(r) + " has " + std::to_string(rec.field_count) +
                            " fields, its declaration " + std::to_string(spec.fields.size()));
        Record record;
        for (std::size_t f = 0; f < rec.field_count; ++f)
          if (rec.fields[f].present)
            record[spec.fields[f].name] = param_value(rec.fields[f], spec.fields[f], Subject{&what, " field '", spec.fields[f].name, "'"});
        out.records.push_back(std::move(record));
      }
      break;
  }
  return out;
}

ParamSpec param_spec(const mg_param_decl& d, const Subject& what_type) {
  if (!d.name) throw PluginError(what_type + ": a parameter has no name");
  const Subject what{&what_type, " parameter '", d.name, "'"};
  ParamSpec s;
  s.name = d.name;
  s.kind = param_kind(d.kind, what);
  s.dimension = c_dim(d.dim, what);
  s.doc = text(d.doc);
  s.min = d.min;
  s.max = d.max;
  s.min_exclusive = (d.flags & MG_PF_MIN_EXCLUSIVE) != 0;
  s.max_exclusive = (d.flags & MG_PF_MAX_EXCLUSIVE) != 0;
  s.knob = (d.flags & MG_PF_KNOB) != 0;
  s.is_path = (d.flags & MG_PF_PATH) != 0;
  s.choices = names(d.choices, d.choice_count, Subject{&what, " choices"});
  const Subject field{&what, " record field"};
  for (std::size_t f = 0; f < d.field_count; ++f)
    s.fields.push_back(param_spec(*element(d.fields, f, offsetof(mg_param_decl, display_unit), field), field));
  const bool has_default = (d.flags & MG_PF_HAS_DEFAULT) != 0;
  s.required = (d.flags & MG_PF_REQUIRED) != 0 && !has_default;
  if (has_default) s.default_value = param_value(d.default_value, s, Subject{&what, " default"});
  if (d.flags & MG_PF_HAS_EXAMPLE) s.example_value = param_value(d.example_value, s, Subject{&what, " example"});
  s.display_unit = text(MG_FIELD_OR(&d, mg_param_decl, display_unit, nullptr));
  s.range_reason = text(MG_FIELD_OR(&d, mg_param_decl, range_reason, nullptr));
  return s;
}

// The id of the frame `ref` names (MG_FRAME(i) of the type's `frames`, already read), "" for
// MG_NO_FRAME.
std::string frame_id(std::int32_t ref, const std::vector<AngleFrame>& frames, const Subject& what) {
  if (ref == MG_NO_FRAME) return {};
  if (ref < 0 || static_cast<std::size_t>(ref) > frames.size())
    throw PluginError(what + " names angle frame " + std::to_string(ref) + ", but the type declares " +
                      std::to_string(frames.size()) + " (MG_FRAME(index into mg_node_desc::frames), or MG_NO_FRAME)");
  return frames[static_cast<std::size_t>(ref) - 1].id;
}

ChannelDecl channel_decl(const mg_channel_decl& d, const std::vector<AngleFrame>& frames, const Subject& what_port) {
  if (!d.name) throw PluginError(what_port + ": a declared channel has no name");
  const Subject what{&what_port, " channel '", d.name, "'"};
  ChannelDecl c;
  c.name = d.name;
  c.dimension = c_dim(d.dim, what);
  c.label = text(d.label);
  c.display_unit = text(d.display_unit);
  c.angle_frame = frame_id(d.angle_frame, frames, what);
  c.derivative_order = d.derivative_order;
  c.flags = d.flags;
  if (d.code_count > 0 && !d.codes) throw PluginError(what + ": its codes are a null pointer");
  for (std::size_t i = 0; i < d.code_count; ++i) {
    if (!d.codes[i].name) throw PluginError(what + ": code " + std::to_string(i) + " has no name");
    c.codes.push_back({d.codes[i].value, d.codes[i].name, text(d.codes[i].doc)});
  }
  c.from_mark = text(d.from_mark);
  return c;
}

// mg_presentation, mg_channel_decl, mg_angle_frame and mg_note_decl came with SDK 1.0 whole: a
// writer fills them whole (node.h, "Required prefixes").
Presentation presentation(const mg_presentation& d, const std::vector<AngleFrame>& frames, const Subject& what) {
  require_prefix(&d, sizeof(mg_presentation), Subject{&what, ": its mg_presentation"});
  Presentation p;
  p.role = static_cast<Role>(d.role);  // an unknown role is drawn plain (present.h)
  if (d.axis) {
    require_prefix(d.axis, sizeof(mg_channel_decl), Subject{&what, ": its axis declaration"});
    p.with_axis(channel_decl(*d.axis, frames, Subject{&what, " axis"}));
  }
  for (std::size_t i = 0; i < d.channel_count; ++i)
    p.with(channel_decl(*element(d.channels, i, sizeof(mg_channel_decl), Subject{&what, " channel"}), frames, what));
  p.x_channel = text(d.x_channel);
  if (d.pair_count > 0 && !d.pairs) throw PluginError(what + ": its x/y pairs are a null pointer");
  for (std::size_t i = 0; i < d.pair_count; ++i) {
    const mg_xy_pair& xy = d.pairs[i];
    if (!xy.x || !xy.y) throw PluginError(what + ": x/y pair " + std::to_string(i) + " names no channel");
    p.pairs.push_back({xy.x, xy.y, text(xy.layer), text(xy.label), xy.stroke});
  }
  if (d.point_count > 0 && !d.points) throw PluginError(what + ": its points are a null pointer");
  for (std::size_t i = 0; i < d.point_count; ++i) {
    const mg_point_marks& m = d.points[i];
    if (!m.port) throw PluginError(what + ": points " + std::to_string(i) + " name no port");
    PointMarks marks;
    marks.port = m.port;
    marks.row = m.row;
    marks.x_channels = names(m.x_channels, m.count, Subject{&what, " points x channels"});
    marks.labels = names(m.labels, m.count, Subject{&what, " points labels"});
    marks.y_from_axis = m.y_from_axis != 0;
    marks.caption = text(m.caption);
    p.points.push_back(std::move(marks));
  }
  p.figure_title = text(d.figure_title);
  p.caption = text(d.caption);
  return p;
}

PortSpec port_spec(const mg_port_decl& d, const std::vector<AngleFrame>& frames, const Subject& what_type, const char* side,
                   std::uint32_t* version) {
  if (!d.name) throw PluginError(what_type + ": an " + side + " port has no name");
  const Subject port{&what_type, " ", side, " '"};
  const Subject what{&port, d.name, "'"};
  PortSpec p;
  p.name = d.name;
  p.doc = text(d.doc);
  switch (d.kind) {
    case MG_VALUE_SCALAR: p.kind = ValueKind::scalar; break;
    case MG_VALUE_SERIES: p.kind = ValueKind::series; break;
    case MG_VALUE_TABLE: p.kind = ValueKind::table; break;
    case MG_VALUE_OBJECT:
      p.kind = ValueKind::handle;
      if (!d.interface || !*d.interface) throw PluginError(what + " carries objects but names no interface");
      // An SDK interface with a C++ class is carried as that class (its C++ kind), so that pre-1.0
      // plugins' ports meet it; any other keeps its interface name.
      if (const SdkInterface* known = sdk_interface_named(d.interface)) p.handle_kind = known->kind;
      else p.handle_kind = d.interface;
      if (version) *version = d.interface_version;
      break;
    default: throw PluginError(what + " has kind " + std::to_string(d.kind) + ", not one of MG_VALUE_*");
  }
  if (p.kind != ValueKind::table) p.dimension = c_dim(d.dim, what);
  p.multiple = (d.flags & MG_PORT_MULTIPLE) != 0;
  p.optional = (d.flags & MG_PORT_OPTIONAL) != 0;
  p.display_unit = text(MG_FIELD_OR(&d, mg_port_decl, display_unit, nullptr));
  p.label = text(MG_FIELD_OR(&d, mg_port_decl, label, nullptr));
  p.angle_frame = frame_id(MG_FIELD_OR(&d, mg_port_decl, angle_frame, MG_NO_FRAME), frames, what);
  if (const mg_presentation* shown = MG_FIELD_OR(&d, mg_port_decl, presentation, nullptr)) p.presentation = presentation(*shown, frames, what);
  return p;
}

}  // namespace

mg_dim to_c_dim(const Dimension& d) { return mg_dim{d.length, d.mass, d.time, d.angle, d.temperature, 0, 0, 0}; }

namespace {
Dimension c_dim(const mg_dim& d, const Subject& what) {
  if (d.current != 0 || d.amount != 0 || d.luminous != 0)
    throw PluginError(what + " has a dimension with electric current, amount of substance or luminous intensity, "
                      "which this mechgraph does not know");
  return Dimension{d.length, d.mass, d.time, d.angle, d.temperature};
}
}  // namespace

Dimension from_c_dim(const mg_dim& d, const std::string& what) { return c_dim(d, Subject{nullptr, what}); }

CNodeDeclaration c_node_declaration(const mg_node_type& type, const std::string& where) {
  const mg_node_desc* d = type.desc;
  if (!d) throw PluginError(where + ": a node type has no description (desc is a null pointer)");
  require_prefix(d, offsetof(mg_node_desc, effects), Subject{nullptr, where, ": a node type's mg_node_desc"});
  if (!d->type || !*d->type) throw PluginError(where + ": a node type has an empty name");
  const Subject what{nullptr, where, ": node type '", d->type, "'"};
  CNodeDeclaration out;
  NodeInfo& info = out.info;
  info.type = d->type;
  info.version = d->version;
  info.summary = text(d->summary);
  // The frames first: ports and channels name them by index. Fields after the outputs may be
  // absent in an older writer's description.
  const std::size_t frame_count = MG_FIELD_OR(d, mg_node_desc, frame_count, 0);
  for (std::size_t i = 0; i < frame_count; ++i) {
    const mg_angle_frame* f = element(d->frames, i, sizeof(mg_angle_frame), Subject{&what, " angle frame"});
    if (!f->id || !*f->id) throw PluginError(what + ": angle frame " + std::to_string(i) + " has no id");
    AngleFrame frame;
    frame.id = f->id;
    frame.label = text(f->label);
    frame.unit_tag = text(f->unit_tag);
    frame.zero = text(f->zero);
    frame.scale = f->scale;
    frame.offset_param = text(f->offset_param);
    frame.mark_spacing = f->mark_spacing;
    frame.mark_labels = names(f->mark_labels, f->mark_label_count, Subject{&what, " angle frame '", frame.id, "' mark labels"});
    frame.before = text(f->before);
    frame.after = text(f->after);
    info.frames.push_back(std::move(frame));
  }
  for (std::size_t i = 0; i < frame_count; ++i)  // base frames once every id is known
    info.frames[i].base_frame =
        frame_id(MG_ELEMENT(mg_angle_frame, d->frames, i)->base_frame, info.frames, Subject{&what, " angle frame '", info.frames[i].id, "'"});
  for (std::size_t i = 0; i < d->param_count; ++i)
    info.params.push_back(param_spec(*element(d->params, i, offsetof(mg_param_decl, display_unit), Subject{&what, " parameter"}), what));
  out.input_interface_versions.assign(d->input_count, 0);
  for (std::size_t i = 0; i < d->input_count; ++i)
    info.inputs.push_back(port_spec(*element(d->inputs, i, offsetof(mg_port_decl, display_unit), Subject{&what, " input"}), info.frames,
                                    what, "input", &out.input_interface_versions[i]));
  out.output_interface_versions.assign(d->output_count, 0);
  for (std::size_t i = 0; i < d->output_count; ++i)
    info.outputs.push_back(port_spec(*element(d->outputs, i, offsetof(mg_port_decl, display_unit), Subject{&what, " output"}), info.frames,
                                     what, "output", &out.output_interface_versions[i]));
  // Everything after the outputs may be absent in an older writer's description.
  const std::size_t effect_count = MG_FIELD_OR(d, mg_node_desc, effect_count, 0);
  for (std::size_t i = 0; i < effect_count; ++i) {
    const mg_effect_decl* e = element(d->effects, i, sizeof(mg_effect_decl), Subject{&what, " effect"});
    if (!e->name) throw PluginError(what + ": an effect has no name");
    info.effects.push_back({e->name, text(e->doc), names(e->outputs, e->output_count, Subject{&what, " effect outputs"}),
                            names(e->params, e->param_count, Subject{&what, " effect parameters"})});
  }
  const std::size_t counter_count = MG_FIELD_OR(d, mg_node_desc, counter_count, 0);
  for (std::size_t i = 0; i < counter_count; ++i) {
    const mg_counter_decl* c = element(d->counters, i, offsetof(mg_counter_decl, doc), Subject{&what, " work counter"});
    if (!c->name) throw PluginError(what + ": a work counter has no name");
    info.work_counters.emplace_back(c->name);
  }
  const std::size_t dep_count = MG_FIELD_OR(d, mg_node_desc, dep_count, 0);
  if (dep_count > 0 && !d->deps) throw PluginError(what + ": its output dependencies are a null pointer");
  for (std::size_t i = 0; i < dep_count; ++i) {
    if (!d->deps[i].output) throw PluginError(what + ": an output dependency names no output");
    info.output_dependencies[d->deps[i].output] = names(d->deps[i].inputs, d->deps[i].input_count, Subject{&what, " output dependencies"});
  }
  const std::size_t note_count = MG_FIELD_OR(d, mg_node_desc, note_count, 0);
  for (std::size_t i = 0; i < note_count; ++i) {
    const mg_note_decl* n = element(d->notes, i, sizeof(mg_note_decl), Subject{&what, " note"});
    if (!n->output) throw PluginError(what + ": a note names no output");
    info.notes.push_back({n->output, text(n->when_param), text(n->doc)});
  }
  return out;
}

}  // namespace mechgraph::detail
