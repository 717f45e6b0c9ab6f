// How mechgraph bench compares a node's outputs: relative differences with their floors, the
// spread over seeds, bit-identity, and what is not compared.
#include <mechgraph/knob_bench_outputs.hpp>

#include <catch2/catch.hpp>

#include <cmath>

using namespace mechgraph;
using Catch::Matchers::WithinAbs;
using Catch::Matchers::WithinRel;

namespace {
OutputValue scalar(const std::string& label, double x, Dimension d = dim::length) { return {label, Value::scalar(x), d, ""}; }
OutputValue series(const std::string& label, std::vector<double> axis, std::vector<double> values) {
  Series s;
  s.axis = std::move(axis);
  s.values = std::move(values);
  return {label, Value::series(std::move(s)), dim::length, ""};
}
OutputValue table(const std::string& label, std::vector<double> axis, std::vector<double> channel) {
  Table t;
  t.axis = {"angle", dim::angle, std::move(axis), ""};
  t.add_channel("lift", dim::length).values = std::move(channel);
  return {label, Value::table(std::move(t)), dim::none, ""};
}
}  // namespace

TEST_CASE("bench outputs: relative difference, with the floor of near-zero scalars and of series", "[bench]") {
  const std::vector<OutputValue> reference = {scalar("n.force", 2000.0, dim::force), scalar("n.margin", 0.0, dim::force),
                                              scalar("n.lift", 0.01), series("n.curve", {0, 1, 2}, {0.0, 4.0, -2.0})};
  const std::vector<OutputValue> trial = {scalar("n.force", 2000.2, dim::force), scalar("n.margin", 0.5, dim::force),
                                          scalar("n.lift", 0.01), series("n.curve", {0, 1, 2}, {0.04, 4.0, -2.0})};
  const OutputDeviation d = relative_difference(trial, reference, {});
  CHECK_THAT(d.per_output.at("n.force"), WithinRel(1e-4, 1e-12));
  // A margin of zero against forces of 2 kN: measured against 1e-3 x 2000 N.
  CHECK_THAT(d.per_output.at("n.margin"), WithinRel(0.5 / 2.0, 1e-12));
  CHECK(d.per_output.at("n.lift") == 0.0);
  // A series element relative to the series' largest magnitude (4), not to its own zero.
  CHECK_THAT(d.per_output.at("n.curve"), WithinRel(0.04 / 4.0, 1e-12));
  CHECK(d.worst == "n.margin");
  CHECK_THAT(d.max_relative, WithinRel(0.25, 1e-12));
  CHECK(d.compared == 6);
}

TEST_CASE("bench outputs: other shapes, work counters and uncertainties are not compared", "[bench]") {
  const std::vector<OutputValue> reference = {series("n.curve", {0, 1, 2}, {1, 2, 3}), table("n.curves", {0, 1}, {1, 2}),
                                              scalar("n.steps", 100, dim::none), scalar("n.mean_error", 1.0)};
  const std::vector<OutputValue> more_points = {series("n.curve", {0, 0.5, 1, 1.5, 2}, {1, 1.5, 2, 2.5, 3}),
                                                table("n.curves", {0, 1.5}, {1, 2}), scalar("n.steps", 200, dim::none),
                                                scalar("n.mean_error", 2.0)};
  const OutputDeviation d = relative_difference(more_points, reference, {"steps"});
  CHECK(d.compared == 0);  // the series has more points, the table's axis moved
  CHECK(d.per_output.empty());
  CHECK_FALSE(is_compared_output("steps", {"steps"}));
  CHECK_FALSE(is_compared_output("mc_out_of_spec_error", {}));
  CHECK(is_compared_output("error", {}));
  // A table channel against its own scale.
  const OutputDeviation same_axis = relative_difference({table("n.curves", {0, 1}, {1.0, -1.98})}, {table("n.curves", {0, 1}, {1.0, -2.0})}, {});
  CHECK_THAT(same_axis.per_output.at("n.curves:lift"), WithinRel(0.01, 1e-12));
}

TEST_CASE("bench outputs: the spread over runs is the sample standard deviation relative to the mean", "[bench]") {
  // 1, 2, 3, 4: mean 2.5, sample standard deviation sqrt(5/3).
  std::vector<std::vector<OutputValue>> runs;
  for (double x : {1.0, 2.0, 3.0, 4.0}) runs.push_back({scalar("n.mean", x), scalar("n.worst_case", 7.0), scalar("n.mean_error", x)});
  const OutputDeviation d = relative_spread(runs, {});
  CHECK_THAT(d.per_output.at("n.mean"), WithinRel(std::sqrt(5.0 / 3.0) / 2.5, 1e-12));
  CHECK(d.per_output.at("n.worst_case") == 0.0);  // the seed does not touch it: exactly no spread
  CHECK_FALSE(d.per_output.count("n.mean_error"));
  CHECK(d.worst == "n.mean");
  // A value near zero beside larger ones of its dimension: against 1e-3 x the largest mean.
  std::vector<std::vector<OutputValue>> near_zero;
  for (double x : {-1e-6, 1e-6}) near_zero.push_back({scalar("n.share", x, dim::none), scalar("n.cpk", 1.5, dim::none)});
  CHECK_THAT(relative_spread(near_zero, {}).per_output.at("n.share"), WithinRel(std::sqrt(2.0) * 1e-6 / 1.5e-3, 1e-12));
  CHECK(relative_spread({runs[0]}, {}).compared == 0);  // one run has no spread
}

TEST_CASE("bench outputs: bit-identical means every numeric output, to the bit", "[bench]") {
  const std::vector<OutputValue> a = {scalar("n.x", 0.1 + 0.2), series("n.s", {0, 1}, {1, 2}), table("n.t", {0, 1}, {3, 4})};
  std::vector<OutputValue> b = a;
  CHECK(bit_identical(a, b));
  b[0] = scalar("n.x", 0.3);  // 0.1 + 0.2 is not 0.3 in binary
  CHECK_FALSE(bit_identical(a, b));
  b = a;
  b[2] = table("n.t", {0, 1}, {3, std::nextafter(4.0, 5.0)});
  CHECK_FALSE(bit_identical(a, b));
  b = a;
  b.pop_back();
  CHECK_FALSE(bit_identical(a, b));
}
