#pragma once
// A sweep ready to run in a test: an inline scene parsed and built, its cases, and the binder
// that writes them (the sweep and block-path tests share it).
#include "test_support.hpp"

#include <mechgraph/scene.hpp>
#include <mechgraph/sweep/case_binder.hpp>
#include <mechgraph/sweep/case_table.hpp>

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

}  // namespace mechgraph::testing
