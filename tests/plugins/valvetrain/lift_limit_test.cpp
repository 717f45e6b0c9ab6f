// The lift limits of the chain model (coil bind, travel stop: chain_model.hpp) against closed forms:
// a free mass pushed by a constant force into a stiff spring-damper contact. Before the contact the
// flight is a parabola; in it the motion is the damped oscillator about the shifted rest F/k,
// written out below; after it a parabola again, back to the contact at the speed it left with.
#include "chain_model.hpp"
#include "hybrid_simulation.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

using namespace mechgraph::valvetrain;
using Catch::Matchers::WithinAbs;
using Catch::Matchers::WithinRel;

namespace {

// delta'' + 2 zeta w delta' + w^2 delta = w^2 d_s from delta = 0, delta' = v0 (d_s = F/k):
//   delta = d_s + exp(-zeta w t) (A cos(w_d t) + B sin(w_d t)),  A = -d_s,  B = (v0 - zeta w d_s) / w_d.
struct ContactSolution {
  double w, zeta, w_d, d_s, A, B;
  ContactSolution(double k, double c, double m, double force, double v0)
      : w(std::sqrt(k / m)), zeta(c / (2.0 * std::sqrt(k * m))), w_d(w * std::sqrt(1.0 - zeta * zeta)), d_s(force / k),
        A(-d_s), B((v0 - zeta * w * d_s) / w_d) {}
  double delta(double t) const { return d_s + std::exp(-zeta * w * t) * (A * std::cos(w_d * t) + B * std::sin(w_d * t)); }
  double rate(double t) const {
    const double e = std::exp(-zeta * w * t), c = std::cos(w_d * t), s = std::sin(w_d * t);
    return e * (-zeta * w * (A * c + B * s) + w_d * (-A * s + B * c));
  }
  // The first return to delta = 0: bisection on the half period's second half (delta > 0 before it).
  double exit_time() const {
    double lo = 0.5 * std::numbers::pi / w_d, hi = 1.5 * std::numbers::pi / w_d;
    for (int i = 0; i < 200; ++i) {
      const double mid = 0.5 * (lo + hi);
      (delta(mid) > 0.0 ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
  }
};

}  // namespace

TEST_CASE("restitution damping: a free mass leaves the contact at e times its impact speed", "[valvetrain][dynamics][chain]") {
  for (const double e : {0.05, 0.3, 0.5, 0.9, 1.0}) {
    const double k = 2e8, m = 0.09, c = restitution_damping(e, k, m);
    const ContactSolution free(k, c, m, 0.0, 1.3);
    // Without a force the contact ends after exactly half a damped period.
    CHECK_THAT(free.exit_time(), WithinRel(std::numbers::pi / free.w_d, 1e-12));
    CHECK_THAT(-free.rate(free.exit_time()) / 1.3, WithinRel(e, 1e-10) || WithinAbs(e, 1e-14));
  }
}

TEST_CASE("lift limit: impacts, rebound and the free flight between them match the closed forms, both integrators",
          "[valvetrain][dynamics][chain]") {
  // One free mass (no cam link, no seat, no spring rate), a constant force F towards the stop at
  // lift a: it starts from rest at 0 and hits at v0 = sqrt(2 a F / m).
  const double m = 0.1, F = 20.0, a = 1e-3, k = 1e8, e = 0.4;
  ChainParams p;
  p.mass = {m};
  p.link_stiffness = {0.0};
  p.link_damping = {0.0};
  p.preload = -F;  // a negative preload pushes the valve up
  p.seat = false;
  p.limits.push_back({a, k, restitution_damping(e, k, m), false, "stop"});
  const ChainModel model(p, [](double) { return DriveValue{}; });

  const double acc = F / m, v0 = std::sqrt(2.0 * a * acc), t_hit = v0 / acc;
  const ContactSolution contact(k, p.limits[0].damping, m, F, v0);
  const double t_out = t_hit + contact.exit_time(), v1 = -contact.rate(contact.exit_time());
  const double t_hit2 = t_out + 2.0 * v1 / acc;  // the parabola up and back: it returns at v1
  const double t_end = t_hit2 + 0.5 * contact.exit_time();

  for (const char* integrator : {"dopri5", "cvode"}) {
    INFO(integrator);
    SimulationOptions options;
    options.integrator = integrator;
    options.rtol = 1e-10;
    options.atol_x = 1e-14;
    options.atol_v = 1e-12;
    options.max_step = 1e-5;
    // The state at the parabola's top between the impacts, in closed form.
    const double t_top = t_out + v1 / acc;
    const SimulationResult r = simulate(model, 0.0, t_end, {t_top}, {}, options);
    REQUIRE(r.events.size() == 3);
    CHECK(r.events[0].kind == "stop");
    CHECK(r.events[1].kind == "stop_release");
    CHECK(r.events[2].kind == "stop");
    CHECK_THAT(r.events[0].t, WithinRel(t_hit, 1e-8));
    CHECK_THAT(r.events[0].speed, WithinRel(v0, 1e-8));
    CHECK_THAT(r.events[1].t, WithinRel(t_out, 1e-8));
    CHECK_THAT(r.events[1].speed, WithinRel(v1, 1e-6));
    // The constant force shifts the rest by F/k = 0.2 um against an amplitude v0/w = 20 um: the
    // rebound ratio is e to about a percent.
    CHECK_THAT(v1 / v0, WithinRel(e, 0.02));
    CHECK_THAT(r.events[2].t, WithinRel(t_hit2, 1e-8));
    CHECK_THAT(r.events[2].speed, WithinRel(v1, 1e-6));
    REQUIRE(r.t.size() == 1);
    CHECK_THAT(r.state[0][0], WithinRel(a - v1 * v1 / (2.0 * acc), 1e-7) || WithinAbs(a - v1 * v1 / (2.0 * acc), 1e-12));
    CHECK_THAT(r.state[0][1], WithinAbs(0.0, 1e-6 * v1));
    CHECK(r.mode[0].engaged == 0u);
  }
}

TEST_CASE("lift limit: the engaged limit's force enters the rates and the Jacobian, the coil bind's the spring force",
          "[valvetrain][dynamics][chain]") {
  const double M = 0.12, kd = 4e6, P0 = 300.0, c_s = 3e4, kb = 1e8, cb = 400.0, a = 9e-3;
  ChainParams p;
  p.mass = {M};
  p.link_stiffness = {kd};
  p.link_damping = {50.0};
  p.preload = P0;
  p.spring_rate = c_s;
  p.limits.push_back({a, kb, cb, true, "coil_bind"});
  const DriveValue drive{10e-3, 1.0, 0.0};
  const ChainModel model(p, [=](double) { return drive; });
  const ChainState s{9.05e-3, 0.7};
  const Mode bound{false, true, 1u};
  ChainState ds;
  model.rhs(bound, 0.0, s, ds);
  const double bind = kb * (s[0] - a) + cb * s[1];
  const double cam = kd * (drive.y - s[0]) + 50.0 * (drive.rate - s[1]);
  CHECK_THAT(ds[1], WithinRel((cam - P0 - c_s * s[0] - bind) / M, 1e-13));
  CHECK_THAT(model.spring_force(s, 1u), WithinRel(P0 + c_s * s[0] + bind, 1e-14));
  CHECK_THAT(model.spring_force(s, 0u), WithinRel(P0 + c_s * s[0], 1e-14));
  // The Jacobian of the engaged mode: d(x'')/dx = -(k_d + c_s + k_b)/M, d(x'')/dx' = -(b + c_b)/M.
  const std::vector<double> J = model.jacobian(bound);
  CHECK_THAT(J[2], WithinRel(-(kd + c_s + kb) / M, 1e-13));
  CHECK_THAT(J[3], WithinRel(-(50.0 + cb) / M, 1e-13));
  // The engaged mode watches for the release, the free one for the engagement.
  const auto& kinds = model.root_kinds(bound);
  CHECK(std::count(kinds.begin(), kinds.end(), RootKind::limit_release) == 1);
  const auto& free_kinds = model.root_kinds(Mode{false, true, 0u});
  CHECK(std::count(free_kinds.begin(), free_kinds.end(), RootKind::limit_engage) == 1);
}
