#include <mechgraph/sweep/case_table.hpp>

#include <mechgraph/csv.hpp>
#include <mechgraph/display_units.hpp>
#include <mechgraph/bounded_read.hpp>
#include <mechgraph/errors.hpp>
#include <mechgraph/large_arrays.hpp>
#include <mechgraph/number_prefix.hpp>
#include <mechgraph/printf_g15.hpp>
#include <mechgraph/text_escape.hpp>
#include <mechgraph/units.hpp>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <limits>
#include <map>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <numeric>
#include <optional>
#include <sstream>
#include <string_view>
#include <unordered_set>

namespace mechgraph {
namespace {

// `s` without the white space at its ends (a view into it).
std::string_view trimmed_view(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return s;
}
std::string trim(std::string_view s) { return std::string(trimmed_view(s)); }

// "5600 rpm" -> "rpm"; "3.5" -> ""; the unit a value was written in, to show the column in it.
std::string unit_of(const std::string& text) { return std::string(unit_after_number(text)); }

bool bare_number(const std::string& text) { return number_prefix_end(text) != 0 && unit_after_number(text).empty(); }

}  // namespace

CaseValue read_case_value(const std::string& text, const std::string& context) {
  CaseValue v{text, std::nullopt, {}};
  try {
    const Quantity q = parse_quantity(text);
    v.si = q.value;
    v.dimension = q.dimension;
  } catch (const UnitError&) {
  }
  if (v.si && !std::isfinite(*v.si)) throw SceneError(context + ": '" + excerpt(text) + "' is not a finite number");
  return v;
}

namespace {

// The point a fraction `t` of the way from `low` to `high`. The plain form when the span is a
// finite number (the points sweeps always had); the weighted form when `high - low` overflows
// (-1e308 m to 1e308 m), which stays finite between finite ends.
double between(double low, double high, double t) {
  const double span = high - low;
  if (std::isfinite(span)) return low + span * t;
  return low * (1.0 - t) + high * t;
}

void require_finite(double x, const std::string& context) {
  if (!std::isfinite(x)) throw SceneError(context + ": a generated value is not a finite number");
}

// The shortest digits that read back to x, laid out as printf's %g lays out that many (at least
// 15): where x has 15 significant digits or fewer this is exactly "%.15g" of x (rounded to 15
// digits x is those digits, the nearest such decimal by far), what rows always held; else its 16
// or 17 digits. From std::to_chars' shortest scientific text, rearranged.
void append_shortest_g(std::string& out, double x) {
  char buffer[40];
  const auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, x, std::chars_format::scientific);
  std::string_view text(buffer, static_cast<std::size_t>(end - buffer));
  const std::size_t e = text.find('e');
  int exponent = 0;
  const char* exponent_begin = text.data() + e + 1 + (text[e + 1] == '+' ? 1 : 0);
  std::from_chars(exponent_begin, text.data() + text.size(), exponent);
  const bool negative = text.front() == '-';
  const std::string_view mantissa = text.substr(negative ? 1 : 0, e - (negative ? 1 : 0));  // "d" or "d.ddd"
  char digits[24];
  std::size_t n = 0;
  for (const char c : mantissa)
    if (c != '.') digits[n++] = c;
  const int precision = std::max(15, static_cast<int>(n));
  if (exponent < -4 || exponent >= precision) {  // %g's scientific layout: to_chars' own
    out.append(text);
    return;
  }
  if (negative) out += '-';
  if (exponent < 0) {
    out += "0.";
    out.append(static_cast<std::size_t>(-exponent - 1), '0');
    out.append(digits, n);
  } else if (static_cast<std::size_t>(exponent) + 1 >= n) {
    out.append(digits, n);
    out.append(static_cast<std::size_t>(exponent) + 1 - n, '0');
  } else {
    out.append(digits, static_cast<std::size_t>(exponent) + 1);
    out += '.';
    out.append(digits + exponent + 1, n - static_cast<std::size_t>(exponent) - 1);
  }
}

// The double a short decimal text reads as, where that is one exact operation (Clinger's fast
// path: at most 15 digits, an integer below 2^53, times or over a power of ten up to 10^22, both
// exact, so the one rounding is the correct one, as from_chars gives), else from_chars. A few dozen
// instructions for the texts "%.15g" makes, where from_chars takes about 400.
double read_decimal(std::string_view text) {
  static constexpr double powers[] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,  1e8,  1e9,  1e10, 1e11,
                                      1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};
  std::size_t i = 0;
  const bool negative = !text.empty() && text[0] == '-';
  if (negative) ++i;
  std::uint64_t mantissa = 0;
  int digits = 0, scale = 0;
  bool point = false;
  for (; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '.') {
      point = true;
    } else if (c >= '0' && c <= '9') {
      mantissa = mantissa * 10 + static_cast<std::uint64_t>(c - '0');
      if (mantissa != 0) ++digits;
      if (point) --scale;
    } else {
      break;
    }
  }
  if (i == text.size() && digits <= 15 && scale >= -22) {
    const double m = static_cast<double>(mantissa);  // exact: below 10^15 < 2^53
    const double x = scale == 0 ? m : m / powers[-scale];
    return negative ? -x : x;
  }
  double y = std::nan("");
  std::from_chars(text.data(), text.data() + text.size(), y);
  return y;
}

// The double nearest x (x itself, else its neighbours out to 8 ulps) that `reads_back` takes, if
// any: where x = si / scale - offset was rounded, a neighbour may be the one that multiplies back.
template <class ReadsBack>
std::optional<double> nearest_reading_back(double x, const ReadsBack& reads_back) {
  if (reads_back(x)) return x;
  double below = x, above = x;
  for (int step = 0; step < 8; ++step) {
    above = std::nextafter(above, std::numeric_limits<double>::infinity());
    if (reads_back(above)) return above;
    below = std::nextafter(below, -std::numeric_limits<double>::infinity());
    if (reads_back(below)) return below;
  }
  return std::nullopt;
}

// A number of a row's inputs: text that reads back to the case's own double through the column's
// unit (`reads_back`: (text + offset) * scale == si, as the cases reader takes a bare number under
// a unit), so that a row reproduces its case exactly. printf's "%.15g" of x where it does (the
// common case, and what rows always held: it also sheds the noise of si / scale - offset, 8.41 mm
// shown as 8.41), else the shortest digits of x (append_shortest_g), else of the double nearest x
// that reads back (x is rounded, and a neighbour may be the one that multiplies back to si).
// False, with nothing appended, when no double within 8 ulps of x does: a value made in SI (a
// grid's point, a sample) that the column's unit cannot express.
template <class ReadsBack>
bool append_shown_number(std::string& out, double x, const ReadsBack& reads_back) {
  const std::size_t at = out.size();
  append_printf_g15(out, x);
  if (reads_back(read_decimal(std::string_view(out).substr(at)))) return true;
  out.resize(at);
  const std::optional<double> z = nearest_reading_back(x, reads_back);
  if (z) append_shortest_g(out, *z);
  return z.has_value();
}

// An offset unit's x = si / scale - offset carries the rounding of its subtraction in its last
// digits (8.41 degC shows as 8.410000000000025): the fewest significant digits, up to 15, that
// still read back to the case's double, so that the row shows the value as it was written.
template <class ReadsBack>
bool append_fewest_digits(std::string& out, double x, const ReadsBack& reads_back) {
  char buffer[48];
  const auto with = [&](int digits) -> std::string_view {
    const auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, x, std::chars_format::general, digits);
    return ec == std::errc() ? std::string_view(buffer, static_cast<std::size_t>(end - buffer)) : std::string_view();
  };
  const auto fits = [&](int digits) {
    const std::string_view text = with(digits);
    return !text.empty() && reads_back(read_decimal(text));
  };
  // From as many digits as the integer part has (fewer would switch to the exponent form,
  // 1.2e+02) to 15; none if 15 do not read back. The fewest that do, by bisection (more digits
  // come nearer x, so once they read back they keep doing so, but for the odd rounding a
  // bisection may step over: what it finds reads back, checked).
  int low = std::clamp(std::abs(x) >= 1.0 ? static_cast<int>(std::floor(std::log10(std::abs(x)))) + 1 : 1, 1, 15), high = 15;
  if (!fits(high)) return false;
  while (low < high) {
    const int middle = (low + high) / 2;
    if (fits(middle)) high = middle;
    else low = middle + 1;
  }
  out.append(with(high));
  return true;
}

// Whether a cell's text is a number as JSON writes one (-?(0|[1-9]d*)(.d+)?([eE][+-]?d+)?): such a
// cell is shown as written, a plain number in CSV and JSON Lines alike; "+8", ".5", "08" or "5."
// are shown as mechgraph writes numbers instead.
bool json_number(std::string_view t) {
  std::size_t i = 0;
  const auto digits = [&] {
    const std::size_t from = i;
    while (i < t.size() && t[i] >= '0' && t[i] <= '9') ++i;
    return i > from;
  };
  if (i < t.size() && t[i] == '-') ++i;
  if (i < t.size() && t[i] == '0') ++i;
  else if (!(i < t.size() && t[i] >= '1' && t[i] <= '9') || !digits()) return false;
  if (i < t.size() && t[i] == '.' && (++i, !digits())) return false;
  if (i < t.size() && (t[i] == 'e' || t[i] == 'E')) {
    ++i;
    if (i < t.size() && (t[i] == '+' || t[i] == '-')) ++i;
    if (!digits()) return false;
  }
  return i == t.size();
}

}  // namespace

std::string exact_text(double x, const Dimension& d) {
  std::string text;
  append_exact_text(text, x, exact_text_unit(d));
  return text;
}

std::string exact_text_unit(const Dimension& d) { return d.dimensionless() ? std::string() : d.si_unit(); }

void append_exact_text(std::string& out, double x, std::string_view si_unit) {
  // The shortest digits that read back as x (std::to_chars without a precision), then the unit.
  char buffer[40];
  const auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, x);
  out.append(buffer, end);
  if (!si_unit.empty()) out.append(1, ' ').append(si_unit);
}

double expressible_in(double si, const std::string& unit) {
  return unit.empty() ? si : expressible_in(si, parse_unit_cached(unit));
}

double expressible_in(double si, const std::optional<UnitScale>& u) {
  if (!u || !std::isfinite(si)) return si;
  const double scale = u->scale, offset = u->offset;
  const auto reads_back = [&](double y) { return (y + offset) * scale == si; };
  const double x = si / scale - offset;
  if (!std::isfinite(x) || nearest_reading_back(x, reads_back)) return si;
  const double on = (x + offset) * scale;
  return std::isfinite(on) ? on : si;
}

std::string CaseValue::written() const { return !text.empty() || !si ? text : exact_text(*si, dimension); }

std::string_view CaseTable::Numbers::Written::given_text(double x, Digits& digits) {
  const auto printed = std::to_chars(digits.data(), digits.data() + digits.size(), x, std::chars_format::general, 17);
  return std::string_view(digits.data(), static_cast<std::size_t>(printed.ptr - digits.data()));
}

void CaseTable::Numbers::Written::append(std::string& out, std::size_t k, std::size_t v) const {
  Digits digits;
  out.append(own_text(k, digits));
  if (in_column_unit[k]) {
    out.push_back(' ');
    out.append(column_units[v]);
  }
}

void CaseTable::Numbers::Written::ValueDimensions::push_back(const Dimension& d, std::size_t width) {
  const std::size_t k = count_++;
  if (!each_.empty() || width == 0) {  // no columns to share (never so in a table with values): each its own
    each_.push_back(d);
    return;
  }
  if (k < width) {
    if (k == 0) column_.reserve(width);
    column_.push_back(d);
    return;
  }
  if (d == column_[k % width]) return;
  // The first value unlike its column's: from here every value keeps its own.
  each_.reserve(2 * count_);
  for (std::size_t j = 0; j < k; ++j) each_.push_back(column_[j % width]);
  each_.push_back(d);
}

void CaseTable::keep_written(std::string_view text, bool in_column_unit, double si, const Dimension& dimension) {
  Numbers::Written& w = numbers.written;
  w.text.append(text);
  w.ends.push_back(static_cast<std::uint32_t>(w.text.size()));
  w.in_column_unit.push_back(in_column_unit ? Numbers::Written::bare_number : Numbers::Written::as_written);
  w.dimensions.push_back(dimension, numbers.dimensions.size());
  numbers.si.push_back(si);
  if (!w.given.empty()) w.given.push_back(std::numeric_limits<double>::quiet_NaN());
}

void CaseTable::keep_given(double x, double si, const Dimension& dimension) {
  Numbers::Written& w = numbers.written;
  w.given.resize(w.ends.size(), std::numeric_limits<double>::quiet_NaN());  // the values before it, if none was given
  w.given.push_back(x);
  w.ends.push_back(static_cast<std::uint32_t>(w.text.size()));  // no text of its own
  w.in_column_unit.push_back(Numbers::Written::given_number);
  w.dimensions.push_back(dimension, numbers.dimensions.size());
  numbers.si.push_back(si);
}

void CaseTable::keep_written(const CaseValue& value, std::string_view cell, std::size_t v) {
  const std::string& unit = numbers.written.column_units[v];
  const bool in_unit = !unit.empty() && value.text.size() == cell.size() + 1 + unit.size() && value.text.starts_with(cell) &&
                       value.text.ends_with(unit) && value.text[cell.size()] == ' ';
  keep_written(in_unit ? cell : std::string_view(value.text), in_unit, value.si ? *value.si : std::numeric_limits<double>::quiet_NaN(),
               value.dimension);
}

void CaseTable::adopt_unit(std::size_t v, const CaseValue& value, const std::string& cell) {
  if (variables[v].unit.empty() && value.si) variables[v].unit = unit_of(cell);
}

std::optional<double> bare_number_in(std::string_view text, const UnitScale& unit) {
  // What parse_quantity makes of "TEXT UNIT": the number by from_chars, then (x + offset) * scale.
  if (text.empty()) return std::nullopt;
  const char* first = text.data() + (text.front() == '+' ? 1 : 0);
  const char* last = text.data() + text.size();
  double x = 0.0;
  const auto [end, ec] = std::from_chars(first, last, x);
  if (ec != std::errc() || end != last || !std::isfinite(x)) return std::nullopt;
  return bare_number_in(x, unit);
}

std::optional<double> bare_number_in(double x, const UnitScale& unit) {
  const double si = (x + unit.offset) * unit.scale;
  if (!std::isfinite(si)) return std::nullopt;
  return si;
}

const CaseValue& CaseTable::cell(std::size_t i, std::size_t v, CaseValue& scratch) const {
  if (!cases.empty()) return cases[i][v];
  number_cell(i, v, scratch);
  if (!numbers.written.ends.empty()) numbers.written.append(scratch.text, i * numbers.dimensions.size() + v, v);
  return scratch;
}

const CaseValue& CaseTable::number_cell(std::size_t i, std::size_t v, CaseValue& scratch) const {
  if (!cases.empty()) return cases[i][v];
  const std::size_t k = i * numbers.dimensions.size() + v;
  scratch.text.clear();
  if (const double x = numbers.si[k]; std::isnan(x)) scratch.si.reset();  // a word
  else scratch.si = x;
  scratch.dimension = numbers.written.ends.empty() ? numbers.dimensions[v] : numbers.written.dimensions.at(k, v);
  return scratch;
}

const std::vector<CaseValue>& CaseTable::row(std::size_t i, std::vector<CaseValue>& scratch) const {
  if (!cases.empty()) return cases[i];
  const std::size_t width = numbers.dimensions.size();
  scratch.resize(width);
  for (std::size_t v = 0; v < width; ++v) cell(i, v, scratch[v]);
  return scratch;
}

namespace {

// splitmix64: a small generator whose output is fixed by its definition on every platform.
struct SplitMix64 {
  std::uint64_t state;
  std::uint64_t next() {
    std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }  // [0, 1)
  std::size_t below(std::size_t n) { return static_cast<std::size_t>(uniform() * static_cast<double>(n)); }
};

std::pair<std::string, std::string> split_assignment(std::string_view text, const char* flag, const char* example) {
  const auto eq = text.find('=');
  if (eq == std::string_view::npos || eq == 0 || eq + 1 == text.size())
    throw SceneError(std::string(flag) + " " + excerpt(text) + ": expected " + example);
  return {trim(text.substr(0, eq)), trim(text.substr(eq + 1))};
}

// The numbers of a range's ends in their one unit ("3000rpm" and "7000" with "rpm": 3000 and 7000),
// when both are written in it and read back to the ends' values through it; else nullopt.
std::optional<std::pair<double, double>> range_numbers(const std::string& from_text, const std::string& to_text, const Quantity& from,
                                                       const Quantity& to, const std::string& from_unit, const std::string& to_unit) {
  if (from_unit.empty() || from_unit != to_unit) return std::nullopt;
  const std::optional<UnitScale>& u = parse_unit_cached(from_unit);
  if (!u) return std::nullopt;
  const auto number = [](const std::string& text) -> std::optional<double> {
    double x = 0.0;
    const std::size_t sign = text.starts_with('+') ? 1 : 0;  // "+5degC" as parse_quantity reads it
    const auto [end, ec] = std::from_chars(text.data() + sign, text.data() + text.size(), x);
    if (ec != std::errc() || end == text.data() + sign) return std::nullopt;
    return x;
  };
  const std::optional<double> a = number(from_text), b = number(to_text);
  if (!a || !b || (*a + u->offset) * u->scale != from.value || (*b + u->offset) * u->scale != to.value) return std::nullopt;
  return std::make_pair(*a, *b);
}

// FROM and TO of a range; one of them may leave its unit to the other.
std::pair<Quantity, std::string> range_end(const std::string& text, const std::string& other, const std::string& context) {
  std::string written = text;
  if (bare_number(text) && !bare_number(other)) written = text + " " + unit_of(other);
  Quantity q;
  try {
    q = parse_quantity(written);
  } catch (const UnitError& e) {
    throw SceneError(context + ": '" + excerpt(text) + "': " + e.what());
  }
  if (!std::isfinite(q.value)) throw SceneError(context + ": '" + excerpt(text) + "' is not a finite number");
  return {q, unit_of(written)};
}

}  // namespace

std::string excerpt(std::string_view text, std::size_t limit) {
  // Shown on a terminal: no control sequence (terminal_text), cut at a character's start.
  if (text.size() <= limit) return terminal_text(text);
  std::size_t cut = limit;
  while (cut > 0 && (static_cast<unsigned char>(text[cut]) & 0xC0) == 0x80) --cut;  // not inside a UTF-8 character
  return terminal_text(text.substr(0, cut)) + "...";
}

std::string read_user_file(const std::filesystem::path& file, std::size_t limit, const std::string& what) {
  try {
    return read_bounded_file(file, limit);
  } catch (const FileReadError& e) {
    throw SceneError(what + ": " + e.what());
  }
}

namespace {

// A variable's unit as append_shown reads it: none, or parsed (nullopt when it is not a unit).
ShownUnit shown_unit(const std::string& unit) {
  ShownUnit shown{!unit.empty(), unit.empty() ? std::nullopt : parse_unit_cached(unit)};
  shown.names_si = shown.scale && !shown.scale->dimension.dimensionless() && shown.scale->dimension.si_unit() == unit;
  return shown;
}

}  // namespace

bool CaseTable::append_shown(std::string& out, std::size_t i, std::size_t v) const {
  return append_shown(out, i, v, shown_unit(variables[v].unit));
}

bool CaseTable::shown_as_written(std::size_t i, std::size_t v, const ShownUnit& unit) const {
  if (!cases.empty() || numbers.written.ends.empty()) return false;
  const std::size_t k = i * numbers.dimensions.size() + v;
  const Numbers::Written& w = numbers.written;
  return w.in_column_unit[k] && unit.given && unit.scale && unit.scale->dimension == w.dimensions.at(k, v) &&
         !(numbers.exact_text_digits && unit.names_si) && w.column_units[v] == variables[v].unit && !variables[v].unit.empty();
}

double CaseTable::shown_given_number(std::size_t i, std::size_t v, const ShownUnit& unit) const {
  // append_shown's first branch shows a given number's digits (a finite number's 17 digits are
  // always a JSON number), which read back to the number itself.
  if (!shown_as_written(i, v, unit)) return std::numeric_limits<double>::quiet_NaN();
  const std::size_t k = i * numbers.dimensions.size() + v;
  const Numbers::Written& w = numbers.written;
  return w.in_column_unit[k] == Numbers::Written::given_number ? w.given[k] : std::numeric_limits<double>::quiet_NaN();
}

bool CaseTable::append_shown(std::string& out, std::size_t i, std::size_t v, const ShownUnit& unit) const {
  // A cases file's bare number under its column's unit, kept without its text: what the branch
  // below makes of its "CELL UNIT" (the cell as written), without making that text.
  if (shown_as_written(i, v, unit)) {
    Numbers::Written::Digits digits;
    const std::string_view cell = numbers.written.own_text(i * numbers.dimensions.size() + v, digits);
    if (json_number(cell)) {
      out.append(cell);
      return true;
    }
  }
  CaseValue made;
  const CaseValue& value = cell(i, v, made);
  if (!value.si) {
    out += value.text;
    return false;
  }
  double x = *value.si;
  if (unit.given) {
    // As to_unit: the value in the column's unit, else as written (a cell in another unit than
    // its column, or 1e308 m in mm, which overflows).
    const std::optional<UnitScale>& u = unit.scale;
    if (!u || !(u->dimension == value.dimension)) {
      out += value.written();
      return false;
    }
    // A sample's number (kept without its text) in a column of its SI unit: the digits of its
    // exact text ("X m", exact_text), as the branch below showed that text (Numbers::exact_text_digits).
    if (cases.empty() && numbers.exact_text_digits && unit.names_si) {
      const std::size_t at = out.size();
      append_exact_text(out, *value.si, {});
      if (json_number(std::string_view(out).substr(at))) return true;
      out.resize(at);
    }
    // A cell read as a bare number under its column's unit (kept as "CELL UNIT"): the cell reads
    // back to this very double by construction, so it is shown as written (and costs a copy).
    const std::string& column_unit = variables[v].unit;
    const std::string& text = value.text;
    if (text.size() > column_unit.size() + 1 && text.ends_with(column_unit) && text[text.size() - column_unit.size() - 1] == ' ') {
      const std::string_view cell(text.data(), text.size() - column_unit.size() - 1);
      if (json_number(cell)) {
        out.append(cell);
        return true;
      }
    }
    x = *value.si / u->scale - u->offset;
    if (!std::isfinite(x)) {
      out += value.written();
      return false;
    }
    const double si = *value.si, scale = u->scale, offset = u->offset;
    const auto reads_back = [si, scale, offset](double y) { return (y + offset) * scale == si; };
    if (offset != 0.0 && append_fewest_digits(out, x, reads_back)) return true;
    if (append_shown_number(out, x, reads_back)) return true;
    // No number in the column's unit is this double: the value with its own unit, exactly (a cell
    // in another unit reads as such), so that the row still reproduces its case.
    out += value.written();
    return false;
  }
  append_shown_number(out, x, [x](double y) { return y == x; });  // x itself reads back always
  return std::isfinite(x);  // always, as values are read and made; else a CSV writer escapes it
}

std::vector<ShownUnit> CaseTable::shown_units() const {
  std::vector<ShownUnit> units;
  for (const SweepVariable& variable : variables) units.push_back(shown_unit(variable.unit));
  return units;
}

std::string CaseTable::shown(std::size_t i, std::size_t v) const {
  std::string out;
  append_shown(out, i, v);
  return out;
}

VarySpec parse_vary(std::string_view text) {
  const auto [name, rhs] = split_assignment(text, "--vary", "NAME=FROM:TO:N (e.g. rpm=3000rpm:7000rpm:9) or NAME=A,B,C");
  VarySpec spec{name, {}, {}, false};
  const std::string context = "--vary " + excerpt(text);
  if (rhs.find(':') != std::string::npos) {
    std::vector<std::string> parts;
    std::size_t start = 0;
    for (std::size_t colon; (colon = rhs.find(':', start)) != std::string::npos; start = colon + 1)
      parts.push_back(trim(rhs.substr(start, colon - start)));
    parts.push_back(trim(rhs.substr(start)));
    if (parts.size() != 3) throw SceneError(context + ": expected FROM:TO:N, e.g. rpm=3000rpm:7000rpm:9");
    const auto [from, from_unit] = range_end(parts[0], parts[1], context);
    const auto [to, to_unit_text] = range_end(parts[1], parts[0], context);
    if (!(from.dimension == to.dimension))
      throw SceneError(context + ": FROM is " + from.dimension.describe() + " but TO is " + to.dimension.describe());
    char* end = nullptr;
    errno = 0;
    const long n = std::strtol(parts[2].c_str(), &end, 10);
    if (end == parts[2].c_str() || *end != '\0' || errno || n < 1 || n > static_cast<long>(max_range_points))
      throw SceneError(context + ": N = '" + excerpt(parts[2]) + "' must be a whole number of points from 1 to 10^7");
    if (n == 1 && from.value != to.value) throw SceneError(context + ": one point (N = 1) needs FROM = TO");
    spec.unit = from_unit.empty() ? to_unit_text : from_unit;
    spec.range = true;
    // Where both ends are numbers in one unit (3000rpm:7000rpm, 3000:7000rpm), the points are
    // spaced evenly in that unit and each is read as a cell of that number in that unit would be:
    // 3500 rpm of the grid is the very double `--set rpm=3500rpm` gives, and its row shows 3500.
    const std::optional<std::pair<double, double>> numbers = range_numbers(parts[0], parts[1], from, to, from_unit, to_unit_text);
    for (long k = 0; k < n; ++k) {
      const double t = static_cast<double>(k) / static_cast<double>(n - 1);
      double x = 0.0;
      if (k == 0 || k == n - 1) {
        x = k == 0 ? from.value : to.value;  // the ends exactly as written
      } else if (numbers) {
        // The point in the unit at 15 significant digits, as it would be written (1.1:1.3:3 has
        // 1.2, not the 1.2000000000000002 of the arithmetic), then read as that cell would be.
        const UnitScale& u = *parse_unit_cached(spec.unit);
        std::string written;
        append_printf_g15(written, between(numbers->first, numbers->second, t));
        x = (read_decimal(written) + u.offset) * u.scale;
      } else {
        // Ends in different units: evenly spaced in SI, each put on the numbers of the range's
        // unit (expressible_in) so that its row reads back to it.
        x = expressible_in(between(from.value, to.value, t), spec.unit);
      }
      require_finite(x, context);
      spec.values.push_back({exact_text(x, from.dimension), x, from.dimension});
    }
    return spec;
  }
  // The commas between values, not those inside a value's brackets ([2, 14, 26] is one list value).
  // (A named reference: a structured binding is not captured by a lambda before clang 16.)
  const std::string& list = rhs;
  const auto next_comma = [&list](std::size_t from) {
    int depth = 0;
    for (std::size_t i = from; i < list.size(); ++i) {
      if (list[i] == '[' || list[i] == '{') ++depth;
      else if ((list[i] == ']' || list[i] == '}') && depth > 0) --depth;
      else if (list[i] == ',' && depth == 0) return i;
    }
    return std::string::npos;
  };
  std::size_t start = 0;
  for (std::size_t comma;; start = comma + 1) {
    comma = next_comma(start);
    const std::string item = trim(rhs.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
    if (item.empty()) throw SceneError(context + ": an empty value in the list");
    spec.values.push_back(read_case_value(item, context));
    if (spec.unit.empty() && spec.values.back().si) spec.unit = unit_of(item);
    if (comma == std::string::npos) break;
  }
  return spec;
}

CaseTable make_grid(const std::vector<VarySpec>& specs) {
  CaseTable table;
  std::size_t total = 1;
  bool ranges_only = !specs.empty();
  for (const VarySpec& s : specs) {
    table.variables.push_back({s.name, s.unit});
    table.origin += (table.origin.empty() ? "--vary " : " --vary ") + s.name;
    if (total > max_sweep_cases / std::max<std::size_t>(s.values.size(), 1))
      throw SceneError("--vary: the grid would have more than " + std::string(max_sweep_cases_text) +
                       " cases; sample it instead (--sample NAME=LO:HI --n N)");
    total *= s.values.size();
    ranges_only = ranges_only && s.range;
  }
  const std::size_t width = specs.size();
  const std::size_t cap = ranges_only ? max_number_cells : max_case_cells;
  if (total > cap / std::max<std::size_t>(width, 1))
    throw SceneError("--vary: " + std::to_string(total) + " cases of " + std::to_string(width) + " values each are more than " +
                     std::to_string(cap) + " values in one sweep");
  // The cases in order, each spec's value index a digit of a mixed-radix counter whose last
  // digit (the last spec) turns fastest.
  std::vector<std::size_t> digit(width, 0);
  const auto next_case = [&] {
    for (std::size_t v = width; v-- > 0;) {
      if (++digit[v] < specs[v].values.size()) return;
      digit[v] = 0;
    }
  };
  if (ranges_only) {
    // Every value a number written as its exact text, which a table of numbers makes again
    // (CaseValue::written; append_shown with exact_text_digits): rows and fingerprint are the
    // same, at 8 bytes a value. A grid of 10^6 cases as rows of CaseValue held 220 MB more and
    // took 0.8 s longer before its first case ran.
    table.numbers.count = total;
    table.numbers.exact_text_digits = true;
    for (const VarySpec& s : specs) table.numbers.dimensions.push_back(s.values.front().dimension);
    reserve_large(table.numbers.si, total * width);
    table.numbers.si.resize(total * width);
    for (std::size_t i = 0; i < total; ++i, next_case())
      for (std::size_t v = 0; v < width; ++v) table.numbers.si[i * width + v] = *specs[v].values[digit[v]].si;
    return table;
  }
  table.cases.reserve(total);
  for (std::size_t i = 0; i < total; ++i, next_case()) {
    std::vector<CaseValue> row;
    row.reserve(width);
    for (std::size_t v = 0; v < width; ++v) row.push_back(specs[v].values[digit[v]]);
    table.cases.push_back(std::move(row));
  }
  return table;
}

SampleSpec parse_sample(std::string_view text) {
  const auto [name, rhs] = split_assignment(text, "--sample", "NAME=LO:HI (e.g. part.length=8mm:10mm)");
  const std::string context = "--sample " + excerpt(text);
  const auto colon = rhs.find(':');
  if (colon == std::string::npos || rhs.find(':', colon + 1) != std::string::npos)
    throw SceneError(context + ": expected LO:HI, e.g. part.length=8mm:10mm");
  const std::string lo_text = trim(rhs.substr(0, colon)), hi_text = trim(rhs.substr(colon + 1));
  const auto [lo, lo_unit] = range_end(lo_text, hi_text, context);
  const auto [hi, hi_unit] = range_end(hi_text, lo_text, context);
  if (!(lo.dimension == hi.dimension))
    throw SceneError(context + ": LO is " + lo.dimension.describe() + " but HI is " + hi.dimension.describe());
  if (!(hi.value > lo.value)) throw SceneError(context + ": HI must be greater than LO");
  return {name, lo.value, hi.value, lo.dimension, lo_unit.empty() ? hi_unit : lo_unit};
}

CaseTable make_latin_hypercube(const std::vector<SampleSpec>& specs, std::size_t n, std::uint64_t seed) {
  if (n == 0) throw SceneError("--n: a sample needs at least one case");
  if (n > max_sweep_cases)
    throw SceneError("--n " + std::to_string(n) + ": at most " + std::string(max_sweep_cases_text) + " cases in one sweep");
  const std::size_t width = specs.size();
  if (n > max_number_cells / std::max<std::size_t>(width, 1))
    throw SceneError("--n " + std::to_string(n) + " cases of " + std::to_string(width) + " values each are more than " +
                     std::to_string(max_number_cells) + " values in one sweep");
  CaseTable table;
  table.origin = "Latin hypercube, " + std::to_string(n) + " cases, seed " + std::to_string(seed);
  // Numbers only (8 bytes a value): a sample of 10^6 cases kept as rows of CaseValue, each with
  // its text, took 3 s and 600 MB to make before its first case ran.
  table.numbers.count = n;
  table.numbers.exact_text_digits = true;
  reserve_large(table.numbers.si, n * width);
  table.numbers.si.resize(n * width);
  SplitMix64 random{seed};
  std::vector<std::uint32_t> stratum(n);  // n <= max_sweep_cases < 2^32: half the scratch of size_t
  static_assert(max_sweep_cases <= 0xFFFFFFFFu);
  for (std::size_t v = 0; v < width; ++v) {
    const SampleSpec& s = specs[v];
    table.variables.push_back({s.name, s.unit});
    table.numbers.dimensions.push_back(s.dimension);
    const std::optional<UnitScale>& unit = s.unit.empty() ? std::nullopt : parse_unit_cached(s.unit);
    std::iota(stratum.begin(), stratum.end(), std::uint32_t{0});
    for (std::size_t i = n; i-- > 1;) std::swap(stratum[i], stratum[random.below(i + 1)]);  // Fisher-Yates
    for (std::size_t i = 0; i < n; ++i) {
      const double u = (static_cast<double>(stratum[i]) + random.uniform()) / static_cast<double>(n);
      const double x = expressible_in(between(s.low, s.high, u), unit);
      if (!std::isfinite(x)) require_finite(x, "--sample " + s.name);  // its message made for a refusal only
      table.numbers.si[i * width + v] = x;
    }
  }
  return table;
}

CaseTable read_cases_csv(const std::filesystem::path& file) {
  const std::string content = read_user_file(file, max_cases_file_bytes, "--cases");
  const std::string where = excerpt(file.string());
  CaseTable table;
  table.origin = file.string();
  int number = 0;
  bool header = false;
  std::vector<std::string> header_units;  // a bare number in a cell is in its column's unit
  std::vector<std::optional<UnitScale>> column_units;  // that unit, parsed (none: unitless or not a unit)
  // A line's fields as views: into the line itself (no quotes, the common line), else into the
  // fields split_csv_line unquoted. Nothing is allocated per line but the values kept.
  std::vector<std::string_view> fields;
  std::vector<std::string> unquoted;
  std::vector<int> starts;  // each field's 1-based column in its line, for the messages
  std::vector<std::string> header_unit_errors;  // per column: why its header's unit is no unit ("" when it is)
  std::vector<int> header_columns;              // per column: where its header stands on line 1
  // The cases as numbers with each value's text beside them (CaseTable::Numbers::Written): no
  // string and no row of CaseValue a case (a million cases of six values held 700 MB that way).
  // The kept texts are parts of the file (a bare number's unit is not repeated): their ends fit
  // 32 bits.
  static_assert(max_cases_file_bytes <= std::numeric_limits<std::uint32_t>::max());
  CaseTable::Numbers::Written& written = table.numbers.written;
  std::size_t width = 0;
  // Lines as std::getline gives them: split at '\n', a last line without one included.
  for (std::size_t at = 0; at < content.size();) {
    const std::size_t newline = content.find('\n', at);
    std::string_view line(content.data() + at, (newline == std::string::npos ? content.size() : newline) - at);
    at = newline == std::string::npos ? content.size() : newline + 1;
    ++number;
    if (number == 1 && line.starts_with("\xEF\xBB\xBF")) line.remove_prefix(3);  // a UTF-8 byte order mark
    const std::string_view trimmed = trimmed_view(line);
    if (trimmed.empty() || trimmed[0] == '#') continue;
    starts.clear();
    if (split_plain_csv_line(line, fields)) {
      for (const std::string_view f : fields) starts.push_back(static_cast<int>(f.data() - line.data()) + 1);
    } else {
      try {
        unquoted = split_csv_line(line);
      } catch (const std::invalid_argument& e) {
        throw SceneError(where + ":" + std::to_string(number) + ":1: " + e.what());
      }
      fields.assign(unquoted.begin(), unquoted.end());
      // Where each field begins in the line as written, its quotes counted.
      bool quoted = false;
      starts.push_back(1);
      for (std::size_t i = 0; i < line.size(); ++i) {
        if (line[i] == '"') quoted = !quoted;  // a doubled quote inside toggles twice
        else if (line[i] == ',' && !quoted) starts.push_back(static_cast<int>(i) + 2);
      }
      starts.resize(fields.size(), starts.empty() ? 1 : starts.back());
    }
    if (!header) {
      header = true;
      // A header may hold hundreds of thousands of columns: each name is looked up in a hash set
      // (linear in the header), never compared with every other name.
      std::unordered_set<std::string> names;
      names.reserve(fields.size());
      for (const std::string_view f : fields) {
        auto [name, tagged] = split_header(f);
        // A label's angle reference ("deg (shaft)", as mechgraph's own CSVs write) names the
        // angle, not a scale: the unit is read without it.
        const std::string unit = unit_without_reference(tagged);
        if (name.empty()) throw SceneError(where + ":" + std::to_string(number) + ":1: a column without a name");
        if (!names.insert(name).second)
          throw SceneError(where + ":" + std::to_string(number) + ":1: column '" + excerpt(name) + "' appears twice");
        table.variables.push_back({name, unit});
        header_units.push_back(unit);
        std::optional<UnitScale> scale;
        std::string unit_error;
        try {
          if (!unit.empty()) scale = parse_unit(" " + unit);  // as parse_quantity reads what follows the number
        } catch (const UnitError& e) {
          unit_error = e.what();  // a word column may name no unit; a number under it is refused with this
        }
        column_units.push_back(scale);
        header_unit_errors.push_back(unit_error);
        header_columns.push_back(starts[table.variables.size() - 1]);
      }
      width = table.variables.size();
      written.column_units = header_units;
      table.numbers.dimensions.assign(width, Dimension{});  // each value keeps its own
      // Room for as many values as the rest of the file's case lines can hold (a value ends at a
      // comma or its line's end; the cells' texts are parts of those lines): the arrays grow once,
      // not by doubling a million-case table several times, and a file of few cases reserves
      // little whatever its header, blank lines or comments (sweep_holdings counts what is reserved).
      std::size_t room = 0, case_bytes = 0;
      for (std::size_t from = at; from < content.size();) {
        const std::size_t end = std::min(content.find('\n', from), content.size());
        const std::string_view case_line = trimmed_view(std::string_view(content).substr(from, end - from));
        if (!case_line.empty() && case_line[0] != '#') {
          room += 1 + static_cast<std::size_t>(std::count(case_line.begin(), case_line.end(), ','));
          case_bytes += case_line.size();
        }
        from = end + 1;
      }
      room = std::min(room, max_case_cells + width);
      written.text.reserve(case_bytes);
      reserve_large(table.numbers.si, room);
      written.ends.reserve(room);
      written.in_column_unit.reserve(room);
      continue;
    }
    if (table.numbers.count >= max_sweep_cases)
      throw SceneError(where + ":" + std::to_string(number) + ":1: more than " + std::string(max_sweep_cases_text) +
                       " cases in one file; split it into several sweeps");
    if ((table.numbers.count + 1) * std::max<std::size_t>(width, 1) > max_case_cells)
      throw SceneError(where + ":" + std::to_string(number) + ":1: more than " + std::to_string(max_case_cells) +
                       " values in one file; split it into several sweeps");
    if (fields.size() != table.variables.size())
      throw SceneError(where + ":" + std::to_string(number) + ":1: " + std::to_string(fields.size()) +
                       " cells, the header has " + std::to_string(table.variables.size()));
    for (std::size_t v = 0; v < fields.size(); ++v) {
      const std::string_view cell = trimmed_view(fields[v]);
      const int column = starts[v];
      if (cell.empty())
        throw SceneError(where + ":" + std::to_string(number) + ":" + std::to_string(column) + ": '" +
                         excerpt(table.variables[v].name) + "' has no value");
      const std::string& unit = header_units[v];
      // A plain number under a column with a unit, the common cell, read at once: what
      // parse_quantity makes of "CELL UNIT" (the number by from_chars, then (x + offset) * scale
      // with the column's unit parsed once), else the general reading below, with its messages.
      if (const std::optional<UnitScale>& u = column_units[v])
        if (const std::optional<double> si = bare_number_in(cell, *u)) {
          table.keep_written(cell, true, *si, u->dimension);  // "CELL UNIT"
          continue;
        }
      const std::string at = where + ":" + std::to_string(number) + ":" + std::to_string(column);
      const std::string cell_text(cell);
      // A number beyond a double's range says so (1e400, 1e-400), not that it is no number.
      {
        double ignored = 0.0;
        const char* first = cell_text.data() + (cell_text.starts_with('+') ? 1 : 0);
        const auto [end, ec] = std::from_chars(first, cell_text.data() + cell_text.size(), ignored);
        if (ec == std::errc::result_out_of_range && end == cell_text.data() + cell_text.size())
          throw SceneError(at + ": '" + excerpt(cell_text) + "' is beyond the range of a double (a magnitude from about 5e-324 to 1.8e308, or 0)");
      }
      CaseValue value = read_case_value(!unit.empty() && bare_number(cell_text) ? cell_text + " " + unit : cell_text, at);
      if (!unit.empty() && !value.si) {
        if (!header_unit_errors[v].empty())  // the header's unit is at fault, not the cell
          throw SceneError(where + ":1:" + std::to_string(header_columns[v]) + ": column '" + excerpt(table.variables[v].name) + "': [" +
                           excerpt(unit) + "] is not a unit: " + header_unit_errors[v]);
        throw SceneError(at + ": '" + excerpt(cell_text) + "' is not a number in " + excerpt(unit));
      }
      table.adopt_unit(v, value, cell_text);
      table.keep_written(value, cell_text, v);  // "CELL UNIT" as the cell and a mark: within the file's size
    }
    ++table.numbers.count;
  }
  if (!header) throw SceneError(where + ":1:1: no header (a line of parameter names, e.g. rpm,part.length [mm])");
  if (table.numbers.count == 0) throw SceneError(where + ": no cases below the header");
  return table;
}

}  // namespace mechgraph
