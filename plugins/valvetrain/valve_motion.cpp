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

OpenPeriod find_open_period(const CamLaw& cam, double rocker_ratio, double lash, int samples, long& evaluations) {
  ValveSearchScratch scratch;
  return find_open_period(cam, rocker_ratio, lash, samples, evaluations, scratch);
}

OpenPeriod find_open_period(const CamLaw& cam, double rocker_ratio, double lash, int samples, long& evaluations,
                            ValveSearchScratch& scratch) {
  if (lash <= 0.0) return {cam.event_begin(), cam.event_end()};
  // The valve moves while g = i h(phi) - lash > 0: the opening is the first crossing of the lash
  // (rising) and the closing the last (falling), found by the certified search over the cam's
  // smooth pieces (numerics/piecewise.hpp), whatever the ramps or the table between them do.
  // A law that declares its lift's monotone runs (CamLaw::monotone_breaks) has each crossing
  // bracketed in its run: Newton with bisection on the law, no interpolation (mechgraph/domain/cam_law_runs.hpp).
  std::optional<numerics::SmoothPieces> pieces;
  std::vector<std::pair<double, bool>>& crossings = scratch.crossings;
  const bool runs = scratch.lift.assign(cam, 0);
  if (runs) {
    scratch.lift.directed_crossings(lash / rocker_ratio, evaluations, crossings);
  } else {
    pieces.emplace([&](double phi, double* v, double*) { v[0] = rocker_ratio * cam.at(phi).lift; }, 1, cam.knots(), samples);
    crossings = pieces->directed_crossings(0, lash);
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
    numerics::Extremum peak = runs ? scratch.lift.maximum(evaluations) : pieces->maximum(0);
    if (runs) peak.value *= rocker_ratio;
    std::ostringstream msg;
    if (peak.value > lash)  // the lift passes the lash, yet no rising and later falling crossing was found
      msg << "the valve's opening and closing at a lash of " << lash * 1e3 << " mm could not be told apart (rocker_ratio * cam "
          << "lift reaches " << peak.value * 1e3 << " mm at " << peak.x * 180.0 / std::numbers::pi << " deg)";
    else
      msg << "the valve never opens: rocker_ratio * cam lift reaches " << peak.value * 1e3 << " mm, not more than the lash of "
          << lash * 1e3 << " mm";
    throw NodeError("lash", msg.str());
  }
  return {*opening, *closing};
}

ValvePeaks find_valve_peaks(const CamLaw& cam, const OpenPeriod& open, double rocker_ratio, double lash, int samples,
                            long& evaluations) {
  ValveSearchScratch scratch;
  return find_valve_peaks(cam, open, rocker_ratio, lash, samples, evaluations, scratch);
}

ValvePeaks find_valve_peaks(const CamLaw& cam, const OpenPeriod& open, double rocker_ratio, double lash, int samples,
                            long& evaluations, ValveSearchScratch& scratch, bool with_velocity) {
  // |velocity| and both acceleration extremes over the open period (each function smooth on each
  // piece; |velocity| is the larger of its two signed extremes).
  numerics::Extremum acc_max, acc_min, v_max, v_min;
  if (scratch.velocity.assign(cam, 1) && scratch.acceleration.assign(cam, 2)) {
    // The cam's monotone runs (closed form): the valve's peaks over the open period are at the
    // run ends inside it, times the rocker ratio (mechgraph/domain/cam_law_runs.hpp). The same
    // method whether the velocity is wanted or not (both runs are asked for), and each point read
    // is the law at that angle whichever run sets read it: the acceleration's peaks are the same
    // with the velocity's points read or not.
    auto scaled = [rocker_ratio](numerics::Extremum e) { return numerics::Extremum{e.x, rocker_ratio * e.value}; };
    CamLawRuns::Peaks peaks[2];
    if (with_velocity) {
      CamLawRuns::peaks({&scratch.velocity, &scratch.acceleration}, open.begin, open.end, evaluations, peaks);
      v_min = scaled(peaks[0].min);
      v_max = scaled(peaks[0].max);
    } else {
      CamLawRuns::peaks({&scratch.acceleration}, open.begin, open.end, evaluations, peaks + 1);
    }
    acc_min = scaled(peaks[1].min);
    acc_max = scaled(peaks[1].max);
  } else {
    std::vector<double> knots{open.begin};
    for (double b : cam.breakpoints())
      if (b > open.begin && b < open.end) knots.push_back(b);
    knots.push_back(open.end);
    numerics::SmoothPieces pieces(
        [&](double x, double* v, double*) {
          const LiftDerivatives d = valve_lift_at(cam, open, rocker_ratio, lash, x);
          v[0] = d.velocity;
          v[1] = d.acceleration;
        },
        2, knots, samples);
    acc_max = pieces.maximum(1);
    acc_min = pieces.minimum(1);
    v_max = pieces.maximum(0);
    v_min = pieces.minimum(0);
    evaluations += pieces.work().evaluations;
  }
  const numerics::Extremum velocity = -v_min.value > v_max.value ? numerics::Extremum{v_min.x, -v_min.value} : v_max;
  return {velocity, acc_max, acc_min};
}

CamValveMotion::CamValveMotion(std::shared_ptr<const CamLaw> cam, double camshaft_speed, double rocker_ratio, double lash,
                               int samples, long& evaluations)
    : CamValveMotion(cam, camshaft_speed, rocker_ratio, lash, find_open_period(*cam, rocker_ratio, lash, samples, evaluations)) {}

CamValveMotion::CamValveMotion(std::shared_ptr<const CamLaw> cam, double camshaft_speed, double rocker_ratio, double lash,
                               OpenPeriod open)
    : cam_(std::move(cam)), camshaft_speed_(camshaft_speed), rocker_ratio_(rocker_ratio), lash_(lash),
      open_begin_(open.begin), open_end_(open.end) {
  knots_.push_back(open_begin_);
  for (double b : cam_->breakpoints())
    if (b > open_begin_ && b < open_end_) knots_.push_back(b);
  knots_.push_back(open_end_);
}

LiftDerivatives CamValveMotion::at(double phi) const {
  // Open between the crossings found at construction; there the valve follows the cam (the lift
  // clipped at 0 against rounding right at the crossings), elsewhere it rests on its seat.
  return valve_lift_at(*cam_, {open_begin_, open_end_}, rocker_ratio_, lash_, phi);
}

}  // namespace mechgraph::valvetrain
