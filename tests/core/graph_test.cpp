#include "test_support.hpp"

#include <mechgraph/errors.hpp>

#include <catch2/catch.hpp>

using namespace mechgraph;
using namespace mechgraph::testing;
using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;

namespace {
const char* two_branches = R"(title: two branches
params:
  len: 2 mm
nodes:
  a:   { type: test.constant, params: { value: $len } }
  b:   { type: test.constant, params: { value: 3 mm } }
  sum: { type: test.add, inputs: { a: a.out, b: [b.out, b.out] } }
  c:   { type: test.constant, params: { value: 7 mm } }
  lone: { type: test.add, inputs: { a: c.out, b: c.out } }
outputs: [ sum.sum ]
)";

void expect_scene_error(const std::string& yaml, const std::string& location, const std::string& text,
                        const std::vector<Override>& overrides = {}) {
  try {
    graph_from(yaml, arith_registry(), overrides);
    FAIL("expected a scene error containing: " << text);
  } catch (const SceneError& e) {
    CHECK_THAT(e.what(), StartsWith(location) && Contains(text));
  }
}
}  // namespace

TEST_CASE("a scene builds into a culled, ordered graph", "[graph]") {
  const Graph g = graph_from(two_branches);
  REQUIRE(g.nodes.size() == 5);
  CHECK(g.nodes[*g.find("a")].needed);
  CHECK(g.nodes[*g.find("sum")].needed);
  CHECK_FALSE(g.nodes[*g.find("c")].needed);
  CHECK_FALSE(g.nodes[*g.find("lone")].needed);
  REQUIRE(g.order.size() == 3);
  CHECK(g.order.back() == *g.find("sum"));
  CHECK(g.nodes[*g.find("a")].params.number("value") == Approx(2e-3).epsilon(1e-15).margin(0));
  CHECK(g.nodes[*g.find("a")].params.text("mode") == "plain");  // default filled in
}

TEST_CASE("overrides from the command line (--set) reach scene and node parameters", "[graph]") {
  const Graph g = graph_from(two_branches, arith_registry(), {parse_override("len=5mm"), parse_override("b.value=1 in")});
  CHECK(g.nodes[*g.find("a")].params.number("value") == Approx(5e-3).epsilon(1e-15).margin(0));
  CHECK(g.nodes[*g.find("b")].params.number("value") == Approx(0.0254).epsilon(1e-15).margin(0));
  CHECK_THROWS_WITH(graph_from(two_branches, arith_registry(), {parse_override("lenn=5mm")}),
                    Contains("--set lenn=5mm") && Contains("did you mean 'len'"));
  CHECK_THROWS_WITH(graph_from(two_branches, arith_registry(), {parse_override("bb.value=5mm")}),
                    Contains("unknown node 'bb'") && Contains("did you mean 'b'"));
  CHECK_THROWS_WITH(parse_override("novalue"), Contains("expected NAME=VALUE"));
  CHECK_THROWS_WITH(graph_from(two_branches, arith_registry(), {parse_override("len=5deg")}),
                    Contains("is angle, expected length") && Contains("--set len=5deg"));
}

TEST_CASE("scene errors carry file:line:column and the valid choices", "[graph]") {
  expect_scene_error("nodes:\n  a: { type: test.constnt, params: { value: 1 mm } }\noutputs: [a.out]\n", "scene.yaml:2:14:",
                     "unknown node type 'test.constnt'; did you mean 'test.constant'?");
  expect_scene_error("nodes:\n  a: { type: test.constant, params: { valu: 1 mm } }\noutputs: [a.out]\n", "scene.yaml:2:39:",
                     "unknown parameter 'valu'; did you mean 'value'?");
  expect_scene_error("nodes:\n  a: { type: test.constant, params: { value: 1 deg } }\noutputs: [a.out]\n", "scene.yaml:2:46:",
                     "'1 deg' is angle, expected length");
  expect_scene_error("nodes:\n  a: { type: test.constant, params: { value: 1 } }\noutputs: [a.out]\n", "scene.yaml:2:46:",
                     "has no unit");
  expect_scene_error("nodes:\n  a: { type: test.constant, params: { value: 1 mmm } }\noutputs: [a.out]\n", "scene.yaml:2:48:",
                     "unknown unit 'mmm'");
  expect_scene_error("nodes:\n  a: { type: test.constant, params: { value: 1 mm, mode: fanzy } }\noutputs: [a.out]\n",
                     "scene.yaml:2:58:", "unknown choice 'fanzy'; did you mean 'fancy'?");
  expect_scene_error("nodes:\n  a: { type: test.constant }\noutputs: [a.out]\n", "scene.yaml:2:3:",
                     "parameter 'value' is required");
  expect_scene_error("nodes:\n  a: { type: test.constant, params: { value: 1 mm } }\noutputs: [a.outt]\n", "scene.yaml:3:11:",
                     "unknown output port 'outt'; did you mean 'out'?");
  expect_scene_error("nodes:\n  a: { type: test.constant, params: { value: 1 mm } }\noutputs: [b.out]\n", "scene.yaml:3:11:",
                     "unknown node 'b'");
  expect_scene_error("nodes:\n  a: { type: test.constant, params: { value: $x } }\noutputs: [a.out]\n", "scene.yaml:2:46:",
                     "unknown scene parameter '$x'");
  expect_scene_error("params: { x: 3 deg }\nnodes:\n  a: { type: test.constant, params: { value: $x } }\noutputs: [a.out]\n",
                     "scene.yaml:3:46:", "($x = '3 deg', set at scene.yaml:1:14)");
  expect_scene_error("nodes:\n  a: { type: test.add, params: { gain: -1 }, inputs: { a: a.sum, b: a.sum } }\noutputs: [a.sum]\n",
                     "scene.yaml:2:40:", "out of range: it must be > 0");
  expect_scene_error("nodes: { a: { type: test.constant, params: { value: 1 mm } } }\noutputs: [a.out]\nefects: []\n",
                     "scene.yaml:3:1:", "unknown scene key 'efects'; did you mean 'effects'?");
  expect_scene_error("nodes: { a: { type: test.constant, params: { value: 1 mm } } }\neffects: [monte_carlo]\noutputs: [a.out]\n",
                     "scene.yaml:2:11:", "unknown effect 'monte_carlo'");
  expect_scene_error("nodes: { a: { type: test.constant, params: { value: 1 mm } } }\noutputs: [a]\n", "scene.yaml:2:11:",
                     "expected 'node.port'");
  expect_scene_error("nodes: { a: { type: test.constant, params: { value: 1 mm } }\n", "scene.yaml:", "YAML syntax");
  expect_scene_error("nodes: { a: { type: test.constant, params: { value: 1 mm } } }\n", "scene.yaml:1:1:",
                     "requests no outputs");
  // Before, the repeat was shown once without a word.
  expect_scene_error("nodes: { a: { type: test.constant, params: { value: 1 mm } } }\noutputs: [a.out,\n  a.out]\n",
                     "scene.yaml:3:3:", "output 'a.out' is listed twice in 'outputs' (first at line 2): list it once");
}

TEST_CASE("connections are checked for kind, dimension and count at load", "[graph]") {
  expect_scene_error(R"(nodes:
  k: { type: test.constant, params: { value: 1 mm } }
  x: { type: test.box, inputs: { x: k.out } }
  s: { type: test.add, inputs: { a: x.box, b: k.out } }
outputs: [s.sum]
)",
                     "scene.yaml:4:37:", "'x.box' is a test_box, the input expects a scalar of length");
  expect_scene_error(R"(nodes:
  k: { type: test.constant, params: { value: 1 mm } }
  s: { type: test.add, inputs: { a: [k.out, k.out], b: k.out } }
outputs: [s.sum]
)",
                     "scene.yaml:3:34:", "input 'a' takes exactly one connection, found 2");
  expect_scene_error(R"(nodes:
  k: { type: test.constant, params: { value: 1 mm } }
  s: { type: test.add, inputs: { a: k.out } }
outputs: [s.sum]
)",
                     "scene.yaml:3:3:", "input 'b' is not connected");
  expect_scene_error(R"(nodes:
  k: { type: test.constant, params: { value: 1 mm } }
  s: { type: test.add, inputs: { a: k.out, c: k.out } }
outputs: [s.sum]
)",
                     "scene.yaml:3:44:", "unknown input port 'c'");
  expect_scene_error(R"(nodes:
  k: { type: test.constant, params: { value: 1 mm } }
  s: { type: test.add, inputs: { a: k.ot, b: k.out } }
outputs: [s.sum]
)",
                     "scene.yaml:3:37:", "did you mean 'out'?");
}

TEST_CASE("cycles are reported at load, culled or not", "[graph]") {
  expect_scene_error(R"(nodes:
  k: { type: test.constant, params: { value: 1 mm } }
  p: { type: test.add, inputs: { a: q.sum, b: k.out } }
  q: { type: test.add, inputs: { a: p.sum, b: k.out } }
  r: { type: test.add, inputs: { a: k.out, b: k.out } }
outputs: [r.sum]
)",
                     "scene.yaml:", "the graph has a cycle: p <- q <- p");
  expect_scene_error(R"(nodes:
  k: { type: test.constant, params: { value: 1 mm } }
  p: { type: test.add, inputs: { a: p.sum, b: k.out } }
outputs: [p.sum]
)",
                     "scene.yaml:3:37:", "connected to the node itself");
}

TEST_CASE("report tables: role rows, explicit cells with series elements, and their errors", "[graph]") {
  const char* scene = R"(nodes:
  a: { type: test.constant, params: { value: 1 mm } }
  b: { type: test.constant, params: { value: 2 mm } }
  s: { type: test.series, params: { points: 3 } }
report:
  - title: by role
    columns: { first: { x: a }, second: { x: b } }
    rows: [ [ value, x.out, mm ] ]
  - title: explicit
    columns: [ one, two ]
    rows:
      - [ mixed, [ a.out, "s.curve[2]" ] ]
      - [ blank, [ "-", b.out ], um ]
)";
  const Graph g = graph_from(scene);
  REQUIRE(g.reports.size() == 2);
  CHECK(g.reports[0].rows[0].cells.size() == 2);
  const auto& mixed = g.reports[1].rows[0].cells;
  REQUIRE(mixed[1]);
  CHECK(mixed[1]->element == std::size_t{2});
  CHECK_FALSE(g.reports[1].rows[1].cells[0]);
  expect_scene_error(R"(nodes: { s: { type: test.series } }
report: { columns: [ one ], rows: [ [ c, [ s.curve ] ] ] })",
                     "scene.yaml:2:44:", "is a series; name one element, e.g. s.curve[0]");
  expect_scene_error(R"(nodes: { a: { type: test.constant, params: { value: 1 mm } } }
report: { columns: [ one, two ], rows: [ [ c, [ a.out ] ] ] })",
                     "scene.yaml:2:47:", "has 1 cells for 2 columns");
  expect_scene_error(R"(nodes: { a: { type: test.constant, params: { value: 1 mm } } }
report: { columns: { one: { x: a } }, rows: [ [ c, y.out ] ] })",
                     "scene.yaml:2:52:", "unknown role 'y'; did you mean 'x'?");
  expect_scene_error(R"(nodes: { a: { type: test.constant, params: { value: 1 mm } } }
report: { columns: { one: { x: a } }, rows: [ [ c, x.out, deg ] ] })",
                     "scene.yaml:2:52:", "unit 'deg' is angle, the value is length");
}

TEST_CASE("a list given where one number is expected: the message shows what was given", "[graph]") {
  const std::string yaml = "params: { len: 2 mm }\nnodes: { a: { type: test.constant, params: { value: $len } } }\noutputs: [a.out]\n";
  try {
    graph_from(yaml, arith_registry(), {parse_override("len=[1mm, 2mm]")});
    FAIL("no error");
  } catch (const SceneError& e) {
    CHECK_THAT(e.what(), Catch::Matchers::Contains("expected one number with its unit, e.g. '9 mm', got the list [1mm, 2mm]") &&
                             Catch::Matchers::Contains("$len = '[1mm, 2mm]'") &&
                             Catch::Matchers::Contains("sweep them (mechgraph sweep SCENE --vary"));
  }
}
