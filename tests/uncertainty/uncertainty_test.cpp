// Uncertainty studies (docs/methods/uncertainty.md): distributions, designs and estimators against
// closed forms; the Ishigami function and a linear model through a graph against their Sobol'
// indices; the same answers on 1, 2 or 5 threads and from shards.
#include "test_support.hpp"

#include <mechgraph/host/study_run.hpp>
#include <mechgraph/host/sweep_rows.hpp>
#include <mechgraph/sweep/case_binder.hpp>
#include <mechgraph/sweep/sweep_runner.hpp>

#include <mechgraph/errors.hpp>
#include <mechgraph/uncertainty/sample_design.hpp>
#include <mechgraph/uncertainty/study_answers.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <numeric>
#include <sstream>

using namespace mechgraph;
using Catch::Matchers::Contains;

namespace {

const PluginRegistry& uq_registry() {
  static const PluginRegistry registry = [] {
    PluginRegistry r;
    r.load_file(testing::test_plugin("test_uq"));
    return r;
  }();
  return registry;
}

StudySpec study_of(const std::string& yaml, const PluginRegistry& registry = uq_registry()) {
  const SceneSpec scene = parse_scene(yaml, "study.yaml");
  return host::study_spec_of(scene, registry);
}

// A whole study in process: the scene's cases on `threads` workers, analysed.
std::unique_ptr<host::StudyOutcome> run_study(const std::string& yaml, unsigned threads, const PluginRegistry& registry = uq_registry()) {
  return host::run_scene_study(parse_scene(yaml, "study.yaml"), registry, {}, std::nullopt, "", "", "", std::nullopt, WorkBudget{}, threads,
                              nullptr);
}
using InProcess = std::unique_ptr<host::StudyOutcome>;

std::string slurp_text(const std::string& file) {
  std::ifstream in(file);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

const char* const uniform_pi = "{ uniform: { lower: -3.141592653589793, upper: 3.141592653589793 } }";

std::string ishigami_scene(const std::string& method, std::size_t samples, const std::string& extra = "") {
  return std::string("params: { x1: 0, x2: 0, x3: 0 }\nuncertainty:\n  method: ") + method + "\n  samples: " + std::to_string(samples) +
         "\n  seed: 5\n  sensitivity: true\n  bootstrap: 50\n  parameters:\n    x1: " + uniform_pi + "\n    x2: " + uniform_pi +
         "\n    x3: " + uniform_pi + "\n" + extra +
         "nodes:\n  f: { type: test.ishigami, params: { x1: $x1, x2: $x2, x3: $x3 } }\noutputs: [f.y]\n";
}

}  // namespace

TEST_CASE("Distributions: quantiles, moments, normal by tolerance and Cp", "[uncertainty]") {
  const StudySpec spec = study_of(R"(uncertainty:
  parameters:
    a: { normal: { mean: 10 mm, sigma: 0.1 mm } }
    b: { normal: { nominal: 10 mm, tolerance: 0.03 mm, cp: 1.5 } }
    c: { normal: { lower: 9.97 mm, upper: 10.03 mm } }
    d: { uniform: { lower: 1, upper: 3 } }
    e: { triangular: { lower: 0, mode: 1, upper: 4 } }
    f: { normal: { mean: 0, sigma: 1 }, truncate: { lower: -1, upper: 2 } }
nodes: {}
)");
  REQUIRE(spec.parameters.size() == 6);
  const Marginal& a = spec.parameters[0].marginal;
  CHECK(a.dimension == dim::length);
  CHECK_THAT(a.quantile(0.5), Catch::Matchers::WithinRel(0.010, 1e-14));
  CHECK_THAT(a.quantile(standard_normal_cdf(1.0)), Catch::Matchers::WithinRel(0.0101, 1e-12));
  // Cp = 2 t / 6 sigma: sigma = 0.03 mm / (3 x 1.5).
  CHECK_THAT(spec.parameters[1].marginal.b, Catch::Matchers::WithinRel(0.03e-3 / 4.5, 1e-14));
  CHECK_THAT(spec.parameters[2].marginal.b, Catch::Matchers::WithinRel(0.06e-3 / 6, 1e-12));
  CHECK_THAT(spec.parameters[3].marginal.quantile(0.25), Catch::Matchers::WithinRel(1.5, 1e-15));
  const Marginal& e = spec.parameters[4].marginal;
  CHECK_THAT(e.mean(), Catch::Matchers::WithinRel(5.0 / 3.0, 1e-15));
  for (double u : {0.01, 0.2, 0.25, 0.7, 0.99}) CHECK_THAT(e.cdf(e.quantile(u)), Catch::Matchers::WithinAbs(u, 1e-14));
  const Marginal& f = spec.parameters[5].marginal;
  CHECK(f.quantile(1e-9) >= -1.0);
  CHECK(f.quantile(1 - 1e-9) <= 2.0);
  // The truncated standard normal's mean: (phi(a) - phi(b)) / (Phi(b) - Phi(a)).
  const auto phi = [](double x) { return std::exp(-0.5 * x * x) / std::sqrt(2 * M_PI); };
  const double exact = (phi(-1) - phi(2)) / (standard_normal_cdf(2) - standard_normal_cdf(-1));
  CHECK_THAT(f.mean(), Catch::Matchers::WithinAbs(exact, 1e-6));

  // Far in the upper tail (lower at +7 and +9 sigma, where F(lower) is 1 - 1.3e-12 and 1 exactly):
  // every quantile finite and inside, the mean against the closed form mu + sigma phi(z) / Q(z),
  // the cdf back to u. A spread in degC is a width: 5 degC of sigma is 5 K, not 278.15 K.
  const StudySpec tail = study_of(R"(uncertainty:
  parameters:
    g: { normal: { mean: 30 um, sigma: 3 um }, truncate: { lower: 51 um } }
    h: { normal: { mean: 30 um, sigma: 3 um }, truncate: { lower: 57 um, upper: 60 um } }
    t: { normal: { mean: 80 degC, sigma: 5 degC } }
    k: { normal: { nominal: 80 degC, tolerance: 15 degC } }
nodes: {}
)");
  for (const double z : {7.0, 9.0}) {
    const Marginal& m = tail.parameters[z == 7.0 ? 0 : 1].marginal;
    for (const double u : {1e-12, 0.25, 0.5, 1 - 1e-9, 1 - 1e-16}) {
      const double x = m.quantile(u);
      CHECK(std::isfinite(x));
      CHECK(x >= *m.lower);
      if (m.upper) CHECK(x <= *m.upper);
    }
    for (const double u : {0.1, 0.5, 0.9}) CHECK_THAT(m.cdf(m.quantile(u)), Catch::Matchers::WithinAbs(u, 1e-9));
    // Lower at z sigma, upper (h) 1 sigma higher: mean = mu + sigma (phi(z) - phi(z + 1)) / (Q(z) - Q(z + 1)).
    const double q_low = 0.5 * std::erfc(z / std::sqrt(2.0)), q_high = z == 7.0 ? 0.0 : 0.5 * std::erfc((z + 1) / std::sqrt(2.0));
    const double phi_high = z == 7.0 ? 0.0 : phi(z + 1);
    const double exact_tail = 30e-6 + 3e-6 * (phi(z) - phi_high) / (q_low - q_high);
    CHECK_THAT(m.mean(), Catch::Matchers::WithinRel(exact_tail, 1e-6));
  }
  CHECK_THAT(tail.parameters[2].marginal.a, Catch::Matchers::WithinRel(353.15, 1e-14));
  CHECK_THAT(tail.parameters[2].marginal.b, Catch::Matchers::WithinRel(5.0, 1e-14));
  CHECK_THAT(tail.parameters[3].marginal.b, Catch::Matchers::WithinRel(5.0, 1e-14));  // 15 K / 3 Cp, Cp 1
}

TEST_CASE("Distributions: errors name file:line:column and the valid names", "[uncertainty]") {
  const auto error_of = [](const std::string& yaml) {
    try {
      study_of(yaml);
    } catch (const SceneError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  CHECK_THAT(error_of("uncertainty:\n  parameters:\n    a: { normal: { mean: 1 mm, sigma: 2 s } }\nnodes: {}\n"),
             Contains("study.yaml:3:") && Contains("sigma is time") && Contains("length"));
  CHECK_THAT(error_of("uncertainty:\n  parameters:\n    a: { normal: { mean: 1 mm, sigm: 2 mm } }\nnodes: {}\n"),
             Contains("study.yaml:3:") && Contains("sigma"));
  CHECK_THAT(error_of("uncertainty:\n  method: sobl\n  parameters:\n    a: { uniform: { lower: 0, upper: 1 } }\nnodes: {}\n"),
             Contains("study.yaml:2:11") && Contains("sobol"));
  CHECK_THAT(error_of("uncertainty:\n  parameters:\n    a: { uniform: { lower: 0, upper: 1 } }\n    b: { uniform: { lower: 0, upper: 1 } }\n"
                      "  correlations: [[a, c, 0.5]]\nnodes: {}\n"),
             Contains("study.yaml:5:22") && Contains("'c'"));
  CHECK_THAT(error_of("uncertainty:\n  sensitivity: true\n  parameters:\n    a: { uniform: { lower: 0, upper: 1 } }\n    b: { uniform: { lower: 0, upper: 1 } }\n"
                      "  correlations: [[a, b, 0.5]]\nnodes: {}\n"),
             Contains("independent"));
  // A truncation past what a double holds (1000 sigma out) keeps nothing: refused at its line.
  CHECK_THAT(error_of("uncertainty:\n  parameters:\n    a: { normal: { mean: 0 mm, sigma: 1 um }, truncate: { lower: 1 mm } }\nnodes: {}\n"),
             Contains("study.yaml:3:") && Contains("keeps no probability"));
  // A quantile level given twice would print its row twice: refused at the second.
  CHECK_THAT(error_of("uncertainty:\n  quantiles: [0.5, 0.9, 0.5]\n  parameters:\n    a: { uniform: { lower: 0, upper: 1 } }\nnodes: {}\n"),
             Contains("study.yaml:2:") && Contains("0.5 is given twice"));
  // Widths a double cannot hold: the draws would overflow. Refused at their lines.
  CHECK_THAT(error_of("uncertainty:\n  parameters:\n    a: { uniform: { lower: -1e308, upper: 1e308 } }\nnodes: {}\n"),
             Contains("study.yaml:3:") && Contains("upper - lower is beyond the range of a double"));
  CHECK_THAT(error_of("uncertainty:\n  parameters:\n    a: { triangular: { lower: -1e308, upper: 1e308 } }\nnodes: {}\n"),
             Contains("study.yaml:3:") && Contains("beyond the range of a double"));
  CHECK_THAT(error_of("uncertainty:\n  parameters:\n    a: { normal: { lower: -1e308, upper: 1e308 } }\nnodes: {}\n"),
             Contains("study.yaml:3:") && Contains("beyond the range of a double"));
  CHECK_THAT(error_of("uncertainty:\n  parameters:\n    a: { normal: { mean: 0, sigma: 5e307 } }\nnodes: {}\n"),
             Contains("study.yaml:3:") && Contains("9 sigma is beyond the range of a double"));
  CHECK(error_of("uncertainty:\n  parameters:\n    a: { uniform: { lower: -1e300, upper: 1e300 } }\nnodes: {}\n") == "no error");
  // Ends near the largest double: the middle is taken without overflowing (a triangular's default
  // mode, a normal's mean), not read through a missing mode; the normal's draws would overflow.
  CHECK(error_of("uncertainty:\n  parameters:\n    a: { triangular: { lower: 1e308, upper: 1.7e308 } }\nnodes: {}\n") == "no error");
  CHECK_THAT(error_of("uncertainty:\n  parameters:\n    a: { normal: { lower: 1e308, upper: 1.7e308 } }\nnodes: {}\n"),
             Contains("study.yaml:3:") && Contains("9 sigma is beyond the range of a double"));
  // A spread below the spacing of doubles at the mean: every draw would be the mean.
  CHECK_THAT(error_of("uncertainty:\n  parameters:\n    a: { normal: { mean: 1e20, sigma: 1 } }\nnodes: {}\n"),
             Contains("study.yaml:3:") && Contains("below the spacing of doubles"));
  CHECK(error_of("uncertainty:\n  parameters:\n    a: { normal: { mean: 1e20, sigma: 1e6 } }\nnodes: {}\n") == "no error");
  // A name that reaches no parameter, and a distribution of the wrong dimension, at its line.
  const std::string scene = "params: { x1: 0 mm, x2: 0 mm, x3: 0 mm }\nuncertainty:\n  parameters:\n    NAME: DIST\n"
                            "nodes:\n  f: { type: test.linear, params: { x1: $x1, x2: $x2, x3: $x3 } }\noutputs: [f.y]\n";
  const auto graph_error = [&](const std::string& name, const std::string& dist) {
    std::string yaml = scene;
    yaml.replace(yaml.find("NAME"), 4, name);
    yaml.replace(yaml.find("DIST"), 4, dist);
    try {
      run_study(yaml, 1);
    } catch (const SceneError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  CHECK_THAT(graph_error("x4", "{ normal: { mean: 1 mm, sigma: 1 um } }"), Contains("study.yaml:4:5") && Contains("x1"));
  CHECK_THAT(graph_error("f.x2", "{ normal: { mean: 1 s, sigma: 1 ms } }"), Contains("study.yaml:4:5") && Contains("length"));
  // A limit on an output the study does not read, at its line, with the outputs it has.
  std::string limits = scene;
  limits.replace(limits.find("NAME"), 4, "x1");
  limits.replace(limits.find("DIST"), 4, "{ normal: { mean: 1 mm, sigma: 1 um } }\n  limits: { f.z: { upper: 1 mm } }");
  try {
    run_study(limits, 1);
    FAIL("a limit on f.z accepted");
  } catch (const SceneError& e) {
    CHECK_THAT(std::string(e.what()), Contains("study.yaml:5:13") && Contains("f.y"));
  }
}

TEST_CASE("Studies: limits and thresholds in their output's dimension, refused before any case runs", "[uncertainty]") {
  // f.y = x1 + x2 + x3 is a length (shown in mm). A bare number would be read in SI (1 m), a
  // time or a mass is no length: each is refused at its line, naming the output's dimension.
  const std::string scene = "params: { x1: 0 mm, x2: 0 mm, x3: 0 mm }\nuncertainty:\n  samples: 8\n  parameters:\n"
                            "    x1: { normal: { mean: 1 mm, sigma: 1 um } }\nEXTRA"
                            "nodes:\n  f: { type: test.linear, params: { x1: $x1, x2: $x2, x3: $x3 } }\noutputs: [f.y]\n";
  const auto error_of = [&](const std::string& extra, const std::vector<Override>& overrides = {}) {
    std::string yaml = scene;
    yaml.replace(yaml.find("EXTRA"), 5, extra);
    try {
      host::run_scene_study(parse_scene(yaml, "study.yaml"), uq_registry(), overrides, std::nullopt, "", "", "", std::nullopt,
                            WorkBudget{}, 1, nullptr);
    } catch (const SceneError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  CHECK_THAT(error_of("  limits: { f.y: { upper: 2 } }\n"),
             Contains("study.yaml:6:13") && Contains("bare number") && Contains("length") && Contains("mm"));
  CHECK_THAT(error_of("  limits: { f.y: { lower: 1 s, upper: 2 s } }\n"), Contains("study.yaml:6:13") && Contains("time") && Contains("length"));
  CHECK_THAT(error_of("  events: { high: { output: f.y, above: 2 kg } }\n"),
             Contains("study.yaml:6:13") && Contains("event 'high'") && Contains("mass") && Contains("length"));
  CHECK_THAT(error_of("  events: { high: { output: f.y, above: 2 } }\n"), Contains("bare number"));
  // In the output's dimension, in any unit of it: taken (the threshold in SI, whatever unit it was written in).
  CHECK(error_of("  limits: { f.y: { upper: 0.002 m } }\n  events: { high: { output: f.y, above: 1.5 mm } }\n") == "no error");
  // A value set on an uncertain parameter would be ignored by every sample: refused, at the parameter.
  CHECK_THAT(error_of("", {parse_override("x1=2 mm")}), Contains("study.yaml:5:5") && Contains("x1=2 mm") && Contains("uncertain"));
  CHECK(error_of("", {parse_override("x2=2 mm")}) == "no error");
  // A distribution on a scene parameter and on the one node parameter it feeds: the node's own
  // draws replace the scene parameter's, whose distribution would change nothing: refused at it.
  CHECK_THAT(error_of("    f.x1: { normal: { mean: 2 mm, sigma: 1 um } }\n"),
             Contains("study.yaml:5:5") && Contains("'x1' has a distribution, and so has every parameter it feeds (f.x1)"));
  // ... or is set: the set value replaces the draws there, and the scene parameter reaches nothing.
  CHECK_THAT(error_of("", {parse_override("f.x1=2 mm")}),
             Contains("study.yaml:5:5") && Contains("'x1' is not used by any node: its distribution changes nothing"));
  // A node parameter set to the uncertain scene parameter is one more use of it, drawn as the others.
  CHECK(error_of("", {parse_override("f.x2=$x1")}) == "no error");
  // A scene parameter set while every parameter it feeds has a distribution: the set value would
  // reach no case (and the run's record would name it): refused at the distribution it loses to.
  CHECK_THAT(error_of("    f.x2: { normal: { mean: 2 mm, sigma: 1 um } }\n", {parse_override("x2=5 mm")}),
             Contains("study.yaml:6:5") && Contains("'x2' is set (x2=5 mm), and every parameter it feeds (f.x2) has a distribution"));
  // An unknown name is said in the study's words, with the scene's parameters.
  CHECK_THAT(error_of("    x9: { normal: { mean: 2 mm, sigma: 1 um } }\n"),
             Contains("study.yaml:6:5") && Contains("study: ") && Contains("x9") && Contains("given a distribution as node.param") &&
                 !Contains("sweep"));
  // A distribution reaching a whole-number parameter: every draw would be refused, so the study is,
  // before it runs, at the distribution.
  CHECK_THAT(error_of("    f.terms: { uniform: { lower: 1, upper: 4 } }\n"),
             Contains("study.yaml:6:5") && Contains("'f.terms' reaches parameter 'terms', a whole number"));
  // A choice of outputs leaves out the limits and events on the scene's other outputs (a name that
  // is no output of the scene is still refused).
  const std::string two = "params: { x1: 0 mm }\nuncertainty:\n  samples: 8\n  parameters:\n"
                          "    x1: { normal: { mean: 1 mm, sigma: 1 um } }\n"
                          "  limits: { g.y: { upper: 3 mm }, LIMITED: { upper: 3 mm } }\n  events: { high: { output: g.y, above: 2 mm } }\n"
                          "nodes:\n  f: { type: test.linear, params: { x1: $x1, x2: 0 mm, x3: 0 mm } }\n"
                          "  g: { type: test.linear, params: { x1: $x1, x2: 1 mm, x3: 0 mm } }\noutputs: [f.y, g.y]\n";
  const auto chosen = [&](const std::string& limited) {
    std::string yaml = two;
    yaml.replace(yaml.find("LIMITED"), 7, limited);
    return host::run_scene_study(parse_scene(yaml, "study.yaml"), uq_registry(), {}, std::nullopt, "", "", "", std::string("f.y"),
                                 WorkBudget{}, 1, nullptr);
  };
  const InProcess kept = chosen("f.y");
  REQUIRE(kept->answers.outputs.size() == 1);
  CHECK(kept->spec.limits.size() == 1);
  CHECK(kept->spec.events.empty());
  CHECK(kept->answers.outputs[0].capability.has_value());
  CHECK_THROWS_WITH(chosen("h.y"), Contains("study.yaml:6:") && Contains("f.y"));
}

TEST_CASE("Designs: strata of Latin hypercube and Sobol', counter streams", "[uncertainty]") {
  const std::size_t n = 256, d = 4;
  for (SamplingMethod m : {SamplingMethod::latin_hypercube, SamplingMethod::sobol}) {
    const UnitDesign design(m, n, d, 9);
    std::vector<std::vector<int>> hits(d, std::vector<int>(n, 0));
    std::vector<double> p(d);
    for (std::size_t i = 0; i < n; ++i) {
      design.point(i, p.data());
      for (std::size_t j = 0; j < d; ++j) {
        REQUIRE(p[j] > 0.0);
        REQUIRE(p[j] < 1.0);
        ++hits[j][static_cast<std::size_t>(p[j] * n)];
      }
    }
    // Every one of the n strata of every coordinate holds exactly one point (for Sobol': the first
    // 2^m points of a digitally shifted net).
    for (std::size_t j = 0; j < d; ++j) CHECK(std::all_of(hits[j].begin(), hits[j].end(), [](int h) { return h == 1; }));
  }
  // A point depends on its index alone: asked out of order, it is the same.
  const UnitDesign sobol(SamplingMethod::sobol, 1000, 3, 2);
  std::vector<double> first(3), again(3), other(3);
  sobol.point(700, first.data());
  sobol.point(3, other.data());
  sobol.point(700, again.data());
  CHECK(first == again);
  CHECK(counter_hash(1, 2, 3, 4) != counter_hash(1, 2, 4, 3));
}

TEST_CASE("Correlated pairs: the Gaussian copula gives the normal scores their correlation", "[uncertainty]") {
  const StudySpec spec = study_of(R"(uncertainty:
  method: monte_carlo
  samples: 40000
  parameters:
    a: { normal: { mean: 0, sigma: 2 } }
    b: { uniform: { lower: 0, upper: 1 } }
  correlations: [[a, b, 0.6]]
nodes: {}
)");
  const CaseTable t = make_study_cases(spec);
  // Made in chunks on three workers: the same table, value for value.
  const CaseTable on_three = make_study_cases(spec, 3);
  REQUIRE(t.size() == 40000);
  REQUIRE(on_three.size() == t.size());
  CHECK(on_three.numbers.si == t.numbers.si);
  double sxy = 0, sxx = 0, syy = 0;
  std::vector<CaseValue> scratch;
  for (std::size_t i = 0; i < t.size(); ++i) {
    const std::vector<CaseValue>& row = t.row(i, scratch);
    const double za = *row[0].si / 2, zb = standard_normal_quantile(*row[1].si);
    sxy += za * zb, sxx += za * za, syy += zb * zb;
  }
  CHECK_THAT(sxy / std::sqrt(sxx * syy), Catch::Matchers::WithinAbs(0.6, 0.01));  // 4 standard errors
}

TEST_CASE("A study's design is kept as numbers only and reads as the rows it stands for", "[uncertainty]") {
  // The stage 1-3 study (its nodes take the block path) with six parameters in mm, deg and rpm,
  // the base radius drawn partly below zero so that the binder refuses some cases: the compact
  // table (CaseTable::Numbers) gives what a table of the same values as rows of CaseValue gives,
  // cell for cell and row for row, in blocks and case by case.
  std::string scene = testing::source_file_text("bench/peers/stages123_study.yaml");
  scene.replace(scene.find("\nnodes:"), 7, R"(
uncertainty:
  method: sobol
  samples: 16
  sensitivity: true
  parameters:
    lift:   { uniform: { lower: 7 mm, upper: 9 mm } }
    action: { uniform: { lower: 120 deg, upper: 140 deg } }
    accel:  { uniform: { lower: 15 deg, upper: 21 deg } }
    r0:     { uniform: { lower: -4 mm, upper: 28 mm } }
    rpm:    { uniform: { lower: 4000 rpm, upper: 7000 rpm } }
    lash:   { uniform: { lower: 0.1 mm, upper: 0.4 mm } }
nodes:)");
  const InProcess study = run_study(scene, 1, testing::project_registry());
  const CaseTable& numbers = study->table;
  REQUIRE(numbers.cases.empty());
  REQUIRE(numbers.size() == 16 * 8);
  const std::size_t width = numbers.variables.size();
  REQUIRE(width == 6);
  CHECK(numbers.numbers.si.size() == numbers.size() * width);
  CaseTable rows;
  rows.variables = numbers.variables;
  std::vector<CaseValue> scratch;
  for (std::size_t i = 0; i < numbers.size(); ++i) rows.cases.push_back(numbers.row(i, scratch));
  REQUIRE(rows.size() == numbers.size());
  CaseValue made;
  for (std::size_t i = 0; i < numbers.size(); ++i)
    for (std::size_t v = 0; v < width; ++v) {
      const CaseValue& c = numbers.cell(i, v, made);
      REQUIRE(c.text.empty());
      REQUIRE(*c.si == numbers.numbers.si[i * width + v]);
      REQUIRE(numbers.shown(i, v) == rows.shown(i, v));
    }
  const CaseBinder binder(study->graph, *study->scene, testing::project_registry(), {}, numbers.variables, BinderUse::study);
  const host::SweepRows lines(study->graph, numbers, host::RowFormat::csv), lines_of_rows(study->graph, rows, host::RowFormat::csv);
  for (const std::size_t block : {std::size_t{0}, std::size_t{16}}) {
    INFO("block size " << block);
    const auto run = [&](const CaseTable& table, const host::SweepRows& writer, SweepSummary& summary) {
      SweepOptions options;
      options.block_size = block;
      for (std::size_t i = 0; i < table.size(); ++i) options.cases.push_back(i);
      MemoCache cache;
      std::string out;
      summary = run_sweep(study->graph, binder, table, cache, options, [&](CaseResult&& r) {
        writer.append_line(out, r, r.failure == CaseFailure::none ? 0 : 1);
      });
      return out;
    };
    SweepSummary from_numbers_summary, from_rows_summary;
    const std::string from_numbers = run(numbers, lines, from_numbers_summary), from_rows = run(rows, lines_of_rows, from_rows_summary);
    CHECK(std::count(from_numbers.begin(), from_numbers.end(), '\n') == 128);
    CHECK(from_numbers_summary.failed > 0);                     // the binder refused some cases
    CHECK(from_numbers_summary.failed < 128);                   // and ran the others
    CHECK(from_numbers_summary.in_blocks == (block ? 128 - from_numbers_summary.failed : 0));
    CHECK(from_numbers_summary.failed == from_rows_summary.failed);
    CHECK(from_numbers == from_rows);
  }
}

TEST_CASE("Monte Carlo statistics against exact convolution", "[uncertainty]") {
  // The sum of two uniforms on [0, 1] is triangular on [0, 2]: mean 1, sigma 1/sqrt(6), quantile
  // p <= 1/2 at sqrt(2p); of two normals N(1, 0.3), N(2, 0.4): N(3, 0.5).
  const auto scene = [](const std::string& d1, const std::string& d2, const std::string& method) {
    return "params: { x1: 0 mm, x2: 0 mm }\nuncertainty:\n  method: " + method + "\n  samples: 20000\n  seed: 4\n  parameters:\n    x1: " +
           d1 + "\n    x2: " + d2 +
           "\n  quantiles: [0.02, 0.5, 0.9]\nnodes:\n  f: { type: test.linear, params: { x1: $x1, x2: $x2, x3: 0 mm } }\noutputs: [f.y]\n";
  };
  for (const std::string method : {"monte_carlo", "latin_hypercube"}) {
    INFO(method);
    const InProcess u = run_study(scene("{ uniform: { lower: 0 mm, upper: 1 mm } }", "{ uniform: { lower: 0 mm, upper: 1 mm } }", method), 2);
    const OutputAnswer& y = u->answers.outputs.at(0);
    CHECK(y.column.unit == "mm");
    const double se = (1 / std::sqrt(6.0)) / std::sqrt(20000.0);
    CHECK_THAT(y.moments.mean, Catch::Matchers::WithinAbs(1.0, 4 * se));
    CHECK_THAT(y.moments.standard_deviation, Catch::Matchers::WithinRel(1 / std::sqrt(6.0), 0.02));
    // A quantile's standard error is sqrt(p (1 - p) / n) / f(x_p); the density is x, or 2 - x.
    const auto quantile_se = [](double p, double density) { return std::sqrt(p * (1 - p) / 20000.0) / density; };
    CHECK_THAT(y.quantiles[0].value, Catch::Matchers::WithinAbs(std::sqrt(2 * 0.02), 4 * quantile_se(0.02, std::sqrt(2 * 0.02))));
    CHECK_THAT(y.quantiles[2].value, Catch::Matchers::WithinAbs(2 - std::sqrt(2 * 0.1), 4 * quantile_se(0.9, std::sqrt(2 * 0.1))));
    // The interval covers the exact quantile (95 %: a seed could miss; this one is checked).
    CHECK(*y.quantiles[1].interval.lower <= 1.0);
    CHECK(*y.quantiles[1].interval.upper >= 1.0);
    const InProcess g = run_study(scene("{ normal: { mean: 1 mm, sigma: 0.3 mm } }", "{ normal: { mean: 2 mm, sigma: 0.4 mm } }", method), 1);
    const OutputAnswer& z = g->answers.outputs.at(0);
    CHECK_THAT(z.moments.mean, Catch::Matchers::WithinAbs(3.0, 4 * 0.5 / std::sqrt(20000.0)));
    CHECK_THAT(z.moments.standard_deviation, Catch::Matchers::WithinRel(0.5, 0.02));
    CHECK_THAT(z.quantiles[2].value, Catch::Matchers::WithinAbs(3 + 0.5 * standard_normal_quantile(0.9), 0.02));
  }
}

TEST_CASE("Cp, Cpk and ppm against their closed forms", "[uncertainty]") {
  // Exact values: the formulas on given moments.
  Moments m;
  m.n = 4;
  m.mean = 10.2;
  m.standard_deviation = 0.1;
  const Capability c = capability({9.5, 10.0, 10.4, 10.6}, m, 9.7, 10.6, 0.95);
  CHECK_THAT(*c.cp, Catch::Matchers::WithinRel(0.9 / 0.6, 1e-14));
  CHECK_THAT(*c.cpk, Catch::Matchers::WithinRel(0.4 / 0.3, 1e-14));
  CHECK_THAT(c.ppm_normal, Catch::Matchers::WithinRel(1e6 * (standard_normal_cdf(-5.0) + standard_normal_cdf(-4.0)), 1e-10));
  CHECK(c.below == 1);
  CHECK(c.above == 0);  // 10.6 is inside a closed limit
  // A normal output N(10, 0.1) mm against [9.75, 10.35] mm: Cpk = min(0.35, 0.25) / 0.3 = 5/6.
  const InProcess r = run_study(R"(params: { x1: 0 mm }
uncertainty:
  method: latin_hypercube
  samples: 50000
  parameters:
    x1: { normal: { mean: 10 mm, sigma: 0.1 mm } }
  limits:
    f.y: { lower: 9.75 mm, upper: 10.35 mm }
nodes:
  f: { type: test.linear, params: { x1: $x1, x2: 0 mm, x3: 0 mm } }
outputs: [f.y]
)",
                                2);
  const Capability& k = *r->answers.outputs.at(0).capability;
  CHECK_THAT(*k.cpk, Catch::Matchers::WithinRel(5.0 / 6.0, 0.01));
  CHECK_THAT(*k.cp, Catch::Matchers::WithinRel(1.0, 0.01));
  const double ppm = 1e6 * (standard_normal_cdf(-2.5) + standard_normal_cdf(-3.5));
  CHECK(1e6 * *k.out_of_spec.clopper_pearson.lower <= ppm);
  CHECK(1e6 * *k.out_of_spec.clopper_pearson.upper >= ppm);
}

TEST_CASE("Cp, Cpk and ppm: failed cases counted out of spec as well, the most the share can be", "[uncertainty]") {
  // The Ishigami output against an upper limit of 8; the same design with the node failing above
  // 10: every failed case lies above the limit (a tail), so the values alone understate the share
  // out of spec, and counting the failures out of spec gives exactly the share the plain run counts.
  const std::string limits = "  limits: { f.y: { upper: 8 } }\n";
  const InProcess plain = run_study(ishigami_scene("monte_carlo", 4000, limits), 2);
  std::string failing = ishigami_scene("monte_carlo", 4000, limits);
  failing.replace(failing.find("x3: $x3 }"), 9, "x3: $x3, fail_above: 10 }");
  const InProcess f = run_study(failing, 2);
  const OutputAnswer& o = f->answers.outputs.at(0);
  const Capability& all = *plain->answers.outputs.at(0).capability;
  const Capability& k = *o.capability;
  REQUIRE(o.failed > 0);
  CHECK(all.failed == 0);
  CHECK(all.out_of_spec_or_failed.events == all.out_of_spec.events);  // nothing failed: the same share
  CHECK(all.out_of_spec_or_failed.trials == all.out_of_spec.trials);
  CHECK(k.failed == o.failed);
  const std::size_t samples = f->answers.samples;  // the A and B rows of Saltelli's design: 8000
  REQUIRE(samples == 8000);
  CHECK(k.out_of_spec.trials == samples - o.failed);
  CHECK(k.out_of_spec.events + o.failed == all.out_of_spec.events);  // the values alone miss the failed tail
  CHECK(k.out_of_spec_or_failed.events == all.out_of_spec.events);
  CHECK(k.out_of_spec_or_failed.trials == samples);
  CHECK(k.out_of_spec_or_failed.estimate == all.out_of_spec.estimate);
  CHECK(*k.out_of_spec_or_failed.wilson.lower == *all.out_of_spec.wilson.lower);
  CHECK(*k.out_of_spec_or_failed.wilson.upper == *all.out_of_spec.wilson.upper);
  CHECK(k.out_of_spec.estimate < k.out_of_spec_or_failed.estimate);
  CHECK_THAT(f->json, Contains("\"ppm_or_failed\":") && Contains("\"out_of_spec_or_failed\":{\"events\":" +
                                                                       std::to_string(all.out_of_spec.events) + ",\"trials\":8000,\"failed\":" +
                                                                       std::to_string(o.failed) + ","));
}

TEST_CASE("Studies: a bare limit or threshold on an output shown in % is read as a plain number, and said so", "[uncertainty]") {
  // The backlash chain's actuator share is a plain number shown in %: a bare 30 is 3000 %, valid
  // (nothing is refused), but an easy slip for 30 %: a warning gives both readings and the spelling
  // of the other; "30 %" or a length's limit draws none.
  std::string scene = testing::source_file_text("scenes/backlash_chain.yaml");
  const auto replace = [&scene](const std::string& from, const std::string& to) {
    const auto at = scene.find(from);
    REQUIRE(at != std::string::npos);
    scene.replace(at, from.size(), to);
  };
  replace("actuator_backlash: 25 um", "actuator_backlash: $act");
  replace("samples: 200000", "samples: 2000");
  replace("\nparams:\n", "\nparams:\n  act: 25 um\n");
  replace("outputs: [ chain.lever_arm ]", "outputs: [ chain.actuator_contribution_worst_case, chain.lever_arm ]");
  const auto dir = std::filesystem::temp_directory_path() / ("mechgraph_bare_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const auto run = [&](const std::string& share, const std::string& threshold) {
    const std::string file = (dir / "chain.yaml").string();
    std::ofstream(file) << scene << "\nuncertainty:\n  samples: 4\n  parameters:\n    act: { uniform: { lower: 20 um, upper: 30 um } }\n"
                        << "  limits:\n    chain.actuator_contribution_worst_case: { upper: " << share << " }\n"
                        << "    chain.lever_arm: { lower: 400 mm }\n"
                        << "  events:\n    big: { output: chain.actuator_contribution_worst_case, above: " << threshold << " }\n";
    return testing::run_cli("study '" + file + "'");
  };
  const auto bare = run("30", "0.25");
  REQUIRE(bare.exit_code == 0);
  CHECK_THAT(bare.err, Contains("chain.yaml:") &&
                           Contains("the upper limit of 'chain.actuator_contribution_worst_case' is the bare number 30, read as a plain "
                                    "number: 3000 % as 'chain.actuator_contribution_worst_case' is shown; if 30 % was meant, write '30 %'") &&
                           Contains("the threshold of event 'big' is the bare number 0.25, read as a plain number: 25 %"));
  const auto with_units = run("30 %", "25 %");
  REQUIRE(with_units.exit_code == 0);
  CHECK(with_units.err.find("bare number") == std::string::npos);  // nor for the lever arm's limit in mm
  std::filesystem::remove_all(dir);
}

TEST_CASE("Moments at the edges: Student's interval, equal values, huge values", "[uncertainty]") {
  // [1, 2, 3]: mean 2, s 1; Student's t with 2 degrees of freedom has the closed-form quantile
  // t = (2p - 1) / sqrt(2 p (1 - p)), 4.3026527297494639 at p = 0.975.
  const Moments three = moments({1.0, 2.0, 3.0}, 0.95);
  const double t2 = 0.95 / std::sqrt(2 * 0.975 * 0.025);
  CHECK_THAT(*three.mean_interval.lower, Catch::Matchers::WithinAbs(2.0 - t2 / std::sqrt(3.0), 1e-13));
  CHECK_THAT(*three.mean_interval.upper, Catch::Matchers::WithinAbs(2.0 + t2 / std::sqrt(3.0), 1e-13));
  // Equal values: that value, a spread of exactly 0, whatever the rounding of their sum.
  const std::vector<double> same(7, -0.9498219918858127);
  const Moments flat = moments(same, 0.95);
  CHECK(flat.mean == same[0]);
  CHECK(flat.standard_deviation == 0.0);
  const Capability out = capability(same, flat, -0.9, std::nullopt, 0.95);  // every value below the lower limit
  CHECK_FALSE(out.cpk.has_value());
  CHECK(out.ppm_normal == 1e6);
  CHECK(capability(same, flat, -1.0, -0.9, 0.95).ppm_normal == 0.0);
  // Values whose squares overflow a double: still finite, the same numbers scaled.
  const Moments huge = moments({1e200, 2e200, 3e200}, 0.95);
  CHECK_THAT(huge.mean, Catch::Matchers::WithinRel(2e200, 1e-15));
  CHECK_THAT(huge.standard_deviation, Catch::Matchers::WithinRel(1e200, 1e-15));
  CHECK(std::isfinite(*huge.mean_interval.upper));
  // The level in labels: 99.9 %, not 100 %.
  CHECK(confidence_percent(0.95) == "95");
  CHECK(confidence_percent(0.999) == "99.9");
  CHECK(confidence_percent(0.9999) == "99.99");
  // Wilson's ends are exactly 0 at no event and 1 at all (a rounding residue was 5.6e-17).
  CHECK(*proportion(0, 3, 0.95).wilson.lower == 0.0);
  CHECK(*proportion(7, 7, 0.9).wilson.upper == 1.0);
}

TEST_CASE("Event probabilities: Wilson and Clopper-Pearson intervals", "[uncertainty]") {
  const Proportion none = proportion(0, 10, 0.95);
  CHECK(*none.clopper_pearson.lower == 0.0);
  CHECK_THAT(*none.clopper_pearson.upper, Catch::Matchers::WithinRel(1 - std::pow(0.025, 0.1), 1e-12));
  const Proportion some = proportion(12, 100, 0.95);
  // Wilson at k = 12, n = 100, z = 1.959964: [0.0700, 0.1981] (Newcombe 1998, method 3).
  CHECK_THAT(*some.wilson.lower, Catch::Matchers::WithinAbs(0.06996, 1e-4));
  CHECK_THAT(*some.wilson.upper, Catch::Matchers::WithinAbs(0.19812, 1e-4));
  // A failed evaluation class counts as the event: the node fails where y > 10, so the failure
  // event and the output event y > 10 of the same design agree.
  const InProcess fails = run_study(ishigami_scene("monte_carlo", 2000, "  events:\n    refused: { failure: evaluation }\n") +
                                        "", 2);
  const InProcess plain_ = run_study(ishigami_scene("monte_carlo", 2000, "  events:\n    high: { output: f.y, above: 10 }\n"), 2);
  (void)fails;
  std::string failing = ishigami_scene("monte_carlo", 2000, "  events:\n    refused: { failure: evaluation }\n");
  failing.replace(failing.find("x3: $x3 }"), 9, "x3: $x3, fail_above: 10 }");
  const InProcess f = run_study(failing, 2);
  REQUIRE(f->answers.events.size() == 1);
  CHECK(f->answers.events[0].probability.events == plain_->answers.events[0].probability.events);
  CHECK(f->answers.events[0].probability.events > 0);
  CHECK(f->answers.outputs[0].failed == f->answers.events[0].probability.events);
}

TEST_CASE("Sobol' indices of the Ishigami function against the closed form", "[uncertainty]") {
  // a = 7, b = 0.1, x_i uniform on [-pi, pi]: V = a^2/8 + b pi^4/5 + b^2 pi^8/18 + 1/2;
  // V1 = (1 + b pi^4/5)^2 / 2, V2 = a^2/8, V3 = 0; VT1 = V1 + V13, V13 = b^2 pi^8 (1/18 - 1/50) ... (8/225).
  const double a = 7, b = 0.1, pi4 = std::pow(M_PI, 4), pi8 = pi4 * pi4;
  const double v = a * a / 8 + b * pi4 / 5 + b * b * pi8 / 18 + 0.5;
  const double v1 = 0.5 * (1 + b * pi4 / 5) * (1 + b * pi4 / 5), v2 = a * a / 8, v13 = b * b * pi8 * 8 / 225;
  const double s[3] = {v1 / v, v2 / v, 0.0}, st[3] = {(v1 + v13) / v, v2 / v, v13 / v};
  for (const std::string method : {"sobol", "latin_hypercube"}) {
    INFO(method);
    const InProcess r = run_study(ishigami_scene(method, 16384), 2);
    const SobolIndices& si = *r->answers.outputs.at(0).sobol;
    REQUIRE(si.indices.size() == 3);
    for (int j = 0; j < 3; ++j) {
      INFO("x" << j + 1);
      CHECK_THAT(si.indices[j].first, Catch::Matchers::WithinAbs(s[j], 0.03));
      CHECK_THAT(si.indices[j].total, Catch::Matchers::WithinAbs(st[j], 0.03));
      CHECK(*si.indices[j].first_interval.lower < si.indices[j].first);
      CHECK(*si.indices[j].first_interval.upper > si.indices[j].first);
    }
  }
}

TEST_CASE("Sobol' indices of a linear model: S_i = ST_i = c_i^2 sigma_i^2 / sum", "[uncertainty]") {
  const InProcess r = run_study(R"(params: { x1: 0 mm, x2: 0 mm, x3: 0 mm }
uncertainty:
  method: sobol
  samples: 8192
  sensitivity: true
  bootstrap: 0
  parameters:
    x1: { normal: { mean: 1 mm, sigma: 0.1 mm } }
    x2: { uniform: { lower: 0 mm, upper: 0.6 mm } }
    x3: { normal: { nominal: 5 mm, tolerance: 0.3 mm } }
nodes:
  f: { type: test.linear, params: { x1: $x1, x2: $x2, x3: $x3, c1: 2, c2: -1, c3: 0.5 } }
outputs: [f.y]
)",
                                2);
  const double v1 = 4 * 0.01, v2 = 0.36 / 12, v3 = 0.25 * 0.01, total = v1 + v2 + v3;
  const double s[3] = {v1 / total, v2 / total, v3 / total};
  const SobolIndices& si = *r->answers.outputs.at(0).sobol;
  for (int j = 0; j < 3; ++j) {
    INFO("x" << j + 1);
    CHECK_THAT(si.indices[j].first, Catch::Matchers::WithinAbs(s[j], 0.01));
    CHECK_THAT(si.indices[j].total, Catch::Matchers::WithinAbs(s[j], 0.01));
  }
  CHECK_THAT(si.variance, Catch::Matchers::WithinRel(total, 0.03));
}

TEST_CASE("Studies: the same bits on 1, 2 and 5 threads", "[uncertainty]") {
  for (const std::string method : {"monte_carlo", "latin_hypercube", "sobol"}) {
    // Two outputs (answered side by side on the threads) and 13 resamples (a last group of 5).
    std::string scene = ishigami_scene(method, 500, "  limits: { f.y: { upper: 10 } }\n  events: { high: { output: f.y, above: 9 } }\n");
    scene.replace(scene.find("bootstrap: 50"), 13, "bootstrap: 13");
    scene.replace(scene.find("outputs: [f.y]"), 14,
                  "  g: { type: test.ishigami, params: { x1: $x2, x2: $x3, x3: $x1 } }\noutputs: [f.y, g.y]");
    const InProcess one = run_study(scene, 1), two = run_study(scene, 2), five = run_study(scene, 5);
    CHECK(one->json == two->json);
    CHECK(one->json == five->json);
    CHECK(one->data.values == five->data.values);
  }
}

TEST_CASE("Studies: shards of a Slurm array give the in-process answers bit for bit", "[uncertainty]") {
  const auto dir = std::filesystem::temp_directory_path() / ("mechgraph_study_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const std::string plugin = " --plugin-dir '" + testing::test_plugin("test_uq").parent_path().string() + "' ";
  const std::string scene = std::string(MECHGRAPH_SOURCE_DIR) + "/tests/uncertainty/ishigami.yaml";
  const auto whole = testing::run_cli(plugin + "study '" + scene + "' --samples 300 --json --threads 2");
  REQUIRE(whole.exit_code == 0);
  // Valid, but Sobol' points stratify only for a power of 2: said, with the two nearest.
  CHECK_THAT(whole.err, Contains("300 Sobol' samples, not a power of 2") && Contains("(256 or 512)"));
  std::string parts;
  for (int shard = 0; shard < 3; ++shard) {
    const std::string part = (dir / ("part-" + std::to_string(shard) + ".csv")).string();
    const auto r = testing::run_cli(plugin + "sweep '" + scene + "' --study --samples 300 --shard " + std::to_string(shard) +
                                    "/3 --threads 1 --out '" + part + "'");
    REQUIRE(r.exit_code == 0);
    parts += " '" + part + "'";
  }
  const std::string merged = (dir / "all.csv").string();
  REQUIRE(testing::run_cli("merge" + parts + " --out '" + merged + "'").exit_code == 0);
  const auto from_rows = testing::run_cli(plugin + "study '" + scene + "' --samples 300 --json --rows '" + merged + "'");
  REQUIRE(from_rows.exit_code == 0);
  CHECK(from_rows.out == whole.out);
  // The same rows after a trip through a Windows editor (a byte order mark, CR LF line ends): the
  // same answers.
  {
    std::ifstream in(merged, std::ios::binary);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::string windows = "\xEF\xBB\xBF";
    for (char c : text) windows += c == '\n' ? std::string("\r\n") : std::string(1, c);
    const std::string saved = (dir / "saved.csv").string();
    std::ofstream(saved, std::ios::binary) << windows;
    std::filesystem::copy_file(merged + ".json", saved + ".json");
    const auto from_saved = testing::run_cli(plugin + "study '" + scene + "' --samples 300 --json --rows '" + saved + "'");
    REQUIRE(from_saved.exit_code == 0);
    CHECK(from_saved.out == whole.out);
    // Rows that are not CSV: JSON Lines are named as such; an unclosed quote is refused at its line.
    const std::string first_line = text.substr(0, text.find('\n') + 1);
    for (const auto& [content, says] : {std::pair<std::string, std::string>{"{\"case\":0}\n", "saved.csv:1: rows in JSON Lines"},
                                        std::pair<std::string, std::string>{first_line + "0,\"unclosed\n", "saved.csv:2:"}}) {
      std::ofstream(saved, std::ios::binary) << content;
      const auto refused = testing::run_cli(plugin + "study '" + scene + "' --samples 300 --rows '" + saved + "'");
      CHECK(refused.exit_code == 2);
      CHECK_THAT(refused.err, Contains(says));
    }
  }
  // Rows of another seed or sample count are refused before they are read, by the design their
  // manifest records (a Sobol' design's first rows are the same for 300 and 600 samples: counted,
  // the rows of 300 were half of the 600's, and "run the missing shards" a dead end).
  for (const std::string& other_design : {std::string("--samples 300 --seed 4"), std::string("--samples 600")}) {
    const auto other = testing::run_cli(plugin + "study '" + scene + "' " + other_design + " --rows '" + merged + "'");
    CHECK(other.exit_code == 2);
    CHECK_THAT(other.err, Contains("all.csv: rows of another design (uncertainty: sobol, 300 samples, seed 3") &&
                              Contains("this study's is uncertainty: sobol, " + std::string(other_design == "--samples 600" ? "600" : "300")) &&
                              Contains("--samples, --method and --seed"));
  }
  // Without a manifest, row by row, naming the row.
  {
    const std::string bare = (dir / "bare.csv").string();
    std::filesystem::copy_file(merged, bare);
    const auto other = testing::run_cli(plugin + "study '" + scene + "' --samples 300 --seed 4 --rows '" + bare + "'");
    CHECK(other.exit_code == 2);
    CHECK_THAT(other.err, Contains("bare.csv:2:") && Contains("another seed"));
  }
  // --resume of another design's complete rows: nothing of this sweep to resume, said so (not
  // "complete already"), and the rows are left as they were.
  {
    const auto size_before = std::filesystem::file_size(merged);
    const auto resumed = testing::run_cli(plugin + "sweep '" + scene + "' --study --samples 600 --threads 1 --resume --out '" + merged + "'");
    CHECK(resumed.exit_code == 2);
    CHECK_THAT(resumed.err, Contains("all.csv holds the complete rows of another sweep (uncertainty: sobol, 300 samples") &&
                                Contains("--force replaces them"));
    CHECK(std::filesystem::file_size(merged) == size_before);
  }
  // Rows of another scene (here: another fixed value, --set, under the same design) are refused by
  // the manifest's fingerprint, though every sampled input matches.
  const auto other_set = testing::run_cli(plugin + "study '" + scene + "' --samples 300 --set f.a=6 --rows '" + merged + "'");
  CHECK(other_set.exit_code == 2);
  CHECK_THAT(other_set.err, Contains("all.csv: the rows of another sweep"));
  // The manifest's record of the rows' format: another than this program writes is refused up
  // front (before, row by row as another seed's); none recorded (manifests before the key) is
  // checked row by row as before; a damaged record is refused, never taken for no manifest.
  {
    std::ifstream in(merged + ".json");
    const std::string manifest((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::size_t key = manifest.find(",\"rows_format\":2");
    REQUIRE(key != std::string::npos);
    const std::string older = (dir / "older.csv").string();
    std::filesystem::copy_file(merged, older);
    const auto with_record = [&](const std::string& record) {
      std::string edited = manifest;
      edited.replace(key, std::string(",\"rows_format\":2").size(), record);
      std::ofstream(older + ".json") << edited;
      return testing::run_cli(plugin + "study '" + scene + "' --samples 300 --json --rows '" + older + "'");
    };
    const auto format1 = with_record(",\"rows_format\":1");
    CHECK(format1.exit_code == 2);
    CHECK_THAT(format1.err, Contains("older.csv: its rows were written by an older mechgraph (rows format 1") &&
                                Contains("run the sweep again with this one"));
    const auto unrecorded = with_record("");
    CHECK(unrecorded.exit_code == 0);
    CHECK(unrecorded.out == whole.out);
    for (const char* damaged : {",\"rows_format\":0", ",\"rows_format\":\"3.1\""}) {
      const auto refused = with_record(damaged);
      CHECK(refused.exit_code == 2);  // before: "no manifest beside it", and the study ran unchecked
      CHECK_THAT(refused.err, Contains("older.csv.json: not a sweep manifest") && Contains("remove it to study the rows"));
    }
  }
  // An exit that is not 0, 2 or 3 is refused, naming the line.
  {
    std::ifstream in(merged);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    in.close();
    const std::size_t second_line = text.find('\n') + 1, end_of_it = text.find('\n', second_line);
    const std::size_t last_comma = text.rfind(',', end_of_it), exit_comma = text.rfind(',', last_comma - 1);
    text.replace(exit_comma + 1, last_comma - exit_comma - 1, "7");
    std::ofstream(merged, std::ios::binary) << text;
  }
  const auto bad_exit = testing::run_cli(plugin + "study '" + scene + "' --samples 300 --rows '" + merged + "'");
  CHECK(bad_exit.exit_code == 2);
  CHECK_THAT(bad_exit.err, Contains("all.csv:2:") && Contains("the exit '7' is not 0, 2 or 3"));
  std::filesystem::remove_all(dir);
}

TEST_CASE("mechgraph study: exit codes, --json and the CSVs of --out", "[uncertainty]") {
  const auto dir = std::filesystem::temp_directory_path() / ("mechgraph_study_out_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const std::string plugin = " --plugin-dir '" + testing::test_plugin("test_uq").parent_path().string() + "' ";
  const std::string scene = std::string(MECHGRAPH_SOURCE_DIR) + "/tests/uncertainty/ishigami.yaml";
  const auto r = testing::run_cli(plugin + "study '" + scene + "' --samples 64 --out '" + (dir / "out").string() + "'");
  REQUIRE(r.exit_code == 0);
  CHECK_THAT(r.out, Contains("Sobol' indices") && Contains("high: "));
  for (const char* f : {"study.json", "summary.csv", "quantiles.csv", "histograms.csv", "sobol.csv", "events.csv", "report.html"})
    CHECK(std::filesystem::is_regular_file(dir / "out" / f));
  // The page: the histogram against both spec limits, the Sobol' chart, the events.
  std::ifstream page_file(dir / "out" / "report.html");
  const std::string page((std::istreambuf_iterator<char>(page_file)), std::istreambuf_iterator<char>());
  CHECK_THAT(page, Contains("LSL -8") && Contains("USL 12") && Contains("Sobol' indices (64 base samples)") && Contains("<td>high</td>"));
  // An interval past the chart's axis ([-0.25, 1.25] at most) is drawn to its end with an arrowhead
  // (x3's first-order lower end, -0.34, with 64 samples); the parameters are in their units.
  CHECK_THAT(page, Contains("<polygon points="));
  CHECK_THAT(page, Contains("<tr><td>x1</td>") && Contains("<th>mean</th><th>standard deviation</th>"));
  // Every figure the terminal prints is on the page too (a printed page has no tooltips): the mean
  // with its interval, the spec line with the ppm interval and the counts, each quantile with its
  // interval, each Sobol' index with its interval; the same text, both written to 6 digits.
  {
    std::istringstream lines(r.out);
    std::size_t mean_lines = 0, spec_lines = 0, quantile_lines = 0, index_lines = 0;
    for (std::string line; std::getline(lines, line);) {
      if (line.rfind("  mean ", 0) == 0 || line.rfind("  spec [", 0) == 0) {
        CHECK_THAT(page, Contains(line.substr(2)));
        ++(line[2] == 'm' ? mean_lines : spec_lines);
      } else if (line.rfind("  quantile ", 0) == 0) {
        const std::size_t colon = line.find(": "), space = line.find(' ', colon + 2);
        CHECK_THAT(page, Contains("<tr><td>" + line.substr(11, colon - 11) + "</td><td>" + line.substr(colon + 2, space - colon - 2) +
                                  "</td><td>" + line.substr(space + 1) + "</td></tr>"));
        ++quantile_lines;
      } else if (const std::size_t s = line.find("S "), st = line.find("   ST "); s != std::string::npos && st != std::string::npos) {
        std::istringstream fields(line);
        std::string name;
        fields >> name;
        const std::string first = line.substr(s + 2, st - s - 2), total = line.substr(st + 6);
        CHECK_THAT(page, Contains("<tr><td>" + name + "</td><td>" + first.substr(0, first.find(' ')) + "</td><td>" +
                                  first.substr(first.find(' ') + 1) + "</td><td>" + total.substr(0, total.find(' ')) + "</td><td>" +
                                  total.substr(total.find(' ') + 1) + "</td></tr>"));
        ++index_lines;
      }
    }
    CHECK(mean_lines == 1);
    CHECK(spec_lines == 1);
    CHECK(quantile_lines >= 3);
    CHECK(index_lines == 3);
  }
  {
    // An upper limit that bounds the histogram has its label left of its line, inside the picture.
    std::string wider = slurp_text(scene);
    wider.replace(wider.find("upper: 12"), 9, "upper: 20");
    const std::string wider_scene = (dir / "wider.yaml").string();
    std::ofstream(wider_scene) << wider;
    REQUIRE(testing::run_cli(plugin + "study '" + wider_scene + "' --samples 64 --out '" + (dir / "wider").string() + "'").exit_code == 0);
    CHECK_THAT(slurp_text((dir / "wider" / "report.html").string()), Contains("text-anchor=\"end\">USL 20</text>"));
  }
  // The counts the terminal prints, in the files too: the cases below and above the limits, an
  // event's cases without a value.
  const auto slurp_file = [](const std::filesystem::path& f) {
    std::ifstream in(f);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  };
  CHECK_THAT(slurp_file(dir / "out" / "summary.csv"), Contains("lower_limit,upper_limit,below,above,cp"));
  CHECK_THAT(slurp_file(dir / "out" / "events.csv"), Contains("event,events,trials,undecided,probability") && Contains("high,"));
  const std::string json = slurp_file(dir / "out" / "study.json");
  CHECK_THAT(json, Contains("\"below\":") && Contains("\"above\":") && Contains("\"undecided\":0"));
  const std::size_t at = r.out.find(" below, ");
  REQUIRE(at != std::string::npos);
  const std::string below_count = r.out.substr(r.out.rfind('(', at) + 1, at - r.out.rfind('(', at) - 1);
  CHECK_THAT(json, Contains("\"below\":" + below_count + ","));
  const std::string bad = (dir / "bad.yaml").string();
  std::ofstream(bad) << "params: {x1: 0}\nuncertainty:\n  parameters:\n    x1: { normal: { mean: 1, sigma: -1 } }\n"
                        "nodes:\n  f: { type: test.ishigami, params: { x1: $x1 } }\noutputs: [f.y]\n";
  const auto e = testing::run_cli(plugin + "study '" + bad + "'");
  CHECK(e.exit_code == 2);
  CHECK_THAT(e.err, Contains("bad.yaml:4:37: sigma must be greater than 0"));
  // Cases that fail say why (the first one's message); when every case fails nothing is answered:
  // an error, with the exit class of the failure (an evaluation error: 3).
  const std::string failing = (dir / "failing.yaml").string();
  const auto failing_scene = [&](const char* limit) {
    std::ofstream(failing) << "params: {x1: 0}\nuncertainty:\n  samples: 32\n  parameters:\n    x1: { uniform: { lower: -3, upper: 3 } }\n"
                              "nodes:\n  f: { type: test.ishigami, params: { x1: $x1, x2: 1, x3: 1, fail_above: "
                           << limit << " } }\noutputs: [f.y]\n";
  };
  failing_scene("-100");
  const auto all_failed = testing::run_cli(plugin + "study '" + failing + "'");
  CHECK(all_failed.exit_code == 3);
  CHECK_THAT(all_failed.err, Contains("every one of the 32 cases failed") && Contains("case 0:") && Contains("deliberate failure"));
  // With fewer than 2 complete base samples a sensitivity study says so, not that the output is flat.
  {
    std::ofstream(failing) << "params: {x1: 0}\nuncertainty:\n  samples: 8\n  sensitivity: true\n  parameters:\n"
                              "    x1: { uniform: { lower: -3, upper: 3 } }\n"
                              "nodes:\n  f: { type: test.ishigami, params: { x1: $x1, x2: 1, x3: 1, fail_above: 4.0 } }\noutputs: [f.y]\n";
    // y = 4.957 + 1.1 sin x1 fails above 4.0 unless sin x1 < -0.87: no base sample has both its cases.
    const auto few = testing::run_cli(plugin + "study '" + failing + "' --seed 2");
    CHECK(few.exit_code == 0);
    CHECK_THAT(few.out, Contains("f.y (0 base samples)\n  (fewer than 2 base samples have a value in every one of their cases"));
  }
    failing_scene("6.1");  // y = (1 + 0.1) sin x1 + 7 sin^2 1 = 4.957 + 1.1 sin x1 <= 6.057: none fails
  CHECK(testing::run_cli(plugin + "study '" + failing + "'").err.find("cases failed") == std::string::npos);
  failing_scene("4.99");  // those with sin x1 above 0.03 fail, about half
  const auto some_failed = testing::run_cli(plugin + "study '" + failing + "'");
  CHECK(some_failed.exit_code == 0);
  CHECK_THAT(some_failed.err, Contains("of 32 cases failed") && Contains("deliberate failure"));
  // Against a limit, the failed cases counted out of spec as well: said on the spec line and in
  // the summary CSV's last three columns.
  {
    std::ofstream(failing) << "params: {x1: 0}\nuncertainty:\n  samples: 32\n  parameters:\n    x1: { uniform: { lower: -3, upper: 3 } }\n"
                              "  limits: { f.y: { upper: 5.5 } }\n"
                              "nodes:\n  f: { type: test.ishigami, params: { x1: $x1, x2: 1, x3: 1, fail_above: 4.99 } }\noutputs: [f.y]\n";
    const std::string out = (dir / "failing_out").string();
    const auto limited = testing::run_cli(plugin + "study '" + failing + "' --out '" + out + "'");
    REQUIRE(limited.exit_code == 0);
    const auto failed_at = limited.out.find("failed counted out of spec ");
    REQUIRE(failed_at != std::string::npos);
    CHECK_THAT(limited.out, Contains("out of spec 0 ppm"));  // no value reaches 5.5
    const std::string summary = slurp_text(out + "/summary.csv");
    CHECK_THAT(summary, Contains(",ppm_normal,ppm_or_failed,ppm_or_failed_lower,ppm_or_failed_upper\n"));
    // The share is failed / 32, as a ppm: the same number on the spec line and in the CSV (there
    // as std::to_chars writes it).
    const std::string shown = limited.out.substr(failed_at + 27, limited.out.find(' ', failed_at + 27) - failed_at - 27);
    const double ppm = std::stod(shown);
    CHECK(ppm > 0);
    CHECK(std::fmod(ppm, 1e6 / 32) == 0);
    char cell[32];
    const auto written = std::to_chars(cell, cell + sizeof cell, ppm);
    CHECK_THAT(summary, Contains("," + std::string(cell, written.ptr) + ","));
  }
  // A parameter that reaches no node the outputs need: said once, at its line, in the study's words.
  const std::string unused = (dir / "unused.yaml").string();
  std::ofstream(unused) << "params: {x1: 0, x2: 0}\nuncertainty:\n  samples: 8\n  parameters:\n"
                           "    x1: { uniform: { lower: -3, upper: 3 } }\n    x2: { uniform: { lower: -3, upper: 3 } }\n"
                           "nodes:\n  f: { type: test.ishigami, params: { x1: $x1 } }\n  g: { type: test.ishigami, params: { x1: $x2 } }\n"
                           "outputs: [f.y]\n";
  const auto unused_run = testing::run_cli(plugin + "study '" + unused + "'");
  CHECK(unused_run.exit_code == 0);
  CHECK_THAT(unused_run.err, Contains("unused.yaml:6:5: 'x2' only reaches nodes the studied outputs do not need"));
  CHECK(unused_run.err.find("only reaches") == unused_run.err.rfind("only reaches"));
  CHECK(unused_run.err.find("sweep:") == std::string::npos);
  // An --out that cannot be written is refused before any case runs (exit 5), naming the folder
  // given: /proc takes no folder, even from root (a read-only parent is the same for other users).
  const auto unwritable = testing::run_cli(plugin + "study '" + scene + "' --samples 64 --out /proc/mechgraph-results");
  CHECK(unwritable.exit_code == 5);
  CHECK_THAT(unwritable.err, Contains("'/proc/mechgraph-results'"));
  CHECK(unwritable.err.find("cases in") == std::string::npos);  // the study's log line after its run
  CHECK(unwritable.out.empty());
  const auto none = testing::run_cli("study '" + std::string(MECHGRAPH_SOURCE_DIR) + "/scenes/valvetrain_cams.yaml'");
  CHECK(none.exit_code == 2);
  CHECK_THAT(none.err, Contains("no 'uncertainty' block"));
  const auto usage = testing::run_cli(plugin + "study '" + scene + "' --method lhs");
  CHECK(usage.exit_code == 2);
  CHECK_THAT(usage.err, Contains("latin_hypercube"));
  std::filesystem::remove_all(dir);
}

TEST_CASE("ISO 286 classes from the fits plugin's tables", "[uncertainty]") {
  // 20 mm H7: 0 .. +21 um; g6: -7 .. -20 um (ISO 286-2). Normal over the zone at Cp 1, or uniform.
  const StudySpec spec = study_of(R"(uncertainty:
  parameters:
    bore:  { iso286: { size: 20 mm, class: H7 } }
    pin:   { iso286: { size: 20 mm, class: g6, distribution: uniform } }
    tight: { iso286: { size: 20 mm, class: H7, cp: 1.33 } }
nodes: {}
)",
                                  testing::project_registry());
  CHECK_THAT(spec.parameters[0].marginal.a, Catch::Matchers::WithinAbs(20.0105e-3, 1e-12));
  CHECK_THAT(spec.parameters[0].marginal.b, Catch::Matchers::WithinAbs(21e-6 / 6, 1e-12));
  CHECK(spec.parameters[1].marginal.kind == Marginal::Kind::uniform);
  CHECK_THAT(spec.parameters[1].marginal.a, Catch::Matchers::WithinAbs(19.980e-3, 1e-12));
  CHECK_THAT(spec.parameters[1].marginal.b, Catch::Matchers::WithinAbs(19.993e-3, 1e-12));
  CHECK_THAT(spec.parameters[2].marginal.b, Catch::Matchers::WithinAbs(21e-6 / (6 * 1.33), 1e-12));
  try {
    study_of("uncertainty:\n  parameters:\n    bore: { iso286: { size: 20 mm, class: Q7 } }\nnodes: {}\n", testing::project_registry());
    FAIL("Q7 accepted");
  } catch (const SceneError& e) {
    CHECK_THAT(std::string(e.what()), Contains("study.yaml:3:43") && Contains("Q7"));
  }
}

TEST_CASE("Studies: an uncertain parameter inside a record, as a tolerance stack writes its links", "[uncertainty]") {
  // stack.linear's mean is the sum of s_i (nominal_i + (upper_i + lower_i) / 2): with a ~ U(9, 11) mm
  // in the first link and 5 mm fixed in the second, mean = a + 5 mm: its study mean 15 mm, its
  // standard deviation (2 mm) / sqrt(12).
  const std::string scene = R"(params: { a: 10 mm }
uncertainty:
  method: sobol
  samples: 256
  parameters:
    a: { uniform: { lower: 9 mm, upper: 11 mm } }
nodes:
  s: { type: stack.linear, params: { links: [ { nominal: $a, upper: 0.1 mm, lower: -0.1 mm }, { nominal: 5 mm, upper: 0.1 mm, lower: -0.1 mm } ] } }
outputs: [s.mean]
)";
  const InProcess r = run_study(scene, 2, testing::project_registry());
  REQUIRE(r->answers.outputs.size() == 1);
  CHECK(r->answers.failed == 0);
  const Moments& m = r->answers.outputs[0].moments;
  CHECK_THAT(m.mean, Catch::Matchers::WithinRel(15.0, 1e-3));  // shown in mm
  CHECK_THAT(m.standard_deviation, Catch::Matchers::WithinRel(2.0 / std::sqrt(12.0), 0.02));
  // A distribution no field of the record can take (a time) is refused at its line.
  std::string wrong = scene;
  wrong.replace(wrong.find("lower: 9 mm, upper: 11 mm"), 25, "lower: 9 s, upper: 11 s");
  CHECK_THROWS_WITH(run_study(wrong, 1, testing::project_registry()),
                    Contains("study.yaml:6:5") && Contains("records of parameter 'links'") && Contains("time"));
}

TEST_CASE("Sobol' indices of an output that does not vary: none, not zeros", "[uncertainty]") {
  const InProcess r = run_study(R"(params: { x1: 0 mm }
uncertainty:
  samples: 64
  sensitivity: true
  bootstrap: 20
  parameters:
    x1: { normal: { mean: 1 mm, sigma: 0.1 mm } }
nodes:
  f: { type: test.linear, params: { x1: $x1, x2: 0 mm, x3: 0 mm } }
  g: { type: test.linear, params: { x1: 1 mm, x2: 0 mm, x3: 0 mm } }
outputs: [f.y, g.y]
)",
                                1);
  REQUIRE(r->answers.outputs.size() == 2);
  REQUIRE(r->answers.outputs[0].sobol.has_value());
  CHECK(r->answers.outputs[0].sobol->indices.size() == 1);
  CHECK_THAT(r->answers.outputs[0].sobol->indices[0].total, Catch::Matchers::WithinAbs(1.0, 0.3));  // 1 exactly, estimated from 64
  REQUIRE(r->answers.outputs[1].sobol.has_value());
  CHECK(r->answers.outputs[1].sobol->variance == 0.0);
  CHECK(r->answers.outputs[1].sobol->indices.empty());
  CHECK_THAT(r->json, Contains("\"g.y\"") && Contains("\"indices\":{}"));
}

TEST_CASE("Sobol' bootstrap: resamples without spread are left out, not counted as 0", "[uncertainty]") {
  // Only base sample 0 varies (A 0, B 2, AB 1 for both parameters; every other value 0): about
  // (19/20)^20 = 36 % of the resamples leave it out and have no spread. Their indices are 0 / 0:
  // left out, the interval is that of the resamples that have it, never pinned at 0 by the rest.
  const std::size_t n = 20;
  std::vector<double> f_a(n, 0.0), f_b(n, 0.0);
  std::vector<std::vector<double>> f_ab(2, std::vector<double>(n, 0.0));
  f_b[0] = 2.0;
  f_ab[0][0] = f_ab[1][0] = 1.0;
  const SobolIndices s = sobol_indices(f_a, f_b, f_ab, 200, 0.95, 7, 1);
  REQUIRE(s.indices.size() == 2);
  for (const SobolIndex& i : s.indices) {
    REQUIRE(i.first_interval.lower.has_value());
    CHECK(*i.first_interval.lower > 0.0);
    CHECK(*i.total_interval.lower > 0.0);
    CHECK(std::isfinite(*i.first_interval.upper));
  }
  // Bit for bit on any threads still.
  const SobolIndices two = sobol_indices(f_a, f_b, f_ab, 200, 0.95, 7, 2);
  CHECK(*two.indices[0].first_interval.lower == *s.indices[0].first_interval.lower);
  CHECK(*two.indices[1].total_interval.upper == *s.indices[1].total_interval.upper);
}

TEST_CASE("Sobol' indices of several outputs at once: each as alone, bit for bit, on any threads", "[uncertainty]") {
  // Three outputs of the same base samples (one with a zero variance); the resamples are drawn
  // once for all of them and each output's indices and intervals equal its own computation.
  const std::size_t n = 3000, d = 3;
  std::vector<SobolSamples> outputs(3);
  for (std::size_t o = 0; o < outputs.size(); ++o) {
    SobolSamples& f = outputs[o];
    f.f_ab.assign(d, {});
    for (std::size_t i = 0; i < n; ++i) {
      const auto model = [&](double x1, double x2, double x3) {
        return o == 2 ? 4.0 : o == 0 ? x1 + 2 * x2 * x2 + 0.1 * x3 : std::sin(x1) * (1 + x3 * x3) + x2;
      };
      double a[3], b[3];
      for (std::size_t j = 0; j < d; ++j) a[j] = counter_uniform(5, 1, i, j), b[j] = counter_uniform(5, 2, i, j);
      f.f_a.push_back(model(a[0], a[1], a[2]));
      f.f_b.push_back(model(b[0], b[1], b[2]));
      for (std::size_t j = 0; j < d; ++j) {
        double m[3] = {a[0], a[1], a[2]};
        m[j] = b[j];
        f.f_ab[j].push_back(model(m[0], m[1], m[2]));
      }
    }
  }
  const std::vector<const SobolSamples*> all{&outputs[0], &outputs[1], &outputs[2]};
  const std::vector<SobolIndices> together = sobol_indices(all, 64, 0.9, 11, 1);
  const std::vector<SobolIndices> on_three = sobol_indices(all, 64, 0.9, 11, 3);
  REQUIRE(together.size() == 3);
  for (std::size_t o = 0; o < 3; ++o) {
    INFO("output " << o);
    const SobolIndices alone = sobol_indices(outputs[o].f_a, outputs[o].f_b, outputs[o].f_ab, 64, 0.9, 11, 2);
    CHECK(together[o].variance == alone.variance);
    REQUIRE(together[o].indices.size() == d);
    for (std::size_t j = 0; j < d; ++j) {
      for (const SobolIndices* r : {&together[o], &on_three[o]}) {
        CHECK(r->indices[j].first == alone.indices[j].first);
        CHECK(r->indices[j].total == alone.indices[j].total);
        CHECK(r->indices[j].first_interval.lower == alone.indices[j].first_interval.lower);
        CHECK(r->indices[j].total_interval.upper == alone.indices[j].total_interval.upper);
      }
    }
  }
  // Output 0 is additive: S_j = ST_j, and the intervals hold the estimates.
  for (std::size_t j = 0; j < d; ++j) {
    CHECK_THAT(together[0].indices[j].first, Catch::Matchers::WithinAbs(together[0].indices[j].total, 0.05));
    CHECK(*together[0].indices[j].total_interval.lower <= together[0].indices[j].total);
    CHECK(*together[0].indices[j].total_interval.upper >= together[0].indices[j].total);
  }
  CHECK(together[2].variance == 0.0);
  SobolSamples shorter = outputs[1];
  shorter.f_a.pop_back();
  CHECK_THROWS_AS(sobol_indices({&outputs[0], &shorter}, 8, 0.9, 11, 1), std::invalid_argument);
}

TEST_CASE("Counter rows: the same numbers as counter_uniform, bit for bit", "[uncertainty]") {
  for (std::uint64_t seed : {0ull, 1ull, 0xFFFFFFFFFFFFFFFFull})
    for (std::uint64_t i : {0ull, 7ull, 1ull << 40}) {
      const CounterRow row(seed, 11, i);
      for (std::uint64_t j : {0ull, 1ull, 999ull, 1ull << 50}) CHECK(row(j) == counter_uniform(seed, 11, i, j));
    }
}

TEST_CASE("Sobol' bootstrap intervals equal those of resamples drawn one by one, a short last group included",
          "[uncertainty]") {
  // The resamples are counted side by side in groups of eight (13: a group of 8 and one of 5).
  // Here each resample is drawn as written in docs/methods/uncertainty.md: draw i of resample r is
  // base sample floor(u(seed, 11, r, i) N), the estimators over the drawn rows (centred on the
  // mean of all values), then the percentile interval of the 13 estimates. A mistake in how the
  // groups are laid out would show here, whichever version of the sums the processor runs.
  const std::size_t n = 500, d = 2, bootstrap = 13;
  const double confidence = 0.8;
  const std::uint64_t seed = 7;
  SobolSamples f;
  f.f_ab.assign(d, {});
  for (std::size_t i = 0; i < n; ++i) {
    const auto model = [](double x1, double x2) { return std::sin(3 * x1) + 2 * x2 * x2 + x1 * x2; };
    const double a[2] = {counter_uniform(9, 1, i, 0), counter_uniform(9, 1, i, 1)};
    const double b[2] = {counter_uniform(9, 2, i, 0), counter_uniform(9, 2, i, 1)};
    f.f_a.push_back(model(a[0], a[1]));
    f.f_b.push_back(model(b[0], b[1]));
    f.f_ab[0].push_back(model(b[0], a[1]));
    f.f_ab[1].push_back(model(a[0], b[1]));
  }
  const SobolIndices got = sobol_indices(f.f_a, f.f_b, f.f_ab, bootstrap, confidence, seed, 2);

  double centre = 0;
  for (std::size_t i = 0; i < n; ++i) centre += f.f_a[i] + f.f_b[i] + f.f_ab[0][i] + f.f_ab[1][i];
  centre /= static_cast<double>(n * (2 + d));
  std::vector<std::vector<double>> first(d), total(d);
  for (std::size_t r = 0; r < bootstrap; ++r) {
    const CounterRow draw(seed, 11, r);
    std::vector<std::size_t> pick(n);
    for (std::size_t i = 0; i < n; ++i) pick[i] = std::min(static_cast<std::size_t>(draw(i) * static_cast<double>(n)), n - 1);
    double sum = 0, squares = 0;
    for (std::size_t i : pick) sum += (f.f_a[i] - centre) + (f.f_b[i] - centre);
    const double mean = sum / (2.0 * n);
    for (std::size_t i : pick) squares += std::pow(f.f_a[i] - centre - mean, 2) + std::pow(f.f_b[i] - centre - mean, 2);
    const double variance = squares / (2.0 * n - 1);
    for (std::size_t j = 0; j < d; ++j) {
      double s1 = 0, s2 = 0;
      for (std::size_t i : pick) {
        const double a = f.f_a[i] - centre, b = f.f_b[i] - centre, ab = f.f_ab[j][i] - centre;
        s1 += b * (ab - a);
        s2 += (a - ab) * (a - ab);
      }
      first[j].push_back(s1 / n / variance);
      total[j].push_back(s2 / (2.0 * n) / variance);
    }
  }
  // Type 7 quantiles of the sorted estimates at (1 -+ confidence) / 2.
  const auto percentile = [&](std::vector<double> x, double p) {
    std::sort(x.begin(), x.end());
    const double h = (static_cast<double>(x.size()) - 1) * p;
    const auto lo = static_cast<std::size_t>(std::floor(h));
    return lo + 1 < x.size() ? x[lo] + (h - static_cast<double>(lo)) * (x[lo + 1] - x[lo]) : x[lo];
  };
  const double alpha = 1 - confidence;
  REQUIRE(got.indices.size() == d);
  for (std::size_t j = 0; j < d; ++j) {
    INFO("x" << j + 1);
    REQUIRE(got.indices[j].first_interval.lower);
    REQUIRE(got.indices[j].total_interval.upper);
    CHECK_THAT(*got.indices[j].first_interval.lower, Catch::Matchers::WithinRel(percentile(first[j], alpha / 2), 1e-9) ||
                                                         Catch::Matchers::WithinAbs(percentile(first[j], alpha / 2), 1e-12));
    CHECK_THAT(*got.indices[j].first_interval.upper, Catch::Matchers::WithinRel(percentile(first[j], 1 - alpha / 2), 1e-9) ||
                                                         Catch::Matchers::WithinAbs(percentile(first[j], 1 - alpha / 2), 1e-12));
    CHECK_THAT(*got.indices[j].total_interval.lower, Catch::Matchers::WithinRel(percentile(total[j], alpha / 2), 1e-9) ||
                                                         Catch::Matchers::WithinAbs(percentile(total[j], alpha / 2), 1e-12));
    CHECK_THAT(*got.indices[j].total_interval.upper, Catch::Matchers::WithinRel(percentile(total[j], 1 - alpha / 2), 1e-9) ||
                                                         Catch::Matchers::WithinAbs(percentile(total[j], 1 - alpha / 2), 1e-12));
  }
}

TEST_CASE("Studies: asked to stop while the answers are made, they give none and say so", "[uncertainty]") {
  // Ctrl-C or SIGTERM after the last case: the bootstrap stops drawing and the outcome is marked
  // stopped (the command then exits 130), where it had finished the answers and exited 0.
  InProcess r = run_study(ishigami_scene("sobol", 256), 2);
  REQUIRE_FALSE(r->summary.stopped);
  const std::atomic<bool> stop{true};
  host::finish_study(*r, &stop);
  CHECK(r->summary.stopped);
  // Not asked: the same answers as before, bit for bit.
  const std::string json = r->json;
  InProcess again = run_study(ishigami_scene("sobol", 256), 2);
  const std::atomic<bool> go_on{false};
  host::finish_study(*again, &go_on);
  CHECK_FALSE(again->summary.stopped);
  CHECK(again->json == json);
}

TEST_CASE("Studies: what a study holds beside its cases and its bootstrap's work are budgeted", "[uncertainty]") {
  // 256 base samples of the Ishigami function with sensitivity: 1280 cases, 50 resamples.
  const auto study_within = [](double max_memory, double max_work) {
    WorkBudget budget;
    budget.max_memory = max_memory;
    budget.max_work = max_work;
    return host::run_scene_study(parse_scene(ishigami_scene("sobol", 256), "study.yaml"), uq_registry(), {}, std::nullopt, "", "", "",
                                 std::nullopt, budget, 1, nullptr);
  };
  CHECK_THROWS_WITH(study_within(1e4, 1e12), Contains("study.yaml: the study would hold about") && Contains("--max-memory"));
  CHECK_THROWS_WITH(study_within(4e9, 5e4), Contains("study.yaml: the study's bootstrap asks for about") && Contains("--max-work"));
  CHECK(study_within(4e9, 1e9)->answers.cases == 1280);
  // The design's own cap, 2.5 x 10^8 values (a value a parameter a case), says how many samples
  // fit, and comes before the memory budget (raising --max-memory could not lift it): 30
  // parameters of 9 x 10^6 Monte Carlo samples are 2.7 x 10^8 values.
  const auto uniforms = [](std::size_t samples, int parameters) {
    std::string yaml = "uncertainty:\n  method: monte_carlo\n  samples: " + std::to_string(samples) + "\n  parameters:\n";
    for (int k = 0; k < parameters; ++k) yaml += "    p" + std::to_string(k) + ": { uniform: { lower: 0, upper: 1 } }\n";
    return study_of(yaml + "nodes: {}\n");
  };
  WorkBudget tight;
  tight.max_memory = 1e4;
  CHECK_THROWS_WITH(host::check_study_budget(uniforms(9'000'000, 30), 1, tight, "study.yaml"),
                    Contains("samples: 9000000") && Contains("at most 8333333 samples"));
  CHECK_NOTHROW(check_design_size(uniforms(8'333'333, 30)));
  // The table keeps a double a value (CaseTable::Numbers), so the budget counts 8 bytes a value:
  // 1.5 x 10^6 Sobol' samples of three parameters (7.5 x 10^6 cases, 2.25 x 10^7 values, which the
  // cap of a table of CaseValue refused) are the memory budget's to judge, and it says so.
  StudySpec sobol = study_of(ishigami_scene("sobol", 1'500'000));
  CHECK_NOTHROW(check_design_size(sobol));
  CHECK_THROWS_WITH(host::check_study_budget(sobol, 1, tight, "study.yaml"), Contains("the study would hold about") && Contains("--max-memory"));
  WorkBudget roomy;
  const double held = host::check_study_budget(sobol, 1, roomy, "study.yaml");
  const double table = 7.5e6 * 3 * sizeof(double), outputs = 7.5e6 * (sizeof(double) + sizeof(CaseFailure));
  const double sobol_rows = 2.0 * 1.5e6 * 5 * sizeof(double), draws = 2.0 * 3 * 50 * sizeof(double);
  const double order = 7.5e6 * sizeof(std::size_t);  // the cases' indices the sweep runs them by
  const double scratch = 3e6 * (sizeof(std::size_t) + sizeof(double));  // 2N statistical rows, one output
  CHECK_THAT(held, Catch::Matchers::WithinRel(table + outputs + sobol_rows + draws + order + scratch, 1e-12));
}

TEST_CASE("Studies: a rare event's study beyond 10^7 evaluations is the budget's to judge, not a count's", "[uncertainty][bounds]") {
  // A 1 ppm event needs some 10^7 plain samples or more for a useful interval; the count cap of
  // 10^7 cases (sized when a design kept written values) refused them. Now a study is bounded by
  // its table (2.5 x 10^8 values) and the memory budget: 3 x 10^7 Monte Carlo samples of two
  // parameters, and 4 x 10^6 Sobol' samples of three (2 x 10^7 cases), pass every check before
  // the design is made; the count's own bound is the table's, and says so.
  const auto uniforms = [](std::size_t samples, int parameters, const char* method) {
    std::string yaml = std::string("uncertainty:\n  method: ") + method + "\n  samples: " + std::to_string(samples) + "\n  parameters:\n";
    for (int k = 0; k < parameters; ++k) yaml += "    p" + std::to_string(k) + ": { uniform: { lower: 0, upper: 1 } }\n";
    return study_of(yaml + "nodes: {}\n");
  };
  StudySpec plain = uniforms(30'000'000, 2, "monte_carlo");
  CHECK(plain.evaluations() == 30'000'000);
  CHECK_NOTHROW(check_design_size(plain));
  const double held = host::check_study_budget(plain, 1, WorkBudget{}, "study.yaml");  // 4 GiB by default
  // design, output, failure, order; and the answers' scratch: indices and values (one output)
  CHECK_THAT(held, Catch::Matchers::WithinRel(3e7 * (2 * 8.0 + 8.0 + sizeof(CaseFailure) + sizeof(std::size_t) + 8.0 + 8.0), 1e-12));
  StudySpec sobol = study_of(ishigami_scene("sobol", 1024));
  host::apply_study_options(sobol, "4000000", "", "");
  CHECK(sobol.evaluations() == 20'000'000);
  CHECK_NOTHROW(check_design_size(sobol));
  WorkBudget study_defaults;  // a study's, as the command line and Python set them
  study_defaults.max_work = 1e12;
  CHECK_NOTHROW(host::check_study_budget(sobol, 1, study_defaults, "study.yaml"));
  // Beyond the table's count: refused by name, before anything is made.
  CHECK_THROWS_WITH(host::apply_study_options(sobol, "60000000", "", ""),
                    Contains("the design would need 300000000 evaluations, more than 2.5 x 10^8"));
  CHECK_THROWS_WITH(host::apply_study_options(sobol, "250000001", "", ""), Contains("is not a whole number from 2 to 250000000"));
  CHECK_THROWS_WITH(uniforms(250'000'001, 1, "monte_carlo"), Contains("samples"));
}
