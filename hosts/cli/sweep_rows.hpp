#pragma once
// The rows of `mechgraph sweep`: one per case, `case`, the varied inputs, the requested outputs
// (a scalar is one column, a series one column per element), then `exit` and `error`. Headers
// read `name [unit]`; values are in the column's unit, written with 17 significant digits so a
// row reads back to the same doubles (the shortest such text). The columns of a series are known once a case has produced
// it, so rows wait until the first case succeeds (or the sweep ends) to fix the header.
#include <mechgraph/graph.hpp>
#include <mechgraph/sweep/sweep_runner.hpp>

#include <optional>
#include <string>
#include <vector>

namespace mechgraph::cli {

enum class RowFormat { csv, jsonl };

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

 private:
  struct Column {
    std::size_t output;                  // index into Graph::outputs
    std::optional<std::size_t> element;  // element of a series
    double scale = 1.0, offset = 0.0;    // shown = si / scale - offset (the display unit, parsed once)
  };
  static double shown(double si, const Column& c) { return si / c.scale - c.offset; }
  Column column(std::size_t output, std::optional<std::size_t> element) const;
  std::vector<std::string> output_headers(const CaseResult* success, std::vector<Column>& columns) const;
  std::string format(const std::vector<std::string>& cells, const std::vector<bool>& numeric) const;

  const Graph& graph_;
  const CaseTable& table_;
  RowFormat format_;
  bool settled_ = false;
  std::vector<std::string> header_;
  std::vector<Column> columns_;
};

/// The exit code a failed case's class maps to (2 scene or usage, 3 evaluation), 0 for success.
int exit_code_of(CaseFailure failure);

}  // namespace mechgraph::cli
