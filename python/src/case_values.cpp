#include "case_values.hpp"

#include <mechgraph/errors.hpp>
#include <mechgraph/units.hpp>

#include <charconv>
#include <cmath>

namespace mechgraph::python {

std::optional<Dimension> target_dimension(const Graph& graph, std::string_view name) {
  const auto spec_dimension = [&](std::size_t node, std::string_view param) -> std::optional<Dimension> {
    const ParamSpec* spec = graph.nodes[node].info().find_param(param);
    if (!spec || spec->kind == ParamKind::record_list) return std::nullopt;
    return spec->dimension;
  };
  if (const auto dot = name.find('.'); dot != std::string_view::npos) {
    const auto node = graph.find(name.substr(0, dot));
    return node ? spec_dimension(*node, name.substr(dot + 1)) : std::nullopt;
  }
  const auto uses = graph.scene_param_uses.find(name);
  if (uses == graph.scene_param_uses.end()) return std::nullopt;
  for (const SceneParamUse& use : uses->second)
    if (!use.nested) return spec_dimension(use.node, use.param);
  return std::nullopt;
}

std::string si_text(double si, Dimension d) {
  char buffer[40];
  const auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, si, std::chars_format::general, 17);
  std::string text(buffer, end);
  if (!d.dimensionless()) text += " " + d.si_unit();
  return text;
}

CaseValue value_from_text(const std::string& text, const std::string& context) { return read_case_value(text, context); }

CaseValue value_from_si(double si, Dimension d, const std::string& context) {
  if (!std::isfinite(si)) throw SceneError(context + ": " + (std::isnan(si) ? "NaN" : "an infinite value") + " is not a value");
  return CaseValue{si_text(si, d), si, d};
}

}  // namespace mechgraph::python
