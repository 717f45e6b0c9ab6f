#pragma once
// Comma-separated rows as RFC 4180 has them: a field with a comma, a quote or a line break is
// quoted, a quote inside is doubled. Rows are single lines here (fields never span lines:
// writers turn line breaks in messages into spaces).
#include <string>
#include <string_view>
#include <vector>

namespace mechgraph {

/// The fields of one line; throws std::invalid_argument for an unterminated quote.
std::vector<std::string> split_csv_line(std::string_view line);

/// One field, quoted when it has to be; line breaks become spaces.
std::string csv_field(std::string_view text);

/// A row of fields joined by commas, without the line break.
std::string csv_row(const std::vector<std::string>& fields);

/// "name [unit]" -> {"name", "unit"}; "name" -> {"name", ""}.
std::pair<std::string, std::string> split_header(std::string_view header);

}  // namespace mechgraph
