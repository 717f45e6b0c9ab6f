// Every cam law walked to the limits of its parameters, its peaks and positive-acceleration phase
// against an independent evaluation. The reference knows nothing of the searches' insets, runs or
// Chebyshev series: it reads each smooth piece of the law (between the law's knots) at the double
// 8 ulps inside either end (or the piece's middle when it is narrower), at 2000 points between,
// refines every sampled local extremum by golden section on the law's own derivatives, and bisects
// the first fall of h'' through zero. Narrow pieces are the subject: a flank of 0.037 deg read at
// a relative 1e-13 of its width was read at its knots, from the neighbouring pieces (a three-arc
// cam near its largest nose radius reported max_acceleration 0 and accel_angle 0).
//
// A row may also be refused, with a message naming the parameter: a shape the mathematics or the
// range of a double excludes. Rows marked `must_compute` are valid designs that must not be.
#include "test_support.hpp"

#include <mechgraph/domain/cam_law.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

using namespace mechgraph;
using namespace mechgraph::testing;

namespace {

constexpr double deg = std::numbers::pi / 180.0;
constexpr int reference_samples = 2000;  // per smooth piece

// `steps` doubles from `from` toward `to`, or the piece's middle when that is nearer.
double inside(double from, double to, int steps) {
  double x = from;
  for (int i = 0; i < steps; ++i) x = std::nextafter(x, to);
  const double mid = from + 0.5 * (to - from);
  if ((to > from && x > mid) || (to < from && x < mid)) x = mid;
  return x == from ? std::nextafter(from, to) : x;
}

double golden(const std::function<double(double)>& f, double a, double b) {
  const double r = 0.5 * (std::sqrt(5.0) - 1.0);
  double c = b - r * (b - a), d = a + r * (b - a), fc = f(c), fd = f(d);
  for (int i = 0; i < 200 && b - a > 4e-16 * (std::abs(a) + std::abs(b)); ++i) {
    if (fc > fd) {
      b = d, d = c, fd = fc, c = b - r * (b - a), fc = f(c);
    } else {
      a = c, c = d, fc = fd, d = a + r * (b - a), fd = f(d);
    }
  }
  return std::max({fc, fd, f(a), f(b)});
}

struct Sample {
  double x;
  LiftDerivatives d;
  std::size_t piece;
};

// The law read piece by piece, ascending: the one-sided points and reference_samples between.
std::vector<Sample> dense(const CamLaw& law) {
  const std::vector<double> k = law.knots();
  std::vector<Sample> out;
  for (std::size_t p = 0; p + 1 < k.size(); ++p) {
    const double a = inside(k[p], k[p + 1], 8), b = inside(k[p + 1], k[p], 8);
    for (int i = 0; i < reference_samples; ++i) {
      const double x = i == 0 ? a : i + 1 == reference_samples ? b : a + (b - a) * i / (reference_samples - 1);
      if (!out.empty() && out.back().piece == p && !(x > out.back().x)) continue;  // a piece of a few doubles
      out.push_back({x, law.at(x), p});
    }
  }
  return out;
}

// The greatest value of `f` (of the derivatives) over the law: samples, then golden section about
// every sampled local maximum inside its piece.
double reference_max(const CamLaw& law, const std::vector<Sample>& s, const std::function<double(const LiftDerivatives&)>& f) {
  double best = -std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < s.size(); ++i) {
    const double v = f(s[i].d);
    best = std::max(best, v);
    const bool left_ok = i == 0 || s[i - 1].piece != s[i].piece || f(s[i - 1].d) <= v;
    const bool right_ok = i + 1 == s.size() || s[i + 1].piece != s[i].piece || f(s[i + 1].d) <= v;
    if (left_ok && right_ok) {
      const double lo = i > 0 && s[i - 1].piece == s[i].piece ? s[i - 1].x : s[i].x;
      const double hi = i + 1 < s.size() && s[i + 1].piece == s[i].piece ? s[i + 1].x : s[i].x;
      if (hi > lo) best = std::max(best, golden([&](double x) { return f(law.at(x)); }, lo, hi));
    }
  }
  return best;
}

// The positive-acceleration phase: from the start of lift to the first fall of h'' through zero
// after it was positive (exact zeros skipped); at a knot where h'' jumps across zero, the knot.
double reference_phase(const CamLaw& law, const std::vector<Sample>& s) {
  const std::vector<double> k = law.knots();
  int last_sign = 0;
  const Sample* last = nullptr;
  for (const Sample& c : s) {
    const int sign = c.d.acceleration > 0.0 ? 1 : c.d.acceleration < 0.0 ? -1 : 0;
    if (sign == 0) continue;
    if (last_sign > 0 && sign < 0) {
      if (last->piece != c.piece) return k[c.piece] - law.event_begin();
      double lo = last->x, hi = c.x;
      for (int i = 0; i < 200; ++i) {
        const double m = 0.5 * (lo + hi);
        if (!(m > lo && m < hi)) break;
        (law.at(m).acceleration > 0.0 ? lo : hi) = m;
      }
      return 0.5 * (lo + hi) - law.event_begin();
    }
    last_sign = sign;
    last = &c;
  }
  return 0.0;
}

struct Row {
  std::string type;
  std::string params;      // the node's parameters
  std::string parameter;   // the one walked to its limit (a refusal must name it)
  bool must_compute = false;
};

std::string number(double v) {
  char text[40];
  std::snprintf(text, sizeof text, "%.17g", v);
  return text;
}

std::vector<Row> rows() {
  std::vector<Row> out;
  // Three-arc, flat and roller: the nose radius up to its limit r2_max = r0 - h cos(phi_p) / (1 - cos(phi_p))
  // = 9 mm here (the flank narrows to nothing and its radius grows without bound), and down to 0.
  const std::string arc = "max_lift: 9 mm, action_angle: 120 deg, base_radius: 18 mm";
  for (const char* follower : {"", ", follower: roller, roller_radius: 10 mm"}) {
    for (double d : {1e-1, 1e-3, 1.0 / 900.0, 1e-4, 1e-5, 1e-6, 1e-8, 1e-10, 1e-12, 1e-14, 1e-15})
      out.push_back({"cam.three_arc", arc + ", nose_radius: " + number(9.0 * (1.0 - d)) + " mm" + follower, "nose_radius",
                     d >= 1e-6});
    for (double r2 : {1.0, 1e-3, 1e-6, 1e-9})
      out.push_back({"cam.three_arc", arc + ", nose_radius: " + number(r2) + " mm" + follower, "nose_radius", false});
    for (double a : {1.0, 1e-2, 1e-4, 1e-6, 1e-9, 59.0, 59.999})
      out.push_back({"cam.three_arc", arc + ", accel_angle: " + number(a) + " deg" + follower, "accel_angle", false});
  }
  // Kurz: the positive phase towards 0 and towards half the action angle; the quarter sine's share
  // of it towards 0 and 1.
  const std::string kurz = "max_lift: 9 mm, action_angle: 120 deg, base_radius: 40 mm";
  for (double f : {1e-1, 1e-2, 1e-3, 1e-4, 1e-6, 1e-9, 1.0 - 1e-1, 1.0 - 1e-3, 1.0 - 1e-6, 1.0 - 1e-9})
    out.push_back({"cam.kurz", kurz + ", accel_angle: " + number(60.0 * f) + " deg", "accel_angle", f >= 1e-3 && f <= 1.0 - 1e-3});
  for (double s : {0.5, 1e-2, 1e-4, 1e-6, 1e-9, 1e-12, 1e-15, 1.0 - 1e-2, 1.0 - 1e-4, 1.0 - 1e-6, 1.0 - 1e-9, 1.0 - 1e-12})
    out.push_back({"cam.kurz", kurz + ", accel_angle: 20 deg, rise_split: " + number(s), "rise_split", s >= 1e-6 && s <= 1.0 - 1e-6});
  // Polydyne and the standard laws over the whole range of the action angle.
  for (const char* type : {"cam.polydyne", "cam.cycloidal", "cam.harmonic", "cam.poly345", "cam.poly4567",
                           "cam.modified_trapezoid", "cam.modified_sine"})
    for (double angle : {0.1, 1.0, 359.9})
      out.push_back({type, "max_lift: 9 mm, base_radius: 40 mm, action_angle: " + number(angle) + " deg", "action_angle", true});
  // Ramps down to the narrowest.
  for (const char* ramp : {"constant_velocity", "cosine"})
    for (double length : {1.0, 1e-2, 1e-4, 1e-6, 1e-9, 1e-12})
      // The ramp's height shrinks with its length (its end velocity, carried into the main lift, stays 0.05 mm/deg).
      out.push_back({"cam.cycloidal", std::string("max_lift: 9 mm, base_radius: 40 mm, action_angle: 120 deg, ramp: ") + ramp +
                                          ", ramp_height: " + number(0.05 * length) + " mm, ramp_length: " + number(length) + " deg",
                     "ramp_length", length >= 1e-6});
  // A program's dwell at full lift, and a rise, down to the narrowest.
  for (double dwell : {10.0, 1e-2, 1e-5, 1e-8, 1e-11, 1e-13})
    out.push_back({"cam.program",
                   "base_radius: 40 mm, segments: [{type: rise, angle: 60 deg, lift: 9 mm, law: modified_trapezoid}, "
                   "{type: dwell, angle: " + number(dwell) + " deg}, {type: return, angle: 60 deg, lift: 9 mm, law: harmonic}]",
                   "segments", dwell >= 1e-8});
  for (double rise : {1.0, 1e-3, 1e-6})
    out.push_back({"cam.program",
                   "base_radius: 40 mm, segments: [{type: rise, angle: " + number(rise) +
                       " deg, lift: 1 mm, law: modified_trapezoid}, {type: return, angle: 60 deg, lift: 1 mm, law: harmonic}]",
                   "segments", true});
  return out;
}

}  // namespace

TEST_CASE("stability: every cam law at the limits of its parameters, peaks and phase against dense evaluation",
          "[stability][cams][limits]") {
  int computed = 0, refused = 0;
  for (const Row& row : rows()) {
    if (!project_registry().find(row.type)) continue;
    INFO(row.type << " { " << row.params << " }");
    const std::string yaml = "nodes:\n  c: { type: " + row.type + ", params: { " + row.params +
                             " } }\noutputs: [c.law, c.max_velocity, c.max_acceleration, c.min_acceleration, c.accel_angle]\n";
    RunResult r;
    try {
      r = run_yaml(yaml, project_registry());
    } catch (const std::exception& e) {
      INFO("refused: " << e.what());
      CHECK(!row.must_compute);
      CHECK(std::string(e.what()).find(row.parameter) != std::string::npos);
      ++refused;
      continue;
    }
    ++computed;
    const auto law = std::dynamic_pointer_cast<const CamLaw>(output(r, "c.law").as_handle());
    REQUIRE(law);
    const std::vector<Sample> s = dense(*law);
    const double max_v = std::max(reference_max(*law, s, [](const LiftDerivatives& d) { return d.velocity; }),
                                  reference_max(*law, s, [](const LiftDerivatives& d) { return -d.velocity; }));
    const double max_a = reference_max(*law, s, [](const LiftDerivatives& d) { return d.acceleration; });
    const double min_a = -reference_max(*law, s, [](const LiftDerivatives& d) { return -d.acceleration; });
    const double a_scale = std::max(std::abs(max_a), std::abs(min_a));
    // A one-sided value is read some ulps inside its piece (8 here, 4 or more in the searches): the
    // two readings may differ by the slope times those ulps, which on a piece of a few hundred ulps
    // is more than 1e-9 of the value. Allowed: 16 ulps of the angle times the next derivative.
    const double max_j = std::max(reference_max(*law, s, [](const LiftDerivatives& d) { return d.jerk; }),
                                  reference_max(*law, s, [](const LiftDerivatives& d) { return -d.jerk; }));
    const double ulps = 16.0 * std::numeric_limits<double>::epsilon() * std::max(-law->event_begin(), law->event_end());
    CHECK_THAT(scalar_output(r, "c.max_velocity"), Catch::Matchers::WithinAbs(max_v, 1e-9 * max_v + ulps * a_scale));
    CHECK_THAT(scalar_output(r, "c.max_acceleration"), Catch::Matchers::WithinAbs(max_a, 1e-9 * a_scale + ulps * max_j));
    CHECK_THAT(scalar_output(r, "c.min_acceleration"), Catch::Matchers::WithinAbs(min_a, 1e-9 * a_scale + ulps * max_j));
    const double half = 0.5 * (law->event_end() - law->event_begin());
    CHECK_THAT(scalar_output(r, "c.accel_angle"), Catch::Matchers::WithinAbs(reference_phase(*law, s), 1e-12 * half + 1e-18));
  }
  INFO(computed << " rows computed, " << refused << " refused");
  CHECK(computed > 100);
}

TEST_CASE("stability: a three-arc cam near its largest nose radius keeps its narrow flank (closed form)",
          "[stability][cams][limits]") {
  // Flat tappet: the flank's acceleration is e cos x, largest at the start of lift (e = r1 - r0),
  // the nose's -a cos t, least at the nose (a = r0 + h - r2); the positive phase is the flank angle
  // phi_p - atan2(e sin phi_p, a + e cos phi_p) (docs/methods/valvetrain.md, the three-arc cam).
  // At 8.99 mm the flank is 0.037 deg wide and e = 24.3 m: the old searches read it from its
  // neighbours and gave max_acceleration 0 and accel_angle 0.
  for (double r2_mm : {8.9, 8.99, 8.999, 8.99999, 8.9999999}) {
    INFO("nose_radius " << r2_mm << " mm");
    const RunResult r = run_yaml("nodes:\n  c: { type: cam.three_arc, params: { max_lift: 9 mm, action_angle: 120 deg, "
                                 "base_radius: 18 mm, nose_radius: " + number(r2_mm) +
                                     " mm } }\noutputs: [c.max_acceleration, c.min_acceleration, c.accel_angle, c.flank_radius]\n",
                                 project_registry());
    const double h = 9e-3, r0 = 18e-3, r2 = r2_mm * 1e-3, phi_p = 60.0 * deg;
    const double a = r0 + h - r2, e = scalar_output(r, "c.flank_radius") - r0;
    CHECK_THAT(scalar_output(r, "c.max_acceleration"), Catch::Matchers::WithinRel(e, 1e-12));
    CHECK_THAT(scalar_output(r, "c.min_acceleration"), Catch::Matchers::WithinRel(-a, 1e-12));
    const double flank = phi_p - std::atan2(e * std::sin(phi_p), a + e * std::cos(phi_p));
    CHECK_THAT(scalar_output(r, "c.accel_angle"), Catch::Matchers::WithinRel(flank, 1e-6));
  }
}
