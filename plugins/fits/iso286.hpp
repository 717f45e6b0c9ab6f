// ISO 286-1:2010 limits and fits: standard tolerances (IT grades) and limit
// deviations of tolerance classes such as "H7" or "g6", looked up from the
// standard's tables (held as reviewed data in iso286.cpp).
//
// Units: SI. Sizes and deviations are in metres. Deviations are signed:
// for a hole, upper = ES and lower = EI; for a shaft, upper = es and lower = ei.
#pragma once

#include <string_view>

namespace mechgraph::fits {

struct LimitDeviations {
    double upper;  // ES (hole) or es (shaft), metres
    double lower;  // EI (hole) or ei (shaft), metres
};

// How the symmetric classes js7..js11 / JS7..JS11 are given when the IT value
// in micrometres is odd. ISO 286-1:2010 Table 2/3 note: such values *may* be
// rounded to the even number immediately below, i.e. +-(ITn - 1)/2, so that
// the deviations are whole micrometres.
enum class JsRounding {
    exact,             // +-ITn/2, as tabulated in ISO 286-2 (e.g. 10 js7 = +-7.5 um)
    whole_micrometre,  // +-(ITn - 1)/2 for js7..js11 when ITn is odd (10 js7 = +-7 um)
};

// Limit deviations of a tolerance class at a nominal size.
//   designation: fundamental-deviation letter(s) followed by a grade, e.g.
//   "H11", "d11", "js7", "ZC12", "h01". Upper case = hole (A..ZC), lower case
//   = shaft (a..zc). Grades: 01, 0, 1..18.
// Size ranges follow ISO 286-1; a size equal to a range limit belongs to the
// lower range (3 mm is in 0 < d <= 3 mm).
// Throws std::invalid_argument for malformed designations, sizes outside
// 0 < d <= 3150 mm, and classes the standard does not define at that size.
LimitDeviations iso286_deviations(double nominal_size_m, std::string_view designation);
LimitDeviations iso286_deviations(double nominal_size_m, std::string_view designation,
                                  JsRounding js_rounding);

// Standard tolerance of a grade ("IT01", "IT0", "IT1".."IT18") at a nominal
// size, in metres (ISO 286-1:2010 Table 1; IT01 and IT0 from Annex A, only up
// to 500 mm). Throws std::invalid_argument as above.
double iso286_standard_tolerance(double nominal_size_m, std::string_view grade);

// True for a hole class (upper-case letters), false for a shaft class.
// Throws std::invalid_argument if the designation is malformed.
bool iso286_is_hole(std::string_view designation);

}  // namespace mechgraph::fits
