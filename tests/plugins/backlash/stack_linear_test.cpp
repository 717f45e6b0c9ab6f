// stack.linear against published stack-ups and closed forms (docs/methods/backlash.md,
// "Stacking methods side by side").
#include "test_support.hpp"

#include "backlash/node_types.hpp"
#include "backlash/stacking.hpp"
#include "backlash/variates.hpp"

#include <mechgraph/errors.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

using namespace mechgraph;
using namespace mechgraph::testing;
using Catch::Matchers::Contains;

namespace {

constexpr double inch = 0.0254;
constexpr double mm = 1e-3;

Record link(double nominal, double upper, double lower, double sensitivity = 1.0, const char* distribution = "normal") {
  return {{"nominal", ParamValue::of_number(nominal)},
          {"upper", ParamValue::of_number(upper)},
          {"lower", ParamValue::of_number(lower)},
          {"sensitivity", ParamValue::of_number(sensitivity)},
          {"distribution", ParamValue::of_choice(distribution)}};
}

ParamValue links_of(std::vector<Record> records) {
  ParamValue v;
  v.kind = ParamKind::record_list;
  v.records = std::move(records);
  return v;
}

struct Run {
  OutputSet out;
  std::map<std::string, double> work;
};

Run run_stack(std::vector<Record> records, std::vector<std::string> effects = {},
              std::map<std::string, ParamValue> extra = {}) {
  auto type = backlash::make_stack_linear_type();
  extra["links"] = links_of(std::move(records));
  Run r;
  RecordingContext ctx(std::move(effects));
  type->evaluate(defaults_of(type->info(), extra), InputSet{}, r.out, ctx);
  r.work = ctx.work;
  return r;
}

double scalar(const OutputSet& o, const std::string& port) { return o.all().at(port).as_scalar(); }
const std::vector<double>& series(const OutputSet& o, const std::string& port) { return o.all().at(port).as_series().values; }

// The motor assembly of P. J. Drake (ed.), "Dimensioning and Tolerancing Handbook", McGraw-Hill
// 1999, chapter 9 (axial gap of a motor's shaft stack, inches), as transcribed, with the book's
// printed results in its comments, in tests/test_McGrawHill.py of github.com/phcreery/dimstack.
// Each part: nominal, upper, lower deviation, direction in the vector loop.
std::vector<Record> drake_motor_assembly() {
  return {
      link(0.375 * inch, 0.0, -0.031 * inch, -1),           // A screw thread length
      link(0.032 * inch, 0.002 * inch, -0.002 * inch, +1),  // B washer length
      link(0.060 * inch, 0.003 * inch, -0.003 * inch, +1),  // C inner bearing cap turned length
      link(0.438 * inch, 0.0, -0.015 * inch, +1),           // D bearing length
      link(0.120 * inch, 0.005 * inch, -0.005 * inch, +1),  // E spacer turned length
      link(1.500 * inch, 0.010 * inch, -0.004 * inch, +1),  // F rotor length
      link(0.120 * inch, 0.005 * inch, -0.005 * inch, +1),  // G spacer turned length
      link(0.438 * inch, 0.0, -0.015 * inch, +1),           // H bearing length
      link(0.450 * inch, 0.007 * inch, -0.007 * inch, +1),  // I pulley casting length
      link(3.019 * inch, 0.012 * inch, 0.0, -1),            // J shaft turned length
      link(0.300 * inch, 0.030 * inch, -0.030 * inch, +1),  // K tapped hole depth
  };
}

// The MITCalc "Tolerance analysis" demonstration (shaft, retaining ring, bearings, sleeves and a
// case, mm), as transcribed with MITCalc's printed results in tests/test_mitcalc.py of
// github.com/phcreery/dimstack.
std::vector<Record> mitcalc_demo() {
  return {
      link(208 * mm, 0.036 * mm, -0.036 * mm, +1),  // a shaft
      link(1.75 * mm, 0.0, -0.06 * mm, -1),         // b retaining ring
      link(23 * mm, 0.0, -0.12 * mm, -1),           // c bearing
      link(20 * mm, 0.026 * mm, -0.026 * mm, +1),   // d bearing sleeve
      link(200 * mm, 0.145 * mm, -0.145 * mm, -1),  // e case
      link(20 * mm, 0.026 * mm, -0.026 * mm, +1),   // f bearing sleeve
      link(23 * mm, 0.0, -0.12 * mm, -1),           // g bearing
  };
}

// |x - printed| within half a unit of the printed last digit.
void check_printed(double value, double printed, double last_digit) {
  CHECK(value == Approx(printed).epsilon(0).margin(0.5 * last_digit));
}

}  // namespace

TEST_CASE("stack.linear reproduces the Drake handbook motor assembly (worst case and RSS)", "[backlash]") {
  const Run r = run_stack(drake_motor_assembly());
  // Printed: gap 0.0615 +- 0.0955 (worst case: -0.034 .. 0.157); RSS 0.0615 +- 0.0381 (0.0234 .. 0.0996) in.
  const double mean = scalar(r.out, "mean") / inch;
  CHECK(mean == Approx(0.0615).epsilon(1e-12).margin(1e-12));
  check_printed((scalar(r.out, "worst_case_max") - scalar(r.out, "mean")) / inch, 0.0955, 1e-4);
  check_printed(scalar(r.out, "worst_case_min") / inch, -0.034, 1e-3);
  check_printed(scalar(r.out, "worst_case_max") / inch, 0.157, 1e-3);
  check_printed(3 * scalar(r.out, "rss_sigma") / inch, 0.0381, 1e-4);
  check_printed(scalar(r.out, "rss_min") / inch, 0.0234, 1e-4);
  check_printed(scalar(r.out, "rss_max") / inch, 0.0996, 1e-4);
  // The tapped hole depth K (+-0.030 of 0.0955) leads both Pareto charts.
  const auto& wc = series(r.out, "contribution_worst_case");
  REQUIRE(wc.size() == 11);
  CHECK(wc[10] == Approx(0.030 / 0.0955).epsilon(1e-12).margin(1e-15));
  CHECK(series(r.out, "contribution_rss")[10] == Approx(0.030 * 0.030 / 0.00144975).epsilon(1e-12).margin(1e-15));
}

TEST_CASE("stack.linear reproduces the MITCalc tolerance-analysis demonstration", "[backlash]") {
  const Run r = run_stack(mitcalc_demo());
  // Printed: mean 0.4, worst case +-0.383 (0.017 .. 0.783) mm; RSS +-0.17825 mm (sigma 0.059417).
  CHECK(scalar(r.out, "mean") / mm == Approx(0.4).epsilon(1e-12).margin(1e-12));
  check_printed((scalar(r.out, "worst_case_max") - scalar(r.out, "mean")) / mm, 0.383, 1e-3);
  check_printed(scalar(r.out, "worst_case_min") / mm, 0.017, 1e-3);
  check_printed(scalar(r.out, "worst_case_max") / mm, 0.783, 1e-3);
  check_printed(3 * scalar(r.out, "rss_sigma") / mm, 0.17825, 1e-5);
  check_printed(scalar(r.out, "rss_sigma") / mm, 0.059417, 1e-6);
}

TEST_CASE("RSS sigma against the closed forms of normal, uniform and triangular links", "[backlash]") {
  // Variances: normal with T = 6 sigma: (h/3)^2; uniform on [m-h, m+h]: (2h)^2/12;
  // symmetric triangular on [m-h, m+h]: (2h)^2/24.
  const double hn = 0.03 * mm, hu = 0.02 * mm, ht = 0.06 * mm;
  const Run r = run_stack({link(10 * mm, hn, -hn, 2.0, "normal"), link(5 * mm, 0.01 * mm + hu, 0.01 * mm - hu, -1.0, "uniform"),
                           link(8 * mm, ht, -ht, 0.5, "triangular")});
  const double vn = 4.0 * (hn / 3) * (hn / 3), vu = (2 * hu) * (2 * hu) / 12, vt = 0.25 * (2 * ht) * (2 * ht) / 24;
  CHECK(scalar(r.out, "rss_sigma") == Approx(std::sqrt(vn + vu + vt)).epsilon(1e-14).margin(0));
  CHECK(scalar(r.out, "mean") == Approx(2 * 10 * mm - 5.01 * mm + 0.5 * 8 * mm).epsilon(1e-14).margin(0));
  CHECK(scalar(r.out, "worst_case_max") - scalar(r.out, "mean") == Approx(2 * hn + hu + 0.5 * ht).epsilon(1e-12).margin(0));
  const auto& share = series(r.out, "contribution_rss");
  CHECK(share[0] == Approx(vn / (vn + vu + vt)).epsilon(1e-13).margin(0));
  CHECK(share[1] == Approx(vu / (vn + vu + vt)).epsilon(1e-13).margin(0));
  CHECK(share[2] == Approx(vt / (vn + vu + vt)).epsilon(1e-13).margin(0));
  const auto& worst = series(r.out, "contribution_worst_case");
  CHECK(worst[0] + worst[1] + worst[2] == Approx(1.0).epsilon(1e-15).margin(1e-15));
  CHECK(worst[1] == Approx(hu / (2 * hn + hu + 0.5 * ht)).epsilon(1e-13).margin(0));
  CHECK(r.out.all().count("mc_mean") == 0);  // Monte Carlo only with its effect
  CHECK(r.work.empty());
}

TEST_CASE("Monte Carlo agrees with the closed forms within its reported standard errors", "[backlash]") {
  const double hn = 0.03 * mm, hu = 0.02 * mm, ht = 0.06 * mm;
  const std::vector<Record> links{link(10 * mm, hn, -hn, 2.0, "normal"), link(5 * mm, 0.01 * mm + hu, 0.01 * mm - hu, -1.0, "uniform"),
                                  link(8 * mm, ht, -ht, 0.5, "triangular")};
  const Run r = run_stack(links, {"monte_carlo"});
  CHECK(r.work.at("samples") == 100000.0);
  const double mean = scalar(r.out, "mean"), sigma = scalar(r.out, "rss_sigma");
  const double mean_error = scalar(r.out, "mc_mean_error"), sigma_error = scalar(r.out, "mc_sigma_error");
  CHECK(mean_error == Approx(scalar(r.out, "mc_sigma") / std::sqrt(1e5)).epsilon(1e-14).margin(0));
  CHECK(sigma_error == Approx(scalar(r.out, "mc_sigma") / std::sqrt(2.0 * 99999)).epsilon(1e-14).margin(0));
  CHECK(scalar(r.out, "mc_mean") == Approx(mean).epsilon(0).margin(4 * mean_error));
  // sigma/sqrt(2(N-1)) is exact for normal samples; these links have kurtosis <= 3, so it is generous.
  CHECK(scalar(r.out, "mc_sigma") == Approx(sigma).epsilon(0).margin(4 * sigma_error));
  CHECK(scalar(r.out, "mc_min") >= scalar(r.out, "worst_case_min") - 2 * hn);  // only the normal link is unbounded
  CHECK(scalar(r.out, "mc_min") < scalar(r.out, "mc_q001"));
  CHECK(scalar(r.out, "mc_q999") < scalar(r.out, "mc_max"));

  // One uniform link: every sample inside [m - h, m + h], the extremes within a few h/N of the ends.
  const Run u = run_stack({link(1 * mm, 0.05 * mm, -0.05 * mm, 1.0, "uniform")}, {"monte_carlo"});
  CHECK(scalar(u.out, "mc_min") >= 0.95 * mm);
  CHECK(scalar(u.out, "mc_max") < 1.05 * mm);
  CHECK(scalar(u.out, "mc_max") > 1.05 * mm - 1e-3 * mm);
  CHECK(scalar(u.out, "mc_sigma") == Approx(0.1 * mm / std::sqrt(12.0)).epsilon(0).margin(4 * scalar(u.out, "mc_sigma_error")));
}

TEST_CASE("Monte Carlo quantiles of a normal stack are the +-3 sigma limits", "[backlash]") {
  const Run r = run_stack({link(120 * mm, 0.05 * mm, -0.05 * mm, 1), link(3.5 * mm, 0, -0.04 * mm, -1)}, {"monte_carlo"});
  const double mean = scalar(r.out, "mean"), sigma = scalar(r.out, "rss_sigma");
  // Standard error of the p-quantile of N normal samples: sqrt(p (1 - p) / N) / phi(z_p) * sigma, z_p = 3.
  const double p = backlash::probability_minus_3_sigma;
  const double q_error = std::sqrt(p * (1 - p) / 1e5) / (std::exp(-4.5) / std::sqrt(2 * std::numbers::pi)) * sigma;
  CHECK(scalar(r.out, "mc_q999") == Approx(mean + 3 * sigma).epsilon(0).margin(4 * q_error));
  CHECK(scalar(r.out, "mc_q001") == Approx(mean - 3 * sigma).epsilon(0).margin(4 * q_error));
  CHECK(scalar(r.out, "rss_max") == Approx(mean + 3 * sigma).epsilon(1e-15).margin(0));
  CHECK(mean == Approx(116.52 * mm).epsilon(1e-14).margin(0));
}

TEST_CASE("Monte Carlo is reproducible: the same seed gives the same numbers, another seed others", "[backlash]") {
  const std::vector<Record> links{link(10 * mm, 0.03 * mm, -0.03 * mm, 1, "triangular"), link(4 * mm, 0.01 * mm, -0.02 * mm, -1, "uniform"),
                                  link(2 * mm, 0.01 * mm, -0.01 * mm, 1, "normal")};
  const std::map<std::string, ParamValue> small{{"samples", ParamValue::of_integer(5000)}};
  auto seeded = small;
  seeded["seed"] = ParamValue::of_integer(7);
  const Run a = run_stack(links, {"monte_carlo"}, small), b = run_stack(links, {"monte_carlo"}, small);
  const Run c = run_stack(links, {"monte_carlo"}, seeded);
  for (const char* port : {"mc_mean", "mc_sigma", "mc_min", "mc_max", "mc_q001", "mc_q999"}) {
    CHECK(scalar(a.out, port) == scalar(b.out, port));
    CHECK(scalar(a.out, port) != scalar(c.out, port));
  }
  CHECK(a.work.at("samples") == 5000.0);
}

TEST_CASE("sample quantiles interpolate between order statistics", "[backlash]") {
  const std::vector<double> sorted{1.0, 2.0, 4.0, 8.0, 16.0};
  CHECK(backlash::quantile_of_sorted(sorted, 0.0) == 1.0);
  CHECK(backlash::quantile_of_sorted(sorted, 1.0) == 16.0);
  CHECK(backlash::quantile_of_sorted(sorted, 0.5) == 4.0);
  CHECK(backlash::quantile_of_sorted(sorted, 0.625) == Approx(6.0).epsilon(1e-15).margin(0));  // h = 2.5
  const auto s = backlash::summarize({3.0, 1.0, 2.0});
  CHECK(s.mean == 2.0);
  CHECK(s.sigma == Approx(1.0).epsilon(1e-15).margin(0));
  CHECK(s.min == 1.0);
  CHECK(s.max == 3.0);
}

TEST_CASE("stack.linear rejects an empty stack and crossed limit deviations, naming the parameter", "[backlash]") {
  auto names_links = [](const NodeError& e) { return e.parameter() == "links"; };
  CHECK_THROWS_MATCHES(run_stack({}), NodeError, Catch::Matchers::Predicate<NodeError>(names_links));
  CHECK_THROWS_MATCHES(run_stack({link(10 * mm, -0.02 * mm, 0.01 * mm)}), NodeError, Catch::Matchers::Predicate<NodeError>(names_links));
  CHECK_THROWS_WITH(run_stack({link(10 * mm, -0.02 * mm, 0.01 * mm)}), Contains("below the lower deviation"));
  CHECK_THROWS_MATCHES(run_stack({link(1 * mm, 0.01 * mm, 0)}, {"monte_carlo"}, {{"samples", ParamValue::of_integer(10)}}),
                       NodeError,
                       Catch::Matchers::Predicate<NodeError>([](const NodeError& e) { return e.parameter() == "samples"; }));
}

TEST_CASE("stack.linear from a scene: units, record fields and defaults through the loader", "[backlash]") {
  REQUIRE(project_registry().find("stack.linear"));  // the backlash plugin, built with the tests
  const char* scene = R"(nodes:
  stack: { type: stack.linear, params: { links: [
           { nominal: 120 mm, upper: 0.05 mm, lower: -0.05 mm, sensitivity: 1, distribution: normal },
           { nominal: 3.5 mm, upper: 0 mm, lower: -0.04 mm, sensitivity: -1 } ] } }
outputs: [ stack.mean, stack.worst_case_max, stack.rss_sigma ]
)";
  MemoCache cache;
  const RunResult r = evaluate(graph_from(scene, project_registry()), cache);
  CHECK(output(r, "stack.mean").as_scalar() == Approx(116.52e-3).epsilon(1e-14).margin(0));
  CHECK(output(r, "stack.worst_case_max").as_scalar() == Approx(116.59e-3).epsilon(1e-14).margin(0));
  CHECK(output(r, "stack.rss_sigma").as_scalar() ==
        Approx(std::hypot(0.05e-3 / 3, 0.02e-3 / 3)).epsilon(1e-13).margin(0));
}

TEST_CASE("summarize: quantiles by selection equal those of the sorted sample", "[backlash][stack]") {
  // Second method: sort everything and interpolate (quantile_of_sorted).
  std::vector<double> sample;
  std::uint64_t state = 12345;
  for (int i = 0; i < 10007; ++i) {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    sample.push_back(static_cast<double>(state >> 11) * 0x1.0p-53 * 3.0 - 1.0);
  }
  const backlash::SampleSummary s = backlash::summarize(sample);
  std::vector<double> sorted = sample;
  std::sort(sorted.begin(), sorted.end());
  CHECK(s.q_low == backlash::quantile_of_sorted(sorted, backlash::probability_minus_3_sigma));
  CHECK(s.q_high == backlash::quantile_of_sorted(sorted, backlash::probability_plus_3_sigma));
  CHECK(s.min == sorted.front());
  CHECK(s.max == sorted.back());
}

TEST_CASE("Monte Carlo variates: normal, uniform and triangular pass a Kolmogorov-Smirnov test", "[backlash][stack]") {
  // Second method: the exact distribution functions. D_n > 1.95 / sqrt(n) has probability ~0.1 %
  // for a correct generator; a wrong ziggurat table or tail shows far above it.
  const std::size_t n = 200000;
  backlash::Variates v(2026);
  auto ks = [&](auto draw, auto cdf) {
    std::vector<double> x(n);
    for (double& xi : x) xi = draw();
    std::sort(x.begin(), x.end());
    double d = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      const double f = cdf(x[i]);
      d = std::max({d, std::abs(f - static_cast<double>(i) / n), std::abs(f - static_cast<double>(i + 1) / n)});
    }
    return d * std::sqrt(static_cast<double>(n));
  };
  const double normal = ks([&] { return v.normal(); }, [](double x) { return 0.5 * std::erfc(-x / std::sqrt(2.0)); });
  const double uniform = ks([&] { return v.uniform(); }, [](double x) { return std::clamp(0.5 * (x + 1.0), 0.0, 1.0); });
  const double triangular = ks([&] { return v.triangular(); },
                               [](double x) { return x < 0 ? 0.5 * (1 + x) * (1 + x) : 1 - 0.5 * (1 - x) * (1 - x); });
  std::vector<double> block(n);
  std::size_t next = n;
  const double normal_block = ks(
      [&] {
        if (next == n) {
          v.normals(block.data(), n);
          next = 0;
        }
        return block[next++];
      },
      [](double x) { return 0.5 * std::erfc(-x / std::sqrt(2.0)); });
  std::vector<double> tri(n);
  v.triangulars(tri.data(), n);
  std::size_t t_next = 0;
  const double triangular_block = ks([&] { return tri[t_next++]; },
                                     [](double x) { return x < 0 ? 0.5 * (1 + x) * (1 + x) : 1 - 0.5 * (1 - x) * (1 - x); });
  CHECK(normal < 1.95);
  CHECK(normal_block < 1.95);
  CHECK(uniform < 1.95);
  CHECK(triangular < 1.95);
  CHECK(triangular_block < 1.95);
  // The ziggurat's tail beyond r = 3.654 and its wedges: the fraction beyond 3 and 4 sigma.
  std::size_t beyond3 = 0, beyond4 = 0;
  const std::size_t m = 4000000;
  std::vector<double> z(m);
  v.normals(z.data(), m);  // the block path: its strips' cores, wedges and tail
  for (double x : z) {
    beyond3 += std::abs(x) > 3.0;
    beyond4 += std::abs(x) > 4.0;
  }
  const double p3 = std::erfc(3.0 / std::sqrt(2.0)), p4 = std::erfc(4.0 / std::sqrt(2.0));
  CHECK(std::abs(static_cast<double>(beyond3) / m - p3) < 4.0 * std::sqrt(p3 / m));
  CHECK(std::abs(static_cast<double>(beyond4) / m - p4) < 4.0 * std::sqrt(p4 / m));
}

TEST_CASE("summarize: the tail selection of a normal sample equals sorting it", "[backlash][stack]") {
  backlash::Variates v(7);
  std::vector<double> sample(100003);
  for (double& x : sample) x = 5.0 + 0.1 * v.normal();
  const backlash::SampleSummary s = backlash::summarize(sample);
  std::sort(sample.begin(), sample.end());
  CHECK(s.q_low == backlash::quantile_of_sorted(sample, backlash::probability_minus_3_sigma));
  CHECK(s.q_high == backlash::quantile_of_sorted(sample, backlash::probability_plus_3_sigma));
}

TEST_CASE("Monte Carlo streamed: the same quantiles as all the samples kept, the moments to rounding", "[backlash][stack]") {
  // Second method: summarize() over every sample kept. A normal stack (tails found at once) and a
  // uniform one (no sample beyond mean + 2 sigma: the stream is run again with nearer thresholds).
  for (const auto distribution : {Distribution::normal, Distribution::uniform}) {
    INFO("distribution " << static_cast<int>(distribution));
    std::vector<ToleranceLink> links = {{"a", 0.010, 1e-4, 1.0, distribution}};
    backlash::PlayStack stack;
    stack.own_mean = 25e-6;
    stack.own_sigma = 25e-6 / 3;
    stack.terms.push_back({1.0, {"fit", {{"hole", 0.02005, 6.5e-5, 1.0, distribution}, {"shaft", 0.01994, 6.5e-5, -1.0, distribution}}}});
    const std::size_t n = 300001;
    const auto stream = backlash::monte_carlo_linear_stack(links, n, 3);
    const auto kept = backlash::summarize(backlash::sample_linear_stack(links, n, 3));
    CHECK(stream.q_low == kept.q_low);
    CHECK(stream.q_high == kept.q_high);
    CHECK(stream.min == kept.min);
    CHECK(stream.max == kept.max);
    CHECK_THAT(stream.mean, Catch::Matchers::WithinRel(kept.mean, 1e-14));
    CHECK_THAT(stream.sigma, Catch::Matchers::WithinRel(kept.sigma, 1e-10));
    const auto play_stream = backlash::monte_carlo_play_stack(stack, n, 9);
    const auto play_kept = backlash::summarize(backlash::sample_play_stack(stack, n, 9));
    CHECK(play_stream.q_high == play_kept.q_high);
    CHECK(play_stream.q_low == play_kept.q_low);
    CHECK_THAT(play_stream.mean, Catch::Matchers::WithinRel(play_kept.mean, 1e-13));
    CHECK_THAT(play_stream.sigma, Catch::Matchers::WithinRel(play_kept.sigma, 1e-10));
  }
}
