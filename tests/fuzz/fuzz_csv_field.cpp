// Fuzz target: csv_field, the one CSV escaping function. Property: a row of fields written with
// csv_row reads back with split_csv_line as the same fields after the documented rule (csv_text:
// line breaks as spaces, a leading ' before formula-like text). The first byte separates fields.
#include <mechgraph/csv.hpp>

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const char separator = static_cast<char>(data[0]);
  std::vector<std::string> fields(1);
  for (std::size_t i = 1; i < size; ++i) {
    const char c = static_cast<char>(data[i]);
    if (c == separator) fields.emplace_back();
    else fields.back() += c;
  }
  std::vector<std::string> expected;
  for (const std::string& f : fields) {
    expected.push_back(mechgraph::csv_text(f));
    const std::string cell = mechgraph::csv_field(f);
    if (cell.find('\n') != std::string::npos || cell.find('\r') != std::string::npos) __builtin_trap();  // one line per row
    // No cell a spreadsheet reads as a formula: '-' only for a number or a lone "-".
    const std::string& text = expected.back();
    const char first = text.empty() ? '\0' : text.front();
    if (first == '=' || first == '+' || first == '@' || first == '\t' || first == '\r') __builtin_trap();
    if (first == '-' && text != "-" && text.find_first_not_of("0123456789.eE+-") != std::string::npos) __builtin_trap();
  }
  const std::string row = mechgraph::csv_row(fields);
  std::vector<std::string> back;
  try {
    back = mechgraph::split_csv_line(row);
  } catch (const std::invalid_argument&) {
    __builtin_trap();  // what csv_row writes always reads back
  }
  if (back != expected) __builtin_trap();
  return 0;
}
