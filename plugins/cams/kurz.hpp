#pragma once
// Kurz cam (docs/methods/valvetrain.md, stage 1): a ShocklessLaw whose acceleration, from the
// start of lift x = 0 to the nose x = phi_p, is
//     A+ sin(pi x / (2 phi_1))                         0 <= x <= phi_1        quarter sine up
//     A+ cos(pi (x - phi_1) / (2 phi_2))               phi_1 <= x <= phi_y    quarter cosine down
//     A- [1 - ((phi_p - x) / phi_3)^2]                 phi_y <= x <= phi_p    parabola, vertex at the nose
// with phi_y = phi_1 + phi_2 the positive phase (accel_angle), phi_3 = phi_p - phi_y, and the
// split sigma = phi_1 / phi_y (rise_split).
//
// Zero velocity at the nose gives A- = -3 A+ phi_y / (pi phi_3) whatever the split. The jerk at the
// positive/negative junction is -A+ pi / (2 phi_2) on the left and 2 A- / phi_3 on the right;
// equal when phi_2 = pi^2 phi_3^2 / (12 phi_y), i.e. sigma* = 1 - pi^2 (phi_3/phi_y)^2 / 12, which
// exists (sigma* > 0) only while phi_3 < sqrt(12)/pi phi_y = 1.103 phi_y.
#include "cam_node.hpp"
#include "shockless.hpp"

#include <memory>
#include <optional>

namespace mechgraph::cams {

/// sigma* = 1 - pi^2 (phi_3/phi_y)^2 / 12: the split with a continuous jerk at the
/// positive/negative junction; <= 0 when that is not attainable.
double kurz_jerk_continuous_split(double accel_angle, double half_action);

/// The split that minimises the larger of the two jerk jumps the law keeps (at the start of lift,
/// A+ pi / (2 phi_1), and at the junction, A+ |pi / (2 phi_2) - k|, k = 6 phi_y / (pi phi_3^2)):
/// equal jumps give sigma = (1 + kappa / (pi + sqrt(pi^2 + kappa^2))) / 2, kappa = k phi_y.
double kurz_minimax_split(double accel_angle, double half_action);

/// The default: sigma* when attainable, else the minimax split.
double kurz_default_split(double accel_angle, double half_action);

/// Builds the law; throws NodeError naming accel_angle or rise_split when infeasible.
std::shared_ptr<const ShocklessLaw> make_kurz_law(const CamBasics& basics, double accel_angle,
                                                  std::optional<double> rise_split);

/// cam.kurz: parameters accel_angle (required) and rise_split (optional); extra output rise_split.
CamLawDefinition kurz_definition();

}  // namespace mechgraph::cams
