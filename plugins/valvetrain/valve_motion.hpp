#pragma once
// The valve's motion over cam angle at one engine speed (shared/methods/valvetrain.md, stage 2):
// valve lift h_v = i h(phi) - lash while that is positive (rocker ratio i = l_v/l_p), zero
// otherwise; derivatives i h', i h'', i h''' over cam angle; in time multiply by w_k, w_k^2, w_k^3
// with the camshaft speed w_k = w_crank / 2 (four-stroke).
#include <mechgraph/domain/cam_law.hpp>

#include <memory>
#include <vector>

namespace mechgraph::valvetrain {

class ValveMotion final : public DomainObject {
 public:
  static constexpr std::string_view kind_name = "valve_motion";
  std::string_view kind() const override { return kind_name; }

  /// Throws NodeError("lash") when the valve never opens.
  ValveMotion(std::shared_ptr<const CamLaw> cam, double camshaft_speed, double rocker_ratio, double lash,
              int samples, long& evaluations);

  /// Valve lift [m] and its derivatives over cam angle [m/rad^k]; zero while closed.
  LiftDerivatives at(double phi) const;
  double camshaft_speed() const { return camshaft_speed_; }  // rad/s
  double open_begin() const { return open_begin_; }          // cam angle where the lash is taken up
  double open_end() const { return open_end_; }
  /// open_begin, the cam law's breakpoints inside the open period, open_end.
  const std::vector<double>& knots() const { return knots_; }
  const CamLaw& cam() const { return *cam_; }
  double rocker_ratio() const { return rocker_ratio_; }
  double lash() const { return lash_; }

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
