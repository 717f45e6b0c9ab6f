#include "test_support.hpp"

#include <mechgraph/errors.hpp>

#include <catch2/catch.hpp>

using namespace mechgraph;
using namespace mechgraph::testing;
using Catch::Matchers::Contains;

namespace {
const char* scene = R"(params: { len: 2 mm }
nodes:
  a:   { type: test.constant, params: { value: $len } }
  b:   { type: test.constant, params: { value: 3 mm } }
  sum: { type: test.add, params: { gain: 2 }, inputs: { a: a.out, b: [b.out, b.out] } }
  c:   { type: test.constant, params: { value: 7 mm } }
  lone: { type: test.add, inputs: { a: c.out, b: c.out } }
outputs: [ sum.sum, sum.twice ]
)";

std::vector<std::string> evaluated(const RunResult& r) {
  std::vector<std::string> out;
  for (const NodeRun& n : r.runs)
    if (!n.reused) out.push_back(n.node);
  return out;
}
}  // namespace

TEST_CASE("only the needed nodes run, each once, producers first", "[evaluator]") {
  MemoCache cache;
  const RunResult r = evaluate(graph_from(scene), cache);
  CHECK(output(r, "sum.sum").as_scalar() == Approx(2 * (2e-3 + 3e-3 + 3e-3)).epsilon(1e-15).margin(1e-18));
  CHECK(output(r, "sum.twice").as_scalar() == Approx(4e-3).epsilon(1e-15).margin(1e-18));
  CHECK(evaluated(r) == std::vector<std::string>{"a", "b", "sum"});
  for (const NodeRun& n : r.runs) CHECK(n.work.at("calls") == 1.0);
}

TEST_CASE("memoisation: a second run with a shared cache re-evaluates only what changed", "[evaluator]") {
  MemoCache cache;
  evaluate(graph_from(scene), cache);
  const RunResult same = evaluate(graph_from(scene), cache);
  CHECK(evaluated(same).empty());
  const RunResult changed = evaluate(graph_from(scene, arith_registry(), {parse_override("len=4mm")}), cache);
  CHECK(evaluated(changed) == std::vector<std::string>{"a", "sum"});
  CHECK(output(changed, "sum.sum").as_scalar() == Approx(2 * (4e-3 + 6e-3)).epsilon(1e-15).margin(1e-18));
  const RunResult gain = evaluate(graph_from(scene, arith_registry(), {parse_override("sum.gain=3")}), cache);
  CHECK(evaluated(gain) == std::vector<std::string>{"sum"});
}

TEST_CASE("identical nodes in one graph are evaluated once", "[evaluator]") {
  MemoCache cache;
  const RunResult r = evaluate(graph_from(R"(nodes:
  x: { type: test.constant, params: { value: 1 mm } }
  y: { type: test.constant, params: { value: 1 mm } }
  s: { type: test.add, inputs: { a: x.out, b: y.out } }
outputs: [s.sum]
)"),
                               cache);
  CHECK(evaluated(r) == std::vector<std::string>{"x", "s"});
  CHECK(output(r, "s.sum").as_scalar() == Approx(2e-3).epsilon(1e-15).margin(1e-18));
}

TEST_CASE("the memo key depends on type, parameters, effects and inputs", "[evaluator]") {
  const Graph g1 = graph_from(scene);
  const Graph g2 = graph_from(scene, arith_registry(), {parse_override("b.value=3.000001mm")});
  const auto h1 = node_hashes(g1), h2 = node_hashes(g2);
  CHECK(h1[*g1.find("a")] == h2[*g2.find("a")]);
  CHECK(h1[*g1.find("b")] != h2[*g2.find("b")]);
  CHECK(h1[*g1.find("sum")] != h2[*g2.find("sum")]);  // through its input
  const char* effect_off = "nodes: { e: { type: test.effectful, params: { value: 1 mm } } }\noutputs: [e.out]\n";
  const char* effect_on = "nodes: { e: { type: test.effectful, params: { value: 1 mm } } }\neffects: [test_effect]\noutputs: [e.out]\n";
  MemoCache cache;
  CHECK(output(evaluate(graph_from(effect_off), cache), "e.out").as_scalar() == Approx(1e-3).epsilon(1e-15).margin(0));
  CHECK(output(evaluate(graph_from(effect_on), cache), "e.out").as_scalar() == Approx(2e-3).epsilon(1e-15).margin(0));
}

TEST_CASE("domain objects flow between nodes", "[evaluator]") {
  MemoCache cache;
  const RunResult r = evaluate(graph_from(R"(nodes:
  k: { type: test.constant, params: { value: 5 mm } }
  b: { type: test.box, inputs: { x: k.out } }
  u: { type: test.unbox, inputs: { box: b.box } }
outputs: [u.x, b.box]
)"),
                               cache);
  CHECK(output(r, "u.x").as_scalar() == Approx(5e-3).epsilon(1e-15).margin(0));
  CHECK(output(r, "b.box").as_handle()->kind() == "test_box");
}

TEST_CASE("a node that emits NaN fails with its name, NodeErrors name node and parameter", "[evaluator]") {
  MemoCache cache;
  CHECK_THROWS_MATCHES(evaluate(graph_from("nodes: { bad: { type: test.nan } }\noutputs: [bad.out]\n"), cache), EvaluationError,
                       Catch::Matchers::Predicate<EvaluationError>([](const EvaluationError& e) {
                         const std::string m = e.what();
                         return m.find("node 'bad' (test.nan)") != std::string::npos && m.find("NaN") != std::string::npos;
                       }));
  CHECK_THROWS_WITH(evaluate(graph_from("nodes: { f: { type: test.fail } }\noutputs: [f.out]\n"), cache),
                    Contains("node 'f' (test.fail), parameter 'limit': limit exceeded"));
}

TEST_CASE("series outputs carry their axis", "[evaluator]") {
  MemoCache cache;
  const RunResult r = evaluate(graph_from("nodes: { s: { type: test.series, params: { points: 3 } } }\noutputs: [s.curve]\n"), cache);
  const Series& s = output(r, "s.curve").as_series();
  CHECK(s.values == std::vector<double>{0.0, 0.25, 1.0});
  CHECK(s.axis == std::vector<double>{0.0, 0.5, 1.0});
}

TEST_CASE("a file named by a parameter enters the memo key with its contents", "[evaluator]") {
  const auto file = std::filesystem::temp_directory_path() / "mechgraph_memo_table.csv";
  std::ofstream(file) << "0, 0\n";
  const std::string yaml = "nodes:\n  t: { type: cam.table, params: { file: '" + file.string() +
                           "', max_lift: 1 mm, action_angle: 10 deg, base_radius: 10 mm } }\noutputs: [t.max_velocity]\n";
  const Graph g = graph_from(yaml, project_registry());
  const auto before = node_hashes(g);
  std::ofstream(file) << "0, 0\n1, 0\n";
  const auto after = node_hashes(g);
  CHECK(before[0] != after[0]);
  std::filesystem::remove(file);
}

TEST_CASE("a node's error points at the parameter's value in the scene, else at the node", "[evaluator]") {
  MemoCache cache;
  CHECK_THROWS_WITH(evaluate(graph_from("nodes:\n  f: { type: test.fail, params: { limit: 2 mm } }\noutputs: [f.out]\n"), cache),
                    Catch::Matchers::StartsWith("scene.yaml:2:42: node 'f' (test.fail), parameter 'limit'"));
  CHECK_THROWS_WITH(evaluate(graph_from("nodes:\n  f: { type: test.fail }\noutputs: [f.out]\n"), cache),
                    Catch::Matchers::StartsWith("scene.yaml:2:3: node 'f' (test.fail), parameter 'limit'"));
}

TEST_CASE("a node learns which of its outputs are read, and may skip the others", "[evaluator]") {
  // valvetrain.valve_motion draws its lift curve (curve_points evaluations) only when it is read.
  const std::string nodes = R"(nodes:
  cam: { type: cam.kurz, params: { max_lift: 8 mm, action_angle: 130 deg, accel_angle: 18 deg, base_radius: 17 mm } }
  v:   { type: valvetrain.valve_motion, inputs: { cam: cam.law }, params: { rpm: 5600 rpm, curve_points: 1001 } }
)";
  const Graph scalars = graph_from(nodes + "outputs: [v.max_lift]\n", project_registry());
  const Graph curve = graph_from(nodes + "outputs: [v.max_lift, v.lift_curve]\n", project_registry());
  CHECK(scalars.nodes[*scalars.find("v")].wanted == std::vector<std::string>{"max_lift"});
  CHECK(scalars.nodes[*scalars.find("cam")].wanted == std::vector<std::string>{"law"});
  MemoCache cache;  // shared: the two graphs must not take each other's results
  const RunResult a = evaluate(scalars, cache), b = evaluate(curve, cache);
  const double work_a = a.runs.back().work.at("evaluations"), work_b = b.runs.back().work.at("evaluations");
  CHECK_FALSE(b.runs.back().reused);
  CHECK(work_b - work_a == 1001);
  CHECK(output(b, "v.lift_curve").as_series().values.size() == 1001);
  CHECK(scalar_output(a, "v.max_lift") == scalar_output(b, "v.max_lift"));
  CHECK(node_hashes(scalars)[*scalars.find("v")] != node_hashes(curve)[*curve.find("v")]);
  CHECK(node_hashes(scalars)[*scalars.find("cam")] == node_hashes(curve)[*curve.find("cam")]);
}
