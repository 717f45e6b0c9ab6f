#include <mechgraph/sweep/block_plan.hpp>

#include <mechgraph/block.hpp>
#include <mechgraph/display_units.hpp>
#include <mechgraph/plugin_registry.hpp>

#include "../node_context.hpp"

#include <algorithm>
#include <cmath>
#include <map>

namespace mechgraph {
namespace {

std::string owner_of(const GraphNode& node) { return "node '" + node.name + "' (" + node.info().type + ")"; }

using Produced = BlockPlan::WorkerState::Produced;

// Evaluates node `i` for `live` (n cases, or 1 for a node no case changes) into `out`. False when
// the whole block must be redone case by case: the node threw, broke its declarations or reported
// a non-finite counter (each case alone then gives the message a run gives). A case with a
// non-finite output or an object that breaks its contract is failed alone.
bool evaluate_block_node(GraphNode& node, const BlockEvaluation& type, std::map<std::string, BlockColumn, std::less<>> varied,
                         const std::vector<Produced>& produced, BlockCases& live, Produced& out) {
  const std::size_t size = live.size();
  BlockParams params(node.params, std::move(varied));
  BlockInputs inputs;
  for (const GraphNode::Input& in : node.inputs) {
    const GraphNode::Source& source = in.sources.front();
    const Produced& from = produced[source.node];
    const auto scalar = std::find(from.ports.begin(), from.ports.end(), source.port);
    const auto handle = std::find(from.handle_ports.begin(), from.handle_ports.end(), source.port);
    if (scalar != from.ports.end()) {
      inputs.add_scalar(in.port, {from.scalars[static_cast<std::size_t>(scalar - from.ports.begin())].data(), from.varied ? 1u : 0u});
    } else if (handle != from.handle_ports.end()) {
      inputs.add_handle(in.port, from.handles[static_cast<std::size_t>(handle - from.handle_ports.begin())]);
    } else {
      return false;  // not made: the single evaluation says why
    }
  }
  BlockOutputs outputs(size);
  for (const std::string& port : node.wanted)
    if (const PortSpec* spec = node.info().find_output(port); spec && spec->kind == ValueKind::scalar) outputs.want_scalar(port);
  NodeContext context(node, nullptr);  // counters summed over the block, only checked to be finite
  try {
    type.evaluate_block(params, inputs, outputs, live, context);
    if (context.bad_counter()) return false;
    out.ports.clear();
    out.scalars.clear();
    for (const auto& [port, column] : outputs.scalars()) {
      for (std::size_t k = 0; k < size; ++k)
        if (!live.failed(k) && !std::isfinite(column[k])) live.fail(k);
      out.ports.push_back(port);
      out.scalars.push_back(column);
    }
    out.handle_ports.clear();
    out.handles.clear();
    for (const std::string& port : node.wanted) {
      const PortSpec* spec = node.info().find_output(port);
      if (!spec || spec->kind != ValueKind::handle) continue;
      const auto it = outputs.handles().find(port);
      if (it == outputs.handles().end() || !it->second) return false;
      const DomainBlock& block = *it->second;
      if (block.kind() != spec->handle_kind || (block.size() != size && block.size() != 1)) return false;
      for (std::size_t k = 0; k < size; ++k)
        if (!live.failed(k) && !block.contract_problem(k).empty()) live.fail(k);
      out.handle_ports.push_back(port);
      out.handles.push_back(it->second);
    }
  } catch (...) {
    return false;
  }
  return true;
}

}  // namespace

BlockPlan::BlockPlan(const Graph& graph, const CaseBinder& binder) : binder_(binder) {
  if (binder.rebuilds()) {
    why_not_ = "a varied parameter sits inside a list or record";
    return;
  }
  targets_ = binder.targets();
  varied_.assign(graph.nodes.size(), 0);
  for (std::size_t v = 0; v < targets_.size(); ++v)
    for (const CaseBinder::Target& t : targets_[v]) {
      if (t.spec->kind != ParamKind::number) {
        why_not_ = "'" + binder.variables()[v].name + "' is not a real number parameter";
        return;
      }
      varied_[t.node] = 1;
    }
  for (std::size_t i : graph.order)
    for (std::size_t u : graph.nodes[i].upstream) varied_[i] = varied_[i] || varied_[u];
  for (const RequestedOutput& o : graph.outputs)
    if (!o.spec || o.spec->kind != ValueKind::scalar) {
      why_not_ = "output '" + o.label + "' is not a single number";
      return;
    }
  for (std::size_t i : graph.order) {
    const GraphNode& node = graph.nodes[i];
    const auto* type = dynamic_cast<const BlockEvaluation*>(node.type->type.get());
    if (!type) {
      why_not_ = owner_of(node) + " does not evaluate blocks";
      return;
    }
    for (const GraphNode::Input& in : node.inputs)
      if (in.sources.size() != 1) {
        why_not_ = owner_of(node) + ": input '" + in.port + "' has several connections";
        return;
      }
    std::vector<std::string> varied;
    for (const auto& targets : targets_)
      for (const CaseBinder::Target& t : targets)
        if (t.node == i) varied.push_back(t.spec->name);
    try {
      if (!type->block_supported(BlockRequest{node.params, node.wanted, varied})) {
        why_not_ = owner_of(node) + " does not evaluate blocks for what is read of it";
        return;
      }
    } catch (...) {
      why_not_ = owner_of(node) + " could not say whether it evaluates blocks";
      return;
    }
  }
}

std::vector<BlockPlan::CaseOutcome> BlockPlan::run(Graph& graph, const CaseTable& table, std::span<const std::size_t> indices,
                                                   WorkerState& state) const {
  const std::size_t n = indices.size();
  std::vector<CaseOutcome> outcomes(n);
  if (state.nodes.size() != graph.nodes.size()) state.nodes.assign(graph.nodes.size(), {});
  // The nodes no case changes, once per worker, as blocks of one case.
  if (!state.constants_made) {
    state.constants_made = true;
    for (std::size_t i : graph.order) {
      if (varied_[i]) continue;
      BlockCases one(1);
      state.nodes[i].varied = false;
      const auto& type = dynamic_cast<const BlockEvaluation&>(*graph.nodes[i].type->type);
      if (!evaluate_block_node(graph.nodes[i], type, {}, state.nodes, one, state.nodes[i]) || one.failed(0)) {
        state.constants_failed = true;
        break;
      }
    }
  }
  if (state.constants_failed) return outcomes;  // every case alone: the first gives the message

  // The varied parameters as columns, each value checked by the binder's own rule; a value it
  // would refuse leaves its case to the per-case path, which refuses it with its message.
  BlockCases cases(n);
  std::vector<std::vector<double>> columns(targets_.size(), std::vector<double>(n, 0.0));
  CaseValue made;
  for (std::size_t v = 0; v < targets_.size(); ++v)
    for (std::size_t k = 0; k < n; ++k) {
      const CaseValue& value = table.number_cell(indices[k], v, made);  // writes_number reads the number only
      if (binder_.writes_number(v, value)) columns[v][k] = *value.si;
      else cases.fail(k);
    }
  // Per node, the column of each varied parameter, written in apply()'s order: where a scene
  // parameter and a node parameter it reaches are both varied, the node's own wins, as case by case.
  std::vector<std::map<std::string, BlockColumn, std::less<>>> varied(graph.nodes.size());
  for (const std::size_t v : binder_.apply_order())
    for (const CaseBinder::Target& t : targets_[v]) varied[t.node][t.spec->name] = BlockColumn{columns[v].data(), 1};

  for (std::size_t i : graph.order) {
    if (!varied_[i]) continue;
    state.nodes[i].varied = true;
    const auto& type = dynamic_cast<const BlockEvaluation&>(*graph.nodes[i].type->type);
    if (!evaluate_block_node(graph.nodes[i], type, std::move(varied[i]), state.nodes, cases, state.nodes[i])) return outcomes;
  }
  // The requested outputs, read from their producers' columns, each with the unit a run shows it
  // in (the scene's units:, else the port's display unit; as check_displayable in the evaluator).
  struct Requested {
    const double* column;
    std::size_t stride;
    UnitScale shown;  // scale 1, offset 0 where the output is shown in SI
  };
  std::vector<Requested> requested;
  for (const RequestedOutput& o : graph.outputs) {
    const Produced& from = state.nodes[o.node];
    const auto port = std::find(from.ports.begin(), from.ports.end(), o.port);
    if (port == from.ports.end()) return outcomes;
    const std::string unit = graph.display_units.unit_for(o.spec->dimension, o.spec->display_unit);
    const std::optional<UnitScale> shown = unit.empty() ? std::nullopt : parse_unit_cached(unit);
    requested.push_back({from.scalars[static_cast<std::size_t>(port - from.ports.begin())].data(), from.varied ? 1u : 0u,
                         shown.value_or(UnitScale{})});
  }
  for (std::size_t k = 0; k < n; ++k) {
    if (cases.failed(k)) continue;
    // A number beyond the range of a double in its shown unit (1e300 m in nm) leaves its case to
    // the per-case path, which refuses it with the run's message: the rows never hold "inf".
    const bool displayable = std::all_of(requested.begin(), requested.end(),
                                         [k](const Requested& r) { return finite_in_unit(std::abs(r.column[k * r.stride]), r.shown); });
    if (!displayable) continue;
    std::vector<Value>& values = outcomes[k].outputs.emplace();
    values.reserve(requested.size());
    for (const Requested& r : requested) values.push_back(Value::scalar(r.column[k * r.stride]));
  }
  return outcomes;
}

}  // namespace mechgraph
