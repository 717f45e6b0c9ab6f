#pragma once
// The limits a YAML document from a stranger must keep before anything converts it: yaml-cpp
// builds aliases as shared nodes, so `&a {p: *a}` is a cycle (endless recursion) and nine nested
// levels of ten aliases each expand to a billion nodes from 634 bytes. Private to libmechgraph.
#include <yaml-cpp/yaml.h>

#include <cstddef>
#include <string>

namespace mechgraph::detail {

struct YamlLimits {
  std::size_t max_depth = 64;          // maps and lists inside each other
  std::size_t max_nodes = 1'000'000;   // nodes visited, an alias counted each time it is used
  std::size_t max_written = 250'000;   // nodes written out (aliases not counted): what yaml-cpp builds
};

/// Reads `text` as a stream of parser events, before any tree is built (a tree costs about 240
/// bytes a node), and throws SceneError at the first: more than max_written nodes, more than
/// max_nodes once every alias is expanded, nesting deeper than max_depth, an alias used inside the
/// node it names (a cycle). A YAML syntax error is left for the loader to report.
void check_yaml_events(std::string_view text, const std::string& file, const YamlLimits& limits = {});

/// Walks the document once and throws SceneError ("file:line:column: ...") on the first of: a node
/// that contains itself (a recursive alias), nesting deeper than max_depth, more than max_nodes
/// nodes in the expanded tree, a key given twice in one map (both places named).
void check_yaml_bounds(const YAML::Node& root, const std::string& file, const YamlLimits& limits = {});

/// Throws SceneError at the first byte of `text` that is not well-formed UTF-8 (line and column
/// counted in bytes from 1), before YAML reads it.
void check_utf8(std::string_view text, const std::string& file);

}  // namespace mechgraph::detail
