// joint.spherical: ISO 12240-1 radial internal clearance by group and bore, explicit clearance,
// ring fits, tilt limit and axial clearance.
// Table cells checked against the ZVL catalogue page "Spherical plain bearings", table "Radial
// clearance" (zvlslovakia.bg), GE bearings steel/steel, in um:
//   d over 12 incl 20:  C2 10-40,  normal 40-82,   C3 82-124
//   d over 20 incl 35:  C2 12-50,  normal 50-100,  C3 100-150
//   d over 90 incl 140: C2 18-85,  normal 85-165,  C3 165-245
//   d over 140 incl 240: C2 18-100, normal 100-192, C3 192-284
#include "test_support.hpp"

#include "joints/node_types.hpp"
#include "joints/spherical_clearance.hpp"

#include <mechgraph/domain/fit.hpp>
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

constexpr double um = 1e-6, mm = 1e-3, deg = std::numbers::pi / 180.0;

OutputSet run_spherical(std::map<std::string, ParamValue> params, const std::vector<std::shared_ptr<const Fit>>& fits = {}) {
  auto type = joints::make_spherical_joint_type();
  InputSet in;
  for (const auto& f : fits) in.add("fits", Value::handle(f));
  OutputSet out;
  RecordingContext ctx;
  type->evaluate(defaults_of(type->info(), params), in, out, ctx);
  return out;
}

ParamValue number(double v) { return ParamValue::of_number(v); }
ParamValue group(const char* g) { return ParamValue::of_choice(g); }
double scalar(const OutputSet& o, const std::string& port) { return o.all().at(port).as_scalar(); }
std::shared_ptr<const JointPlay> play_of(const OutputSet& o) {
  return std::dynamic_pointer_cast<const JointPlay>(o.all().at("play").as_handle());
}

auto names(const std::string& parameter, const std::string& text = {}) {
  return Catch::Matchers::Predicate<NodeError>([=](const NodeError& e) {
    return e.parameter() == parameter && std::string(e.what()).find(text) != std::string::npos;
  });
}

}  // namespace

TEST_CASE("ISO 12240-1 radial internal clearance: table cells", "[joints][spherical]") {
  using joints::ClearanceGroup;
  struct Cell {
    double bore_mm;
    ClearanceGroup group;
    double min_um, max_um;
  };
  for (const Cell& c : {Cell{20, ClearanceGroup::normal, 40, 82}, Cell{20, ClearanceGroup::c2, 10, 40},
                        Cell{20, ClearanceGroup::c3, 82, 124}, Cell{12.5, ClearanceGroup::normal, 40, 82},
                        Cell{25, ClearanceGroup::c3, 100, 150}, Cell{35, ClearanceGroup::normal, 50, 100},
                        Cell{40, ClearanceGroup::c2, 15, 60}, Cell{80, ClearanceGroup::normal, 72, 142},
                        Cell{140, ClearanceGroup::c3, 165, 245}, Cell{160, ClearanceGroup::c2, 18, 100},
                        Cell{240, ClearanceGroup::normal, 100, 192}, Cell{240, ClearanceGroup::c3, 192, 284}}) {
    INFO("bore " << c.bore_mm << " mm, group " << joints::to_string(c.group));
    const joints::ClearanceRange r = joints::radial_internal_clearance(c.bore_mm * mm, c.group);
    CHECK_THAT(r.min, WithinRel(c.min_um * um, 1e-12));
    CHECK_THAT(r.max, WithinRel(c.max_um * um, 1e-12));
  }
  // "20 mm" as a scene parses it may be a rounding off 0.020: it stays in the row "incl. 20".
  CHECK_THAT(joints::radial_internal_clearance(20 * mm * (1 + 1e-15), ClearanceGroup::normal).max, WithinRel(82 * um, 1e-12));
  CHECK_THAT(joints::radial_internal_clearance(20.001 * mm, ClearanceGroup::normal).max, WithinRel(100 * um, 1e-12));
}

TEST_CASE("ISO 12240-1 radial internal clearance: groups ordered C2 < normal < C3 in every row", "[joints][spherical]") {
  const auto& table = joints::radial_clearance_table();
  REQUIRE(table.size() == 6);
  for (std::size_t i = 0; i < table.size(); ++i) {
    const auto& row = table[i];
    INFO("row " << row.bore_over / mm << " - " << row.bore_incl / mm << " mm");
    CHECK(row.c2.min < row.c2.max);
    CHECK(row.c2.max <= row.normal.min);  // adjacent groups meet (equal in this table)
    CHECK(row.normal.min < row.normal.max);
    CHECK(row.normal.max <= row.c3.min);
    CHECK(row.c3.min < row.c3.max);
    if (i > 0) {
      CHECK(row.bore_over == table[i - 1].bore_incl);  // no gaps between rows
      CHECK(row.normal.max > table[i - 1].normal.max);  // clearance grows with the bore
    }
  }
  for (double bore : {15 * mm, 50 * mm, 200 * mm}) {
    const OutputSet c2 = run_spherical({{"bore", number(bore)}, {"clearance_group", group("C2")}});
    const OutputSet n = run_spherical({{"bore", number(bore)}, {"clearance_group", group("normal")}});
    const OutputSet c3 = run_spherical({{"bore", number(bore)}, {"clearance_group", group("C3")}});
    CHECK(scalar(c2, "play_mean") < scalar(n, "play_mean"));
    CHECK(scalar(n, "play_mean") < scalar(c3, "play_mean"));
    CHECK(scalar(c2, "play_max") <= scalar(n, "play_min"));
    CHECK(scalar(n, "play_max") <= scalar(c3, "play_min"));
  }
}

TEST_CASE("joint.spherical: the group's clearance is the play, labelled by group and bore", "[joints][spherical]") {
  const OutputSet out = run_spherical({{"bore", number(20 * mm)}, {"clearance_group", group("C3")}});
  CHECK_THAT(scalar(out, "play_min"), WithinRel(82 * um, 1e-12));
  CHECK_THAT(scalar(out, "play_max"), WithinRel(124 * um, 1e-12));
  CHECK_THAT(scalar(out, "play_mean"), WithinRel(103 * um, 1e-12));
  CHECK_THAT(scalar(out, "internal_clearance_min"), WithinRel(82 * um, 1e-12));
  CHECK_THAT(scalar(out, "internal_clearance_max"), WithinRel(124 * um, 1e-12));
  const auto play = play_of(out);
  REQUIRE(play);
  CHECK(play->kind() == "joint_play");
  REQUIRE(play->terms().size() == 1);  // no fits connected: the port is optional
  CHECK(play->terms()[0].label == "radial internal clearance C3, bore 20 mm");
  CHECK(play->terms()[0].links.size() == 1);
  CHECK_THAT(play->terms()[0].links[0].half_range, WithinRel(21 * um, 1e-12));
  CHECK(play->terms()[0].links[0].distribution == Distribution::normal);
  CHECK(out.all().count("axial_play_min") == 0);  // no axial data given
  const OutputSet normal = run_spherical({{"bore", number(20 * mm)}, {"clearance_distribution", ParamValue::of_choice("uniform")}});
  CHECK(play_of(normal)->terms()[0].label == "radial internal clearance CN, bore 20 mm");
  CHECK(play_of(normal)->terms()[0].links[0].distribution == Distribution::uniform);
}

TEST_CASE("joint.spherical: explicit radial clearance overrides the group, both or neither", "[joints][spherical]") {
  const OutputSet out = run_spherical({{"bore", number(20 * mm)},
                                       {"clearance_group", group("C3")},
                                       {"radial_clearance_min", number(30 * um)},
                                       {"radial_clearance_max", number(60 * um)}});
  CHECK_THAT(scalar(out, "play_min"), WithinRel(30 * um, 1e-12));
  CHECK_THAT(scalar(out, "play_max"), WithinRel(60 * um, 1e-12));
  CHECK_THAT(scalar(out, "play_mean"), WithinRel(45 * um, 1e-12));
  CHECK(play_of(out)->terms()[0].label == "radial internal clearance 30-60 um, bore 20 mm");
  // Without a bore, and for a bore the table does not cover, explicit values still work.
  const OutputSet small = run_spherical({{"bore", number(8 * mm)}, {"radial_clearance_min", number(32 * um)},
                                         {"radial_clearance_max", number(68 * um)}});
  CHECK_THAT(scalar(small, "play_max"), WithinRel(68 * um, 1e-12));
  CHECK_NOTHROW(run_spherical({{"radial_clearance_min", number(32 * um)}, {"radial_clearance_max", number(68 * um)}}));

  CHECK_THROWS_MATCHES(run_spherical({{"bore", number(20 * mm)}, {"radial_clearance_min", number(30 * um)}}), NodeError,
                       names("radial_clearance_max"));
  CHECK_THROWS_MATCHES(run_spherical({{"bore", number(20 * mm)}, {"radial_clearance_max", number(30 * um)}}), NodeError,
                       names("radial_clearance_min"));
  CHECK_THROWS_MATCHES(run_spherical({{"radial_clearance_min", number(60 * um)}, {"radial_clearance_max", number(30 * um)}}),
                       NodeError, names("radial_clearance_max", "below"));
  CHECK_THROWS_MATCHES(run_spherical({}), NodeError, names("bore", "needed"));
}

TEST_CASE("joint.spherical: deflection beyond the tilt limit is an error naming deflection and the limit", "[joints][spherical]") {
  CHECK_NOTHROW(run_spherical({{"bore", number(20 * mm)}, {"deflection", number(6 * deg)}}));
  CHECK_THROWS_MATCHES(run_spherical({{"bore", number(20 * mm)}, {"deflection", number(8 * deg)}}), NodeError,
                       names("deflection", "deflection 8 deg exceeds the bearing's tilt limit alpha = 6 deg"));
  CHECK_THROWS_WITH(run_spherical({{"bore", number(20 * mm)}, {"deflection", number(8 * deg)}}), Contains("joint.cardan"));
  // A bearing with a larger catalogue tilt angle (small bores: GE 4 E tilts 16 deg) allows more.
  CHECK_NOTHROW(run_spherical({{"bore", number(20 * mm)}, {"deflection", number(8 * deg)}, {"tilt_limit", number(9 * deg)}}));
  CHECK_THROWS_MATCHES(
      run_spherical({{"bore", number(20 * mm)}, {"deflection", number(10 * deg)}, {"tilt_limit", number(9 * deg)}}), NodeError,
      names("deflection", "alpha = 9 deg"));
}

TEST_CASE("joint.spherical: a bore outside the table is an error listing the covered range", "[joints][spherical]") {
  for (double bore : {10 * mm, 12 * mm, 250 * mm, 300 * mm}) {
    INFO("bore " << bore / mm << " mm");
    CHECK_THROWS_MATCHES(run_spherical({{"bore", number(bore)}}), NodeError, names("bore", "12 mm < d <= 240 mm"));
  }
}

TEST_CASE("joint.spherical: ring fits add their clearance, a press-fitted ring adds none", "[joints][spherical]") {
  // Pin in the inner ring 20 H7/g6: H7 +21/0, g6 -7/-20 um -> clearance 7..41, mean 24 um.
  auto pin = std::make_shared<const Fit>("20 H7/g6", 0.020, LimitPair{21 * um, 0.0}, LimitPair{-7 * um, -20 * um},
                                         Distribution::normal, Distribution::normal);
  // Outer ring in the housing 35 N7/h6 (D = 35 mm, 30-50 range): N7 -8/-33, h6 0/-16 um -> -33..8, mean -12.5 um.
  auto ring = std::make_shared<const Fit>("35 N7/h6", 0.035, LimitPair{-8 * um, -33 * um}, LimitPair{0.0, -16 * um},
                                          Distribution::normal, Distribution::normal);
  const OutputSet out = run_spherical({{"bore", number(20 * mm)}}, {pin, ring});
  CHECK_THAT(scalar(out, "play_min"), WithinRel((40 + 7 + 0) * um, 1e-12));
  CHECK_THAT(scalar(out, "play_max"), WithinRel((82 + 41 + 8) * um, 1e-12));
  CHECK_THAT(scalar(out, "play_mean"), WithinRel((61 + 24 + 0) * um, 1e-12));
  REQUIRE(play_of(out)->terms().size() == 3);
  CHECK(play_of(out)->terms()[1].label == "20 H7/g6");
  CHECK(play_of(out)->terms()[2].label == "35 N7/h6");
}

TEST_CASE("joint.spherical: axial internal clearance from the sphere geometry and from a factor", "[joints][spherical]") {
  // GE 40 ES (SKF data as listed by tikindustrial.com): d = 40 mm, dk = 52.4 mm, outer ring
  // width C = 22 mm, tilt angle 6 deg; normal group for d = 40: 60..120 um.
  const double bore = 40 * mm, dk = 52.4 * mm, C = 22 * mm;
  const OutputSet out = run_spherical({{"bore", number(bore)}, {"ball_diameter", number(dk)}, {"outer_ring_width", number(C)}});
  // Independent route: the axial shift a at which the inner sphere (radius Ri) touches the edge of
  // the outer ring's band (axial position C/2 on the sphere of radius Ro = Ri + cr/2), found by
  // bisection on the distance from the shifted centre to that edge.
  auto by_bisection = [&](double cr) {
    const long double Ri = dk / 2, Ro = Ri + cr / 2, z = C / 2, rho = std::sqrt(Ro * Ro - z * z);
    auto gap = [&](long double a) { return std::sqrt(rho * rho + (z - a) * (z - a)) - Ri; };
    long double lo = 0, hi = z;  // gap(lo) > 0 > gap(hi)
    for (int i = 0; i < 200; ++i) {
      const long double mid = (lo + hi) / 2;
      (gap(mid) > 0 ? lo : hi) = mid;
    }
    return static_cast<double>(lo + hi);  // 2 a
  };
  CHECK_THAT(scalar(out, "axial_play_min"), WithinRel(by_bisection(60 * um), 1e-9));
  CHECK_THAT(scalar(out, "axial_play_max"), WithinRel(by_bisection(120 * um), 1e-9));
  // ~ cr dk / C: about 2.4 times the radial clearance for this bearing
  CHECK_THAT(scalar(out, "axial_play_min"), WithinRel(60 * um * dk / C, 0.01));
  CHECK_THAT(joints::axial_internal_clearance(0.0, dk, C), WithinAbs(0.0, 1e-20));
  CHECK(out.all().count("play") == 1);  // the axial clearance is not part of the radial play
  CHECK_THAT(scalar(out, "play_max"), WithinRel(120 * um, 1e-12));

  const OutputSet factor = run_spherical({{"bore", number(20 * mm)}, {"axial_play_factor", number(2.5)}});
  CHECK_THAT(scalar(factor, "axial_play_min"), WithinRel(100 * um, 1e-12));
  CHECK_THAT(scalar(factor, "axial_play_max"), WithinRel(205 * um, 1e-12));

  CHECK_THROWS_MATCHES(run_spherical({{"bore", number(bore)}, {"ball_diameter", number(dk)}}), NodeError, names("outer_ring_width"));
  CHECK_THROWS_MATCHES(run_spherical({{"bore", number(bore)}, {"outer_ring_width", number(C)}}), NodeError, names("ball_diameter"));
  CHECK_THROWS_MATCHES(run_spherical({{"bore", number(bore)}, {"axial_play_factor", number(2.5)}, {"ball_diameter", number(dk)},
                                      {"outer_ring_width", number(C)}}),
                       NodeError, names("axial_play_factor", "not both"));
  CHECK_THROWS_MATCHES(
      run_spherical({{"bore", number(bore)}, {"ball_diameter", number(dk)}, {"outer_ring_width", number(60 * mm)}}), NodeError,
      names("outer_ring_width", "smaller than the ball diameter"));
}
