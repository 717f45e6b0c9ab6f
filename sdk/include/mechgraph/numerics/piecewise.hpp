#pragma once
// Certified searches over piecewise-smooth functions of one variable: the pieces are given by
// sorted knots (the law's breakpoints plus the interval ends), inside each piece the function is
// smooth. Every extremum, root and crossing in mechgraph goes through here.
//
// How nothing is missed (docs/methods/numerics.md): each piece is sampled at Chebyshev points,
// doubling from a starting density until the interpolant's coefficients reach a plateau of
// rounding noise (then the interpolant is the function to rounding level between the samples as
// well); pieces that do not resolve at 257 points are halved. The extrema of the interpolant are
// at its ends and at the roots of its derivative, which are found by subdivision with a bound
// that excludes a cell only when it proves there is no root in it; the best candidates are then
// evaluated on the function itself. The result does not depend on the starting density beyond
// rounding; `samples_per_piece` is only where the doubling starts (>= 3).
//
// At a knot the one-sided values belong to their pieces (the samples are pulled inside by
// one_sided_point: a relative 1e-13 of the piece, at least a few ulps of the knot), so a jump at a
// knot is seen from both sides, on a piece of any width down to two ulps. A piece with no double
// strictly inside cannot be evaluated and is skipped. Every routine counts the function
// evaluations it made.
#include <functional>
#include <optional>
#include <span>
#include <vector>

namespace mechgraph::numerics {

using Function1D = std::function<double(double)>;

/// Where the one-sided value of the piece between `from` and `to` is read at its end `from`:
/// toward `to` by 1e-13 of the width, but by at least 4 ulps of the larger end (a function tells its
/// pieces apart to a few roundings of the angle), and never past the middle (a piece of a few ulps
/// is read at its middle). A relative inset alone rounds to nothing on a piece narrower than about
/// 1e-3 of its angle: the knot itself was read then, and a jump there was seen from the wrong side.
double one_sided_point(double from, double to);

/// Whether some double lies strictly between a and b (a < b): a piece without one has no point a
/// function can be evaluated at that belongs to it alone.
bool has_interior(double a, double b);

struct Extremum {
  double x = 0.0;
  double value = 0.0;
};

/// Several functions of one sample: `sample(x, values, slopes)` writes `count` values at x (the
/// lift, velocity and acceleration a law gives in one call, say). `slopes` is scratch space of
/// `count` doubles the sampler may ignore (kept for samplers written against an earlier version).
using Sampler = std::function<void(double x, double* values, double* slopes)>;

/// What a search did, beyond its evaluations: for the work reports and the tests.
struct SearchWork {
  long evaluations = 0;   // calls of the function (or sampler)
  long pieces = 0;        // smooth pieces interpolated (after any halving)
  long unresolved = 0;    // pieces whose interpolant never reached rounding level (halved 4 times)
  long cells = 0;         // subdivision cells examined by the root searches
  int most_points = 0;    // the most points one piece needed
};

/// `count` functions sampled together, interpolated piece by piece to rounding level: build once,
/// then ask for the extrema and crossings of each. The sampler (and anything it refers to) must
/// outlive the object; the true function is evaluated again at the best candidates.
class SmoothPieces {
 public:
  SmoothPieces(Sampler sample, std::size_t count, std::span<const double> knots, int samples_per_piece);
  /// The global maximum / minimum of function j over all pieces.
  Extremum maximum(std::size_t j);
  Extremum minimum(std::size_t j);
  /// Every x where function j crosses `level` (changes sign of f_j - level), ascending; a knot
  /// where f_j jumps across the level counts; touching the level without crossing does not.
  std::vector<double> crossings(std::size_t j, double level);
  /// For each crossing of `level`, whether f_j rises through it (true) or falls (false).
  std::vector<std::pair<double, bool>> directed_crossings(std::size_t j, double level);
  const SearchWork& work() const { return work_; }

 private:
  struct Piece {
    double a = 0.0, b = 0.0;   // interpolation interval (knots pulled in by one_sided_point)
    double knot = 0.0;         // where the piece begins: the knot itself (a halving's midpoint)
    int n = 0;                 // intervals: n + 1 Chebyshev points
    std::vector<double> values;                     // (n + 1) x count, point-major, x descending
    std::vector<std::vector<double>> coefficients;  // per function, cut at its plateau
    std::vector<double> tail;                       // per function: sum |c_k| of the cut tail
    std::vector<char> resolved;                     // per function: reached rounding level
    std::vector<int> top, bottom;                   // per function: its largest and smallest sample
  };
  void resolve(double a, double b, int n, int depth);
  Extremum extreme(std::size_t j, double sign);
  double value_at(std::size_t j, double x);
  double scale(std::size_t j) const;  // max |f_j| over the samples

  Sampler sample_;
  std::size_t count_;
  std::vector<Piece> pieces_;
  std::vector<double> scratch_, slopes_;
  SearchWork work_;
};

/// Global maximum of f on [knots.front(), knots.back()] (certified, above).
Extremum maximize_piecewise(const Function1D& f, std::span<const double> knots, int samples_per_piece,
                            long& evaluations);
Extremum minimize_piecewise(const Function1D& f, std::span<const double> knots, int samples_per_piece,
                            long& evaluations);

/// The global maximum of each of the `count` functions of one sampler (certified, above). To
/// minimise, negate. `maxima` receives `count` results.
void maximize_piecewise_together(const Sampler& sample, std::size_t count, std::span<const double> knots,
                                 int samples_per_piece, long& evaluations, Extremum* maxima);

/// First x where f changes sign going from knots.front() to knots.back(). A knot where f jumps
/// across zero counts as a root; a function that only touches zero (or stays at zero) does not
/// change sign there.
std::optional<double> first_sign_change(const Function1D& f, std::span<const double> knots,
                                        int samples_per_piece, long& evaluations);

/// Every x where f changes sign, in ascending order.
std::vector<double> all_sign_changes(const Function1D& f, std::span<const double> knots, int samples_per_piece,
                                     long& evaluations);

/// Integral of f over [knots.front(), knots.back()], adaptive Gauss-Kronrod (15-point) on each
/// piece to relative tolerance `tolerance`. `error_estimate` receives the summed estimate.
double integrate_piecewise(const Function1D& f, std::span<const double> knots, double tolerance,
                           long& evaluations, double* error_estimate = nullptr);

}  // namespace mechgraph::numerics
