#include <mechgraph/display_units.hpp>

#include <map>

#include <mechgraph/did_you_mean.hpp>
#include <mechgraph/error_subject.hpp>
#include <mechgraph/errors.hpp>
#include <mechgraph/units.hpp>

#include <algorithm>
#include <array>
#include <cstdlib>

namespace mechgraph {

const std::vector<std::pair<std::string, Dimension>>& DisplayUnits::quantities() {
  static const std::vector<std::pair<std::string, Dimension>> q{
      {"length", dim::length},         {"angle", dim::angle},
      {"mass", dim::mass},             {"time", dim::time},
      {"temperature", dim::temperature}, {"area", dim::area},
      {"velocity", dim::velocity},     {"acceleration", dim::acceleration},
      {"angular_speed", dim::angular_speed}, {"frequency", dim::frequency},
      {"force", dim::force},           {"stress", dim::stress},
      {"stiffness", dim::stiffness},   {"mass_moment_of_inertia", dim::moment_of_inertia},
  };
  return q;
}

DisplayUnits DisplayUnits::from_scene(const std::vector<std::pair<std::string, RawValue>>& units) {
  DisplayUnits out;
  std::vector<std::string> names;
  for (const auto& q : quantities()) names.push_back(q.first);
  for (const auto& [name, value] : units) {
    const auto q = std::find_if(quantities().begin(), quantities().end(), [&wanted = name](const auto& e) { return e.first == wanted; });
    if (q == quantities().end()) throw_scene_error_at(value.key_where, "units: " + unknown_name_message("quantity", name, names));
    if (value.kind != RawValue::Kind::scalar)
      throw_scene_error_at(value.where, "units: " + name + " takes one unit, e.g. " + name + ": mm");
    UnitScale scale;
    try {
      scale = parse_unit(value.text);
    } catch (const UnitError& e) {
      SourceLocation at = value.where;
      at.column += static_cast<int>(e.column());
      throw_scene_error_at(at, "units: " + name + ": " + e.what());
    }
    if (!(scale.dimension == q->second))
      throw_scene_error_at(value.where, "units: " + name + " is a " + q->second.describe() + " but '" + value.text +
                       "' is a " + (scale.dimension.dimensionless() ? std::string("pure number") : scale.dimension.describe()));
    if (scale.offset != 0.0)
      throw_scene_error_at(value.where, "units: " + name + ": '" + value.text +
                       "' has an offset (degC); results are shown in units without one, e.g. K");
    out.named_.emplace_back(q->second, value.text);
  }
  return out;
}

std::string DisplayUnits::unit_for(Dimension d) const {
  if (d.dimensionless()) return {};
  for (const auto& [dimension, unit] : named_)
    if (dimension == d) return unit;
  // Compose from the base quantities the scene names: numerator symbols joined by '*', each
  // denominator symbol after a '/' ("mm/deg^2"); a base the dimension needs but the scene does not
  // name leaves the whole value in SI.
  const std::array<std::pair<int, Dimension>, 5> bases{{{d.length, dim::length},
                                                         {d.mass, dim::mass},
                                                         {d.time, dim::time},
                                                         {d.angle, dim::angle},
                                                         {d.temperature, dim::temperature}}};
  std::string numerator, denominator;
  for (const auto& [power, base] : bases) {
    if (power == 0) continue;
    const auto it = std::find_if(named_.begin(), named_.end(), [&wanted = base](const auto& e) { return e.first == wanted; });
    if (it == named_.end()) return {};
    const int n = std::abs(power);
    const std::string term = it->second + (n == 1 ? std::string() : "^" + std::to_string(n));
    if (power > 0) numerator += (numerator.empty() ? "" : "*") + term;
    else denominator += "/" + term;
  }
  if (numerator.empty()) {
    // Only negative powers: write them as such ("s^-1"), which the parser reads back.
    std::string out;
    for (const auto& [power, base] : bases) {
      if (power == 0) continue;
      const auto it = std::find_if(named_.begin(), named_.end(), [&wanted = base](const auto& e) { return e.first == wanted; });
      out += (out.empty() ? "" : "*") + it->second + "^" + std::to_string(power);
    }
    return out;
  }
  return numerator + denominator;
}

std::string DisplayUnits::unit_for(Dimension d, const std::string& fallback) const {
  std::string u = unit_for(d);
  return u.empty() ? fallback : u;
}

std::string unit_with_reference(const std::string& unit, const std::string& reference) {
  if (reference.empty() || unit.find("deg") == std::string::npos) return unit;
  return unit + " (" + reference + ")";
}

std::string unit_without_reference(const std::string& unit) {
  const std::size_t open = unit.rfind(" (");
  if (open == std::string::npos || unit.empty() || unit.back() != ')' || unit.find("deg") >= open) return unit;
  return unit.substr(0, open);
}

const std::optional<UnitScale>& parse_unit_cached(std::string_view unit) {
  thread_local std::map<std::string, std::optional<UnitScale>, std::less<>> parsed;
  auto at = parsed.find(unit);
  if (at == parsed.end()) {
    std::optional<UnitScale> scale;
    try {
      scale = parse_unit(unit);
    } catch (const UnitError&) {
      // nullopt: the caller decides (a writer refuses the unit, a row shows the value as written)
    }
    at = parsed.emplace(std::string(unit), scale).first;
  }
  return at->second;
}

}  // namespace mechgraph
