#include <mechgraph/graph.hpp>

#include "c_node_type.hpp"

#include <sys/stat.h>
#include <mechgraph/semantic_version.hpp>

#include <mechgraph/did_you_mean.hpp>
#include <mechgraph/bounded_read.hpp>
#include <mechgraph/error_subject.hpp>
#include <mechgraph/errors.hpp>
#include <mechgraph/units.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <map>
#include <set>
#include <sstream>

#include <spdlog/spdlog.h>

namespace mechgraph {

Override parse_override(std::string_view text) {
  const auto eq = text.find('=');
  if (eq == std::string_view::npos || eq == 0 || eq + 1 == text.size())
    throw SceneError("--set " + std::string(text) + ": expected NAME=VALUE, e.g. --set rpm=6000rpm or --set part.length=10mm");
  return {std::string(text.substr(0, eq)), std::string(text.substr(eq + 1)), std::string(text)};
}


void mark_wanted_outputs(Graph& graph) {
  for (GraphNode& n : graph.nodes) n.wanted.clear();
  auto want = [&](std::size_t node, const std::string& port) {
    auto& w = graph.nodes[node].wanted;
    if (std::find(w.begin(), w.end(), port) == w.end()) w.push_back(port);
  };
  for (const GraphNode& n : graph.nodes) {
    if (!n.needed) continue;
    for (const GraphNode::Input& in : n.inputs)
      for (const GraphNode::Source& src : in.sources) want(src.node, src.port);
  }
  for (const RequestedOutput& o : graph.outputs) want(o.node, o.port);
  for (GraphNode& n : graph.nodes) {
    std::sort(n.wanted.begin(), n.wanted.end());
    refresh_wanted_mask(n);
  }
}

void refresh_wanted_mask(GraphNode& node) {
  const std::vector<PortSpec>& outputs = node.info().outputs;
  node.wanted_mask.assign(outputs.size(), 0);
  for (std::size_t i = 0; i < outputs.size(); ++i)
    node.wanted_mask[i] = std::binary_search(node.wanted.begin(), node.wanted.end(), outputs[i].name) ? 1 : 0;
}

std::optional<std::size_t> Graph::find(std::string_view name) const {
  if (auto it = index.find(name); it != index.end()) return it->second;
  return std::nullopt;
}

namespace {

[[noreturn]] void fail(const SourceLocation& where, const std::string& message) { throw_scene_error_at(where, message); }



// A raw value as it was written, for messages: "5 mm", "[5000rpm, 6000rpm]", "{a: 1}".
std::string written_text(const RawValue& v) {
  switch (v.kind) {
    case RawValue::Kind::scalar: return v.text;
    case RawValue::Kind::list: {
      std::string out = "[";
      for (std::size_t i = 0; i < v.items.size(); ++i) out += (i ? ", " : "") + written_text(v.items[i]);
      return out + "]";
    }
    case RawValue::Kind::map: {
      std::string out = "{";
      for (std::size_t i = 0; i < v.fields.size(); ++i)
        out += (i ? ", " : "") + v.fields[i].first + ": " + written_text(v.fields[i].second);
      return out + "}";
    }
  }
  return v.text;
}

std::string example_unit(Dimension d) {
  if (d == dim::length) return "e.g. '9 mm'";
  if (d == dim::angle) return "e.g. '130 deg'";
  if (d == dim::angular_speed) return "e.g. '5600 rpm'";
  if (d == dim::mass) return "e.g. '85 g'";
  if (d == dim::force) return "e.g. '400 N'";
  if (d == dim::stiffness) return "e.g. '30 N/mm'";
  if (d == dim::stress) return "e.g. '80 GPa'";
  return "in " + d.si_unit();
}

class GraphBuilder {
 public:
  GraphBuilder(const SceneSpec& scene, const PluginRegistry& registry, const std::vector<Override>& overrides)
      : scene_(scene), registry_(registry) {
    for (const auto& [name, value] : scene.params) scene_params_[name] = value;
    apply_overrides(overrides);
  }

  Graph build() {
    check_requirements();
    graph_.title = scene_.title;
    graph_.file = scene_.file;
    graph_.display_units = DisplayUnits::from_scene(scene_.units);
    for (const NodeSpec& n : scene_.nodes) {
      if (!graph_.index.emplace(n.name, graph_.index.size()).second) fail(n.where, "node '" + n.name + "' is defined twice");
    }
    for (const NodeSpec& n : scene_.nodes) graph_.nodes.push_back(resolve_node(n));
    resolve_effects();
    for (std::size_t i = 0; i < scene_.nodes.size(); ++i) connect(i, scene_.nodes[i]);
    check_cycles();
    for (const PortRef& r : scene_.outputs) request(r, r.where);
    graph_.scene_output_count = graph_.outputs.size();
    for (const ReportSpec& table : scene_.report) resolve_report(table);
    if (graph_.outputs.empty())
      fail({scene_.file, 1, 1}, "the scene requests no outputs: add 'outputs: [node.port, ...]' (or a report)");
    cull_and_order();
    mark_wanted_outputs(graph_);
    return std::move(graph_);
  }

 private:
  // ----- requires: { plugin: "requirement" }
  void check_requirements() const {
    for (const PluginRequirement& r : scene_.requirements) {
      VersionRequirement wanted;
      try {
        wanted = VersionRequirement::parse(r.requirement);
      } catch (const std::invalid_argument& e) {
        fail(r.where, "requires " + r.plugin + ": " + e.what());
      }
      const PluginInfo* loaded = nullptr;
      std::vector<std::string> ids;
      for (const PluginInfo& p : registry_.plugins()) {
        ids.push_back(p.id);
        if (p.id == r.plugin) loaded = &p;
      }
      if (!loaded)
        fail(r.where, "the scene requires plugin '" + r.plugin + "' " + r.requirement + ", which is not loaded; " +
                          unknown_name_message("plugin", r.plugin, ids));
      const auto version = SemanticVersion::parse(loaded->version);
      if (!version || !wanted.satisfied_by(*version))
        fail(r.where, "the scene requires plugin '" + r.plugin + "' " + r.requirement + ", but the loaded one is " +
                          loaded->version + " (" + loaded->path.string() + "); load a matching build with --plugin-dir");
    }
  }

  // ----- overrides
  void apply_overrides(const std::vector<Override>& overrides) {
    for (const Override& o : overrides) {
      const RawValue v = parse_raw_value(o.value, {"--set " + o.text, 0, 0});
      const auto dot = o.target.find('.');
      if (dot == std::string::npos) {
        if (!scene_params_.count(o.target)) {
          std::vector<std::string> valid;
          for (const auto& [k, unused] : scene_params_) valid.push_back(k);
          throw SceneError("--set " + o.text + ": " + unknown_name_message("scene parameter", o.target, valid) +
                           " (a node parameter is set as node.param)");
        }
        scene_params_[o.target] = v;
      } else {
        node_overrides_[o.target.substr(0, dot)].emplace_back(o.target.substr(dot + 1), v);
        override_texts_[o.target.substr(0, dot)] = o.text;
      }
    }
    for (const auto& [node, list] : node_overrides_) {
      const bool exists = std::any_of(scene_.nodes.begin(), scene_.nodes.end(), [&wanted = node](const NodeSpec& n) { return n.name == wanted; });
      if (!exists) throw SceneError("--set " + override_texts_[node] + ": " + unknown_name_message("node", node, node_names()));
    }
  }

  std::vector<std::string> node_names() const {
    std::vector<std::string> out;
    for (const NodeSpec& n : scene_.nodes) out.push_back(n.name);
    return out;
  }

  // ----- parameters
  // Follows `$name` to the scene parameter; returns the value and, for messages, where it was defined.
  const RawValue& dereference(const RawValue& v, std::string& via) const {
    if (v.kind != RawValue::Kind::scalar || v.text.empty() || v.text[0] != '$') return v;
    const std::string name = v.text.substr(1);
    auto it = scene_params_.find(name);
    if (it == scene_params_.end()) {
      std::vector<std::string> valid;
      for (const auto& [k, unused] : scene_params_) valid.push_back(k);
      fail(v.where, unknown_name_message("scene parameter", "$" + name, valid));
    }
    std::string origin = it->second.where.str();
    if (origin.size() >= 2 && origin.substr(origin.size() - 2) == ": ") origin.resize(origin.size() - 2);
    via = " ($" + name + " = '" + written_text(it->second) + "', set at " + origin + ")";
    return it->second;
  }

  double parse_number(const RawValue& written, const ParamSpec& spec, const std::string& owner) const {
    std::string via;
    const RawValue& v = dereference(written, via);
    const std::string what = "parameter '" + spec.name + "' of " + owner;
    if (v.kind != RawValue::Kind::scalar)
      fail(written.where, what + ": expected one number with its unit, " + example_unit(spec.dimension) + ", got " +
                              (v.kind == RawValue::Kind::list ? "the list " : "the map ") + written_text(v) + via +
                              (v.kind == RawValue::Kind::list ? "; a run takes one value: to compare several, sweep them (mechgraph sweep SCENE --vary NAME=A,B,C or --vary NAME=FROM:TO:N)" : ""));
    Quantity q;
    try {
      q = parse_quantity(v.text);
    } catch (const UnitError& e) {
      SourceLocation at = v.where;
      if (at.line) at.column += static_cast<int>(e.column());
      fail(at, what + ": " + e.what() + via);
    }
    if (!(q.dimension == spec.dimension)) {
      if (q.dimension.dimensionless())
        fail(written.where, what + ": '" + v.text + "' has no unit; expected " + spec.dimension.describe() + ", " +
                                example_unit(spec.dimension) + via);
      fail(written.where, what + ": '" + v.text + "' is " + q.dimension.describe() + ", expected " +
                              spec.dimension.describe() + " (" + example_unit(spec.dimension) + ")" + via);
    }
    if (const std::string problem = spec.value_problem(q.value); !problem.empty())
      fail(written.where, what + " = '" + v.text + "' " + problem + via);
    return q.value;
  }

  ParamValue parse_param(const RawValue& written, const ParamSpec& spec, const std::string& owner) const {
    std::string via;
    const RawValue& v = dereference(written, via);
    const std::string what = "parameter '" + spec.name + "' of " + owner;
    switch (spec.kind) {
      case ParamKind::number: return ParamValue::of_number(parse_number(written, spec, owner));
      case ParamKind::integer: return ParamValue::of_integer(static_cast<long>(parse_number(written, spec, owner)));
      case ParamKind::choice: {
        if (v.kind != RawValue::Kind::scalar) fail(written.where, what + ": expected one of the choices" + via);
        if (std::find(spec.choices.begin(), spec.choices.end(), v.text) == spec.choices.end())
          fail(v.where, what + ": " + unknown_name_message("choice", v.text, spec.choices) + via);
        return ParamValue::of_choice(v.text);
      }
      case ParamKind::text: {
        if (v.kind != RawValue::Kind::scalar) fail(written.where, what + ": expected text" + via);
        std::string text = v.text;
        if (spec.is_path && !text.empty() && !std::filesystem::path(text).is_absolute() && v.where.line != 0)
          text = (std::filesystem::path(scene_.file).parent_path() / text).lexically_normal().string();
        // A file a scene names is refused at load when it is there but no regular file (a folder,
        // a FIFO, a device such as /dev/zero): `validate` says so, nothing waits on it later.
        if (spec.is_path && !text.empty()) {
          struct stat st {};
          if (::stat(text.c_str(), &st) == 0 && !S_ISREG(st.st_mode))
            fail(v.where, what + ": " + quoted_text_excerpt(text, 200) + " is " +
                              (S_ISDIR(st.st_mode) ? "a folder" : S_ISFIFO(st.st_mode) ? "a FIFO" : "a device or socket") +
                              ", not a regular file" + via);
        }
        return ParamValue::of_text(text);
      }
      case ParamKind::number_list: {
        if (v.kind != RawValue::Kind::list) fail(written.where, what + ": expected a list, e.g. [2, 6, 10]" + via);
        ParamSpec element = spec;
        element.kind = ParamKind::number;
        std::vector<double> out;
        for (const RawValue& item : v.items) out.push_back(parse_number(item, element, owner));
        return ParamValue::of_list(std::move(out));
      }
      case ParamKind::record_list: {
        // A single map is a list of one record (`spec: { upper: 0.5 mm }`).
        if (v.kind != RawValue::Kind::list && v.kind != RawValue::Kind::map)
          fail(written.where, what + ": expected a list of records (or one record { field: value, ... })" + via);
        const std::vector<RawValue> one{v};
        const std::vector<RawValue>& items = v.kind == RawValue::Kind::map ? one : v.items;
        ParamValue out;
        out.kind = ParamKind::record_list;
        std::size_t index = 0;
        for (const RawValue& item : items) {
          if (item.kind != RawValue::Kind::map) fail(item.where, what + ": each entry is a map { field: value, ... }");
          const std::string item_owner = owner + ", entry " + std::to_string(index++);
          out.records.push_back(parse_record(item, spec.fields, item_owner));
        }
        return out;
      }
    }
    fail(written.where, what + ": unsupported parameter kind");
  }

  Record parse_record(const RawValue& map, const std::vector<ParamSpec>& fields, const std::string& owner) const {
    Record record;
    std::vector<std::string> valid;
    for (const ParamSpec& f : fields) valid.push_back(f.name);
    for (const auto& [key, value] : map.fields) {
      auto it = std::find_if(fields.begin(), fields.end(), [&wanted = key](const ParamSpec& f) { return f.name == wanted; });
      if (it == fields.end()) fail(value.key_where, owner + ": " + unknown_name_message("field", key, valid));
      record[key] = parse_param(value, *it, owner);
    }
    for (const ParamSpec& f : fields) {
      if (record.count(f.name)) continue;
      if (f.default_value) record[f.name] = *f.default_value;
      else if (f.required) fail(map.where, owner + ": field '" + f.name + "' is required (" + f.doc + ")");
    }
    return record;
  }

  GraphNode resolve_node(const NodeSpec& n) {
    GraphNode node;
    node.name = n.name;
    node.where = n.where;
    node.type = registry_.find(n.type);
    if (!node.type) {
      const std::string message = n.type_where.str() + unknown_name_message("node type", n.type, registry_.type_names());
      if (registry_.skipped().empty()) throw SceneErrorAt({n.type_where, n.name, {}}, message);
      // It may live in a plugin file that could not be loaded: that is the failure to report.
      std::string skipped;
      for (const SkippedPlugin& s : registry_.skipped()) skipped += "\n  " + s.reason;
      throw PluginError(message + "; plugin files were skipped, one of them may provide it:" + skipped);
    }
    const NodeInfo& info = node.info();
    const std::string owner = "node '" + n.name + "' (" + n.type + ")";
    std::vector<std::pair<std::string, RawValue>> written = n.params;
    if (auto it = node_overrides_.find(n.name); it != node_overrides_.end()) {
      for (const auto& [name, value] : it->second) {
        auto w = std::find_if(written.begin(), written.end(), [&wanted = name](const auto& p) { return p.first == wanted; });
        if (w != written.end()) w->second = value;
        else written.emplace_back(name, value);
      }
    }
    std::vector<std::string> valid;
    for (const ParamSpec& p : info.params) valid.push_back(p.name);
    std::set<std::string> seen;
    for (const auto& [name, value] : written) {
      const ParamSpec* spec = info.find_param(name);
      if (!spec)
        throw SceneErrorAt({value.key_where, n.name, name}, value.key_where.str() + owner + ": " + unknown_name_message("parameter", name, valid));
      seen.insert(name);
      record_scene_param_uses(graph_.nodes.size(), name, value, false);
      try {
        node.params.set(name, parse_param(value, *spec, owner));
      } catch (const SceneErrorAt& e) {  // the same error, with the node and parameter as data
        throw SceneErrorAt({e.subject().where, n.name, name}, e.what());
      }
      node.param_where[name] = value.where;
    }
    for (const ParamSpec& p : info.params) {
      if (seen.count(p.name)) continue;
      if (p.default_value) node.params.set(p.name, *p.default_value);
      else if (p.required) fail(n.where, owner + ": parameter '" + p.name + "' is required (" + p.doc + ")");
    }
    return node;
  }

  // Notes where `$name` values land, so a sweep can set a scene parameter on the built graph.
  void record_scene_param_uses(std::size_t node, const std::string& param, const RawValue& v, bool nested) {
    if (v.kind == RawValue::Kind::scalar) {
      if (!v.text.empty() && v.text[0] == '$') graph_.scene_param_uses[v.text.substr(1)].push_back({node, param, nested});
      return;
    }
    for (const RawValue& item : v.items) record_scene_param_uses(node, param, item, true);
    for (const auto& [key, field] : v.fields) record_scene_param_uses(node, param, field, true);
  }

  // ----- connections
  void connect(std::size_t index, const NodeSpec& n) {
    GraphNode& node = graph_.nodes[index];
    const NodeInfo& info = node.info();
    const std::string owner = "node '" + n.name + "' (" + info.type + ")";
    std::vector<std::string> valid;
    for (const PortSpec& p : info.inputs) valid.push_back(p.name);
    for (const NodeSpec::InputSpec& in : n.inputs) {
      const PortSpec* spec = info.find_input(in.port);
      if (!spec) fail(in.where, owner + ": " + unknown_name_message("input port", in.port, valid));
      if (!spec->multiple && in.sources.size() != 1)
        fail(in.where, owner + ": input '" + in.port + "' takes exactly one connection, found " + std::to_string(in.sources.size()));
      GraphNode::Input input{in.port, {}};
      for (const PortRef& ref : in.sources) {
        const auto producer = graph_.find(ref.node);
        if (!producer) fail(ref.where, owner + ", input '" + in.port + "': " + unknown_name_message("node", ref.node, node_names()));
        if (*producer == index) fail(ref.where, owner + ": input '" + in.port + "' is connected to the node itself (a cycle)");
        const NodeInfo& pinfo = graph_.nodes[*producer].info();
        const PortSpec* out = pinfo.find_output(ref.port);
        if (!out) {
          std::vector<std::string> outs;
          for (const PortSpec& p : pinfo.outputs) outs.push_back(p.name);
          fail(ref.where, owner + ", input '" + in.port + "', node '" + ref.node + "' (" + pinfo.type + "): " +
                              unknown_name_message("output port", ref.port, outs));
        }
        check_compatible(*out, *spec, ref, owner + ", input '" + in.port + "'");
        check_interface_version(graph_.nodes[*producer], *out, node, *spec, ref, owner + ", input '" + in.port + "'");
        check_effect_on(*producer, ref.port, ref.where, owner + ", input '" + in.port + "': '" + ref.str() + "'");
        input.sources.push_back({*producer, ref.port});
        if (std::find(node.upstream.begin(), node.upstream.end(), *producer) == node.upstream.end())
          node.upstream.push_back(*producer);
      }
      node.inputs.push_back(std::move(input));
    }
    for (const PortSpec& p : info.inputs) {
      if (p.optional) continue;
      const bool connected = std::any_of(n.inputs.begin(), n.inputs.end(), [&](const auto& i) { return i.port == p.name; });
      if (!connected)
        fail(n.where, owner + ": input '" + p.name + "' is not connected; it expects " + describe_port(p) + " (" + p.doc + ")");
    }
  }

  static std::string describe_port(const PortSpec& p) {
    if (p.kind == ValueKind::handle) return "a " + p.handle_kind + (p.multiple ? " (one or more)" : "");
    if (p.kind == ValueKind::table) return "a table of curves";
    return std::string("a ") + std::string(to_string(p.kind)) + " of " + p.dimension.describe();
  }

  void check_compatible(const PortSpec& out, const PortSpec& in, const PortRef& ref, const std::string& what) const {
    bool ok = out.kind == in.kind;
    if (ok && in.kind == ValueKind::handle) ok = out.handle_kind == in.handle_kind;
    if (ok && in.kind != ValueKind::handle) ok = out.dimension == in.dimension;
    if (!ok)
      fail(ref.where, what + ": '" + ref.str() + "' is " + describe_port(out) + ", the input expects " + describe_port(in));
  }

  // An object port's interface at a version (docs/design/sdk-1.0.md, 1.7): the producer must offer
  // at least the version the consumer reads, else the consumer would query a table the object does
  // not have. 0 on either side is a port without a version (a private pre-1.0 kind): names only.
  void check_interface_version(const GraphNode& producer, const PortSpec& out, const GraphNode& consumer, const PortSpec& in,
                               const PortRef& ref, const std::string& what) const {
    if (in.kind != ValueKind::handle) return;
    const NodeInfo& pinfo = producer.info();
    const NodeInfo& cinfo = consumer.info();
    const std::uint32_t offered = producer.type->interface_version(true, static_cast<std::size_t>(&out - pinfo.outputs.data()));
    const std::uint32_t needed = consumer.type->interface_version(false, static_cast<std::size_t>(&in - cinfo.inputs.data()));
    if (offered == 0 || needed == 0 || offered >= needed) return;
    fail(ref.where, what + ": '" + ref.str() + "' of node '" + producer.name + "' (" + pinfo.type + ", plugin '" +
                        producer.type->plugin_id + "') offers interface " + detail::interface_of_port(in) + " version " +
                        std::to_string(offered) + ", but node '" + consumer.name + "' (" + cinfo.type + ", plugin '" +
                        consumer.type->plugin_id + "') needs version " + std::to_string(needed) +
                        " or later; update the plugin of '" + producer.name + "'");
  }

  void check_cycles() const {
    enum class Mark { none, active, done };
    std::vector<Mark> mark(graph_.nodes.size(), Mark::none);
    std::vector<std::size_t> path;
    std::function<void(std::size_t)> visit = [&](std::size_t i) {
      if (mark[i] == Mark::done) return;
      if (mark[i] == Mark::active) {
        auto start = std::find(path.begin(), path.end(), i);
        std::string cycle;
        for (auto it = start; it != path.end(); ++it) cycle += graph_.nodes[*it].name + " <- ";
        cycle += graph_.nodes[i].name;
        fail(graph_.nodes[i].where, "the graph has a cycle: " + cycle + " (each node takes an input from the next)");
      }
      mark[i] = Mark::active;
      path.push_back(i);
      for (std::size_t u : graph_.nodes[i].upstream) visit(u);
      path.pop_back();
      mark[i] = Mark::done;
    };
    for (std::size_t i = 0; i < graph_.nodes.size(); ++i) visit(i);
  }

  // The scene's effects reach every node that implements them; a node's own `effects:` add to
  // those for that node alone (and must be effects its type implements).
  void resolve_effects() {
    const std::vector<std::string> known = registry_.effect_names();
    for (const auto& [name, where] : scene_.effects) {
      if (std::find(known.begin(), known.end(), name) == known.end())
        fail(where, unknown_name_message("effect", name, known) + " (no loaded node type implements it)");
      if (std::find(graph_.effects.begin(), graph_.effects.end(), name) == graph_.effects.end()) graph_.effects.push_back(name);
    }
    for (std::size_t i = 0; i < graph_.nodes.size(); ++i) {
      GraphNode& n = graph_.nodes[i];
      const NodeInfo& info = n.info();
      for (const std::string& e : graph_.effects)
        if (info.implements_effect(e)) n.effects_read.push_back(e);
      for (const auto& [name, where] : scene_.nodes[i].effects) {
        if (!info.implements_effect(name)) {
          std::vector<std::string> valid;
          for (const EffectSpec& e : info.effects) valid.push_back(e.name);
          fail(where, "node '" + n.name + "' (" + info.type + "): " + unknown_name_message("effect", name, valid) +
                          (valid.empty() ? " (this node type implements no effects)" : ""));
        }
        if (std::find(n.effects_read.begin(), n.effects_read.end(), name) == n.effects_read.end())
          n.effects_read.push_back(name);
      }
      for (const auto& [param, where] : n.param_where) {
        const EffectSpec* effect = info.effect_of_param(param);
        if (effect && !effect_on(n, effect->name))
          spdlog::warn("{}node '{}' ({}): parameter '{}' is unused: it belongs to effect '{}', which is off for this node",
                       where.str(), n.name, info.type, param, effect->name);
      }
    }
  }

  static bool effect_on(const GraphNode& n, std::string_view effect) {
    return std::find(n.effects_read.begin(), n.effects_read.end(), effect) != n.effects_read.end();
  }

  // An output that an effect brings exists only while the effect is on for its node.
  void check_effect_on(std::size_t node, const std::string& port, const SourceLocation& where, const std::string& what) const {
    const GraphNode& n = graph_.nodes[node];
    const EffectSpec* effect = n.info().effect_of_output(port);
    if (!effect || effect_on(n, effect->name)) return;
    fail(where, what + " needs effect '" + effect->name + "', which is off for node '" + n.name + "': add it to the scene's " +
                    "'effects:' or to the node's own 'effects: [" + effect->name + "]'");
  }

  std::size_t request(const PortRef& ref, const SourceLocation& where) {
    const auto node = graph_.find(ref.node);
    if (!node) fail(where, "output '" + ref.str() + "': " + unknown_name_message("node", ref.node, node_names()));
    const NodeInfo& info = graph_.nodes[*node].info();
    const PortSpec* spec = info.find_output(ref.port);
    if (!spec) {
      std::vector<std::string> outs;
      for (const PortSpec& p : info.outputs) outs.push_back(p.name);
      fail(where, "output '" + ref.str() + "' of node '" + ref.node + "' (" + info.type + "): " +
                      unknown_name_message("output port", ref.port, outs));
    }
    check_effect_on(*node, ref.port, where, "output '" + ref.str() + "'");
    const auto [it, added] = requested_.emplace(std::make_pair(*node, ref.port), graph_.outputs.size());
    if (added) graph_.outputs.push_back({*node, ref.port, spec, ref.str()});
    return it->second;
  }

  void resolve_report(const ReportSpec& spec) {
    ResolvedReport report;
    report.title = spec.title;
    std::set<std::string> roles;
    for (const auto& c : spec.columns) {
      report.columns.push_back(c.label);
      for (const auto& [role, node] : c.roles) roles.insert(role);
    }
    for (const auto& row : spec.rows) {
      ResolvedReport::Row out{row.label, row.unit, {}};
      std::vector<std::optional<CellRef>> cells = row.cells;
      if (cells.empty()) {
        if (!roles.count(row.role))
          fail(row.where, "report row '" + row.label + "': " + unknown_name_message("role", row.role, {roles.begin(), roles.end()}));
        for (const auto& c : spec.columns) {
          auto it = std::find_if(c.roles.begin(), c.roles.end(), [&](const auto& r) { return r.first == row.role; });
          if (it == c.roles.end()) cells.emplace_back();
          else cells.push_back(CellRef{it->second, row.port, std::nullopt, row.where});
        }
      }
      for (const auto& cell : cells) {
        if (!cell) {
          out.cells.emplace_back();
          continue;
        }
        const std::size_t index = request(PortRef{cell->node, cell->port, cell->where}, cell->where);
        const PortSpec& port = *graph_.outputs[index].spec;
        const std::string what = "report row '" + row.label + "', '" + graph_.outputs[index].label + "'";
        if (port.kind == ValueKind::handle) fail(cell->where, what + " is a " + port.handle_kind + "; a table cell needs a number");
        if (port.kind == ValueKind::table)
          fail(cell->where, what + " is a table of curves; a table cell needs a number (request it in 'outputs:' for its CSV)");
        if (port.kind == ValueKind::series && !cell->element)
          fail(cell->where, what + " is a series; name one element, e.g. " + graph_.outputs[index].label + "[0]");
        if (port.kind == ValueKind::scalar && cell->element) fail(cell->where, what + " is a scalar; it has no elements");
        if (!row.unit.empty()) {
          try {
            to_unit(1.0, port.dimension, row.unit);
          } catch (const UnitError& e) {
            fail(row.where, "report row '" + row.label + "': " + e.what());
          }
        }
        out.cells.push_back(ResolvedReport::Cell{index, cell->element});
      }
      report.rows.push_back(std::move(out));
    }
    graph_.reports.push_back(std::move(report));
  }

  void cull_and_order() {
    std::vector<std::size_t> stack;
    for (const RequestedOutput& o : graph_.outputs) stack.push_back(o.node);
    while (!stack.empty()) {
      const std::size_t i = stack.back();
      stack.pop_back();
      if (graph_.nodes[i].needed) continue;
      graph_.nodes[i].needed = true;
      for (std::size_t u : graph_.nodes[i].upstream) stack.push_back(u);
    }
    // Depth-first post-order: producers before consumers, scene order otherwise.
    std::vector<bool> placed(graph_.nodes.size(), false);
    std::function<void(std::size_t)> place = [&](std::size_t i) {
      if (placed[i]) return;
      placed[i] = true;
      for (std::size_t u : graph_.nodes[i].upstream) place(u);
      graph_.order.push_back(i);
    };
    for (std::size_t i = 0; i < graph_.nodes.size(); ++i)
      if (graph_.nodes[i].needed) place(i);
  }

  const SceneSpec& scene_;
  const PluginRegistry& registry_;
  std::map<std::string, RawValue> scene_params_;
  std::map<std::string, std::vector<std::pair<std::string, RawValue>>> node_overrides_;
  std::map<std::string, std::string> override_texts_;
  std::map<std::pair<std::size_t, std::string>, std::size_t> requested_;  // (node, port) -> index in outputs
  Graph graph_;
};

}  // namespace

Graph build_graph(const SceneSpec& scene, const PluginRegistry& registry, const std::vector<Override>& overrides) {
  return GraphBuilder(scene, registry, overrides).build();
}

}  // namespace mechgraph
