#pragma once
// The cases of a sweep: which parameters vary (by the name `--set` uses: `rpm` for a scene
// parameter, `part.length` for a node's) and the value each takes in each case. Three ways to
// make them: a full grid (`--vary`), a table read from CSV (`--cases`) and a Latin hypercube
// sample (`--sample`, reproducible from its seed).
#include <mechgraph/dimension.hpp>
#include <mechgraph/units.hpp>

#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string_view>
#include <string>
#include <vector>

namespace mechgraph {

/// The most values a table of numbers only may hold (CaseTable::Numbers: a Latin hypercube, a
/// study's design): 2.5 x 10^8, 2 GB at a double each; checked before the table is built.
inline constexpr std::size_t max_number_cells = 250'000'000;
/// The most values (cases x varied parameters) one sweep's table of written values may hold (a
/// grid, a cases file, Python's columns: a CaseValue each, with its text): 2 x 10^7, about 2 GB as
/// they are kept; checked before the table is built.
inline constexpr std::size_t max_case_cells = 20'000'000;
/// The most cases one sweep may have (a sample, a study's design, a grid, a cases file, a manifest
/// a merge reads): 2.5 x 10^8, as many as a table of numbers holds values. It is the tables' own
/// caps that bind first (max_number_cells, max_case_cells); this one bounds a count read from a
/// file or an option before anything is allocated for it. (It was 10^7 while every table kept
/// written values: a rare event's study needs more, docs/methods/uncertainty.md.)
inline constexpr std::size_t max_sweep_cases = max_number_cells;
/// max_sweep_cases as messages write it.
inline constexpr std::string_view max_sweep_cases_text = "2.5 x 10^8";
/// The most points of one `--vary` range: 10^7 (its values are made before the grid's size is
/// checked).
inline constexpr std::size_t max_range_points = 10'000'000;
/// The largest cases file read (256 MiB) and the largest sweep manifest (64 KiB: a dozen fields).
inline constexpr std::size_t max_cases_file_bytes = std::size_t{256} << 20;
inline constexpr std::size_t max_manifest_bytes = std::size_t{64} << 10;

/// read_bounded_file (bounded_read.hpp: a regular file only, non-blocking, at most `limit` bytes)
/// with its refusal as a SceneError "`what`: 'FILE' is a FIFO (named pipe), not a regular file".
std::string read_user_file(const std::filesystem::path& file, std::size_t limit, const std::string& what);

/// At most `limit` bytes of user text for an error message, UTF-8 kept whole and readable (unlike
/// quoted_text_excerpt's \xNN), controls as '?' (terminal_text), "..." where it was cut.
std::string excerpt(std::string_view text, std::size_t limit = 200);

/// One value of one case: a number with its dimension (SI), or a word (a choice such as an
/// integrator's name) for parameters that take one.
struct CaseValue {
  std::string text;                // as written, or made from the number; empty for a number generated in bulk
  std::optional<double> si;        // when it is a number
  Dimension dimension;             // of the number

  /// The value as text: `text`, or for a number without one its exact_text (a study's million
  /// cases keep their numbers only, and a message or a rebuilt scene asks for the text).
  std::string written() const;
};

/// x in SI as text that reads back as exactly x: the shortest such digits and the SI unit of `d`
/// ("0.0025 m"); the text of a generated case value.
std::string exact_text(double x, const Dimension& d);
/// exact_text appended to `out`, the unit given as its text (exact_text_unit): a writer of many
/// values makes each variable's unit once.
void append_exact_text(std::string& out, double x, std::string_view si_unit);
/// The unit exact_text writes for `d`: its SI unit, "" for a dimensionless value.
std::string exact_text_unit(const Dimension& d);

/// The double nearest `si` that a number written in `unit` reads back to ((number + offset) *
/// scale): `si` itself where some number does (a value written in that unit, most values), else
/// (x + offset) * scale for x = si / scale - offset. A value made in SI (a grid's point, a sample)
/// is put on it, so that a row shows it in its column's unit and reads back to it exactly. `si`
/// unchanged for "" or a text that is no unit.
double expressible_in(double si, const std::string& unit);
/// The same for a unit parsed once (nullopt: `si` unchanged), for a design's millions of values.
double expressible_in(double si, const std::optional<UnitScale>& unit);

/// A number written without a unit in a column of `unit` (a cases file's bare cell, a Python
/// column's number): (x + offset) * scale, the value read_case_value reads from "TEXT UNIT",
/// without reading the unit again; nullopt where TEXT is not a plain number ("+" allowed) or the
/// value is not finite (read_case_value's own reading then decides, with its message).
std::optional<double> bare_number_in(std::string_view text, const UnitScale& unit);
/// The same for a number already read (finite x, as from_chars reads TEXT): nullopt where the value
/// is not finite.
std::optional<double> bare_number_in(double x, const UnitScale& unit);

/// A number with its unit if `text` reads as one ("5600 rpm"), else a word (a choice). An infinite
/// or NaN number ("1e400 m", "nan") is a SceneError naming `context`: no such value reaches a node.
CaseValue read_case_value(const std::string& text, const std::string& context);

struct SweepVariable {
  std::string name;  // "rpm", "part.length"
  std::string unit;  // the unit its values are shown in ("" = SI, or a word)
};

/// A variable's unit as CaseTable::append_shown reads it, parsed once for a writer of many rows.
struct ShownUnit {
  bool given = false;              // the variable has a unit ("" = SI)
  std::optional<UnitScale> scale;  // that unit parsed; nullopt when it is not one (values shown as written)
  bool names_si = false;           // the unit is written as its dimension's SI unit ("m", "N/m"): exact_text's
};

struct CaseTable {
  std::vector<SweepVariable> variables;
  /// cases[i][v]: variable v in case i, as read or made (a cases file, a grid, a sample, a
  /// caller's table). Empty where `numbers` holds the cases.
  std::vector<std::vector<CaseValue>> cases;
  /// A table of numbers only, kept compactly: a study's design, a million cases or more, at 8
  /// bytes a value where a row of CaseValue takes an allocation and 56 bytes a value (on a
  /// virtual machine, touching that memory for the first time was a fifth of a study's time).
  /// A table keeps its cases one way or the other, never both: `numbers` only while `cases` is
  /// empty. Read either through size(), cell() and row().
  struct Numbers {
    std::size_t count = 0;              // cases
    std::vector<Dimension> dimensions;  // of each variable's values (none where `written` keeps each value's)
    std::vector<double> si;             // si[i * dimensions.size() + v]: variable v in case i, SI
    /// A value in a column named by its SI unit ("m") shows the digits of its exact text, as a
    /// sample's rows did while each value kept that text (make_latin_hypercube sets it); else
    /// as every number made in SI is shown (a study's design: %.15g where that reads back).
    bool exact_text_digits = false;
    /// The values as a file wrote them (a cases file), kept beside the numbers without a string
    /// each: value k (k = i * width + v) is what a CaseValue of it held. Empty where the text is
    /// made from the numbers.
    struct Written {
      /// in_column_unit's marks: the text as written; a bare number, its CaseValue text
      /// "TEXT UNIT"; the same for a number given as a double in its column's unit (a Python
      /// column's), kept in `given`, its TEXT the 17 significant digits made when asked.
      static constexpr std::uint8_t as_written = 0, bare_number = 1, given_number = 2;
      std::string text;                          // every value's own text, one after another (none for a given number)
      std::vector<std::uint32_t> ends;           // value k's ends at ends[k], starts at ends[k - 1] (or 0)
      std::vector<std::uint8_t> in_column_unit;  // as_written, bare_number or given_number
      /// Each value's dimension (a word's, NaN in si, none), kept once a column while every value
      /// of the column has the first row's (the common table: 5 bytes a value fewer, 30 MB at
      /// 10^6 x 6), each value's own from the first value that differs.
      class ValueDimensions {
       public:
        /// The next value's (k = size(), variable k % width; width 0 keeps every value's own).
        void push_back(const Dimension& d, std::size_t width);
        /// Value k's, of variable v (k = i * width + v).
        const Dimension& at(std::size_t k, std::size_t v) const { return each_.empty() ? column_[v] : each_[k]; }
        std::size_t size() const { return count_; }
        /// What the dimensions hold, in bytes (a table's holdings count it).
        std::size_t bytes_held() const { return (column_.capacity() + each_.capacity()) * sizeof(Dimension); }

       private:
        std::vector<Dimension> column_;  // the first row's, one a variable
        std::vector<Dimension> each_;    // every value's, once one differs from its column's
        std::size_t count_ = 0;
      };
      ValueDimensions dimensions;
      std::vector<std::string> column_units;     // per variable: the UNIT of its bare numbers
      /// given[k]: value k's number where in_column_unit[k] is given_number, else NaN; empty where
      /// no value is given so. 8 bytes a value where its digits took up to 24 and were read back.
      std::vector<double> given;
      /// Room for the text of a given number.
      using Digits = std::array<char, 32>;
      /// Value k's own text (without " UNIT" where in_column_unit), made in `digits` for a given
      /// number.
      std::string_view own_text(std::size_t k, Digits& digits) const {
        if (in_column_unit[k] == given_number) return given_text(given[k], digits);
        const std::size_t begin = k == 0 ? 0 : ends[k - 1];
        return std::string_view(text).substr(begin, ends[k] - begin);
      }
      /// A given number's text: std::to_chars with 17 significant digits, which reads back to x.
      static std::string_view given_text(double x, Digits& digits);
      /// Value k's CaseValue text appended to `out` (v: its variable).
      void append(std::string& out, std::size_t k, std::size_t v) const;
    } written;
  } numbers;
  /// The next value of a table kept as numbers with their texts (Numbers::Written), value k =
  /// i * width + v in that order: `text` as written (only the number before " UNIT" where
  /// in_column_unit), `si` NaN for a word. The caller sizes dimensions and column_units first
  /// and counts the cases.
  void keep_written(std::string_view text, bool in_column_unit, double si, const Dimension& dimension);
  /// keep_written of `value`, read from the cell `cell` of variable v: its text "CELL UNIT" (UNIT
  /// the variable's written.column_units) kept as the cell and the mark.
  void keep_written(const CaseValue& value, std::string_view cell, std::size_t v);
  /// The next value as a number `x` given in its column's unit (Written::given_number): what
  /// keep_written keeps of the cell "DIGITS UNIT", DIGITS x's 17 significant digits, without
  /// making them. `si`: (x + offset) * scale of that unit, finite.
  void keep_given(double x, double si, const Dimension& dimension);
  /// A column whose header names no unit takes the unit of its first number written with one
  /// ("5000 rpm": rpm), so that its rows show the numbers in it: `value` read from `cell` of
  /// variable v. The unit it reads bare numbers in stays the header's (none).
  void adopt_unit(std::size_t v, const CaseValue& value, const std::string& cell);
  std::string origin;  // "--vary ...", "FILE.csv", "--sample ... --seed S"

  /// How many cases the table holds, however it keeps them.
  std::size_t size() const { return cases.empty() ? numbers.count : cases.size(); }
  /// Variable v of case i: the stored value, or `scratch` made from the numbers (a number with no
  /// text: CaseValue::written() makes it when asked). Valid while both live.
  const CaseValue& cell(std::size_t i, std::size_t v, CaseValue& scratch) const;
  /// cell() without the text a table of numbers keeps or makes: the number and its dimension (a
  /// word: no number, its text empty), for a check that reads numbers only.
  const CaseValue& number_cell(std::size_t i, std::size_t v, CaseValue& scratch) const;
  /// Case i's values, the same way (`scratch` keeps its storage from case to case).
  const std::vector<CaseValue>& row(std::size_t i, std::vector<CaseValue>& scratch) const;

  /// The value of variable v in case i as the output shows it (in the variable's unit).
  std::string shown(std::size_t i, std::size_t v) const;
  /// shown(i, v) appended to `out` (the rows of a sweep are written without a string per cell);
  /// true when what it appended is a finite number's digits as std::to_chars writes them (a CSV
  /// cell as it is), false for text as written.
  bool append_shown(std::string& out, std::size_t i, std::size_t v) const;
  /// The same with variable v's unit parsed beforehand (shown_units()[v]).
  bool append_shown(std::string& out, std::size_t i, std::size_t v, const ShownUnit& unit) const;
  /// Where append_shown shows a given number (Written::given_number) as its digits, that number
  /// (the digits read back to it), else NaN: a reader of the shown numbers skips making and
  /// reading them.
  double shown_given_number(std::size_t i, std::size_t v, const ShownUnit& unit) const;
  /// Whether append_shown shows value (i, v) as its own text (a number written or given in its
  /// column's unit, shown in that unit), where that text is a number.
  bool shown_as_written(std::size_t i, std::size_t v, const ShownUnit& unit) const;
  /// Each variable's unit, parsed (append_shown parses it at each call).
  std::vector<ShownUnit> shown_units() const;
};

/// Every number a sweep generates or reads is finite: an infinite or NaN end, list value or
/// generated point is a SceneError naming the option.
/// `NAME=FROM:TO:N` (units in FROM and TO as in scenes, TO may omit it; N >= 1 points, ends
/// included) or `NAME=A,B,C` (the values listed, numbers with units or words).
struct VarySpec {
  std::string name;
  std::vector<CaseValue> values;
  std::string unit;
  /// FROM:TO:N: every value a number whose text is its exact_text, which a table of numbers
  /// makes again (make_grid keeps a grid of ranges only as numbers).
  bool range = false;
};
VarySpec parse_vary(std::string_view text);

/// The full grid of the specs; the last one varies fastest. A grid of ranges only is kept as
/// numbers (CaseTable::Numbers, within max_number_cells), showing and fingerprinting as the same
/// values kept as text; a grid with a list keeps its values as written (within max_case_cells).
CaseTable make_grid(const std::vector<VarySpec>& specs);

/// `NAME=LO:HI` for a Latin hypercube sample.
struct SampleSpec {
  std::string name;
  double low = 0.0, high = 0.0;  // SI
  Dimension dimension;
  std::string unit;
};
SampleSpec parse_sample(std::string_view text);

/// n cases, each variable's range cut in n equal strata with one point in each, strata paired at
/// random: the same (specs, n, seed) give the same cases on every machine (splitmix64 + own
/// shuffle, nothing implementation-defined). Kept as numbers (CaseTable::Numbers, within
/// max_number_cells), each on its variable's unit's numbers (expressible_in).
CaseTable make_latin_hypercube(const std::vector<SampleSpec>& specs, std::size_t n, std::uint64_t seed);

/// A CSV file of cases: a header of parameter names (`name` or `name [unit]`), then one case per
/// row; a cell is a number with its unit (`5600 rpm`), a bare number in the header's unit, or a
/// word. Blank lines and lines starting with '#' are skipped; a UTF-8 byte order mark before the
/// header is skipped (spreadsheets write one). Numbers must be finite. The file is read through
/// read_bounded_file (max_cases_file_bytes) and may hold at most max_sweep_cases cases. Throws
/// SceneError "file:line:column".
CaseTable read_cases_csv(const std::filesystem::path& file);

}  // namespace mechgraph
