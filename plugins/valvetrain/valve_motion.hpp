#pragma once
// The valve's motion over cam angle at one engine speed (docs/methods/valvetrain.md, stage 2):
// valve lift h_v = i h(phi) - lash while that is positive (rocker ratio i = l_v/l_p), zero
// otherwise; derivatives i h', i h'', i h''' over cam angle; in time multiply by w_k, w_k^2, w_k^3
// with the camshaft speed w_k = w_crank / 2 (four-stroke).
#include <mechgraph/domain/cam_law_runs.hpp>
#include <mechgraph/domain/valve_motion.hpp>
#include <mechgraph/numerics/piecewise.hpp>

#include <memory>
#include <utility>
#include <vector>

namespace mechgraph::valvetrain {

/// The cam angles where the valve opens (the lash taken up) and closes.
struct OpenPeriod {
  double begin = 0.0, end = 0.0;  // rad
};

/// What the searches below keep from case to case: the cam's monotone runs (lift, velocity,
/// acceleration) and the crossings found, so that a block of cases reuses their storage instead of
/// allocating them per case. One per thread (a block runs on one).
struct ValveSearchScratch {
  CamLawRuns lift, velocity, acceleration;
  std::vector<std::pair<double, bool>> crossings;
};

/// The open period of the valve on `cam` through rocker ratio i with a lash: the first rising and
/// the last falling crossing of i h = lash (the whole event without lash). Throws NodeError("lash")
/// when the valve never opens. Shared by the single and the block evaluation.
OpenPeriod find_open_period(const CamLaw& cam, double rocker_ratio, double lash, int samples, long& evaluations);
OpenPeriod find_open_period(const CamLaw& cam, double rocker_ratio, double lash, int samples, long& evaluations,
                            ValveSearchScratch& scratch);

/// Valve lift and its derivatives over cam angle at phi: i h - lash (clipped at 0 against
/// rounding at the crossings) and i h', i h'', i h''' inside the open period, zero outside.
inline LiftDerivatives valve_lift_at(const CamLaw& cam, const OpenPeriod& open, double rocker_ratio, double lash, double phi) {
  if (phi < open.begin || phi > open.end) return {};
  const LiftDerivatives h = cam.at(phi);
  const double lift = rocker_ratio * h.lift - lash;
  return {lift > 0.0 ? lift : 0.0, rocker_ratio * h.velocity, rocker_ratio * h.acceleration, rocker_ratio * h.jerk};
}

/// The valve's peaks over its open period over cam angle (velocity in m/rad, acceleration in
/// m/rad^2), from the cam's monotone runs where it declares them, else from one certified
/// interpolation of each smooth piece. Shared by the single and the block evaluation.
struct ValvePeaks {
  numerics::Extremum velocity;  // the largest |velocity|
  numerics::Extremum max_acceleration, min_acceleration;
};
ValvePeaks find_valve_peaks(const CamLaw& cam, const OpenPeriod& open, double rocker_ratio, double lash, int samples,
                            long& evaluations);
/// `with_velocity` false: the acceleration's peaks only (velocity left zero; the velocity's run
/// ends are not read), when nothing reads max_velocity (the block path's outputs).
ValvePeaks find_valve_peaks(const CamLaw& cam, const OpenPeriod& open, double rocker_ratio, double lash, int samples,
                            long& evaluations, ValveSearchScratch& scratch, bool with_velocity = true);

/// The valve motion a cam law, a rocker ratio and a lash give (the ValveMotion contract).
class CamValveMotion final : public ValveMotion {
 public:
  /// Throws NodeError("lash") when the valve never opens.
  CamValveMotion(std::shared_ptr<const CamLaw> cam, double camshaft_speed, double rocker_ratio, double lash,
              int samples, long& evaluations);
  /// With the open period known (find_open_period).
  CamValveMotion(std::shared_ptr<const CamLaw> cam, double camshaft_speed, double rocker_ratio, double lash, OpenPeriod open);

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
