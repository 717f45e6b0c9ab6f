#pragma once
// Extremes and zero crossings of a smooth quantity q(t) inside one integration step, found on the
// integrator's dense output instead of at the step's ends or an output grid (docs/methods/
// valvetrain.md, "Extremes and events from the dense output").
//
// q and its rate q' are known at the ends a, b of the step. Between them:
//  - q' changes sign: one interior turning point. For a q that is concave (a maximum) or convex (a
//    minimum) across the step, the tangents at the ends bound it:
//      t_x = (q_b - q_a + q'_a a - q'_b b) / (q'_a - q'_b),   bound = q_a + q'_a (t_x - a),
//    and the turning point is refined (TOMS 748 on q', to a bracket sqrt(rtol) of the step wide, so
//    the extremum's value is off by about rtol q'' h^2) only where that bound could matter.
//  - q' has one sign at both ends: q is taken monotone, unless the cubic Hermite interpolant of
//    (q, q') at the ends turns twice inside; then q' is sampled between its turns and each piece is
//    looked at as above.
// A crossing is a fall of q from above zero to zero or below (a rise is the fall of -q); a start
// at zero counts as above when q' > 0 there, so a hop that leaves zero and comes back inside one
// step is a crossing too.
#include <array>
#include <optional>
#include <type_traits>

namespace mechgraph::valvetrain {

struct Sample {
  double t = 0.0;
  double value = 0.0;
  double rate = 0.0;  // dq/dt
};

/// q and q' at a time inside the step (from the dense output): a reference to a callable
/// Sample(double t) that outlives it (not owned, nothing allocated: probes are made every step).
class Probe {
 public:
  template <class F, class = std::enable_if_t<!std::is_same_v<std::decay_t<F>, Probe>>>
  Probe(const F& f) : object_(&f), call_([](const void* o, double t) { return (*static_cast<const F*>(o))(t); }) {}
  Sample operator()(double t) const { return call_(object_, t); }

 private:
  const void* object_;
  Sample (*call_)(const void*, double);
};

/// A step cut where q' may change sign: 2 or 3 samples in time order.
struct Pieces {
  std::array<Sample, 3> at;
  std::size_t size = 2;
};

struct SearchWork {
  long evaluations = 0;  // probes called
  long refinements = 0;  // turning points and crossings refined
};

class DenseSearch {
 public:
  /// `rtol`: the integration's relative tolerance (sets how narrowly turning points are bracketed).
  explicit DenseSearch(double rtol);

  /// [a, b] as pieces on each of which q' changes sign at most once: {a, b}, or {a, m, b} with q
  /// sampled at m between the Hermite interpolant's two turns.
  Pieces pieces(const Sample& a, const Sample& b, const Probe& q, SearchWork& work) const;

  /// On a piece whose q' falls from + to -: the interior maximum, refined when the tangent bound
  /// exceeds `beat` (otherwise it cannot beat it, and nullopt).
  std::optional<Sample> interior_max(const Sample& a, const Sample& b, double beat, const Probe& q, SearchWork& work) const;
  /// On a piece whose q' rises from - to +: the interior minimum, refined when the bound is below `beat`.
  std::optional<Sample> interior_min(const Sample& a, const Sample& b, double beat, const Probe& q, SearchWork& work) const;

  /// The first time in (a, b] at which q falls from above zero to zero or below, to full precision
  /// (the time returned is on the side that has fallen), or nullopt.
  std::optional<double> first_fall(const Sample& a, const Sample& b, const Probe& q, SearchWork& work) const;

  /// The tangent bound of a piece whose q' changes sign (see above).
  static double tangent_bound(const Sample& a, const Sample& b);

 private:
  std::optional<double> fall_in_piece(Sample a, const Sample& b, const Probe& q, SearchWork& work) const;
  Sample refine_turn(const Sample& a, const Sample& b, bool maximum, const Probe& q, SearchWork& work) const;
  double root(const Sample& above, const Sample& below, const Probe& q, SearchWork& work) const;
  double relative_width_;
};

}  // namespace mechgraph::valvetrain
