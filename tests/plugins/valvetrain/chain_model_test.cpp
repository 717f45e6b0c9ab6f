// The chain model's right-hand side for the single mass (its own inner-loop path in
// ChainModel::rates) against the equation of motion written out, in every mode, and against the
// model's Jacobian (the model is affine in the state within a mode: ds(s) = ds(0) + J s).
#include "chain_model.hpp"

#include <catch2/catch.hpp>

#include <cmath>

using namespace mechgraph::valvetrain;
using Catch::Matchers::WithinAbs;
using Catch::Matchers::WithinRel;

TEST_CASE("chain model: the single mass's rates are M x'' = F_c - P0 - c_s x in every mode", "[valvetrain][dynamics][chain]") {
  const double M = 0.13, k = 4e6, b = 85.0, P0 = 350.0, c_s = 3.2e4;
  for (const bool unilateral : {false, true}) {
    ChainParams p;
    p.mass = {M};
    p.link_stiffness = {k};
    p.link_damping = {b};
    p.preload = P0;
    p.spring_rate = c_s;
    p.contact_loss = unilateral;
    const DriveValue drive{4e-3, 1.7, -900.0};
    const ChainModel model(p, [=](double) { return drive; });
    // The cam pushing (y > x, F_c > 0), and clear of the valve (y < x).
    for (const double x : {2.5e-3, 5e-3}) {
      const double v = 0.8;
      const ChainState s{x, v};
      for (const Mode mode : {Mode{false, true}, Mode{false, false}, Mode{true, true}}) {
        INFO("contact_loss " << unilateral << ", x = " << x << ", seated " << mode.seated << ", contact " << mode.contact);
        ChainState ds;
        model.rhs(mode, 0.0, s, ds);
        REQUIRE(ds.size() == 2);
        const double cam = k * (drive.y - x) + b * (drive.rate - v);
        const bool pushes = mode.contact && (!unilateral || (drive.y > x && cam > 0.0));
        const double accel = mode.seated ? 0.0 : ((pushes ? cam : 0.0) - P0 - c_s * x) / M;
        CHECK(ds[0] == (mode.seated ? 0.0 : v));
        CHECK_THAT(ds[1], WithinRel(accel, 1e-14) || WithinAbs(accel, 1e-12));
        // The second method: the Jacobian applied to the state, plus the rates at the zero state
        // (same mode; where the unilateral cam's contact changes with the state the map is not affine).
        if (!pushes && mode.contact && unilateral) continue;
        const std::vector<double> J = model.jacobian(mode);
        ChainState at_zero;
        model.rhs(mode, 0.0, ChainState{0.0, 0.0}, at_zero);
        for (int r = 0; r < 2; ++r) {
          const double affine = at_zero[r] + J[r * 2] * x + J[r * 2 + 1] * v;
          CHECK_THAT(ds[r], WithinRel(affine, 1e-12) || WithinAbs(affine, 1e-9));
        }
      }
    }
  }
}
