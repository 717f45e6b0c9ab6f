#pragma once
// Opening and closing ramps that take up the lash, for any cam law symmetric about the nose.
// See docs/methods/valvetrain.md, stage 1 (ramps are our extension of the source).
//
// Definition (all angles from the nose; the main law spans [-P, P], the ramps have length L and
// height H_r; x = (phi + P + L)/L in [0, 1] on the opening ramp, w = (phi + P)/P in [0, 1] from
// the end of the ramp to the nose):
//
//   h(phi) = R(phi) + M(phi),   R even, M the main law (zero outside [-P, P]).
//
//   opening ramp (x in [0, 1]):
//     constant_velocity  R = H_r x                     R' = v_r = H_r/L
//     cosine             R = H_r (1 - cos(pi x/2))     R' = v_r sin(pi x/2),  v_r = pi H_r/(2L)
//   under the main law (w in [0, 1]): the ramp velocity v_r is carried into the main lift and
//   faded out by the nose with the 3-4-5 polynomial s(w) = 10w^3 - 15w^4 + 6w^5:
//     R' = v_r (1 - s(w)),  R = H_r + v_r P F(w),  F(w) = w - 5w^4/2 + 3w^5 - w^6,  F(1) = 1/2.
//   The closing side is the mirror image (odd derivatives change sign).
//
// So the ramp's share of the lift at the nose is R(0) = H_r + v_r P/2 and the main law is built
// with max_lift - R(0): max_lift is the total lift. The event is [-(P + L), P + L], i.e.
// action_angle + 2 ramp_length.
//
// Continuity (of R; the main law adds its own at +-P):
//  - constant_velocity: the velocity jumps from 0 to v_r at the start of the ramp (and back at its
//    end on the closing side): the acceleration there is an impulse, the ramp is NOT shockless.
//    At the ramp/main junction R is continuous up to the third derivative.
//  - cosine: lift and velocity continuous at the start of the ramp, the acceleration jumps to
//    H_r (pi/(2L))^2 (finite, no impulse); at the junction lift, velocity and acceleration are
//    continuous (R'' = 0 on both sides), the jerk jumps by v_r (pi/(2L))^2.
//  - the fade is smooth at the nose (R' = R'' = R''' = 0 there).
// The lash is taken up at the ramp velocity v_r (constant over the whole constant_velocity ramp).
#include <mechgraph/domain/cam_law.hpp>

#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace mechgraph::cams {

enum class RampType { none, constant_velocity, cosine };

std::string_view ramp_type_name(RampType type);
std::optional<RampType> ramp_type_from_name(std::string_view name);
/// "none", "constant_velocity", "cosine": the choices of the cam nodes' `ramp` parameter.
std::vector<std::string> ramp_type_names();

struct RampSpec {
  RampType type = RampType::none;
  double height = 0.0;  // m, H_r
  double length = 0.0;  // rad, L (each side)
};

/// dh/dphi of the ramp where it meets the main law, v_r [m/rad]; 0 for RampType::none.
double ramp_end_velocity(const RampSpec& ramp);

/// The ramp's share of the lift at the nose, H_r + v_r P/2, for a main law spanning [-P, P].
double ramp_lift_at_nose(const RampSpec& ramp, double half_action_angle);

/// The ramp part R alone (no main law) at phi, for a main law spanning [-P, P]: zero outside
/// [-(P + L), P + L].
LiftDerivatives ramp_part(const RampSpec& ramp, double half_action_angle, double phi);

/// A main law with ramps superposed as defined above. Throws NodeError naming `ramp`,
/// `ramp_height` or `ramp_length` when the request is invalid (main law not symmetric about the
/// nose, non-positive height or length, total event not below 360 deg).
class RampedLaw final : public CamLaw {
 public:
  RampedLaw(std::shared_ptr<const CamLaw> main, RampSpec ramp);

  double event_begin() const override { return -(half_main_ + ramp_.length); }
  double event_end() const override { return half_main_ + ramp_.length; }
  LiftDerivatives evaluate_in_event(double phi) const override;
  /// The main law's breakpoints, the ramp/main junctions and the nose.
  std::vector<double> breakpoints() const override;
  /// Main law's max_lift plus R(0): exact when the main law peaks at the nose (R peaks there).
  double max_lift() const override;
  double base_radius() const override { return main_->base_radius(); }
  double roller_radius() const override { return main_->roller_radius(); }

  const CamLaw& main_law() const { return *main_; }
  const RampSpec& ramp() const { return ramp_; }

 private:
  std::shared_ptr<const CamLaw> main_;
  RampSpec ramp_;
  double half_main_;
};

}  // namespace mechgraph::cams
