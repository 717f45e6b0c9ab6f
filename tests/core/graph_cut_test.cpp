#include "test_support.hpp"

#include <mechgraph/evaluator.hpp>
#include <mechgraph/graph_cut.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

using namespace mechgraph;
using namespace mechgraph::testing;

namespace {
// `top` and `mid` are culled (no output reads them) and written before their producers.
const char* culled_chain = R"(title: a culled chain
nodes:
  top: { type: test.add, inputs: { a: mid.sum, b: c.out } }
  mid: { type: test.add, inputs: { a: a.out, b: b.out } }
  a:   { type: test.constant, params: { value: 2 mm } }
  b:   { type: test.constant, params: { value: 3 mm } }
  c:   { type: test.constant, params: { value: 7 mm } }
  sum: { type: test.add, inputs: { a: a.out, b: b.out } }
outputs: [ sum.sum ]
)";

std::vector<std::string> names_in_order(const Graph& g) {
  std::vector<std::string> names;
  for (std::size_t i : g.order) names.push_back(g.nodes[i].name);
  return names;
}

std::size_t position(const std::vector<std::string>& names, const std::string& name) {
  return static_cast<std::size_t>(std::find(names.begin(), names.end(), name) - names.begin());
}
}  // namespace

TEST_CASE("a graph cut to a node keeps it and its producers in dependency order", "[graph]") {
  SECTION("a needed node: the scene's order, restricted") {
    Graph g = graph_from(culled_chain);
    cut_to_producers(g, *g.find("sum"));
    CHECK(names_in_order(g) == std::vector<std::string>{"a", "b", "sum"});
    CHECK(g.outputs.empty());
    CHECK(g.reports.empty());
    CHECK(g.nodes[*g.find("sum")].needed);
    CHECK_FALSE(g.nodes[*g.find("c")].needed);
    // Each kept node keeps what it was wanted for in the whole scene.
    CHECK(g.nodes[*g.find("sum")].wanted == std::vector<std::string>{"sum"});
  }
  SECTION("a culled node and its culled producers: producers first, whatever the scene's order") {
    Graph g = graph_from(culled_chain);
    cut_to_producers(g, *g.find("top"));
    const std::vector<std::string> names = names_in_order(g);
    REQUIRE(names.size() == 5);  // top, mid, a, b, c; not sum
    CHECK(position(names, "sum") == names.size());
    CHECK(position(names, "a") < position(names, "mid"));
    CHECK(position(names, "b") < position(names, "mid"));
    CHECK(position(names, "mid") < position(names, "top"));
    CHECK(position(names, "c") < position(names, "top"));
    for (const char* n : {"top", "mid", "a", "b", "c"}) CHECK(g.nodes[*g.find(n)].needed);
    CHECK_FALSE(g.nodes[*g.find("sum")].needed);
    // Requested and evaluated: (2 mm + 3 mm) + 7 mm.
    const std::size_t top = *g.find("top");
    const std::vector<PortSpec>& ports = g.nodes[top].info().outputs;
    const auto port = std::find_if(ports.begin(), ports.end(), [](const PortSpec& p) { return p.name == "sum"; });
    REQUIRE(port != ports.end());
    g.outputs.push_back(RequestedOutput{top, "sum", &*port, "top.sum"});
    mark_wanted_outputs(g);
    MemoCache cache;
    const RunResult r = evaluate(g, cache);
    REQUIRE(r.outputs.size() == 1);
    CHECK_THAT(r.outputs[0].value.as_scalar(), Catch::Matchers::WithinRel(12e-3, 1e-15) || Catch::Matchers::WithinAbs(12e-3, 1e-18));
    CHECK(r.runs.size() == 5);
  }
  SECTION("a node index past the graph's nodes is refused, the graph unchanged") {
    Graph g = graph_from(culled_chain);
    const std::vector<std::string> before = names_in_order(g);
    CHECK_THROWS_AS(cut_to_producers(g, g.nodes.size()), std::out_of_range);
    CHECK(names_in_order(g) == before);
    CHECK(g.outputs.size() == 1);
  }
}
