#pragma once
// The number at the start of a value's text ("8.5 mm" -> "8.5"), found as parse_quantity
// (units.hpp) finds it: spaces and tabs, a '+', then what std::from_chars reads. Never strtod,
// which reads by the process's LC_NUMERIC: in a Python session that has called
// locale.setlocale(locale.LC_ALL, "de_DE.UTF-8") it reads "8.5" as 8.
#include <cctype>
#include <charconv>
#include <cstddef>
#include <string_view>

namespace mechgraph {

/// Where the number that starts `text` ends (an index into text); 0 when no number starts it.
inline std::size_t number_prefix_end(std::string_view text) {
  std::size_t i = text.find_first_not_of(" \t");
  if (i == std::string_view::npos) return 0;
  if (text[i] == '+') ++i;
  double value = 0.0;
  const auto [end, ec] = std::from_chars(text.data() + i, text.data() + text.size(), value);
  // An out-of-range number ("1e400") still ends where its digits do, as strtod's did.
  if (ec != std::errc() && ec != std::errc::result_out_of_range) return 0;
  return static_cast<std::size_t>(end - text.data());
}

/// The text after that number without the blanks around it: the unit the value was written in
/// ("8.5 mm" -> "mm", "3.5" -> ""); "" when no number starts the text.
inline std::string_view unit_after_number(std::string_view text) {
  const std::size_t end = number_prefix_end(text);
  if (end == 0) return {};
  text.remove_prefix(end);
  const auto blank = [](char c) { return std::isspace(static_cast<unsigned char>(c)) != 0; };
  while (!text.empty() && blank(text.front())) text.remove_prefix(1);
  while (!text.empty() && blank(text.back())) text.remove_suffix(1);
  return text;
}

}  // namespace mechgraph
