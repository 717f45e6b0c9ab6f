// CamLawRuns (mechgraph/domain/cam_law_runs.hpp): extrema and crossings from a law's declared
// monotone runs, against closed forms (also past the 32 points peaks() keeps on the stack); the cam
// summary through them equals the generic search's; the conformance kit catches a law whose
// declared runs are wrong.
#include <mechgraph/domain/cam_geometry.hpp>
#include <mechgraph/domain/cam_law_runs.hpp>
#include <mechgraph/numerics/piecewise.hpp>
#include <mechgraph/testing/cam_law_conformance.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>
#include <vector>

using namespace mechgraph;
using Catch::Matchers::WithinAbs;
using Catch::Matchers::WithinRel;

namespace {

constexpr double deg = std::numbers::pi / 180.0;

// h = H s^3, s = 1 - x^2, x = (phi - c) / w on (c - w, c + w) (an asymmetric event when c != 0):
//   h'   = -6 H x s^2 / w                   sign change at x = 0
//   h''  = 6 H s (5 x^2 - 1) / w^2          at x = +-1/sqrt(5)
//   h''' = 24 H x (3 - 5 x^2) / w^3         at x = 0, +-sqrt(3/5)
// `declared` says which runs the law gives: 0 none, 1 the true ones, 2 wrong ones (order 2 with
// the nose only, so h'' would be taken as monotone across its peaks).
class Bump final : public CamLaw {
 public:
  Bump(double c, double w, int declared) : c_(c), w_(w), declared_(declared) {}
  double event_begin() const override { return c_ - w_; }
  double event_end() const override { return c_ + w_; }
  std::vector<double> breakpoints() const override { return {}; }
  double max_lift() const override { return H; }
  double base_radius() const override { return 0.04; }
  LiftDerivatives evaluate_in_event(double phi) const override {
    const double x = (phi - c_) / w_, s = 1 - x * x;
    return {H * s * s * s, -6 * H * x * s * s / w_, 6 * H * s * (5 * x * x - 1) / (w_ * w_),
            24 * H * x * (3 - 5 * x * x) / (w_ * w_ * w_)};
  }
  bool monotone_breaks(int order, std::vector<double>& breaks) const override {
    if (declared_ == 0) return false;
    const double a = w_ / std::sqrt(5.0), b = w_ * std::sqrt(0.6);
    if (order == 0) breaks = {c_};
    else if (order == 1) breaks = {c_ - a, c_ + a};
    else breaks = declared_ == 2 ? std::vector<double>{c_} : std::vector<double>{c_ - b, c_, c_ + b};
    return true;
  }
  static constexpr double H = 0.01;

 private:
  double c_, w_;
  int declared_;
};

}  // namespace

TEST_CASE("monotone runs: extrema and crossings against the closed forms", "[sdk][cam_runs]") {
  const double c = 7 * deg, w = 55 * deg;
  const Bump law(c, w, 1);
  const double H = Bump::H;
  long evaluations = 0;
  const auto velocity = CamLawRuns::of(law, 1);
  const auto acceleration = CamLawRuns::of(law, 2);
  const auto lift = CamLawRuns::of(law, 0);
  REQUIRE(velocity);
  REQUIRE(acceleration);
  REQUIRE(lift);
  // h' peaks at x = -+1/sqrt(5): 96 H / (25 sqrt(5) w).
  const double v_peak = 96 * H / (25 * std::sqrt(5.0) * w);
  CHECK_THAT(velocity->maximum(evaluations).value, WithinRel(v_peak, 1e-13));
  CHECK_THAT(velocity->maximum(evaluations).x, WithinAbs(c - w / std::sqrt(5.0), 1e-15));
  CHECK_THAT(velocity->minimum(evaluations).value, WithinRel(-v_peak, 1e-13));
  // h'' peaks at x = +-sqrt(3/5): 4.8 H / w^2; least at the nose: -6 H / w^2.
  CHECK_THAT(acceleration->maximum(evaluations).value, WithinRel(4.8 * H / (w * w), 1e-13));
  CHECK_THAT(acceleration->minimum(evaluations).value, WithinRel(-6 * H / (w * w), 1e-13));
  // Over a part of the event: [c - 0.9 w, c - 0.6 w] holds the peak at x = -sqrt(3/5) = -0.7746.
  CHECK_THAT(acceleration->maximum(c - 0.9 * w, c - 0.6 * w, evaluations).value, WithinRel(4.8 * H / (w * w), 1e-13));
  // An interval inside one run: the extremes are its ends.
  const double x1 = -0.5, x2 = -0.3;
  auto h2 = [&](double x) { const double s = 1 - x * x; return 6 * H * s * (5 * x * x - 1) / (w * w); };
  CHECK_THAT(acceleration->maximum(c + x1 * w, c + x2 * w, evaluations).value, WithinRel(std::max(h2(x1), h2(x2)), 1e-13));
  CHECK_THAT(acceleration->minimum(c + x1 * w, c + x2 * w, evaluations).value, WithinRel(std::min(h2(x1), h2(x2)), 1e-13));
  // Lift crossings of L: s = (L / H)^(1/3), x = -+sqrt(1 - s); rising then falling.
  const double L = 0.0037;
  const auto cross = lift->directed_crossings(L, evaluations);
  REQUIRE(cross.size() == 2);
  const double xs = std::sqrt(1 - std::cbrt(L / H));
  CHECK_THAT(cross[0].first, WithinAbs(c - xs * w, 1e-14));
  CHECK(cross[0].second);
  CHECK_THAT(cross[1].first, WithinAbs(c + xs * w, 1e-14));
  CHECK_FALSE(cross[1].second);
  // h'' through zero: rising at the start? It starts at 0 and is positive just inside: the walk
  // skips the exact zero, so the first crossing is the fall at x = -1/sqrt(5).
  const auto zeros = acceleration->directed_crossings(0.0, evaluations);
  REQUIRE(zeros.size() == 2);
  CHECK_THAT(zeros[0].first, WithinAbs(c - w / std::sqrt(5.0), 1e-14));
  CHECK_FALSE(zeros[0].second);
  CHECK(zeros[1].second);
  CHECK(evaluations < 200);
}

TEST_CASE("monotone runs: the cam summary equals the generic search's", "[sdk][cam_runs]") {
  // w = 80 deg: the contour is convex (rho at the nose r0 + H - 6 H / w^2 = 19 mm).
  for (double c : {0.0, 11 * deg, -23 * deg}) {
    const Bump with(c, 80 * deg, 1), without(c, 80 * deg, 0);
    const CamSummary a = summarize(with, 16), b = summarize(without, 16);
    CHECK_THAT(a.max_velocity, WithinRel(b.max_velocity, 1e-12));
    CHECK_THAT(a.max_acceleration, WithinRel(b.max_acceleration, 1e-12));
    CHECK_THAT(a.min_acceleration, WithinRel(b.min_acceleration, 1e-12));
    CHECK_THAT(a.accel_angle, WithinRel(b.accel_angle, 1e-12));
    CHECK_THAT(a.accel_angle, WithinRel(80 * deg * (1 - 1 / std::sqrt(5.0)), 1e-13));
    CHECK_THAT(a.min_curvature_radius, WithinRel(b.min_curvature_radius, 1e-12));
    // Without the curvature asked for, the flat contour is proven free of undercut instead.
    const CamSummary proven = summarize(with, 16, false);
    CHECK_FALSE(proven.curvature_exact);
    CHECK(proven.min_curvature_radius > 0.0);
  }
  // An undercut one (w = 40 deg: rho = r0 + H - 6 H / w^2 < 0 at the nose) is measured, not proven.
  const CamSummary undercut = summarize(Bump(0.0, 40 * deg, 1), 16, false);
  CHECK(undercut.curvature_exact);
  CHECK_THAT(undercut.min_curvature_radius, WithinRel(0.04 + 0.01 - 6 * 0.01 / std::pow(40 * deg, 2), 1e-12));
}

TEST_CASE("monotone runs: the conformance kit passes true runs and catches false ones", "[sdk][cam_runs]") {
  const testing::Report good = testing::check_cam_law(Bump(5 * deg, 50 * deg, 1), "bump");
  CHECK(good.count(testing::Check::Status::failed) == 0);
  CHECK(good.count(testing::Check::Status::passed) >= 3);
  const testing::Report bad = testing::check_cam_law(Bump(5 * deg, 50 * deg, 2), "lying bump");
  REQUIRE(bad.count(testing::Check::Status::failed) == 1);
  bool named = false;
  for (const testing::Check& ch : bad.checks())
    if (ch.status == testing::Check::Status::failed) named = ch.name == "monotone runs of the acceleration";
  CHECK(named);
}

TEST_CASE("monotone runs: several orders' peaks from one evaluation per point equal each order's own", "[sdk][cam_runs]") {
  const Bump law(3 * deg, 70 * deg, 1);
  const auto velocity = CamLawRuns::of(law, 1);
  const auto acceleration = CamLawRuns::of(law, 2);
  REQUIRE(velocity);
  REQUIRE(acceleration);
  for (const auto& [a, b] : std::vector<std::pair<double, double>>{{-67 * deg, 73 * deg}, {-40 * deg, 10 * deg}, {5 * deg, 6 * deg}}) {
    long shared = 0, alone = 0;
    const auto p = CamLawRuns::peaks({&*velocity, &*acceleration}, a, b, shared);
    REQUIRE(p.size() == 2);
    CHECK(p[0].max.value == velocity->maximum(a, b, alone).value);
    CHECK(p[0].min.value == velocity->minimum(a, b, alone).value);
    CHECK(p[1].max.value == acceleration->maximum(a, b, alone).value);
    CHECK(p[1].min.value == acceleration->minimum(a, b, alone).value);
    CHECK(shared < alone);
  }
}

TEST_CASE("cam summary parts: only what is asked for is computed, the undercut figure always is", "[sdk][cam_runs]") {
  const Bump law(0.0, 80 * deg, 1);
  const CamSummary all = summarize(law, 16);
  const CamSummary none = summarize(law, 16, CamSummaryParts{false, false, false});
  CHECK_FALSE(none.peaks_known);
  CHECK_FALSE(none.phase_known);
  CHECK_FALSE(none.curvature_exact);
  CHECK(none.min_curvature_radius > 0.0);
  CHECK(none.evaluations < all.evaluations);
  const CamSummary peaks_only = summarize(law, 16, CamSummaryParts{true, false, true});
  CHECK(peaks_only.peaks_known);
  CHECK(peaks_only.max_velocity == all.max_velocity);
  CHECK(peaks_only.min_acceleration == all.min_acceleration);
  CHECK(peaks_only.min_curvature_radius == all.min_curvature_radius);
  // A law without runs gets every part from its one interpolation.
  const CamSummary generic = summarize(Bump(0.0, 80 * deg, 0), 16, CamSummaryParts{false, false, false});
  CHECK(generic.peaks_known);
  CHECK(generic.phase_known);
  CHECK(generic.curvature_exact);
}

TEST_CASE("monotone runs: storage reused from law to law gives what of() gives, bit for bit", "[sdk][cam_runs]") {
  // A block path keeps one CamLawRuns per order and assigns each case's law into it; a law that
  // declares no runs between two that do leaves nothing behind (assign says false).
  CamLawRuns reused;
  std::vector<std::pair<double, bool>> crossings;
  const std::vector<Bump> laws{Bump(3 * deg, 70 * deg, 1), Bump(-5 * deg, 40 * deg, 0), Bump(9 * deg, 55 * deg, 1),
                               Bump(0.0, 80 * deg, 2)};
  for (const Bump& law : laws) {
    for (int order = 0; order <= 2; ++order) {
      const auto fresh = CamLawRuns::of(law, order);
      REQUIRE(reused.assign(law, order) == fresh.has_value());
      if (!fresh) continue;
      long a = 0, b = 0;
      CHECK(reused.maximum(a).value == fresh->maximum(b).value);
      CHECK(reused.minimum(a).x == fresh->minimum(b).x);
      const double level = 0.3 * Bump::H * (order == 0 ? 1.0 : 0.0);
      reused.directed_crossings(level, a, crossings);
      CHECK(crossings == fresh->directed_crossings(level, b));
      CamLawRuns::Peaks into[1];
      CamLawRuns::peaks({&reused}, law.event_begin(), law.event_end(), a, into);
      const auto returned = CamLawRuns::peaks({&*fresh}, law.event_begin(), law.event_end(), b);
      CHECK(into[0].max.value == returned[0].max.value);
      CHECK(into[0].min.x == returned[0].min.x);
      CHECK(a == b);  // the same evaluations
    }
  }
  CHECK_FALSE(reused.assign(laws[0], 3));  // no such order
}

namespace {

// m waves of h = A_j (1 - cos t) / 2, t = 2 pi (phi - e0) / P, on (e0, e0 + m P), each wave j with
// its own amplitude A_j (a permutation of H/12 .. H, so each extremum lies in one wave):
//   h'   =  A_j k sin t / 2,  h'' = A_j k^2 cos t / 2,  h''' = -A_j k^3 sin t / 2,  k = 2 pi / P.
// h and h' are continuous where the waves meet (t = 2 pi j: h = h' = 0); h'' jumps there from
// A_{j-1} k^2 / 2 to A_j k^2 / 2 (a breakpoint). Runs: h at t = pi j, h' at t = pi/2 + pi j (24
// cuts for 12 waves), h'' at t = pi j (23 cuts, the jumps among them): more than 32 run ends.
class Waves final : public CamLaw {
 public:
  static constexpr int m = 12;
  static constexpr double H = 8e-3;
  static constexpr double e0 = -150 * deg, P = 300 * deg / m, k = 2 * std::numbers::pi / P;
  explicit Waves(bool declared) : declared_(declared) {}
  static double amplitude(int j) { return H * (1 + (5 * j + 3) % m) / m; }  // 5 is prime to 12: a permutation
  double event_begin() const override { return e0; }
  double event_end() const override { return e0 + m * P; }
  std::vector<double> breakpoints() const override {
    std::vector<double> b;
    for (int j = 1; j < m; ++j) b.push_back(e0 + j * P);
    return b;
  }
  double max_lift() const override { return H; }
  double base_radius() const override { return 0.03; }
  LiftDerivatives evaluate_in_event(double phi) const override {
    const double u = (phi - e0) / P, t = 2 * std::numbers::pi * u;
    const double A = amplitude(std::clamp(static_cast<int>(std::floor(u)), 0, m - 1));
    return {A * (1 - std::cos(t)) / 2, A * k * std::sin(t) / 2, A * k * k * std::cos(t) / 2, -A * k * k * k * std::sin(t) / 2};
  }
  bool monotone_breaks(int order, std::vector<double>& breaks) const override {
    if (!declared_) return false;
    breaks.clear();
    for (int j = order == 1 ? 0 : 1; j < 2 * m; ++j) breaks.push_back(e0 + (order == 1 ? 0.25 * P : 0.0) + 0.5 * j * P);
    return true;
  }

 private:
  bool declared_;
};

}  // namespace

TEST_CASE("monotone runs: one run set alone reads the points, values and count the shared table reads", "[sdk][cam_runs]") {
  // peaks() of one set keeps no table of points (only the last one read); of several, a table
  // shared between them. The same set given twice reads every point once: its count and answer
  // are then the single set's. A run of two ulps (one double inside) gives the same point at both
  // of its ends, read once either way.
  class Ulps final : public CamLaw {
   public:
    double event_begin() const override { return -0.6; }
    double event_end() const override { return 0.6; }
    std::vector<double> breakpoints() const override { return {}; }
    double max_lift() const override { return 0.01; }
    double base_radius() const override { return 0.04; }
    LiftDerivatives evaluate_in_event(double phi) const override { return inner_.evaluate_in_event(phi); }
    bool monotone_breaks(int order, std::vector<double>& breaks) const override {
      if (order != 2) return inner_.monotone_breaks(order, breaks);
      const double c = 0.1, two_ulps = std::nextafter(std::nextafter(c, 1.0), 1.0);
      breaks = {-0.3, c, two_ulps, 0.45};
      return true;
    }

   private:
    Bump inner_{0.0, 0.6, 1};
  };
  const Bump bump(3 * deg, 70 * deg, 1);
  const Ulps ulps;
  for (const CamLaw* law : std::initializer_list<const CamLaw*>{&bump, &ulps}) {
    const auto acceleration = CamLawRuns::of(*law, 2);
    REQUIRE(acceleration);
    const double e0 = law->event_begin(), e1 = law->event_end();
    for (const auto& [a, b] : std::vector<std::pair<double, double>>{{e0, e1}, {e0 + 0.1, e1 - 0.2}, {0.05, 0.2}}) {
      INFO("over [" << a << ", " << b << "] rad");
      long alone = 0, twice = 0;
      const auto one = CamLawRuns::peaks({&*acceleration}, a, b, alone);
      const auto two = CamLawRuns::peaks({&*acceleration, &*acceleration}, a, b, twice);
      REQUIRE(one.size() == 1);
      REQUIRE(two.size() == 2);
      CHECK(alone > 0);
      CHECK(alone == twice);
      for (const CamLawRuns::Peaks& p : two) {
        CHECK(one[0].max.value == p.max.value);
        CHECK(one[0].max.x == p.max.x);
        CHECK(one[0].min.value == p.min.value);
        CHECK(one[0].min.x == p.min.x);
      }
    }
  }
}

TEST_CASE("monotone runs: peaks over more run ends than the stack holds, against the closed form and the generic search",
          "[sdk][cam_runs]") {
  // CamLawRuns::peaks keeps the points it reads in 32 slots on the stack and moves them to the heap
  // beyond: over these intervals the two orders together read 57 to 98 distinct points, each alone 28
  // to 50 (the stack and the heap both).
  const Waves law(true), generic(false);
  const auto velocity = CamLawRuns::of(law, 1);
  const auto acceleration = CamLawRuns::of(law, 2);
  REQUIRE(velocity);
  REQUIRE(acceleration);
  // The declared runs are the law's true ones (the kit samples them densely).
  const testing::Report kit = testing::check_cam_law(law, "waves");
  int runs_checked = 0;
  for (const testing::Check& ch : kit.checks())
    if (ch.name.rfind("monotone runs", 0) == 0) {
      INFO(ch.name << ": " << ch.detail);
      CHECK(ch.status == testing::Check::Status::passed);
      ++runs_checked;
    }
  CHECK(runs_checked == 3);  // lift, velocity, acceleration
  using W = Waves;
  const double v_scale = W::H * W::k / 2, a_scale = W::H * W::k * W::k / 2;
  // The closed form over [a, b] (a and b where no extremum is): the extremes of each wave whose
  // peak lies inside; h'' peaks at the meeting points t = 2 pi j from either side.
  struct Expected {
    double v_max, v_max_at, v_min, v_min_at, a_max, a_min, a_min_at;
    std::vector<double> a_max_at;  // where it is reached (two one-sided values of one amplitude)
  };
  auto closed_form = [&](double a, double b) {
    Expected e{-1e300, 0, 1e300, 0, -1e300, 1e300, 0, {}};
    for (int j = 0; j < W::m; ++j) {
      const double A = W::amplitude(j), at_v_max = W::e0 + (j + 0.25) * W::P, at_v_min = W::e0 + (j + 0.75) * W::P,
                   at_a_min = W::e0 + (j + 0.5) * W::P;
      if (at_v_max > a && at_v_max < b && A * W::k / 2 > e.v_max) e.v_max = A * W::k / 2, e.v_max_at = at_v_max;
      if (at_v_min > a && at_v_min < b && -A * W::k / 2 < e.v_min) e.v_min = -A * W::k / 2, e.v_min_at = at_v_min;
      if (at_a_min > a && at_a_min < b && -A * W::k * W::k / 2 < e.a_min) e.a_min = -A * W::k * W::k / 2, e.a_min_at = at_a_min;
      for (double at : {W::e0 + j * W::P, W::e0 + (j + 1) * W::P}) {
        if (at < a || at > b) continue;
        const double value = A * W::k * W::k / 2;
        if (value > e.a_max) e.a_max = value, e.a_max_at.clear();
        if (value == e.a_max) e.a_max_at.push_back(at);
      }
    }
    return e;
  };
  const double e1 = law.event_end();
  struct Case {
    double a, b;
    long least_points;  // distinct points the two orders read together
  };
  for (const Case& c : {Case{W::e0 + 0.3 * W::P, e1 - 0.4 * W::P, 92}, Case{W::e0 + 5.1 * W::P, e1, 57}, Case{W::e0, e1, 98}}) {
    INFO("over [" << c.a / deg << ", " << c.b / deg << "] deg");
    const Expected e = closed_form(c.a, c.b);
    long together = 0, each = 0;
    const auto p = CamLawRuns::peaks({&*velocity, &*acceleration}, c.a, c.b, together);
    REQUIRE(p.size() == 2);
    CHECK(together >= c.least_points);  // past the 32 on the stack
    // Against the closed form: values to rounding, the places exactly where the runs meet.
    CHECK_THAT(p[0].max.value, WithinRel(e.v_max, 1e-13) || WithinAbs(e.v_max, 1e-15 * v_scale));
    CHECK_THAT(p[0].min.value, WithinRel(e.v_min, 1e-13) || WithinAbs(e.v_min, 1e-15 * v_scale));
    CHECK_THAT(p[1].max.value, WithinRel(e.a_max, 1e-13) || WithinAbs(e.a_max, 1e-15 * a_scale));
    CHECK_THAT(p[1].min.value, WithinRel(e.a_min, 1e-13) || WithinAbs(e.a_min, 1e-15 * a_scale));
    CHECK_THAT(p[0].max.x, WithinAbs(e.v_max_at, 1e-13));
    CHECK_THAT(p[0].min.x, WithinAbs(e.v_min_at, 1e-13));
    CHECK_THAT(p[1].min.x, WithinAbs(e.a_min_at, 1e-13));
    bool a_max_at_a_peak = false;
    for (double at : e.a_max_at) a_max_at_a_peak = a_max_at_a_peak || std::abs(p[1].max.x - at) <= 1e-13;
    INFO("h'' greatest at " << p[1].max.x / deg << " deg");
    CHECK(a_max_at_a_peak);
    // Each order alone (its own points) gives the same, bit for bit.
    CHECK(p[0].max.value == velocity->maximum(c.a, c.b, each).value);
    CHECK(p[0].min.x == velocity->minimum(c.a, c.b, each).x);
    CHECK(p[1].max.value == acceleration->maximum(c.a, c.b, each).value);
    CHECK(p[1].min.x == acceleration->minimum(c.a, c.b, each).x);
    // The generic certified search over the same interval, split at the law's breakpoints.
    std::vector<double> knots{c.a};
    for (double x : law.breakpoints())
      if (x > c.a && x < c.b) knots.push_back(x);
    knots.push_back(c.b);
    numerics::SmoothPieces pieces(
        [&](double x, double* v, double*) {
          const LiftDerivatives d = law.evaluate_in_event(x);
          v[0] = d.velocity;
          v[1] = d.acceleration;
        },
        2, knots, 16);
    CHECK_THAT(p[0].max.value, WithinRel(pieces.maximum(0).value, 1e-12) || WithinAbs(pieces.maximum(0).value, 1e-14 * v_scale));
    CHECK_THAT(p[0].min.value, WithinRel(pieces.minimum(0).value, 1e-12) || WithinAbs(pieces.minimum(0).value, 1e-14 * v_scale));
    CHECK_THAT(p[1].max.value, WithinRel(pieces.maximum(1).value, 1e-12) || WithinAbs(pieces.maximum(1).value, 1e-14 * a_scale));
    CHECK_THAT(p[1].min.value, WithinRel(pieces.minimum(1).value, 1e-12) || WithinAbs(pieces.minimum(1).value, 1e-14 * a_scale));
  }
  // The cam summary (the production caller: both orders over the event) equals the generic path's.
  const CamSummary with = summarize(law, 16), without = summarize(generic, 16);
  CHECK_THAT(with.max_velocity, WithinRel(without.max_velocity, 1e-12));
  CHECK_THAT(with.max_acceleration, WithinRel(without.max_acceleration, 1e-12));
  CHECK_THAT(with.min_acceleration, WithinRel(without.min_acceleration, 1e-12));
  CHECK_THAT(with.max_velocity, WithinRel(v_scale, 1e-13));
  CHECK_THAT(with.min_acceleration, WithinRel(-a_scale, 1e-13));
}

TEST_CASE("monotone runs: a crossing near a run's end starts from that end's Taylor polynomial", "[sdk][cam_runs]") {
  // The bump leaves its foot as 8 H (1 + x)^3 (its lift, velocity and acceleration are zero there,
  // its jerk 48 H / w^3): the cubic polynomial at the run's end nearly is the lift, so each of the
  // two crossings of a low level (a lash) takes at most four of the law's evaluations after the
  // four the walk reads at the runs' ends. Started from the chord of the run, the same crossings
  // took 6 to 9 each (22, 18 and 16 evaluations for the first three levels, 18 near the nose).
  const double c = 3 * deg, w = 60 * deg;
  const Bump law(c, w, 1);
  const auto lift = CamLawRuns::of(law, 0);
  REQUIRE(lift);
  for (double L : {1e-6, 1e-4, 0.0037 * 0.1, 0.0037}) {
    INFO("level " << L);
    long evaluations = 0;
    const auto cross = lift->directed_crossings(L, evaluations);
    REQUIRE(cross.size() == 2);
    const double xs = std::sqrt(1 - std::cbrt(L / Bump::H));
    CHECK_THAT(cross[0].first, WithinAbs(c - xs * w, 1e-14));
    CHECK_THAT(cross[1].first, WithinAbs(c + xs * w, 1e-14));
    CHECK(evaluations <= 4 + 2 * 4);
  }
  // A level near the nose: the nose's polynomial (a parabola) starts it.
  long evaluations = 0;
  const double L = 0.999 * Bump::H;
  const auto cross = lift->directed_crossings(L, evaluations);
  REQUIRE(cross.size() == 2);
  CHECK_THAT(cross[0].first, WithinAbs(c - std::sqrt(1 - std::cbrt(0.999)) * w, 1e-14));
  CHECK(evaluations <= 4 + 2 * 3);
}
