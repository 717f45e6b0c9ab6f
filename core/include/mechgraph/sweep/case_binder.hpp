#pragma once
// Puts one case's values into a graph that was built once: each sweep variable is resolved to the
// node parameters it reaches (a scene parameter `rpm` to every `$rpm`, `part.length` to that
// one), and each case's value is checked against the parameter's dimension and range before it is
// written. No YAML is read per case. A variable that reaches into a list or a record (a stack
// link's field) cannot be written in place: such sweeps build each case's graph anew from the
// parsed scene, which `rebuilds()` says.
#include <mechgraph/graph.hpp>
#include <mechgraph/sweep/case_table.hpp>

#include <string>
#include <vector>

namespace mechgraph {

/// Who gives the values, for the messages: a sweep ("sweep: 'rmp': unknown ...", a value's origin
/// "(swept rpm)"), a program setting the parameters of one run (the Python module's `set=`:
/// "set rmp: unknown ...", "(set rpm)"), whose messages must not speak of a sweep, or an
/// uncertainty study ("study: 'rmp': unknown ...", "(sampled rpm)"), which says itself, once and
/// at the parameter's line, what a variable that reaches no needed node means
/// (reaches_needed_node).
enum class BinderUse { sweep, set, study };

class CaseBinder {
 public:
  /// Resolves the variables on `base` (built from `scene` with `overrides`); throws SceneError for
  /// an unknown name, with the valid ones. `scene` and `registry` must outlive the binder.
  CaseBinder(const Graph& base, const SceneSpec& scene, const PluginRegistry& registry,
             std::vector<Override> overrides, std::vector<SweepVariable> variables, BinderUse use = BinderUse::sweep);

  /// Writes one case into `graph`, which holds the base graph or an earlier case of it. Throws
  /// SceneError naming the variable, the node parameter and the limit it breaks.
  void apply(Graph& graph, const std::vector<CaseValue>& values) const;

  /// Whether variable v reaches a node the requested outputs need (else giving it changes nothing).
  bool reaches_needed_node(std::size_t v) const { return reaches_needed_[v] != 0; }

  /// Where one graph keeps each varied parameter's value, found once (a sweep's worker binds its
  /// copy of the graph, then writes every case without a lookup by name). Valid while that graph
  /// lives and is not rebuilt. For a binder that rebuilds(), apply() through slots writes the plain
  /// parameters only, not the values inside lists and records: enough for the work estimate
  /// (sweep/case_estimate.hpp), not for a run.
  struct Slots {
    std::vector<std::vector<ParamValue*>> of_variable;  // per variable, per target
  };
  Slots bind(Graph& graph) const;
  /// apply() through slots bound on the graph: the same checks and messages.
  void apply(const Slots& slots, const Graph& graph, const std::vector<CaseValue>& values) const;
  /// Whether apply() writes `value` of variable v, a number, into every real-number parameter it
  /// reaches without refusing it (the block path of sweeps takes such values as columns, and
  /// leaves any other to apply() and its message).
  bool writes_number(std::size_t v, const CaseValue& value) const;

  bool rebuilds() const { return rebuild_; }
  /// Marks the nodes a case changes (the targets of the varied parameters and everything
  /// downstream of them) as not memoised: in a sweep their results never repeat, so storing and
  /// looking them up in the memo cache is work for nothing. Call after apply() when rebuilds().
  void mark_unmemoised(Graph& graph) const;
  const std::vector<SweepVariable>& variables() const { return variables_; }

  /// A node parameter a variable reaches.
  struct Target {
    std::size_t node;
    const ParamSpec* spec;
  };
  /// Per variable, the node parameters it is written to (in the order apply() writes them).
  const std::vector<std::vector<Target>>& targets() const { return targets_; }
  /// The order apply() writes the variables in (scene parameters, then node parameters: where both
  /// reach one node parameter, the node's own wins); a block path follows it.
  const std::vector<std::size_t>& apply_order() const { return apply_order_; }

 private:
  const SceneSpec& scene_;
  const PluginRegistry& registry_;
  std::vector<Override> overrides_;
  std::vector<SweepVariable> variables_;
  std::vector<std::vector<Target>> targets_;  // per variable
  std::vector<std::string> swept_labels_;     // per variable: where its values come from, "(swept x)"
  BinderUse use_ = BinderUse::sweep;
  std::vector<char> reaches_needed_;  // per variable
  std::vector<std::size_t> apply_order_;  // the variables' indices: scene parameters, then node parameters
  bool rebuild_ = false;
};

/// A `--vary` list's bare numbers in the list's unit: `rpm=5000,6000rpm` is two speeds, as a
/// range's bare end takes the other end's unit (3000:7000rpm). Only where the variable has a unit
/// with a dimension (the first number written with one) and every parameter it reaches is a number
/// of that dimension: a bare number there would be refused. Anywhere else nothing changes
/// (`gain=-1,1mm` on a dimensionless gain keeps -1, and the 1mm is refused in its case).
/// It reads values as written (`table.cases`): a table of numbers (CaseTable::Numbers, a sample or
/// a study's design) has no bare number to read and is left as it is.
void read_bare_numbers_in_list_unit(CaseTable& table, const CaseBinder& binder);

}  // namespace mechgraph
