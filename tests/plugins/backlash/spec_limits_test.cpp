// Results against specification limits: Cp, Cpk and ppm out of spec from the normal model against
// published figures (+-3 sigma: 2700 ppm; 4.5 sigma one-sided: the 3.4 ppm of "six sigma"), and the
// Monte Carlo share out of spec against the normal model within its standard error; the streamed
// count against a count over kept samples; refusals.
#include "backlash/node_types.hpp"
#include "backlash/spec_limits.hpp"
#include "backlash/stacking.hpp"
#include "test_support.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

using namespace mechgraph;
using namespace mechgraph::backlash;
using namespace mechgraph::testing;

namespace {

constexpr double mm = 1e-3;

Record link(double nominal, double upper, double lower) {
  return {{"nominal", ParamValue::of_number(nominal)},
          {"upper", ParamValue::of_number(upper)},
          {"lower", ParamValue::of_number(lower)},
          {"sensitivity", ParamValue::of_number(1.0)},
          {"distribution", ParamValue::of_choice("normal")}};
}

ParamValue records(std::vector<Record> r) {
  ParamValue v;
  v.kind = ParamKind::record_list;
  v.records = std::move(r);
  return v;
}

Record spec(std::optional<double> lower, std::optional<double> upper) {
  Record r;
  if (lower) r["lower"] = ParamValue::of_number(*lower);
  if (upper) r["upper"] = ParamValue::of_number(*upper);
  return r;
}

OutputSet run_stack(const Record& limits, bool monte_carlo, long samples = 200000) {
  auto type = make_stack_linear_type();
  // Two normal links of T = 0.06 mm (sigma 0.01 mm each): sigma = 0.01 sqrt(2) mm about 10 mm.
  std::map<std::string, ParamValue> p{{"links", records({link(6 * mm, 0.03 * mm, -0.03 * mm), link(4 * mm, 0.03 * mm, -0.03 * mm)})},
                                      {"spec", records({limits})},
                                      {"samples", ParamValue::of_integer(samples)}};
  OutputSet out;
  RecordingContext ctx(monte_carlo ? std::vector<std::string>{"monte_carlo"} : std::vector<std::string>{});
  type->evaluate(defaults_of(type->info(), p), InputSet{}, out, ctx);
  return out;
}

double scalar(const OutputSet& o, const char* port) { return o.all().at(port).as_scalar(); }

}  // namespace

TEST_CASE("the normal model's Cp, Cpk and ppm match the published figures") {
  SpecLimits both{-3.0, 3.0};
  Capability c = normal_capability(0.0, 1.0, both);
  REQUIRE(c.cp);
  CHECK_THAT(*c.cp, Catch::Matchers::WithinRel(1.0, 1e-15));
  CHECK_THAT(c.cpk, Catch::Matchers::WithinRel(1.0, 1e-15));
  CHECK_THAT(c.ppm, Catch::Matchers::WithinRel(2699.796, 1e-6));  // 2 (1 - Phi(3)) = 0.2699796 %
  // Off centre by 1.5 sigma inside +-6 sigma: Cp 2, Cpk 1.5, 3.4 ppm (3.398 above + ~0 below).
  c = normal_capability(1.5, 1.0, SpecLimits{-6.0, 6.0});
  CHECK_THAT(*c.cp, Catch::Matchers::WithinRel(2.0, 1e-15));
  CHECK_THAT(c.cpk, Catch::Matchers::WithinRel(1.5, 1e-15));
  CHECK_THAT(c.ppm, Catch::Matchers::WithinRel(3.3977, 1e-4));
  // One-sided: no Cp.
  c = normal_capability(0.0, 2.0, SpecLimits{std::nullopt, 6.0});
  CHECK_FALSE(c.cp);
  CHECK_THAT(c.cpk, Catch::Matchers::WithinRel(1.0, 1e-15));
  CHECK_THAT(c.ppm, Catch::Matchers::WithinRel(1349.898, 1e-6));
  CHECK_THROWS_AS(normal_capability(0.0, 0.0, both), NodeError);
}

TEST_CASE("stack.linear against its spec: RSS model, and Monte Carlo within its standard error") {
  const double sigma = 0.01 * mm * std::sqrt(2.0);
  // Limits at mean -2 sigma and +2.5 sigma: ppm = 1e6 (Phi(-2) + Phi(-2.5)) = 22750.1 + 6209.7.
  const Record limits = spec(10 * mm - 2.0 * sigma, 10 * mm + 2.5 * sigma);
  const OutputSet rss = run_stack(limits, false);
  CHECK_THAT(1e6 * scalar(rss, "out_of_spec"), Catch::Matchers::WithinRel(22750.13 + 6209.67, 1e-5));
  CHECK_THAT(scalar(rss, "cp"), Catch::Matchers::WithinRel(4.5 / 6.0, 1e-12));
  CHECK_THAT(scalar(rss, "cpk"), Catch::Matchers::WithinRel(2.0 / 3.0, 1e-12));
  CHECK(rss.all().count("mc_out_of_spec") == 0);

  const OutputSet mc = run_stack(limits, true);
  const double ppm = 1e6 * scalar(mc, "mc_out_of_spec"), error = 1e6 * scalar(mc, "mc_out_of_spec_error");
  CHECK(error > 0.0);
  CHECK_THAT(error, Catch::Matchers::WithinRel(1e6 * std::sqrt(0.02896 * (1 - 0.02896) / 200000), 0.02));
  CHECK(std::abs(ppm - (22750.13 + 6209.67)) < 4.0 * error);
  CHECK_THAT(scalar(mc, "mc_cpk"), Catch::Matchers::WithinRel(2.0 / 3.0, 0.02));
  bool noted = false;
  for (const std::string& n : mc.notes()) noted = noted || n.find("samples outside spec") != std::string::npos;
  CHECK(noted);

  // A one-sided spec far out: no sample outside, the note gives the 3/N bound.
  const OutputSet none = run_stack(spec(std::nullopt, 11 * mm), true, 10000);
  CHECK(scalar(none, "mc_out_of_spec") == 0.0);
  CHECK(none.all().count("cp") == 0);
  bool bound = false;
  for (const std::string& n : none.notes()) bound = bound || n.find("below 3/N = 300 ppm") != std::string::npos;
  CHECK(bound);
}

TEST_CASE("the streamed count outside the limits equals the count over kept samples") {
  std::vector<ToleranceLink> links = {{"a", 0.010, 1e-4, 1.0, Distribution::normal}};
  const SampleLimits limits{0.010 - 2.2e-4 / 3.0, 0.010 + 2.0e-4 / 3.0};
  const std::size_t n = 300001;  // above the streaming threshold
  const SampleSummary stream = monte_carlo_linear_stack(links, n, 5, limits);
  const std::vector<double> kept = sample_linear_stack(links, n, 5);
  const auto below = static_cast<std::size_t>(std::count_if(kept.begin(), kept.end(), [&](double x) { return x < limits.lower; }));
  const auto above = static_cast<std::size_t>(std::count_if(kept.begin(), kept.end(), [&](double x) { return x > limits.upper; }));
  CHECK(stream.below == below);
  CHECK(stream.above == above);
  CHECK(below > 100);
}

TEST_CASE("spec refusals name spec") {
  CHECK_THROWS_WITH(run_stack(spec(11 * mm, 9 * mm), false), Catch::Contains("must be below upper"));
  CHECK_THROWS_WITH(run_stack(Record{}, false), Catch::Contains("spec needs a lower or an upper limit"));
}
