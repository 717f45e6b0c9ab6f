// cam.kurz and the generic ShocklessLaw: nose conditions, shocklessness, continuity at the
// junctions, the default rise_split (jerk continuity, or the minimax fallback), exact derivatives
// against central differences and quadrature, and the accel_angle the summary finds.
#include "cam_test_support.hpp"

#include <catch2/catch.hpp>

#include "kurz.hpp"
#include "registration.hpp"
#include "shockless.hpp"

#include <boost/math/quadrature/gauss_kronrod.hpp>

#include <cmath>
#include <map>
#include <numbers>
#include <optional>
#include <string>
#include <thread>
#include <vector>

namespace {

using namespace mechgraph;
using namespace mechgraph::cams;

constexpr double pi = std::numbers::pi;
constexpr double deg = pi / 180.0;
constexpr double mm = 1e-3;


OutputSet run_kurz(const std::map<std::string, ParamValue>& given) { return mechgraph::cams::testing::run_cam("cam.kurz", given); }

const CamBasics kBasics{9 * mm, 130 * deg, 17 * mm};

constexpr double kSide = 1e-10;  // offset of the one-sided values at a breakpoint

// One-sided values at a breakpoint b (phi), from the left and from the right.
std::pair<LiftDerivatives, LiftDerivatives> sides(const CamLaw& law, double b) {
  return {law.at(b - kSide), law.at(b + kSide)};
}

// Scale of each derivative for margins: h_max / phi_p^k.
double scale(const CamLaw& law, int k) { return law.max_lift() / std::pow(law.event_end(), k); }

// Margin for comparing one-sided values of a continuous quantity whose derivative is `slope`:
// they differ by about 2 kSide |slope|.
double side_margin(double slope_left, double slope_right, double floor) {
  return 4.0 * kSide * std::max(std::abs(slope_left), std::abs(slope_right)) + floor;
}

void check_derivatives(const CamLaw& law) {
  const double step = 1e-5;
  int checked = 0;
  for (int i = 1; i < 80; ++i) {
    const double phi = law.event_begin() + (law.event_end() - law.event_begin()) * i / 80.0 + 1.3e-3;
    if (phi + step >= law.event_end()) continue;
    bool near = false;
    for (double b : law.breakpoints()) near = near || std::abs(phi - b) < 3.0 * step;
    if (near) continue;
    const LiftDerivatives m = law.at(phi - step), c = law.at(phi), p = law.at(phi + step);
    CHECK(c.velocity == Approx((p.lift - m.lift) / (2 * step)).epsilon(1e-7).margin(1e-9 * scale(law, 1)));
    CHECK(c.acceleration == Approx((p.velocity - m.velocity) / (2 * step)).epsilon(1e-7).margin(1e-9 * scale(law, 2)));
    CHECK(c.jerk == Approx((p.acceleration - m.acceleration) / (2 * step)).epsilon(1e-6).margin(1e-8 * scale(law, 3)));
    ++checked;
  }
  CHECK(checked > 60);
}

void check_nose_and_start(const ShocklessLaw& law) {
  const LiftDerivatives nose = law.at(0.0);
  CHECK(nose.lift == Approx(law.max_lift()).epsilon(1e-14).margin(0));
  CHECK(nose.velocity == Approx(0.0).margin(1e-15 * scale(law, 1)));
  CHECK(nose.acceleration == Approx(law.negative_amplitude()).epsilon(1e-14).margin(0));
  // Shockless: the acceleration leaves zero continuously at the start of lift (and the end).
  for (double phi : {law.event_begin() + 1e-12, law.event_end() - 1e-12}) {
    const LiftDerivatives d = law.at(phi);
    CHECK(std::abs(d.acceleration) < 1e-9 * scale(law, 2));
    CHECK(std::abs(d.velocity) < 1e-15 * scale(law, 1));
    CHECK(std::abs(d.lift) < 1e-20);
  }
  // h, h', h'' continuous at every junction, both sides of the nose.
  for (double b : law.breakpoints()) {
    const auto [l, r] = sides(law, b);
    INFO("breakpoint " << b / deg << " deg");
    CHECK(l.lift == Approx(r.lift).epsilon(1e-12).margin(side_margin(l.velocity, r.velocity, 1e-15 * scale(law, 0))));
    CHECK(l.velocity ==
          Approx(r.velocity).epsilon(1e-12).margin(side_margin(l.acceleration, r.acceleration, 1e-15 * scale(law, 1))));
    CHECK(l.acceleration == Approx(r.acceleration).epsilon(1e-12).margin(side_margin(l.jerk, r.jerk, 1e-13 * scale(law, 2))));
  }
}

}  // namespace

TEST_CASE("kurz: nose conditions, shocklessness and continuity", "[cams][kurz]") {
  for (double accel : {12.0, 18.0, 25.0, 34.0, 45.0}) {
    for (std::optional<double> split : {std::optional<double>{}, std::optional<double>{0.3}, std::optional<double>{0.8}}) {
      INFO("accel_angle " << accel << " deg, split " << (split ? *split : -1.0));
      const auto law = make_kurz_law(kBasics, accel * deg, split);
      check_nose_and_start(*law);
      CHECK(law->breakpoints().size() == 4);  // sine/cosine and positive/negative junctions, both sides
      // Zero velocity at the nose, independently: A- = -3 A+ phi_y / (pi phi_3).
      const double phi_y = accel * deg, phi_3 = 65 * deg - phi_y;
      CHECK(law->negative_amplitude() ==
            Approx(-3.0 * law->positive_amplitude() * phi_y / (pi * phi_3)).epsilon(1e-13).margin(0));
      // The positive phase ends at accel_angle: h'' > 0 before, < 0 after.
      CHECK(law->at(-65 * deg + phi_y - 1e-6).acceleration > 0.0);
      CHECK(law->at(-65 * deg + phi_y + 1e-6).acceleration < 0.0);
    }
  }
}

TEST_CASE("kurz: lift and velocity are the integrals of the acceleration", "[cams][kurz]") {
  const auto law = make_kurz_law(kBasics, 18 * deg, std::nullopt);
  // Quadrature of h'' (and h') piece by piece from the start of lift, against the closed forms.
  std::vector<double> knots{law->event_begin()};
  for (double b : law->breakpoints())
    if (b < 0.0) knots.push_back(b);  // the rising half
  knots.push_back(0.0);
  double v = 0.0, h = 0.0;
  for (std::size_t k = 0; k + 1 < knots.size(); ++k) {
    const double a = knots[k], b = knots[k + 1];
    h += boost::math::quadrature::gauss_kronrod<double, 61>::integrate(
        [&](double x) { return law->at(x).velocity; }, a, b, 15, 1e-14);
    v += boost::math::quadrature::gauss_kronrod<double, 61>::integrate(
        [&](double x) { return law->at(x).acceleration; }, a, b, 15, 1e-14);
    const LiftDerivatives at_b = law->at(b - 1e-14);
    CHECK(v == Approx(at_b.velocity).epsilon(1e-11).margin(1e-13 * scale(*law, 1)));
    CHECK(h == Approx(at_b.lift).epsilon(1e-11).margin(1e-13 * scale(*law, 0)));
  }
  CHECK(h == Approx(kBasics.max_lift).epsilon(1e-12).margin(0));
}

TEST_CASE("kurz: default rise_split makes the jerk continuous when it can", "[cams][kurz]") {
  // phi_3 = 31 deg < 1.103 phi_y = 37.5 deg: attainable.
  const double phi_y = 34 * deg, phi_p = 65 * deg;
  const double split = kurz_default_split(phi_y, phi_p);
  CHECK(split == Approx(1.0 - pi * pi * std::pow(31.0 / 34.0, 2) / 12.0).epsilon(1e-15).margin(0));
  CHECK(split > 0.0);
  const auto law = make_kurz_law(kBasics, phi_y, std::nullopt);
  for (double b : {-(phi_p - phi_y), phi_p - phi_y}) {
    const auto [l, r] = sides(*law, b);
    CHECK(l.jerk == Approx(r.jerk).epsilon(1e-7).margin(1e-8 * scale(*law, 3)));
  }
  // With another split the jerk jumps there.
  const auto other = make_kurz_law(kBasics, phi_y, 0.6);
  const auto [l, r] = sides(*other, -(phi_p - phi_y));
  CHECK(std::abs(l.jerk - r.jerk) > 0.1 * std::abs(l.jerk));
  // The jerk is continuous across the nose (the parabola's vertex) and at the sine/cosine junction.
  const auto [nl, nr] = sides(*law, 0.0);
  CHECK(nl.jerk == Approx(nr.jerk).margin(1e-8 * scale(*law, 3)));
  const auto [sl, sr] = sides(*law, -phi_p + split * phi_y);
  CHECK(sl.jerk == Approx(sr.jerk).margin(1e-7 * scale(*law, 3)));
}

TEST_CASE("kurz: default rise_split when jerk continuity is out of reach", "[cams][kurz]") {
  // phi_3 = 47 deg > 1.103 * 18 deg: no split makes the junction jerk continuous; the default
  // equalises the two jerk jumps (start of lift and positive/negative junction).
  const double phi_y = 18 * deg, phi_p = 65 * deg;
  CHECK(kurz_jerk_continuous_split(phi_y, phi_p) <= 0.0);
  const double split = kurz_default_split(phi_y, phi_p);
  CHECK(split == kurz_minimax_split(phi_y, phi_p));
  CHECK(split > 0.5);
  CHECK(split < 0.62);
  const auto law = make_kurz_law(kBasics, phi_y, std::nullopt);
  const double start_jump = std::abs(law->at(-phi_p + 1e-12).jerk);
  const auto [l, r] = sides(*law, -(phi_p - phi_y));
  const double junction_jump = std::abs(l.jerk - r.jerk);
  CHECK(start_jump == Approx(junction_jump).epsilon(1e-7).margin(0));
  // ... and it is the minimum of the larger jump: nearby splits do worse.
  for (double s : {split - 0.02, split + 0.02}) {
    const auto o = make_kurz_law(kBasics, phi_y, s);
    const auto [ol, orr] = sides(*o, -(phi_p - phi_y));
    const double worst = std::max(std::abs(o->at(-phi_p + 1e-12).jerk), std::abs(ol.jerk - orr.jerk));
    CHECK(worst > start_jump);
  }
}

TEST_CASE("kurz: exact derivatives match central differences", "[cams][kurz]") {
  check_derivatives(*make_kurz_law(kBasics, 18 * deg, std::nullopt));
  check_derivatives(*make_kurz_law(kBasics, 34 * deg, std::nullopt));
  check_derivatives(*make_kurz_law({6 * mm, 100 * deg, 14 * mm}, 10 * deg, 0.25));
}

TEST_CASE("kurz: another member of the shockless family uses the same code", "[cams][kurz]") {
  // Negative phase a quarter sine rising to its peak at the nose (zero slope there too).
  const double phi_p = 60 * deg;
  std::vector<ShapeSegment> positive{{std::make_shared<const QuarterSineRise>(), 10 * deg},
                                     {std::make_shared<const QuarterCosineFall>(), 12 * deg}};
  std::vector<ShapeSegment> negative{{std::make_shared<const QuarterSineRise>(), phi_p - 22 * deg}};
  const ShocklessLaw law(8 * mm, 2 * phi_p, 15 * mm, positive, negative);
  check_nose_and_start(law);
  check_derivatives(law);
  // Velocity condition in closed form: A+ (2/pi) 22 deg = -A- (2/pi) 38 deg.
  CHECK(law.negative_amplitude() == Approx(-law.positive_amplitude() * 22.0 / 38.0).epsilon(1e-13).margin(0));
  // Shapes that do not join are a programming error.
  std::vector<ShapeSegment> broken{{std::make_shared<const QuarterCosineFall>(), 22 * deg}};
  CHECK_THROWS_AS(ShocklessLaw(8 * mm, 2 * phi_p, 15 * mm, broken, negative), std::invalid_argument);
}

TEST_CASE("kurz node: accel_angle reproduced, outputs, errors", "[cams][kurz]") {
  std::map<std::string, ParamValue> p{{"max_lift", ParamValue::of_number(9 * mm)},
                                      {"action_angle", ParamValue::of_number(130 * deg)},
                                      {"base_radius", ParamValue::of_number(17 * mm)},
                                      {"accel_angle", ParamValue::of_number(18 * deg)}};
  const OutputSet out = run_kurz(p);
  CHECK(out.all().at("accel_angle").as_scalar() == Approx(18 * deg).epsilon(1e-9).margin(1e-12));
  CHECK(out.all().at("rise_split").as_scalar() == kurz_default_split(18 * deg, 65 * deg));
  const auto law = std::dynamic_pointer_cast<const ShocklessLaw>(out.all().at("law").as_handle());
  REQUIRE(law);
  CHECK(out.all().at("max_acceleration").as_scalar() == Approx(law->positive_amplitude()).epsilon(1e-9).margin(0));
  CHECK(out.all().at("min_acceleration").as_scalar() == Approx(law->negative_amplitude()).epsilon(1e-9).margin(0));
  CHECK(out.all().at("min_curvature_radius").as_scalar() > 0.0);

  p["rise_split"] = ParamValue::of_number(0.4);
  CHECK(run_kurz(p).all().at("rise_split").as_scalar() == 0.4);

  p["accel_angle"] = ParamValue::of_number(70 * deg);
  try {
    run_kurz(p);
    FAIL("expected a NodeError");
  } catch (const NodeError& e) {
    CHECK(e.parameter() == "accel_angle");
    CHECK_THAT(e.what(), Catch::Contains("half the action angle (65 deg)"));
  }
  try {
    make_kurz_law(kBasics, 18 * deg, 1.0);
    FAIL("expected a NodeError");
  } catch (const NodeError& e) {
    CHECK(e.parameter() == "rise_split");
  }
}

TEST_CASE("shockless shapes: the kept end values and moments equal the shape's functions, made once across threads", "[cams][kurz]") {
  // AccelShape::ends() is computed on first use and shared by every law of the shape (a sweep
  // builds one per case on many threads): the same numbers as the functions give, bit for bit.
  const std::vector<std::shared_ptr<const AccelShape>> shapes{std::make_shared<const QuarterSineRise>(),
                                                              std::make_shared<const QuarterCosineFall>(),
                                                              std::make_shared<const ParabolaToVertex>()};
  for (const auto& shape : shapes) {
    std::vector<const ShapeEnds*> seen(8, nullptr);
    std::vector<std::thread> threads;
    for (std::size_t t = 0; t < seen.size(); ++t) threads.emplace_back([&, t] { seen[t] = &shape->ends(); });
    for (std::thread& t : threads) t.join();
    for (const ShapeEnds* e : seen) {
      REQUIRE(e == seen.front());
      CHECK(e->value0 == shape->value(0.0));
      CHECK(e->value1 == shape->value(1.0));
      CHECK(e->slope1 == shape->slope(1.0));
      CHECK(e->integral1 == shape->integral(1.0));
      CHECK(e->integral2 == shape->integral2(1.0));
      double i3 = 0.0, j1 = 0.0, j2 = 0.0;
      REQUIRE(e->has_moments == shape->moments(1.0, i3, j1, j2));
      CHECK(e->i3 == i3);
      CHECK(e->j1 == j1);
      CHECK(e->j2 == j2);
      const ShapeValues all = shape->all(0.3), one_by_one{shape->value(0.3), shape->slope(0.3), shape->integral(0.3), shape->integral2(0.3)};
      CHECK(all.value == one_by_one.value);
      CHECK(all.slope == one_by_one.slope);
    }
  }
}
