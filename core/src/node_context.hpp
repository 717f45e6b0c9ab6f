#pragma once
// What a node sees while it evaluates, inside the host: the effects it reads, a logger that names
// it, what is read of it, and its work counters. With a NodeRun the counters are recorded (a run);
// without one (a sweep's lean run, a block of cases) they are only checked to be finite, the first
// non-finite one kept for the refusal. The evaluator and the block path of sweeps share it.
#include <mechgraph/evaluator.hpp>
#include <mechgraph/graph.hpp>
#include <mechgraph/node.hpp>

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>

namespace mechgraph {

class NodeContext final : public EvalContext {
 public:
  // `run` null: a sweep's lean run, which keeps no counters but still refuses a non-finite one.
  NodeContext(const GraphNode& node, NodeRun* run) : node_(node), run_(run) {}
  bool effect(std::string_view name) const override {
    for (const std::string& e : node_.effects_read)
      if (e == name) return true;
    return false;
  }
  void log(LogLevel level, std::string_view message) override {
    switch (level) {
      case LogLevel::debug: spdlog::debug("[{}] {}", node_.name, message); break;
      case LogLevel::info: spdlog::info("[{}] {}", node_.name, message); break;
      case LogLevel::warn: spdlog::warn("[{}] {}", node_.name, message); break;
    }
  }
  // A counter the type does not declare is refused, as through the C boundary (a defect of the
  // plugin the conformance kit names).
  void report_work(std::string_view counter, double amount) override {
    const std::vector<std::string>& declared = node_.info().work_counters;
    if (std::find(declared.begin(), declared.end(), counter) == declared.end())
      throw std::logic_error("report_work on undeclared counter '" + std::string(counter) + "'");
    if (run_) {
      run_->work[std::string(counter)] += amount;
    } else if (!std::isfinite(amount) && !bad_counter_) {
      bad_counter_ = std::pair<std::string, double>(counter, amount);
    }
  }
  // Asked over a hundred times a case by the stage 1-3 nodes: one search of the few outputs read.
  // (An output the type does not declare is not wanted here, and wanted through the C boundary,
  // where the node then sets it and is refused for it: plugin-test, which runs through C, names
  // such a defect.)
  bool wanted(std::string_view output) const override {
    return std::binary_search(node_.wanted.begin(), node_.wanted.end(), output, std::less<>());
  }
  const std::optional<std::pair<std::string, double>>& bad_counter() const { return bad_counter_; }
  /// wanted() for each declared output, in declaration order (GraphNode::wanted_mask), or nullptr
  /// when the node's mask does not match its list (code that edited `wanted` and did not refresh).
  const std::int32_t* wanted_mask() const {
    const std::vector<std::int32_t>& mask = node_.wanted_mask;
    if (mask.size() != node_.info().outputs.size()) return nullptr;
    std::size_t ones = 0;
    for (std::int32_t m : mask) ones += static_cast<std::size_t>(m);
    return ones == node_.wanted.size() ? mask.data() : nullptr;
  }

 private:
  const GraphNode& node_;
  NodeRun* run_;
  std::optional<std::pair<std::string, double>> bad_counter_;
};

}  // namespace mechgraph
