#pragma once
// The moving parts of a lower-camshaft valve train (tappet, pushrod, rocker, valve) and the
// designed spring, as the valvetrain nodes pass them on (docs/methods/valvetrain.md, stage 4c).
//
// Reduced to the valve (rocker arms l_v on the valve side, l_p on the pushrod side):
//   M_ws  = m_valve + m_retainer + J_rocker / l_v^2 + (m_pushrod + m_tappet) (l_p / l_v)^2
//   M_red = M_ws + m_s / 3         (a third of a uniform coil moves with the valve)
#include <mechgraph/domain/spring.hpp>

#include <memory>
#include <string_view>

namespace mechgraph::valvetrain {

class TrainMasses final : public DomainObject {
 public:
  static constexpr std::string_view kind_name = "valve_train_masses";
  std::string_view kind() const override { return kind_name; }

  double valve = 0.0, retainer = 0.0, tappet = 0.0, pushrod = 0.0;  // kg
  double rocker_inertia = 0.0;                                        // kg m^2, about the rocker shaft
  double arm_valve = 1.0, arm_pushrod = 1.0;                          // m: l_v, l_p

  double rocker_ratio() const { return arm_valve / arm_pushrod; }
  double without_spring() const {
    const double back = arm_pushrod / arm_valve;
    return valve + retainer + rocker_inertia / (arm_valve * arm_valve) + (pushrod + tappet) * back * back;
  }
};

/// What valvetrain.spring_design decided: the sized spring, the masses and the reduced mass.
class SpringDesign final : public DomainObject {
 public:
  static constexpr std::string_view kind_name = "valve_spring_design";
  std::string_view kind() const override { return kind_name; }

  std::shared_ptr<const Spring> spring;
  std::shared_ptr<const TrainMasses> masses;
  double reduced_mass = 0.0;  // M_red, kg, valve side
  double safety_factor = 0.0;
};

}  // namespace mechgraph::valvetrain
