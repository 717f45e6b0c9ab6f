#pragma once
// A scene file as written: the YAML read into plain structures that remember where each piece
// stood (file:line:column), before any plugin is consulted. Checking names, units and
// connections against the loaded node types is graph.hpp's job.
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace mechgraph {

struct SourceLocation {
  std::string file;
  int line = 0;    // 1-based; 0 when the value did not come from a file (e.g. --set)
  int column = 0;  // 1-based
  std::string str() const;  // "file:line:column: " or the origin label
};

struct RawField;

/// A YAML value as written: a scalar's text, a list or a map, with its location.
struct RawValue {
  enum class Kind { scalar, list, map } kind = Kind::scalar;
  std::string text;
  std::vector<RawValue> items;
  std::vector<RawField> fields;  // of a map, in the order written
  SourceLocation where;
  SourceLocation key_where;  // where the key that holds this value stands
};

/// One key of a map and its value (a pair, spelled out: a std::pair of a type still being defined
/// is not allowed, and clang says so).
struct RawField {
  std::string first;
  RawValue second;
  RawField() = default;
  RawField(std::string key, RawValue value) : first(std::move(key)), second(std::move(value)) {}
};

/// "node.port" as written in `inputs:` or `outputs:`.
struct PortRef {
  std::string node;
  std::string port;
  SourceLocation where;
  std::string str() const { return node + "." + port; }
};

struct NodeSpec {
  std::string name;
  std::string type;
  SourceLocation where;       // the node's name
  SourceLocation type_where;  // its type
  std::vector<std::pair<std::string, RawValue>> params;
  struct InputSpec {
    std::string port;
    SourceLocation where;
    std::vector<PortRef> sources;
    bool listed = false;  // written as a list
  };
  std::vector<InputSpec> inputs;
  std::vector<std::pair<std::string, SourceLocation>> effects;  // this node's own, added to the scene's
};

/// One cell written out in full: "node.port", "node.port[i]" (element i of a series) or "-".
struct CellRef {
  std::string node;
  std::string port;
  std::optional<std::size_t> element;
  SourceLocation where;
};

/// A table of the report. Columns map roles to nodes and a row names `role.port`, so one row
/// reads the same port in every column; or a row lists its cells one per column.
struct ReportSpec {
  std::string title;
  struct Column {
    std::string label;
    std::vector<std::pair<std::string, std::string>> roles;  // role -> node
    SourceLocation where;
  };
  struct Row {
    std::string label;
    std::string role;                              // with `port`: the same port in every column
    std::string port;
    std::vector<std::optional<CellRef>> cells;     // or: explicit cells, one per column
    std::string unit;
    SourceLocation where;
  };
  std::vector<Column> columns;
  std::vector<Row> rows;
  SourceLocation where;
};

/// `requires: { myplugin: ">=1.0" }`: the plugin versions a scene needs (semantic_version.hpp).
struct PluginRequirement {
  std::string plugin;       // plugin id
  std::string requirement;  // ">=0.2, <1"
  SourceLocation where;     // the requirement's text
};

struct SceneSpec {
  std::string file;
  std::string title;
  std::vector<PluginRequirement> requirements;
  std::vector<std::pair<std::string, RawValue>> params;
  std::vector<std::pair<std::string, RawValue>> units;  // `units: { length: mm }`: display units (display_units.hpp)
  std::vector<NodeSpec> nodes;
  std::vector<std::pair<std::string, SourceLocation>> effects;
  std::vector<PortRef> outputs;
  std::vector<ReportSpec> report;  // `report:` is one table or a list of tables
  /// `uncertainty:` as written (distributions on parameters, the sampling, spec limits, events);
  /// read by uncertainty/study_spec.hpp, which knows its shape. Absent: no study.
  std::optional<RawValue> uncertainty;
};

/// The largest scene file read: 1 MiB (a scene is a few pages of text; anything larger is refused
/// unread; YAML builds about 240 bytes per node, so this bounds the tree too).
constexpr std::size_t max_scene_bytes = 1u << 20;

/// Why `name` cannot name a node or a scene parameter (empty when it can): names start with an
/// ASCII letter or '_', hold letters, digits, '_' and '-', at most 64 of them. They become file
/// names, CSV headers and plot titles, so nothing else is allowed ('/', '.', '$', spaces, controls).
std::string name_problem(std::string_view name);

/// Reads and shape-checks a scene; throws SceneError("file:line:column: ...").
/// Refused before any node is made: more than max_scene_bytes, bytes that are not UTF-8, more than
/// 250000 YAML nodes written, a YAML alias cycle or expansion beyond a million nodes, nesting
/// deeper than 64, a key given twice.
SceneSpec load_scene(const std::filesystem::path& file);
SceneSpec parse_scene(std::string_view yaml_text, const std::string& file_label);

/// Reads one value written on the command line (`--set x=[2, 6, 10]`) as YAML, so lists work
/// there as in the file; every part of it is located at `where`.
RawValue parse_raw_value(std::string_view text, const SourceLocation& where);

/// Parses "node.port", "node.port[3]" or "-" (an empty cell).
std::optional<CellRef> parse_cell_ref(std::string_view text, const SourceLocation& where);

/// Splits "node.port"; throws SceneError at `where` if malformed.
PortRef parse_port_ref(std::string_view text, const SourceLocation& where);
/// The entry of `list` naming the same output as `ref` (node.port), or null. A list of outputs
/// names each once: a repeat would be shown once without a word (scene, --outputs, Python).
const PortRef* listed_before(const std::vector<PortRef>& list, const PortRef& ref);

}  // namespace mechgraph
