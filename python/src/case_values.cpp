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

std::string yaml_quoted(std::string_view text) {
  static constexpr char hex[] = "0123456789ABCDEF";
  std::string out = "\"";
  for (std::size_t i = 0; i < text.size(); ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c == '"' || c == '\\') {
      out += '\\';
      out += static_cast<char>(c);
    } else if (c < 0x20 || c == 0x7F) {
      out += "\\x";
      out += hex[c >> 4];
      out += hex[c & 0xF];
    } else if (c == 0xC2 && i + 1 < text.size() && static_cast<unsigned char>(text[i + 1]) < 0xA0) {
      const auto c1 = static_cast<unsigned char>(text[++i]);  // U+0080..U+009F
      out += "\\u00";
      out += hex[c1 >> 4];
      out += hex[c1 & 0xF];
    } else {
      out += static_cast<char>(c);
    }
  }
  return out + "\"";
}

CaseValue value_from_text(const std::string& text, const std::string& context) { return read_case_value(text, context); }

CaseValue value_from_si(double si, Dimension d, const std::string& context) {
  if (!std::isfinite(si)) throw SceneError(context + ": " + (std::isnan(si) ? "NaN" : "an infinite value") + " is not a value");
  return CaseValue{si_text(si, d), si, d};
}

}  // namespace mechgraph::python
