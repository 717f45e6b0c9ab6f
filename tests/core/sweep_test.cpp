// Sweeps in process: cases made by grid, CSV and Latin hypercube; case values written into a built
// graph (checked against building the graph with --set, the second method); the bounded memo
// cache; rows in case order and bit-identical for any thread count; failed cases and stopping.
#include "sweep_support.hpp"
#include "test_support.hpp"

#include <mechgraph/error_subject.hpp>
#include <mechgraph/errors.hpp>
#include <mechgraph/memo_cache.hpp>
#include <mechgraph/units.hpp>
#include <mechgraph/sweep/case_estimate.hpp>
#include <mechgraph/sweep/sweep_runner.hpp>
#include <mechgraph/work_estimate.hpp>

#include <catch2/catch.hpp>

#include <numbers>

#include <unistd.h>

#include <cmath>
#include <fstream>
#include <numeric>
#include <set>

using namespace mechgraph;
using namespace mechgraph::testing;
using Catch::Matchers::Contains;
using Catch::Matchers::WithinAbs;
using Catch::Matchers::WithinRel;

namespace {

const char* two_constants = R"(title: sweep
params: { len: 2 mm, other: 1 mm }
nodes:
  a: { type: test.constant, params: { value: $len } }
  b: { type: test.constant, params: { value: 5 mm } }
  s: { type: test.add, inputs: { a: a.out, b: b.out }, params: { gain: 2 } }
outputs: [ s.sum, a.out ]
)";

// The scene of the budget's tests: a real number, an integer and a choice to vary, and types
// without a forecast (the conventions).
const char* estimated_scene = R"(params: { len: 2 mm }
nodes:
  c: { type: test.constant, params: { value: $len } }
  s: { type: test.add, inputs: { a: c.out, b: c.out }, params: { gain: 2 } }
  q: { type: test.series, params: { points: 5 } }
  t: { type: test.table, params: { points: 4 } }
outputs: [ s.sum, q.curve, t.curves ]
)";

std::vector<CaseResult> sweep_all(const Prepared& p, unsigned threads, MemoCache& cache) {
  SweepOptions options;
  options.threads = threads;
  for (std::size_t i = 0; i < p.table.size(); ++i) options.cases.push_back(i);
  std::vector<CaseResult> rows;
  run_sweep(p.graph, *p.binder, p.table, cache, options, [&](CaseResult&& r) { rows.push_back(std::move(r)); });
  return rows;
}

}  // namespace

TEST_CASE("sweep --vary: FROM:TO:N includes both ends exactly, units in either end, lists of words", "[sweep]") {
  const VarySpec v = parse_vary("rpm=3000rpm:7000:5");
  REQUIRE(v.values.size() == 5);
  const double rpm = 2 * M_PI / 60;
  CHECK(*v.values.front().si == 3000 * rpm);
  CHECK(*v.values.back().si == 7000 * rpm);
  CHECK_THAT(*v.values[1].si, WithinRel(4000 * rpm, 1e-15));
  CHECK(v.unit == "rpm");
  CHECK(v.values[2].dimension == dim::angular_speed);
  const VarySpec words = parse_vary("integrator=cvode,dopri5");
  REQUIRE(words.values.size() == 2);
  CHECK_FALSE(words.values[0].si);
  CHECK(words.values[1].text == "dopri5");
  CHECK_THROWS_WITH(parse_vary("rpm=3000rpm:7000mm:3"), Contains("FROM is angle/time but TO is length"));
  CHECK_THROWS_WITH(parse_vary("rpm=3000rpm:7000rpm:0"), Contains("whole number of points"));
  CHECK_THROWS_WITH(parse_vary("rpm"), Contains("expected NAME=FROM:TO:N"));
}

TEST_CASE("a grid runs every combination, the last axis fastest", "[sweep]") {
  const CaseTable t = make_grid({parse_vary("a=1mm:3mm:3"), parse_vary("b=x,y")});
  REQUIRE(t.cases.size() == 6);
  CHECK(t.shown(0, 0) == "1");
  CHECK(t.shown(1, 1) == "y");
  CHECK(t.shown(5, 0) == "3");
  CHECK(t.variables[0].unit == "mm");
}

TEST_CASE("Latin hypercube: one point per stratum of every variable, reproducible from the seed", "[sweep]") {
  const std::vector<SampleSpec> specs = {parse_sample("lift=8mm:10mm"), parse_sample("rpm=3000rpm:6000rpm")};
  const std::size_t n = 50;
  const CaseTable t = make_latin_hypercube(specs, n, 7);
  REQUIRE(t.size() == n);
  CHECK(t.cases.empty());  // kept as numbers, 8 bytes a value
  CaseValue scratch;
  const auto si = [&scratch](const CaseTable& table, std::size_t i, std::size_t v) { return *table.cell(i, v, scratch).si; };
  for (std::size_t v = 0; v < specs.size(); ++v) {
    std::set<std::size_t> strata;
    for (std::size_t i = 0; i < n; ++i) {
      const double u = (si(t, i, v) - specs[v].low) / (specs[v].high - specs[v].low);
      REQUIRE(u >= 0.0);
      REQUIRE(u < 1.0);
      strata.insert(static_cast<std::size_t>(u * n));
    }
    CHECK(strata.size() == n);  // each of the n strata holds exactly one case
  }
  const CaseTable again = make_latin_hypercube(specs, n, 7);
  const CaseTable other = make_latin_hypercube(specs, n, 8);
  bool same = true, differs = false;
  for (std::size_t i = 0; i < n; ++i) {
    same = same && si(again, i, 0) == si(t, i, 0) && si(again, i, 1) == si(t, i, 1);
    differs = differs || si(other, i, 0) != si(t, i, 0);
  }
  CHECK(same);
  CHECK(differs);
  // Values written as text read back to the same doubles (a rebuilt graph sees the same case).
  CHECK(parse_quantity(t.cell(3, 1, scratch).written()).value == si(t, 3, 1));
  CHECK_THROWS_WITH(parse_sample("lift=10mm:8mm"), Contains("HI must be greater than LO"));
}

TEST_CASE("sweep --cases: header units, units in cells, words, and located errors", "[sweep]") {
  const auto dir = std::filesystem::temp_directory_path() / ("mechgraph_sweep_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const auto file = dir / "cases.csv";
  std::ofstream(file) << "# designs to try\nlift [mm],rpm,integrator\n8,5000 rpm,cvode\n\n9.5,6000rpm,\"dopri5\"\n";
  const CaseTable t = read_cases_csv(file);
  REQUIRE(t.size() == 2);
  CaseValue scratch;
  CHECK_THAT(*t.cell(1, 0, scratch).si, WithinRel(9.5e-3, 1e-15));
  CHECK(t.variables[0].unit == "mm");
  CHECK(t.variables[1].unit == "rpm");
  CHECK(t.shown(1, 1) == "6000");
  CHECK(t.cell(1, 2, scratch).text == "dopri5");
  CHECK_FALSE(t.cell(1, 2, scratch).si);
  std::ofstream(file) << "lift [mm],rpm\n8,5000 rpm\n9\n";
  CHECK_THROWS_WITH(read_cases_csv(file), Contains("cases.csv:3:1: 1 cells, the header has 2"));
  std::ofstream(file) << "lift [mm],rpm\n8,\n";
  CHECK_THROWS_WITH(read_cases_csv(file), Contains("cases.csv:2:3: 'rpm' has no value"));
  // Columns counted in the line as written, quotes included; a header's unit at fault named on
  // line 1; a number beyond a double's range said so.
  std::ofstream(file) << "lift [mm],action [deg],rpm [rpm]\n\"8.0\",\"130.0\",fast\n";
  CHECK_THROWS_WITH(read_cases_csv(file), Contains("cases.csv:2:15: 'fast' is not a number in rpm"));
  std::ofstream(file) << "rpm [rpm],lift [mmm]\n5000,8\n";
  CHECK_THROWS_WITH(read_cases_csv(file), Contains("cases.csv:1:11: column 'lift': [mmm] is not a unit") && Contains("mm"));
  std::ofstream(file) << "lift [mm]\n1e400\n";
  CHECK_THROWS_WITH(read_cases_csv(file), Contains("cases.csv:2:1: '1e400' is beyond the range of a double"));
  // A byte order mark, CRLF line ends, padded cells, no line break at the end.
  std::ofstream(file) << "\xEF\xBB\xBFlift [mm],rpm\r\n 8 ,5000 rpm\r\n\r\n9.5\t,\"6000 rpm\"";
  const CaseTable u = read_cases_csv(file);
  REQUIRE(u.size() == 2);
  CHECK(u.variables[0].name == "lift");
  CHECK(u.cell(0, 0, scratch).text == "8 mm");
  CHECK(u.cell(1, 0, scratch).text == "9.5 mm");
  CHECK_THAT(*u.cell(1, 1, scratch).si, WithinRel(6000.0 * std::numbers::pi / 30.0, 1e-15));
  // A header as mechgraph's own CSVs write it, the angle reference after degrees: read as degrees.
  std::ofstream(file) << "timing [deg (crank)],rate [mm/deg (cam)]\n90,2\n";
  const CaseTable tagged = read_cases_csv(file);
  CHECK(tagged.variables[0].unit == "deg");
  CHECK(tagged.variables[1].unit == "mm/deg");
  CHECK_THAT(*tagged.cell(0, 0, scratch).si, WithinRel(std::numbers::pi / 2, 1e-15));
  CHECK_THAT(*tagged.cell(0, 1, scratch).si, WithinRel(2e-3 / (std::numbers::pi / 180.0), 1e-15));
  std::ofstream(file) << "lift [mm],rpm\r\n8,5000 rpm\r\n\"9\",x y,\r\n";
  CHECK_THROWS_WITH(read_cases_csv(file), Contains("cases.csv:3:1: 3 cells, the header has 2"));
  std::filesystem::remove_all(dir);
}

TEST_CASE("case values set on the built graph equal a graph built with --set (second method)", "[sweep]") {
  Prepared p = prepare(two_constants, make_grid({parse_vary("len=1mm:4mm:4"), parse_vary("s.gain=1,3")}));
  MemoCache cache;
  const auto rows = sweep_all(p, 1, cache);
  REQUIRE(rows.size() == 8);
  for (const CaseResult& r : rows) {
    REQUIRE(r.failure == CaseFailure::none);
    const auto& c = p.table.cases[r.index];
    const RunResult direct = run_yaml(two_constants, arith_registry(), {parse_override("len=" + c[0].text), parse_override("s.gain=" + c[1].text)});
    CHECK(r.outputs[0].as_scalar() == scalar_output(direct, "s.sum"));
    CHECK(r.outputs[1].as_scalar() == scalar_output(direct, "a.out"));
  }
  CHECK_THAT(rows[7].outputs[0].as_scalar(), WithinRel(3 * (4e-3 + 5e-3), 1e-15));
  // b never changes: evaluated once, then reused by every case.
  CHECK(cache.hits() >= 7);
}

TEST_CASE("a case outside a parameter's range, of the wrong dimension or an unknown choice fails alone", "[sweep]") {
  Prepared p = prepare(two_constants, make_grid({parse_vary("s.gain=2,-1,3 mm,abc")}));
  MemoCache cache;
  const auto rows = sweep_all(p, 2, cache);
  REQUIRE(rows.size() == 4);
  CHECK(rows[0].failure == CaseFailure::none);
  CHECK(rows[1].failure == CaseFailure::scene);
  CHECK_THAT(rows[1].error, Contains("s.gain = '-1'") && Contains("parameter 'gain' of node 's' (test.add) is out of range: it must be > 0"));
  CHECK_THAT(rows[2].error, Contains("is dimensionless (1), the value is length"));
  CHECK_THAT(rows[3].error, Contains("s.gain = 'abc'"));
  CHECK(rows[3].failure == CaseFailure::scene);
  for (std::size_t i = 1; i < rows.size(); ++i) CHECK(rows[i].outputs.empty());  // a refused case has no values
}

TEST_CASE("an evaluation error in one case is its row's error, the sweep goes on", "[sweep]") {
  const char* yaml = R"(title: failing
nodes:
  f: { type: test.fail, params: { limit: 1 mm } }
  a: { type: test.constant, params: { value: 1 mm } }
outputs: [ a.out, f.out ]
)";
  Prepared p = prepare(yaml, make_grid({parse_vary("a.value=1mm:2mm:3")}));
  MemoCache cache;
  const auto rows = sweep_all(p, 2, cache);
  REQUIRE(rows.size() == 3);
  for (const CaseResult& r : rows) {
    CHECK(r.failure == CaseFailure::evaluation);
    CHECK_THAT(r.error, Contains("node 'f' (test.fail), parameter 'limit'"));
  }
}

TEST_CASE("unknown sweep variables name the valid ones", "[sweep]") {
  const SceneSpec scene = parse_scene(two_constants, "sweep.yaml");
  const Graph g = build_graph(scene, arith_registry());
  auto bind = [&](const std::string& name) { CaseBinder(g, scene, arith_registry(), {}, {{name, ""}}); };
  CHECK_THROWS_WITH(bind("lne"), Contains("unknown scene parameter 'lne'; did you mean 'len'?"));
  CHECK_THROWS_WITH(bind("other"), Contains("'other' is not used by any node"));
  CHECK_THROWS_WITH(bind("s.gian"), Contains("node 's' (test.add): unknown parameter 'gian'; did you mean 'gain'?"));
  CHECK_THROWS_WITH(bind("q.gain"), Contains("unknown node 'q'"));
}

TEST_CASE("an evaluation error carries its node, parameter and place as data", "[evaluator]") {
  const char* yaml = R"(title: failing
nodes:
  f: { type: test.fail, params: { limit: 1 mm } }
outputs: [ f.out ]
)";
  try {
    run_yaml(yaml, arith_registry());
    FAIL("test.fail did not fail");
  } catch (const NodeEvaluationError& e) {
    CHECK(e.subject().node == "f");
    CHECK(e.subject().parameter == "limit");
    CHECK(e.subject().where.line == 3);  // where `limit` is written
    CHECK_THAT(std::string(e.what()), Contains("node 'f' (test.fail), parameter 'limit'"));
  }
}

TEST_CASE("a binder for a run's set= speaks of set, and its errors carry node and parameter", "[sweep]") {
  const SceneSpec scene = parse_scene(two_constants, "sweep.yaml");
  Graph g = build_graph(scene, arith_registry());
  auto bind = [&](const std::string& name) { CaseBinder(g, scene, arith_registry(), {}, {{name, ""}}, BinderUse::set); };
  for (const char* name : {"lne", "other", "s.gian", "q.gain"}) {
    try {
      bind(name);
      FAIL("no error for " << name);
    } catch (const SceneError& e) {
      const std::string message = e.what();
      CHECK_THAT(message, Contains(std::string("set ") + name));
      CHECK(message.find("sweep") == std::string::npos);
      CHECK(message.find("vari") == std::string::npos);
    }
  }
  const CaseBinder binder(g, scene, arith_registry(), {}, {{"s.gain", ""}}, BinderUse::set);
  try {
    binder.apply(g, {read_case_value("3 mm", "set s.gain")});
    FAIL("a length for a gain was taken");
  } catch (const SceneErrorAt& e) {
    CHECK(e.subject().node == "s");
    CHECK(e.subject().parameter == "gain");
    CHECK(e.subject().where.line == 0);
  }
}

TEST_CASE("a variable inside a list is swept by building each case anew, with the same results", "[sweep]") {
  const char* yaml = R"(title: nested
params: { w: 2 mm }
nodes:
  stack: { type: stack.linear, params: { links: [ { label: a, nominal: $w, upper: 0.1 mm, lower: 0 mm, sensitivity: 1 },
                                                  { label: b, nominal: 10 mm, upper: 0 mm, lower: -0.1 mm, sensitivity: -1 } ] } }
outputs: [ stack.mean ]
)";
  Prepared p = prepare(yaml, make_grid({parse_vary("w=11mm:13mm:3")}), project_registry());
  CHECK(p.binder->rebuilds());
  MemoCache cache;
  const auto rows = sweep_all(p, 2, cache);
  REQUIRE(rows.size() == 3);
  for (const CaseResult& r : rows) {
    REQUIRE(r.failure == CaseFailure::none);
    // mean = (w + 0.05 mm) - (10 mm - 0.05 mm)
    CaseValue scratch;
    CHECK_THAT(r.outputs[0].as_scalar(), WithinAbs(*p.table.cell(r.index, 0, scratch).si + 0.1e-3 - 10e-3, 1e-15));
  }
}

TEST_CASE("rows come in case order and are bit-identical for 1, 2 and 4 threads", "[sweep]") {
  const std::string yaml = R"(title: valve
params: { rpm: 5600 rpm }
nodes:
  cam:   { type: cam.kurz, params: { max_lift: 8 mm, action_angle: 130 deg, accel_angle: 18 deg, base_radius: 17 mm } }
  valve: { type: valvetrain.valve_motion, inputs: { cam: cam.law }, params: { rpm: $rpm, rocker_ratio: 1.5, lash: 0.25 mm } }
  ta:    { type: valvetrain.time_area, inputs: { valve: valve.motion }, params: { seat_diameter: 34 mm, seat_angle: 45 deg } }
outputs: [ ta.time_area, valve.max_acceleration ]
)";
  Prepared p = prepare(yaml, make_grid({parse_vary("rpm=3000rpm:7000rpm:7"), parse_vary("cam.max_lift=7mm:9mm:3")}), project_registry());
  std::vector<std::vector<CaseResult>> runs;
  for (unsigned threads : {1u, 2u, 4u}) {
    MemoCache cache;
    runs.push_back(sweep_all(p, threads, cache));
  }
  for (const auto& rows : runs) {
    REQUIRE(rows.size() == 21);
    for (std::size_t i = 0; i < rows.size(); ++i) {
      REQUIRE(rows[i].index == i);
      REQUIRE(rows[i].failure == CaseFailure::none);
      for (std::size_t j = 0; j < 2; ++j) CHECK(rows[i].outputs[j].as_scalar() == runs[0][i].outputs[j].as_scalar());
    }
  }
  // Time-area scales as 1/rpm for one cam: a check that each case really got its speed.
  CHECK_THAT(runs[0][0].outputs[0].as_scalar() * 3000, WithinRel(runs[0][18].outputs[0].as_scalar() * 7000, 1e-12));
}

TEST_CASE("stopping: started cases finish and every finished row is handed over, in order", "[sweep]") {
  Prepared p = prepare(two_constants, make_grid({parse_vary("len=1mm:100mm:100")}));
  MemoCache cache;
  std::atomic<bool> stop{false};
  SweepOptions options;
  options.threads = 2;
  options.stop = &stop;
  options.window = 2;  // workers stay within two cases of the oldest unfinished one: a prompt stop
  for (std::size_t i = 0; i < 100; ++i) options.cases.push_back(i);
  std::vector<std::size_t> seen;
  const SweepSummary s = run_sweep(p.graph, *p.binder, p.table, cache, options, [&](CaseResult&& r) {
    seen.push_back(r.index);
    if (seen.size() == 10) stop = true;
  });
  CHECK(s.stopped);
  CHECK(s.run == seen.size());
  REQUIRE(seen.size() >= 10);
  CHECK(seen.size() <= 10 + 2);  // the cases already started when the stop came
  for (std::size_t i = 0; i < seen.size(); ++i) CHECK(seen[i] == i);
}

TEST_CASE("memo cache: bounded, least recently used dropped first", "[sweep][memo]") {
  MemoCache cache(3);
  auto entry = [] { return std::make_shared<const OutputSet>(); };
  cache.store(1, entry());
  cache.store(2, entry());
  cache.store(3, entry());
  CHECK(cache.find(1));  // 1 is now the most recent; 2 the least
  cache.store(4, entry());
  CHECK(cache.size() == 3);
  CHECK_FALSE(cache.find(2));
  CHECK(cache.find(3));
  CHECK(cache.find(4));
  CHECK(cache.evictions() == 1);
  CHECK(cache.hits() == 3);
  CHECK(cache.misses() == 1);
  cache.erase(3);
  CHECK(cache.size() == 2);
  MemoCache one(0);  // a capacity of zero still holds one entry
  one.store(1, entry());
  CHECK(one.size() == 1);
}

TEST_CASE("sweep fast path: nodes a case changes skip the memo cache, the others are shared, rows as evaluated alone",
          "[sweep][memo]") {
  // masses and spring do not depend on the swept values: memoised and shared by every case; the
  // cam (lift), valve and time-area (rpm downstream) change with every case: never stored.
  const std::string yaml = R"(title: valve
params: { rpm: 5600 rpm }
nodes:
  cam:   { type: cam.kurz, params: { max_lift: 8 mm, action_angle: 130 deg, accel_angle: 18 deg, base_radius: 17 mm } }
  valve: { type: valvetrain.valve_motion, inputs: { cam: cam.law }, params: { rpm: $rpm, rocker_ratio: 1.5, lash: 0.25 mm } }
  ta:    { type: valvetrain.time_area, inputs: { valve: valve.motion }, params: { seat_diameter: 34 mm, seat_angle: 45 deg } }
  train: { type: valvetrain.masses, params: { valve_mass: 55 g, retainer_mass: 18 g, tappet_mass: 60 g, pushrod_mass: 50 g,
                                              rocker_inertia: 4e-5 kg*m^2, arm_valve: 45 mm, arm_pushrod: 30 mm } }
outputs: [ ta.time_area, valve.max_acceleration, train.mass_without_spring ]
)";
  Prepared p = prepare(yaml, make_grid({parse_vary("rpm=3000rpm:7000rpm:3"), parse_vary("cam.max_lift=7mm:9mm:2")}),
                       project_registry());
  Graph marked = p.graph;
  p.binder->mark_unmemoised(marked);
  for (const GraphNode& n : marked.nodes) CHECK(n.memoised == (n.name == "train"));
  MemoCache cache;
  const auto rows = sweep_all(p, 1, cache);
  REQUIRE(rows.size() == 6);
  CHECK(cache.size() == 1);  // the masses, once
  for (const CaseResult& r : rows) {
    REQUIRE(r.failure == CaseFailure::none);
    CHECK(r.reused == (r.index == 0 ? 0 : 1));
    std::vector<CaseValue> scratch;
    const std::vector<CaseValue>& c = p.table.row(r.index, scratch);  // a grid of ranges: kept as numbers
    const RunResult alone = run_yaml(yaml, project_registry(),
                                     {parse_override("rpm=" + c[0].written()), parse_override("cam.max_lift=" + c[1].written())});
    CHECK(r.outputs[0].as_scalar() == scalar_output(alone, "ta.time_area"));
    CHECK(r.outputs[1].as_scalar() == scalar_output(alone, "valve.max_acceleration"));
    CHECK(r.outputs[2].as_scalar() == scalar_output(alone, "train.mass_without_spring"));
  }
}

TEST_CASE("sweep budget: a cases file's estimate equals the same cases kept as rows of text", "[sweep][bounds]") {
  // The estimate binds a value that apply() writes as a number without its text, any other with
  // it: words (a choice), values refused (another dimension, out of range) and integers.
  const std::string yaml = estimated_scene;
  const auto dir = std::filesystem::temp_directory_path() / ("mechgraph_estimate_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const auto file = dir / "cases.csv";
  {
    std::ofstream out(file);
    out << "len [mm],c.mode,s.gain,q.points\n";
    const char* modes[] = {"plain", "fancy", "odd"};
    const char* lengths[] = {"3", "2.5 mm", "0.004 m", "3 s"};
    for (int i = 0; i < 5000; ++i)  // more than one chunk of the parallel estimate
      out << lengths[i % 4] << "," << modes[i % 3] << "," << (i % 7 == 0 ? "-1" : "1.5") << "," << (i % 5 == 0 ? 100000 : 10 + i % 9) << "\n";
  }
  Prepared numbers = prepare(yaml, read_cases_csv(file));
  std::filesystem::remove_all(dir);
  REQUIRE(numbers.table.cases.empty());  // kept as numbers with their texts
  CaseTable rows_table;
  rows_table.variables = numbers.table.variables;
  for (std::size_t i = 0; i < numbers.table.size(); ++i) {
    std::vector<CaseValue> row;
    rows_table.cases.push_back(numbers.table.row(i, row));
  }
  Prepared rows = prepare(yaml, std::move(rows_table));
  std::vector<std::size_t> all(numbers.table.size());
  std::iota(all.begin(), all.end(), std::size_t{0});
  for (unsigned threads : {1u, 2u}) {
    const SweepEstimate a = estimate_cases(numbers.graph, *numbers.binder, numbers.table, all, threads);
    const SweepEstimate b = estimate_cases(rows.graph, *rows.binder, rows.table, all, threads);
    CHECK(a.total.work == b.total.work);
    CHECK(a.largest_memory == b.largest_memory);
    CHECK(a.largest_case == b.largest_case);
  }
  // Cases refused before they run (a word not among the choices, a time, a negative gain) have
  // no work: the file's work is below that of its cases bound alike with none refused.
  const SweepEstimate e = estimate_cases(numbers.graph, *numbers.binder, numbers.table, all);
  std::size_t bound = 0;
  for (std::size_t c : all) {
    Graph copy = rows.graph;
    try {
      rows.binder->apply(rows.binder->bind(copy), copy, rows.table.cases[c]);
      ++bound;
    } catch (const SceneError&) {
    }
  }
  CHECK(bound > 0);
  CHECK(bound < all.size() / 2);
  CHECK(e.total.work > 0);
}

TEST_CASE("sweep budget: the per-case estimate equals each case estimated alone (second method)", "[sweep][bounds]") {
  // Types without a forecast (the conventions): a real number changes nothing they count, an
  // integer does; RepeatedNodeEstimate keeps the first and recounts the second.
  const std::string yaml = estimated_scene;
  // 4800 cases: more than one chunk of the parallel estimate.
  Prepared p = prepare(yaml, make_grid({parse_vary("len=1mm:4mm:600"), parse_vary("s.gain=1,3"), parse_vary("q.points=10,100000"),
                                        parse_vary("t.points=7,9")}));
  std::vector<std::size_t> all(p.table.size());
  std::iota(all.begin(), all.end(), std::size_t{0});
  const SweepEstimate e = estimate_cases(p.graph, *p.binder, p.table, all);
  for (unsigned threads : {2u, 3u}) {  // the same figures on any number of threads
    const SweepEstimate on = estimate_cases(p.graph, *p.binder, p.table, all, threads);
    CHECK(on.total.work == e.total.work);
    CHECK(on.largest_memory == e.largest_memory);
    CHECK(on.largest_case == e.largest_case);
  }
  double work = 0, largest_memory = 0, largest_work = -1;
  std::size_t largest_case = 0;
  for (std::size_t c : all) {
    Graph copy = p.graph;
    p.binder->apply(p.binder->bind(copy), copy, p.table.cases[c]);
    const WorkEstimate alone = estimate_work(copy);
    work += alone.work;
    largest_memory = std::max(largest_memory, alone.memory);
    if (alone.work > largest_work) largest_work = alone.work, largest_case = c;
  }
  CHECK_THAT(e.total.work, WithinRel(work, 1e-12));
  CHECK_THAT(e.largest_memory, WithinRel(largest_memory, 1e-12));
  CHECK(e.largest_case == largest_case);
  CHECK(p.table.cases[e.largest_case][2].text == "100000");
}
