// The Monte Carlo histogram of a stack or chain: every sample counted once; the streamed histogram
// equal, bin for bin, to the kept samples binned over the same edges (second method); its counts
// against the normal law's probabilities of the bins (closed form, within binomial error); the
// spec limits carried as axis marks; degenerate and tiny spreads.
#include "backlash/mc_histogram.hpp"
#include "backlash/node_types.hpp"
#include "backlash/stacking.hpp"
#include "test_support.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <numeric>

using namespace mechgraph;
using namespace mechgraph::backlash;
using namespace mechgraph::testing;
using Catch::Matchers::WithinAbs;
using Catch::Matchers::WithinRel;

namespace {

std::size_t total(const Histogram& h) { return std::accumulate(h.counts.begin(), h.counts.end(), std::size_t{0}) + h.under + h.over; }

// The same edges, counted directly from the samples (k = floor((x - low)/width)). A sample within
// rounding of an edge (1e-9 of a bin) may fall either side of it: `ambiguous` counts those.
std::vector<std::size_t> bin_directly(const std::vector<double>& samples, const Histogram& h, std::size_t& ambiguous) {
  std::vector<std::size_t> counts(h.counts.size(), 0);
  ambiguous = 0;
  for (double x : samples) {
    const double v = (x - h.low) / h.width, u = std::floor(v);
    ambiguous += std::abs(v - std::round(v)) < 1e-9;
    if (u >= 0.0 && u < static_cast<double>(counts.size())) ++counts[static_cast<std::size_t>(u)];
    else if (x <= h.top && x >= h.low) ++counts.back();
  }
  return counts;
}

// Bin for bin the same, but for samples on an edge (each moves one count between two bins).
void check_same_bins(const Histogram& h, const std::vector<double>& samples) {
  std::size_t ambiguous = 0;
  const std::vector<std::size_t> direct = bin_directly(samples, h, ambiguous);
  REQUIRE(direct.size() == h.counts.size());
  std::size_t differ = 0;
  for (std::size_t k = 0; k < direct.size(); ++k)
    differ += direct[k] > h.counts[k] ? direct[k] - h.counts[k] : h.counts[k] - direct[k];
  INFO("samples on an edge: " << ambiguous);
  CHECK(differ <= 2 * ambiguous);
  CHECK(ambiguous * 1000 < samples.size());  // a few: the comparison still means something
}

double normal_cdf(double z) { return 0.5 * std::erfc(-z / std::sqrt(2.0)); }

}  // namespace

TEST_CASE("summarize's histogram spans the samples from the least to the greatest and counts each once", "[backlash][histogram]") {
  const std::vector<double> samples{0.5, 1.0, 1.0, 2.0, 3.0, 4.0, 4.5, 5.0};
  const SampleSummary s = summarize(samples, {}, 9);
  REQUIRE(s.histogram.counts.size() == 9);
  CHECK(s.histogram.low == 0.5);
  CHECK_THAT(s.histogram.width, WithinRel(0.5, 1e-14));
  CHECK(total(s.histogram) == samples.size());
  CHECK(s.histogram.under == 0);
  CHECK(s.histogram.over == 0);
  // Bins of 0.5 from 0.5: 0.5 | 1.0 1.0 | - | 2.0 | - | 3.0 | - | 4.0 | 4.5 5.0 (the top edge in the last bin).
  const std::vector<std::size_t> expected{1, 2, 0, 1, 0, 1, 0, 1, 2};
  CHECK(s.histogram.counts == expected);
  CHECK(summarize(samples).histogram.empty());  // none asked for
}

TEST_CASE("a histogram of equal samples is one bin holding them all", "[backlash][histogram]") {
  for (double v : {0.0, 2.5e-6, -7.0}) {
    const SampleSummary s = summarize(std::vector<double>(5, v), {}, 40);
    REQUIRE(s.histogram.counts.size() == 1);
    CHECK(s.histogram.counts[0] == 5);
    CHECK(s.histogram.width > 0.0);
    CHECK(s.histogram.low <= v);
    CHECK(v < s.histogram.low + s.histogram.width);
  }
}

TEST_CASE("the streamed histogram equals the kept samples binned over its edges", "[backlash][histogram]") {
  // Second method: every sample kept (sample_linear_stack, the same seed gives the same sequence)
  // and binned directly. A normal stack, a uniform one, and a clipped play stack (a wall at zero).
  const std::size_t n = 300001;
  for (const auto distribution : {Distribution::normal, Distribution::uniform}) {
    INFO("distribution " << static_cast<int>(distribution));
    const std::vector<ToleranceLink> links = {{"a", 0.010, 1e-4, 1.0, distribution}, {"b", -0.002, 5e-5, 1.0, distribution}};
    const SampleSummary stream = monte_carlo_linear_stack(links, n, 5, {}, 30);
    const std::vector<double> kept = sample_linear_stack(links, n, 5);
    CHECK(total(stream.histogram) == n);
    check_same_bins(stream.histogram, kept);
    CHECK(stream.histogram.counts.front() > 0);  // the empty ends are trimmed
    CHECK(stream.histogram.counts.back() > 0);
    // Bins laid across the pilot's range: about 30 of them across the whole sample.
    CHECK(stream.histogram.counts.size() >= 30);
    CHECK(stream.histogram.counts.size() <= 46);
  }
  PlayStack stack;
  stack.own_mean = 0.0;  // half the actuator's samples clipped to zero: a spike in the first bin
  stack.own_sigma = 10e-6;
  stack.terms.push_back({1.0, {"fit", {{"hole", 0.02005, 6.5e-5, 1.0, Distribution::normal}, {"shaft", 0.01994, 6.5e-5, -1.0, Distribution::normal}}}});
  const SampleSummary play = monte_carlo_play_stack(stack, n, 2, {}, 25);
  CHECK(total(play.histogram) == n);
  check_same_bins(play.histogram, sample_play_stack(stack, n, 2));
}

TEST_CASE("the histogram of a normal stack follows the normal law bin by bin", "[backlash][histogram]") {
  // Closed form: the expected count of bin [a, b) is N (Phi((b - mu)/sigma) - Phi((a - mu)/sigma));
  // each count is binomial, within 5 of its standard deviations (plus one count) of it.
  const double mu = 0.010, sigma = 1e-4 / 3.0;  // one normal link, T = 6 sigma
  const std::vector<ToleranceLink> links = {{"a", mu, 1e-4, 1.0, Distribution::normal}};
  for (const std::size_t n : {std::size_t{50000}, std::size_t{1000000}}) {  // kept, then streamed
    INFO("samples " << n);
    const Histogram h = monte_carlo_linear_stack(links, n, 11, {}, 40).histogram;
    const double N = static_cast<double>(n);
    double chi2 = 0.0;
    for (std::size_t k = 0; k < h.counts.size(); ++k) {
      const double a = h.low + static_cast<double>(k) * h.width, b = a + h.width;
      const double p = normal_cdf((b - mu) / sigma) - normal_cdf((a - mu) / sigma);
      const double expected = N * p, spread = std::sqrt(N * p * (1.0 - p));
      CHECK(std::abs(static_cast<double>(h.counts[k]) - expected) <= 5.0 * spread + 1.0);
      if (expected > 20.0) chi2 += std::pow(static_cast<double>(h.counts[k]) - expected, 2) / expected;
    }
    CHECK(chi2 < 3.0 * static_cast<double>(h.counts.size()));  // chi-square per bin about 1
  }
}

TEST_CASE("stack.linear and backlash.chain output the histogram with the spec limits marked", "[backlash][histogram]") {
  auto type = make_stack_linear_type();
  auto records = [](std::vector<Record> r) {
    ParamValue v;
    v.kind = ParamKind::record_list;
    v.records = std::move(r);
    return v;
  };
  const Record link{{"nominal", ParamValue::of_number(0.010)},
                    {"upper", ParamValue::of_number(3e-5)},
                    {"lower", ParamValue::of_number(-3e-5)}};
  const Record spec{{"lower", ParamValue::of_number(0.00997)}, {"upper", ParamValue::of_number(0.01004)}};
  std::map<std::string, ParamValue> p{{"links", records({link, link})},
                                      {"spec", records({spec})},
                                      {"samples", ParamValue::of_integer(20000)},
                                      {"histogram_bins", ParamValue::of_integer(25)}};
  OutputSet out;
  RecordingContext ctx(std::vector<std::string>{"monte_carlo"});
  type->evaluate(defaults_of(type->info(), p), InputSet{}, out, ctx);
  const Table& t = out.all().at("mc_histogram").as_table();
  CHECK(t.histogram);
  CHECK(t.axis.dimension == dim::length);
  REQUIRE(t.axis.values.size() == 25);  // 20000 samples kept: exactly the bins asked for
  const std::vector<double>& count = t.find("count")->values;
  CHECK(std::accumulate(count.begin(), count.end(), 0.0) == 20000.0);
  // Centres evenly spaced from mc_min + width/2 to mc_max - width/2.
  const double width = t.axis.values[1] - t.axis.values[0];
  CHECK_THAT(t.axis.values.front() - 0.5 * width, WithinAbs(out.all().at("mc_min").as_scalar(), 1e-12));
  CHECK_THAT(t.axis.values.back() + 0.5 * width, WithinAbs(out.all().at("mc_max").as_scalar(), 1e-12));
  REQUIRE(t.axis_marks.size() == 2);
  CHECK(t.axis_marks[0].label == "LSL");
  CHECK(t.axis_marks[0].value == 0.00997);
  CHECK(t.axis_marks[1].label == "USL");
  CHECK(t.axis_marks[1].value == 0.01004);
  // Without monte_carlo there are no samples to count: the output is the effect's.
  OutputSet plain;
  RecordingContext off;
  type->evaluate(defaults_of(type->info(), p), InputSet{}, plain, off);
  CHECK(plain.all().count("mc_histogram") == 0);
}
