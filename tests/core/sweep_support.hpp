#pragma once
// A sweep ready to run in a test: an inline scene parsed and built, its cases, and the binder
// that writes them; its rows on a number of threads and blocks, and the check that two runs of
// it give the same rows (the sweep and block-path tests share them).
#include "test_support.hpp"

#include <mechgraph/memo_cache.hpp>
#include <mechgraph/scene.hpp>
#include <mechgraph/sweep/case_binder.hpp>
#include <mechgraph/sweep/case_table.hpp>
#include <mechgraph/sweep/sweep_runner.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <cstddef>

#include <memory>
#include <string>
#include <vector>

namespace mechgraph::testing {

struct Prepared {
  SceneSpec scene;
  Graph graph;
  CaseTable table;
  std::unique_ptr<CaseBinder> binder;
};

inline Prepared prepare(const std::string& yaml, CaseTable table, const PluginRegistry& registry = arith_registry()) {
  Prepared p{parse_scene(yaml, "sweep.yaml"), {}, std::move(table), nullptr};
  p.graph = build_graph(p.scene, registry);
  p.binder = std::make_unique<CaseBinder>(p.graph, p.scene, registry, std::vector<Override>{}, p.table.variables);
  return p;
}

struct Swept {
  std::vector<CaseResult> rows;
  SweepSummary summary;
};

/// Every case of `p` on `threads` threads, in blocks of `block_size` cases (0: each case alone).
inline Swept sweep(const Prepared& p, unsigned threads, std::size_t block_size) {
  SweepOptions options;
  options.threads = threads;
  options.block_size = block_size;
  for (std::size_t i = 0; i < p.table.size(); ++i) options.cases.push_back(i);
  MemoCache cache;
  Swept s;
  s.summary = run_sweep(p.graph, *p.binder, p.table, cache, options, [&](CaseResult&& r) { s.rows.push_back(std::move(r)); });
  return s;
}

/// Case for case: the same failure, the same message, the same numbers bit for bit (the block
/// path runs the same functions of the node types as a case alone); the relative difference is
/// shown where two differ.
inline void require_same_rows(const Swept& blocks, const Swept& alone) {
  REQUIRE(blocks.rows.size() == alone.rows.size());
  for (std::size_t i = 0; i < alone.rows.size(); ++i) {
    INFO("case " << i);
    const CaseResult& b = blocks.rows[i];
    const CaseResult& a = alone.rows[i];
    REQUIRE(b.index == a.index);
    REQUIRE(b.failure == a.failure);
    REQUIRE(b.error == a.error);
    REQUIRE(b.outputs.size() == a.outputs.size());
    for (std::size_t j = 0; j < a.outputs.size(); ++j) {
      const double x = b.outputs[j].as_scalar(), y = a.outputs[j].as_scalar();
      INFO("output " << j << ": " << x << " against " << y << ", relative difference " << std::abs(x - y) / std::abs(y));
      CHECK(x == y);
    }
  }
}

}  // namespace mechgraph::testing
