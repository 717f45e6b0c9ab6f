// nose_timing places the nose, the angle of maximum lift, on every cam: an asymmetric program's
// nose is not its event's centre. A 3-4-5 rise of 8 mm over 50 deg straight into a cycloidal return
// over 90 deg: the maximum is at the junction, -70 + 50 = -20 deg from the law's zero (the event's
// centre), in closed form; the events from TDC follow from it.
#include "cam_test_support.hpp"

#include <mechgraph/domain/cam_law.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

namespace mechgraph::cams {
namespace {

constexpr double deg = std::numbers::pi / 180.0;
using Catch::Matchers::WithinAbs;

OutputSet run_program(std::vector<Record> segments, double nose_timing) {
  NodeTypeList types;
  add_program_type(types);
  ParamValue v;
  v.kind = ParamKind::record_list;
  v.records = std::move(segments);
  OutputSet out;
  mechgraph::testing::RecordingContext ctx;
  types.front()->evaluate(mechgraph::testing::defaults_of(types.front()->info(), {{"segments", v},
                                                                                 {"base_radius", ParamValue::of_number(40e-3)},
                                                                                 {"nose_timing", ParamValue::of_number(nose_timing)}}),
                          InputSet{}, out, ctx);
  return out;
}

TEST_CASE("nose_timing means the nose on an asymmetric program, the event centre is its own quantity", "[cams][nose]") {
  const std::vector<Record> segments = {
      {{"type", ParamValue::of_choice("rise")}, {"angle", ParamValue::of_number(50 * deg)},
       {"lift", ParamValue::of_number(8e-3)}, {"law", ParamValue::of_choice("poly345")}},
      {{"type", ParamValue::of_choice("return")}, {"angle", ParamValue::of_number(90 * deg)},
       {"lift", ParamValue::of_number(8e-3)}, {"law", ParamValue::of_choice("cycloidal")}}};
  const OutputSet out = run_program(segments, 108 * deg);
  const auto& all = out.all();
  const double nose = all.at("nose_angle").as_scalar();
  CHECK_THAT(nose, WithinAbs(-20 * deg, 1e-9));
  // Seat to seat the event runs -70 .. 70 deg: its centre lies 20 deg after the nose.
  CHECK_THAT(all.at("event_centre").as_scalar(), WithinAbs(20 * deg, 1e-9));
  const double open = all.at("opening_angle").as_scalar(), close = all.at("closing_angle").as_scalar();
  CHECK_THAT(all.at("centreline").as_scalar(), WithinAbs(0.5 * (open + close) - nose, 1e-12));
  // From TDC: the nose at 108 deg crank, every event twice its cam angle from the nose away.
  const Table& t = all.at("events").as_table();
  CHECK_THAT(t.find("opening_atdc")->values[0], WithinAbs(108 * deg + 2 * (open - nose), 1e-9));
  CHECK_THAT(t.find("closing_atdc")->values[0], WithinAbs(108 * deg + 2 * (close - nose), 1e-9));
  CHECK_THAT(t.find("centreline_atdc")->values[0], WithinAbs(108 * deg + 2 * (0.5 * (open + close) - nose), 1e-9));
  CHECK_THAT(t.find("centreline")->values[0], WithinAbs(0.5 * (open + close) - nose, 1e-12));
  // The lift is largest exactly there (a second method: the law itself around the nose).
  const auto law = std::dynamic_pointer_cast<const CamLaw>(all.at("law").as_handle());
  CHECK(law->at(nose).lift == Approx(8e-3).epsilon(1e-12).margin(1e-15));
  CHECK(law->at(nose - 1 * deg).lift < law->at(nose).lift);
  CHECK(law->at(nose + 1 * deg).lift < law->at(nose).lift);
}

TEST_CASE("a symmetric lobe's nose is its zero: the events from TDC are unchanged", "[cams][nose]") {
  const OutputSet out = testing::run_cam("cam.kurz", {{"max_lift", ParamValue::of_number(9e-3)},
                                                      {"action_angle", ParamValue::of_number(130 * deg)},
                                                      {"accel_angle", ParamValue::of_number(18 * deg)},
                                                      {"base_radius", ParamValue::of_number(40e-3)},
                                                      {"nose_timing", ParamValue::of_number(105 * deg)}});
  CHECK_THAT(out.all().at("nose_angle").as_scalar(), WithinAbs(0.0, 1e-9));
  CHECK_THAT(out.all().at("centreline").as_scalar(), WithinAbs(0.0, 1e-9));
  CHECK_THAT(out.all().at("event_centre").as_scalar(), WithinAbs(0.0, 1e-9));
  CHECK_THAT(out.all().at("events").as_table().find("centreline_atdc")->values[0], WithinAbs(105 * deg, 1e-8));
}

}  // namespace
}  // namespace mechgraph::cams
