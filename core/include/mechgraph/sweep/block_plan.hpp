#pragma once
// The block path of a sweep (mechgraph/block.hpp): when every node a sweep needs can evaluate a
// block of cases at once, the cases run in blocks: each varied parameter a column, each node
// called once per block, no per-case graph, memo lookup or output map. A case a node cannot do
// on the block path (an error, a refused value, a non-finite output) is redone alone on the
// per-case path, whose result or message it then carries: rows are the same either way, the
// block path only makes them faster.
#include <mechgraph/graph.hpp>
#include <mechgraph/sweep/case_binder.hpp>
#include <mechgraph/sweep/case_table.hpp>
#include <mechgraph/value.hpp>

#include <cstddef>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace mechgraph {

class DomainBlock;

class BlockPlan {
 public:
  /// The plan for sweeping over `graph` (built from the scene, bound by `binder`, which must
  /// outlive the plan). It is
  /// usable when the binder writes numbers in place (no rebuilt graphs), every varied parameter is
  /// a number, every requested output a scalar, and every needed node offers BlockEvaluation and
  /// says yes to what is read of it; else why_not() says which node or value stands in the way.
  BlockPlan(const Graph& graph, const CaseBinder& binder);

  bool usable() const { return why_not_.empty(); }
  const std::string& why_not() const { return why_not_; }

  /// What one worker keeps between blocks: the outputs of the nodes no case changes, made once.
  struct WorkerState {
    struct Produced {
      std::vector<std::vector<double>> scalars;          // per output port of the node (by `ports`)
      std::vector<std::string> ports;
      std::vector<std::shared_ptr<const DomainBlock>> handles;
      std::vector<std::string> handle_ports;
      bool varied = false;
    };
    std::vector<Produced> nodes;  // per graph node
    bool constants_made = false;
    bool constants_failed = false;
  };

  /// The result of one case of a block: its requested outputs, or nothing when the case must be
  /// redone alone (per-case path).
  struct CaseOutcome {
    std::optional<std::vector<Value>> outputs;
  };

  /// Runs the cases `indices` of `table` as one block on `graph` (a worker's copy, bound by the
  /// binder: its varied parameters are written through their slots).
  std::vector<CaseOutcome> run(Graph& graph, const CaseTable& table, std::span<const std::size_t> indices,
                               WorkerState& state) const;

 private:
  const CaseBinder& binder_;
  std::vector<std::vector<CaseBinder::Target>> targets_;  // per variable
  std::vector<char> varied_;                  // per graph node: a case changes it
  std::string why_not_;
};

}  // namespace mechgraph
