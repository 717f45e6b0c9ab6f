// Which parameters a forecast reads (ForecastReads, c/node_forecast_reads.h,
// mechgraph.node.forecast_reads/1): what the cam types name, through C as on the pre-1.0 entry; a
// sweep's budget that asks such a forecast once while the cases change none of them and still
// gives each case's figures; and the conformance kit's check, which a type that reads a parameter
// it does not name fails.
#include "sweep_support.hpp"
#include "test_support.hpp"
#include "../../core/src/c_node_type.hpp"  // forecast_reads, make_c_node_type

#include <mechgraph/detail/export_node.hpp>
#include <mechgraph/sweep/case_estimate.hpp>
#include <mechgraph/testing/node_conformance.hpp>
#include <mechgraph/work_estimate.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <numeric>

using namespace mechgraph;
using namespace mechgraph::testing;

namespace {

std::string stages123() { return source_file_text("bench/peers/stages123_study.yaml"); }

const char* one_cam = R"(nodes:
  kurz: { type: cam.kurz, params: { max_lift: 8 mm, action_angle: 130 deg, base_radius: 26 mm, accel_angle: 18 deg } }
outputs: [ kurz.max_lift ]
)";

std::vector<std::string> sorted(std::vector<std::string> v) {
  std::sort(v.begin(), v.end());
  return v;
}

// A type with a forecast of `points` and a `gain` it reads or not; it says it reads `named`.
class Counted final : public NodeType, public ForecastReads {
 public:
  Counted(bool reads_gain, std::optional<std::vector<std::string>> named, bool reads_mode = false)
      : reads_gain_(reads_gain), reads_mode_(reads_mode), named_(std::move(named)) {
    info_.type = "test.counted";
    info_.summary = "a forecast of points (and of gain when it reads it)";
    info_.params = {ParamSpec::integer("points", "rows").with_default(100).at_least(1).at_most(1e6),
                    ParamSpec::number("gain", Dimension{}, "a factor").with_default(1.0).at_least(0.5).at_most(4.0),
                    ParamSpec::choice("mode", {"fast", "slow"}, "how").with_default(std::string("fast"))};
    info_.outputs = {PortSpec::scalar("y", Dimension{}, "points times gain")};
  }
  const NodeInfo& info() const override { return info_; }
  void evaluate(const ParamSet& p, const InputSet&, OutputSet& out, EvalContext&) const override {
    out.set("y", Value::scalar(p.number("points") * p.number("gain")));
  }
  std::optional<WorkForecast> forecast(const ParamSet& p, const InputSizes&) const override {
    WorkForecast f;
    f.items = static_cast<double>(p.integer("points")) * (reads_gain_ ? p.number("gain") : 1.0);
    if (reads_mode_ && p.text("mode") == "slow") f.items *= 2;
    return f;
  }
  std::optional<std::vector<std::string>> forecast_reads() const override { return named_; }

 private:
  NodeInfo info_;
  bool reads_gain_, reads_mode_;
  std::optional<std::vector<std::string>> named_;
};

const Check* find_check(const Report& r, const std::string& suite, const std::string& name) {
  for (const Check& c : r.checks())
    if (c.suite == suite && c.name == name) return &c;
  return nullptr;
}
const std::string reads_check = "its forecast reads only the parameters it names";

}  // namespace

TEST_CASE("the cam types name what their forecast reads, through C as on the pre-1.0 entry", "[sdk1][forecast]") {
  const Graph c = graph_from(stages123(), builtin_sdk1_registry());
  const Graph cxx = graph_from(stages123(), builtin_pre10_registry());
  std::size_t cams = 0;
  for (std::size_t i = 0; i < c.nodes.size(); ++i) {
    INFO("node " << c.nodes[i].name);
    const auto through_c = mechgraph::detail::forecast_reads(*c.nodes[i].type->type);
    const auto direct = mechgraph::detail::forecast_reads(*cxx.nodes[i].type->type);
    REQUIRE(through_c.has_value() == direct.has_value());
    if (!direct) continue;
    CHECK(sorted(*through_c) == sorted(*direct));
    if (c.nodes[i].info().type.rfind("cam.", 0) == 0) {
      ++cams;
      CHECK(sorted(*direct) == sorted({"ramp", "samples", "curve_points"}));
    }
  }
  CHECK(cams == 3);
  // cam.contour and valvetrain.float_speed say what theirs read too.
  for (const char* type : {"cam.contour", "valvetrain.float_speed"}) {
    INFO(type);
    REQUIRE(project_registry().find(type));
    CHECK(mechgraph::detail::forecast_reads(*project_registry().find(type)->type));
  }
  // The table law's cost reads its data.
  const NodeType* table = project_registry().find("cam.table") ? project_registry().find("cam.table")->type.get() : nullptr;
  REQUIRE(table);
  const auto reads = mechgraph::detail::forecast_reads(*table);
  REQUIRE(reads);
  for (const char* name : {"angles", "file", "smoothing", "curve_points"})
    CHECK(std::find(reads->begin(), reads->end(), name) != reads->end());
}

TEST_CASE("a repeated estimate asks a forecast once while no case changes what it reads", "[sdk1][forecast][bounds]") {
  for (const PluginRegistry* registry : {&project_registry(), &builtin_sdk1_registry()}) {
    Graph g = graph_from(one_cam, *registry);
    const std::vector<double> sizes(g.nodes.size(), 1.0);
    const NodeType& type = *g.nodes[0].type->type;
    CHECK(forecast_reads_none_of(type, {"max_lift", "action_angle"}));
    CHECK_FALSE(forecast_reads_none_of(type, {"max_lift", "curve_points"}));
    RepeatedNodeEstimate fixed(g, 0, false, false, forecast_reads_none_of(type, {"max_lift"}));
    RepeatedNodeEstimate varied(g, 0, false, false, forecast_reads_none_of(type, {"curve_points"}));
    const double first = fixed(g, sizes).work;
    CHECK(varied(g, sizes).work == first);
    // Written in place as a binder writes: a parameter the forecast reads. The estimate told only
    // max_lift varies keeps its figure (it does not ask again); the one told curve_points does.
    g.nodes[0].params.slot("curve_points") = ParamValue::of_integer(50000);
    const double more = estimate_node(g, 0, sizes, false, false).work;
    REQUIRE(more > first);
    CHECK(fixed(g, sizes).work == first);
    CHECK(varied(g, sizes).work == more);
  }
}

TEST_CASE("a repeated estimate asks again when its inputs' sizes change", "[sdk1][forecast][bounds]") {
  // cam.contour's forecast reads its samples, curve_points and chord_error, and the size of its cam.
  const char* contour = R"(nodes:
  kurz: { type: cam.kurz, params: { max_lift: 8 mm, action_angle: 130 deg, base_radius: 26 mm, accel_angle: 18 deg } }
  ct:   { type: cam.contour, inputs: { cam: kurz.law }, params: { roller_radius: 10 mm } }
outputs: [ ct.points ]
)";
  for (const PluginRegistry* registry : {&project_registry(), &builtin_sdk1_registry()}) {
    const Graph g = graph_from(contour, *registry);
    const std::size_t ct = 1;
    REQUIRE(g.nodes[ct].name == "ct");
    REQUIRE(forecast_reads_none_of(*g.nodes[ct].type->type, {"roller_radius"}));
    RepeatedNodeEstimate fixed(g, ct, false, false, true);
    std::vector<double> sizes(g.nodes.size(), 1.0);
    for (double pieces : {16.0, 16.0, 40.0, 40.0, 16.0}) {
      sizes[0] = pieces;  // the law's pieces, as the cam's forecast gives them
      INFO("cam of " << pieces << " pieces");
      CHECK(fixed(g, sizes).work == estimate_node(g, ct, sizes, false, false).work);
    }
    CHECK(estimate_node(g, ct, std::vector<double>{40.0, 1.0}, false, false).work !=
          estimate_node(g, ct, std::vector<double>{16.0, 1.0}, false, false).work);
  }
}

TEST_CASE("a sweep's budget with forecasts asked once gives each case's figures", "[sdk1][forecast][sweep][bounds]") {
  for (const char* varied : {"lift=7mm:9mm", "points=200:90000"}) {
    INFO(varied);
    std::vector<SampleSpec> specs{parse_sample(varied), parse_sample("rpm=4000rpm:7000rpm")};
    // The cams' curve_points from a scene parameter: a parameter their forecast reads, so that a
    // sweep of it gives every case its own figure.
    std::string scene = stages123();
    const auto replace = [&scene](const std::string& from, const std::string& to) {
      const auto at = scene.find(from);
      REQUIRE(at != std::string::npos);
      scene.replace(at, from.size(), to);
    };
    replace("params:\n", "params:\n  points: 400\n");
    for (int k = 0; k < 2; ++k) replace("accel_angle: $accel }", "accel_angle: $accel, curve_points: $points }");
    replace("38, 50] }", "38, 50], curve_points: $points }");
    CaseTable table = make_latin_hypercube(specs, 200, 11);
    if (std::string(varied).rfind("points", 0) == 0)
      for (std::size_t i = 0; i < table.size(); ++i) {  // an integer parameter takes whole numbers
        double& points = table.numbers.si[i * table.variables.size()];
        points = std::round(points);
      }
    for (const PluginRegistry* registry : {&project_registry(), &builtin_sdk1_registry()}) {
      Prepared p = prepare(scene, table, *registry);
      std::vector<std::size_t> all(table.size());
      std::iota(all.begin(), all.end(), std::size_t{0});
      const SweepEstimate e = estimate_cases(p.graph, *p.binder, p.table, all);
      double work = 0, largest = -1;
      std::size_t largest_case = 0;
      std::vector<CaseValue> row;
      for (std::size_t k : all) {
        Graph copy = p.graph;
        p.binder->apply(p.binder->bind(copy), copy, p.table.row(k, row));
        const double w = estimate_work(copy).work;
        work += w;
        if (w > largest) {
          largest = w;
          largest_case = k;
        }
      }
      CHECK_THAT(e.total.work, Catch::Matchers::WithinRel(work, 1e-12) || Catch::Matchers::WithinAbs(work, 1e-9));
      CHECK(e.largest_case == largest_case);
    }
  }
}

TEST_CASE("a sweep whose cases change no figure estimates one case and counts the cases that bind", "[sdk1][forecast][sweep][bounds]") {
  // stages123 over lift and rpm: the cams' forecasts read neither, the valve motion and time-area
  // types have no forecast (their tables answer no mechgraph.node.forecast/1) and no integer
  // varies, so every case has the first one's figures. Two cases are refused (a negative lift):
  // they have no work, and the largest case is one that binds.
  const PluginRegistry& registry = project_registry();
  for (const char* type : {"valvetrain.valve_motion", "valvetrain.time_area"}) {
    REQUIRE(registry.find(type));
    CHECK_FALSE(registry.find(type)->offers_forecast);
  }
  REQUIRE(registry.find("cam.kurz"));
  CHECK(registry.find("cam.kurz")->offers_forecast);
  std::vector<SampleSpec> specs{parse_sample("lift=7mm:9mm"), parse_sample("rpm=4000rpm:7000rpm")};
  CaseTable table = make_latin_hypercube(specs, 50, 3);
  for (std::size_t k : {std::size_t{0}, std::size_t{17}})
    table.numbers.si[k * table.variables.size()] = -1e-3;  // refused by max_lift's range: the case never runs
  Prepared p = prepare(stages123(), table, registry);
  std::vector<std::size_t> all(table.size());
  std::iota(all.begin(), all.end(), std::size_t{0});
  for (unsigned threads : {1u, 2u}) {
    INFO(threads << " threads");
    const SweepEstimate e = estimate_cases(p.graph, *p.binder, p.table, all, threads);
    double work = 0, largest = -1, memory = 0;
    std::size_t largest_case = 0, bound = 0;
    std::vector<CaseValue> row;
    for (std::size_t k : all) {
      Graph copy = p.graph;
      try {
        p.binder->apply(p.binder->bind(copy), copy, p.table.row(k, row));
      } catch (const SceneError&) {
        continue;
      }
      ++bound;
      const WorkEstimate one = estimate_work(copy);
      work += one.work;
      memory = std::max(memory, one.memory);
      if (one.work > largest) {
        largest = one.work;
        largest_case = k;
      }
    }
    CHECK(bound == 48);
    CHECK_THAT(e.total.work, Catch::Matchers::WithinRel(work, 1e-12) || Catch::Matchers::WithinAbs(work, 1e-9));
    CHECK_THAT(e.largest_memory, Catch::Matchers::WithinRel(memory, 1e-12) || Catch::Matchers::WithinAbs(memory, 1e-9));
    CHECK(memory > 0);
    CHECK(e.largest_case == largest_case);
    CHECK(e.largest_case == 1);
  }
}

TEST_CASE("the conformance kit fails a forecast that reads a parameter it does not name", "[sdk][forecast][conformance]") {
  // The kit's verdict on `type` (none: the check did not run), with its detail.
  const auto verdict = [](const NodeType& type) -> std::optional<Check> {
    NodeCheckOptions options;
    options.threads = 0;
    const Report r = check_node_type(type, options);
    const Check* c = find_check(r, "node test.counted", reads_check);
    return c ? std::optional<Check>(*c) : std::nullopt;
  };
  const auto fails = [&](const NodeType& type, const std::string& saying) {
    const std::optional<Check> c = verdict(type);
    REQUIRE(c);
    CHECK(c->status == Check::Status::failed);
    CHECK_THAT(c->detail, Catch::Matchers::Contains(saying));
  };
  SECTION("named truly") {
    const std::optional<Check> c = verdict(Counted(true, std::vector<std::string>{"points", "gain"}));
    REQUIRE(c);
    CHECK(c->status == Check::Status::passed);
    CHECK_THAT(c->detail, Catch::Matchers::Contains("1 parameters not named probed"));  // mode: its other choice
    // A name too many costs only speed: still true.
    const std::optional<Check> more = verdict(Counted(false, std::vector<std::string>{"points", "gain"}));
    REQUIRE(more);
    CHECK(more->status == Check::Status::passed);
  }
  SECTION("a number, an integer or a choice read but not named") {
    fails(Counted(true, std::vector<std::string>{"points"}), "'gain' is not named, but setting it to");
    fails(Counted(false, std::vector<std::string>{"gain"}), "'points' is not named");
    fails(Counted(false, std::vector<std::string>{"points"}, true), "'mode' is not named, but setting it to 'slow'");
  }
  SECTION("a name that is no parameter") { fails(Counted(false, std::vector<std::string>{"point"}), "'point'"); }
  SECTION("a type that does not say is not checked") { CHECK_FALSE(verdict(Counted(true, std::nullopt))); }
}

TEST_CASE("what a forecast reads crosses the C boundary by parameter index", "[sdk1][forecast]") {
  const auto through_c = [](std::shared_ptr<const NodeType> type) {
    static std::vector<std::unique_ptr<mechgraph::detail::NodeTypeExport>> kept;  // the C side lives on, as in a plugin
    kept.push_back(std::make_unique<mechgraph::detail::NodeTypeExport>(std::move(type), "test"));
    return mechgraph::detail::make_c_node_type(*kept.back()->c_type(), "test", true);
  };
  const auto named = through_c(std::make_shared<const Counted>(true, std::vector<std::string>{"gain", "points"}));
  CHECK(mechgraph::detail::forecast_reads(*named) == std::optional<std::vector<std::string>>(std::vector<std::string>{"gain", "points"}));
  // Not said, or a name that is no parameter: nothing crosses, the host asks case by case.
  CHECK_FALSE(mechgraph::detail::forecast_reads(*through_c(std::make_shared<const Counted>(true, std::nullopt))));
  CHECK_FALSE(mechgraph::detail::forecast_reads(*through_c(std::make_shared<const Counted>(true, std::vector<std::string>{"point"}))));
  // The kit's check on the host's view (as `mechgraph plugin-test` runs it) sees a false claim
  // and passes a true one; the forecasts cross C.
  for (const bool honest : {false, true}) {
    const auto type = through_c(std::make_shared<const Counted>(true, honest ? std::vector<std::string>{"points", "gain"}
                                                                             : std::vector<std::string>{"points"}));
    Report r;
    check_forecast_reads(*type, defaults_of(type->info()), {}, r, "node test.counted");
    const Check* c = find_check(r, "node test.counted", reads_check);
    REQUIRE(c);
    CHECK(c->status == (honest ? Check::Status::passed : Check::Status::failed));
  }
}
