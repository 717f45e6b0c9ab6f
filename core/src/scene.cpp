#include <mechgraph/scene.hpp>

#include "yaml_bounds.hpp"

#include <mechgraph/bounded_read.hpp>
#include <mechgraph/did_you_mean.hpp>
#include <mechgraph/error_subject.hpp>
#include <mechgraph/errors.hpp>
#include <mechgraph/text_escape.hpp>

#include <yaml-cpp/yaml.h>

#include <charconv>
#include <fstream>
#include <functional>
#include <sstream>

namespace mechgraph {

SceneErrorAt::~SceneErrorAt() = default;

std::string SourceLocation::str() const {
  if (line == 0) return file.empty() ? std::string() : file + ": ";
  return file + ":" + std::to_string(line) + ":" + std::to_string(column) + ": ";
}

namespace {

class SceneReader {
 public:
  explicit SceneReader(std::string file) : file_(std::move(file)) {}

  SourceLocation at(const YAML::Node& n) const {
    const YAML::Mark m = n.Mark();
    return {file_, m.line + 1, m.column + 1};
  }

  [[noreturn]] void fail(const SourceLocation& where, const std::string& message) const {
    throw_scene_error_at(where, message);
  }

  std::string scalar(const YAML::Node& n, const std::string& what) const {
    if (!n.IsScalar()) fail(at(n), "expected " + what + " (a single value), found " + shape(n));
    return n.Scalar();
  }

  static std::string shape(const YAML::Node& n) {
    if (n.IsMap()) return "a map";
    if (n.IsSequence()) return "a list";
    if (n.IsNull()) return "nothing";
    return quoted_text_excerpt(n.Scalar());
  }

  RawValue raw(const YAML::Node& n) const {
    RawValue v;
    v.where = at(n);
    if (n.IsSequence()) {
      v.kind = RawValue::Kind::list;
      for (const auto& item : n) v.items.push_back(raw(item));
    } else if (n.IsMap()) {
      v.kind = RawValue::Kind::map;
      for (const auto& kv : n) {
        RawValue field = raw(kv.second);
        field.key_where = at(kv.first);
        v.fields.emplace_back(scalar(kv.first, "a key"), std::move(field));
      }
    } else if (n.IsScalar()) {
      v.text = n.Scalar();
    } else {
      fail(v.where, "expected a value, found nothing");
    }
    return v;
  }

  void check_keys(const YAML::Node& map, const std::vector<std::string>& valid, const std::string& what) const {
    for (const auto& kv : map) {
      const std::string key = scalar(kv.first, "a key");
      if (std::find(valid.begin(), valid.end(), key) == valid.end())
        fail(at(kv.first), unknown_name_message(what, key, valid));
    }
  }

  const YAML::Node& expect_map(const YAML::Node& n, const std::string& what) const {
    if (!n.IsMap()) fail(at(n), "expected " + what + " as a map (name: value), found " + shape(n));
    return n;
  }

  SceneSpec read(const YAML::Node& root) {
    SceneSpec scene;
    scene.file = file_;
    if (!root.IsMap()) fail({file_, 1, 1}, "a scene is a map with keys title, requires, params, units, uncertainty, nodes, effects, outputs, report");
    check_keys(root, {"title", "requires", "params", "units", "uncertainty", "nodes", "effects", "outputs", "report"}, "scene key");
    if (root["title"]) scene.title = scalar(root["title"], "a title");
    if (const YAML::Node r = root["requires"]; r && !r.IsNull()) {
      if (!r.IsMap()) fail(at(r), "expected requires as a map of plugin: version requirement, e.g. requires: { myplugin: \">=1.0\" }");
      for (const auto& kv : r)
        scene.requirements.push_back({scalar(kv.first, "a plugin id"), scalar(kv.second, "a version requirement"), at(kv.second)});
    }
    if (const YAML::Node p = root["params"]; p && !p.IsNull()) {
      expect_map(p, "params");
      for (const auto& kv : p) {
        RawValue v = raw(kv.second);
        v.key_where = at(kv.first);
        const std::string name = scalar(kv.first, "a parameter name");
        if (const std::string why = name_problem(name); !why.empty()) fail(at(kv.first), "scene parameter name " + why);
        scene.params.emplace_back(name, std::move(v));
      }
    }
    if (const YAML::Node u = root["units"]; u && !u.IsNull()) {
      if (!u.IsMap()) fail(at(u), "expected units as a map of quantity: unit, e.g. units: { length: mm, angle: deg }");
      for (const auto& kv : u) {
        RawValue v = raw(kv.second);
        v.key_where = at(kv.first);
        scene.units.emplace_back(scalar(kv.first, "a quantity name"), std::move(v));
      }
    }
    if (const YAML::Node u = root["uncertainty"]; u && !u.IsNull()) {
      if (!u.IsMap()) fail(at(u), "expected uncertainty as a map (parameters, method, samples, ...), found " + shape(u));
      scene.uncertainty = raw(u);
    }
    const YAML::Node nodes = root["nodes"];
    if (!nodes || nodes.IsNull()) fail({file_, 1, 1}, "the scene has no 'nodes'");
    expect_map(nodes, "nodes");
    for (const auto& kv : nodes) scene.nodes.push_back(read_node(kv.first, kv.second));
    if (const YAML::Node e = root["effects"]; e && !e.IsNull()) {
      if (!e.IsSequence()) fail(at(e), "expected effects as a list, e.g. [monte_carlo]");
      for (const auto& item : e) scene.effects.emplace_back(scalar(item, "an effect name"), at(item));
    }
    if (const YAML::Node o = root["outputs"]; o && !o.IsNull()) {
      if (!o.IsSequence()) fail(at(o), "expected outputs as a list of node.port");
      for (const auto& item : o) {
        PortRef ref = parse_port_ref(scalar(item, "node.port"), at(item));
        if (const PortRef* earlier = listed_before(scene.outputs, ref))
          fail(ref.where, "output '" + ref.str() + "' is listed twice in 'outputs' (first at line " +
                              std::to_string(earlier->where.line) + "): list it once");
        scene.outputs.push_back(std::move(ref));
      }
    }
    if (const YAML::Node r = root["report"]; r && !r.IsNull()) {
      if (r.IsSequence())
        for (const auto& table : r) scene.report.push_back(read_report(table));
      else
        scene.report.push_back(read_report(r));
    }
    return scene;
  }

  NodeSpec read_node(const YAML::Node& key, const YAML::Node& body) {
    NodeSpec node;
    node.name = scalar(key, "a node name");
    node.where = at(key);
    if (const std::string why = name_problem(node.name); !why.empty()) fail(node.where, "node name " + why);
    expect_map(body, "node '" + node.name + "'");
    check_keys(body, {"type", "params", "inputs", "effects", "doc"}, "node key");
    if (!body["type"]) fail(at(body), "node '" + node.name + "' has no 'type'");
    node.type = scalar(body["type"], "a node type");
    node.type_where = at(body["type"]);
    if (const YAML::Node p = body["params"]; p && !p.IsNull()) {
      expect_map(p, "params of node '" + node.name + "'");
      for (const auto& kv : p) {
        RawValue v = raw(kv.second);
        v.key_where = at(kv.first);
        node.params.emplace_back(scalar(kv.first, "a parameter name"), std::move(v));
      }
    }
    if (const YAML::Node in = body["inputs"]; in && !in.IsNull()) {
      expect_map(in, "inputs of node '" + node.name + "'");
      for (const auto& kv : in) {
        NodeSpec::InputSpec input;
        input.port = scalar(kv.first, "an input port name");
        input.where = at(kv.first);
        if (kv.second.IsSequence()) {
          input.listed = true;
          for (const auto& item : kv.second) input.sources.push_back(parse_port_ref(scalar(item, "node.port"), at(item)));
        } else {
          input.sources.push_back(parse_port_ref(scalar(kv.second, "node.port"), at(kv.second)));
        }
        node.inputs.push_back(std::move(input));
      }
    }
    if (const YAML::Node e = body["effects"]; e && !e.IsNull()) {
      if (!e.IsSequence()) fail(at(e), "expected the effects of node '" + node.name + "' as a list, e.g. [elastic_drive]");
      for (const auto& item : e) node.effects.emplace_back(scalar(item, "an effect name"), at(item));
    }
    return node;
  }

  ReportSpec read_report(const YAML::Node& r) {
    ReportSpec report;
    report.where = at(r);
    expect_map(r, "report");
    check_keys(r, {"title", "columns", "rows"}, "report key");
    if (r["title"]) report.title = scalar(r["title"], "a title");
    const YAML::Node columns = r["columns"];
    if (!columns) fail(report.where, "report has no 'columns' (label: { role: node, ... }, or a list of labels)");
    if (columns.IsSequence()) {
      for (const auto& label : columns) report.columns.push_back({scalar(label, "a column label"), {}, at(label)});
    } else {
      expect_map(columns, "report columns");
      for (const auto& kv : columns) {
        ReportSpec::Column c;
        c.label = scalar(kv.first, "a column label");
        c.where = at(kv.first);
        expect_map(kv.second, "the roles of column '" + c.label + "'");
        for (const auto& role : kv.second) c.roles.emplace_back(scalar(role.first, "a role"), scalar(role.second, "a node name"));
        report.columns.push_back(std::move(c));
      }
    }
    const YAML::Node rows = r["rows"];
    if (!rows || !rows.IsSequence()) fail(report.where, "report has no 'rows' list ([label, role.port, unit])");
    for (const auto& row : rows) {
      if (!row.IsSequence() || row.size() < 2 || row.size() > 3)
        fail(at(row), "a report row is [label, role.port, unit] or [label, [node.port, node.port[i], -, ...], unit]");
      ReportSpec::Row out;
      out.label = scalar(row[0], "a row label");
      out.where = at(row[1]);
      if (row[1].IsSequence()) {
        if (row[1].size() != report.columns.size())
          fail(at(row[1]), "row '" + out.label + "' has " + std::to_string(row[1].size()) + " cells for " +
                               std::to_string(report.columns.size()) + " columns");
        for (const auto& cell : row[1]) out.cells.push_back(parse_cell_ref(scalar(cell, "node.port"), at(cell)));
      } else {
        const PortRef ref = parse_port_ref(scalar(row[1], "role.port"), at(row[1]));
        out.role = ref.node;
        out.port = ref.port;
      }
      if (row.size() == 3) out.unit = scalar(row[2], "a unit");
      report.rows.push_back(std::move(out));
    }
    return report;
  }

 private:
  std::string file_;
};

}  // namespace

std::optional<CellRef> parse_cell_ref(std::string_view text, const SourceLocation& where) {
  if (text == "-") return std::nullopt;
  std::optional<std::size_t> element;
  if (!text.empty() && text.back() == ']') {
    const auto open = text.rfind('[');
    std::size_t index = 0;
    const auto digits = text.substr(open + 1, text.size() - open - 2);
    auto [ptr, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), index);
    if (open == std::string_view::npos || digits.empty() || ec != std::errc() || ptr != digits.data() + digits.size())
      throw_scene_error_at(where, "expected 'node.port[index]' with a whole index, found '" + std::string(text) + "'");
    element = index;
    text = text.substr(0, open);
  }
  const PortRef ref = parse_port_ref(text, where);
  return CellRef{ref.node, ref.port, element, where};
}

PortRef parse_port_ref(std::string_view text, const SourceLocation& where) {
  const auto dot = text.find('.');
  if (dot == std::string_view::npos || dot == 0 || dot + 1 == text.size() || text.find('.', dot + 1) != std::string_view::npos)
    throw_scene_error_at(where, "expected 'node.port', found '" + std::string(text) + "'");
  return {std::string(text.substr(0, dot)), std::string(text.substr(dot + 1)), where};
}

const PortRef* listed_before(const std::vector<PortRef>& list, const PortRef& ref) {
  for (const PortRef& earlier : list)
    if (earlier.node == ref.node && earlier.port == ref.port) return &earlier;
  return nullptr;
}

RawValue parse_raw_value(std::string_view text, const SourceLocation& where) {
  constexpr std::size_t max_value_bytes = 1 << 20;
  if (text.size() > max_value_bytes)
    throw_scene_error_at(where, "a value of " + std::to_string(text.size()) + " bytes is more than the limit of 1 MiB");
  detail::check_utf8(text, where.file);
  detail::check_yaml_events(text, where.file, {16, 100'000, 100'000});
  YAML::Node node;
  try {
    node = YAML::Load(std::string(text));
  } catch (const YAML::Exception& e) {
    throw_scene_error_at(where, "cannot read " + quoted_text_excerpt(text) + ": " + e.msg);
  }
  detail::check_yaml_bounds(node, where.file, {16, 100'000, 100'000});
  RawValue v = SceneReader(where.file).raw(node);
  std::function<void(RawValue&)> relocate = [&](RawValue& r) {
    r.where = where;
    r.key_where = where;
    for (auto& item : r.items) relocate(item);
    for (auto& [k, field] : r.fields) relocate(field);
  };
  relocate(v);
  return v;
}

SceneSpec parse_scene(std::string_view yaml_text, const std::string& file_label) {
  // The bound of a scene file holds for a scene given as text (Python's Scene.from_text) as well.
  if (yaml_text.size() > max_scene_bytes)
    throw SceneError(file_label + ": a scene of " + std::to_string(yaml_text.size()) + " bytes is more than the limit of " +
                     std::to_string(max_scene_bytes) + " bytes (1 MiB); nothing of it was read");
  detail::check_utf8(yaml_text, file_label);
  detail::check_yaml_events(yaml_text, file_label);
  YAML::Node root;
  try {
    root = YAML::Load(std::string(yaml_text));
  } catch (const YAML::Exception& e) {
    throw_scene_error_at(SourceLocation{file_label, e.mark.line + 1, e.mark.column + 1}, "YAML syntax: " + e.msg);
  }
  detail::check_yaml_bounds(root, file_label);
  return SceneReader(file_label).read(root);
}

SceneSpec load_scene(const std::filesystem::path& file) {
  std::string text;
  try {
    text = read_bounded_file(file, max_scene_bytes);
  } catch (const FileReadError& e) {
    throw SceneError(std::string("the scene: ") + e.what());
  }
  return parse_scene(text, file.string());
}

std::string name_problem(std::string_view name) {
  constexpr std::size_t max_name = 64;
  const auto letter = [](char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_'; };
  const auto digit = [](char c) { return c >= '0' && c <= '9'; };
  if (name.empty()) return "is empty";
  if (name.size() > max_name) return quoted_text_excerpt(name, 40) + " is longer than " + std::to_string(max_name) + " characters";
  bool ok = letter(name.front());
  for (char c : name) ok = ok && (letter(c) || digit(c) || c == '-');
  if (!ok)
    return quoted_text_excerpt(name) + " is not a name: it starts with a letter or '_' and holds only ASCII letters, digits, '_' and '-'";
  return {};
}

}  // namespace mechgraph
