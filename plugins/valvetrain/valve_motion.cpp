#include "valve_motion.hpp"

#include <mechgraph/domain/cam_law_runs.hpp>
#include <mechgraph/errors.hpp>
#include <mechgraph/numerics/piecewise.hpp>

#include <algorithm>
#include <limits>
#include <numbers>
#include <optional>
#include <sstream>

namespace mechgraph::valvetrain {

CamValveMotion::CamValveMotion(std::shared_ptr<const CamLaw> cam, double camshaft_speed, double rocker_ratio, double lash,
                         int samples, long& evaluations)
    : cam_(std::move(cam)), camshaft_speed_(camshaft_speed), rocker_ratio_(rocker_ratio), lash_(lash) {
  const std::vector<double> cam_knots = cam_->knots();
  if (lash_ <= 0.0) {
    open_begin_ = cam_->event_begin();
    open_end_ = cam_->event_end();
  } else {
    // The valve moves while g = i h(phi) - lash > 0: the opening is the first crossing of the lash
    // (rising) and the closing the last (falling), found by the certified search over the cam's
    // smooth pieces (numerics/piecewise.hpp), whatever the ramps or the table between them do.
    // A law that declares its lift's monotone runs (CamLaw::monotone_breaks) has each crossing
    // bracketed in its run: TOMS 748 on the law, no interpolation (mechgraph/domain/cam_law_runs.hpp).
    std::optional<numerics::SmoothPieces> pieces;
    std::vector<std::pair<double, bool>> crossings;
    const auto runs = CamLawRuns::of(*cam_, 0);
    if (runs) {
      crossings = runs->directed_crossings(lash_ / rocker_ratio_, evaluations);
    } else {
      pieces.emplace([&](double phi, double* v, double*) { v[0] = rocker_ratio_ * cam_->at(phi).lift; }, 1, cam_knots,
                     samples);
      crossings = pieces->directed_crossings(0, lash_);
      evaluations += pieces->work().evaluations;
    }
    std::optional<double> opening, closing;
    for (const auto& [x, rising] : crossings)
      if (rising) {
        opening = x;
        break;
      }
    for (auto c = crossings.rbegin(); c != crossings.rend(); ++c)
      if (!c->second) {
        closing = c->first;
        break;
      }
    if (!opening || !closing || !(*closing > *opening)) {
      numerics::Extremum peak = runs ? runs->maximum(evaluations) : pieces->maximum(0);
      if (runs) peak.value *= rocker_ratio_;
      std::ostringstream msg;
      if (peak.value > lash_)  // the lift passes the lash, yet no rising and later falling crossing was found
        msg << "the valve's opening and closing at a lash of " << lash_ * 1e3 << " mm could not be told apart (rocker_ratio * cam "
            << "lift reaches " << peak.value * 1e3 << " mm at " << peak.x * 180.0 / std::numbers::pi << " deg)";
      else
        msg << "the valve never opens: rocker_ratio * cam lift reaches " << peak.value * 1e3 << " mm, not more than the lash of "
            << lash_ * 1e3 << " mm";
      throw NodeError("lash", msg.str());
    }
    open_begin_ = *opening;
    open_end_ = *closing;
  }
  knots_.push_back(open_begin_);
  for (double b : cam_->breakpoints())
    if (b > open_begin_ && b < open_end_) knots_.push_back(b);
  knots_.push_back(open_end_);
}

LiftDerivatives CamValveMotion::at(double phi) const {
  // Open between the crossings found at construction; there the valve follows the cam (the lift
  // clipped at 0 against rounding right at the crossings), elsewhere it rests on its seat.
  if (phi < open_begin_ || phi > open_end_) return {};
  const LiftDerivatives h = cam_->at(phi);
  const double lift = std::max(0.0, rocker_ratio_ * h.lift - lash_);
  return {lift, rocker_ratio_ * h.velocity, rocker_ratio_ * h.acceleration, rocker_ratio_ * h.jerk};
}

}  // namespace mechgraph::valvetrain
