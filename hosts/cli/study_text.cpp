#include "study_text.hpp"

#include <charconv>

namespace mechgraph::cli {

std::string study_number(double x) {
  char buffer[32];
  const auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, x, std::chars_format::general, 6);
  return std::string(buffer, end);
}

std::string study_number(const std::optional<double>& x) { return x ? study_number(*x) : "-"; }

std::string study_interval(const Interval& i) { return "[" + study_number(i.lower) + ", " + study_number(i.upper) + "]"; }

std::string study_unit(const StudyColumn& c) {
  const std::string u = !c.shown.empty() ? c.shown : c.unit.empty() ? c.dimension.si_unit() : c.unit;
  return u == "1" ? "" : u;
}

std::string moments_text(const Moments& m) {
  return "mean " + study_number(m.mean) + " " + study_interval(m.mean_interval) + ", standard deviation " +
         study_number(m.standard_deviation) + ", min " + study_number(m.min) + ", max " + study_number(m.max);
}

std::string capability_text(const OutputAnswer& o) {
  const Capability& c = *o.capability;
  const auto per_million = [](const std::optional<double>& x) { return x ? std::optional<double>(1e6 * *x) : std::nullopt; };
  return "spec [" + study_number(o.lower) + ", " + study_number(o.upper) + "]: Cp " + study_number(c.cp) + ", Cpk " +
         study_number(c.cpk) + ", out of spec " + study_number(1e6 * c.out_of_spec.estimate) + " ppm " +
         study_interval({per_million(c.out_of_spec.wilson.lower), per_million(c.out_of_spec.wilson.upper)}) + " (" +
         std::to_string(c.below) + " below, " + std::to_string(c.above) + " above; normal model " + study_number(c.ppm_normal) + " ppm)" +
         (c.failed == 0 ? std::string()
                        : "; with the " + std::to_string(c.failed) + " failed counted out of spec " +
                              study_number(1e6 * c.out_of_spec_or_failed.estimate) + " ppm " +
                              study_interval({per_million(c.out_of_spec_or_failed.wilson.lower),
                                              per_million(c.out_of_spec_or_failed.wilson.upper)}));
}

}  // namespace mechgraph::cli
