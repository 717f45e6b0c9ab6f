#include <mechgraph/units.hpp>

#include "decimal_number.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <numbers>
#include <sstream>
#include <string>

namespace mechgraph {
namespace {

struct UnitSymbol {
  const char* symbol;
  double scale;
  Dimension dimension;
};

constexpr double pi = std::numbers::pi;

// std::from_chars for a double, also where the C++ library lacks it (decimal_number.hpp).
std::from_chars_result read_double(const char* first, const char* last, double& value) {
#if defined(__cpp_lib_to_chars)
  return std::from_chars(first, last, value);
#else
  return detail::read_double_with_strtod(first, last, value);
#endif
}

// The unit symbols of the scene language, SI scale of each.
const UnitSymbol unit_table[] = {
    {"m", 1.0, dim::length},
    {"cm", 1e-2, dim::length},
    {"mm", 1e-3, dim::length},
    {"um", 1e-6, dim::length},
    {"µm", 1e-6, dim::length},
    {"nm", 1e-9, dim::length},
    {"in", 0.0254, dim::length},
    {"rad", 1.0, dim::angle},
    {"deg", pi / 180.0, dim::angle},
    {"arcmin", pi / 10800.0, dim::angle},
    {"arcsec", pi / 648000.0, dim::angle},
    {"rev", 2.0 * pi, dim::angle},
    {"s", 1.0, dim::time},
    {"ms", 1e-3, dim::time},
    {"us", 1e-6, dim::time},
    {"min", 60.0, dim::time},
    {"h", 3600.0, dim::time},
    {"rpm", 2.0 * pi / 60.0, dim::angular_speed},
    {"Hz", 1.0, dim::frequency},
    {"kHz", 1e3, dim::frequency},
    {"kg", 1.0, dim::mass},
    {"g", 1e-3, dim::mass},
    {"t", 1e3, dim::mass},
    {"N", 1.0, dim::force},
    {"kN", 1e3, dim::force},
    {"mN", 1e-3, dim::force},
    {"Pa", 1.0, dim::stress},
    {"kPa", 1e3, dim::stress},
    {"MPa", 1e6, dim::stress},
    {"GPa", 1e9, dim::stress},
    {"J", 1.0, dim::force * dim::length},
    {"K", 1.0, dim::temperature},
    {"%", 1e-2, dim::none},
    {"ppm", 1e-6, dim::none},
    {"1", 1.0, dim::none},
};

const UnitSymbol* find_symbol(std::string_view s) {
  for (const UnitSymbol& u : unit_table)
    if (s == u.symbol) return &u;
  return nullptr;
}

constexpr int max_power = 16;

bool is_symbol_char(char c) { return c != '*' && c != '/' && c != '^' && c != ' ' && c != '\t'; }

std::string trim_copy(std::string_view s) {
  const auto b = s.find_first_not_of(" \t");
  if (b == std::string_view::npos) return {};
  const auto e = s.find_last_not_of(" \t");
  return std::string(s.substr(b, e - b + 1));
}

}  // namespace

std::string known_unit_symbols() {
  std::string out;
  for (const UnitSymbol& u : unit_table) {
    if (std::string_view(u.symbol) == "1" || std::string_view(u.symbol) == "µm") continue;
    if (!out.empty()) out += ' ';
    out += u.symbol;
  }
  return out + " degC";
}

UnitScale parse_unit(std::string_view text) {
  UnitScale result;
  const std::string trimmed = trim_copy(text);
  if (trimmed.empty()) return result;
  // Temperatures on the Celsius scale are affine: only alone, never in a product.
  if (trimmed == "degC" || trimmed == "°C") return {1.0, 273.15, dim::temperature};

  std::size_t i = text.find_first_not_of(" \t");
  int sign = +1;  // +1 numerator, -1 after '/'
  bool expect_symbol = true;
  while (i < text.size()) {
    const char c = text[i];
    if (c == ' ' || c == '\t') { ++i; continue; }
    if (!expect_symbol) {
      if (c == '*') { expect_symbol = true; ++i; continue; }
      if (c == '/') {
        if (sign < 0) throw UnitError("a unit may have only one '/'", i);
        sign = -1;
        expect_symbol = true;
        ++i;
        continue;
      }
      throw UnitError(std::string("expected '*' or '/' in unit, found '") + c + "'", i);
    }
    const std::size_t start = i;
    while (i < text.size() && is_symbol_char(text[i])) ++i;
    const std::string_view symbol = text.substr(start, i - start);
    if (symbol.empty()) throw UnitError("expected a unit symbol", start);
    const UnitSymbol* u = find_symbol(symbol);
    if (!u) {
      if (symbol == "degC") throw UnitError("degC cannot be combined with other units; use K", start);
      throw UnitError("unknown unit '" + std::string(symbol) + "'; valid units are: " + known_unit_symbols(), start);
    }
    int power = 1;
    if (i < text.size() && text[i] == '^') {
      ++i;
      const char* first = text.data() + i;
      const char* last = text.data() + text.size();
      // Read as a wider integer and bounded before any use: std::abs(INT_MIN) is INT_MIN, which
      // once let "m^-2147483648" through as a power that wrapped to nothing.
      long long wide = 0;
      auto [ptr, ec] = std::from_chars(first, last, wide);
      if (ec == std::errc::result_out_of_range || (ec == std::errc() && (wide < -max_power || wide > max_power)))
        throw UnitError("a power of a unit must lie within -" + std::to_string(max_power) + ".." +
                            std::to_string(max_power) + ", found " + std::string(first, ptr),
                        i);
      if (ec != std::errc() || wide == 0) throw UnitError("expected a non-zero integer power after '^'", i);
      power = static_cast<int>(wide);
      i += static_cast<std::size_t>(ptr - first);
    }
    power *= sign;
    result.scale *= std::pow(u->scale, power);
    // Each base exponent is kept in 8 bits: refuse a product that would leave +-16 (no physical
    // quantity comes near it) before it could wrap.
    const Dimension d = u->dimension.pow(power);
    for (const auto& [have, add] : {std::pair{result.dimension.length, d.length}, {result.dimension.mass, d.mass},
                                   {result.dimension.time, d.time}, {result.dimension.angle, d.angle},
                                   {result.dimension.temperature, d.temperature}})
      if (std::abs(have + add) > max_power) throw UnitError("the unit's dimension has an exponent beyond -16..16", start);
    result.dimension = result.dimension * d;
    expect_symbol = false;
  }
  if (expect_symbol) throw UnitError("unit ends with an operator", text.size());
  if (!std::isfinite(result.scale) || !(result.scale > 0.0))
    throw UnitError("the unit's size in SI is beyond the range of a double", 0);
  return result;
}

Quantity parse_quantity(std::string_view text) {
  std::size_t i = text.find_first_not_of(" \t");
  if (i == std::string_view::npos) throw UnitError("expected a number with a unit, found nothing", 0);
  const char* first = text.data() + i;
  const char* last = text.data() + text.size();
  if (*first == '+') ++first;
  double value = 0.0;
  auto [ptr, ec] = read_double(first, last, value);
  if (ec == std::errc::result_out_of_range) throw UnitError("number out of the range of a double", i);
  if (ec != std::errc()) throw UnitError("expected a number at the start of '" + std::string(text) + "'", i);
  if (!std::isfinite(value)) throw UnitError("the number must be finite", i);
  const std::size_t unit_start = static_cast<std::size_t>(ptr - text.data());
  UnitScale unit;
  try {
    unit = parse_unit(text.substr(unit_start));
  } catch (const UnitError& e) {
    throw UnitError(e.what(), unit_start + e.column());
  }
  const double si = (value + unit.offset) * unit.scale;
  if (!std::isfinite(si)) throw UnitError("the value in SI units is beyond the range of a double", i);
  return {si, unit.dimension};
}

double to_unit(double value_in_si, Dimension dimension, std::string_view unit) {
  const UnitScale u = parse_unit(unit);
  if (!(u.dimension == dimension))
    throw UnitError("unit '" + std::string(unit) + "' is " + u.dimension.describe() + ", the value is " +
                        dimension.describe(),
                    0);
  const double shown = value_in_si / u.scale - u.offset;
  // 1e300 m is finite, in nm it is not: never hand a writer "inf".
  if (!std::isfinite(shown) && std::isfinite(value_in_si)) {
    std::ostringstream value;
    value.precision(6);
    value << value_in_si;
    throw UnitError("the value " + value.str() + " " + dimension.si_unit() +
                        " is beyond the range of a double in '" + std::string(unit) + "'",
                    0);
  }
  return shown;
}

}  // namespace mechgraph
