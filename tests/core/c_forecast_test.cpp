// A node type's own work forecast through the SDK 1.x C boundary (c/node_forecast.h,
// mechgraph.node.forecast/1): the plugin's bridge refreshes the thread's sets in place
// (detail/export_node.hpp, detail/bridge_sets.hpp) and a sweep's budget binds the forecast to the
// case graph's parameters once (core/src/c_node_type.cpp, bind_forecast; RepeatedNodeEstimate).
// The built-in cams and valvetrain built on MECHGRAPH_PLUGIN_1 (test_plugins/builtin_sdk1) must
// forecast exactly what the same C++ types forecast on the pre-1.0 entry: for varied parameters,
// for parameters and inputs that come and go from one call to the next, on several threads at
// once, and in a sweep's budget.
#include "sweep_support.hpp"
#include "test_support.hpp"
#include "../../core/src/c_node_type.hpp"  // bind_forecast: what a sweep's budget asks for each case

#include <mechgraph/block.hpp>
#include <mechgraph/detail/forecast_override.hpp>
#include <mechgraph/sweep/case_estimate.hpp>
#include <mechgraph/work_estimate.hpp>

#include <catch2/catch.hpp>

#include <atomic>
#include <fstream>
#include <numeric>
#include <sstream>
#include <string_view>
#include <thread>

using namespace mechgraph;
using namespace mechgraph::testing;

namespace {

std::string stages123() { return source_file_text("bench/peers/stages123_study.yaml"); }

// Cams of several laws with ramps and a nose timing, the valve motion and time-area behind one, and
// a contour, whose forecast reads the size of its input.
const char* cams = R"(nodes:
  kurz: { type: cam.kurz, params: { max_lift: 8 mm, action_angle: 130 deg, base_radius: 26 mm, accel_angle: 18 deg,
                                    ramp: cosine, ramp_height: 0.2 mm, ramp_length: 20 deg, nose_timing: 110 deg } }
  arc:  { type: cam.three_arc, params: { max_lift: 8 mm, action_angle: 130 deg, base_radius: 26 mm, accel_angle: 18 deg } }
  poly: { type: cam.polydyne, params: { max_lift: 8 mm, action_angle: 130 deg, base_radius: 26 mm, exponents: [2, 14, 26, 38, 50] } }
  v:    { type: valvetrain.valve_motion, inputs: { cam: kurz.law }, params: { rpm: 5600 rpm, rocker_ratio: 1.5, lash: 0.25 mm } }
  ta:   { type: valvetrain.time_area, inputs: { valve: v.motion }, params: { seat_diameter: 34 mm } }
  ct:   { type: cam.contour, inputs: { cam: arc.law }, params: { roller_radius: 10 mm, chord_error: 0.002 mm } }
outputs: [ ta.time_area, poly.max_lift, ct.points ]
)";

// `params` without the entries named in `drop` (a ParamSet has no way to remove one).
ParamSet without(const ParamSet& params, std::initializer_list<const char*> drop) {
  ParamSet out;
  for (const auto& [name, value] : params.all())
    if (std::find(drop.begin(), drop.end(), std::string_view(name)) == drop.end()) out.set(name, value);
  return out;
}

// The variants each node is forecast with, in an order in which parameters come and go, texts and
// lists change length, and real numbers change.
std::vector<ParamSet> variants(const ParamSet& base, std::size_t seed) {
  std::vector<ParamSet> out{base, without(base, {"samples", "curve_points", "nose_timing", "ramp", "ramp_height", "ramp_length"})};
  ParamSet more = base;
  more.slot("samples") = ParamValue::of_integer(64);
  more.slot("curve_points") = ParamValue::of_integer(1000 + static_cast<long>(seed));
  if (base.has("max_lift")) more.slot("max_lift").number *= 1.0 + 0.01 * static_cast<double>(seed % 7);
  if (base.has("ramp")) more.slot("ramp") = ParamValue::of_choice("constant_velocity");
  if (base.has("exponents")) more.slot("exponents").numbers = {2, 10, 18, 26, 34, 42, 50};
  out.push_back(more);
  out.push_back(without(base, {"samples"}));
  out.push_back(base);
  return out;
}

std::vector<InputSizes> size_variants(const NodeInfo& info) {
  std::vector<InputSizes> out{{}};
  InputSizes some;
  for (const PortSpec& p : info.inputs) some[p.name] = 7;
  out.push_back(some);
  for (auto& [name, size] : some) size = 3;  // the same inputs, other sizes
  out.push_back(some);
  out.push_back({});
  out.push_back(some);
  return out;
}

// Whether the C type's forecast of every variant equals the C++ type's; `problem` says where not.
bool same_forecasts(const Graph& c, const Graph& cxx, std::size_t seed, std::string& problem) {
  for (std::size_t i = 0; i < c.nodes.size(); ++i) {
    const NodeType& c_type = *c.nodes[i].type->type;
    const NodeType& cxx_type = *cxx.nodes[i].type->type;
    for (const ParamSet& params : variants(c.nodes[i].params, seed))
      for (const InputSizes& sizes : size_variants(c_type.info())) {
        const std::optional<WorkForecast> a = c_type.forecast(params, sizes);
        // A C++ forecast may throw (cam.contour without its samples); through C that is no
        // forecast, and a sweep's budget takes both alike (work_estimate.cpp, forecast_of).
        std::optional<WorkForecast> b;
        try {
          b = cxx_type.forecast(params, sizes);
        } catch (const std::exception&) {
        }
        const bool same = a.has_value() == b.has_value() &&
                          (!a || (a->items == b->items && a->memory == b->memory && a->output_size == b->output_size &&
                                  a->driver == b->driver));
        if (!same) {
          problem = "node " + c.nodes[i].name + ": " + (a ? a->driver : "none") + " / " + (b ? b->driver : "none");
          return false;
        }
      }
  }
  return true;
}

}  // namespace

TEST_CASE("forecasts through C equal the C++ types' as parameters and inputs come and go", "[sdk1][forecast]") {
  const Graph c = graph_from(cams, builtin_sdk1_registry());
  const Graph cxx = graph_from(cams, builtin_pre10_registry());
  REQUIRE(c.nodes.size() == cxx.nodes.size());
  for (std::size_t i = 0; i < c.nodes.size(); ++i) REQUIRE(c.nodes[i].name == cxx.nodes[i].name);
  REQUIRE(c.nodes.front().type->type->forecast(c.nodes.front().params, {}));  // the cams forecast
  const GraphNode& contour = c.nodes.back();
  REQUIRE(contour.name == "ct");  // whose forecast reads its input's size
  REQUIRE(contour.type->type->forecast(contour.params, {{"cam", 7.0}})->items != contour.type->type->forecast(contour.params, {})->items);
  std::string problem;
  for (std::size_t seed = 0; seed < 3; ++seed) {
    INFO("seed " << seed);
    CHECK(same_forecasts(c, cxx, seed, problem));
    INFO(problem);
  }
}

TEST_CASE("forecasts through C on several threads at once, each its own sets", "[sdk1][forecast][threads]") {
  const Graph c = graph_from(cams, builtin_sdk1_registry());
  const Graph cxx = graph_from(cams, builtin_pre10_registry());
  std::atomic<int> failures{0};
  std::vector<std::thread> threads;
  for (std::size_t t = 0; t < 4; ++t)
    threads.emplace_back([&, t] {
      std::string problem;
      for (std::size_t round = 0; round < 40; ++round)
        if (!same_forecasts(c, cxx, t + round, problem)) ++failures;
    });
  for (std::thread& t : threads) t.join();
  CHECK(failures == 0);
}

TEST_CASE("a sweep's budget through C types equals the pre-1.0 build's and each case's alone", "[sdk1][forecast][sweep][bounds]") {
  std::vector<SampleSpec> specs;
  for (const char* s : {"lift=7mm:9mm", "action=120deg:140deg", "accel=15deg:21deg", "r0=24mm:28mm", "rpm=4000rpm:7000rpm"})
    specs.push_back(parse_sample(s));
  const CaseTable table = make_latin_hypercube(specs, 300, 5);
  Prepared c = prepare(stages123(), table, builtin_sdk1_registry());
  const Prepared cxx = prepare(stages123(), table, builtin_pre10_registry());
  std::vector<std::size_t> all(table.size());
  std::iota(all.begin(), all.end(), std::size_t{0});
  const SweepEstimate e = estimate_cases(c.graph, *c.binder, c.table, all);
  const SweepEstimate pre = estimate_cases(cxx.graph, *cxx.binder, cxx.table, all);
  CHECK(e.total.work == pre.total.work);
  CHECK(e.largest_memory == pre.largest_memory);
  CHECK(e.largest_case == pre.largest_case);
  const SweepEstimate two = estimate_cases(c.graph, *c.binder, c.table, all, 2);
  CHECK(two.total.work == e.total.work);
  double work = 0;
  std::vector<CaseValue> row;
  for (std::size_t k : all) {
    Graph copy = c.graph;
    c.binder->apply(c.binder->bind(copy), copy, c.table.row(k, row));
    work += estimate_work(copy).work;
  }
  CHECK_THAT(e.total.work, Catch::Matchers::WithinRel(work, 1e-12));
}

TEST_CASE("a repeated estimate given another graph than its own asks the type afresh", "[sdk1][forecast][bounds]") {
  Graph bound = graph_from(cams, builtin_sdk1_registry());
  const Graph other = graph_from(cams, builtin_sdk1_registry(), {{"kurz.curve_points", "5000", "kurz.curve_points=5000"}});
  const std::size_t kurz = 0;
  REQUIRE(bound.nodes[kurz].name == "kurz");
  RepeatedNodeEstimate repeated(bound, kurz, false, true);
  const std::vector<double> sizes(bound.nodes.size(), 1.0);
  CHECK(repeated(bound, sizes).work == estimate_node(bound, kurz, sizes, false, false).work);
  const double other_work = estimate_node(other, kurz, sizes, false, false).work;
  CHECK(other_work != estimate_node(bound, kurz, sizes, false, false).work);
  CHECK(repeated(other, sizes).work == other_work);
  // Its own graph, a value written in place (as a sweep's binder writes it): read afresh.
  bound.nodes[kurz].params.slot("curve_points").number = 5000;
  CHECK(repeated(bound, sizes).work == other_work);
}

TEST_CASE("a repeated estimate reads texts and lists written in place into its own graph", "[sdk1][forecast][bounds]") {
  Graph g = graph_from(cams, builtin_sdk1_registry());
  const std::vector<double> sizes(g.nodes.size(), 1.0);
  std::vector<RepeatedNodeEstimate> repeated;
  for (std::size_t i = 0; i < g.nodes.size(); ++i) repeated.emplace_back(g, i, false, true);
  const auto same = [&] {
    for (std::size_t i = 0; i < g.nodes.size(); ++i) {
      INFO("node " << g.nodes[i].name);
      CHECK(repeated[i](g, sizes).work == estimate_node(g, i, sizes, false, false).work);
    }
  };
  same();
  const double with_ramp = estimate_node(g, 0, sizes, false, false).work;
  g.nodes[0].params.slot("ramp").text = "none";  // a text: fewer pieces
  same();
  CHECK(estimate_node(g, 0, sizes, false, false).work != with_ramp);
  GraphNode& poly = g.nodes[2];
  REQUIRE(poly.name == "poly");
  // A longer list: its storage moved (the forecast must read the new one; ASan would see the old).
  poly.params.slot("exponents").numbers = {2, 6, 10, 14, 18, 22, 26, 30, 34, 38, 42, 46, 50};
  same();
}

// --- a type without a forecast of its own declares none (detail/forecast_override.hpp) ----------

namespace {
const NodeInfo& no_info() {
  static const NodeInfo info;
  return info;
}
class KeepsDefault final : public NodeType {
 public:
  const NodeInfo& info() const override { return no_info(); }
  void evaluate(const ParamSet&, const InputSet&, OutputSet&, EvalContext&) const override {}
};
class Forecasts : public NodeType {
 public:
  const NodeInfo& info() const override { return no_info(); }
  void evaluate(const ParamSet&, const InputSet&, OutputSet&, EvalContext&) const override {}
  std::optional<WorkForecast> forecast(const ParamSet&, const InputSizes&) const override { return WorkForecast{1, 2, 3, {}}; }
};
class InheritsForecast final : public Forecasts {};  // its base's own forecast
// NodeType behind another polymorphic base (its vtable a secondary one), with and without.
class BlocksFirst final : public BlockEvaluation, public NodeType {
 public:
  const NodeInfo& info() const override { return no_info(); }
  void evaluate(const ParamSet&, const InputSet&, OutputSet&, EvalContext&) const override {}
  bool block_supported(const BlockRequest&) const override { return false; }
  void evaluate_block(const BlockParams&, const BlockInputs&, BlockOutputs&, BlockCases&, EvalContext&) const override {}
};
class BlocksFirstForecasts final : public BlockEvaluation, public NodeType {
 public:
  const NodeInfo& info() const override { return no_info(); }
  void evaluate(const ParamSet&, const InputSet&, OutputSet&, EvalContext&) const override {}
  bool block_supported(const BlockRequest&) const override { return false; }
  void evaluate_block(const BlockParams&, const BlockInputs&, BlockOutputs&, BlockCases&, EvalContext&) const override {}
  std::optional<WorkForecast> forecast(const ParamSet&, const InputSizes&) const override { return std::nullopt; }
};
}  // namespace

TEST_CASE("the C layer tells a node type with a forecast of its own from one that keeps the default", "[sdk1][forecast]") {
  CHECK_FALSE(detail::has_own_forecast(KeepsDefault{}));
  CHECK(detail::has_own_forecast(Forecasts{}));
  CHECK(detail::has_own_forecast(InheritsForecast{}));
  CHECK_FALSE(detail::has_own_forecast(BlocksFirst{}));
  CHECK(detail::has_own_forecast(BlocksFirstForecasts{}));  // an override that answers "cannot say" still asks
  // The built-in types (their C++ objects, as the pre-1.0 entry hands them over): the cams and
  // float speed forecast, the valve motion and the time-area keep the default; on
  // MECHGRAPH_PLUGIN_1 the latter answer NULL for mechgraph.node.forecast/1 and are counted by the
  // conventions, with the same figures (the test above and the sweep budget's below).
  const PluginRegistry& cxx = builtin_pre10_registry();
  for (const char* type : {"cam.kurz", "cam.three_arc", "cam.polydyne", "cam.contour", "valvetrain.float_speed"}) {
    INFO(type);
    CHECK(detail::has_own_forecast(*cxx.find(type)->type));
  }
  for (const char* type : {"valvetrain.valve_motion", "valvetrain.time_area"}) {
    INFO(type);
    CHECK_FALSE(detail::has_own_forecast(*cxx.find(type)->type));
  }
}

TEST_CASE("a sweep's budget asks through C only the types with a forecast of their own", "[sdk1][forecast]") {
  // On MECHGRAPH_PLUGIN_1 the valve motion and the time-area (default forecast) answer NULL for
  // mechgraph.node.forecast/1: the host binds no forecast for them, and counts them by the
  // conventions without a call through C per case; the cams bind theirs.
  const Graph c = graph_from(cams, builtin_sdk1_registry());
  for (const GraphNode& n : c.nodes) {
    INFO(n.name << " (" << n.info().type << ")");
    const bool keeps_default = n.info().type == "valvetrain.valve_motion" || n.info().type == "valvetrain.time_area";
    CHECK((detail::bind_forecast(*n.type->type, n.params) == nullptr) == keeps_default);
    CHECK_FALSE((keeps_default && n.type->type->forecast(n.params, {})));
  }
}
