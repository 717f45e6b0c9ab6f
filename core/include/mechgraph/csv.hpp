#pragma once
// Comma-separated rows as RFC 4180 has them: a field with a comma, a quote or a line break is
// quoted, a quote inside is doubled. Rows are single lines here (fields never span lines:
// csv_field turns line breaks into spaces). Every cell and header mechgraph writes from user
// text (node names, labels, --cases cells, series headers, error messages) goes through
// csv_field, the one escaping function for CSV.
//
// Spreadsheet formula injection (OWASP "CSV injection"): a cell that is not a number and starts
// with = + - @ TAB or CR is read by Excel or LibreOffice as a formula; csv_field puts a single
// quote before it, which spreadsheets show as text. Numbers ("-2", "-1.5e-3") and a lone "-" (an
// empty cell's mark) are left alone.
#include <string>
#include <string_view>
#include <vector>

namespace mechgraph {

/// The fields of one line; throws std::invalid_argument for an unterminated quote.
std::vector<std::string> split_csv_line(std::string_view line);
/// The fields of a line without quotes as views into it (`fields` reused: nothing allocated once it
/// has room), the same fields split_csv_line gives; false, and `fields` empty, when the line has a
/// quote (split_csv_line reads it then).
bool split_plain_csv_line(std::string_view line, std::vector<std::string_view>& fields);

/// One field, quoted when it has to be; line breaks become spaces; a formula-like text cell gets a
/// leading ' (see above). split_csv_line(csv_field(t)) gives csv_text(t).
std::string csv_field(std::string_view text);
/// csv_field(text) appended to `out` (the one escaping function; csv_field and csv_row are it).
void append_csv_field(std::string& out, std::string_view text);

/// The text a reader gets back from csv_field(text): line breaks (CR, LF) as spaces, then a
/// leading ' when the text is not a number and starts with = + - @ or TAB.
std::string csv_text(std::string_view text);

/// A row of fields joined by commas, without the line break.
std::string csv_row(const std::vector<std::string>& fields);

/// "name [unit]" -> {"name", "unit"}; "name" -> {"name", ""}.
std::pair<std::string, std::string> split_header(std::string_view header);

}  // namespace mechgraph
