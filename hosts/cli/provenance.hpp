#pragma once
// What a result was made from, kept with it (results.json and `run --json`): the program and its
// version, the scene file and its SHA-1, the scene's parameters as written, every --set override,
// each node's type, plugin and plugin version with its parameters as written and as used (SI), the
// seeds and sample counts of random nodes, and the plugins loaded. Enough to rerun a result, or to
// see why two results differ.
#include <mechgraph/graph.hpp>
#include <mechgraph/json_writer.hpp>
#include <mechgraph/plugin_registry.hpp>

#include <string>
#include <vector>

namespace mechgraph::cli {

struct RunInputs {
  std::string scene_file;
  std::vector<std::string> overrides;  // --set texts, in the order given
};

/// SHA-1 of a file's bytes, as 40 hex digits; throws IoError if it cannot be read.
std::string file_sha1(const std::string& file);

/// Writes the "provenance" member (key and object) into an open JSON object.
void write_provenance(JsonWriter& json, const Graph& graph, const PluginRegistry& registry, const RunInputs& inputs);

}  // namespace mechgraph::cli
