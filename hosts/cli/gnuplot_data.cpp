#include "gnuplot_data.hpp"

#include <mechgraph/text_escape.hpp>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <stdexcept>

namespace mechgraph::cli {

void write_gnuplot_datablock(std::ostream& script, const std::string& name, const std::vector<const std::vector<double>*>& columns,
                             const std::vector<std::size_t>& pieces_from) {
  const bool identifier = !name.empty() && std::all_of(name.begin(), name.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_';
  });
  if (!identifier) throw std::invalid_argument("a gnuplot datablock name must be an identifier");
  std::size_t rows = columns.empty() ? 0 : columns.front()->size();
  for (const std::vector<double>* c : columns) rows = std::min(rows, c->size());
  script << '$' << name << " << EOD\n";
  std::string line;
  char buffer[32];
  std::size_t next_piece = 0;
  for (std::size_t i = 0; i < rows; ++i) {
    bool piece = false;
    while (next_piece < pieces_from.size() && pieces_from[next_piece] <= i) piece = piece || pieces_from[next_piece++] == i;
    if (piece && i > 0) script << '\n';  // a blank line: gnuplot draws no line across it
    line.clear();
    bool finite = true;
    for (const std::vector<double>* c : columns) {
      const double v = (*c)[i];
      finite = finite && std::isfinite(v);
      const auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, v, std::chars_format::general, 17);
      if (!line.empty()) line += ' ';
      line.append(buffer, end);
    }
    if (finite) script << line << '\n';
  }
  script << "EOD\n";
}

void write_gnuplot_xtic_labels(std::ostream& script, const std::string& options, const std::vector<std::string>& labels) {
  if (labels.empty()) return;
  script << "set xtics " << options << " (";
  for (std::size_t i = 0; i < labels.size(); ++i) script << (i ? ", " : "") << gnuplot_string(labels[i]) << ' ' << i;
  script << ")\n";
}

bool is_whole_svg(std::string_view text) {
  std::size_t end = text.size();
  while (end > 0 && (text[end - 1] == '\n' || text[end - 1] == '\r' || text[end - 1] == ' ' || text[end - 1] == '\t')) --end;
  return text.find("<svg") != std::string_view::npos && end >= 6 && text.substr(end - 6, 6) == "</svg>";
}

}  // namespace mechgraph::cli
