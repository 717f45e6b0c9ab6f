// mechgraph bench's engine: the knob ladders, each knob's own converged reference and its floor,
// knobs that cannot act, the Monte Carlo spread over seeds, the advice and the work reported.
#include "test_support.hpp"

#include <mechgraph/errors.hpp>
#include <mechgraph/evaluator.hpp>
#include <mechgraph/knob_bench.hpp>

#include <yaml-cpp/yaml.h>

#include <catch2/catch.hpp>

#include <cmath>
#include <set>

using namespace mechgraph;
using namespace mechgraph::testing;
using Catch::Matchers::Contains;
using Catch::Matchers::WithinAbs;
using Catch::Matchers::WithinRel;

namespace {
Graph scene(const std::string& name, const std::vector<Override>& overrides = {}) {
  return build_graph(load_scene(std::string(MECHGRAPH_SOURCE_DIR) + "/scenes/" + name), project_registry(), overrides);
}
Graph study(const std::vector<Override>& overrides) { return scene("valvetrain_cams.yaml", overrides); }

const KnobStudy& knob_of(const KnobBench& bench, const std::string& node, const std::string& knob) {
  for (const KnobStudy& k : bench.knobs)
    if (k.node == node && k.knob == knob) return k;
  FAIL("no study of " << node << "." << knob);
  throw std::logic_error("unreachable");
}

std::vector<KnobTrial> trials_of(const KnobBench& bench, const KnobStudy& k) {
  return {bench.trials.begin() + static_cast<std::ptrdiff_t>(k.first_trial),
          bench.trials.begin() + static_cast<std::ptrdiff_t>(k.first_trial + k.trial_count)};
}

double evaluated(const Graph& graph, const std::string& label) {
  MemoCache cache;
  return scalar_output(evaluate(graph, cache), label);
}
}  // namespace

TEST_CASE("bench: the rectangle sum converges at second order against its own converged reference", "[bench]") {
  KnobBenchOptions options;
  options.node = "ta_arc";
  options.repeats = 1;
  const Graph rectangle = study({parse_override("ta_arc.method=rectangle")});
  const KnobBench bench = bench_knobs(rectangle, options);
  const KnobStudy& step = knob_of(bench, "ta_arc", "step");
  // The step halved until successive sums agree to 1e-3 x the tolerance (1e-9).
  CHECK(step.not_measured.empty());
  CHECK(step.converged);
  CHECK(step.floor <= 1e-12);
  CHECK(step.reference_steps >= 3);
  std::vector<double> step_errors;
  int defaults = 0;
  for (const KnobTrial& t : trials_of(bench, step)) {
    CHECK(t.failure.empty());
    CHECK(t.node == "ta_arc");
    CHECK(t.work.at("evaluations") > 0);
    CHECK(t.reference_floor == step.floor);
    CHECK_FALSE(t.below_floor);
    step_errors.push_back(t.max_relative_error);
    defaults += t.is_default ? 1 : 0;
    if (t.setting == "1 deg") {
      // Independent: the rectangle sum at 1 deg against the adaptive Gauss-Kronrod integral.
      const double exact = evaluated(study({}), "ta_arc.time_area");
      const double sum = evaluated(rectangle, "ta_arc.time_area");
      CHECK_THAT(t.errors.at("ta_arc.time_area"), WithinRel(std::abs(sum - exact) / exact, 1e-4) || WithinAbs(std::abs(sum - exact) / exact, 1e-12));
    }
  }
  CHECK(defaults == 1);
  REQUIRE(step_errors.size() == 7);  // default x 2^-3 .. x 2^3
  // The three-arc law with lash has kinks in the flow area's slope: the sum is second order.
  for (std::size_t i = 1; i < step_errors.size(); ++i) {
    const double ratio = step_errors[i - 1] / step_errors[i];
    CHECK(ratio > 2.5);
    CHECK(ratio < 6.0);
  }
  // The method: the rectangle sum against the first choice (exact), whose floor is how far it
  // moves when the step and the tolerance are tightened.
  const KnobStudy& method = knob_of(bench, "ta_arc", "method");
  CHECK(method.reference == "exact");
  CHECK(method.floor < 1e-12);
  for (const KnobTrial& t : trials_of(bench, method)) {
    if (t.setting == "exact") CHECK(t.max_relative_error == 0.0);
    if (t.setting == "rectangle") CHECK_THAT(t.max_relative_error, WithinRel(step_errors[3], 1e-3));
  }
  // Under the rectangle sum the quadrature's tolerance cannot act: not measured, no advice.
  const KnobStudy& tolerance = knob_of(bench, "ta_arc", "tolerance");
  CHECK(tolerance.trial_count == 0);
  CHECK(tolerance.not_measured == "not measured: tolerance does not change any output or the work in this scene");
}

TEST_CASE("bench: the integrator's tolerance ladder falls with the tolerance, not flat at the reference's own error", "[bench]") {
  KnobBenchOptions options;
  options.node = "elastic";
  options.repeats = 1;
  options.steps = 2;
  const KnobBench bench = bench_knobs(scene("valvetrain_dynamics.yaml"), options);
  const KnobStudy& tolerance = knob_of(bench, "elastic", "tolerance");
  // Tightened /4 a step for the 8 steps allowed (1e-8 / 4^8), the other knobs at the scene's.
  CHECK(tolerance.reference == "1.52588e-13");
  CHECK(tolerance.reference_steps == 8);
  CHECK_THAT(tolerance.stopped, Contains("not converged (the step limit of 8 steps)"));
  REQUIRE(std::isfinite(tolerance.floor));
  const auto trials = trials_of(bench, tolerance);
  REQUIRE(trials.size() == 5);  // 4e-8 .. 2.5e-9
  for (std::size_t i = 1; i < trials.size(); ++i) {
    INFO(trials[i].setting);
    CHECK(trials[i].max_relative_error < trials[i - 1].max_relative_error);
  }
  // The error follows the tolerance: x16 tighter is several times more accurate (the reference
  // with every knob tightened gave 1.28e-4 at every rung: curve_points' error, not the tolerance's).
  CHECK(trials.front().max_relative_error / trials.back().max_relative_error > 4.0);
  CHECK(trials.back().max_relative_error < 1e-5);
  CHECK(tolerance.floor < 1e-2 * trials.back().max_relative_error);
  for (const KnobTrial& t : trials) CHECK_THAT(t.worst_output, Contains("elastic."));
  // coils belongs to spring_surge, off for this node: not measured, said so, no advice.
  const KnobStudy& coils = knob_of(bench, "elastic", "coils");
  CHECK(coils.trial_count == 0);
  CHECK(coils.not_measured == "not measured: coils belongs to the effect spring_surge, which is off for this node");
  KnobBench copy = bench;
  for (const KnobAdvice& a : advise_knobs(copy, 1e-3)) {
    if (a.knob == "coils") {
      CHECK_FALSE(a.recommended);
      CHECK(a.text == coils.not_measured);
    }
    if (a.knob == "tolerance") {
      REQUIRE(a.recommended);
      CHECK(error_bound(copy.trials[*a.recommended]) <= 1e-3);
    }
  }
}

TEST_CASE("bench: a node without elastic_drive measures only what acts, the integrator's knobs say why not", "[bench]") {
  KnobBenchOptions options;
  options.node = "rigid";
  options.repeats = 1;
  options.steps = 1;
  const KnobBench bench = bench_knobs(scene("valvetrain_dynamics.yaml"), options);
  for (const char* knob : {"tolerance", "integrator"}) {
    INFO(knob);
    CHECK(knob_of(bench, "rigid", knob).not_measured ==
          "not measured: " + std::string(knob) + " belongs to the effect elastic_drive, which is off for this node");
  }
  CHECK(knob_of(bench, "rigid", "curve_points").not_measured.empty());
  CHECK(knob_of(bench, "rigid", "curve_points").trial_count == 3);
}

TEST_CASE("bench: a reference the budget stops is reported as such, an unknown floor recommends nothing", "[bench]") {
  KnobBenchOptions options;
  options.node = "elastic";
  options.repeats = 1;
  options.steps = 1;
  options.max_work = 6e3;  // less than the reference's next steps need (under 3e4 it now converges)
  const KnobBench limited = bench_knobs(scene("valvetrain_dynamics.yaml"), options);
  const KnobStudy& points = knob_of(limited, "elastic", "curve_points");
  CHECK_FALSE(points.converged);
  CHECK_THAT(points.stopped, Contains("--max-work"));
  // No time at all for a reference: how converged it is, is not known, and nothing is recommended.
  options.max_work = 1e9;
  options.reference_seconds = 0.0;
  KnobBench untimed = bench_knobs(scene("valvetrain_dynamics.yaml"), options);
  const KnobStudy& tolerance = knob_of(untimed, "elastic", "tolerance");
  CHECK(tolerance.reference_steps == 0);
  CHECK(std::isinf(tolerance.floor));
  CHECK_THAT(tolerance.stopped, Contains("--reference-time"));
  for (const KnobAdvice& a : advise_knobs(untimed, 1.0))
    if (a.knob == "tolerance") {
      CHECK_FALSE(a.recommended);
      CHECK_THAT(a.text, Contains("how far the reference is converged is not known"));
    }
}

TEST_CASE("bench: the Monte Carlo error is the spread over seeds and falls as 1/sqrt(n) within its uncertainty", "[bench]") {
  KnobBenchOptions options;
  options.node = "chain";
  options.repeats = 1;
  options.steps = 1;
  options.seeds = 32;
  const Graph graph = scene("backlash_chain.yaml", {parse_override("chain.samples=20000")});
  REQUIRE(is_monte_carlo(graph.nodes[*graph.find("chain")]));
  CHECK_FALSE(is_monte_carlo(scene("valvetrain_dynamics.yaml").nodes[0]));
  const KnobBench bench = bench_knobs(graph, options);
  const KnobStudy& samples = knob_of(bench, "chain", "samples");
  CHECK(samples.monte_carlo);
  CHECK(samples.seeds == 32);
  const auto trials = trials_of(bench, samples);
  REQUIRE(trials.size() == 3);  // 10000, 20000, 40000 samples
  const double u = 1.0 / std::sqrt(2.0 * 31.0);  // relative standard error of a standard deviation
  for (const KnobTrial& t : trials) {
    INFO(t.setting);
    REQUIRE(t.failure.empty());
    CHECK_THAT(t.error_uncertainty, WithinRel(u * t.max_relative_error, 1e-12));
    CHECK(t.reference_floor == 0.0);
    // Outputs the seed does not touch have no spread; uncertainties are not compared.
    CHECK(t.errors.at("chain.rod_backlash_max") == 0.0);
    CHECK(t.errors.at("chain.lever_arm") == 0.0);
    CHECK_FALSE(t.errors.count("chain.mc_mean_error"));
    CHECK(t.errors.at("chain.rod_backlash_mc_mean") > 0.0);
  }
  // Falling within the uncertainties: no rise beyond two standard errors of the difference.
  for (std::size_t i = 1; i < trials.size(); ++i)
    CHECK(trials[i].max_relative_error <
          trials[i - 1].max_relative_error + 2.0 * std::hypot(trials[i].error_uncertainty, trials[i - 1].error_uncertainty));
  // Over a 4x step, 1/sqrt(n) halves the spread: the ratio is 2 within three standard errors.
  const double ratio = trials[0].max_relative_error / trials[2].max_relative_error;
  CHECK(std::abs(ratio - 2.0) < 3.0 * ratio * std::sqrt(2.0) * u);
  // Independent: the spread of the mean over seeds is the standard error the node states for one
  // run, sigma / sqrt(n), relative to the mean (within the spread's own uncertainty).
  for (const KnobTrial& t : trials) {
    INFO(t.setting);
    Graph g = scene("backlash_chain.yaml", {parse_override("chain.samples=" + t.setting)});
    const std::size_t chain = *g.find("chain");
    for (const char* port : {"rod_backlash_mc_mean", "mc_mean_error"})
      g.outputs.push_back({chain, port, g.nodes[chain].info().find_output(port), std::string("chain.") + port});
    mark_wanted_outputs(g);
    MemoCache cache;
    const RunResult r = evaluate(g, cache);
    const double stated = scalar_output(r, "chain.mc_mean_error") / scalar_output(r, "chain.rod_backlash_mc_mean");
    CHECK_THAT(t.errors.at("chain.rod_backlash_mc_mean"), WithinRel(stated, 3.0 * u));
  }
}

TEST_CASE("bench: every needed node with knobs is studied, each knob once", "[bench]") {
  KnobBenchOptions options;
  options.repeats = 1;
  options.steps = 1;
  const Graph graph = study({});
  const KnobBench bench = bench_knobs(graph, options);
  std::set<std::string> nodes;
  std::set<std::pair<std::string, std::string>> knobs;
  for (const KnobStudy& k : bench.knobs) {
    nodes.insert(k.node);
    CHECK(knobs.insert({k.node, k.knob}).second);
    if (!k.not_measured.empty()) CHECK(k.trial_count == 0);
    // The exact time-area's step cannot act (it is the rectangle sum's).
    if (k.knob == "step" && k.type == "valvetrain.time_area") CHECK_THAT(k.not_measured, Contains("does not change any output"));
  }
  std::size_t with_knobs = 0;
  for (std::size_t i : graph.order)
    for (const ParamSpec& p : graph.nodes[i].info().params)
      if (p.knob && graph.nodes[i].params.has(p.name)) {
        ++with_knobs;
        break;
      }
  CHECK(with_knobs == 21);
  CHECK(nodes.size() == with_knobs);
  std::size_t trials = 0;
  for (const KnobStudy& k : bench.knobs) trials += k.trial_count;
  CHECK(trials == bench.trials.size());
}

TEST_CASE("bench: unknown nodes and nodes without knobs are errors", "[bench]") {
  KnobBenchOptions options;
  options.node = "ta_kurtz";
  CHECK_THROWS_WITH(bench_knobs(study({}), options), Contains("did you mean 'ta_kurz'"));
  options.node = "a";
  CHECK_THROWS_WITH(bench_knobs(graph_from("nodes: { a: { type: test.constant, params: { value: 1 mm } } }\noutputs: [a.out]\n"),
                                options),
                    Contains("has no accuracy knobs"));
}

namespace {
KnobTrial trial(const std::string& setting, double seconds, double error, bool is_default = false) {
  KnobTrial t;
  t.node = "n";
  t.type = "t";
  t.knob = "samples";
  t.setting = setting;
  t.seconds = seconds;
  t.max_relative_error = error;
  t.is_default = is_default;
  return t;
}
KnobBench one_knob(std::vector<KnobTrial> trials, double floor = 0.0, bool monte_carlo = false) {
  KnobBench bench;
  KnobStudy k;
  k.node = "n";
  k.type = "t";
  k.knob = "samples";
  k.floor = floor;
  k.monte_carlo = monte_carlo;
  k.trial_count = trials.size();
  for (KnobTrial& t : trials) {
    t.reference_floor = floor;
    t.below_floor = t.max_relative_error < floor;
  }
  bench.trials = std::move(trials);
  bench.knobs.push_back(k);
  return bench;
}
}  // namespace

TEST_CASE("bench advice: Pareto front, the cheapest setting within the tolerance, a default far off the front", "[bench]") {
  std::vector<KnobTrial> trials = {trial("8", 1.0, 1e-6), trial("16", 2.0, 1e-10), trial("32", 4.0, 1e-10, true),
                                   trial("64", 8.0, 1e-14), trial("128", 9.0, 1e-12)};
  trials.push_back(trial("256", 0.0, 0.0));
  trials.back().failure = "did not converge";
  KnobBench bench = one_knob(trials);
  const auto advice = advise_knobs(bench, 1e-9);
  REQUIRE(advice.size() == 1);
  CHECK(bench.trials[0].on_front);
  CHECK(bench.trials[1].on_front);
  CHECK_FALSE(bench.trials[2].on_front);  // as accurate as 16 and slower
  CHECK(bench.trials[3].on_front);
  CHECK_FALSE(bench.trials[4].on_front);  // 64 is faster and more accurate
  CHECK_FALSE(bench.trials[5].on_front);  // failed
  REQUIRE(advice[0].recommended);
  CHECK(*advice[0].recommended == 1);
  CHECK(advice[0].current_off_front);  // 16 is as accurate in half the time
  CHECK_THAT(advice[0].text, Contains("within 1e-09: samples = 16") && Contains("far off the front"));
  const auto strict = advise_knobs(bench, 1e-15);
  CHECK_FALSE(strict[0].recommended);
  CHECK_THAT(strict[0].text, Contains("no setting on the ladder reaches 1e-15; the most accurate is samples = 64"));
}

TEST_CASE("bench advice: recommended only where error + uncertainty + the reference's floor is within the tolerance", "[bench]") {
  // A reference converged to 3e-9: settings whose errors are below 1e-9 still cannot be said to
  // be within 1e-9; within 1e-8 the cheapest whose error + floor fits is.
  KnobBench floored = one_knob({trial("8", 1.0, 6e-9), trial("16", 2.0, 4e-9), trial("32", 4.0, 1e-10, true)}, 3e-9);
  CHECK(floored.trials[2].below_floor);
  CHECK(error_bound(floored.trials[1]) == 4e-9 + 3e-9);
  auto advice = advise_knobs(floored, 1e-9);
  CHECK_FALSE(advice[0].recommended);
  CHECK_THAT(advice[0].text, Contains("the most accurate is samples = 32 (error < 3e-09") && Contains("converged only to 3e-09"));
  advice = advise_knobs(floored, 8e-9);
  REQUIRE(advice[0].recommended);
  CHECK(*advice[0].recommended == 1);  // 8: 6e-9 + 3e-9 > 8e-9
  // Monte Carlo: the spread's uncertainty counts.
  std::vector<KnobTrial> spread = {trial("1000", 1.0, 0.8e-2), trial("4000", 4.0, 0.4e-2)};
  spread[0].error_uncertainty = 0.3e-2;
  spread[1].error_uncertainty = 0.15e-2;
  KnobBench random = one_knob(spread, 0.0, true);
  advice = advise_knobs(random, 1e-2);
  REQUIRE(advice[0].recommended);
  CHECK(*advice[0].recommended == 1);
  CHECK_THAT(advice[0].text, Contains("error 0.004 +- 0.0015"));
}

TEST_CASE("bench: the work of the ladders is estimated before anything runs", "[bench]") {
  const Graph graph = scene("backlash_chain.yaml");
  KnobBenchOptions options;
  options.steps = 1;
  options.repeats = 1;
  options.seeds = 8;
  const WorkEstimate e = estimate_bench_work(graph, options);
  // Only chain has a knob: its own estimate (200000 samples, 40 bins, its lists) x one knob x
  // (2^2 + 1) rungs x 8 seeds.
  Graph alone = graph;
  alone.order = {*graph.find("chain")};
  const double chain = estimate_work(alone).work;
  CHECK(chain > 200000.0);
  CHECK_THAT(e.work, WithinRel(chain * 5.0 * 8.0, 1e-12));
  WorkBudget small;
  small.max_work = 1e6;
  CHECK_THROWS_WITH(check_work_budget(graph, e, small, 1, false), Contains("chain.samples = 200000 x 40 evaluations"));
}
