#include <mechgraph/sweep/case_binder.hpp>

#include <mechgraph/did_you_mean.hpp>
#include <mechgraph/error_subject.hpp>
#include <mechgraph/errors.hpp>
#include <mechgraph/units.hpp>
#include <mechgraph/display_units.hpp>

#include <spdlog/spdlog.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <string_view>
#include <unordered_set>

namespace mechgraph {
namespace {

std::string owner_of(const GraphNode& node) { return "node '" + node.name + "' (" + node.info().type + ")"; }

// The rule a number of a case meets to be written into a number or integer parameter: a finite
// number of the parameter's dimension inside its range. apply() says which part a value breaks.
bool admits_number(const ParamSpec& spec, const CaseValue& value) {
  // value_problem() is empty exactly when admits() holds, and for an integer when the value is
  // also whole: a real number's range is all there is to ask, without the words (a sweep asks
  // this of every target of every variable of every case, twice).
  return value.si && std::isfinite(*value.si) && value.dimension == spec.dimension && spec.admits(*value.si) &&
         (spec.kind != ParamKind::integer || spec.value_problem(*value.si).empty());
}

// The start of a message about variable `name`: "sweep: 'rpm'" or, for a run's set=, "set rpm".
std::string about(BinderUse use, const std::string& name) {
  if (use == BinderUse::study) return "study: '" + name + "'";
  return use == BinderUse::sweep ? "sweep: '" + name + "'" : "set " + name;
}

// What `name` could have meant: a node's parameters for "node.x", else the nodes or the scene's.
std::string unknown_variable(const Graph& graph, const std::string& name, BinderUse use) {
  std::vector<std::string> valid;
  const auto dot = name.find('.');
  if (dot != std::string::npos) {
    if (const auto node = graph.find(name.substr(0, dot))) {
      for (const ParamSpec& p : graph.nodes[*node].info().params) valid.push_back(p.name);
      return about(use, name) + ": " + owner_of(graph.nodes[*node]) + ": " + unknown_name_message("parameter", name.substr(dot + 1), valid);
    }
    for (const GraphNode& n : graph.nodes) valid.push_back(n.name);
    return about(use, name) + ": " + unknown_name_message("node", name.substr(0, dot), valid);
  }
  for (const auto& [scene_param, uses] : graph.scene_param_uses) valid.push_back(scene_param);
  if (use == BinderUse::set)
    return about(use, name) + ": " + unknown_name_message("scene parameter", name, valid) + " (a node's parameter is set as node.param)";
  if (use == BinderUse::study)
    return "study: " + unknown_name_message("scene parameter", name, valid) + " (a node's parameter is given a distribution as node.param)";
  return "sweep: " + unknown_name_message("scene parameter", name, valid) + " (a node's parameter is varied as node.param)";
}

}  // namespace

CaseBinder::CaseBinder(const Graph& base, const SceneSpec& scene, const PluginRegistry& registry,
                       std::vector<Override> overrides, std::vector<SweepVariable> variables, BinderUse use)
    : scene_(scene), registry_(registry), overrides_(std::move(overrides)), variables_(std::move(variables)), use_(use) {
  std::unordered_set<std::string_view> varied;  // linear in the variables, however many
  varied.reserve(variables_.size());
  for (std::size_t v = 0; v < variables_.size(); ++v) {
    const std::string& name = variables_[v].name;
    if (!varied.insert(name).second)
      throw SceneError(about(use, name) + (use == BinderUse::sweep ? " is varied twice" : " is given twice"));
    std::vector<Target> targets;
    bool nested = false;
    if (const auto dot = name.find('.'); dot == std::string::npos) {
      auto it = base.scene_param_uses.find(name);
      if (it == base.scene_param_uses.end()) {
        const bool defined = std::any_of(scene.params.begin(), scene.params.end(), [&](const auto& p) { return p.first == name; });
        if (defined && use == BinderUse::sweep)
          throw SceneError("sweep: scene parameter '" + name + "' is not used by any node: varying it changes nothing");
        if (defined && use == BinderUse::study)
          throw SceneError("study: scene parameter '" + name + "' is not used by any node: its distribution changes nothing");
        if (defined) throw SceneError("set " + name + ": scene parameter '" + name + "' is not used by any node: setting it changes nothing");
        throw SceneError(unknown_variable(base, name, use));
      }
      for (const SceneParamUse& use : it->second) {
        const GraphNode& node = base.nodes[use.node];
        nested = nested || use.nested;
        targets.push_back({use.node, node.info().find_param(use.param)});
      }
    } else {
      const auto node = base.find(name.substr(0, dot));
      const ParamSpec* spec = node ? base.nodes[*node].info().find_param(name.substr(dot + 1)) : nullptr;
      if (!spec) throw SceneError(unknown_variable(base, name, use));
      // A node parameter written as `$x` in the scene is replaced for this node only.
      targets.push_back({*node, spec});
    }
    for (const Target& t : targets)
      if (t.spec->kind == ParamKind::number_list || t.spec->kind == ParamKind::record_list) nested = true;
    const bool reaches = std::any_of(targets.begin(), targets.end(), [&](const Target& t) { return base.nodes[t.node].needed; });
    reaches_needed_.push_back(reaches ? 1 : 0);
    if (!reaches && use != BinderUse::study) {
      if (use == BinderUse::sweep)
        spdlog::warn("sweep: '{}' only reaches nodes the requested outputs do not need: varying it changes nothing", name);
      else
        spdlog::debug("set {}: reaches no node the requested outputs need", name);
    }
    rebuild_ = rebuild_ || nested;
    targets_.push_back(std::move(targets));
    swept_labels_.push_back((use == BinderUse::sweep ? "(swept " : use == BinderUse::study ? "(sampled " : "(set ") + name + ")");
  }
  // Scene parameters first, then node parameters: where a variable names a node's parameter that a
  // scene parameter varied beside it also reaches, the node's own wins, as with `run --set` (and
  // whatever the order of the columns).
  for (std::size_t v = 0; v < variables_.size(); ++v)
    if (variables_[v].name.find('.') == std::string::npos) apply_order_.push_back(v);
  for (std::size_t v = 0; v < variables_.size(); ++v)
    if (variables_[v].name.find('.') != std::string::npos) apply_order_.push_back(v);
  if (rebuild_ && use == BinderUse::sweep)
    spdlog::info("sweep: a varied parameter sits inside a list or record; each case's graph is built anew from the scene");
}

void CaseBinder::mark_unmemoised(Graph& graph) const {
  std::vector<char> varied(graph.nodes.size(), 0);
  for (const auto& targets : targets_)
    for (const Target& t : targets)
      if (t.node < varied.size()) varied[t.node] = 1;
  // graph.order is topological: a node is varied when it is a target or reads a varied node.
  for (std::size_t i : graph.order) {
    for (std::size_t u : graph.nodes[i].upstream) varied[i] = varied[i] || varied[u];
    graph.nodes[i].memoised = !varied[i];
  }
}

CaseBinder::Slots CaseBinder::bind(Graph& graph) const {
  Slots slots;
  for (std::size_t v = 0; v < variables_.size(); ++v) {
    std::vector<ParamValue*>& of = slots.of_variable.emplace_back();
    for (const Target& t : targets_[v]) {
      GraphNode& node = graph.nodes[t.node];
      // A parameter the scene left to its default gets its slot now; every case writes it.
      of.push_back(&node.params.slot(t.spec->name));
      node.param_where[t.spec->name] = SourceLocation{swept_labels_[v], 0, 0};
    }
  }
  return slots;
}

void CaseBinder::apply(Graph& graph, const std::vector<CaseValue>& values) const {
  if (rebuild_) {
    std::vector<Override> overrides = overrides_;
    for (std::size_t v = 0; v < variables_.size(); ++v)
      overrides.push_back({variables_[v].name, values[v].written(), variables_[v].name + "=" + values[v].written()});
    graph = build_graph(scene_, registry_, overrides);
    return;
  }
  apply(bind(graph), graph, values);
}

void CaseBinder::apply(const Slots& slots, const Graph& graph, const std::vector<CaseValue>& values) const {
  for (const std::size_t v : apply_order_) {
    const CaseValue& value = values[v];
    // The messages are built only when one is thrown (a sweep applies millions of values).
    const auto what = [&] { return variables_[v].name + " = '" + excerpt(value.written()) + "'"; };
    for (std::size_t k = 0; k < targets_[v].size(); ++k) {
      const Target& t = targets_[v][k];
      const GraphNode& node = graph.nodes[t.node];
      const ParamSpec& spec = *t.spec;
      const auto param = [&] { return "parameter '" + spec.name + "' of " + owner_of(node); };
      const auto subject = [&] { return ErrorSubject{{}, node.name, spec.name}; };  // as data (error_subject.hpp)
      ParamValue& slot = *slots.of_variable[v][k];
      switch (spec.kind) {
        case ParamKind::number:
        case ParamKind::integer: {
          if (admits_number(spec, value)) {
            // Written in place: a number needs no new ParamValue.
            slot.kind = spec.kind;
            slot.number = spec.kind == ParamKind::integer ? static_cast<double>(static_cast<long>(*value.si)) : *value.si;
            break;
          }
          // Refused: the message says which part of the rule the value breaks.
          if (!value.si) {
            std::string why = "not a number with a unit";
            try {
              parse_quantity(value.text);
            } catch (const UnitError& e) {
              why = e.what();
            }
            throw SceneErrorAt(subject(), what() + ": " + param() + ": " + why);
          }
          // Read values are finite already (case_table); a table built by a library caller may not be.
          if (!std::isfinite(*value.si)) throw SceneErrorAt(subject(), what() + ": " + param() + ": not a finite number");
          if (!(value.dimension == spec.dimension))
            throw SceneErrorAt(subject(), what() + ": " + param() + " is " + spec.dimension.describe() + " (" + spec.dimension.si_unit() +
                             "), the value is " + (value.dimension.dimensionless() ? "a bare number" : value.dimension.describe()));
          throw SceneErrorAt(subject(), what() + ": " + param() + " " + spec.value_problem(*value.si));
        }
        case ParamKind::choice:
          if (std::find(spec.choices.begin(), spec.choices.end(), value.written()) == spec.choices.end())
            throw SceneErrorAt(subject(), what() + ": " + param() + ": " + unknown_name_message("choice", value.written(), spec.choices));
          slot = ParamValue::of_choice(value.written());
          break;
        case ParamKind::text: slot = ParamValue::of_text(value.written()); break;
        case ParamKind::number_list:
        case ParamKind::record_list: break;  // rebuilt, never bound
      }
    }
  }
}

bool CaseBinder::writes_number(std::size_t v, const CaseValue& value) const {
  for (const Target& t : targets_[v])
    if (t.spec->kind != ParamKind::number || !admits_number(*t.spec, value)) return false;
  return true;
}

void read_bare_numbers_in_list_unit(CaseTable& table, const CaseBinder& binder) {
  for (std::size_t v = 0; v < table.variables.size(); ++v) {
    const std::string& unit = table.variables[v].unit;
    if (unit.empty()) continue;
    const std::optional<UnitScale>& scale = parse_unit_cached(unit);
    if (!scale || scale->dimension.dimensionless()) continue;
    const std::vector<CaseBinder::Target>& targets = binder.targets()[v];
    const auto takes_the_unit = [&](const CaseBinder::Target& t) {
      return (t.spec->kind == ParamKind::number || t.spec->kind == ParamKind::integer) && t.spec->dimension == scale->dimension;
    };
    if (targets.empty() || !std::all_of(targets.begin(), targets.end(), takes_the_unit)) continue;
    for (std::vector<CaseValue>& row : table.cases) {
      CaseValue& value = row[v];
      // A number written without a unit: its text reads whole as the number (not a word, not "nan").
      if (!value.si || !value.dimension.dimensionless() || value.text.empty()) continue;
      double number = 0.0;
      const char* first = value.text.data() + (value.text.front() == '+' ? 1 : 0);
      const char* end = value.text.data() + value.text.size();
      const std::from_chars_result read = std::from_chars(first, end, number);
      if (read.ec != std::errc() || read.ptr != end || number != *value.si) continue;
      // Read as a cases file's cell under its column's unit ("CELL UNIT"): the value --set gives;
      // one beyond a double in that unit is then text, and its case fails as "1e308h" written out.
      value = read_case_value(value.text + " " + unit, "--vary " + excerpt(table.variables[v].name));
    }
  }
}

}  // namespace mechgraph
