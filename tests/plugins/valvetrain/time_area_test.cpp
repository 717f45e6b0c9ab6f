// Valve motion and time-area against closed forms (methods/valvetrain.md, stages 2-3); the valve's
// SVAJ curves in time and its events at a checking valve lift ("Cam curves and events").
#include "test_support.hpp"

#include "flow_area.hpp"
#include "node_types.hpp"
#include "valve_motion.hpp"

#include <mechgraph/domain/cam_curves.hpp>
#include <mechgraph/domain/cam_law.hpp>
#include <mechgraph/domain/valve_motion.hpp>
#include <mechgraph/numerics/piecewise.hpp>
#include <mechgraph/errors.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

using namespace mechgraph;
using namespace mechgraph::testing;
using Catch::Matchers::Contains;
using Catch::Matchers::WithinAbs;
using Catch::Matchers::WithinRel;

namespace {

constexpr double pi = std::numbers::pi;

// A law with closed-form integrals: h = H/2 (1 + cos(2 pi phi / phi_d)) on |phi| < phi_d/2.
//   int h dphi = H phi_d / 2,   int h^2 dphi = 3 H^2 phi_d / 8.
class CosineBump final : public CamLaw {
 public:
  CosineBump(double H, double phi_d) : H_(H), d_(phi_d) {}
  double event_begin() const override { return -d_ / 2; }
  double event_end() const override { return d_ / 2; }
  LiftDerivatives evaluate_in_event(double phi) const override {
    const double k = 2 * pi / d_;
    return {H_ / 2 * (1 + std::cos(k * phi)), -H_ / 2 * k * std::sin(k * phi), -H_ / 2 * k * k * std::cos(k * phi),
            H_ / 2 * k * k * k * std::sin(k * phi)};
  }
  std::vector<double> breakpoints() const override { return {}; }
  double max_lift() const override { return H_; }
  double base_radius() const override { return 0.017; }

 private:
  double H_, d_;
};

struct Study {
  double H = 9e-3, phi_d = 130 * pi / 180, rpm = 5600 * 2 * pi / 60, d0 = 0.034, a = pi / 4;
};


OutputSet run_motion(const Study& s, double rocker, double lash, std::map<std::string, ParamValue> more = {}) {
  auto type = valvetrain::make_valve_motion_type();
  InputSet in;
  in.add("cam", Value::handle(std::make_shared<const CosineBump>(s.H, s.phi_d)));
  OutputSet out;
  RecordingContext ctx;
  more["rpm"] = ParamValue::of_number(s.rpm);
  more["rocker_ratio"] = ParamValue::of_number(rocker);
  more["lash"] = ParamValue::of_number(lash);
  type->evaluate(defaults_of(type->info(), more), in, out, ctx);
  CHECK(ctx.work.at("evaluations") > 0);
  return out;
}

double scalar(const OutputSet& o, const std::string& port) { return o.all().at(port).as_scalar(); }

OutputSet run_time_area(const OutputSet& motion, const std::map<std::string, ParamValue>& params) {
  auto type = valvetrain::make_time_area_type();
  InputSet in;
  in.add("valve", motion.all().at("motion"));
  OutputSet out;
  RecordingContext ctx;
  type->evaluate(defaults_of(type->info(), params), in, out, ctx);
  return out;
}

}  // namespace

TEST_CASE("valve motion: lift, velocity and acceleration in time", "[valvetrain]") {
  const Study s;
  const double i = 1.4;
  const OutputSet m = run_motion(s, i, 0.0);
  const double wk = s.rpm / 2, k = 2 * pi / s.phi_d;
  CHECK_THAT(scalar(m, "max_lift"), WithinRel(i * s.H, 1e-12));
  CHECK_THAT(scalar(m, "max_velocity"), WithinRel(wk * i * s.H / 2 * k, 1e-10));
  CHECK_THAT(scalar(m, "max_acceleration"), WithinRel(wk * wk * i * s.H / 2 * k * k, 1e-9));
  CHECK_THAT(scalar(m, "min_acceleration"), WithinRel(-wk * wk * i * s.H / 2 * k * k, 1e-10));
  CHECK_THAT(scalar(m, "open_angle"), WithinRel(s.phi_d, 1e-14));
  const Series& curve = m.all().at("lift_curve").as_series();
  CHECK(curve.values.size() == 361);
  CHECK_THAT(curve.values[180], WithinRel(i * s.H, 1e-12));
}

TEST_CASE("valve lash shortens the open period where i h = lash", "[valvetrain]") {
  const Study s;
  const double i = 1.5, lash = 0.3e-3;
  const OutputSet m = run_motion(s, i, lash);
  // i H/2 (1 + cos(k phi)) = lash  =>  phi = acos(2 lash / (i H) - 1) / k
  const double phi_open = std::acos(2 * lash / (i * s.H) - 1) * s.phi_d / (2 * pi);
  CHECK_THAT(scalar(m, "open_angle"), WithinRel(2 * phi_open, 1e-12));
  CHECK_THAT(scalar(m, "max_lift"), WithinRel(i * s.H - lash, 1e-12));
  CHECK_THROWS_MATCHES(run_motion(s, 1.0, 10e-3), NodeError, Catch::Matchers::Predicate<NodeError>([](const NodeError& e) {
                         return e.parameter() == "lash" && std::string(e.what()).find("never opens") != std::string::npos;
                       }));
}

TEST_CASE("valve events at a checking valve lift: rocker ratio and lash in the closed form", "[valvetrain][events]") {
  // x = i H/2 (1 + cos k phi) - lash reaches c at phi = -+acos(2 (c + lash)/(i H) - 1)/k.
  const Study s;
  const double i = 1.5, lash = 0.25e-3, k = 2 * pi / s.phi_d, deg = pi / 180;
  auto at = [&](double c) { return std::acos(2 * (c + lash) / (i * s.H) - 1) / k; };
  const OutputSet m = run_motion(s, i, lash);
  CHECK_THAT(scalar(m, "opening_angle"), WithinAbs(-at(1e-3), 1e-12));
  CHECK_THAT(scalar(m, "closing_angle"), WithinAbs(at(1e-3), 1e-12));
  CHECK_THAT(scalar(m, "duration"), WithinAbs(2 * at(1e-3), 1e-12));
  CHECK_THAT(scalar(m, "crank_duration"), WithinAbs(4 * at(1e-3), 1e-12));
  CHECK_THAT(scalar(m, "centreline"), WithinAbs(0.0, 1e-12));
  const Table& e = m.all().at("events").as_table();
  REQUIRE(e.axis.values.size() == 3);  // 1 mm, 0.050 in, the seat
  CHECK_THAT(e.find("crank_opening")->values[1], WithinAbs(-2 * at(0.050 * 25.4e-3), 1e-12));
  // Seat to seat: the open period, which the lash shortens.
  CHECK_THAT(e.find("duration")->values[2], WithinAbs(scalar(m, "open_angle"), 1e-14));
  CHECK(e.find("opening_atdc") == nullptr);  // no installed timing given
  CHECK(m.all().at("events").as_table().channels.size() == 8);

  // Installed: the nose 105 deg after the overlap TDC (an intake); events from TDC, quoted in a note.
  const OutputSet timed = run_motion(s, i, lash, {{"nose_timing", ParamValue::of_number(105 * deg)}});
  const Table& t = timed.all().at("events").as_table();
  CHECK_THAT(t.find("opening_atdc")->values[0], WithinAbs(105 * deg - 2 * at(1e-3), 1e-12));
  CHECK_THAT(t.find("closing_atdc")->values[0], WithinAbs(105 * deg + 2 * at(1e-3), 1e-12));
  CHECK_THAT(t.find("centreline_atdc")->values[0], WithinAbs(105 * deg, 1e-12));

  // A checking lift the valve never reaches names the parameter and the valve's lift.
  CHECK_THROWS_MATCHES(run_motion(s, i, lash, {{"checking_lift", ParamValue::of_number(20e-3)}}), NodeError,
                       Catch::Matchers::Predicate<NodeError>([](const NodeError& e) {
                         return e.parameter() == "checking_lift" && std::string(e.what()).find("valve's lift 13.25 mm") != std::string::npos;
                       }));
}

TEST_CASE("a valve below its checking lift: the events table keeps the seat row, a wanted scalar is an error", "[valvetrain][events]") {
  // The report reads tables only: it must not fail on a valve that never reaches 1 mm.
  struct TablesOnly final : EvalContext {
    bool effect(std::string_view) const override { return false; }
    void log(LogLevel, std::string_view) override {}
    void report_work(std::string_view, double) override {}
    bool wanted(std::string_view output) const override { return output == "events" || output == "svaj"; }
  };
  const Study s;
  auto type = valvetrain::make_valve_motion_type();
  InputSet in;
  in.add("cam", Value::handle(std::make_shared<const CosineBump>(0.8e-3, s.phi_d)));  // 0.8 mm of lift
  const ParamSet p = defaults_of(type->info(), {{"rpm", ParamValue::of_number(s.rpm)}});
  OutputSet out;
  TablesOnly tables;
  type->evaluate(p, in, out, tables);
  const Table& e = out.all().at("events").as_table();
  REQUIRE(e.axis.values.size() == 1);  // neither 1 mm nor 0.050 in is reached: the seat only
  CHECK(e.axis.values[0] == 0.0);
  CHECK_THAT(e.find("duration")->values[0], WithinAbs(s.phi_d, 1e-14));
  CHECK(out.all().count("opening_angle") == 0);
  REQUIRE(out.notes().size() == 1);
  CHECK_THAT(out.notes()[0], Contains("checking_lift 1 mm is not below the valve's lift 0.8 mm"));
  OutputSet all;
  RecordingContext everything;
  CHECK_THROWS_AS(type->evaluate(p, in, all, everything), NodeError);
}

TEST_CASE("events quoted the engine way from the installed nose", "[valvetrain][events]") {
  const double deg = pi / 180;
  // 250 deg crank at the checking lift, centred on the nose: +-62.5 deg cam.
  const LiftEvents e{-62.5 * deg, 62.5 * deg, 125 * deg, 0.0};
  // Intake nose at 110 ATDC: opens 110 - 125 = -15 (15 BTDC), closes 235 (55 ABDC).
  CHECK(quote_events(e, 110 * deg) == "intake: opens 15.0 deg BTDC, closes 55.0 deg ABDC");
  // Exhaust nose at 112 BTDC: opens -237 (57 BBDC), closes 13 ATDC.
  CHECK(quote_events(e, -112 * deg) == "exhaust: opens 57.0 deg BBDC, closes 13.0 deg ATDC");
  // An intake opening late: after TDC.
  CHECK(quote_events(e, 130 * deg) == "intake: opens 5.0 deg ATDC, closes 75.0 deg ABDC");
}

TEST_CASE("valve svaj: lift and its derivatives in time, against the closed form", "[valvetrain][events]") {
  const Study s;
  const double i = 1.4, k = 2 * pi / s.phi_d, w = s.rpm / 2;
  const OutputSet m = run_motion(s, i, 0.0, {{"curve_points", ParamValue::of_integer(101)}});
  const Table& t = m.all().at("svaj").as_table();
  REQUIRE(t.axis.values.size() == 101);
  CHECK_THAT(t.axis.values.front(), WithinAbs(-0.6 * s.phi_d, 1e-15));  // the open period widened a tenth each side
  CHECK(t.find("velocity")->dimension == dim::velocity);
  CHECK(t.find("acceleration")->dimension == dim::acceleration);
  CHECK(t.find("jerk")->display_unit == "m/s^3");
  const double A = i * s.H / 2;
  for (std::size_t r = 0; r < t.axis.values.size(); ++r) {
    const double phi = t.axis.values[r];
    const bool open = std::abs(phi) < s.phi_d / 2;
    CHECK_THAT(t.find("crank_angle")->values[r], WithinAbs(2 * phi, 1e-15));
    CHECK_THAT(t.find("lift")->values[r], WithinAbs(open ? A * (1 + std::cos(k * phi)) : 0.0, 1e-15));
    CHECK_THAT(t.find("velocity")->values[r], WithinAbs(open ? -w * A * k * std::sin(k * phi) : 0.0, 1e-11));
    CHECK_THAT(t.find("acceleration")->values[r], WithinAbs(open ? -w * w * A * k * k * std::cos(k * phi) : 0.0, 1e-7));
    CHECK_THAT(t.find("jerk")->values[r], WithinAbs(open ? w * w * w * A * k * k * k * std::sin(k * phi) : 0.0, 1e-3));
  }
}

TEST_CASE("time-area: exact quadrature against the closed form, rectangle sum converges", "[valvetrain]") {
  const Study s;
  const OutputSet m = run_motion(s, 1.0, 0.0);
  // angle-area = pi (d0 cos a int h + sin a cos^2 a int h^2)
  const double c = std::cos(s.a), sn = std::sin(s.a);
  const double angle_area = pi * (s.d0 * c * s.H * s.phi_d / 2 + sn * c * c * 3 * s.H * s.H * s.phi_d / 8);
  const double wk = s.rpm / 2;
  const OutputSet exact = run_time_area(m, {{"seat_diameter", ParamValue::of_number(s.d0)}});
  CHECK_THAT(scalar(exact, "angle_area"), WithinRel(angle_area, 1e-13));
  CHECK_THAT(scalar(exact, "time_area"), WithinRel(angle_area / wk, 1e-13));
  CHECK_THAT(scalar(exact, "mean_flow_area"), WithinRel(angle_area / s.phi_d, 1e-13));
  CHECK_THAT(scalar(exact, "open_duration"), WithinRel(s.phi_d / wk, 1e-14));

  // The source's sum, written out here independently: A ~ (dphi / w_k) sum f_v(phi_i),
  // phi_i = phi_open + i dphi while phi_i <= phi_close.
  for (double step_deg : {5.0, 2.0, 1.0, 0.3}) {
    const double step = step_deg * pi / 180;
    double sum = 0.0;
    for (int i = 0; -s.phi_d / 2 + i * step <= s.phi_d / 2; ++i) {
      const double phi = -s.phi_d / 2 + i * step;
      const double h = s.H / 2 * (1 + std::cos(2 * pi * phi / s.phi_d));
      sum += pi * h * (s.d0 * c + h * sn * c * c);
    }
    const OutputSet rect = run_time_area(m, {{"seat_diameter", ParamValue::of_number(s.d0)},
                                             {"method", ParamValue::of_choice("rectangle")},
                                             {"step", ParamValue::of_number(step)}});
    INFO("step " << step_deg << " deg");
    CHECK_THAT(scalar(rect, "angle_area"), WithinRel(sum * step, 1e-13));
    CHECK_THAT(scalar(rect, "time_area"), WithinRel(sum * step / wk, 1e-13));
  }
}

TEST_CASE("three-stage flow area: continuous, equal to the cone formula in stage 1, the port area in stage 3", "[valvetrain]") {
  valvetrain::SeatGeometry seat{0.030, pi / 4, true, 2e-3, 0.031, 0.007};
  const valvetrain::FlowArea staged(seat);
  valvetrain::SeatGeometry cone = seat;
  cone.three_stage = false;
  const valvetrain::FlowArea conical(cone);
  REQUIRE(staged.stage_lifts().size() == 2);
  const double L1 = staged.stage_lifts()[0], L2 = staged.stage_lifts()[1];
  CHECK_THAT(L1, WithinRel(2e-3 / (std::sin(pi / 4) * std::cos(pi / 4)), 1e-14));
  CHECK_THAT(staged(0.5 * L1), WithinRel(conical(0.5 * L1), 1e-15));
  for (double L : {L1, L2}) CHECK_THAT(staged(L * (1 - 1e-12)), WithinRel(staged(L * (1 + 1e-12)), 1e-9));
  CHECK_THAT(staged(2 * L2), WithinRel(pi / 4 * (0.031 * 0.031 - 0.007 * 0.007), 1e-14));
  CHECK(staged(0.0) == 0.0);
  valvetrain::SeatGeometry narrow = seat;
  narrow.port_diameter = 0.012;
  CHECK_THROWS_WITH(valvetrain::FlowArea(narrow), Contains("too small for the seat"));
}

TEST_CASE("time-area with three stages integrates across the stage changes", "[valvetrain]") {
  const Study s;
  const OutputSet m = run_motion(s, 1.0, 0.0);
  const std::map<std::string, ParamValue> staged{{"seat_diameter", ParamValue::of_number(0.030)},
                                                 {"flow_area", ParamValue::of_choice("three_stage")},
                                                 {"seat_width", ParamValue::of_number(1.5e-3)},
                                                 {"port_diameter", ParamValue::of_number(0.029)},
                                                 {"stem_diameter", ParamValue::of_number(0.007)}};
  const double exact = scalar(run_time_area(m, staged), "angle_area");
  auto fine = staged;
  fine["method"] = ParamValue::of_choice("rectangle");
  fine["step"] = ParamValue::of_number(0.005 * pi / 180);
  CHECK_THAT(scalar(run_time_area(m, fine), "angle_area"), WithinRel(exact, 1e-6));
  auto missing = staged;
  missing.erase("port_diameter");
  CHECK_THROWS_WITH(run_time_area(m, missing), Contains("port_diameter"));
}

TEST_CASE("hard case: lash just below the valve's full lift leaves a tiny, finite open period", "[valvetrain]") {
  const Study s;
  const double lash = s.H * (1 - 1e-6);  // the valve opens by 9 nm
  // Events at half of that: the test context reads every output, the events' scalars too.
  const OutputSet m = run_motion(s, 1.0, lash, {{"checking_lift", ParamValue::of_number(4.5e-9)}});
  CHECK(scalar(m, "duration") > 0.0);
  CHECK(scalar(m, "duration") < scalar(m, "open_angle"));
  // H/2 (1 + cos k phi) = lash  =>  open angle = 2 acos(2 lash/H - 1) / k
  const double open = 2 * std::acos(2 * lash / s.H - 1) * s.phi_d / (2 * pi);
  CHECK_THAT(scalar(m, "open_angle"), WithinRel(open, 1e-6));
  CHECK_THAT(scalar(m, "max_lift"), WithinRel(s.H - lash, 1e-6));
  const OutputSet ta = run_time_area(m, {{"seat_diameter", ParamValue::of_number(s.d0)}});
  CHECK(std::isfinite(scalar(ta, "time_area")));
  CHECK(scalar(ta, "time_area") > 0.0);
  // Near the top the lift is a parabola: angle-area ~ pi d0 cos a (2/3) (H - lash) open.
  CHECK_THAT(scalar(ta, "angle_area"), WithinRel(pi * s.d0 * std::cos(s.a) * 2.0 / 3.0 * (s.H - lash) * open, 1e-4));
}

TEST_CASE("hard case: the flow area reaches the port 1e-7 below the top, exact agrees with a fine sum", "[valvetrain]") {
  const Study s;
  const OutputSet m = run_motion(s, 1.0, 0.0);
  // Choose the port so that stage 3 begins 1e-9 below the full lift: the flow area is flat only
  // over a sliver around the nose. The exact method must agree with a very fine rectangle sum.
  const double w = 1.5e-3, a = s.a, d0 = 0.030, Ds = 0.007;
  const double L2 = s.H * (1 - 1e-7);
  // L2 = sqrt(q^2 - w^2) + w tan a, q = (Dp^2 - Ds^2)/(4 Dm)  =>  Dp from L2.
  const double q = std::sqrt(std::pow(L2 - w * std::tan(a), 2) + w * w);
  const double Dp = std::sqrt(4 * (d0 + w) * q + Ds * Ds);
  const std::map<std::string, ParamValue> staged{{"seat_diameter", ParamValue::of_number(d0)},
                                                 {"flow_area", ParamValue::of_choice("three_stage")},
                                                 {"seat_width", ParamValue::of_number(w)},
                                                 {"port_diameter", ParamValue::of_number(Dp)},
                                                 {"stem_diameter", ParamValue::of_number(Ds)}};
  const double exact = scalar(run_time_area(m, staged), "angle_area");
  auto fine = staged;
  fine["method"] = ParamValue::of_choice("rectangle");
  fine["step"] = ParamValue::of_number(0.002 * pi / 180);
  CHECK_THAT(scalar(run_time_area(m, fine), "angle_area"), WithinRel(exact, 1e-7));
}

TEST_CASE("time-area: a tolerance below the round-off floor is refused at load with the floor", "[valvetrain]") {
  const std::string scene = R"(nodes:
  cam: { type: cam.kurz, params: { max_lift: 8 mm, action_angle: 130 deg, accel_angle: 18 deg, base_radius: 17 mm } }
  v:   { type: valvetrain.valve_motion, inputs: { cam: cam.law }, params: { rpm: 5600 rpm } }
  ta:  { type: valvetrain.time_area, inputs: { valve: v.motion }, params: { seat_diameter: 34 mm, tolerance: 1e-14 } }
outputs: [ta.time_area]
)";
  CHECK_THROWS_WITH(graph_from(scene, project_registry()), Contains("scene.yaml:4:") && Contains("'tolerance'") &&
                                                               Contains("must be >= 1e-13"));
  // At the floor the Kurz case costs what it did at the default (it once took 2e6 evaluations at
  // 1e-14), and the default already gives the value to 1e-13.
  std::string at_floor = scene;
  at_floor.replace(at_floor.find("1e-14"), 5, "1e-13");
  std::string at_default = scene;
  at_default.replace(at_default.find(", tolerance: 1e-14"), 18, "");
  const RunResult tight = run_yaml(at_floor, project_registry()), normal = run_yaml(at_default, project_registry());
  CHECK(tight.runs.back().work.at("evaluations") < 1000);
  CHECK_THAT(scalar_output(normal, "ta.time_area"), WithinRel(scalar_output(tight, "ta.time_area"), 1e-13));
}

TEST_CASE("time-area in closed form (the law's integrals of h and h^2) equals quadrature of the flow area", "[valvetrain]") {
  // Polydyne, flat three-arc and Kurz give lift_integrals: the node takes the closed form (a law
  // without them, the cosine bump above, takes quadrature). It must equal Gauss-Kronrod at 1e-13 of
  // the flow area over the motion, with and without lash, for several rocker ratios (the lash
  // crossing on the flank and on the nose).
  const char* cams[] = {
      "type: cam.polydyne, params: { max_lift: 8 mm, action_angle: 130 deg, base_radius: 25 mm, exponents: [2, 14, 26, 38, 50] }",
      "type: cam.polydyne, params: { max_lift: 6 mm, action_angle: 95 deg, base_radius: 40 mm, exponents: [2, 100, 300, 600, 994] }",
      "type: cam.three_arc, params: { max_lift: 8 mm, action_angle: 130 deg, base_radius: 25 mm, accel_angle: 18 deg }",
      "type: cam.kurz, params: { max_lift: 8 mm, action_angle: 130 deg, base_radius: 25 mm, accel_angle: 18 deg }"};
  for (const char* cam : cams)
    for (double lash : {0.0, 0.3, 5.0})
      for (double rocker : {1.0, 1.6}) {
        INFO(cam << ", lash " << lash << " mm, rocker " << rocker);
        const std::string yaml = std::string("nodes:\n  c: { ") + cam +
                                 " }\n  v: { type: valvetrain.valve_motion, inputs: { cam: c.law }, params: { rpm: 5000 rpm, "
                                 "rocker_ratio: " + std::to_string(rocker) + ", lash: " + std::to_string(lash) +
                                 " mm } }\n  ta: { type: valvetrain.time_area, inputs: { valve: v.motion }, params: { "
                                 "seat_diameter: 34 mm, seat_angle: 40 deg } }\noutputs: [ta.angle_area, v.motion]\n";
        const RunResult r = run_yaml(yaml, project_registry());
        const auto motion = std::dynamic_pointer_cast<const ValveMotion>(output(r, "v.motion").as_handle());
        REQUIRE(motion);
        const double a = 40 * pi / 180, d0 = 34e-3;
        long evaluations = 0;
        const double quadrature = numerics::integrate_piecewise(
            [&](double phi) {
              const double x = motion->at(phi).lift;
              return pi * x * (d0 * std::cos(a) + x * std::sin(a) * std::cos(a) * std::cos(a));
            },
            motion->knots(), 1e-13, evaluations);
        CHECK_THAT(scalar_output(r, "ta.angle_area"), WithinRel(quadrature, 1e-12));
      }
}

TEST_CASE("time-area: a lift whose square overflows is refused naming the input, never infinite", "[valvetrain][hard]") {
  Study s;
  s.H = 1e160;  // the flow area grows as the lift squared: 1e320 m^2 is beyond a double
  // (a checking lift the valve reaches at that scale: 1 mm is lost in the rounding of 1e160 m)
  const OutputSet m = run_motion(s, 1.0, 0.0, {{"checking_lift", ParamValue::of_number(s.H / 10)}});
  REQUIRE(std::isfinite(scalar(m, "max_lift")));
  for (const char* method : {"exact", "rectangle"}) {
    INFO(method);
    try {
      run_time_area(m, {{"seat_diameter", ParamValue::of_number(s.d0)}, {"method", ParamValue::of_choice(method)}});
      FAIL("no refusal");
    } catch (const NodeError& e) {
      CHECK(e.parameter() == "valve");
      CHECK_THAT(e.what(), Contains("beyond the range of a double"));
    }
  }
}
