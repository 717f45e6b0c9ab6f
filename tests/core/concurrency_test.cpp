// Nodes are pure and the memo cache is thread-safe: evaluating graphs on several threads at once,
// sharing one cache, gives exactly the results of evaluating them one after the other.
#include "test_support.hpp"

#include <catch2/catch.hpp>

#include <future>

using namespace mechgraph;
using namespace mechgraph::testing;

TEST_CASE("a sweep evaluated on four threads with one shared cache equals the sequential sweep", "[evaluator][threads]") {
  const SceneSpec scene = load_scene(std::filesystem::path(MECHGRAPH_SOURCE_DIR) / "scenes" / "valvetrain_cams.yaml");
  std::vector<Graph> graphs;
  for (int i = 0; i < 16; ++i)
    graphs.push_back(build_graph(scene, project_registry(), {parse_override("rpm=" + std::to_string(3000 + 250 * i) + "rpm")}));

  std::vector<RunResult> sequential;
  for (const Graph& g : graphs) {
    MemoCache own;
    sequential.push_back(evaluate(g, own));
  }

  MemoCache shared;
  std::vector<std::future<RunResult>> futures;
  std::vector<RunResult> parallel(graphs.size());
  for (int t = 0; t < 4; ++t)
    futures.push_back(std::async(std::launch::async, [&, t] {
      for (std::size_t i = static_cast<std::size_t>(t); i < graphs.size(); i += 4) parallel[i] = evaluate(graphs[i], shared);
      return RunResult{};
    }));
  for (auto& f : futures) f.get();

  for (std::size_t i = 0; i < graphs.size(); ++i) {
    REQUIRE(parallel[i].outputs.size() == sequential[i].outputs.size());
    for (std::size_t k = 0; k < sequential[i].outputs.size(); ++k) {
      const Value& a = parallel[i].outputs[k].value;
      const Value& b = sequential[i].outputs[k].value;
      if (b.kind() == ValueKind::scalar) CHECK(a.as_scalar() == b.as_scalar());  // bit for bit
    }
  }
  // Per speed: 3 valve motions, 3 time-areas, 6 spring designs, 6 resonances. The cams, the masses
  // and the spring model do not depend on rpm: shared across the sweep, a few duplicates from races.
  CHECK(shared.size() < 16 * 18 + 5 + 4);
}

TEST_CASE("one graph on several threads: same results, runs in dependency order, failures reported", "[evaluator][threads]") {
  for (const char* name : {"valvetrain_cams.yaml", "backlash_chain.yaml"}) {
    INFO(name);
    const Graph g = build_graph(load_scene(std::filesystem::path(MECHGRAPH_SOURCE_DIR) / "scenes" / name), project_registry());
    MemoCache one, many;
    const RunResult sequential = evaluate(g, one, 1);
    const RunResult parallel = evaluate(g, many, 4);
    REQUIRE(parallel.runs.size() == sequential.runs.size());
    for (std::size_t i = 0; i < sequential.runs.size(); ++i) CHECK(parallel.runs[i].node == sequential.runs[i].node);
    REQUIRE(parallel.outputs.size() == sequential.outputs.size());
    for (std::size_t k = 0; k < sequential.outputs.size(); ++k)
      if (sequential.outputs[k].value.kind() == ValueKind::scalar)
        CHECK(parallel.outputs[k].value.as_scalar() == sequential.outputs[k].value.as_scalar());
  }
  MemoCache cache;
  const Graph broken = graph_from(R"(nodes:
  a: { type: test.constant, params: { value: 1 mm } }
  b: { type: test.constant, params: { value: 2 mm } }
  n: { type: test.nan }
  s: { type: test.add, inputs: { a: a.out, b: n.out } }
outputs: [s.sum]
)");
  CHECK_THROWS_WITH(evaluate(broken, cache, 3), Catch::Matchers::Contains("node 'n' (test.nan)"));
}
