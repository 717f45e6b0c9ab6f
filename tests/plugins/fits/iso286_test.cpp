// Tests for the ISO 286 limits-and-fits lookup (plugins/fits/iso286.*).
#include "iso286.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

using mechgraph::fits::iso286_deviations;
using mechgraph::fits::iso286_is_hole;
using mechgraph::fits::iso286_standard_tolerance;
using mechgraph::fits::JsRounding;
using mechgraph::fits::LimitDeviations;

namespace {

constexpr double kMm = 1e-3;
constexpr double kUm = 1e-6;
constexpr double kAbs = 1e-12;  // metres

Catch::Matchers::Floating::WithinAbsMatcher near_um(double um) { return Catch::Matchers::WithinAbs(um * kUm, kAbs); }

struct Cell {
    double size_mm;
    const char* cls;
    double upper_um;
    double lower_um;
};

void check_cells(const std::vector<Cell>& cells) {
    for (const Cell& c : cells) {
        INFO(c.size_mm << " mm " << c.cls);
        const LimitDeviations d = iso286_deviations(c.size_mm * kMm, c.cls);
        CHECK_THAT(d.upper, near_um(c.upper_um));
        CHECK_THAT(d.lower, near_um(c.lower_um));
    }
}

std::string error_of(const std::function<void()>& f) {
    try {
        f();
    } catch (const std::invalid_argument& e) {
        return e.what();
    }
    return "<no std::invalid_argument thrown>";
}

// ISO 286-1 size ranges (upper limits, mm) used by the fundamental deviations.
const std::vector<double> kRangeUpperMm = {3,   6,   10,  14,  18,  24,  30,   40,   50,   65,   80,
                                           100, 120, 140, 160, 180, 200, 225,  250,  280,  315,  355,
                                           400, 450, 500, 560, 630, 710, 800,  900,  1000, 1120, 1250,
                                           1400, 1600, 1800, 2000, 2240, 2500, 2800, 3150};

const std::vector<std::string> kShaftLetters = {"a", "b", "c", "cd", "d", "e", "ef", "f", "fg", "g",
                                                "h", "js", "j", "k", "m", "n", "p", "r", "s", "t",
                                                "u", "v", "x", "y", "z", "za", "zb", "zc"};

const std::vector<std::string> kGrades = {"01", "0", "1",  "2",  "3",  "4",  "5",  "6",  "7",  "8",
                                          "9",  "10", "11", "12", "13", "14", "15", "16", "17", "18"};

int grade_number(const std::string& g) { return g == "01" ? -1 : std::stoi(g); }

std::string upper(std::string s) {
    for (char& ch : s) ch = static_cast<char>(ch - 'a' + 'A');
    return s;
}

// Sizes probed for each range: a size inside it and its upper limit itself
// (which, by the boundary rule, belongs to that range).
std::vector<double> probe_sizes_mm() {
    std::vector<double> sizes;
    double lower = 0.0;
    for (double up : kRangeUpperMm) {
        sizes.push_back((lower + up) / 2.0);
        sizes.push_back(up);
        lower = up;
    }
    return sizes;
}

// Where ISO 286-1:2010 Tables 1..3 define a tolerance class (written down
// independently of the implementation from the tables' empty cells and notes).
bool expected_defined(bool hole, const std::string& l, int n, double mm) {
    if (n <= 0 && mm > 500) return false;                   // IT01, IT0 only to 500 mm
    if ((l == "a" || l == "b") && mm <= 1) return false;    // note to Tables 2 and 3
    if ((l == "a" || l == "b" || l == "c") && mm > 500) return false;
    if ((l == "cd" || l == "ef" || l == "fg") && mm > 10) return false;
    if (l == "t" && mm <= 24) return false;
    if (l == "v" && (mm <= 14 || mm > 500)) return false;
    if (l == "y" && (mm <= 18 || mm > 500)) return false;
    if ((l == "x" || l == "z" || l == "za" || l == "zb" || l == "zc") && mm > 500) return false;
    const bool delta_zone = mm > 3 && mm <= 500;  // where Table 3 adds Delta (IT3..IT8 only)
    if (!hole) {
        if (l == "j") return ((n >= 5 && n <= 7) && mm <= 500) || (n == 8 && mm <= 3);
        return true;
    }
    if (l == "j") return n >= 6 && n <= 8 && mm <= 500;
    if (l == "k") return n <= 8 ? !(delta_zone && n < 3) : mm <= 3;
    if (l == "m") return !(delta_zone && n < 3);
    if (l == "n") return n <= 8 ? !(delta_zone && n < 3) : mm > 1;
    if (l >= "p") return !(delta_zone && n < 3);  // P..ZC (letters sort after "p")
    return true;
}

}  // namespace

TEST_CASE("iso286: limit deviations match published ISO 286-2 cells", "[fits][iso286]") {
    check_cells({
        // Examples of ISO 286-2:2010 Tables (hole H, shafts d, g, k, f, s; hole P, U, D),
        // values as printed in the standard's tables.
        {20, "H11", 130, 0},
        {20, "d11", -65, -195},
        {25, "H7", 21, 0},
        {25, "g6", -7, -20},
        {50, "k6", 18, 2},
        {30, "P7", -14, -35},
        {10, "js7", 7.5, -7.5},
        {40, "f7", -25, -50},
        {120, "s7", 114, 79},
        {400, "U7", -414, -471},
        {2500, "D11", 1580, 480},
        // ISO 286-2:1988/Cor.1:2006 corrected cells (A13 315..355, E8 80..120,
        // R10 18..30, f9 250..315 mm).
        {340, "A13", 2090, 1200},
        {100, "E8", 126, 72},
        {25, "R10", -28, -112},
        {300, "f9", -56, -186},
        // ISO 286-2 hole tables (Roymech transcription, SKF housing tables).
        {8, "K6", 2, -7},
        {280, "M6", -9, -41},  // Table 3 special case M6 250..315 mm
        {5, "M8", 2, -16},
        {45, "N7", -8, -33},
        {4, "J7", 6, -6},
        {90, "J6", 16, -6},
        {210, "R6", -71, -100},
        {390, "JS8", 44.5, -44.5},
        {300, "K8", 25, -56},
        {250, "G8", 87, 15},
        {360, "E11", 485, 125},
        {5, "K4", 0.5, -3.5},
        // ISO 286-2 shaft tables (Roymech transcription).
        {150, "r6", 90, 65},
        {350, "a12", -1200, -1770},
        {5, "e13", -20, -200},
        {60, "m5", 24, 11},
        {70, "n6", 39, 20},
        {15, "p6", 29, 18},
        {300, "h12", 0, -520},
        {50, "k5", 13, 2},
        // Key and keyway widths (ISO 286-2 via DIN 6885-1 tables): 6 and 8 mm.
        {6, "N9", 0, -30},
        {6, "P9", -12, -42},
        {6, "JS9", 15, -15},
        {6, "D10", 78, 30},
        {8, "N9", 0, -36},
        {8, "JS9", 18, -18},
        {10, "D10", 98, 40},
        // Small sizes (ISO 286-2 first column, 0 < d <= 3 mm).
        {2, "H7", 10, 0},
        {2, "N9", -4, -29},
        {1, "js9", 12.5, -12.5},
        {2, "K9", 0, -25},
        {2, "j8", 8, -6},
        {0.5, "zc11", 120, 60},
        // Large sizes (ISO 286-2 columns above 500 mm; DME Table 5 deviations).
        {1000, "h6", 0, -56},
        {600, "F7", 146, 76},
        {1500, "u6", 1678, 1600},
        {3000, "P6", -240, -375},
        {700, "M7", -30, -110},
        {2400, "R8", -460, -740},
        {3150, "g7", -38, -248},
        // Intermediate ranges and the fine letters of Table 2.
        {16, "v7", 57, 39},
        {20, "y6", 76, 63},
        {5, "cd7", -46, -58},
        {5, "ef8", -14, -32},
        {8, "FG9", 44, 8},
    });
}

TEST_CASE("iso286: standard tolerances from ISO 286-1 Table 1 and Annex A", "[fits][iso286]") {
    CHECK_THAT(iso286_standard_tolerance(1 * kMm, "IT01"), near_um(0.3));    // Annex A Table 5
    CHECK_THAT(iso286_standard_tolerance(1 * kMm, "IT0"), near_um(0.5));     // Annex A Table 5
    CHECK_THAT(iso286_standard_tolerance(500 * kMm, "IT01"), near_um(4));    // Annex A Table 5
    CHECK_THAT(iso286_standard_tolerance(3150 * kMm, "IT17"), near_um(21000));  // Table 1: 21 mm
    CHECK_THAT(iso286_standard_tolerance(3150 * kMm, "IT18"), near_um(33000));  // Table 1: 33 mm
    CHECK_THAT(iso286_standard_tolerance(150 * kMm, "IT3"), near_um(8));     // Table 1
    CHECK_THAT(iso286_standard_tolerance(150 * kMm, "IT10"), near_um(160));  // Table 1
    CHECK_THAT(iso286_standard_tolerance(25 * kMm, "IT7"), near_um(21));     // Table 1
    CHECK_THAT(iso286_standard_tolerance(1100 * kMm, "IT1"), near_um(13));   // Table 1 (>500 mm)
}

TEST_CASE("iso286: a size equal to a range limit belongs to the lower range", "[fits][iso286]") {
    CHECK_THAT(iso286_deviations(3 * kMm, "H7").upper, near_um(10));  // 0 < d <= 3
    CHECK_THAT(iso286_deviations(0.003, "H7").upper, near_um(10));
    CHECK_THAT(iso286_deviations(3.0001 * kMm, "H7").upper, near_um(12));  // 3 < d <= 6
    CHECK_THAT(iso286_deviations(10 * kMm, "js7").upper, near_um(7.5));     // 6 < d <= 10
    CHECK_THAT(iso286_deviations(10.0001 * kMm, "js7").upper, near_um(9));  // 10 < d <= 18
    CHECK_THAT(iso286_deviations(65 * kMm, "r6").lower, near_um(41));       // 50 < d <= 65
    CHECK_THAT(iso286_deviations(65.0001 * kMm, "r6").lower, near_um(43));  // 65 < d <= 80
    CHECK_THAT(iso286_standard_tolerance(500 * kMm, "IT0"), near_um(6));
    CHECK_THROWS_AS(iso286_standard_tolerance(500.001 * kMm, "IT0"), std::invalid_argument);
    CHECK_THROWS_AS(iso286_deviations(24 * kMm, "t7"), std::invalid_argument);
    CHECK_THAT(iso286_deviations(24.0001 * kMm, "t7").lower, near_um(41));
    CHECK_THROWS_AS(iso286_deviations(1 * kMm, "a9"), std::invalid_argument);
    CHECK_THAT(iso286_deviations(1.001 * kMm, "a9").upper, near_um(-270));
    CHECK_THAT(iso286_deviations(3150 * kMm, "H7").upper, near_um(210));
    CHECK_THROWS_AS(iso286_deviations(3150.001 * kMm, "H7"), std::invalid_argument);
}

TEST_CASE("iso286: js/JS rounding option for js7..js11", "[fits][iso286]") {
    const auto r = JsRounding::whole_micrometre;
    CHECK_THAT(iso286_deviations(10 * kMm, "js7", r).upper, near_um(7));     // IT7 = 15
    CHECK_THAT(iso286_deviations(10 * kMm, "js7", r).lower, near_um(-7));
    CHECK_THAT(iso286_deviations(40 * kMm, "JS7", r).upper, near_um(12));    // IT7 = 25
    CHECK_THAT(iso286_deviations(2 * kMm, "js9", r).upper, near_um(12));     // IT9 = 25
    CHECK_THAT(iso286_deviations(10 * kMm, "js6", r).upper, near_um(4.5));   // grade 6: not rounded
    CHECK_THAT(iso286_deviations(10 * kMm, "js12", r).upper, near_um(75));   // IT12 = 150
    CHECK_THAT(iso286_deviations(40 * kMm, "JS7").upper, near_um(12.5));     // default: exact
}

TEST_CASE("iso286: the whole table obeys the standard's rules", "[fits][iso286]") {
    int defined = 0;
    int undefined = 0;
    for (double mm : probe_sizes_mm()) {
        const double size = mm * kMm;
        INFO("size " << mm << " mm");

        // Standard tolerances: strictly increasing with the grade.
        double previous_it = 0.0;
        for (const std::string& g : kGrades) {
            if (grade_number(g) <= 0 && mm > 500) continue;
            const double it = iso286_standard_tolerance(size, "IT" + g);
            if (!(it > previous_it)) FAIL_CHECK("IT" << g << " = " << it << " not above the grade below");
            previous_it = it;
        }

        for (const std::string& l : kShaftLetters) {
            for (const std::string& g : kGrades) {
                const int n = grade_number(g);
                for (bool hole : {false, true}) {
                    const std::string cls = (hole ? upper(l) : l) + g;
                    INFO(cls);
                    const bool expect = expected_defined(hole, l, n, mm);
                    LimitDeviations d{};
                    bool got = true;
                    try {
                        d = iso286_deviations(size, cls);
                    } catch (const std::invalid_argument&) {
                        got = false;
                    }
                    if (got != expect) {
                        FAIL_CHECK(cls << (expect ? " should exist" : " should not exist"));
                        continue;
                    }
                    if (!got) {
                        ++undefined;
                        continue;
                    }
                    ++defined;
                    const double it = iso286_standard_tolerance(size, "IT" + g);
                    if (std::fabs((d.upper - d.lower) - it) > kAbs) {
                        FAIL_CHECK(cls << ": upper - lower = " << d.upper - d.lower << ", IT = " << it);
                    }
                    if (l == "js" && (std::fabs(d.upper + d.lower) > kAbs || std::fabs(d.upper - it / 2) > kAbs)) {
                        FAIL_CHECK(cls << " not symmetric +-IT/2");
                    }
                }
            }
        }
    }
    CHECK(defined > 50000);
    CHECK(undefined > 1000);
}

TEST_CASE("iso286: holes A..H mirror shafts a..h (EI = -es)", "[fits][iso286]") {
    const std::vector<std::string> letters = {"a", "b", "c", "cd", "d", "e", "ef", "f", "fg", "g", "h"};
    int checked = 0;
    for (double mm : probe_sizes_mm()) {
        for (const std::string& l : letters) {
            if (!expected_defined(false, l, 7, mm)) continue;
            for (const char* g : {"1", "7", "11", "18"}) {
                const auto shaft = iso286_deviations(mm * kMm, l + g);
                const auto hole = iso286_deviations(mm * kMm, upper(l) + g);
                INFO(mm << " mm " << l << g);
                CHECK_THAT(hole.lower, Catch::Matchers::WithinAbs(-shaft.upper, kAbs));
                CHECK_THAT(hole.upper, Catch::Matchers::WithinAbs(-shaft.lower, kAbs));
                ++checked;
            }
        }
    }
    CHECK(checked > 1000);
}

TEST_CASE("iso286: holes K..ZC follow ES = -ei + Delta where Table 3 applies it", "[fits][iso286]") {
    // Delta = ITn - IT(n-1) for 3 < d <= 500 mm, grades IT3..IT8 (K, M, N)
    // and IT3..IT7 (P..ZC); elsewhere ES = -ei of the same shaft letter,
    // except N above IT8 (ES = 0 for 3 < d <= 500 mm) and the M6 special case.
    // The reference shaft for K, M, N is the IT4..IT7 column (k6, m6, n6).
    const std::vector<std::string> letters = {"k", "m", "n", "p", "r", "s", "t", "u", "v",
                                              "x", "y", "z", "za", "zb", "zc"};
    int with_delta = 0;
    for (double mm : probe_sizes_mm()) {
        const double size = mm * kMm;
        for (const std::string& l : letters) {
            if (!expected_defined(false, l, 7, mm)) continue;
            const bool kmn = l == "k" || l == "m" || l == "n";
            const double ei = iso286_deviations(size, kmn ? l + "6" : l + "7").lower;
            for (int n = 3; n <= 18; ++n) {
                const std::string cls = upper(l) + std::to_string(n);
                if (!expected_defined(true, l, n, mm)) continue;
                INFO(mm << " mm " << cls);
                const double es = iso286_deviations(size, cls).upper;
                const bool delta_zone = mm > 3 && mm <= 500;
                const int max_delta_grade = kmn ? 8 : 7;
                double expected = -ei;
                if (delta_zone && n <= max_delta_grade) {
                    const double delta = iso286_standard_tolerance(size, "IT" + std::to_string(n)) -
                                         iso286_standard_tolerance(size, "IT" + std::to_string(n - 1));
                    expected = -ei + delta;
                    ++with_delta;
                    if (l == "m" && n == 6 && mm > 250 && mm <= 315) expected = -9 * kUm;  // special case
                } else if (l == "n" && n > 8 && delta_zone) {
                    expected = 0.0;
                }
                CHECK_THAT(es, Catch::Matchers::WithinAbs(expected, kAbs));
            }
        }
    }
    CHECK(with_delta > 1000);
}

TEST_CASE("iso286: standard tolerance does not decrease with size", "[fits][iso286]") {
    for (const std::string& g : kGrades) {
        double previous = 0.0;
        for (double mm : probe_sizes_mm()) {
            if (grade_number(g) <= 0 && mm > 500) break;
            const double it = iso286_standard_tolerance(mm * kMm, "IT" + g);
            INFO("IT" << g << " at " << mm << " mm");
            CHECK(it >= previous);
            previous = it;
        }
    }
}

TEST_CASE("iso286: errors name the offending input and what is valid", "[fits][iso286]") {
    using Catch::Matchers::Contains;
    const double s = 20 * kMm;

    const std::string grade = error_of([&] { iso286_deviations(s, "H19"); });
    CHECK_THAT(grade, Contains("H19") && Contains("IT19 does not exist") && Contains("IT01, IT0, IT1..IT18"));

    const std::string letter = error_of([&] { iso286_deviations(s, "zz7"); });
    CHECK_THAT(letter, Contains("zz7") && Contains("unknown fundamental deviation 'zz'") &&
                           Contains("valid shaft letters are a, b, c, cd, d, e, ef, f, fg, g, h, js, j, k, m, n, "
                                    "p, r, s, t, u, v, x, y, z, za, zb, zc"));

    const std::string hole_letter = error_of([&] { iso286_deviations(s, "Q7"); });
    CHECK_THAT(hole_letter, Contains("'Q'") && Contains("valid hole letters are A, B, C, CD"));

    CHECK_THAT(error_of([&] { iso286_deviations(s, "h"); }), Contains("'h'") && Contains("missing tolerance grade"));
    CHECK_THAT(error_of([&] { iso286_deviations(s, "7"); }),
               Contains("'7'") && Contains("missing fundamental deviation"));
    CHECK_THAT(error_of([&] { iso286_deviations(s, ""); }), Contains("empty designation"));
    CHECK_THAT(error_of([&] { iso286_deviations(s, "Js7"); }), Contains("Js7") && Contains("mixes upper and lower"));
    CHECK_THAT(error_of([&] { iso286_deviations(s, "H7x"); }), Contains("H7x") && Contains("unexpected text"));

    CHECK_THAT(error_of([&] { iso286_deviations(0.0, "H7"); }), Contains("0 mm") && Contains("0 < size <= 3150 mm"));
    CHECK_THAT(error_of([&] { iso286_deviations(4000 * kMm, "H7"); }),
               Contains("4000 mm") && Contains("0 < size <= 3150 mm"));
    CHECK_THAT(error_of([&] { iso286_deviations(-5 * kMm, "H7"); }), Contains("-5 mm"));
    CHECK_THAT(error_of([&] { iso286_standard_tolerance(0.0, "IT7"); }), Contains("0 mm"));

    CHECK_THAT(error_of([&] { iso286_standard_tolerance(600 * kMm, "IT01"); }),
               Contains("IT01") && Contains("600 mm") && Contains("up to 500 mm"));
    CHECK_THAT(error_of([&] { iso286_deviations(600 * kMm, "h01"); }),
               Contains("h01") && Contains("600 mm") && Contains("up to 500 mm"));
    CHECK_THAT(error_of([&] { iso286_standard_tolerance(s, "IT19"); }),
               Contains("IT19 does not exist (IT01, IT0, IT1..IT18)"));
    CHECK_THAT(error_of([&] { iso286_standard_tolerance(s, "7"); }), Contains("'7'") && Contains("IT7"));

    // Cells the standard leaves empty.
    CHECK_THAT(error_of([&] { iso286_deviations(1 * kMm, "a11"); }),
               Contains("a11") && Contains("not used for nominal sizes <= 1 mm"));
    CHECK_THAT(error_of([&] { iso286_deviations(1 * kMm, "N9"); }), Contains("N9") && Contains("above IT8"));
    CHECK_THAT(error_of([&] { iso286_deviations(20 * kMm, "t7"); }),
               Contains("t7") && Contains("18 < d <= 24 mm") && Contains("24 < d <= 3150 mm"));
    CHECK_THAT(error_of([&] { iso286_deviations(600 * kMm, "c11"); }), Contains("c11") && Contains("0 < d <= 500 mm"));
    CHECK_THAT(error_of([&] { iso286_deviations(20 * kMm, "cd7"); }), Contains("cd7") && Contains("0 < d <= 10 mm"));
    CHECK_THAT(error_of([&] { iso286_deviations(20 * kMm, "j9"); }), Contains("j9") && Contains("j5, j6, j7"));
    CHECK_THAT(error_of([&] { iso286_deviations(20 * kMm, "j8"); }), Contains("j8") && Contains("j8 (0 < d <= 3 mm)"));
    CHECK_THAT(error_of([&] { iso286_deviations(600 * kMm, "J7"); }), Contains("J7") && Contains("J6, J7 and J8"));
    CHECK_THAT(error_of([&] { iso286_deviations(20 * kMm, "K9"); }), Contains("K9") && Contains("above IT8"));
    CHECK_THAT(error_of([&] { iso286_deviations(20 * kMm, "P2"); }),
               Contains("P2") && Contains("Delta only for IT3..IT8"));
}

TEST_CASE("iso286: hole or shaft from the designation", "[fits][iso286]") {
    CHECK(iso286_is_hole("H7"));
    CHECK(iso286_is_hole("ZC12"));
    CHECK(iso286_is_hole("JS01"));
    CHECK_FALSE(iso286_is_hole("h7"));
    CHECK_FALSE(iso286_is_hole("js7"));
    CHECK_THROWS_AS(iso286_is_hole("zz7"), std::invalid_argument);
    CHECK_THROWS_AS(iso286_is_hole("H"), std::invalid_argument);
}
