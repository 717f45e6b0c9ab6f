// Stability table of sweep case values at the edges of a parameter's range: on the limit the
// value is taken; one ulp beyond it the case fails alone, naming the parameter and the limit.
#include "test_support.hpp"

#include <mechgraph/sweep/sweep_runner.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <limits>

using namespace mechgraph;
using namespace mechgraph::testing;
using Catch::Matchers::Contains;

TEST_CASE("stability: sweep values on and one ulp beyond a range limit", "[stability][sweep]") {
  const char* yaml = R"(nodes:
  a: { type: test.constant, params: { value: 1 mm } }
  s: { type: test.add, inputs: { a: a.out, b: a.out } }
outputs: [s.sum]
)";
  const SceneSpec scene = parse_scene(yaml, "edge.yaml");
  const Graph graph = build_graph(scene, arith_registry());
  // s.gain must be > 0: the least normal double is in, zero and -0 are out; huge values are in.
  CaseTable table;
  table.variables = {{"s.gain", ""}};
  for (double v : {std::numeric_limits<double>::min(), 0.0, -0.0, 1e300, std::nextafter(0.0, -1.0)})
    table.cases.push_back({CaseValue{std::to_string(v), v, {}}});
  const CaseBinder binder(graph, scene, arith_registry(), {}, table.variables);
  SweepOptions options;
  for (std::size_t i = 0; i < table.size(); ++i) options.cases.push_back(i);
  MemoCache cache;
  std::vector<CaseResult> rows;
  run_sweep(graph, binder, table, cache, options, [&](CaseResult&& r) { rows.push_back(std::move(r)); });
  REQUIRE(rows.size() == 5);
  CHECK(rows[0].failure == CaseFailure::none);
  CHECK(rows[0].outputs[0].as_scalar() > 0.0);
  for (std::size_t i : {1u, 2u, 4u}) {
    INFO("case " << i);
    CHECK(rows[i].failure == CaseFailure::scene);
    CHECK_THAT(rows[i].error, Contains("parameter 'gain' of node 's'") && Contains("must be > 0"));
  }
  CHECK(rows[3].failure == CaseFailure::none);  // 1e300 x 2 mm is finite
  CHECK(std::isfinite(rows[3].outputs[0].as_scalar()));
}
