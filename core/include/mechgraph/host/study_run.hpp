#pragma once
// An uncertainty study of a scene, as the command line and the Python module run it: the scene's
// `uncertainty:` block read (ISO 286 limits from the loaded fits plugin), its parameters checked
// against the graph (names, dimensions; errors at the block's file:line:column), its cases made
// (uncertainty/sample_design.hpp) and run by the sweep runner on the worker pool, the values taken
// as the sweep's rows show them, then analysed (uncertainty/study_answers.hpp).
#include <mechgraph/graph.hpp>
#include <mechgraph/host/scene_loading.hpp>
#include <mechgraph/work_estimate.hpp>
#include <mechgraph/sweep/case_binder.hpp>
#include <mechgraph/uncertainty/sample_design.hpp>
#include <mechgraph/uncertainty/study_answers.hpp>

#include <atomic>
#include <functional>
#include <memory>
#include <optional>
#include <set>
#include <string>

namespace mechgraph::host {

/// The node type that answers ISO 286 limits for a study's `iso286:` parameters.
inline constexpr const char* iso286_node_type = "fit.iso286";

/// ISO 286 deviations by the loaded fit.iso286 node type (an empty function when none is loaded).
Iso286Limits iso286_limits(const PluginRegistry& registry);

/// The scene's study; throws SceneError when the scene has no `uncertainty:` block.
StudySpec study_spec_of(const SceneSpec& scene, const PluginRegistry& registry);

/// Checks that every uncertain parameter reaches a number parameter of the graph with the
/// dimension of its distribution. Throws SceneError at the parameter's location.
void check_study_parameters(const StudySpec& spec, const Graph& graph, const SceneSpec& scene, const PluginRegistry& registry,
                            const std::vector<Override>& overrides);

/// The scalar outputs of the graph, in the units a sweep's rows show them.
std::vector<StudyColumn> study_columns(const Graph& graph);

/// With a choice of outputs (--outputs, Python's outputs=): the limits and events on outputs of
/// the scene that the choice leaves out are dropped, each with a note (a name that is no output of
/// the scene stays, for check_study_outputs to refuse).
void leave_out_unstudied(StudySpec& spec, const std::vector<StudyColumn>& columns, const std::set<std::string>& scene_outputs);

/// A value as the sweep's rows show it (si / scale - offset).
inline double shown_value(double si, const StudyColumn& c) { return si / c.scale - c.offset; }

/// Runs every case of `table` (or `cases`, when given) and gathers the values of `columns`.
StudyData evaluate_study(const Graph& graph, const CaseBinder& binder, const CaseTable& table, const std::vector<StudyColumn>& columns,
                         unsigned threads, const std::atomic<bool>* stop, SweepSummary* summary = nullptr);

}  // namespace mechgraph::host

namespace mechgraph::host {

/// --samples, --method and --seed (empty: the scene's) over the scene's settings; throws
/// UsageError for a value out of range, naming the option as `names` do.
void apply_study_options(StudySpec& spec, const std::string& samples, const std::string& method, const std::string& seed,
                         const OptionNames& names = {});

}  // namespace mechgraph::host

namespace mechgraph::host {

/// A study run in process (Python's Scene.study, `mechgraph study`): its settings, the design,
/// the values and the answers.
struct StudyOutcome {
  StudySpec spec;
  std::unique_ptr<SceneSpec> scene;  // the scene studied (the graph's binder refers to it)
  Graph graph;
  std::vector<StudyColumn> columns;
  CaseTable table;
  StudyData data;
  StudyAnswers answers;  // refers to `spec`: keep the outcome whole
  SweepSummary summary;
  std::string json;      // write_study_json
  unsigned threads = 1;  // for the analysis (the bootstrap); the answers do not depend on it
};

/// `block` merged over the scene's `uncertainty:` (a key of `block` replaces the scene's, except
/// `parameters`, which are merged by name); `block` may be absent.
RawValue merged_uncertainty(const SceneSpec& scene, const std::optional<RawValue>& block);

/// Reads the study (`block` over the scene's), builds and checks its graph and makes its design
/// (on `threads` workers, the same table on any number), running nothing: the outcome's spec,
/// scene, graph, columns and table. With a `budget`, what the study holds beside its cases and
/// its bootstrap's work are checked against it first (check_study_budget; `held` gets the bytes).
/// `check_spec`, when given, sees the study's settings complete (samples, method, parameters)
/// before anything is built or drawn, and may refuse them by throwing.
std::unique_ptr<StudyOutcome> prepare_scene_study(SceneSpec scene, const PluginRegistry& registry, const std::vector<Override>& overrides,
                                                  const std::optional<RawValue>& block, const std::string& samples, const std::string& method,
                                                  const std::string& seed, const std::optional<std::string>& outputs,
                                                  unsigned threads = 1, const WorkBudget* budget = nullptr, double* held = nullptr,
                                                  const OptionNames& option_names = {},
                                                  const std::function<void(const StudySpec&)>& check_spec = {});

/// The memory a study holds beside its cases (the design, the outputs' values, the cases' order,
/// the answers' scratch on `threads` threads, the Sobol' rows and bootstrap draws) against
/// budget.max_memory, its bootstrap's work against budget.max_work;
/// throws SceneError "FILE: ..." naming the biggest term and the flag that raises the budget (the
/// design's own cap, check_design_size, first). Returns the bytes held.
double check_study_budget(const StudySpec& spec, std::size_t outputs, const WorkBudget& budget, const std::string& file,
                          unsigned threads = 1);

/// Analyses outcome.data into outcome.answers and outcome.json.
/// `stop` (Ctrl-C, SIGTERM) ends it early; outcome.summary.stopped then says so.
void finish_study(StudyOutcome& outcome, const std::atomic<bool>* stop = nullptr);

/// prepare_scene_study, then runs its cases within `budget` on
/// `threads` and analyses them. summary.stopped: `stop` was set, nothing analysed.
std::unique_ptr<StudyOutcome> run_scene_study(SceneSpec scene, const PluginRegistry& registry, const std::vector<Override>& overrides,
                                              const std::optional<RawValue>& block, const std::string& samples, const std::string& method,
                                              const std::string& seed, const std::optional<std::string>& outputs, const WorkBudget& budget,
                                              unsigned threads, const std::atomic<bool>* stop, const OptionNames& option_names = {});

}  // namespace mechgraph::host
