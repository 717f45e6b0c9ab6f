#pragma once
// The data gnuplot reads, written into its script as inline datablocks of numbers only.
//
// Why not the CSV beside the plot: gnuplot does not read CSV as RFC 4180 does (a doubled quote in
// a quoted field, a comma inside one), so a label such as `shaft 1", ground` shifted a bar's value
// into another column or dropped the bar. Text never reaches gnuplot as data: labels and titles go
// into the script as gnuplot_string constants (text_escape.hpp), and the data as numbers in a
// datablock (`$NAME << EOD` ... `EOD`), whose lines hold nothing but numbers, so no text can end
// the block or shift a column.
#include <cstddef>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

namespace mechgraph::cli {

/// Writes `$NAME << EOD`, one line per row of the columns (numbers separated by a space, 17
/// significant digits), `EOD`. A row stops at the shortest column; a row holding a non-finite
/// number is left out (gnuplot would read "inf" as text). `name` must be an identifier (letters,
/// digits, '_'), chosen by the caller, never user text: std::invalid_argument otherwise.
/// `pieces_from`: rows (ascending) before which a blank line is written, so that gnuplot draws the
/// curve in pieces and no line joins row i - 1 to row i (a jump of the curve there).
void write_gnuplot_datablock(std::ostream& script, const std::string& name, const std::vector<const std::vector<double>*>& columns,
                             const std::vector<std::size_t>& pieces_from = {});

/// `set xtics OPTIONS (LABEL 0, LABEL 1, ...)`: tic labels at 0, 1, 2 ... each a gnuplot_string
/// constant; `options` is the caller's fixed text ("rotate by -30"), never user text. Nothing for
/// no labels.
void write_gnuplot_xtic_labels(std::ostream& script, const std::string& options, const std::vector<std::string>& labels);

/// Whether `text` is an SVG document gnuplot finished: an "<svg" element and "</svg>" at its end
/// (whitespace after it allowed). A plot cut short by a full disk has lost its end.
bool is_whole_svg(std::string_view text);

}  // namespace mechgraph::cli
