#pragma once
// What a scene asks of the machine, estimated from its parameters before anything runs, and the
// budget it must keep: a scene from a stranger cannot start an hour of work, take gigabytes of
// memory or write a gigabyte of files unless the user says so (--max-work, --max-memory,
// --max-output).
//
// Each needed node, in dependency order, is estimated by its type's NodeType::forecast when the
// type gives one (its work items, peak memory and the size of what it outputs, from its parameters
// and the sizes of its inputs: a law read from a table file has a piece per row of it, and every search
// downstream resolves them all). A type that gives none is counted by the conventions of the SDK
// (docs/writing-plugins.md, "Counts of work"): an integer parameter whose name ends in `points`,
// `samples` or `bins` counts work items of its node, `revolutions` multiplies them, every record of
// a record list and every number of a number list counts as work items, and every piece of an
// input beyond the first costs inputs_items_per_piece items (a certified search resolves it); its
// memory is memory_per_item bytes a work item (a count of points: memory_per_row a point, at least)
// and its output is as large as its largest input. A
// node's curves are written with a row per point. The estimate is an upper bound of the order of
// magnitude, not a prediction of seconds: its use is to refuse what is absurd, naming the term that
// makes it so. tests/core/work_estimate_calibration_test.cpp holds every built-in node type to
// measured cost within a stated factor.
#include <mechgraph/graph.hpp>

#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace mechgraph {
namespace detail {
class BoundForecast;  // core/src/c_node_type.hpp
}

struct WorkEstimate {
  struct Term {
    std::string what;    // "k.curve_points = 1000000"
    double work = 0;     // work items it brings to one evaluation of the scene
    double bytes = 0;    // bytes of result files it brings when curves are written
    double memory = 0;   // bytes it holds at its peak
  };
  double work = 0;       // work items of one evaluation of every needed node
  double bytes = 0;      // bytes of the requested curves as CSV (or JSON)
  double memory = 0;     // bytes held by one evaluation: every needed node's peak, added up
  std::vector<Term> terms;
};

/// A sweep's default work budget, for all its cases together.
inline constexpr double sweep_default_max_work = 1e12;
/// Conventions for a node type without a forecast (see above).
inline constexpr double inputs_items_per_piece = 200.0;
inline constexpr double memory_per_item = 16.0;
inline constexpr double memory_per_row = 128.0;  // a curve's row: up to 16 channels of 8 bytes
inline constexpr double memory_per_input_piece = 4096.0;

/// How the user raises each limit, as a refusal names it before the amount: the command line's
/// flags, or Python's keywords (python_budget_names).
struct BudgetNames {
  const char* work = "--max-work ";
  const char* memory = "--max-memory ";
  const char* output = "--max-output ";
};
inline constexpr BudgetNames python_budget_names{"max_work=", "max_memory=", "max_output="};

struct WorkBudget {
  double max_work = 1e9;                        // work items of one evaluation (a sweep: sweep_default_max_work, all cases)
  double max_bytes = 256.0 * (1 << 20);         // bytes of result files or of curves on standard output
  double max_memory = 4.0 * (1 << 30);          // bytes held by one evaluation (a sweep: by its threads together)
  BudgetNames names;                            // in the refusals: how to raise each limit
  double memory_beside = 0.0;                   // bytes the caller holds beside what is checked (a study's own
                                                // storage), already taken off max_memory: a refusal counts them back
  const char* beside_holder = "the study";      // who holds them, as a refusal names it
};

/// One node's estimate: its terms (work, memory, bytes) and the size of what it outputs.
struct NodeEstimate {
  double work = 0, bytes = 0, memory = 0;
  double output_size = 1;
  std::vector<WorkEstimate::Term> terms;  // filled only when asked for (messages); the totals always
};

/// Node `index` of `graph`; `output_sizes[i]` is what node i outputs (1 where not estimated yet).
/// `writes` says whether its series or table outputs are written (requested).
NodeEstimate estimate_node(const Graph& graph, std::size_t index, const std::vector<double>& output_sizes, bool writes,
                           bool with_terms);

/// estimate_node for one node case after case (the cases of a sweep): the same figures, with what
/// no case changes kept between calls. The map of input sizes is refreshed in place; a type without
/// a forecast is counted by the conventions again only when its inputs' sizes change or some case
/// changes an integer parameter of it (`integers_vary`): the conventions read integer parameters,
/// list lengths and input sizes, never a real number (tests/core/work_estimate_test.cpp).
/// The contract: it is given the graph it was made with each time, whose parameters change only in
/// place (CaseBinder::apply with the graph's slots), never by assigning or rebuilding the graph or
/// a node's ParamSet: an SDK 1.x type's forecast is bound to the entries of the node's ParamSet
/// once (detail::bind_forecast), and pointers into a set that was assigned or rebuilt would read
/// other or freed entries, which the check it does (the set's address and entry count) cannot
/// always see. A graph built anew needs estimators made anew. Move-only: each worker its own.
class RepeatedNodeEstimate {
 public:
  /// `forecast_fixed`: the node's forecast reads none of the parameters the cases change
  /// (forecast_reads_none_of): it is asked again only when its inputs' sizes change.
  RepeatedNodeEstimate(const Graph& graph, std::size_t index, bool writes, bool integers_vary, bool forecast_fixed = false);
  RepeatedNodeEstimate(RepeatedNodeEstimate&&) = default;
  RepeatedNodeEstimate& operator=(RepeatedNodeEstimate&&) = default;
  RepeatedNodeEstimate(const RepeatedNodeEstimate&) = delete;
  RepeatedNodeEstimate& operator=(const RepeatedNodeEstimate&) = delete;
  NodeEstimate operator()(const Graph& graph, const std::vector<double>& output_sizes);

 private:
  std::size_t index_;
  bool writes_, integers_vary_;
  InputSizes sizes_;                // what a forecast reads: the sizes in_map_ holds
  std::vector<double> now_, in_map_;  // this case's input sizes in port order; those sizes_ holds
  double rows_ = 0;
  std::optional<NodeEstimate> conventions_;
  std::vector<double> conventions_sizes_;
  double conventions_rows_ = 0;
  std::shared_ptr<detail::BoundForecast> bound_;            // null for a type other than an SDK 1.x one with a forecast
  const ParamSet* bound_params_ = nullptr;              // the set it is bound to
  std::size_t bound_entries_ = 0;                       // its entries then
  bool forecast_fixed_ = false;                         // its forecast reads no varied parameter
  std::optional<NodeEstimate> forecast_;                // the last one, while forecast_fixed_
  std::vector<double> forecast_sizes_;                  // the sizes it was made for (as now_)
};
/// Whether `type`'s forecast says which parameters it reads (ForecastReads, SDK 1.3) and none of
/// them is in `varied`: then the cases that change only `varied` all have the same forecast.
bool forecast_reads_none_of(const NodeType& type, const std::vector<std::string>& varied);

/// Whether each node has a requested series or table output (whose rows are written).
std::vector<char> writing_nodes(const Graph& graph);

WorkEstimate estimate_work(const Graph& graph);

/// Throws SceneError when `cases` evaluations of the scene exceed the budget's work, the files
/// written (when `writes_curves`) exceed its bytes, or `concurrent` evaluations at once exceed its
/// memory: the message gives the estimate, the budget, the biggest term and the option that raises
/// the budget. `where`, when given, says which case the estimate is of ("case 17 of cases.csv").
void check_work_budget(const Graph& graph, const WorkEstimate& estimate, const WorkBudget& budget, double cases,
                       bool writes_curves, double concurrent = 1, const std::string& where = {});

/// An amount as the budget messages write it: whole below 10^6, else three significant digits.
std::string budget_amount(double v);

}  // namespace mechgraph
