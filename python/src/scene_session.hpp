#pragma once
// One scene held by Python: parsed once, its graph built once per choice of outputs and varied
// names, and a memo cache kept across runs, so a second run that changes one parameter writes that
// value into the built graph (CaseBinder, as a sweep does) and evaluates only the nodes downstream
// of it. Nothing in here knows Python: module.cpp converts.
//
// Thread-safety: a session serialises its runs (a run writes into its built graph); sweeps work on
// their own copies and may run beside runs.
#include <mechgraph/host/sweep_rows.hpp>

#include <mechgraph/evaluator.hpp>
#include <mechgraph/graph.hpp>
#include <mechgraph/sweep/case_binder.hpp>
#include <mechgraph/sweep/sweep_runner.hpp>

#include <mechgraph/host/study_run.hpp>

#include <atomic>
#include <map>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

namespace mechgraph::python {

/// One `set=` entry: text with its unit ("6500 rpm", a word; a number given with its unit becomes
/// such text), a number, or a list of numbers for a list parameter. A number or list without a unit
/// is refused for a parameter with a dimension unless marked SI (unit_rule.hpp).
struct SetValue {
  std::string name;
  std::variant<std::string, double, std::vector<double>> value;
  std::string unit;  // a list's numbers are in this unit ("deg"); "": SI when `si`, else bare
  bool si = false;   // marked as SI (mechgraph.si, si=True)
};

struct SessionRun {
  RunResult result;
  std::vector<std::string> overrides;  // "name=value" as --set would write each value; an array "name=<N values, SI>"
  std::shared_ptr<const std::vector<SetValue>> sets;  // what the run was given: its provenance is made from these
  std::size_t scene_output_count = 0;  // the first outputs of result are the ones asked for
  double seconds = 0.0;                // wall time of the evaluation
};

/// An input column of a sweep's rows: a number a row, or (where any row holds text or nothing) the
/// cells as SweepRows::input_value gives them.
struct SessionInputColumn {
  std::vector<double> numbers;                                           // empty when `cells` holds the column
  std::vector<std::variant<std::monostate, double, std::string>> cells;  // none, a number, or text as written
};

/// The rows of a sweep as `mechgraph sweep --format jsonl` writes them, with the header, as values
/// kept by column (no allocation a row: a million rows are a few arrays).
struct SessionSweep {
  std::vector<std::string> header;
  std::size_t inputs = 0;                            // varied-input columns after `case`
  std::vector<std::size_t> cases;                    // each row's case number, in case order
  std::vector<SessionInputColumn> input_columns;     // one per input
  std::vector<double> outputs;                       // row by row, a value per output column (NaN: the case failed)
  std::vector<int> exits;                            // each row's exit code
  std::vector<std::pair<std::size_t, std::string>> errors;  // (row, message) of each failed row, in row order
  SweepSummary summary;
  std::size_t failed = 0;
};

/// The budget of a call from Python: `max_work` and `max_memory` as given (0: the default of the
/// command that does the same, `sweep` true for a sweep's or a study's work over all its cases),
/// its refusals naming the keywords (max_work=...) instead of the command's flags.
WorkBudget python_budget(double max_work, double max_memory, bool sweep);

class SceneSession {
 public:
  SceneSession(std::shared_ptr<const PluginRegistry> registry, SceneSpec scene);

  /// Builds the scene as written and checks it and its work estimate within `budget`, evaluating
  /// nothing.
  void validate(const WorkBudget& budget);

  /// Evaluates `outputs` (empty: the scene's outputs and report) with `sets` applied, once its work
  /// estimate with those values is within `budget` (as `mechgraph run --set` checks it); the memo
  /// cache is kept. Throws SceneError or EvaluationError.
  SessionRun run(std::shared_ptr<const std::vector<SetValue>> sets, const std::vector<std::string>& outputs, unsigned threads,
                 const WorkBudget& budget);

  /// Runs one case per row of `table` on `threads` workers (0: one per core) with the rows of
  /// `mechgraph sweep`; `stop` set: no new case starts. `sets` are fixed for every case (text or
  /// a number in SI; each goes to the scene as the text it is, never read as YAML).
  /// `done` (if given) counts the cases finished, for a progress bar.
  SessionSweep sweep(const CaseTable& table, const std::vector<SetValue>& sets,
                     const std::vector<std::string>& outputs, unsigned threads, const std::atomic<bool>* stop,
                     const WorkBudget& budget, std::atomic<std::size_t>* done = nullptr);

  /// What sweep() checks before its first case, nothing run: the work of every row of `table`
  /// within `budget`, what `threads` cases hold at once within its memory (check_sweep_budget).
  /// For a sweep whose rows run elsewhere in chunks (mechgraph.dask.sweep): the whole is checked
  /// here, not only each chunk there. Throws SceneError naming the case.
  void check_sweep(const CaseTable& table, const std::vector<SetValue>& sets, const std::vector<std::string>& outputs,
                   unsigned threads, const WorkBudget& budget);

  /// An uncertainty study of the scene (study_run.hpp): `block` merged over its `uncertainty:`,
  /// `sets` fixed for every case (as sweep() takes them); empty samples/method/seed: the block's.
  std::unique_ptr<host::StudyOutcome> study(const std::vector<SetValue>& sets, const std::optional<RawValue>& block,
                                           const std::string& samples, const std::string& method, const std::string& seed,
                                           const std::vector<std::string>& outputs, unsigned threads, const std::atomic<bool>* stop,
                                           const WorkBudget& budget);

  /// The same study prepared (graph and design), nothing run: for a study whose cases run elsewhere
  /// (mechgraph.dask.study), analysed with host::finish_study once their values are in.
  /// `check_spec`: as host::prepare_scene_study takes it (the settings, before anything is drawn).
  std::unique_ptr<host::StudyOutcome> prepare_study(const std::vector<SetValue>& sets, const std::optional<RawValue>& block,
                                                   const std::string& samples, const std::string& method, const std::string& seed,
                                                   const std::vector<std::string>& outputs, const WorkBudget& budget,
                                                   const std::function<void(const StudySpec&)>& check_spec = {});

  /// The graph a run evaluated, its parameters as the run used them (for the provenance): a copy
  /// of the graph prepared for the run's outputs and names, given the run's `sets` the way run()
  /// gives them (values bound in place, arrays written into their list parameters), so nothing is
  /// read as YAML and nothing of the scene's own rows stays where an array replaced them.
  Graph graph_for(const std::vector<SetValue>& sets, const std::vector<std::string>& outputs);

  const SceneSpec& scene() const { return scene_; }
  const PluginRegistry& registry() const { return *registry_; }
  /// The dimension a `set=` name reaches (see case_values.hpp), from the scene's own graph.
  std::optional<Dimension> dimension_of(const std::string& name);
  /// The unit the scene writes `name` in (unit_rule.hpp), for messages.
  std::string scene_unit_of(std::string_view name, Dimension d) const;
  /// Refuses a bare number (no unit, not marked SI) for a `name` with a dimension.
  void require_unit_or_si(const std::string& context, const std::string& name, double given);

  /// Memo cache counters: hits, misses, entries dropped.
  std::size_t cache_hits() const { return cache_->hits(); }
  std::size_t cache_misses() const { return cache_->misses(); }
  void clear_cache();

 private:
  struct Prepared {
    std::unique_ptr<SceneSpec> scene;  // the binder keeps a reference: a stable address
    Graph graph;                        // written case after case
    std::unique_ptr<CaseBinder> binder;
  };
  // What a run's `set=` entries become: the binder's names and values, the arrays for list
  // parameters, and the override texts.
  struct BoundSets {
    std::vector<std::string> names, list_names, overrides;
    std::vector<CaseValue> values;
    std::vector<const SetValue*> lists;
  };
  BoundSets bound_sets(const std::vector<SetValue>& sets);
  // A sweep's or a study's fixed `sets` as overrides (each value one quoted YAML scalar).
  std::vector<Override> fixed_overrides(const std::vector<SetValue>& sets);
  Prepared prepare(const std::vector<std::string>& outputs, const std::vector<std::string>& names) const;
  // A sweep's graph (the fixed `sets` applied, `outputs` or the scene's) and the binder of the
  // table's variables, handed to `use`: sweep() runs them, check_sweep() estimates them.
  void with_sweep_graph(const CaseTable& table, const std::vector<SetValue>& sets, const std::vector<std::string>& outputs,
                        const std::function<void(const Graph&, const CaseBinder&)>& use);
  void give(const CaseBinder& binder, Graph& graph, const BoundSets& sets) const;
  Prepared& prepared(const std::vector<std::string>& outputs, const std::vector<std::string>& names,
                     const std::vector<std::string>& list_names);
  SceneSpec with_outputs(const std::vector<std::string>& outputs) const;

  std::shared_ptr<const PluginRegistry> registry_;
  SceneSpec scene_;
  std::mutex mutex_;  // runs one at a time: they write into prepared graphs
  std::map<std::string, Prepared> prepared_;
  std::mutex plain_mutex_;      // dimension_of is called from runs and from sweeps' case tables
  std::optional<Graph> plain_;  // the scene as written (dimension_of)
  std::unique_ptr<MemoCache> cache_ = std::make_unique<MemoCache>();
};

}  // namespace mechgraph::python
