#pragma once
// An uncertainty study of a scene, as the command line and the Python module run it: the scene's
// `uncertainty:` block read (ISO 286 limits from the loaded fits plugin), its parameters checked
// against the graph (names, dimensions; errors at the block's file:line:column), its cases made
// (uncertainty/sample_design.hpp) and run by the sweep runner on the worker pool, the values taken
// as the sweep's rows show them, then analysed (uncertainty/study_answers.hpp).
#include <mechgraph/graph.hpp>
#include <mechgraph/sweep/case_binder.hpp>
#include <mechgraph/uncertainty/sample_design.hpp>
#include <mechgraph/uncertainty/study_answers.hpp>

#include <atomic>
#include <optional>

namespace mechgraph::cli {

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

/// A value as the sweep's rows show it (si / scale - offset).
inline double shown_value(double si, const StudyColumn& c) { return si / c.scale - c.offset; }

/// Runs every case of `table` (or `cases`, when given) and gathers the values of `columns`.
StudyData evaluate_study(const Graph& graph, const CaseBinder& binder, const CaseTable& table, const std::vector<StudyColumn>& columns,
                         unsigned threads, const std::atomic<bool>* stop, SweepSummary* summary = nullptr);

}  // namespace mechgraph::cli

namespace mechgraph::cli {

/// --samples, --method and --seed (empty: the scene's) over the scene's settings; throws
/// UsageError for a value out of range, naming the option.
void apply_study_options(StudySpec& spec, const std::string& samples, const std::string& method, const std::string& seed);

}  // namespace mechgraph::cli
