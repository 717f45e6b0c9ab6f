// The cam node types' block path (mechgraph/block.hpp) case by case against their single
// evaluation, bit for bit: the common numbers read from the block's columns, the law's own
// preparation for a block (CamLawDefinition::prepare_block: the polydyne's exponent series, the
// three-arc's choices, found once per block), the law's own scalars kept in one set per block, the
// cases a node refuses (alone, or every case when the preparation itself refuses); every answer of
// a law compared, not only its points.
#include "cam_test_support.hpp"

#include <catch2/catch.hpp>

#include <mechgraph/block.hpp>
#include <mechgraph/domain/cam_law_block.hpp>

#include <cmath>
#include <map>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

using namespace mechgraph;
using namespace mechgraph::cams::testing;

namespace {

constexpr double deg = std::numbers::pi / 180.0;
constexpr double mm = 1e-3;

// Every answer of `law` equal bit for bit to `alone`'s: the figures, the breakpoints, the points at
// 33 angles and one ulp either side of every knot, the monotone runs, the lift integrals over
// whole, partial and empty spans, and the higher derivatives.
void check_law_equals(const CamLaw& law, const CamLaw& alone) {
  REQUIRE(law.event_begin() == alone.event_begin());
  REQUIRE(law.event_end() == alone.event_end());
  CHECK(law.max_lift() == alone.max_lift());
  CHECK(law.base_radius() == alone.base_radius());
  CHECK(law.roller_radius() == alone.roller_radius());
  CHECK(law.breakpoints() == alone.breakpoints());
  const double begin = law.event_begin(), end = law.event_end(), width = end - begin;
  std::vector<double> angles;
  for (int j = 1; j < 34; ++j) angles.push_back(begin + width * j / 34.0);
  for (double knot : law.knots()) {
    if (knot > begin) angles.push_back(std::nextafter(knot, begin));
    if (knot < end) angles.push_back(std::nextafter(knot, end));
    if (knot > begin && knot < end) angles.push_back(knot);
  }
  for (double phi : angles) {
    INFO("at " << phi);
    const LiftDerivatives a = law.evaluate_in_event(phi), b = alone.evaluate_in_event(phi);
    CHECK(a.lift == b.lift);
    CHECK(a.velocity == b.velocity);
    CHECK(a.acceleration == b.acceleration);
    CHECK(a.jerk == b.jerk);
    double a4 = 0.0, a5 = 0.0, b4 = 0.0, b5 = 0.0;
    CHECK(law.higher_derivatives(phi, a4, a5) == alone.higher_derivatives(phi, b4, b5));
    CHECK(a4 == b4);
    CHECK(a5 == b5);
  }
  for (int order = 0; order <= 2; ++order) {
    std::vector<double> a, b;
    CHECK(law.monotone_breaks(order, a) == alone.monotone_breaks(order, b));
    CHECK(a == b);
  }
  for (const auto& [from, to] : {std::pair{begin, end}, std::pair{begin + 0.3 * width, end - 0.2 * width},
                                 std::pair{begin + 0.6 * width, begin + 0.6 * width}}) {
    double a1 = 0.0, a2 = 0.0, b1 = 0.0, b2 = 0.0;
    CHECK(law.lift_integrals(from, to, a1, a2) == alone.lift_integrals(from, to, b1, b2));
    CHECK(a1 == b1);
    CHECK(a2 == b2);
  }
}

// Evaluates `type` as one block of the cases given by `varied` (a column of values per name) on top
// of `given`, and checks each case against the single evaluation of its parameters: refused by
// both or by neither; every answer of the law (check_law_equals) and the scalar outputs `scalars`
// equal bit for bit.
void check_block_equals_single(const std::string& type, const std::map<std::string, ParamValue>& given,
                               const std::map<std::string, std::vector<double>>& varied,
                               const std::vector<std::string>& scalars) {
  const NodeType& node = cam_type(type);
  const auto* blocks = dynamic_cast<const BlockEvaluation*>(&node);
  REQUIRE(blocks);
  const std::size_t n = varied.begin()->second.size();
  ParamSet fixed = mechgraph::testing::defaults_of(node.info(), given);
  std::map<std::string, BlockColumn, std::less<>> columns;
  for (const auto& [name, values] : varied) columns[name] = BlockColumn{values.data(), 1};
  BlockParams params(fixed, columns);
  BlockOutputs out(n);
  for (const std::string& port : scalars) out.want_scalar(port);
  BlockCases cases(n);
  mechgraph::testing::RecordingContext ctx;
  blocks->evaluate_block(params, BlockInputs{}, out, cases, ctx);
  const auto& laws = dynamic_cast<const CamLawBlock&>(*out.handles().at("law"));
  for (std::size_t k = 0; k < n; ++k) {
    INFO(type << ", case " << k);
    std::map<std::string, ParamValue> one = given;
    for (const auto& [name, values] : varied) one[name] = ParamValue::of_number(values[k]);
    OutputSet single;
    bool refused = false;
    try {
      single = run_cam(type, one);
    } catch (const NodeError&) {
      refused = true;
    }
    REQUIRE(cases.failed(k) == refused);
    if (refused) continue;
    const CamLaw& law = laws.law(k);
    const auto& alone = dynamic_cast<const CamLaw&>(*single.all().at("law").as_handle());
    check_law_equals(law, alone);
    for (const std::string& port : scalars) CHECK(out.scalars().at(port)[k] == single.all().at(port).as_scalar());
  }
}

ParamValue number(double v) { return ParamValue::of_number(v); }

}  // namespace

TEST_CASE("cam blocks: three-arc cases equal their single evaluations, by accel_angle and by nose_radius", "[cams][blocks]") {
  const std::map<std::string, ParamValue> common{{"max_lift", number(8 * mm)}, {"action_angle", number(130 * deg)},
                                                 {"base_radius", number(26 * mm)}};
  auto with = [&](std::map<std::string, ParamValue> more) {
    more.insert(common.begin(), common.end());
    return more;
  };
  // A flat tappet by accel_angle; 80 deg is past half the action angle: that case alone is refused.
  check_block_equals_single("cam.three_arc", with({{"accel_angle", number(18 * deg)}}),
                            {{"accel_angle", {16 * deg, 18 * deg, 80 * deg, 20 * deg}}, {"max_lift", {7 * mm, 8 * mm, 8 * mm, 9 * mm}}},
                            {"max_lift", "flank_radius", "nose_radius"});
  // A roller by nose_radius, its radius varied (0 is refused by the law: that case alone).
  check_block_equals_single("cam.three_arc",
                            with({{"nose_radius", number(6 * mm)}, {"follower", ParamValue::of_choice("roller")},
                                  {"roller_radius", number(10 * mm)}}),
                            {{"roller_radius", {8 * mm, 0.0, 12 * mm}}, {"nose_radius", {5 * mm, 6 * mm, 7 * mm}}},
                            {"max_lift", "flank_radius"});
  // Both accel_angle and nose_radius: the block's preparation refuses, so each case is refused alone.
  check_block_equals_single("cam.three_arc", with({{"accel_angle", number(18 * deg)}, {"nose_radius", number(6 * mm)}}),
                            {{"accel_angle", {16 * deg, 18 * deg}}}, {"max_lift"});
}

TEST_CASE("cam blocks: polydyne cases share one exponent series and equal their single evaluations", "[cams][blocks]") {
  const std::map<std::string, ParamValue> common{{"max_lift", number(8 * mm)}, {"action_angle", number(130 * deg)},
                                                 {"base_radius", number(26 * mm)}};
  auto with = [&](std::map<std::string, ParamValue> more) {
    more.insert(common.begin(), common.end());
    return more;
  };
  const std::map<std::string, std::vector<double>> varied{{"max_lift", {7 * mm, 8 * mm, 9 * mm}},
                                                          {"action_angle", {120 * deg, 130 * deg, 140 * deg}},
                                                          {"base_radius", {24 * mm, 26 * mm, 28 * mm}}};
  check_block_equals_single("cam.polydyne", with({{"exponents", ParamValue::of_list({2, 14, 26, 38, 50})}}), varied,
                            {"max_lift", "exponent_q"});
  check_block_equals_single("cam.polydyne", common, varied, {"max_lift", "exponent_q"});  // the default exponents
  // accel_angle: q found per case (no block preparation).
  check_block_equals_single("cam.polydyne", with({{"accel_angle", number(30 * deg)}}),
                            {{"accel_angle", {28 * deg, 30 * deg}}, {"max_lift", {8 * mm, 9 * mm}}}, {"max_lift", "exponent_q"});
  // Exponents the law refuses: the preparation refuses, and so does every case alone.
  check_block_equals_single("cam.polydyne", with({{"exponents", ParamValue::of_list({2, 6, 9, 14, 18})}}),
                            {{"max_lift", {7 * mm, 8 * mm}}}, {"max_lift"});
}

TEST_CASE("cam blocks: Kurz cases equal their single evaluations, rise_split kept per case", "[cams][blocks]") {
  check_block_equals_single("cam.kurz",
                            {{"max_lift", number(8 * mm)}, {"action_angle", number(130 * deg)}, {"base_radius", number(26 * mm)},
                             {"accel_angle", number(18 * deg)}},
                            {{"accel_angle", {16 * deg, 18 * deg, 70 * deg, 20 * deg}}, {"action_angle", {120 * deg, 130 * deg, 130 * deg, 140 * deg}}},
                            {"max_lift", "rise_split"});
  // rise_split given and varied; 1.2 is refused by the law, that case alone.
  check_block_equals_single("cam.kurz",
                            {{"max_lift", number(8 * mm)}, {"action_angle", number(130 * deg)}, {"base_radius", number(26 * mm)},
                             {"accel_angle", number(18 * deg)}, {"rise_split", number(0.5)}},
                            {{"rise_split", {0.3, 1.2, 0.55, 0.7}}, {"base_radius", {24 * mm, 26 * mm, 27 * mm, 28 * mm}}},
                            {"max_lift", "rise_split"});
}
