#pragma once
// The valve's motion over cam angle at one engine speed (docs/methods/valvetrain.md, stage 2):
// valve lift h_v = i h(phi) - lash while that is positive (rocker ratio i = l_v/l_p), zero
// otherwise; derivatives i h', i h'', i h''' over cam angle; in time multiply by w_k, w_k^2, w_k^3
// with the camshaft speed w_k = w_crank / 2 (four-stroke).
#include <mechgraph/domain/valve_motion.hpp>

#include <memory>
#include <vector>

namespace mechgraph::valvetrain {

/// The valve motion a cam law, a rocker ratio and a lash give (the ValveMotion contract).
class CamValveMotion final : public ValveMotion {
 public:
  /// Throws NodeError("lash") when the valve never opens.
  CamValveMotion(std::shared_ptr<const CamLaw> cam, double camshaft_speed, double rocker_ratio, double lash,
              int samples, long& evaluations);

  /// Valve lift [m] and its derivatives over cam angle [m/rad^k]; zero while closed.
  LiftDerivatives at(double phi) const override;
  double camshaft_speed() const override { return camshaft_speed_; }  // rad/s
  double open_begin() const override { return open_begin_; }          // cam angle where the lash is taken up
  double open_end() const override { return open_end_; }
  /// open_begin, the cam law's breakpoints inside the open period, open_end.
  const std::vector<double>& knots() const override { return knots_; }
  const CamLaw& cam() const override { return *cam_; }
  double rocker_ratio() const override { return rocker_ratio_; }
  double lash() const override { return lash_; }

 private:
  std::shared_ptr<const CamLaw> cam_;
  double camshaft_speed_;
  double rocker_ratio_;
  double lash_;
  double open_begin_ = 0.0;
  double open_end_ = 0.0;
  std::vector<double> knots_;
};

}  // namespace mechgraph::valvetrain
