#include "sweep_fingerprint.hpp"

#include <mechgraph/bounded_read.hpp>
#include <mechgraph/hash.hpp>
#include <mechgraph/scene.hpp>

#include <cstdio>
#include <set>

namespace mechgraph::cli {
namespace {

// Every file the sweep reads, by the path its nodes are given: the files the scene names (a
// table) and, where a varied input is such a parameter, the file of each case's value.
std::set<std::string> files_read(const Graph& graph, const CaseTable& table) {
  std::set<std::string> files;
  for (std::size_t i : graph.order) {
    const GraphNode& node = graph.nodes[i];
    for (const auto& [name, value] : node.params.all())
      if (const ParamSpec* spec = node.info().find_param(name); spec && spec->is_path && !value.text.empty()) files.insert(value.text);
  }
  for (std::size_t v = 0; v < table.variables.size(); ++v) {
    const std::string& name = table.variables[v].name;
    bool names_file = false;
    const auto is_path = [&](std::size_t node, const std::string& param) {
      const ParamSpec* spec = graph.nodes[node].info().find_param(param);
      return spec && spec->is_path;
    };
    if (const auto dot = name.find('.'); dot != std::string::npos) {
      if (const auto node = graph.find(name.substr(0, dot))) names_file = is_path(*node, name.substr(dot + 1));
    } else if (const auto uses = graph.scene_param_uses.find(name); uses != graph.scene_param_uses.end()) {
      for (const SceneParamUse& use : uses->second) names_file = names_file || is_path(use.node, use.param);
    }
    const bool numbers_only = table.cases.empty() && table.numbers.written.ends.empty();
    if (names_file && !numbers_only) {  // a path is a word: a table of numbers only (a sample, a design) names none
      CaseValue scratch;
      for (std::size_t i = 0; i < table.size(); ++i)
        if (const CaseValue& value = table.cell(i, v, scratch); !value.text.empty()) files.insert(value.text);
    }
  }
  return files;
}

// Which sweep a file of rows belongs to: the scene's text, the contents of every file it reads,
// the --set values, every case, the columns. A table file edited between a stopped sweep and its
// --resume is another sweep: its rows are not mixed with the old table's.
}  // namespace

std::string sweep_fingerprint(const std::string& scene_file, const std::vector<std::string>& sets, const CaseTable& table,
                        const Graph& graph, host::RowFormat format) {
  Hasher h;
  h.add(read_user_file(scene_file, max_scene_bytes, "scene"));
  for (const std::string& file : files_read(graph, table)) {
    h.add(file);
    // Bounded as the nodes read it; a file that cannot be read counts as such (the case fails).
    try {
      h.add(std::string_view("contents")).add(read_bounded_file(file));
    } catch (const FileReadError&) {
      h.add(std::string_view("unreadable"));
    }
  }
  for (const std::string& s : sets) h.add(s);
  for (const SweepVariable& v : table.variables) h.add(v.name).add(v.unit);
  // Every case as written() gives it: a table of numbers (a sample of millions) hashes each
  // value's exact text made in one buffer, each variable's unit made once.
  if (table.cases.empty() && !table.numbers.written.ends.empty()) {
    // A cases file's values as written: a bare number's "CELL UNIT" hashed from its parts.
    const CaseTable::Numbers::Written& written = table.numbers.written;
    const std::size_t width = table.numbers.dimensions.size();
    CaseTable::Numbers::Written::Digits digits;
    for (std::size_t k = 0; k < written.ends.size(); ++k) {
      const std::string_view text = written.own_text(k, digits);
      if (written.in_column_unit[k]) h.add_joined({text, " ", written.column_units[k % width]});
      else h.add(text);
    }
  } else if (table.cases.empty()) {
    std::vector<std::string> units;
    for (const Dimension& d : table.numbers.dimensions) units.push_back(exact_text_unit(d));
    std::string text;
    for (std::size_t i = 0; i < table.numbers.count; ++i)
      for (std::size_t v = 0; v < units.size(); ++v) {
        text.clear();
        append_exact_text(text, table.numbers.si[i * units.size() + v], units[v]);
        h.add(std::string_view(text));
      }
  } else {
    for (const std::vector<CaseValue>& row : table.cases)
      for (const CaseValue& v : row) {
        if (!v.text.empty()) h.add(std::string_view(v.text));  // written() without its copy
        else h.add(v.written());
      }
  }
  for (const RequestedOutput& o : graph.outputs) h.add(o.label);
  h.add(static_cast<std::uint64_t>(format));
  char hex[20];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(h.value()));
  return hex;
}

}  // namespace mechgraph::cli
