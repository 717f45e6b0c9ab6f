#pragma once
// Numbers as a person reads them (the terminal, the report page, Python's display): six significant
// digits, and a value that is rounding noise beside what it is shown with printed as 0.
//
// Rounding noise is what a difference of nearly equal numbers keeps: the midpoint of two events at
// -52.7 deg and +52.7 deg comes out as 3.5e-11 deg, the error of its operands, not a position. A value smaller than `noise_ratio` times the largest magnitude of the
// same quantity shown beside it is below every tolerance a node computes to (root finds, integrators
// and certified searches stop at 1e-10 relative at best) and is shown as 0. An angle is also measured
// against a full turn, so that an angle of 9e-15 deg shown alone reads 0. Data files (CSV,
// JSON) keep every digit: this is presentation only.
#include <string>

#include "mechgraph/dimension.hpp"
#include "mechgraph/value.hpp"

namespace mechgraph {

inline constexpr double noise_ratio = 1e-9;

/// The magnitude (SI) below which a value of `dimension` is rounding noise when it is shown beside
/// values up to `largest_si` in magnitude (0: shown alone).
double noise_floor(const Dimension& dimension, double largest_si);

/// The largest finite magnitude (SI) of the columns of `table` (axis included) of `dimension`: the
/// scale a table's value of that dimension is read against.
double table_largest(const Table& table, const Dimension& dimension);

/// `shown` (the value in the unit it is printed in) as "%.6g" text; "0" when its SI value `si` is
/// below `floor` in magnitude (and for -0).
std::string shown_number(double shown, double si, double floor);

}  // namespace mechgraph
