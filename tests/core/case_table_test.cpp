// CaseTable::append_shown (core/src/sweep/case_table.cpp): a row's inputs read back to their case's
// doubles exactly, through the column's unit, and are printf's "%.15g" wherever that already does
// (what rows always held).
#include <mechgraph/sweep/case_table.hpp>
#include <mechgraph/sweep/case_estimate.hpp>
#include <mechgraph/dimension.hpp>
#include <mechgraph/units.hpp>

#include <catch2/catch.hpp>

#include <unistd.h>

#include <bit>
#include <charconv>
#include <filesystem>
#include <fstream>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <string>

using namespace mechgraph;

namespace {

CaseTable one_column(const std::string& unit, const Dimension& dimension, const std::vector<double>& si) {
  CaseTable table;
  table.variables.push_back({"x", unit});
  for (double v : si) table.cases.push_back({CaseValue{"", v, dimension}});
  return table;
}

double parsed(const std::string& text) {
  double y = std::nan("");
  std::from_chars(text.data(), text.data() + text.size(), y);
  return y;
}

std::string by_printf(double x) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.15g", x);
  return buffer;
}

}  // namespace

TEST_CASE("Case tables: a row's inputs read back to the case's doubles, %.15g where that does", "[core][sweep]") {
  // A cases file's number as its cell was written, when it is a number as JSON writes one.
  {
    CaseTable table;
    table.variables.push_back({"x", "mm"});
    for (const char* cell : {"8.410630376935433", "+8.5", "08", ".5", "1e-3", "-0.25"})
      table.cases.push_back({CaseValue{std::string(cell) + " mm", parse_quantity(std::string(cell) + " mm").value, dim::length}});
    CHECK(table.shown(0, 0) == "8.410630376935433");
    CHECK(table.shown(1, 0) == "8.5");  // not "+8.5": CSV would take it for a formula, JSON not for a number
    CHECK(table.shown(2, 0) == "8");
    CHECK(table.shown(3, 0) == "0.5");
    CHECK(table.shown(4, 0) == "1e-3");
    CHECK(table.shown(5, 0) == "-0.25");
  }
  std::mt19937_64 bits(11);
  std::vector<double> values{0.0, -0.0, 1.0, -2.5, 8.41, 0.30293537157365913, 1e-5, 9.99999999999999e-5, 1e15, 1e-300, 5e-324,
                             123456789012345.6, 99999999999999.99, 6162.0407036911765};
  std::uniform_real_distribution<double> exponent(-7.0, 17.0), mantissa(1.0, 10.0);
  for (int i = 0; i < 20000; ++i) {
    const double x = mantissa(bits) * std::pow(10.0, std::floor(exponent(bits)));
    values.push_back(i % 2 ? x : -x);
    values.push_back(std::round(x * 1000.0) / 1000.0);  // few digits, the usual input
  }
  const CaseTable plain = one_column("", Dimension{}, values);
  for (std::size_t i = 0; i < values.size(); ++i) {
    const std::string shown = plain.shown(i, 0);
    INFO(shown);
    CHECK(parsed(shown) == values[i]);
    if (parsed(by_printf(values[i])) == values[i]) CHECK(shown == by_printf(values[i]));
  }
  // Through a unit: (text + offset) * scale, as the cases reader takes a bare number under it.
  for (const char* unit : {"mm", "degC", "deg", "rpm"}) {
    const UnitScale u = parse_unit(std::string(" ") + unit);
    std::vector<double> si;
    for (int i = 0; i < 2000; ++i) si.push_back((mantissa(bits) * 10.0 + u.offset) * u.scale);
    for (const double written : {8.41, 0.25, 5600.0, 120.0}) si.push_back((written + u.offset) * u.scale);
    const CaseTable table = one_column(unit, u.dimension, si);
    for (std::size_t i = 0; i < si.size(); ++i) {
      const std::string shown = table.shown(i, 0);
      INFO(unit << ": " << shown);
      CHECK((parsed(shown) + u.offset) * u.scale == si[i]);
    }
    // Values made in SI (a grid's points, a sample): the column's unit cannot express every one of
    // them; such a value is shown with its own unit, exactly, so the row still reads back to it.
    std::uniform_real_distribution<double> in_si(si.front() * 0.9, si.front() * 1.1);
    std::vector<double> made;
    for (int i = 0; i < 3000; ++i) made.push_back(in_si(bits));
    const CaseTable generated = one_column(unit, u.dimension, made);
    std::size_t own_unit = 0;
    for (std::size_t i = 0; i < made.size(); ++i) {
      const std::string shown = generated.shown(i, 0);
      INFO(unit << ": " << shown);
      if (std::isfinite(parsed(shown)) && shown.find(' ') == std::string::npos) {
        CHECK((parsed(shown) + u.offset) * u.scale == made[i]);
      } else {
        ++own_unit;
        CHECK(parse_quantity(shown).value == made[i]);
      }
    }
    CHECK(own_unit < made.size());
    // Put on the unit's numbers first (expressible_in, as grids, samples and studies make them):
    // every one a number in the column's unit, reading back exactly, each within a few ulps of where it was.
    std::vector<double> snapped;
    for (const double m : made) snapped.push_back(expressible_in(m, std::string(unit)));
    const CaseTable on_unit = one_column(unit, u.dimension, snapped);
    for (std::size_t i = 0; i < snapped.size(); ++i) {
      const std::string shown = on_unit.shown(i, 0);
      INFO(unit << ": " << shown);
      REQUIRE(shown.find(' ') == std::string::npos);
      CHECK((parsed(shown) + u.offset) * u.scale == snapped[i]);
      CHECK(std::abs(snapped[i] - made[i]) <= 4 * std::abs(made[i]) * std::numeric_limits<double>::epsilon());
    }
    // A value written with few digits is shown so again, in an offset unit too (its subtraction's
    // rounding, 8.410000000000025 degC, is not shown).
    CHECK(table.shown(si.size() - 4, 0) == "8.41");
    CHECK(table.shown(si.size() - 3, 0) == "0.25");
    CHECK(table.shown(si.size() - 1, 0) == "120");
  }
}

TEST_CASE("Case tables: a grid's points in its unit are the doubles those numbers give as cells", "[core][sweep]") {
  // 3000rpm:7000rpm:9 has 3500 rpm: the double `--set rpm=3500rpm` gives, and its row shows 3500.
  struct Range {
    std::string vary, unit;
    double from, to;
    long n;
  };
  for (const Range& r : {Range{"rpm=3000rpm:7000rpm:9", "rpm", 3000, 7000, 9}, Range{"a=0.1mm:0.7:7", "mm", 0.1, 0.7, 7},
                         Range{"t=20degC:30degC:11", "degC", 20, 30, 11}, Range{"x=0:1:11", "", 0, 1, 11},
                         Range{"phi=-20deg:40deg:13", "deg", -20, 40, 13}, Range{"lash=1.1mm:1.3mm:3", "mm", 1.1, 1.3, 3},
                         Range{"x=0.1mm:0.4mm:4", "mm", 0.1, 0.4, 4}, Range{"t=+5degC:10degC:3", "degC", 5, 10, 3},
                         Range{"r=3000:7000rpm:5", "rpm", 3000, 7000, 5}}) {
    INFO(r.vary);
    const CaseTable table = make_grid({parse_vary(r.vary)});
    REQUIRE(table.size() == static_cast<std::size_t>(r.n));
    CaseValue scratch;
    for (long k = 0; k < r.n; ++k) {
      const double number = r.from + (r.to - r.from) * static_cast<double>(k) / static_cast<double>(r.n - 1);
      char text[64];
      std::snprintf(text, sizeof text, "%.15g %s", number, r.unit.c_str());
      INFO(text);
      CHECK(*table.cell(static_cast<std::size_t>(k), 0, scratch).si == parse_quantity(text).value);
      std::snprintf(text, sizeof text, "%.15g", number);
      CHECK(table.shown(static_cast<std::size_t>(k), 0) == text);
    }
  }
  // Ends in different units: evenly spaced in SI, each on the numbers of the range's unit.
  const CaseTable mixed = make_grid({parse_vary("a=1mm:0.5cm:5")});
  REQUIRE(mixed.size() == 5);
  CaseValue scratch;
  for (std::size_t k = 0; k < mixed.size(); ++k) {
    const std::string shown = mixed.shown(k, 0);
    INFO(shown);
    CHECK(parse_quantity(shown + " mm").value == *mixed.cell(k, 0, scratch).si);
  }
}

TEST_CASE("Case tables: a grid of ranges kept as numbers shows and writes what rows of text did", "[core][sweep]") {
  // Each range's values as parse_vary makes them (a number with its exact text), laid out as the
  // grid was before it kept numbers: rows of those very values, the last range the fastest.
  const std::vector<VarySpec> specs{parse_vary("lift=7mm:9mm:3"),      parse_vary("t=20degC:90degC:4"),
                                    parse_vary("rpm=4000:7000rpm:3"),  parse_vary("ratio=1.4:1.6:2"),
                                    parse_vary("action=120deg:140deg:3"), parse_vary("k=20N/mm:30N/mm:2"),
                                    // In the SI unit itself, where %.15g and the exact text's digits differ;
                                    // ends in different units, put on the range's unit's numbers.
                                    parse_vary("x=1e15m:2e17m:4"),     parse_vary("a=1mm:0.5cm:3")};
  const CaseTable numbers = make_grid(specs);
  REQUIRE(numbers.cases.empty());
  const std::size_t n = 3 * 4 * 3 * 2 * 3 * 2 * 4 * 3;
  REQUIRE(numbers.size() == n);
  REQUIRE(numbers.numbers.si.size() == n * specs.size());
  CaseTable texts;
  texts.variables = numbers.variables;
  for (std::size_t i = 0; i < n; ++i) {
    std::vector<CaseValue> row(specs.size());
    std::size_t rest = i;
    for (std::size_t v = specs.size(); v-- > 0;) {
      row[v] = specs[v].values[rest % specs[v].values.size()];
      rest /= specs[v].values.size();
    }
    texts.cases.push_back(std::move(row));
  }
  CaseValue scratch;
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t v = 0; v < specs.size(); ++v) {
      INFO("case " << i << ", " << specs[v].name);
      const CaseValue& cell = numbers.cell(i, v, scratch);
      REQUIRE(cell.si);
      CHECK(*cell.si == *texts.cases[i][v].si);
      CHECK(cell.dimension == texts.cases[i][v].dimension);
      CHECK(cell.written() == texts.cases[i][v].text);
      CHECK(numbers.shown(i, v) == texts.shown(i, v));
    }
  // A list among the ranges keeps the grid's values as written (a word, "3000rpm" as typed).
  const CaseTable listed = make_grid({parse_vary("lift=7mm:9mm:3"), parse_vary("rpm=3000rpm,4000rpm")});
  REQUIRE(listed.cases.size() == 6);
  CHECK(listed.cases[1][1].text == "4000rpm");
  CHECK(listed.shown(5, 0) == "9");
}

TEST_CASE("Case tables: a grid of ranges is bounded by its numbers, a grid with a list by rows of text", "[core][sweep][bounds]") {
  // Two ranges of 3163 points: 1.0004 x 10^7 cases of 2 values, past max_case_cells (the rows of
  // text it was refused by) and 160 MB as numbers.
  const CaseTable big = make_grid({parse_vary("a=1mm:2mm:3163"), parse_vary("b=1:2:3163")});
  CHECK(big.size() == 3163u * 3163u);
  CaseValue scratch;
  CHECK(*big.cell(big.size() - 1, 0, scratch).si == parse_quantity("2 mm").value);
  // Each cap is checked before anything is allocated.
  const VarySpec wide = parse_vary("w=1:2:4000");
  CHECK_THROWS_WITH(make_grid({wide, wide, parse_vary("z=1:2:10")}),
                    Catch::Matchers::Contains("160000000 cases of 3 values each are more than 250000000 values in one sweep"));
  CHECK_THROWS_WITH(make_grid({wide, wide, parse_vary("z=1,2")}),
                    Catch::Matchers::Contains("32000000 cases of 3 values each are more than 20000000 values in one sweep"));
}

TEST_CASE("Case tables: a Latin hypercube kept as numbers shows and writes what rows of text did", "[core][sweep]") {
  // make_latin_hypercube keeps its cases as CaseTable::Numbers. The same values as rows of
  // CaseValue with their exact text (how the sample was kept before) must give the same cells in
  // every unit: a row and a rebuilt case do not depend on how the table keeps them (the draw and
  // the fingerprint are pinned in tests/cli/sweep_cli_test.cpp).
  const std::vector<SampleSpec> specs{parse_sample("lift=7mm:9mm"), parse_sample("t=20degC:90degC"),
                                      parse_sample("rpm=4000rpm:7000rpm"), parse_sample("ratio=1.4:1.6"),
                                      parse_sample("action=120deg:140deg"), parse_sample("k=20N/mm:30N/mm"),
                                      // In the SI unit itself, where %.15g and the exact text's digits differ.
                                      parse_sample("x=1e15m:2e17m"), parse_sample("f=1e14N:1e16N")};
  const std::size_t n = 500;
  const CaseTable numbers = make_latin_hypercube(specs, n, 3);
  REQUIRE(numbers.cases.empty());
  REQUIRE(numbers.size() == n);
  REQUIRE(numbers.numbers.si.size() == n * specs.size());
  CaseTable texts;
  texts.variables = numbers.variables;
  CaseValue scratch;
  for (std::size_t i = 0; i < n; ++i) {
    std::vector<CaseValue> row;
    for (std::size_t v = 0; v < specs.size(); ++v) {
      const CaseValue& cell = numbers.cell(i, v, scratch);
      REQUIRE(cell.si);
      CHECK(cell.dimension == specs[v].dimension);
      row.push_back({exact_text(*cell.si, cell.dimension), cell.si, cell.dimension});
    }
    texts.cases.push_back(std::move(row));
  }
  std::string text;
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t v = 0; v < specs.size(); ++v) {
      INFO("case " << i << ", " << specs[v].name);
      CHECK(numbers.shown(i, v) == texts.shown(i, v));
      const CaseValue& cell = numbers.cell(i, v, scratch);
      CHECK(cell.written() == texts.cases[i][v].text);
      text.clear();
      append_exact_text(text, *cell.si, exact_text_unit(cell.dimension));
      CHECK(text == texts.cases[i][v].text);
    }
}

TEST_CASE("Case tables: a table of numbers shows a sample's digits or a study's, as each did before", "[core][sweep]") {
  // In a column named by its SI unit a sample's value showed its exact text's digits (to_chars'
  // shortest), a study's design value %.15g where that reads back: rows written by earlier builds
  // are resumed and read as rows of the same sweep or study only if each keeps its own.
  CaseTable table;
  table.variables = {{"len", "m"}, {"d", "mm"}};
  table.numbers.count = 3;
  table.numbers.dimensions = {dim::length, dim::length};
  table.numbers.si = {1.5755532090945693e+17, 2e-3, 100000.0, 3e-3, 0.0003, 4e-3};
  CHECK(table.shown(0, 0) == "1.5755532090945693e+17");
  CHECK(table.shown(1, 0) == "100000");
  CHECK(table.shown(2, 0) == "0.0003");
  CHECK(table.shown(0, 1) == "2");
  table.numbers.exact_text_digits = true;
  CHECK(table.shown(0, 0) == "157555320909456928");
  CHECK(table.shown(1, 0) == "1e+05");
  CHECK(table.shown(2, 0) == "3e-04");
  CHECK(table.shown(0, 1) == "2");  // another unit than the SI unit: the same either way
}

TEST_CASE("Case tables: a sample's size is bounded by its numbers, not by rows of text", "[core][sweep][bounds]") {
  // A sample of 3.4 x 10^6 cases of 6 values (2.04 x 10^7 values, 163 MB as numbers) was refused
  // by the cap sized for rows of text (max_case_cells); a sample is held at 8 bytes a value.
  std::vector<SampleSpec> six;
  for (const char* s : {"a=1mm:2mm", "b=1:2", "c=1deg:2deg", "d=1rpm:2rpm", "e=1N:2N", "f=1s:2s"}) six.push_back(parse_sample(s));
  const std::size_t n = max_case_cells / six.size() + 1;
  const CaseTable big = make_latin_hypercube(six, n, 1);
  CHECK(big.size() == n);
  CHECK(big.numbers.si.size() == n * six.size());
  CaseValue scratch;
  CHECK(std::isfinite(*big.cell(n - 1, 5, scratch).si));
  // Its own cap (max_number_cells) is checked before anything is allocated.
  const std::vector<SampleSpec> many(26, parse_sample("x=1:2"));
  CHECK_THROWS_WITH(make_latin_hypercube(many, 10'000'000, 1),
                    Catch::Matchers::Contains("cases of 26 values each are more than 250000000 values in one sweep"));
  CHECK_THROWS_WITH(make_latin_hypercube(six, max_sweep_cases + 1, 1), Catch::Matchers::Contains("at most 2.5 x 10^8 cases"));
}

TEST_CASE("Case tables: a cases file is kept as numbers with each value's text beside them", "[core][sweep]") {
  // What each cell's CaseValue held while a cases file kept a row of them: its text as written
  // ("CELL UNIT" for a bare number under the header's unit), its number read from that text, a
  // word with no number.
  const auto dir = std::filesystem::temp_directory_path() / ("mechgraph_case_table_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const auto file = dir / "cases.csv";
  // A column without a header unit takes its first number's ("5000 rpm"); a bare number under it
  // stays bare.
  std::ofstream(file) << "len [mm],gain,t [degC],n\n1,0.5,20,5000 rpm\n# a comment\n\n2.5 mm,+2,\"300 K\",6000\n"
                         "\"0.003 m\",1.5,-5,7e3 rpm\n 4 ,abc,1e1,x\n";
  const CaseTable table = read_cases_csv(file);
  // Blank and comment lines reserve nothing: a file of one case under a wide header and many
  // comments holds room for one case's values.
  {
    std::ofstream out(file);
    out << "a,b,c,d,e,f,g,h\n";
    for (int i = 0; i < 10000; ++i) out << "# ,,,,,,,,,,,,,,,,\n\n";
    out << "1,2,3,4,5,6,7,8\n";
  }
  const CaseTable commented = read_cases_csv(file);
  std::filesystem::remove_all(dir);
  CHECK(commented.size() == 1);
  CHECK(commented.numbers.si.capacity() <= 8);
  CHECK(commented.numbers.written.text.capacity() <= 64);
  REQUIRE(table.size() == 4);
  CHECK(table.cases.empty());
  CHECK(table.variables[3].unit == "rpm");
  const std::vector<std::vector<std::string>> texts{{"1 mm", "0.5", "20 degC", "5000 rpm"},
                                                    {"2.5 mm", "+2", "300 K", "6000"},
                                                    {"0.003 m", "1.5", "-5 degC", "7e3 rpm"},
                                                    {"4 mm", "abc", "1e1 degC", "x"}};
  CaseTable rows;  // the same values as rows of CaseValue
  rows.variables = table.variables;
  for (const auto& line : texts) {
    std::vector<CaseValue> row;
    for (const std::string& text : line) row.push_back(read_case_value(text, "test"));
    rows.cases.push_back(std::move(row));
  }
  CaseValue scratch, bare;
  for (std::size_t i = 0; i < 4; ++i)
    for (std::size_t v = 0; v < 4; ++v) {
      INFO("case " << i << ", variable " << v);
      const CaseValue& expected = rows.cases[i][v];
      const CaseValue& cell = table.cell(i, v, scratch);
      CHECK(cell.text == expected.text);
      CHECK(cell.written() == expected.text);
      CHECK(cell.si == expected.si);
      CHECK(cell.dimension == expected.dimension);
      CHECK(table.shown(i, v) == rows.shown(i, v));
      // The number alone, as a block's check reads it: the same number and dimension, no text.
      const CaseValue& number = table.number_cell(i, v, bare);
      CHECK(number.si == expected.si);
      CHECK(number.dimension == expected.dimension);
      CHECK(number.text.empty());
    }
  CHECK_FALSE(table.cell(3, 1, scratch).si);  // the word
  // A bare number is shown as written, another unit's value in the column's unit.
  CHECK(table.shown(3, 0) == "4");
  CHECK(table.shown(2, 0) == "3");
  // Its holdings count the texts (as written, not as reserved) and everything else kept beside the
  // numbers.
  const CaseTable::Numbers::Written& w = table.numbers.written;
  CHECK(sweep_holdings(table, 0) == static_cast<double>(table.numbers.si.capacity() * sizeof(double) + w.text.size() +
                                                         w.ends.capacity() * sizeof(std::uint32_t) + w.in_column_unit.capacity() +
                                                         w.dimensions.bytes_held()));
}

TEST_CASE("Case tables: values' dimensions are kept once a column until one differs", "[core][sweep]") {
  // Three variables; rows 0 to 2 alike (length, angle, none), row 3's angle a word (none).
  const std::vector<Dimension> row{dim::length, dim::angle, dim::none};
  CaseTable table;
  table.numbers.dimensions.assign(row.size(), Dimension{});
  table.numbers.written.column_units = {"mm", "deg", ""};
  for (int i = 0; i < 3; ++i)
    for (std::size_t v = 0; v < row.size(); ++v) table.keep_written("1", v < 2, 1.0, row[v]);
  table.numbers.count = 3;
  const CaseTable::Numbers::Written::ValueDimensions& d = table.numbers.written.dimensions;
  CHECK(d.size() == 9);
  CHECK(d.bytes_held() == 3 * sizeof(Dimension));  // the first row's alone, not one a value
  for (std::size_t k = 0; k < 9; ++k) CHECK(d.at(k, k % 3) == row[k % 3]);
  // A value unlike its column's: every value keeps its own from then on, those before included.
  table.keep_written("1", true, 1.0, dim::length);
  table.keep_written("auto", false, std::numeric_limits<double>::quiet_NaN(), dim::none);
  table.keep_written("1", false, 1.0, dim::none);
  table.keep_written("2", true, 2.0, dim::length);  // a row after the change
  table.numbers.count = 4;
  CHECK(d.size() == 13);
  CHECK(d.bytes_held() >= 13 * sizeof(Dimension));
  for (std::size_t k = 0; k < 12; ++k) CHECK(d.at(k, k % 3) == (k == 10 ? dim::none : row[k % 3]));
  CHECK(d.at(12, 0) == dim::length);
  CaseValue scratch;
  CHECK(table.number_cell(3, 1, scratch).dimension == dim::none);
  CHECK_FALSE(table.number_cell(3, 1, scratch).si);
  CHECK(table.number_cell(2, 1, scratch).dimension == dim::angle);
  // Without a width there are no columns to share: every value keeps its own.
  CaseTable::Numbers::Written::ValueDimensions unshared;
  unshared.push_back(dim::length, 0);
  unshared.push_back(dim::time, 0);
  CHECK(unshared.size() == 2);
  CHECK(unshared.at(0, 0) == dim::length);
  CHECK(unshared.at(1, 0) == dim::time);
}

TEST_CASE("Case tables: a number's value in a unit is that of its 17 digits read as a cell", "[core][sweep]") {
  // Python's columns give numbers (kept as given, CaseTable::keep_given, shown as their 17 digits); the value is taken from the
  // number itself (bare_number_in(double)), which must be what the text read as a cell gives.
  std::mt19937_64 random(31);
  std::uniform_real_distribution<double> exponent(-300.0, 300.0), unit_interval(0.0, 1.0);
  const std::vector<std::string> units{"mm", "deg", "rpm", "degC", "degF", "um", "N/mm", "m"};
  for (const std::string& unit : units) {
    const UnitScale scale = *parse_unit_cached(unit);
    for (int k = 0; k < 20000; ++k) {
      const double magnitude = std::pow(10.0, exponent(random)) * unit_interval(random);
      const double x = k % 2 ? -magnitude : magnitude;
      char buffer[40];
      const auto printed = std::to_chars(buffer, buffer + sizeof buffer, x, std::chars_format::general, 17);
      const std::optional<double> from_text = bare_number_in(std::string_view(buffer, static_cast<std::size_t>(printed.ptr - buffer)), scale);
      const std::optional<double> from_number = bare_number_in(x, scale);
      REQUIRE(from_text.has_value() == from_number.has_value());
      if (from_text) REQUIRE(std::bit_cast<std::uint64_t>(*from_text) == std::bit_cast<std::uint64_t>(*from_number));
    }
    // The largest numbers overflow in SI the same way read either way.
    CHECK(bare_number_in(std::numeric_limits<double>::max(), scale).has_value() == bare_number_in("1.7976931348623157e308", scale).has_value());
    CHECK(bare_number_in(0.0, scale) == bare_number_in("0", scale));
  }
}

TEST_CASE("Case tables: a number given as a double is kept without text and shown as its 17 digits", "[core][sweep]") {
  // Python's numpy columns with a unit: CaseTable::keep_given keeps the number, and everything a
  // table shows of it is what keep_written of its 17 digits as the cell "DIGITS UNIT" showed.
  const std::vector<std::string> units{"", "mm", "degC"};  // a word column first: the given numbers come later
  const auto make = [&](bool given) {
    CaseTable table;
    for (std::size_t v = 0; v < units.size(); ++v) table.variables.push_back({"x" + std::to_string(v), units[v]});
    table.numbers.dimensions.assign(units.size(), Dimension{});
    table.numbers.written.column_units = units;
    std::mt19937_64 random(7);
    std::uniform_real_distribution<double> exponent(-30.0, 30.0);
    for (std::size_t i = 0; i < 200; ++i) {
      table.keep_written(i % 2 ? "roller" : "flat", false, std::numeric_limits<double>::quiet_NaN(), Dimension{});
      for (std::size_t v = 1; v < units.size(); ++v) {
        const UnitScale scale = *parse_unit_cached(units[v]);
        const double x = (i % 3 ? 1.0 : -1.0) * std::pow(10.0, exponent(random)) * (i == 5 ? 0.0 : 1.0);
        const double si = *bare_number_in(x, scale);
        if (given) {
          table.keep_given(x, si, scale.dimension);
        } else {
          CaseTable::Numbers::Written::Digits digits;
          table.keep_written(CaseTable::Numbers::Written::given_text(x, digits), true, si, scale.dimension);
        }
      }
      ++table.numbers.count;
    }
    return table;
  };
  const CaseTable given = make(true), written = make(false);
  CHECK(given.numbers.written.text.size() < written.numbers.written.text.size() / 4);  // the words' text only
  const std::vector<ShownUnit> shown_units = given.shown_units();
  CaseValue a, b;
  for (std::size_t i = 0; i < given.size(); ++i)
    for (std::size_t v = 0; v < units.size(); ++v) {
      INFO("case " << i << ", variable " << v);
      const CaseValue& g = given.cell(i, v, a);
      const CaseValue& w = written.cell(i, v, b);
      CHECK(g.text == w.text);
      CHECK(g.si == w.si);
      CHECK(g.dimension == w.dimension);
      CHECK(given.shown(i, v) == written.shown(i, v));
      std::string shown_given, shown_written;
      CHECK(given.append_shown(shown_given, i, v, shown_units[v]) == written.append_shown(shown_written, i, v, shown_units[v]));
      CHECK(shown_given == shown_written);
      // The number the row shows, without its digits: the digits read back.
      const double number = given.shown_given_number(i, v, shown_units[v]);
      if (v == 0) {
        CHECK(std::isnan(number));
      } else {
        double read = 0.0;
        REQUIRE(std::from_chars(shown_written.data(), shown_written.data() + shown_written.size(), read).ec == std::errc());
        CHECK(std::bit_cast<std::uint64_t>(number) == std::bit_cast<std::uint64_t>(read));
      }
      CHECK(std::isnan(written.shown_given_number(i, v, shown_units[v])));  // a written cell is read as written
    }
  // Its holdings count the given numbers.
  const CaseTable::Numbers::Written& w = given.numbers.written;
  CHECK(sweep_holdings(given, 0) == static_cast<double>(given.numbers.si.capacity() * sizeof(double) + w.text.size() +
                                                         w.ends.capacity() * sizeof(std::uint32_t) + w.in_column_unit.capacity() +
                                                         w.dimensions.bytes_held() + w.given.capacity() * sizeof(double)));
}
