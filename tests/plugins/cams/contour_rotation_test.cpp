// cam.contour turned the way it says: the contour points the node outputs are rotated rigidly by
// the cam angle theta about the cam centre (ccw: +theta, cw: -theta, seen from the front), the
// follower stands on the fixed axis +y (a roller's axis offset by +e for ccw, -e for cw: the
// offset's side per docs/methods/valvetrain.md, "The cam contour"), and the lift it sees is
// recovered from the rotated polygon alone and compared with the law's h(theta). Symmetric and
// asymmetric lobes (an asymmetric one shows a lift run backwards), both directions, flat face,
// roller and offset roller (both signs).
#include "cam_test_support.hpp"
#include "contour.hpp"
#include "program_law.hpp"
#include "rise_law.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

namespace mechgraph::cams {
namespace {

constexpr double pi = std::numbers::pi;
constexpr double deg = pi / 180.0;


OutputSet cut(std::shared_ptr<const CamLaw> law, const std::map<std::string, ParamValue>& given) {
  InputSet in;
  in.add("cam", Value::handle(std::move(law)));
  OutputSet out;
  mechgraph::testing::RecordingContext ctx;
  testing::contour_type().evaluate(mechgraph::testing::defaults_of(testing::contour_type().info(), given), in, out, ctx);
  return out;
}

// The largest height y of a circle of radius r centred on the vertical line x = c that touches the
// segment a-b from above: max over the segment of y(t) + sqrt(r^2 - (x(t) - c)^2), a concave
// function of t on the stretch where |x(t) - c| <= r (golden-section search there).
double circle_on_segment(double ax, double ay, double bx, double by, double c, double r) {
  const double dx = bx - ax, dy = by - ay;
  double lo = 0.0, hi = 1.0;
  if (dx != 0.0) {
    double t1 = (c - r - ax) / dx, t2 = (c + r - ax) / dx;
    if (t1 > t2) std::swap(t1, t2);
    lo = std::max(lo, t1);
    hi = std::min(hi, t2);
  } else if (std::abs(ax - c) > r) {
    return -1e300;
  }
  if (lo > hi) return -1e300;
  auto g = [&](double t) {
    const double x = ax + t * dx - c;
    return ay + t * dy + std::sqrt(std::max(0.0, r * r - x * x));
  };
  const double k = (std::sqrt(5.0) - 1.0) / 2.0;
  double a = lo, b = hi;
  for (int i = 0; i < 80 && b - a > 1e-15; ++i) {
    const double m1 = b - k * (b - a), m2 = a + k * (b - a);
    if (g(m1) < g(m2)) a = m1;
    else b = m2;
  }
  return std::max({g(lo), g(hi), g(0.5 * (a + b))});
}

struct Case {
  std::string name;
  std::shared_ptr<const CamLaw> law;
  bool roller = false;
  double rr = 0.0, e = 0.0;
};

void check_turned(const Case& k, const std::string& rotation) {
  const double chord = 1e-6;
  std::map<std::string, ParamValue> given{{"rotation", ParamValue::of_choice(rotation)},
                                          {"chord_error", ParamValue::of_number(chord)}};
  if (k.roller) {
    given["follower"] = ParamValue::of_choice("roller");
    given["roller_radius"] = ParamValue::of_number(k.rr);
    given["offset"] = ParamValue::of_number(k.e);
  } else {
    given["follower"] = ParamValue::of_choice("flat");
  }
  const OutputSet out = cut(k.law, given);
  const Table& c = out.all().at("contour").as_table();
  const auto& x = c.find("x")->values;
  const auto& y = c.find("y")->values;
  const double sigma = rotation == "ccw" ? 1.0 : -1.0;
  const double r0 = k.law->base_radius();
  const double s0 = std::sqrt((r0 + k.rr) * (r0 + k.rr) - k.e * k.e);
  // Tolerance: every point lies on the contour and the contour strays from the chords by at most
  // chord_error (checked at midpoints and quarters), so the polygon's support function is low by
  // at most chord_error; for the roller the circle drops along the axis by at most
  // chord_error / cos(alpha) (alpha below 35 deg here: 1.23 chord_error). 2 chord_error covers both.
  const double tol = 2.0 * chord;
  const double begin = k.law->event_begin(), end = k.law->event_end();
  std::vector<double> q(2 * x.size());
  double worst = 0.0;
  for (double theta = begin - 10 * deg; theta <= end + 10 * deg; theta += 0.5 * deg) {
    // Rotate rigidly by sigma theta about the cam centre.
    const double cs = std::cos(sigma * theta), sn = std::sin(sigma * theta);
    double lift = -1e300;
    if (!k.roller) {
      // Flat face perpendicular to +y: the support function of the turned polygon along +y.
      for (std::size_t i = 0; i < x.size(); ++i) lift = std::max(lift, sn * x[i] + cs * y[i]);
      lift -= r0;
    } else {
      for (std::size_t i = 0; i < x.size(); ++i) {
        q[2 * i] = cs * x[i] - sn * y[i];
        q[2 * i + 1] = sn * x[i] + cs * y[i];
      }
      const double axis = sigma * k.e;
      for (std::size_t i = 0; i < x.size(); ++i) {
        const std::size_t j = (i + 1) % x.size();
        lift = std::max(lift, circle_on_segment(q[2 * i], q[2 * i + 1], q[2 * j], q[2 * j + 1], axis, k.rr));
      }
      lift -= s0;
    }
    const double expected = k.law->at(theta).lift;
    worst = std::max(worst, std::abs(lift - expected));
    INFO(k.name << ", rotation " << rotation << ", cam angle " << theta / deg << " deg");
    CHECK_THAT(lift, Catch::Matchers::WithinAbs(expected, tol) || Catch::Matchers::WithinRel(expected, 1e-9));
  }
  INFO(k.name << ", rotation " << rotation);
  CHECK(worst <= tol);
}

std::shared_ptr<const CamLaw> asymmetric() {
  // 40 deg rise, 100 deg return, 4 mm (cam.program), base radius 60 mm.
  return std::make_shared<const ProgramLaw>(
      std::vector<CamSegment>{{CamSegment::Kind::rise, 40 * deg, 4e-3, RiseShape::cycloidal},
                              {CamSegment::Kind::ret, 100 * deg, 4e-3, RiseShape::cycloidal}},
      60e-3);
}

std::shared_ptr<const CamLaw> symmetric() {
  return std::make_shared<const SymmetricRiseReturnLaw>(RiseShape::cycloidal, 8e-3, 130 * deg, 40e-3, 0.0);
}

TEST_CASE("the contour turned in its stated direction under the follower gives the law's lift", "[contour][rotation]") {
  const std::vector<Case> cases = {
      {"symmetric, flat", symmetric()},
      {"symmetric, roller", symmetric(), true, 10e-3, 0.0},
      {"symmetric, roller offset +4 mm", symmetric(), true, 10e-3, 4e-3},
      {"symmetric, roller offset -4 mm", symmetric(), true, 10e-3, -4e-3},
      {"asymmetric, flat", asymmetric()},
      {"asymmetric, roller", asymmetric(), true, 10e-3, 0.0},
      {"asymmetric, roller offset +4 mm", asymmetric(), true, 10e-3, 4e-3},
      {"asymmetric, roller offset -4 mm", asymmetric(), true, 10e-3, -4e-3},
  };
  for (const Case& k : cases)
    for (const char* rotation : {"ccw", "cw"}) {
      DYNAMIC_SECTION(k.name << ", " << rotation) { check_turned(k, rotation); }
    }
}

}  // namespace
}  // namespace mechgraph::cams
