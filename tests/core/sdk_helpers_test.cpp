// The pieces the SDK folds into one place: the distribution parser, the parameter range check, the
// examples the conformance kit evaluates with, and the kit's own verdicts on known-good and
// known-bad objects (sdk/include/mechgraph/).
#include <mechgraph/domain/cam_geometry.hpp>
#include <mechgraph/domain/tolerance.hpp>
#include <mechgraph/testing/node_conformance.hpp>

#include <catch2/catch.hpp>

#include <numbers>

using namespace mechgraph;
using Catch::Matchers::Contains;

namespace {

constexpr double deg = std::numbers::pi / 180.0;

// h = H (1 - (phi/w)^2)^3 on (-w, w): C2 at the event's ends, exact derivatives.
class Bump final : public CamLaw {
 public:
  Bump(double begin, double end) : begin_(begin), end_(end) {}
  double event_begin() const override { return begin_; }
  double event_end() const override { return end_; }
  std::vector<double> breakpoints() const override { return {}; }
  double max_lift() const override { return 1e-2; }
  double base_radius() const override { return 4e-2; }
  LiftDerivatives evaluate_in_event(double phi) const override {
    const double c = 0.5 * (begin_ + end_), w = 0.5 * (end_ - begin_), x = (phi - c) / w, s = 1 - x * x;
    const double H = 1e-2;
    return {H * s * s * s, H * 3 * s * s * (-2 * x) / w, H * (24 * x * x * s - 6 * s * s) / (w * w),
            H * (-48 * x * x * x + 72 * x * s) / (w * w * w)};
  }

 private:
  double begin_, end_;
};

}  // namespace

TEST_CASE("one distribution parser: names, refusal listing the choices, the parameter spec", "[sdk]") {
  CHECK(distribution_names() == std::vector<std::string>{"normal", "uniform", "triangular"});
  CHECK(parse_distribution("uniform") == Distribution::uniform);
  CHECK_FALSE(parse_distribution("Uniform"));
  CHECK(distribution_from("triangular", "d") == Distribution::triangular);
  CHECK_THROWS_WITH(distribution_from("gaussian", "links", "link 2"),
                    Contains("link 2: distribution 'gaussian' is not one of normal, uniform, triangular"));
  const ParamSpec p = distribution_param("spread", "how it spreads");
  CHECK(p.kind == ParamKind::choice);
  CHECK(p.choices == distribution_names());
  CHECK(p.default_value->text == "normal");
}

TEST_CASE("one parameter range check: inclusive and exclusive ends, whole numbers, display units", "[sdk]") {
  auto angle = ParamSpec::number("a", dim::angle, "an angle", "deg").at_least(0.1 * deg).below(2 * std::numbers::pi);
  CHECK(angle.admits(0.1 * deg));
  CHECK_FALSE(angle.admits(2 * std::numbers::pi));
  CHECK_FALSE(angle.admits(std::nan("")));
  CHECK_THAT(angle.value_problem(0.0), Contains("is out of range: it must be >= 0.1 deg and < 360 deg"));
  CHECK(angle.value_problem(1.0).empty());
  auto n = ParamSpec::integer("n", "count").at_least(2);
  CHECK(n.value_problem(2.5) == "must be a whole number");
  CHECK_THAT(n.value_problem(1e300), Contains("too large"));
  CHECK_THAT(ParamSpec::number("r", dim::length, "radius").positive().value_problem(0.0), Contains("> 0 m"));
}

TEST_CASE("the harness fills defaults, then examples, and checks text values like the host", "[sdk]") {
  NodeInfo info;
  info.type = "t.x";
  info.params = {ParamSpec::number("lift", dim::length, "lift", "mm").positive().with_example(9e-3),
                 ParamSpec::integer("samples", "n").with_default(16).at_least(4),
                 ParamSpec::number("must", dim::length, "no default, no example")};
  CHECK_THROWS_WITH(testing::params_with_defaults(info), Contains("'must' has neither a default nor an example"));
  const ParamSet p = testing::params_with_defaults(info, {{"must", "2 mm"}});
  CHECK(p.number("lift") == 9e-3);
  CHECK(p.integer("samples") == 16);
  CHECK(p.number("must") == Approx(2e-3).epsilon(1e-15).margin(0));
  CHECK_THROWS_WITH(testing::params_with_defaults(info, {{"must", "2 s"}}), Contains("expected a value in m"));
  CHECK_THROWS_WITH(testing::params_with_defaults(info, {{"must", "1 mm"}, {"samples", "3"}}), Contains("is out of range"));
}

TEST_CASE("the kit passes a good law and names what a bad one breaks", "[sdk]") {
  testing::CamLawCheckOptions c2;
  c2.continuity = 2;
  const testing::Report good = testing::check_cam_law(Bump(-60 * deg, 60 * deg), "bump", c2);
  INFO(good.str());
  CHECK(good.passed());
  CHECK_THAT(good.str(), Contains("PASS  bump: continuous at breakpoints and event ends up to the acceleration"));
  testing::CamLawCheckOptions c3;
  c3.continuity = 3;  // the jerk steps at the ends: (-48 + 0) / w^3 != 0
  CHECK_FALSE(testing::check_cam_law(Bump(-60 * deg, 60 * deg), "bump", c3).passed());
  const testing::Report wide = testing::check_cam_law(Bump(-250 * deg, 50 * deg), "wide");
  CHECK_FALSE(wide.passed());
  CHECK_THAT(wide.str(), Contains("FAIL  wide: the host's contract check (its event begins at -250 deg"));
  // The cam geometry every cam node uses, on the same law: curvature of a flat-tappet contour
  // r0 + h + h'' at the nose, and the undercut refusal with the base radius that removes it.
  const Bump bump(-60 * deg, 60 * deg);
  const LiftDerivatives nose = bump.at(0.0);
  CHECK(contour_curvature_radius(bump, 0.0) == Approx(0.04 + nose.lift + nose.acceleration).epsilon(1e-12).margin(1e-15));
  const CamSummary s = summarize(bump, 16);
  CHECK(s.max_velocity > 0);
  CamSummary undercut = s;
  undercut.min_curvature_radius = -1e-3;
  CHECK_THROWS_WITH(refuse_undercut(undercut, 0.04, {}, 16), Contains("undercut") && Contains("raise base_radius"));
}

TEST_CASE("the kit refuses a channel that jumps at events on a type with no events output", "[sdk][presentation]") {
  NodeInfo info;
  info.type = "t.jumpy";
  Presentation p;
  p.with(ChannelDecl::of("speed").flag(channel_flag::jumps_at_events));
  info.outputs = {PortSpec::table("curves", "speed over time").presented(p)};
  CHECK_THAT(testing::detail::presentation_problem(info), Catch::Matchers::Contains("no output of role events"));
  Presentation events;
  events.role = Role::events;
  info.outputs.push_back(PortSpec::table("events", "impacts").presented(events));
  CHECK(testing::detail::presentation_problem(info).empty());
}

namespace {

// A node type with blocks: y = 2 x, or (with `off_by` set) a block path that drifts from it.
class Doubler final : public NodeType, public BlockEvaluation {
 public:
  explicit Doubler(double off_by = 0.0) : off_by_(off_by) {
    info_.type = "t.doubler";
    info_.params = {ParamSpec::number("x", dim::length, "input", "mm").with_default(1e-3)};
    info_.outputs = {PortSpec::scalar("y", dim::length, "2 x", "mm")};
  }
  const NodeInfo& info() const override { return info_; }
  void evaluate(const ParamSet& p, const InputSet&, OutputSet& out, EvalContext&) const override {
    out.set_scalar("y", 2.0 * p.number("x"));
  }
  bool block_supported(const BlockRequest&) const override { return true; }
  void evaluate_block(const BlockParams& p, const BlockInputs&, BlockOutputs& out, BlockCases& cases, EvalContext&) const override {
    const BlockColumn x = p.number("x");
    double* y = out.scalar("y");
    for_each_live_case(cases, [&](std::size_t i) {
      if (y) y[i] = 2.0 * x[i] + off_by_;
    });
  }

 private:
  NodeInfo info_;
  double off_by_;
};

}  // namespace

TEST_CASE("the kit holds a node type's blocks to its single evaluation, bit for bit", "[sdk][blocks]") {
  const auto verdict = [](const NodeType& type) {
    const testing::Report report = testing::check_node_type(type);
    for (const auto& c : report.checks())
      if (c.name == testing::block_check) return c;
    FAIL("no block check in:\n" << report.str());
    return testing::Check{};
  };
  CHECK(verdict(Doubler()).status == testing::Check::Status::passed);
  const auto drifting = verdict(Doubler(1e-18));
  CHECK(drifting.status == testing::Check::Status::failed);
  CHECK_THAT(drifting.detail, Contains("case 0, output 'y'"));
}
