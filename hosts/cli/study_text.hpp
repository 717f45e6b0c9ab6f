#pragma once
// The figures of an uncertainty study's answers as text, one writing for the terminal
// (`mechgraph study`) and the page (study_page.hpp): numbers to 6 significant digits, an absent
// bound as "-", so that both show the same figures in the same words.
#include <mechgraph/uncertainty/study_answers.hpp>

#include <optional>
#include <string>

namespace mechgraph::cli {

std::string study_number(double x);
std::string study_number(const std::optional<double>& x);  // "-" when absent
std::string study_interval(const Interval& i);                // "[lower, upper]"
/// The unit an output is shown in ("" for a plain number).
std::string study_unit(const StudyColumn& c);
/// "mean M [lo, hi], standard deviation S, min A, max B".
std::string moments_text(const Moments& m);
/// "spec [LSL, USL]: Cp .., Cpk .., out of spec N ppm [lo, hi] (b below, a above; normal model P ppm)",
/// and where samples failed "; with the F failed counted out of spec M ppm [lo, hi]"; for an
/// output with limits (o.capability).
std::string capability_text(const OutputAnswer& o);

}  // namespace mechgraph::cli
