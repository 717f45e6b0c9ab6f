#include <mechgraph/evaluator.hpp>

#include "node_context.hpp"

#include <mechgraph/error_subject.hpp>
#include <mechgraph/bounded_read.hpp>
#include <mechgraph/hash.hpp>
#include <mechgraph/units.hpp>
#include <mechgraph/worker_threads.hpp>

#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <exception>
#include <thread>
#include <cmath>
#include <fstream>
#include <iterator>
#include <map>
#include <mutex>
#include <optional>
#include <sstream>

namespace mechgraph {

NodeEvaluationError::~NodeEvaluationError() = default;

namespace {

void hash_param(Hasher& h, const ParamValue& v) {
  h.add(static_cast<std::uint64_t>(v.kind));
  switch (v.kind) {
    case ParamKind::number:
    case ParamKind::integer: h.add(v.number); break;
    case ParamKind::choice:
    case ParamKind::text: h.add(v.text); break;
    case ParamKind::number_list:
      h.add(static_cast<std::uint64_t>(v.numbers.size()));
      for (double x : v.numbers) h.add(x);
      break;
    case ParamKind::record_list:
      h.add(static_cast<std::uint64_t>(v.records.size()));
      for (const Record& r : v.records) {
        h.add(static_cast<std::uint64_t>(r.size()));
        for (const auto& [name, field] : r) {
          h.add(name);
          hash_param(h, field);
        }
      }
      break;
  }
}

void hash_file(Hasher& h, const std::string& path) {
  // Bounded like every read of a file a scene names: a FIFO, a device or a huge file is not read
  // here (the node refuses it by name when it runs).
  try {
    h.add(read_bounded_file(path));
  } catch (const FileReadError&) {
    h.add(std::string_view("unreadable"));
  }
}


std::string format_double(double x) {
  std::ostringstream os;
  os.precision(6);
  os << x;
  return os.str();
}

std::string where_of(const GraphNode& node) { return "node '" + node.name + "' (" + node.info().type + ")"; }


// A table's channels are as long as its axis and named once each.
void check_table_shape(const GraphNode& node, const std::string& port, const Table& t) {
  for (std::size_t i = 0; i < t.channels.size(); ++i) {
    const Table::Column& c = t.channels[i];
    if (c.values.size() != t.axis.values.size())
      throw EvaluationError(where_of(node) + " produced table '" + port + "' whose channel '" + c.name + "' has " +
                            std::to_string(c.values.size()) + " values for an axis of " +
                            std::to_string(t.axis.values.size()));
    if (c.name == t.axis.name)
      throw EvaluationError(where_of(node) + " produced table '" + port + "' with a channel named like its axis ('" + c.name + "')");
    for (std::size_t j = 0; j < i; ++j)
      if (t.channels[j].name == c.name)
        throw EvaluationError(where_of(node) + " produced table '" + port + "' with channel '" + c.name + "' twice");
  }
}

// A series' axis, values and (when present) labels have one entry per element: a shorter axis
// would be read past its end by every writer.
void check_series_shape(const GraphNode& node, const std::string& port, const Series& s) {
  if (s.axis.size() != s.values.size())
    throw EvaluationError(node.where.str() + where_of(node) + " produced series '" + port + "' with " +
                          std::to_string(s.values.size()) + " values over an axis of " + std::to_string(s.axis.size()) +
                          " (they must be as long; a defect of its plugin)");
  if (!s.labels.empty() && s.labels.size() != s.values.size())
    throw EvaluationError(node.where.str() + where_of(node) + " produced series '" + port + "' with " +
                          std::to_string(s.labels.size()) + " labels for " + std::to_string(s.values.size()) +
                          " values (labels are one per value, or none; a defect of its plugin)");
}

// Checks what a node produced against what it declared, and ties handles to the plugin's library.
std::shared_ptr<const OutputSet> checked_outputs(const GraphNode& node, OutputSet&& produced) {
  std::vector<std::pair<std::string, Value>> handles;  // kept alive with their plugin (below)
  for (const auto& [port, value] : produced.all()) {
    const PortSpec* spec = node.info().find_output(port);
    if (!spec) throw EvaluationError(where_of(node) + " produced output '" + port + "', which it does not declare");
    if (value.kind() != spec->kind)
      throw EvaluationError(where_of(node) + " produced a " + std::string(to_string(value.kind())) + " at output '" + port +
                            "', declared as a " + std::string(to_string(spec->kind)));
    // Shapes first: the finiteness check below and every writer index the arrays together.
    if (value.kind() == ValueKind::series) check_series_shape(node, port, value.as_series());
    if (value.kind() == ValueKind::table) check_table_shape(node, port, value.as_table());
    if (!all_finite(value))
      throw EvaluationError(node.where.str() + where_of(node) + " produced a NaN or infinite value at output '" + port +
                            "': its parameters or inputs are beyond what it can compute, and it did not say which "
                            "(please report it: a node must refuse such inputs naming the parameter)");
    if (value.kind() == ValueKind::handle) {
      if (!value.as_handle() || value.as_handle()->kind() != spec->handle_kind)
        throw EvaluationError(where_of(node) + " produced no " + spec->handle_kind + " at output '" + port + "'");
      // The interface's own contract (e.g. an event inside (-pi, pi)): refused, never truncated.
      if (const std::string problem = value.as_handle()->contract_problem(); !problem.empty())
        throw EvaluationError(node.where.str() + where_of(node) + " produced a " + spec->handle_kind + " at output '" +
                              port + "' that breaks the " + spec->handle_kind + " contract: " + problem);
      handles.emplace_back(port, Value::handle(node.type->keep_alive(value.as_handle())));
    }
  }
  // Everything checked: the node's own set is kept (moved, not copied), its handles wrapped.
  auto checked = std::make_shared<OutputSet>(std::move(produced));
  for (auto& [port, value] : handles) checked->set(std::move(port), std::move(value));
  return checked;
}

}  // namespace

std::vector<std::uint64_t> node_hashes(const Graph& graph) {
  std::vector<std::uint64_t> hashes(graph.nodes.size(), 0);
  for (std::size_t i : graph.order) {
    const GraphNode& node = graph.nodes[i];
    if (!node.memoised) continue;  // never looked up (and all it feeds is unmemoised too): no key
    Hasher h;
    h.add(node.info().type).add(static_cast<std::uint64_t>(node.info().version));
    for (const auto& [name, value] : node.params.all()) {
      h.add(name);
      hash_param(h, value);
      // A file named by a parameter is part of the input: its contents enter the key, so an
      // edited table is not mistaken for the cached one.
      if (const ParamSpec* spec = node.info().find_param(name); spec && spec->is_path) hash_file(h, value.text);
    }
    for (const std::string& e : node.effects_read) h.add(e);
    // What is read of it: a node may leave out outputs nobody reads, so its results depend on it.
    for (const std::string& w : node.wanted) h.add(w);
    for (const GraphNode::Input& in : node.inputs) {
      h.add(in.port);
      for (const GraphNode::Source& s : in.sources) h.add(hashes[s.node]).add(s.port);
    }
    hashes[i] = h.value();
  }
  return hashes;
}

namespace {

// Work counters are numbers like the outputs: a NaN one would reach the JSON writer mid-print.
[[noreturn]] void refuse_counter(const GraphNode& node, const std::string& counter, double amount) {
  throw EvaluationError(node.where.str() + where_of(node) + " reported work counter '" + counter + "' as " +
                        (std::isnan(amount) ? "NaN" : "infinite") + " (a work counter is a finite count; a defect of its plugin)");
}

// Evaluates node i (or takes it from the cache); its producers are in `produced` already. Fills
// `record` (name, time, counters, notes) when given; a sweep's lean run passes none. Returns
// whether the node was taken from the cache.
bool run_node_unnamed(const Graph& graph, std::size_t i, const std::vector<std::uint64_t>& hashes,
                      std::vector<std::shared_ptr<const OutputSet>>& produced, MemoCache& cache, NodeRun* record) {
  const GraphNode& node = graph.nodes[i];
  if (record) *record = NodeRun{node.name, node.info().type, hashes[i], false, 0.0, {}, {}};
  if (auto hit = node.memoised ? cache.find(hashes[i]) : nullptr) {
    produced[i] = hit;
    if (record) {
      record->reused = true;
      record->notes = hit->notes();
    }
    spdlog::debug("{} reused from the memo cache", where_of(node));
    return true;
  }
  InputSet inputs;
  for (const GraphNode::Input& in : node.inputs)
    for (const GraphNode::Source& s : in.sources) {
      const auto& outs = produced[s.node]->all();
      auto it = outs.find(s.port);
      if (it == outs.end())
        throw EvaluationError(where_of(node) + ": its input '" + in.port + "' needs '" + graph.nodes[s.node].name + "." +
                              s.port + "', which that node did not produce: it needs an effect or parameters that node "
                              "was not given");
      inputs.add(in.port, it->second);
    }
  OutputSet outputs;
  NodeContext context(node, record);
  std::chrono::steady_clock::time_point start;
  if (record) start = std::chrono::steady_clock::now();
  try {
    node.type->type->evaluate(node.params, inputs, outputs, context);
  } catch (const NodeError& e) {
    // Point at the parameter's value in the scene when it was written there, else at the node.
    auto at = node.param_where.find(e.parameter());
    const SourceLocation& where = at != node.param_where.end() ? at->second : node.where;
    throw NodeEvaluationError({where, node.name, e.parameter()},
                              where.str() + where_of(node) + ", parameter '" + e.parameter() + "': " + e.what());
  } catch (const EvaluationError&) {
    throw;
  } catch (const std::bad_alloc&) {
    throw EvaluationError(where_of(node) + ": ran out of memory (an allocation failed)");
  } catch (const std::exception& e) {
    throw EvaluationError(where_of(node) + ": " + e.what());
  } catch (...) {
    throw EvaluationError(where_of(node) + " threw something that is not a std::exception (a defect of its plugin)");
  }
  if (record) {
    record->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    for (const auto& [counter, amount] : record->work)
      if (!std::isfinite(amount)) refuse_counter(node, counter, amount);
  } else if (const auto& bad = context.bad_counter()) {
    refuse_counter(node, bad->first, bad->second);
  }
  // The checks call plugin code too (a domain object's kind() and contract_problem()): whatever
  // it throws is this node's evaluation error, never the end of the host.
  try {
    produced[i] = checked_outputs(node, std::move(outputs));
  } catch (const EvaluationError&) {
    throw;
  } catch (const std::exception& e) {
    throw EvaluationError(where_of(node) + ": checking its outputs: " + e.what());
  } catch (...) {
    throw EvaluationError(where_of(node) + ": checking its outputs, its plugin threw something that is not a "
                                           "std::exception (a defect of its plugin)");
  }
  if (record) record->notes = produced[i]->notes();
  if (node.memoised) cache.store(hashes[i], produced[i]);
  if (record) spdlog::debug("{} evaluated in {:.3g} s", where_of(node), record->seconds);
  return false;
}

// An EvaluationError while evaluating node i carries the node as data (error_subject.hpp).
NodeEvaluationError named(const GraphNode& node, const EvaluationError& e) {
  return NodeEvaluationError({node.where, node.name, {}}, e.what());
}

bool run_node(const Graph& graph, std::size_t i, const std::vector<std::uint64_t>& hashes,
              std::vector<std::shared_ptr<const OutputSet>>& produced, MemoCache& cache, NodeRun* record) {
  try {
    return run_node_unnamed(graph, i, hashes, produced, cache, record);
  } catch (const NodeEvaluationError&) {
    throw;
  } catch (const EvaluationError& e) {
    throw named(graph.nodes[i], e);
  }
}

// Runs the needed nodes on `threads` workers: a node starts as soon as all its producers are done.
void run_parallel(const Graph& graph, const std::vector<std::uint64_t>& hashes,
                  std::vector<std::shared_ptr<const OutputSet>>& produced, MemoCache& cache, unsigned threads,
                  std::vector<NodeRun>& runs) {
  const std::size_t n = graph.nodes.size();
  std::vector<std::size_t> waiting(n, 0);                 // producers not finished yet
  std::vector<std::vector<std::size_t>> consumers(n);
  for (std::size_t i : graph.order)
    for (std::size_t u : graph.nodes[i].upstream) {
      ++waiting[i];
      consumers[u].push_back(i);
    }
  // A node identical to an earlier one (same memo hash) waits for it and is then reused from the
  // cache, as it is on one thread: which nodes run and which are reused does not depend on --threads.
  std::map<std::uint64_t, std::size_t> first_with_hash;
  for (std::size_t i : graph.order) {
    const auto [it, fresh] = first_with_hash.emplace(hashes[i], i);
    if (!fresh) {
      ++waiting[i];
      consumers[it->second].push_back(i);
    }
  }
  std::vector<std::size_t> ready;
  for (std::size_t i : graph.order)
    if (waiting[i] == 0) ready.push_back(i);
  std::vector<NodeRun> by_node(n);
  std::mutex mutex;
  std::condition_variable changed;
  std::size_t remaining = graph.order.size();
  std::exception_ptr failure;
  auto worker = [&] {
    std::unique_lock lock(mutex);
    while (true) {
      changed.wait(lock, [&] { return !ready.empty() || remaining == 0 || failure; });
      if (remaining == 0 || failure) return;
      const std::size_t i = ready.back();
      ready.pop_back();
      lock.unlock();
      NodeRun run;
      std::exception_ptr error;
      try {
        run_node(graph, i, hashes, produced, cache, &run);
      } catch (...) {
        error = std::current_exception();
      }
      lock.lock();
      if (error) {
        if (!failure) failure = error;
      } else {
        by_node[i] = std::move(run);
        --remaining;
        for (std::size_t c : consumers[i])
          if (--waiting[c] == 0) ready.push_back(c);
      }
      changed.notify_all();
    }
  };
  // The calling thread works too; threads that cannot start leave their nodes to the others.
  // Whatever escapes a worker (no memory) ends the run as an error, never std::terminate.
  run_on_workers(threads, [&](unsigned) {
    try {
      worker();
    } catch (...) {
      std::lock_guard lock(mutex);
      if (!failure) failure = std::current_exception();
      changed.notify_all();
    }
  });
  if (failure) std::rethrow_exception(failure);
  for (std::size_t i : graph.order) runs.push_back(std::move(by_node[i]));
}

// Every number of a requested output must stay finite in the unit it is shown in: 1e300 m is
// finite in metres but not in nanometres (units: {length: nm}), and a writer would print "inf".
// Refused here, naming the output and the unit, before anything is printed.
void check_displayable(const GraphNode& node, const std::string& label, const Value& value, Dimension dimension,
                       const std::string& display_unit, const DisplayUnits& units) {
  auto check = [&](const std::vector<double>& xs, Dimension d, const std::string& own_unit, const std::string& what) {
    if (xs.empty()) return;
    const std::string unit = units.unit_for(d, own_unit);
    if (unit.empty()) return;
    const std::optional<UnitScale>& parsed = parse_unit_cached(unit);
    if (!parsed) return;  // the writers refuse a unit they cannot read; nothing to check against here
    const UnitScale& u = *parsed;
    double largest = 0.0;
    for (double x : xs) largest = std::max(largest, std::abs(x));
    if (!finite_in_unit(largest, u))
      throw EvaluationError(node.where.str() + where_of(node) + " output '" + label + "'" + what + ": " +
                            format_double(largest) + " " + d.si_unit() + " is beyond the range of a double in " + unit +
                            " (the display unit); show it in a larger unit (the scene's units:) or check the inputs");
  };
  switch (value.kind()) {
    case ValueKind::scalar: check({value.as_scalar()}, dimension, display_unit, ""); break;
    case ValueKind::series:
      check(value.as_series().values, dimension, display_unit, "");
      check(value.as_series().axis, value.as_series().axis_dimension, "", ", its axis");
      break;
    case ValueKind::table: {
      const Table& t = value.as_table();
      check(t.axis.values, t.axis.dimension, t.axis.display_unit, ", axis '" + t.axis.name + "'");
      for (const Table::Column& c : t.channels) check(c.values, c.dimension, c.display_unit, ", channel '" + c.name + "'");
      break;
    }
    case ValueKind::handle: break;
  }
}

}  // namespace

namespace {

// The value of requested output o, once every node has run.
const Value& requested_value(const Graph& graph, const RequestedOutput& o,
                             const std::vector<std::shared_ptr<const OutputSet>>& produced) {
  const auto& outs = produced[o.node]->all();
  auto it = outs.find(o.port);
  if (it == outs.end())
    throw EvaluationError(where_of(graph.nodes[o.node]) + " did not produce the requested output '" + o.label +
                          "': that output needs an effect or parameters this node was not given (see 'mechgraph "
                          "describe " + graph.nodes[o.node].info().type + "')");
  return it->second;
}

}  // namespace

RunResult evaluate(const Graph& graph, MemoCache& cache, unsigned threads) {
  RunResult result;
  const std::vector<std::uint64_t> hashes = node_hashes(graph);
  std::vector<std::shared_ptr<const OutputSet>> produced(graph.nodes.size());
  if (threads <= 1 || graph.order.size() <= 1) {
    for (std::size_t i : graph.order) run_node(graph, i, hashes, produced, cache, &result.runs.emplace_back());
  } else {
    run_parallel(graph, hashes, produced, cache, std::min<unsigned>(threads, static_cast<unsigned>(graph.order.size())),
                 result.runs);
  }
  for (const RequestedOutput& o : graph.outputs) {
    try {
      const Value& value = requested_value(graph, o, produced);
      result.outputs.push_back(
          {o.label, value, o.spec->dimension, graph.display_units.unit_for(o.spec->dimension, o.spec->display_unit)});
      const OutputValue& out = result.outputs.back();
      check_displayable(graph.nodes[o.node], o.label, out.value, out.dimension, out.display_unit, graph.display_units);
    } catch (const NodeEvaluationError&) {
      throw;
    } catch (const EvaluationError& e) {
      throw named(graph.nodes[o.node], e);
    }
  }
  return result;
}

RunValues evaluate_values(const Graph& graph, MemoCache& cache, unsigned threads) {
  RunValues result;
  if (threads > 1 && graph.order.size() > 1) {
    RunResult full = evaluate(graph, cache, threads);
    for (OutputValue& o : full.outputs) result.values.push_back(std::move(o.value));
    for (const NodeRun& r : full.runs) ++(r.reused ? result.reused : result.evaluated);
    return result;
  }
  const std::vector<std::uint64_t> hashes = node_hashes(graph);
  std::vector<std::shared_ptr<const OutputSet>> produced(graph.nodes.size());
  for (std::size_t i : graph.order) ++(run_node(graph, i, hashes, produced, cache, nullptr) ? result.reused : result.evaluated);
  result.values.reserve(graph.outputs.size());
  for (const RequestedOutput& o : graph.outputs) {
    const Value& value = requested_value(graph, o, produced);
    // As evaluate(): every number must stay finite in the unit it is shown in.
    check_displayable(graph.nodes[o.node], o.label, value, o.spec->dimension,
                      graph.display_units.unit_for(o.spec->dimension, o.spec->display_unit), graph.display_units);
    result.values.push_back(value);
  }
  return result;
}

double report_cell_value(const RunResult& result, const ResolvedReport::Row& row, const ResolvedReport::Cell& cell) {
  const OutputValue& o = result.outputs.at(cell.output);
  if (!cell.element) return o.value.as_scalar();
  const auto& values = o.value.as_series().values;
  if (*cell.element >= values.size())
    throw EvaluationError("report row '" + row.label + "': " + o.label + " has " + std::to_string(values.size()) +
                          " elements, the row asks for element " + std::to_string(*cell.element));
  return values[*cell.element];
}

}  // namespace mechgraph
