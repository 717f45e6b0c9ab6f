#pragma once
// A scene resolved against the loaded node types: every parameter parsed into SI and checked,
// every connection checked for kind and dimension, cycles refused, and the nodes the requested
// outputs need put in dependency order. Everything here happens before evaluation, so a scene
// that builds is a scene whose only remaining failures are numerical.
#include <mechgraph/display_units.hpp>
#include <mechgraph/plugin_registry.hpp>
#include <mechgraph/scene.hpp>

#include <map>
#include <optional>
#include <string>
#include <vector>

namespace mechgraph {

/// `--set NAME=VALUE`: a scene parameter (`rpm=6000rpm`) or a node parameter (`part.length=10mm`).
struct Override {
  std::string target;
  std::string value;
  std::string text;  // as typed, for messages
};
Override parse_override(std::string_view text);

struct GraphNode {
  std::string name;
  const RegisteredType* type = nullptr;
  SourceLocation where;
  ParamSet params;
  std::map<std::string, SourceLocation> param_where;  // where each written parameter's value stands
  struct Source {
    std::size_t node;
    std::string port;
  };
  struct Input {
    std::string port;
    std::vector<Source> sources;
  };
  std::vector<Input> inputs;
  std::vector<std::size_t> upstream;       // distinct producer nodes
  std::vector<std::string> effects_read;   // scene effects this node implements
  std::vector<std::string> wanted;         // its outputs read downstream (mark_wanted_outputs)
  std::vector<std::int32_t> wanted_mask;   // the same by declared output: 1 read, 0 not (mark_wanted_outputs)
  bool needed = false;
  bool memoised = true;                    // looked up in and stored to the memo cache (a sweep clears it)
  const NodeInfo& info() const { return type->type->info(); }
};

struct RequestedOutput {
  std::size_t node;
  std::string port;
  const PortSpec* spec = nullptr;
  std::string label;  // "node.port"
};

struct ResolvedReport {
  std::string title;
  std::vector<std::string> columns;
  struct Cell {
    std::size_t output;                   // index into Graph::outputs
    std::optional<std::size_t> element;   // element of a series output
  };
  struct Row {
    std::string label;
    std::string unit;                       // display unit ("" = SI)
    std::vector<std::optional<Cell>> cells;  // per column; empty = "-"
  };
  std::vector<Row> rows;
};

/// Where a scene parameter went: parameter `param` of node `node`, written as `$name` on its own
/// (nested = false) or inside a list or record (nested = true).
struct SceneParamUse {
  std::size_t node;
  std::string param;
  bool nested = false;
};

struct Graph {
  std::string title;
  std::string file;
  std::vector<GraphNode> nodes;
  std::vector<RequestedOutput> outputs;  // the scene's outputs, then what the report needs
  std::size_t scene_output_count = 0;    // how many of `outputs` the scene's `outputs:` named
  std::vector<std::string> effects;
  std::vector<std::size_t> order;        // needed nodes in dependency order
  std::vector<ResolvedReport> reports;
  DisplayUnits display_units;            // the scene's `units:` (empty: SI everywhere)
  std::map<std::string, std::size_t, std::less<>> index;  // node name -> position in `nodes`
  std::map<std::string, std::vector<SceneParamUse>, std::less<>> scene_param_uses;  // `$name` -> where it went

  std::optional<std::size_t> find(std::string_view name) const;
};

/// Fills each node's `wanted` from the connections of needed nodes and from `outputs`; build_graph
/// calls it, and so must code that changes which outputs a built graph requests.
void mark_wanted_outputs(Graph& graph);
/// Makes `node.wanted_mask` say what `node.wanted` says: code that edits `wanted` calls it after.
void refresh_wanted_mask(GraphNode& node);


/// Throws SceneError naming file:line:column for every problem it finds (the first one).
Graph build_graph(const SceneSpec& scene, const PluginRegistry& registry, const std::vector<Override>& overrides = {});

}  // namespace mechgraph
