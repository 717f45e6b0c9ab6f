#include <mechgraph/csv.hpp>

#include <charconv>
#include <cctype>
#include <cmath>
#include <stdexcept>

namespace mechgraph {

bool split_plain_csv_line(std::string_view line, std::vector<std::string_view>& fields) {
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  fields.clear();
  if (line.find('"') != std::string_view::npos) return false;
  for (std::size_t start = 0;;) {
    const std::size_t comma = line.find(',', start);
    fields.push_back(line.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start));
    if (comma == std::string_view::npos) return true;
    start = comma + 1;
  }
}

std::vector<std::string> split_csv_line(std::string_view line) {
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  std::vector<std::string> fields(1);
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted) {
      if (c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
        fields.back() += '"';
        ++i;
      } else if (c == '"') {
        quoted = false;
      } else {
        fields.back() += c;
      }
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      fields.emplace_back();
    } else {
      fields.back() += c;
    }
  }
  if (quoted) throw std::invalid_argument("a quoted field is not closed");
  return fields;
}

namespace {

// Whether a whole cell is a finite number as mechgraph writes them ("-2", "1.5e-3"): such a cell
// is data, not a formula, even when it starts with '-'.
bool number_cell(std::string_view text) {
  if (text.empty()) return false;
  // Only '-' as a sign: mechgraph never writes "+2", and a spreadsheet reads "+2" as a formula.
  const std::string_view digits = text.front() == '-' ? text.substr(1) : text;
  if (digits.empty() || !(std::isdigit(static_cast<unsigned char>(digits.front())) || digits.front() == '.')) return false;
  double value = 0;
  const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
  return ec == std::errc() && end == digits.data() + digits.size() && std::isfinite(value);
}

// What a spreadsheet would start a formula with (OWASP's list; CR cannot remain: it became a space).
bool formula_start(char c) { return c == '=' || c == '+' || c == '-' || c == '@' || c == '\t' || c == '\r'; }

}  // namespace

void append_csv_field(std::string& out, std::string_view text) {
  // Most cells (numbers, plain words) need nothing: appended as they are, without a copy. One
  // pass finds line breaks and what needs quotes.
  bool breaks = false, quote = false;
  for (const char c : text) {
    breaks |= c == '\n' || c == '\r';
    quote |= c == ',' || c == '"';
  }
  // As csv_text decides it: on the text with its line breaks already spaces.
  const char front = text.empty() ? ' ' : (text.front() == '\n' || text.front() == '\r') ? ' ' : text.front();
  const bool formula = formula_start(front) && text != "-" && !number_cell(text);
  if (!breaks && !formula && !quote) {
    out.append(text);
    return;
  }
  if (quote) out += '"';
  if (formula) out += '\'';
  for (char c : text) {
    if (c == '\n' || c == '\r') c = ' ';
    if (c == '"') out += '"';
    out += c;
  }
  if (quote) out += '"';
}

std::string csv_text(std::string_view text) {
  std::string out(text);
  for (char& c : out)
    if (c == '\n' || c == '\r') c = ' ';
  // A lone "-" (the report's empty-cell mark) cannot start a formula and stays as it is.
  if (!out.empty() && out != "-" && formula_start(out.front()) && !number_cell(out)) out.insert(out.begin(), '\'');
  return out;
}

std::string csv_field(std::string_view text) {
  std::string out;
  append_csv_field(out, text);
  return out;
}

std::string csv_row(const std::vector<std::string>& fields) {
  std::string out;
  for (std::size_t i = 0; i < fields.size(); ++i) {
    if (i) out += ',';
    append_csv_field(out, fields[i]);
  }
  return out;
}

std::pair<std::string, std::string> split_header(std::string_view header) {
  auto trim = [](std::string_view s) {
    while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
    while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
    return s;
  };
  header = trim(header);
  if (!header.empty() && header.back() == ']') {
    const auto open = header.rfind('[');
    if (open != std::string_view::npos && open > 0 && header[open - 1] == ' ')
      return {std::string(trim(header.substr(0, open))), std::string(trim(header.substr(open + 1, header.size() - open - 2)))};
  }
  return {std::string(header), {}};
}

}  // namespace mechgraph
