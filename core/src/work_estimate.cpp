#include <mechgraph/work_estimate.hpp>

#include "c_node_type.hpp"

#include <mechgraph/errors.hpp>
#include <mechgraph/printf_number.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <set>

namespace mechgraph {
namespace {

bool ends_with(std::string_view s, std::string_view tail) {
  return s.size() >= tail.size() && s.substr(s.size() - tail.size()) == tail;
}

// A CSV row of a curve: about ten channels of about 18 characters each.
constexpr double bytes_per_row = 180.0;
// A node whose curves have no points parameter writes a few hundred rows.
constexpr double default_rows = 361.0;

std::string amount(double v) { return v < 1e6 ? printf_f(v, 0) : printf_g(v, 3); }

// Below a mebibyte in bytes ("4096 bytes", not "0 MiB": a budget of a few kilobytes is one).
std::string mebibytes(double bytes) { return bytes < (1 << 20) ? amount(bytes) + " bytes" : amount(bytes / (1 << 20)) + " MiB"; }

// A plugin's figure, made safe to add up: negative or NaN is no bound at all (infinite), so the
// budget refuses it naming the node rather than admitting it.
double figure(double v) { return std::isnan(v) || v < 0 ? std::numeric_limits<double>::infinity() : v; }

// The conventions for a type without a forecast: counts named points, samples, bins, times
// revolutions; list lengths.
void count_by_conventions(const GraphNode& n, NodeEstimate& e, double& rows, bool with_terms) {
  double revolutions = 1;
  struct Count {
    std::string what;
    double work;
    double row_memory = 0;  // a count of points: the rows of a curve it keeps (not times revolutions)
  };
  std::vector<Count> counts;
  // Parameters of an effect that is off are not read: they cost nothing.
  std::set<std::string> idle;
  for (const EffectSpec& effect : n.info().effects)
    if (std::find(n.effects_read.begin(), n.effects_read.end(), effect.name) == n.effects_read.end())
      idle.insert(effect.params.begin(), effect.params.end());
  for (const auto& [name, value] : n.params.all()) {
    if (idle.count(name)) continue;
    const auto what = [&, name = std::string_view(name)] { return with_terms ? n.name + "." + std::string(name) : std::string(); };
    if (value.kind == ParamKind::integer) {
      if (name == "revolutions") revolutions = std::max(1.0, value.number);
      if (ends_with(name, "points") || ends_with(name, "samples") || ends_with(name, "bins")) {
        counts.push_back({with_terms ? what() + " = " + amount(value.number) : std::string(), value.number,
                          ends_with(name, "points") ? value.number * memory_per_row : 0.0});
        if (ends_with(name, "points")) rows = std::max(rows, value.number);
      }
    } else if (value.kind == ParamKind::record_list && !value.records.empty()) {
      const double k = static_cast<double>(value.records.size());
      counts.push_back({with_terms ? what() + " (" + amount(k) + " records)" : std::string(), k});
    } else if (value.kind == ParamKind::number_list && !value.numbers.empty()) {
      const double k = static_cast<double>(value.numbers.size());
      counts.push_back({with_terms ? what() + " (" + amount(k) + " numbers)" : std::string(), k});
    }
  }
  for (Count& c : counts) {
    const double work = c.work * revolutions, memory = std::max(work * memory_per_item, c.row_memory);
    e.work += work;
    e.memory += memory;
    if (with_terms)
      e.terms.push_back({revolutions > 1 ? c.what + " x " + amount(revolutions) + " revolutions" : c.what, work, 0, memory});
  }
}

}  // namespace

std::vector<char> writing_nodes(const Graph& graph) {
  std::vector<char> writing(graph.nodes.size(), 0);
  for (const RequestedOutput& o : graph.outputs)
    if (o.spec && (o.spec->kind == ValueKind::series || o.spec->kind == ValueKind::table) && o.node < writing.size())
      writing[o.node] = 1;
  return writing;
}

namespace {

// The size of each connected input (the largest of its sources' outputs, at least 1), in port
// order into `sizes` (emptied first); returns the largest.
double connected_input_sizes(const GraphNode& n, const std::vector<double>& output_sizes, std::vector<double>& sizes) {
  sizes.clear();
  double largest_input = 1;
  for (const GraphNode::Input& in : n.inputs) {
    if (in.sources.empty()) continue;
    double size = 0;
    for (const GraphNode::Source& s : in.sources) size = std::max(size, s.node < output_sizes.size() ? output_sizes[s.node] : 1.0);
    size = std::max(figure(size), 1.0);
    sizes.push_back(size);
    largest_input = std::max(largest_input, size);
  }
  return largest_input;
}

// `sizes` (connected_input_sizes' order) as the map a forecast reads: one entry per connected port.
void write_input_sizes(const GraphNode& n, const std::vector<double>& sizes, InputSizes& map) {
  std::size_t k = 0;
  for (const GraphNode::Input& in : n.inputs)
    if (!in.sources.empty()) map[in.port] = sizes[k++];
}

// Both: the map of each connected input's size; returns the largest.
double input_sizes(const GraphNode& n, const std::vector<double>& output_sizes, InputSizes& sizes) {
  std::vector<double> in_order;
  const double largest_input = connected_input_sizes(n, output_sizes, in_order);
  write_input_sizes(n, in_order, sizes);
  return largest_input;
}

std::optional<WorkForecast> forecast_of(const GraphNode& n, const InputSizes& sizes) {
  try {
    return n.type->type->forecast(n.params, sizes);
  } catch (...) {
    // The contract says never; a plugin that throws anyway is counted by the conventions.
    return std::nullopt;
  }
}

std::optional<WorkForecast> bound_forecast_of(detail::BoundForecast& forecast, const InputSizes& sizes) {
  try {
    return forecast(sizes);
  } catch (...) {
    return std::nullopt;  // as forecast_of
  }
}

// The rows its curves are written with when the type gives a forecast: the points convention.
double forecast_rows(const GraphNode& n) {
  double rows = 0;
  for (const auto& [name, value] : n.params.all())
    if (value.kind == ParamKind::integer && ends_with(name, "points")) rows = std::max(rows, value.number);
  return rows;
}

void take_forecast(const GraphNode& n, const WorkForecast& forecast, NodeEstimate& e, bool with_terms) {
  e.work = figure(forecast.items);
  e.memory = figure(forecast.memory);
  e.output_size = std::max(figure(forecast.output_size), 1.0);
  if (with_terms)
    e.terms.push_back({n.name + (forecast.driver.empty() ? std::string() : "." + forecast.driver) + " (" + n.info().type + ")",
                       e.work, 0, e.memory});
}

// A type without a forecast: the conventions, then every input's pieces beyond the first, which
// the node's searches resolve. Returns the rows of its curves.
double take_conventions(const GraphNode& n, const InputSizes& sizes, double largest_input, NodeEstimate& e, bool with_terms) {
  double rows = 0;
  count_by_conventions(n, e, rows, with_terms);
  e.output_size = largest_input;
  for (const auto& [port, size] : sizes) {
    if (!(size > 1)) continue;
    const double work = size * inputs_items_per_piece, memory = size * memory_per_input_piece;
    e.work += work;
    e.memory += memory;
    if (with_terms) e.terms.push_back({n.name + "." + port + " (an input of " + amount(size) + " pieces)", work, 0, memory});
  }
  return rows;
}

void take_rows(const GraphNode& n, double rows, NodeEstimate& e, bool with_terms) {
  const double r = rows > 0 ? rows : default_rows;
  e.bytes = r * bytes_per_row;
  if (with_terms) e.terms.push_back({n.name + "'s curves (" + amount(r) + " rows)", 0, e.bytes, 0});
}

}  // namespace

NodeEstimate estimate_node(const Graph& graph, std::size_t index, const std::vector<double>& output_sizes, bool writes,
                           bool with_terms) {
  const GraphNode& n = graph.nodes[index];
  NodeEstimate e;
  InputSizes sizes;
  const double largest_input = input_sizes(n, output_sizes, sizes);
  double rows = 0;
  if (const std::optional<WorkForecast> forecast = forecast_of(n, sizes)) {
    take_forecast(n, *forecast, e, with_terms);
    rows = forecast_rows(n);
  } else {
    rows = take_conventions(n, sizes, largest_input, e, with_terms);
  }
  if (writes) take_rows(n, rows, e, with_terms);
  return e;
}

bool forecast_reads_none_of(const NodeType& type, const std::vector<std::string>& varied) {
  const std::optional<std::vector<std::string>> reads = detail::forecast_reads(type);
  return reads && std::none_of(varied.begin(), varied.end(), [&](const std::string& name) {
           return std::find(reads->begin(), reads->end(), name) != reads->end();
         });
}

RepeatedNodeEstimate::RepeatedNodeEstimate(const Graph& graph, std::size_t index, bool writes, bool integers_vary,
                                           bool forecast_fixed)
    : index_(index), writes_(writes), integers_vary_(integers_vary), forecast_fixed_(forecast_fixed) {
  const GraphNode& n = graph.nodes[index];
  input_sizes(n, std::vector<double>(graph.nodes.size(), 1.0), sizes_);  // the keys, once
  if (!integers_vary_) rows_ = forecast_rows(n);
  bound_ = detail::bind_forecast(*n.type->type, n.params);
  bound_params_ = &n.params;
  bound_entries_ = n.params.all().size();
}

NodeEstimate RepeatedNodeEstimate::operator()(const Graph& graph, const std::vector<double>& output_sizes) {
  const GraphNode& n = graph.nodes[index_];
  // The sizes of the connected inputs as input_sizes() makes them, in port order: compared with the
  // ones the cached figures were made for, and written into the map a forecast reads only when they
  // differ from what it holds (a sweep's cases mostly change no size).
  const double largest_input = connected_input_sizes(n, output_sizes, now_);
  if (now_ != in_map_) {
    write_input_sizes(n, now_, sizes_);
    in_map_ = now_;
  }
  NodeEstimate e;
  double rows = 0;
  // The bound forecast while this is the set it was bound to, with the entries it had (a set is
  // written in place, and has no way to remove an entry).
  const bool bound = bound_ && &n.params == bound_params_ && n.params.all().size() == bound_entries_;
  if (forecast_fixed_ && forecast_ && forecast_sizes_ == now_) {
    // It reads none of the parameters the cases change, and its inputs are as large as before.
    e = *forecast_;
    rows = integers_vary_ ? forecast_rows(n) : rows_;
  } else if (const std::optional<WorkForecast> forecast = bound ? bound_forecast_of(*bound_, sizes_) : forecast_of(n, sizes_)) {
    take_forecast(n, *forecast, e, false);
    rows = integers_vary_ ? forecast_rows(n) : rows_;
    if (forecast_fixed_) {
      forecast_ = e;
      forecast_sizes_ = now_;
    }
  } else if (!integers_vary_ && conventions_ && conventions_sizes_ == now_) {
    // The conventions read integer parameters, list lengths and input sizes only: none changed.
    e = *conventions_;
    rows = conventions_rows_;
  } else {
    rows = take_conventions(n, sizes_, largest_input, e, false);
    conventions_ = e;
    conventions_sizes_ = now_;
    conventions_rows_ = rows;
  }
  if (writes_) take_rows(n, rows, e, false);
  return e;
}

WorkEstimate estimate_work(const Graph& graph) {
  WorkEstimate e;
  const std::vector<char> writing = writing_nodes(graph);
  std::vector<double> sizes(graph.nodes.size(), 1.0);
  for (std::size_t index : graph.order) {
    NodeEstimate n = estimate_node(graph, index, sizes, writing[index] != 0, true);
    sizes[index] = n.output_size;
    e.work += n.work;
    e.bytes += n.bytes;
    e.memory += n.memory;
    for (WorkEstimate::Term& t : n.terms) e.terms.push_back(std::move(t));
  }
  return e;
}

std::string budget_amount(double v) { return amount(v); }

void check_work_budget(const Graph& graph, const WorkEstimate& e, const WorkBudget& budget, double cases,
                       bool writes_curves, double concurrent, const std::string& where) {
  const auto biggest = [&](auto key) {
    const auto it = std::max_element(e.terms.begin(), e.terms.end(), [&](const auto& a, const auto& b) { return key(a) < key(b); });
    return it == e.terms.end() ? std::string("-") : it->what;
  };
  const std::string per_case = !where.empty() ? " " + where : cases > 1 ? " over " + amount(cases) + " cases" : std::string();
  const double work = e.work * cases;
  if (!(work <= budget.max_work))
    throw SceneError(graph.file + ": the scene asks for about " + amount(work) + " work items" + per_case +
                     ", more than the budget of " + amount(budget.max_work) + "; the biggest term is " +
                     biggest([](const WorkEstimate::Term& t) { return t.work; }) +
                     ". Lower it, or raise the budget with " + budget.names.work + amount(std::max(work * 1.01, 1.0)));
  const double memory = e.memory * std::max(concurrent, 1.0);
  if (!(memory <= budget.max_memory)) {
    // What the caller holds beside (a study's own storage) is in the budget the user gave and in
    // the value that lets this through.
    const double beside = budget.memory_beside, whole = memory + beside;
    // The larger part named: the cases' biggest term, or what is held beside them (a sweep's
    // table of millions of cases of a few bytes each).
    const std::string biggest_part = beside > memory ? std::string("what ") + budget.beside_holder + " holds beside them"
                                                     : biggest([](const WorkEstimate::Term& t) { return t.memory; });
    throw SceneError(graph.file + ": the scene would hold about " + mebibytes(memory) + " of memory" +
                     (concurrent > 1 ? " (" + amount(concurrent) + " cases at once)" : std::string()) +
                     (beside > 0 ? ", " + mebibytes(whole) + " with the " + mebibytes(beside) + " " + budget.beside_holder + " holds beside them"
                                 : std::string()) +
                     ", more than the budget of " + mebibytes(budget.max_memory + beside) + "; the biggest term is " +
                     biggest_part +
                     ". Lower it, or raise the budget with " + budget.names.memory + amount(std::max(whole * 1.01, 1.0)));
  }
  if (writes_curves && !(e.bytes <= budget.max_bytes))
    throw SceneError(graph.file + ": the scene would write about " + amount(e.bytes / (1 << 20)) +
                     " MiB of curves, more than the budget of " + amount(budget.max_bytes / (1 << 20)) +
                     " MiB; the biggest term is " + biggest([](const WorkEstimate::Term& t) { return t.bytes; }) +
                     ". Lower it, or raise the budget with " + budget.names.output + amount(std::max(e.bytes * 1.01, 1.0)));
}

}  // namespace mechgraph
