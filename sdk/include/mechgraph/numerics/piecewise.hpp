#pragma once
// Numerics over piecewise-smooth functions of one variable: the pieces are given by sorted knots
// (the law's breakpoints plus the interval ends), inside each piece the function is smooth.
// Every routine counts the function evaluations it made, so nodes can report their work.
#include <functional>
#include <optional>
#include <span>
#include <vector>

namespace mechgraph::numerics {

using Function1D = std::function<double(double)>;

struct Extremum {
  double x = 0.0;
  double value = 0.0;
};

/// Global maximum of f on [knots.front(), knots.back()]: `samples_per_piece` uniform samples in
/// each piece (ends included, one-sided at the knots), then Brent's method around the best
/// sample of each piece to full double precision in x.
Extremum maximize_piecewise(const Function1D& f, std::span<const double> knots, int samples_per_piece,
                            long& evaluations);
Extremum minimize_piecewise(const Function1D& f, std::span<const double> knots, int samples_per_piece,
                            long& evaluations);

/// Several functions of one sample: `sample(x, values, slopes)` writes `count` values at x and,
/// where it knows them, their derivatives (NaN where it does not): the lift, velocity and
/// acceleration a law gives in one call, say, with the next derivative as slope.
using Sampler = std::function<void(double x, double* values, double* slopes)>;

/// The global maximum of each of the `count` functions: every piece sampled once for all of them
/// (`samples_per_piece` points, ends one-sided), then each function refined in the bracket of its
/// best sample, in every piece whose samples come close enough to the best that it may hold the
/// maximum (its best sample plus twice its drop to the neighbouring samples reaches the overall
/// best sample). The refinement finds the root of the slope by TOMS 748 where the slope is known
/// and changes sign in the bracket (the maximum of a smooth function), else runs Brent's method
/// on the values. To minimise, negate the value and the slope. `maxima` receives `count` results.
void maximize_piecewise_together(const Sampler& sample, std::size_t count, std::span<const double> knots,
                                 int samples_per_piece, long& evaluations, Extremum* maxima);

/// First x where f changes sign going from knots.front() to knots.back() (a bracket found by
/// sampling, then TOMS 748 to machine precision). A knot where f jumps across zero counts as a
/// root; a function that only touches zero (or stays at zero) does not change sign there.
std::optional<double> first_sign_change(const Function1D& f, std::span<const double> knots,
                                        int samples_per_piece, long& evaluations);

/// Every x where f changes sign, in ascending order (each bracket refined with TOMS 748); roots
/// closer together than the sample spacing may be missed, so pass enough samples.
std::vector<double> all_sign_changes(const Function1D& f, std::span<const double> knots, int samples_per_piece,
                                     long& evaluations);

/// Integral of f over [knots.front(), knots.back()], adaptive Gauss-Kronrod (15-point) on each
/// piece to relative tolerance `tolerance`. `error_estimate` receives the summed estimate.
double integrate_piecewise(const Function1D& f, std::span<const double> knots, double tolerance,
                           long& evaluations, double* error_estimate = nullptr);

}  // namespace mechgraph::numerics
