#include "valve_motion.hpp"

#include <mechgraph/errors.hpp>
#include <mechgraph/numerics/piecewise.hpp>

#include <algorithm>
#include <sstream>

namespace mechgraph::valvetrain {

CamValveMotion::CamValveMotion(std::shared_ptr<const CamLaw> cam, double camshaft_speed, double rocker_ratio, double lash,
                         int samples, long& evaluations)
    : cam_(std::move(cam)), camshaft_speed_(camshaft_speed), rocker_ratio_(rocker_ratio), lash_(lash) {
  std::vector<double> cam_knots{cam_->event_begin()};
  for (double b : cam_->breakpoints()) cam_knots.push_back(b);
  cam_knots.push_back(cam_->event_end());
  if (lash_ <= 0.0) {
    open_begin_ = cam_->event_begin();
    open_end_ = cam_->event_end();
  } else {
    // The valve moves while i h(phi) > lash. The top of the lift brackets both crossings, however
    // narrow the open period is: the opening is the first crossing before the top, the closing the
    // last one after it.
    auto gap = [&](double phi) { return rocker_ratio_ * cam_->at(phi).lift - lash_; };
    const numerics::Extremum top = numerics::maximize_piecewise(gap, cam_knots, samples, evaluations);
    if (!(top.value > 0.0)) {
      std::ostringstream msg;
      msg << "the valve never opens: rocker_ratio * cam lift reaches " << (top.value + lash_) * 1e3
          << " mm, not more than the lash of " << lash_ * 1e3 << " mm";
      throw NodeError("lash", msg.str());
    }
    std::vector<double> rising{cam_->event_begin()}, falling{top.x};
    for (double b : cam_->breakpoints()) (b < top.x ? rising : falling).push_back(b);
    rising.push_back(top.x);
    falling.push_back(cam_->event_end());
    const auto opening = numerics::first_sign_change(gap, rising, samples, evaluations);
    const std::vector<double> closings = numerics::all_sign_changes(gap, falling, samples, evaluations);
    if (!opening || closings.empty())
      throw NodeError("lash", "the opening or closing angle of the valve could not be bracketed");
    open_begin_ = *opening;
    open_end_ = closings.back();
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
