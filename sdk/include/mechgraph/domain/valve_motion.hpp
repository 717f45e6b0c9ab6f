#pragma once
// ValveMotion: the valve's kinematic motion at one engine speed, as the cam and the rocker make it
// (docs/methods/valvetrain.md, stage 2). Made by `valvetrain.valve_motion`; read by the stage 3-4
// nodes, the dynamics and reports of any plugin.
//
// Contract
//  - Cam angle phi in radians, from the nose, as for CamLaw. `at(phi)` gives the valve lift x [m]
//    (valve side: rocker ratio i times the tappet lift, less the lash) and its derivatives over cam
//    angle [m/rad^k]; zero outside the open period [open_begin(), open_end()].
//  - `drive(phi)` is the cam's displacement reduced to the valve, y = i h(phi) - lash, with its
//    derivatives: negative while the lash is open. It is what an elastic drive pushes with.
//  - `camshaft_speed()` w_k [rad/s] turns derivatives over cam angle into time: velocity w_k x',
//    acceleration w_k^2 x'', jerk w_k^3 x'''.
//  - `knots()`: open_begin, the cam law's breakpoints inside the open period, open_end, sorted.
//    Between knots the motion is smooth; integrators and extremum searches split there.
//  - Who checks what: the maker refuses a valve that never opens (lash larger than the lift);
//    consumers may assume open_begin() < open_end().
//  - Implementations are immutable and thread-safe.
#include <mechgraph/domain/cam_law.hpp>

#include <vector>

namespace mechgraph {

class MECHGRAPH_INTERFACE ValveMotion : public DomainObject {
 public:
  ~ValveMotion() override;  // out of line (key function, sdk/src/interfaces.cpp)
  static constexpr std::string_view kind_name = "valve_motion";
  std::string_view kind() const override { return kind_name; }

  virtual LiftDerivatives at(double phi) const = 0;
  virtual double camshaft_speed() const = 0;
  virtual double open_begin() const = 0;
  virtual double open_end() const = 0;
  virtual const std::vector<double>& knots() const = 0;
  virtual double rocker_ratio() const = 0;
  virtual double lash() const = 0;
  virtual const CamLaw& cam() const = 0;

  /// The cam's displacement reduced to the valve, y = i h - lash, and its derivatives over cam angle.
  LiftDerivatives drive(double phi) const {
    const LiftDerivatives h = cam().at(phi);
    const double i = rocker_ratio();
    return {i * h.lift - lash(), i * h.velocity, i * h.acceleration, i * h.jerk};
  }
  /// Valve acceleration in time [m/s^2] at cam angle phi.
  double acceleration_in_time(double phi) const {
    const double w = camshaft_speed();
    return w * w * at(phi).acceleration;
  }
};

}  // namespace mechgraph
