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
