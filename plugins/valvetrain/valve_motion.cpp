#include "valve_motion.hpp"

#include <mechgraph/errors.hpp>
#include <mechgraph/numerics/piecewise.hpp>

#include <boost/math/tools/roots.hpp>

#include <algorithm>
#include <limits>
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
    // The valve moves while g = i h(phi) - lash > 0. One pass of samples over the event (ends of
    // each piece one-sided at the breakpoints) finds the top of g; the opening is the first sign
    // change before it and the closing the last one after it, each bracketed by neighbouring
    // samples and refined by TOMS 748. Only when no sample is open (a lash just below the full
    // lift leaves a sliver narrower than the sampling) is the top refined first.
    auto gap = [&](double phi) { return rocker_ratio_ * cam_->at(phi).lift - lash_; };
    std::vector<double> xs, gs;
    for (std::size_t p = 0; p + 1 < cam_knots.size(); ++p) {
      const double a = cam_knots[p], b = cam_knots[p + 1];
      if (!(b > a)) continue;
      const double inset = 1e-13 * (b - a);
      for (int i = 0; i < samples; ++i) {
        const double x = i == 0 ? a + inset : i == samples - 1 ? b - inset : a + (b - a) * static_cast<double>(i) / (samples - 1);
        xs.push_back(x);
        gs.push_back(gap(x));
      }
    }
    evaluations += static_cast<long>(xs.size());
    std::size_t top = static_cast<std::size_t>(std::max_element(gs.begin(), gs.end()) - gs.begin());
    if (!(gs[top] > 0.0)) {
      const numerics::Extremum peak = numerics::maximize_piecewise(gap, cam_knots, samples, evaluations);
      if (!(peak.value > 0.0)) {
        std::ostringstream msg;
        msg << "the valve never opens: rocker_ratio * cam lift reaches " << (peak.value + lash_) * 1e3
            << " mm, not more than the lash of " << lash_ * 1e3 << " mm";
        throw NodeError("lash", msg.str());
      }
      top = static_cast<std::size_t>(std::upper_bound(xs.begin(), xs.end(), peak.x) - xs.begin());
      xs.insert(xs.begin() + static_cast<long>(top), peak.x);
      gs.insert(gs.begin() + static_cast<long>(top), peak.value);
    }
    auto refine = [&](std::size_t i) {  // the sign change between samples i - 1 and i
      std::uintmax_t iterations = 200;
      const auto r = boost::math::tools::toms748_solve(gap, xs[i - 1], xs[i], gs[i - 1], gs[i],
                                                       boost::math::tools::eps_tolerance<double>(std::numeric_limits<double>::digits - 3),
                                                       iterations);
      evaluations += static_cast<long>(iterations);
      return 0.5 * (r.first + r.second);
    };
    auto changes = [&](std::size_t i) { return (gs[i - 1] > 0.0 && gs[i] < 0.0) || (gs[i - 1] < 0.0 && gs[i] > 0.0); };
    std::optional<double> opening, closing;
    for (std::size_t i = 1; i <= top && !opening; ++i)
      if (changes(i)) opening = refine(i);
    for (std::size_t i = gs.size() - 1; i > top && !closing; --i)
      if (changes(i)) closing = refine(i);
    if (!opening || !closing) throw NodeError("lash", "the opening or closing angle of the valve could not be bracketed");
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
