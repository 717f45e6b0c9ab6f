#pragma once
// The rows of `mechgraph sweep`: one per case, `case`, the varied inputs, the requested outputs
// (a scalar is one column, a series one column per element), then `exit` and `error`. Headers
// read `name [unit]` (an angle with the frame its port declares, `name [deg (shaft)]`, the
// report's rule: angle_reference.hpp); values are in the column's unit, written with 17 significant digits so a
// row reads back to the same doubles (the shortest such text). The columns of a series are known once a case has produced
// it, so rows wait until the first case succeeds (or the sweep ends) to fix the header.
//
// Column names are unique, so a JSON Lines object never has the same key twice: `case`, `exit`
// and `error` are reserved; a varied input named like one of them is written `in.NAME`, an output
// whose name an earlier column has (a swept parameter that is also an output) `out.NAME`.
// Every CSV cell goes through csv_field (RFC 4180, formula-like text neutralised).
//
// RowChecker re-reads rows written earlier (--resume, merge) and refuses, naming FILE:line, any
// row this code would not have written: a cell count other than the header's, a case number that
// is not a whole number below the sweep's count, not this shard's or not after the previous row's,
// an exit other than 0, 2 or 3, an output cell that is neither empty nor a finite number.
#include <mechgraph/graph.hpp>
#include <mechgraph/sweep/case_table.hpp>
#include <mechgraph/sweep/sweep_runner.hpp>

#include <functional>
#include <optional>
#include <string>
#include <variant>
#include <vector>

namespace mechgraph::host {

enum class RowFormat { csv, jsonl };

/// The header of the column of scalar output `output` of `graph` (its label, its unit and the
/// angle it counts): what a sweep writes and a study reading its rows looks for.
std::string sweep_column_name(const Graph& graph, std::size_t output);

struct SweepRow {
  std::vector<std::string> cells;  // as text; numbers unquoted in JSON Lines
  std::vector<bool> numeric;
};

class SweepRows {
 public:
  SweepRows(const Graph& graph, const CaseTable& table, RowFormat format);

  /// Fixes the columns from a successful case (or from the scalar outputs alone when none
  /// succeeded). Idempotent.
  void settle(const CaseResult* success);
  /// Adopts the header of a file being resumed; throws UsageError if it is not this sweep's.
  void adopt(const std::vector<std::string>& header);
  bool settled() const { return settled_; }

  const std::vector<std::string>& header() const { return header_; }
  /// The row of one case; a success whose shape differs from the header becomes a failed row.
  std::string line(const CaseResult& result, int exit_code) const;
  /// line(result, exit_code) appended to `out` (CSV rows without a string per cell).
  void append_line(std::string& out, const CaseResult& result, int exit_code) const;

  /// The row of one case without its inputs, for a caller that keeps numbers as numbers (the
  /// Python module's numpy columns): what line() writes as JSON Lines, before it becomes text. Its
  /// exit code is returned; a success appends one value per output column (in its unit) to
  /// `outputs`, a failure appends nothing and sets `error` (else cleared). The inputs come column
  /// by column from input_number (input_value where a column holds text).
  int outcome(const CaseResult& result, int exit_code, std::vector<double>& outputs, std::string& error) const;
  /// The number of output columns a success appends (the header settled).
  std::size_t output_columns() const { return columns_.size(); }
  /// The input columns' headers (`name [unit]`).
  std::vector<std::string> input_headers() const;
  /// Input v of case i as a row holds it: none (an empty cell), a number (the row's text read
  /// back), or text as written; `cell` is scratch as for input_number.
  std::variant<std::monostate, double, std::string> input_value(std::size_t i, std::size_t v, std::string& cell) const;
  /// Input v of case i as input_value gives a number, NaN where it gives none or text; `cell`
  /// is scratch (its storage kept from call to call: a study's million rows make no string each).
  double input_number(std::size_t i, std::size_t v, std::string& cell) const;

 private:
  struct Column {
    std::size_t output;                  // index into Graph::outputs
    std::optional<std::size_t> element;  // element of a series
    double scale = 1.0, offset = 0.0;    // shown = si / scale - offset (the display unit, parsed once)
  };
  static double shown(double si, const Column& c) { return si / c.scale - c.offset; }
  Column column(std::size_t output, std::optional<std::size_t> element) const;
  std::vector<std::string> output_headers(const CaseResult* success, std::vector<Column>& columns) const;
  std::string shape_problem(const CaseResult& result) const;  // "" when its series fit the header
  double cell_value(const CaseResult& result, const Column& c) const;
  std::string format(const std::vector<std::string>& cells, const std::vector<bool>& numeric) const;
  static void make_unique(std::vector<std::string>& names, const std::vector<std::string>& taken, const std::string& prefix);

  const Graph& graph_;
  const CaseTable& table_;
  std::vector<ShownUnit> input_units_;  // table_.shown_units(), parsed once for every row
  RowFormat format_;
  bool settled_ = false;
  std::vector<std::string> header_;
  std::vector<Column> columns_;
};

/// run_sweep's results (in case order) handed on as rows: a result before the first success waits,
/// because the columns of a series are known only once a case has produced it. `header_fixed` is
/// called once, when the columns are fixed here (not when the rows adopted a resumed header);
/// `row` with every result, in case order.
class RowSequencer {
 public:
  RowSequencer(SweepRows& rows, std::function<void()> header_fixed, std::function<void(const CaseResult&)> row)
      : rows_(rows), header_fixed_(std::move(header_fixed)), row_(std::move(row)) {}
  void operator()(CaseResult&& result);
  /// After the sweep: fixes the columns from the scalar outputs alone when no case succeeded, and
  /// hands on what waited.
  void finish();

 private:
  void settle(const CaseResult* success);
  SweepRows& rows_;
  std::function<void()> header_fixed_;
  std::function<void(const CaseResult&)> row_;
  std::vector<CaseResult> waiting_;
};

/// What another tool may have put around the lines of a rows file: a UTF-8 byte order mark before
/// the first, a carriage return before each line break (CR LF, as Windows saves text). mechgraph
/// writes neither.
struct ForeignLineMarks {
  bool byte_order_mark = false;
  bool carriage_return = false;
  bool any() const { return byte_order_mark || carriage_return; }
};
/// Removes them from `line` (line `number` of its file, 1-based) and says which were there: `merge`
/// and `study --rows` read past them (merge writes LF, no mark), `--resume` refuses them (it
/// appends to the file as it is, which would mix the line ends).
ForeignLineMarks strip_foreign_line_marks(std::string& line, std::size_t number);
/// The words for what was found (a clause: "ends in CR LF ..." / "starts with a UTF-8 byte order mark").
std::string foreign_line_marks_text(const ForeignLineMarks& marks);

/// The rules a row read back must follow.
struct RowRules {
  RowFormat format = RowFormat::csv;
  std::size_t cases = 0;                  // case numbers lie below this
  std::size_t shard = 0, shards = 1;      // and are shard mod shards
  std::optional<std::size_t> inputs;      // varied-input columns after `case`, when known
  /// --resume knows the cases: the text input `v` of case `i` shows (CaseTable::shown). CSV rows
  /// must then carry exactly that text, so a row edited to other inputs is refused.
  std::function<std::string(std::size_t i, std::size_t v)> shown_input;
};

/// Checks rows one at a time, in file order; see the file comment.
class RowChecker {
 public:
  RowChecker(RowRules rules, std::string file) : rules_(std::move(rules)), file_(std::move(file)) {}
  /// CSV: the header line (read before any row); throws UsageError for a malformed one.
  void header(std::string_view line, std::size_t number);
  const std::vector<std::string>& header_cells() const { return header_; }
  /// One row: its case number and whether it records a failure. Throws UsageError "FILE:line: ...".
  struct Row {
    std::size_t index;
    bool failed;
  };
  Row row(std::string_view line, std::size_t number);

 private:
  [[noreturn]] void refuse(std::size_t number, const std::string& why) const;
  std::size_t case_number(std::string_view text, std::size_t number);
  void check_exit_and_outputs(const std::vector<std::string>& cells, const std::vector<bool>& plain, std::size_t number) const;
  RowRules rules_;
  std::string file_;
  std::vector<std::string> header_;        // CSV header, or the first JSON row's keys
  std::optional<std::size_t> previous_;
};

/// A cell's number when it is a finite number as the rows write them (std::from_chars over all of
/// it, in no locale: strtod reads "8.5" as 8 where a program has set a German locale), else none.
std::optional<double> finite_number_in_cell(std::string_view text);
/// Whether a cell is a finite number as the rows write them.
inline bool finite_number_cell(std::string_view text) { return finite_number_in_cell(text).has_value(); }

/// The exit code a failed case's class maps to (2 scene or usage, 3 evaluation), 0 for success.
int exit_code_of(CaseFailure failure);

}  // namespace mechgraph::host
