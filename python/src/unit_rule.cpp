#include "unit_rule.hpp"

#include <mechgraph/display_units.hpp>
#include <mechgraph/errors.hpp>
#include <mechgraph/number_prefix.hpp>
#include <mechgraph/units.hpp>

#include <charconv>
#include <cmath>
#include <cstdlib>

namespace mechgraph::python {
namespace {

const RawValue* find_value(const std::vector<std::pair<std::string, RawValue>>& values, std::string_view name) {
  for (const auto& [key, value] : values)
    if (key == name) return &value;
  return nullptr;
}

// The unit part of "8 mm" ("mm"), if it is of dimension `d`; "" otherwise.
std::string written_unit(const std::string& text, Dimension d) {
  const std::string unit(unit_after_number(text));
  if (unit.empty()) return {};
  try {
    return parse_unit(unit).dimension == d ? unit : std::string();
  } catch (const UnitError&) {
    return {};
  }
}

}  // namespace

std::string scene_unit(const SceneSpec& scene, std::string_view name, Dimension d) {
  const RawValue* value = nullptr;
  if (const auto dot = name.find('.'); dot != std::string_view::npos) {
    for (const NodeSpec& node : scene.nodes)
      if (node.name == name.substr(0, dot)) value = find_value(node.params, name.substr(dot + 1));
  } else {
    value = find_value(scene.params, name);
  }
  if (value && value->kind == RawValue::Kind::scalar && !value->text.empty() && value->text[0] == '$')
    value = find_value(scene.params, std::string_view(value->text).substr(1));
  if (value) {
    const RawValue& first = value->kind == RawValue::Kind::list && !value->items.empty() ? value->items.front() : *value;
    if (first.kind == RawValue::Kind::scalar)
      if (std::string unit = written_unit(first.text, d); !unit.empty()) return unit;
  }
  try {
    if (std::string unit = DisplayUnits::from_scene(scene.units).unit_for(d); !unit.empty()) return unit;
  } catch (const SceneError&) {
    // a scene whose units: are wrong does not build; SI below
  }
  return d.si_unit();
}

std::string bare_number_refusal(const std::string& context, std::string_view name, std::string_view given, Dimension d,
                                const std::string& unit, BareKind kind) {
  const std::string n(name), si = d.si_unit();
  const std::string what = n + " has dimension " + d.describe() + " (the scene's unit: " + unit +
                           (unit == si ? "" : "; SI: " + si) + ")";
  switch (kind) {
    case BareKind::number:
      return context + ": " + std::string(given) + " is a bare number, but " + what + ". Give its unit: \"" +
             std::string(given) + " " + unit + "\", (" + std::string(given) + ", \"" + unit +
             "\") or a pint quantity; or mark a number in SI: mechgraph.si(...) or si=True";
    case BareKind::array:
      return context + ": an array of bare numbers, but " + what + ". Give its unit: (values, \"" + unit +
             "\") or a pint quantity; or mark numbers in SI: mechgraph.si(values) or si=True";
    case BareKind::column:
      return context + ": numbers without a unit, but " + what + ". Name the unit in the header ('" + n + " [" + unit +
             "]'), give (values, \"" + unit + "\") or a pint quantity, or mark numbers in SI: mechgraph.si(values) or si=True";
  }
  return context;
}

ErrorSubject subject_of(std::string_view name) {
  const auto dot = name.find('.');
  if (dot == std::string_view::npos) return {{}, {}, std::string(name)};
  return {{}, std::string(name.substr(0, dot)), std::string(name.substr(dot + 1))};
}

std::string number_text(double x) {
  char buffer[40];
  const auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, x);
  return std::string(buffer, end);
}

std::vector<double> values_in_si(const std::vector<double>& values, const std::string& unit, Dimension expected,
                                 const std::string& context) {
  UnitScale u;
  try {
    u = parse_unit(unit);
  } catch (const UnitError& e) {
    throw SceneError(context + ": unit '" + unit + "': " + e.what());
  }
  if (!(u.dimension == expected))
    throw SceneError(context + ": unit '" + unit + "' is " + (u.dimension.dimensionless() ? "dimensionless" : u.dimension.describe()) +
                     ", the parameter is " + (expected.dimensionless() ? "dimensionless" : expected.describe()));
  std::vector<double> out(values.size());
  for (std::size_t i = 0; i < values.size(); ++i) {
    out[i] = (values[i] + u.offset) * u.scale;  // as parse_quantity computes "x unit"
    if (!std::isfinite(out[i])) throw SceneError(context + ": element " + std::to_string(i) + " is not a finite number in SI");
  }
  return out;
}

}  // namespace mechgraph::python
