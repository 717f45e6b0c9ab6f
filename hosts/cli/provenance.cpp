#include "provenance.hpp"

#include <mechgraph/bounded_read.hpp>
#include <mechgraph/errors.hpp>
#include <mechgraph/scene.hpp>

#include <boost/uuid/detail/sha1.hpp>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <set>

#ifndef MECHGRAPH_VERSION
#define MECHGRAPH_VERSION "0"
#endif

namespace mechgraph::cli {
namespace {

// A value as the scene wrote it: a scalar's text, a list or a map of them.
void write_raw(JsonWriter& json, const RawValue& v) {
  switch (v.kind) {
    case RawValue::Kind::scalar: json.value(v.text); break;
    case RawValue::Kind::list:
      json.begin_array();
      for (const RawValue& item : v.items) write_raw(json, item);
      json.end_array();
      break;
    case RawValue::Kind::map:
      json.begin_object();
      for (const RawField& f : v.fields) {
        json.key(f.first);
        write_raw(json, f.second);
      }
      json.end_object();
      break;
  }
}

// A parameter as the node received it (SI).
void write_used(JsonWriter& json, const ParamValue& v) {
  switch (v.kind) {
    case ParamKind::number: json.value(v.number); break;
    case ParamKind::integer: json.value(static_cast<long>(v.number)); break;
    case ParamKind::choice:
    case ParamKind::text: json.value(v.text); break;
    case ParamKind::number_list: json.numbers(v.numbers); break;
    case ParamKind::record_list:
      json.begin_array();
      for (const Record& r : v.records) {
        json.begin_object();
        for (const auto& [name, field] : r) {
          json.key(name);
          write_used(json, field);
        }
        json.end_object();
      }
      json.end_array();
      break;
  }
}

}  // namespace

std::string file_sha1(const std::string& file) {
  std::string bytes;
  try {
    bytes = read_bounded_file(file, max_scene_bytes);
  } catch (const FileReadError& e) {
    throw IoError(std::string("cannot hash the scene: ") + e.what());
  }
  boost::uuids::detail::sha1 sha;
  sha.process_bytes(bytes.data(), bytes.size());
  boost::uuids::detail::sha1::digest_type digest;
  sha.get_digest(digest);
  std::string hex;
  char part[9];
  for (unsigned word : digest) {
    std::snprintf(part, sizeof part, "%08x", word);
    hex += part;
  }
  return hex;
}

void write_provenance(JsonWriter& json, const Graph& graph, const PluginRegistry& registry, const RunInputs& inputs) {
  const SceneSpec scene = load_scene(inputs.scene_file);
  json.key("provenance").begin_object();
  json.key("program").begin_object().key("name").value("mechgraph").key("version").value(MECHGRAPH_VERSION).end_object();
  json.key("scene").begin_object();
  json.key("file").value(inputs.scene_file);
  json.key("sha1").value(file_sha1(inputs.scene_file));
  json.key("title").value(graph.title);
  json.end_object();
  json.key("overrides").begin_array();
  for (const std::string& o : inputs.overrides) json.value(o);
  json.end_array();
  json.key("scene_params").begin_object();
  for (const auto& [name, value] : scene.params) {
    json.key(name);
    write_raw(json, value);
  }
  json.end_object();

  // Each evaluated (needed) node: what it is, where it came from, what it was given and used.
  std::set<std::string> plugins_used;
  json.key("nodes").begin_object();
  for (std::size_t index : graph.order) {
    const GraphNode& n = graph.nodes[index];
    const NodeSpec* spec = nullptr;
    for (const NodeSpec& s : scene.nodes)
      if (s.name == n.name) spec = &s;
    plugins_used.insert(n.type->plugin_id);
    json.key(n.name).begin_object();
    json.key("type").value(n.info().type);
    json.key("type_version").value(static_cast<long>(n.info().version));
    json.key("plugin").value(n.type->plugin_id);
    for (const PluginInfo& p : registry.plugins())
      if (p.id == n.type->plugin_id) json.key("plugin_version").value(p.version);
    json.key("given").begin_object();
    if (spec)
      for (const auto& [name, value] : spec->params) {
        json.key(name);
        write_raw(json, value);
      }
    json.end_object();
    json.key("used_si").begin_object();
    for (const auto& [name, value] : n.params.all()) {
      json.key(name);
      write_used(json, value);
    }
    json.end_object();
    json.end_object();
  }
  json.end_object();

  // Random nodes: a parameter named seed, with the node's sample count beside it.
  json.key("random").begin_object();
  for (std::size_t index : graph.order) {
    const GraphNode& n = graph.nodes[index];
    if (!n.params.has("seed")) continue;
    // A seed that belongs to an effect counts only while the node runs with that effect.
    if (const EffectSpec* e = n.info().effect_of_param("seed");
        e && std::find(n.effects_read.begin(), n.effects_read.end(), e->name) == n.effects_read.end())
      continue;
    json.key(n.name).begin_object();
    json.key("seed").value(static_cast<long>(n.params.number("seed")));
    if (n.params.has("samples")) json.key("samples").value(static_cast<long>(n.params.number("samples")));
    json.end_object();
  }
  json.end_object();

  json.key("plugins").begin_object();
  for (const PluginInfo& p : registry.plugins()) {
    if (!plugins_used.count(p.id)) continue;
    json.key(p.id).begin_object();
    json.key("version").value(p.version);
    json.key("sdk_version").value(p.sdk_version);
    json.key("file").value(p.path.string());
    json.end_object();
  }
  json.end_object();
  json.end_object();
}

}  // namespace mechgraph::cli
