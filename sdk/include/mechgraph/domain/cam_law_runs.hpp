#pragma once
// Extrema and crossings of a cam law's lift or derivative from its monotone runs
// (CamLaw::monotone_breaks; docs/methods/numerics.md, "Closed-form queries").
//
// On a run [e_i, e_i+1] the function f = h^(order) is continuous and monotone, so
//  - its extremes over [a, b] are among f(a), f(b) and the one-sided values at the cuts inside;
//  - a crossing of a level inside a run is bracketed by the run's ends (one sign change at most)
//    and found on the law itself (Halley's steps on the next two derivatives, safeguarded by
//    bisection); where f jumps across the level at a cut, the cut is the crossing.
// One-sided values at a cut are read where the generic search reads its knots
// (numerics::one_sided_point: 1e-13 of the run's width inside, at least 4 ulps of the angle, at
// most the middle), so both paths agree on a jump to rounding on runs of any width from two ulps;
// a run with no double strictly inside is skipped (it has no angle of its own).
// Everything is certified by the law's declaration alone; the conformance kit checks it.
#include <mechgraph/domain/cam_law.hpp>
#include <mechgraph/numerics/piecewise.hpp>

#include <initializer_list>
#include <optional>
#include <utility>
#include <vector>

namespace mechgraph {

class CamLawRuns {
 public:
  /// The runs of h^(order) (0: lift, 1: velocity, 2: acceleration) over the whole event, or
  /// nullopt when the law does not declare them (then use numerics::SmoothPieces).
  static std::optional<CamLawRuns> of(const CamLaw& law, int order);
  /// Runs to be filled by assign(): storage a block path reuses from case to case (of() makes a
  /// vector per law). Not to be searched before assign() has returned true.
  CamLawRuns() = default;
  /// The runs of h^(order) of `law`, as of() makes them, into this object's storage (no
  /// allocation once it has held as many cuts); false, and nothing to search, where of() gives nullopt.
  bool assign(const CamLaw& law, int order);

  /// Greatest / least h^(order) over [a, b] inside the event (a < b).
  numerics::Extremum maximum(double a, double b, long& evaluations) const { return extreme(a, b, 1.0, evaluations); }
  numerics::Extremum minimum(double a, double b, long& evaluations) const { return extreme(a, b, -1.0, evaluations); }
  /// Over the whole event.
  numerics::Extremum maximum(long& evaluations) const { return maximum(edges_.front(), edges_.back(), evaluations); }
  numerics::Extremum minimum(long& evaluations) const { return minimum(edges_.front(), edges_.back(), evaluations); }
  /// The least and greatest value over [a, b] of each of several run sets of one law (e.g. the
  /// velocity's and the acceleration's), from one evaluation per distinct point read: the orders
  /// share their cuts more often than not, and one evaluation gives every derivative.
  struct Peaks {
    numerics::Extremum min, max;
  };
  static std::vector<Peaks> peaks(std::initializer_list<const CamLawRuns*> runs, double a, double b, long& evaluations);
  /// The same into out[0 .. runs.size()) (no allocation).
  static void peaks(std::initializer_list<const CamLawRuns*> runs, double a, double b, long& evaluations, Peaks* out);
  /// Every angle of the event where h^(order) crosses `level` (its sign of f - level changes,
  /// zeros skipped), ascending, with true where it rises through it; as
  /// numerics::SmoothPieces::directed_crossings.
  std::vector<std::pair<double, bool>> directed_crossings(double level, long& evaluations) const;
  /// The same into `found` (emptied first; its storage reused from call to call).
  void directed_crossings(double level, long& evaluations, std::vector<std::pair<double, bool>>& found) const;

 private:
  CamLawRuns(const CamLaw& law, int order, std::vector<double> edges) : law_(&law), order_(order), edges_(std::move(edges)) {}
  double value(double x) const;
  double value_of(const LiftDerivatives& d) const {
    return order_ == 0 ? d.lift : order_ == 1 ? d.velocity : d.acceleration;
  }
  /// The crossing of `level` inside one run between a and b, where g = h^(order) - level is ga and gb
  /// of opposite signs.
  double root_in_run(double level, double a, double b, double ga, double gb, long& evaluations) const;
  /// The same, started where the Taylor polynomial of h^(order) at the end nearer the level (its
  /// derivatives da, db, read by the walk) crosses it: a root near a run's end (the valve's opening
  /// and closing, a lash above the foot of the lift) then takes one or two of the law's evaluations.
  double root_in_run(double level, double a, double b, const LiftDerivatives& da, const LiftDerivatives& db,
                     long& evaluations) const;
  numerics::Extremum extreme(double a, double b, double sign, long& evaluations) const;

  const CamLaw* law_ = nullptr;
  int order_ = 0;
  std::vector<double> edges_;  // event_begin, the cuts, event_end
};

}  // namespace mechgraph
